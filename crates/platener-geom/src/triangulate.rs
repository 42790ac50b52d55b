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
        self.triangles.iter().flat_map(|&[a, b, c]| [[a, b], [b, c], [c, a]])
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
        .map(|q| {
            exact
                .get(&[q.x, q.y])
                .copied()
                .unwrap_or_else(|| grid::from_grid([q.x, q.y]))
        })
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
    let mut t = Triangulation { points, triangles };
    t.split_pinches();
    Ok(t)
}

impl Triangulation {
    /// Gives each fan of triangles around a point its own copy of the point, so that where
    /// the outline touches itself or a hole (a pinch) the boundary still runs as separate
    /// simple loops: every boundary point then has one edge in and one out, and a solid
    /// extruded from it uses every edge exactly twice. The copies keep the coordinates.
    fn split_pinches(&mut self) {
        let slots = self.triangles.len() * 3;
        // Directed edge → the slot (3 · triangle + corner) it starts at.
        let mut edges: Vec<([u32; 2], usize)> = (0..slots)
            .map(|s| ([self.corner(s), self.corner(next(s))], s))
            .collect();
        edges.sort_unstable();
        let find_edge = |e: [u32; 2]| edges.binary_search_by(|(k, _)| k.cmp(&e)).ok().map(|i| edges[i].1);
        let mut fans = UnionFind::new(slots);
        for s in 0..slots {
            // Across the edge leaving this corner lies the neighbour's slot of the same point.
            if let Some(t) = find_edge([self.corner(next(s)), self.corner(s)]) {
                fans.union(s, next(t));
            }
        }
        let mut first_fan: BTreeMap<u32, usize> = BTreeMap::new();
        let mut copy_of_fan: BTreeMap<usize, u32> = BTreeMap::new();
        for s in 0..slots {
            let (point, fan) = (self.corner(s), fans.find(s));
            if *first_fan.entry(point).or_insert(fan) == fan {
                continue;
            }
            let copy = *copy_of_fan.entry(fan).or_insert_with(|| {
                self.points.push(self.points[point as usize]);
                (self.points.len() - 1) as u32
            });
            self.triangles[s / 3][s % 3] = copy;
        }
    }

    fn corner(&self, slot: usize) -> u32 {
        self.triangles[slot / 3][slot % 3]
    }
}

/// The next corner's slot in the same triangle.
fn next(slot: usize) -> usize {
    slot - slot % 3 + (slot + 1) % 3
}

/// Disjoint sets of slots (path halving, union by index), for the fans around each point.
struct UnionFind(Vec<usize>);

impl UnionFind {
    fn new(n: usize) -> Self {
        UnionFind((0..n).collect())
    }

    fn find(&mut self, mut x: usize) -> usize {
        while self.0[x] != x {
            self.0[x] = self.0[self.0[x]];
            x = self.0[x];
        }
        x
    }

    fn union(&mut self, a: usize, b: usize) {
        let (a, b) = (self.find(a), self.find(b));
        self.0[a.max(b)] = a.min(b);
    }
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
