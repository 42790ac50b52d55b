//! Whether a part, moved along a straight line, runs into another: the blocking relation of
//! assembly planning (the non-directional blocking graph of Wilson and Latombe, "Geometric
//! reasoning about mechanical assembly", 1994, tested here for a few directions only).
//!
//! The moving part stands for its interior sample points (a grid half its thickness apart,
//! only where they can reach the other part's box). Each point's ray, from its place along the direction of motion, is cast
//! against every piece of the other part shrunk by [`SLACK`]: parts of a plan touch face to
//! face and must slide along each other freely, while a finger or tab in the way overlaps
//! the sweep by its whole width. A blocking overlap narrower than the sampling step (half a
//! thickness) may be missed; the order's tests move each part in along its direction and
//! measure the overlap independently.

use glam::{DVec2, DVec3};
use platener_geom::Polygon;
use platener_geom::slab::Slab;

use super::Solid;

/// Overlap shallower than this (mm) is touching, not blocking.
pub(crate) const SLACK: f64 = 0.05;

/// A direction component under this counts as zero: the motion is parallel to that axis.
const PARALLEL: f64 = 1e-12;

/// Fraction of a step the sampling grid is shifted by (1/√2 − 0.5): sample points never lie
/// exactly on another part's face, which CAD models put on round numbers.
const SHIFT: f64 = 0.207_106_781_186_547_5;

/// Whether moving `part` from its place along the unit vector `away`, any distance, sweeps
/// some point of it through `other`'s interior deeper than [`SLACK`]. Points already inside
/// `other` in place (a JimJoint's barb, meant to overlap) are left out: the motion did not
/// cause that overlap.
pub(crate) fn blocks(part: &Solid, away: DVec3, other: &Solid) -> bool {
    let shrunk = (other.lo + SLACK, other.hi - SLACK);
    if sweep_interval((part.lo, part.hi), away, shrunk).is_none() {
        return false;
    }
    let mut points = points_near(part, shadow((part.lo, part.hi), away, shrunk));
    points.retain(|p| !(other.near_box(*p, 0.0) && other.contains(*p)));
    // Points on one line along the motion sweep one ray: the one farthest back covers the
    // others (a shaft rising through a stack of layers is columns of such points).
    let line = |p: &DVec3| {
        let q = (*p - away * p.dot(away)) * 1e6;
        [q.x.round() as i64, q.y.round() as i64, q.z.round() as i64]
    };
    points.sort_by_cached_key(|p| (line(p), (p.dot(away) * 1e6).round() as i64));
    points.dedup_by_key(|p| line(p));
    let mut cuts = Vec::new();
    other.pieces.iter().any(|piece| {
        let (lo, hi) = piece.model_bounds();
        let (lo, hi) = (lo + SLACK, hi - SLACK);
        points.iter().any(|&p| {
            sweep_interval((p, p), away, (lo, hi)).is_some_and(|span| ray_enters(piece, p, away, span, &mut cuts))
        })
    })
}

/// The part of the box `within` whose points can reach the box `target` moving along `dir`: a
/// box holding every such point (exact for a direction along an axis).
fn shadow(within: (DVec3, DVec3), dir: DVec3, target: (DVec3, DVec3)) -> (DVec3, DVec3) {
    let (mut lo, mut hi) = within;
    for k in 0..3 {
        if dir[k] < PARALLEL {
            lo[k] = lo[k].max(target.0[k]);
        }
        if dir[k] > -PARALLEL {
            hi[k] = hi[k].min(target.1[k]);
        }
    }
    (lo, hi)
}

/// Interior sample points of `solid` in the model box `near`: on a grid half the thickness
/// apart in each piece's plane (between 0.5 and 2 mm, so every finger and tab, at least a
/// thickness wide, holds several), at the middle of each half of the thickness. Rows of the
/// grid are filled between the outline's crossings (even–odd, so holes stay empty), and only
/// rows and columns whose local box meets `near` are visited: a part tested against a thin
/// neighbour samples only the strip that can reach it.
fn points_near(solid: &Solid, near: (DVec3, DVec3)) -> Vec<DVec3> {
    let step = (solid.thickness / 2.0).clamp(0.5, 2.0);
    let layers = ((solid.thickness / step).ceil() as usize).max(1);
    let mut out = Vec::new();
    let mut xs = Vec::new();
    for piece in &solid.pieces {
        let dz = piece.thickness / layers as f64;
        let (lo, hi) = piece.polygon.bounds();
        let (a, b) = platener_geom::boxes::bounds2((0..8).map(|k| {
            let corner = DVec3::new(
                if k & 1 == 0 { near.0.x } else { near.1.x },
                if k & 2 == 0 { near.0.y } else { near.1.y },
                if k & 4 == 0 { near.0.z } else { near.1.z },
            );
            piece.frame.to_local(corner).truncate()
        }));
        let (a, b) = (a.max(lo), b.min(hi));
        if a.x > b.x || a.y > b.y {
            continue;
        }
        let first_row = ((a.y - lo.y) / step - 0.5 + SHIFT).floor().max(0.0) as usize;
        let mut row = first_row;
        loop {
            let y = lo.y + (row as f64 + 0.5 - SHIFT) * step;
            if y > b.y {
                break;
            }
            row += 1;
            if y < a.y {
                continue;
            }
            xs.clear();
            for ring in std::iter::once(&piece.polygon.outer).chain(&piece.polygon.holes) {
                for (i, p) in ring.iter().enumerate() {
                    let q = ring[(i + 1) % ring.len()];
                    if (p.y > y) != (q.y > y) {
                        xs.push(p.x + (y - p.y) * (q.x - p.x) / (q.y - p.y));
                    }
                }
            }
            xs.sort_by(f64::total_cmp);
            for span in xs.chunks_exact(2) {
                let (x0, x1) = (span[0].max(a.x), span[1].min(b.x));
                let mut col = ((x0 - lo.x) / step - 0.5 - SHIFT).ceil().max(0.0) as usize;
                loop {
                    let x = lo.x + (col as f64 + 0.5 + SHIFT) * step;
                    if x > x1 {
                        break;
                    }
                    col += 1;
                    for k in 0..layers {
                        out.push(piece.frame.to_model(DVec3::new(x, y, (k as f64 + 0.5) * dz)));
                    }
                }
            }
        }
    }
    out
}

/// The interval of `t ≥ 0` over which the box `a` moved by `t · dir` overlaps the box `b`
/// (open boxes), if any.
fn sweep_interval(a: (DVec3, DVec3), dir: DVec3, b: (DVec3, DVec3)) -> Option<(f64, f64)> {
    let (mut t0, mut t1) = (0.0f64, f64::INFINITY);
    for k in 0..3 {
        let d = dir[k];
        if d.abs() < PARALLEL {
            if a.0[k] >= b.1[k] || a.1[k] <= b.0[k] {
                return None;
            }
            continue;
        }
        let (x, y) = ((b.0[k] - a.1[k]) / d, (b.1[k] - a.0[k]) / d);
        t0 = t0.max(x.min(y));
        t1 = t1.min(x.max(y));
    }
    (t0 < t1).then_some((t0, t1))
}

/// Whether the ray `p + t · away`, `t` in `span`, passes through `piece`'s interior deeper
/// than [`SLACK`] (through its thickness and across its outline). `cuts` is scratch space.
fn ray_enters(piece: &Slab, p: DVec3, away: DVec3, span: (f64, f64), cuts: &mut Vec<f64>) -> bool {
    let f = &piece.frame;
    let l = f.to_local(p);
    let d = DVec3::new(f.u.dot(away), f.v.dot(away), f.n.dot(away));
    let (mut t0, mut t1) = span;
    let (z0, z1) = (SLACK, piece.thickness - SLACK);
    if d.z.abs() < PARALLEL {
        if l.z <= z0 || l.z >= z1 {
            return false;
        }
    } else {
        let (x, y) = ((z0 - l.z) / d.z, (z1 - l.z) / d.z);
        t0 = t0.max(x.min(y));
        t1 = t1.min(x.max(y));
    }
    if t0 >= t1 {
        return false;
    }
    let (a, b) = (l.truncate() + d.truncate() * t0, l.truncate() + d.truncate() * t1);
    segment_enters(&piece.polygon, a, b, cuts)
}

/// Whether the segment `a`–`b` has a point inside `polygon` farther than [`SLACK`] from its
/// boundary. The segment is cut where it crosses the boundary; each stretch between two cuts
/// is inside or outside as a whole and is judged by its middle (inside a convex stretch the
/// middle is at least half as deep as the deepest point).
fn segment_enters(polygon: &Polygon, a: DVec2, b: DVec2, cuts: &mut Vec<f64>) -> bool {
    let ab = b - a;
    let (lo, hi) = (a.min(b), a.max(b));
    cuts.clear();
    cuts.extend([0.0, 1.0]);
    for ring in std::iter::once(&polygon.outer).chain(&polygon.holes) {
        for (i, &p) in ring.iter().enumerate() {
            let q = ring[(i + 1) % ring.len()];
            if p.x.max(q.x) < lo.x || p.x.min(q.x) > hi.x || p.y.max(q.y) < lo.y || p.y.min(q.y) > hi.y {
                continue;
            }
            let e = q - p;
            let den = ab.perp_dot(e);
            // Parallel: no crossing (a stretch along an edge is judged by its depth, ~0).
            if den.abs() < PARALLEL {
                continue;
            }
            let s = (p - a).perp_dot(e) / den;
            let r = (p - a).perp_dot(ab) / den;
            if s > 0.0 && s < 1.0 && (0.0..=1.0).contains(&r) {
                cuts.push(s);
            }
        }
    }
    cuts.sort_by(f64::total_cmp);
    cuts.windows(2).any(|w| {
        let m = a + ab * ((w[0] + w[1]) / 2.0);
        polygon.contains(m) && polygon.boundary_distance_squared(m) > SLACK * SLACK
    })
}

#[cfg(test)]
mod tests {
    use glam::{DVec2, DVec3};
    use platener_geom::slab::Slab;
    use platener_geom::{Frame, Polygon};

    use super::{Solid, blocks};

    fn plate(id: u32, origin: DVec3, n: DVec3, w: f64, h: f64) -> Solid {
        let polygon = Polygon::new(vec![
            DVec2::ZERO,
            DVec2::new(w, 0.0),
            DVec2::new(w, h),
            DVec2::new(0.0, h),
        ]);
        Solid::from_slab(
            id,
            Slab {
                frame: Frame::on_plane(origin, n),
                polygon,
                thickness: 3.0,
            },
        )
    }

    /// A plate lying on another slides off sideways and lifts off, but cannot go down.
    #[test]
    fn a_plate_on_a_plate_is_blocked_only_downwards() {
        let floor = plate(1, DVec3::ZERO, DVec3::Z, 50.0, 50.0);
        let top = plate(2, DVec3::new(10.0, 10.0, 3.0), DVec3::Z, 20.0, 20.0);
        assert!(blocks(&top, -DVec3::Z, &floor));
        for free in [DVec3::Z, DVec3::X, -DVec3::X, DVec3::Y, -DVec3::Y] {
            assert!(!blocks(&top, free, &floor), "{free}");
        }
        // Tilted down by 10°, the sweep dives into the floor.
        let tilted = DVec3::new(10f64.to_radians().cos(), 0.0, -10f64.to_radians().sin());
        assert!(blocks(&top, tilted, &floor));
    }

    /// A peg in a hole of a plate comes out along the hole's axis only.
    #[test]
    fn a_peg_leaves_its_hole_along_its_axis() {
        let mut board = plate(1, DVec3::ZERO, DVec3::Z, 40.0, 40.0);
        let hole = vec![
            DVec2::new(15.0, 18.5),
            DVec2::new(15.0, 21.5),
            DVec2::new(25.0, 21.5),
            DVec2::new(25.0, 18.5),
        ];
        board.pieces[0].polygon.holes.push(hole);
        // The peg: a 10 × 20 plate standing in the hole, normal +y (its u is −x, so it
        // starts at x = 25), from z = −5 to 15.
        let peg = plate(2, DVec3::new(25.0, 18.5, -5.0), DVec3::Y, 10.0, 20.0);
        assert!((peg.frame().u + DVec3::X).length() < 1e-9);
        assert!(!blocks(&peg, DVec3::Z, &board));
        assert!(!blocks(&peg, -DVec3::Z, &board));
        for side in [DVec3::X, -DVec3::X, DVec3::Y, -DVec3::Y] {
            assert!(blocks(&peg, side, &board), "{side}");
        }
    }
}
