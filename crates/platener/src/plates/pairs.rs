//! Finding pairs of parallel, opposite-facing shapes without comparing all pairs.
//!
//! Normals are folded onto one hemisphere and hashed into cells as wide as the chord of the
//! parallel angle, so every parallel neighbour is in one of the 27 cells around a normal (or
//! around its mirror, for normals near the fold). Within a cell shapes are sorted by plane
//! offset, so only planes within the search distance are looked at: a model of 10 000 shapes
//! needs a few thousand comparisons, not fifty million.

use glam::DVec3;
use platener_geom::weld::CellMap;

use crate::shapes::Shape;

/// Two shapes on parallel planes with opposite normals, and how they face.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Pair {
    /// The shapes, `a < b`.
    pub a: u32,
    /// See `a`.
    pub b: u32,
    /// Distance between the planes (mm, ≥ 0).
    pub distance: f64,
    /// Whether the normals face apart (material between: a plate) rather than towards each
    /// other (empty space between: a slot or a gap).
    pub apart: bool,
}

fn fold(n: DVec3) -> DVec3 {
    let up = if n.z.abs() > 1e-12 {
        n.z > 0.0
    } else if n.y.abs() > 1e-12 {
        n.y > 0.0
    } else {
        n.x > 0.0
    };
    if up { n } else { -n }
}

/// Every pair of shapes whose normals are within `angle` (radians) of opposite and whose
/// planes are at most `max_distance` apart. `center` is subtracted from positions first so
/// that plane offsets stay small.
pub(super) fn opposite_pairs(shapes: &[Shape], angle: f64, max_distance: f64, center: DVec3) -> Vec<Pair> {
    let cell = 2.0 * (angle / 2.0).sin() * 1.0001 + 1e-12;
    let key = |c: DVec3| {
        [
            (c.x / cell).floor() as i64,
            (c.y / cell).floor() as i64,
            (c.z / cell).floor() as i64,
        ]
    };
    let folded: Vec<(DVec3, f64)> = shapes
        .iter()
        .map(|s| {
            let c = fold(s.frame.n);
            (c, c.dot(s.frame.origin - center))
        })
        .collect();
    let max_reach = shapes
        .iter()
        .map(|s| (s.frame.origin - center).length())
        .fold(0.0, f64::max);
    // Offsets along normals up to `cell` apart differ by up to cell·|p| for the same point.
    let window = max_distance + cell * max_reach + 1e-9;
    let mut cells: CellMap<[i64; 3], Vec<(f64, u32)>> = CellMap::default();
    for (i, (c, o)) in folded.iter().enumerate() {
        cells.entry(key(*c)).or_default().push((*o, i as u32));
    }
    for list in cells.values_mut() {
        list.sort_by(|x, y| x.0.total_cmp(&y.0).then(x.1.cmp(&y.1)));
    }
    let cos_max = angle.cos();
    let mut pairs = Vec::new();
    for (i, shape) in shapes.iter().enumerate() {
        let (c, o) = folded[i];
        for (sign, axis) in [(1.0, c), (-1.0, -c)] {
            let k = key(axis);
            for dx in -1..=1 {
                for dy in -1..=1 {
                    for dz in -1..=1 {
                        let Some(list) = cells.get(&[k[0] + dx, k[1] + dy, k[2] + dz]) else {
                            continue;
                        };
                        // Offsets in this cell are along ±c: compare in c's sense.
                        let target = sign * o;
                        let start = list.partition_point(|e| e.0 < target - window);
                        for &(_, j) in list[start..].iter().take_while(|e| e.0 <= target + window) {
                            if j as usize <= i {
                                continue;
                            }
                            let other = &shapes[j as usize];
                            let (n, m) = (shape.frame.n, other.frame.n);
                            if n.dot(m) > -cos_max {
                                continue;
                            }
                            let avg = (n - m).normalize();
                            let d = (other.frame.origin - shape.frame.origin).dot(avg);
                            if d.abs() <= max_distance {
                                pairs.push(Pair {
                                    a: i as u32,
                                    b: j,
                                    distance: d.abs(),
                                    apart: d < 0.0,
                                });
                            }
                        }
                    }
                }
            }
        }
    }
    // A pair can be found through both the cell and its mirror near the fold.
    pairs.sort_by_key(|p| (p.a, p.b));
    pairs.dedup_by(|x, y| (x.a, x.b) == (y.a, y.b));
    pairs
}
