//! Is a point inside the model? Ray parity and winding, voted over three axes.
//!
//! A ray from the point along +x, +y and +z each counts the triangles it crosses; an odd count
//! says inside. So does a winding of 2 or more (crossings counted +1 where the surface faces
//! the ray's way, −1 otherwise): where two outward-wound shells overlap (a figurine's leg
//! modelled into its body, a cabin on a hull, common in printable models) the parity is even
//! but the point is inside both. On a closed surface the three rays agree; on an open or non-manifold one
//! (many real files) they may not, and the majority decides, which is right far more often
//! than one ray alone. Rays meeting an edge exactly are ignored: the points tested are random,
//! so that happens with probability zero.
//!
//! Each axis has a uniform grid over the other two coordinates holding the triangles whose
//! projected box touches a cell, so a ray tests only the triangles of its cell.

use glam::{DVec2, DVec3};

/// Cells per side of each axis grid, at most (triangles spread over at most 256² cells).
const MAX_CELLS: usize = 256;
/// Cell entries per grid, at most (128 MiB of indices); the grid is coarsened until it fits.
const MAX_ENTRIES: usize = 1 << 25;

/// The three grids of one mesh.
pub(crate) struct Inside<'a> {
    vertices: &'a [DVec3],
    triangles: &'a [[u32; 3]],
    grids: [AxisGrid; 3],
}

/// Triangles binned over the two coordinates other than `axis`.
struct AxisGrid {
    axis: usize,
    min: DVec2,
    cell: DVec2,
    n: usize,
    /// Cell `i` holds `items[starts[i]..starts[i + 1]]`.
    starts: Vec<u32>,
    items: Vec<u32>,
}

/// The two coordinates of `p` other than `axis`.
fn across(p: DVec3, axis: usize) -> DVec2 {
    match axis {
        0 => DVec2::new(p.y, p.z),
        1 => DVec2::new(p.z, p.x),
        _ => DVec2::new(p.x, p.y),
    }
}

impl AxisGrid {
    fn new(vertices: &[DVec3], triangles: &[[u32; 3]], axis: usize) -> Self {
        let boxes: Vec<(DVec2, DVec2)> = triangles
            .iter()
            .map(|t| {
                let [a, b, c] = t.map(|i| across(vertices[i as usize], axis));
                (a.min(b).min(c), a.max(b).max(c))
            })
            .collect();
        let (min, max) = boxes.iter().fold(
            (DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY)),
            |(lo, hi), b| (lo.min(b.0), hi.max(b.1)),
        );
        let size = (max - min).max(DVec2::splat(1e-9));
        let mut n = ((triangles.len() as f64).sqrt() as usize).clamp(1, MAX_CELLS);
        let mut grid = loop {
            let grid = Self {
                axis,
                min,
                cell: size / n as f64,
                n,
                starts: vec![0; n * n + 1],
                items: Vec::new(),
            };
            // Many long triangles over a fine grid would fill too many cells: coarsen.
            let entries: usize = boxes
                .iter()
                .map(|(lo, hi)| {
                    let (c0, c1) = (grid.cell_of(*lo), grid.cell_of(*hi));
                    (c1.0 - c0.0 + 1) * (c1.1 - c0.1 + 1)
                })
                .sum();
            if entries <= MAX_ENTRIES || n == 1 {
                break grid;
            }
            n /= 2;
        };
        // Two passes (count, then fill) keep every cell's list in one array.
        for pass in 0..2 {
            let mut fill = grid.starts.clone();
            for (i, (lo, hi)) in boxes.iter().enumerate() {
                let (c0, c1) = (grid.cell_of(*lo), grid.cell_of(*hi));
                for cy in c0.1..=c1.1 {
                    for cx in c0.0..=c1.0 {
                        let k = cy * grid.n + cx;
                        if pass == 0 {
                            grid.starts[k + 1] += 1;
                        } else {
                            grid.items[fill[k] as usize] = i as u32;
                            fill[k] += 1;
                        }
                    }
                }
            }
            if pass == 0 {
                let cells = grid.n * grid.n;
                for k in 0..cells {
                    grid.starts[k + 1] += grid.starts[k];
                }
                grid.items = vec![0; grid.starts[cells] as usize];
            }
        }
        grid
    }

    fn cell_of(&self, p: DVec2) -> (usize, usize) {
        let c = ((p - self.min) / self.cell).floor();
        let clamp = |v: f64| (v.max(0.0) as usize).min(self.n - 1);
        (clamp(c.x), clamp(c.y))
    }

    /// Whether the ray from `p` along +axis crosses the surface an odd number of times, or
    /// winds round it twice or more.
    fn odd(&self, vertices: &[DVec3], triangles: &[[u32; 3]], p: DVec3) -> bool {
        let q = across(p, self.axis);
        let (lo, hi) = (self.min, self.min + self.cell * self.n as f64);
        if q.x < lo.x || q.y < lo.y || q.x > hi.x || q.y > hi.y {
            return false;
        }
        let (cx, cy) = self.cell_of(q);
        let k = cy * self.n + cx;
        let (mut odd, mut winding) = (false, 0i64);
        for &t in &self.items[self.starts[k] as usize..self.starts[k + 1] as usize] {
            let corners = triangles[t as usize].map(|i| vertices[i as usize]);
            if let Some(sign) = crosses(corners, p, q, self.axis) {
                odd = !odd;
                winding += sign;
            }
        }
        odd || winding >= 2
    }
}

/// Whether the ray from `p` (whose cross-axis coordinates are `q`) along +axis passes through
/// the triangle's interior: `Some(1)` when the triangle faces along the ray (the ray leaves
/// the body there), `Some(-1)` when it faces against it.
fn crosses(corners: [DVec3; 3], p: DVec3, q: DVec2, axis: usize) -> Option<i64> {
    let [a, b, c] = corners.map(|v| across(v, axis) - q);
    let (e0, e1, e2) = (a.perp_dot(b), b.perp_dot(c), c.perp_dot(a));
    let inside = (e0 > 0.0 && e1 > 0.0 && e2 > 0.0) || (e0 < 0.0 && e1 < 0.0 && e2 < 0.0);
    if !inside {
        return None;
    }
    // Barycentric weights of q in the projected triangle give the crossing's height.
    let sum = e0 + e1 + e2;
    let h = (corners[2][axis] * e0 + corners[0][axis] * e1 + corners[1][axis] * e2) / sum;
    // The projected winding is the sign of the normal's component along the axis ((y, z),
    // (z, x), (x, y) are right-handed with x, y, z).
    (h > p[axis]).then_some(if e0 > 0.0 { 1 } else { -1 })
}

impl AxisGrid {
    /// How many times the whole line through `p` along the axis crosses the surface below
    /// `p` and above it.
    fn crossings(&self, vertices: &[DVec3], triangles: &[[u32; 3]], p: DVec3) -> [usize; 2] {
        let q = across(p, self.axis);
        let (lo, hi) = (self.min, self.min + self.cell * self.n as f64);
        if q.x < lo.x || q.y < lo.y || q.x > hi.x || q.y > hi.y {
            return [0, 0];
        }
        let (cx, cy) = self.cell_of(q);
        let k = cy * self.n + cx;
        let mut counts = [0, 0];
        let mut below = p;
        below[self.axis] = f64::NEG_INFINITY;
        for &t in &self.items[self.starts[k] as usize..self.starts[k + 1] as usize] {
            let corners = triangles[t as usize].map(|i| vertices[i as usize]);
            if crosses(corners, below, q, self.axis).is_some() {
                let above = crosses(corners, p, q, self.axis).is_some();
                counts[usize::from(above)] += 1;
            }
        }
        counts
    }
}

impl<'a> Inside<'a> {
    /// How many times the line through `p` along model axis `axis` (0, 1, 2 for x, y, z)
    /// crosses the surface before `p` and after it: whether a gap in a section at `p` is
    /// enclosed by the model along that axis.
    pub(crate) fn crossings(&self, p: DVec3, axis: usize) -> [usize; 2] {
        self.grids[axis].crossings(self.vertices, self.triangles, p)
    }

    /// The grids for this mesh.
    pub(crate) fn new(vertices: &'a [DVec3], triangles: &'a [[u32; 3]]) -> Self {
        Self {
            vertices,
            triangles,
            grids: [0, 1, 2].map(|axis| AxisGrid::new(vertices, triangles, axis)),
        }
    }

    /// Whether `p` is inside the model: at least two of the three rays say so.
    pub(crate) fn contains(&self, p: DVec3) -> bool {
        if self.triangles.is_empty() {
            return false;
        }
        let votes = self
            .grids
            .iter()
            .filter(|g| g.odd(self.vertices, self.triangles, p))
            .count();
        votes >= 2
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use platener_fixtures::samples::cuboid;

    fn indexed(tris: &[crate::read::Triangle]) -> (Vec<DVec3>, Vec<[u32; 3]>) {
        let vertices: Vec<DVec3> = tris.iter().flatten().copied().collect();
        let triangles = (0..tris.len() as u32).map(|t| [3 * t, 3 * t + 1, 3 * t + 2]).collect();
        (vertices, triangles)
    }

    #[test]
    fn where_two_shells_overlap_is_inside_and_a_cavity_is_not() {
        // Two overlapping cubes, each its own outward shell: x 0–20 and x 10–30.
        let mut tris = cuboid(DVec3::ZERO, DVec3::splat(20.0));
        tris.extend(cuboid(DVec3::new(10.0, 0.0, 0.0), DVec3::new(30.0, 20.0, 20.0)));
        // A cavity: a small cube wound inwards inside the first one's own part.
        let cavity: Vec<_> = cuboid(DVec3::new(2.0, 2.0, 2.0), DVec3::new(6.0, 6.0, 6.0))
            .into_iter()
            .map(|[a, b, c]| [a, c, b])
            .collect();
        tris.extend(cavity);
        let (v, t) = indexed(&tris);
        let inside = Inside::new(&v, &t);
        let at = |x: f64, y: f64, z: f64| inside.contains(DVec3::new(x, y, z) + DVec3::new(0.013, 0.017, 0.019));
        assert!(at(15.0, 10.0, 10.0), "in both");
        assert!(at(8.0, 10.0, 10.0) && at(25.0, 10.0, 10.0), "in one");
        assert!(!at(4.0, 4.0, 4.0), "in the cavity");
        assert!(!at(35.0, 10.0, 10.0) && !at(15.0, 25.0, 10.0), "outside");
    }
}
