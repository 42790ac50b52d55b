//! Triangulating polygons with holes, on the project grid (i_triangle's integer sweep line).
//!
//! The 3D scenes draw a plate's faces as triangles. The polygon is snapped to the
//! [`crate::grid`] (1 µm) and triangulated by i_triangle's exact integer core, which also
//! resolves self-touching rings the same way the booleans do (non-zero fill). This file is
//! the only place that calls i_triangle.
//!
//! Points that are corners of the input keep their exact input coordinates (not the snapped
//! ones), so a solid built from the triangulation has the same bounds as the polygon; points
//! i_triangle makes itself (where rings cross) are on the grid. Areas therefore agree with
//! [`Polygon::area`] to within the snapping: at most half a grid step times the perimeter.

use std::collections::BTreeMap;

use glam::DVec2;
use i_overlay::i_float::int::point::IntPoint;
use i_triangle::int::triangulatable::IntTriangulatable;

use crate::boolean::ring_to_grid;
use crate::grid::{self, GridError};
use crate::polygon::Polygon;

/// Triangles covering a polygon: points in mm and counter-clockwise index triples.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Triangulation {
    /// The triangles' corners, in the polygon's 2D frame (mm).
    pub points: Vec<DVec2>,
    /// Each triangle's corners (indices into `points`), counter-clockwise.
    pub triangles: Vec<[u32; 3]>,
}

impl Triangulation {
    /// The sum of the triangles' areas (mm²).
    pub fn area(&self) -> f64 {
        self.triangles
            .iter()
            .map(|t| {
                let [a, b, c] = t.map(|i| self.points[i as usize]);
                0.5 * (b - a).perp_dot(c - a)
            })
            .sum()
    }

    /// Edges used by one triangle only, directed as in that triangle (the covered side on
    /// the left): the outline's edges counter-clockwise, the holes' clockwise.
    ///
    /// A solid's side walls are built along these, so they meet the caps edge for edge even
    /// where the triangulation dropped a straight vertex or split a ring where it touched
    /// itself. Returned in triangle order (deterministic).
    pub fn boundary_edges(&self) -> Vec<[u32; 2]> {
        let mut directed: Vec<[u32; 2]> = self.directed_edges().collect();
        directed.sort_unstable();
        self.directed_edges()
            .filter(|&[a, b]| directed.binary_search(&[b, a]).is_err())
            .collect()
    }

    fn directed_edges(&self) -> impl Iterator<Item = [u32; 2]> + '_ {
        self.triangles
            .iter()
            .flat_map(|&[a, b, c]| [[a, b], [b, c], [c, a]])
    }
}

/// Triangulates `polygon` (outer ring and holes, any orientation) on the project grid.
///
/// Holes remove area whichever way they are wound; rings with fewer than three points are
/// ignored. Fails only for coordinates the grid cannot hold (non-finite, beyond
/// [`grid::LIMIT`]).
pub fn triangulate(polygon: &Polygon) -> Result<Triangulation, GridError> {
    let mut exact: BTreeMap<[i32; 2], DVec2> = BTreeMap::new();
    let mut shape = Vec::with_capacity(1 + polygon.holes.len());
    for (i, ring) in std::iter::once(&polygon.outer).chain(&polygon.holes).enumerate() {
        let mut contour = ring_to_grid(ring)?;
        for (q, p) in contour.iter().zip(ring) {
            exact.entry([q.x, q.y]).or_insert(*p);
        }
        if contour.len() < 3 {
            continue;
        }
        // i_triangle fills by the non-zero rule: outer counter-clockwise, holes clockwise.
        let ccw = doubled_area(&contour) > 0;
        if ccw != (i == 0) {
            contour.reverse();
        }
        if i == 0 || !shape.is_empty() {
            shape.push(contour);
        }
    }
    if shape.is_empty() {
        return Ok(Triangulation::default());
    }
    let raw = shape.triangulate().into_triangulation::<u32>();
    let points: Vec<DVec2> = raw
        .points
        .iter()
        .map(|q| exact.get(&[q.x, q.y]).copied().unwrap_or_else(|| grid::from_grid([q.x, q.y])))
        .collect();
    let triangles = raw
        .indices
        .chunks_exact(3)
        .map(|t| {
            let [a, b, c] = [t[0], t[1], t[2]];
            let [pa, pb, pc] = [a, b, c].map(|i| raw.points[i as usize]);
            if orient(pa, pb, pc) < 0 { [a, c, b] } else { [a, b, c] }
        })
        .collect();
    Ok(Triangulation { points, triangles })
}

/// Twice the signed area of an integer ring, exact in i64.
fn doubled_area(ring: &[IntPoint<i32>]) -> i64 {
    let n = ring.len();
    (0..n)
        .map(|i| {
            let (a, b) = (ring[i], ring[(i + 1) % n]);
            i64::from(a.x) * i64::from(b.y) - i64::from(b.x) * i64::from(a.y)
        })
        .sum()
}

/// The sign of the turn a → b → c, exact in i64: positive counter-clockwise.
fn orient(a: IntPoint<i32>, b: IntPoint<i32>, c: IntPoint<i32>) -> i64 {
    let (abx, aby) = (i64::from(b.x) - i64::from(a.x), i64::from(b.y) - i64::from(a.y));
    let (acx, acy) = (i64::from(c.x) - i64::from(a.x), i64::from(c.y) - i64::from(a.y));
    abx * acy - aby * acx
}

#[cfg(test)]
mod tests;
