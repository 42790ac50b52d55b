//! The model's thinnest wall, measured before welding: the weld must stay below it.
//!
//! A wall is material between two opposite faces: a face F facing +u and, behind it, a face G
//! facing −u whose projections along u overlap. Triangles are grouped into planes by their
//! rounded unit normal and offset (one sort, no hashing, so the result is deterministic);
//! planes on one line of directions are sorted by position, and each +u plane looks back for
//! the nearest −u plane it overlaps. Bevels do not fool it: a bevel's face is not
//! anti-parallel to the face across a wall, and two bevels that are anti-parallel lie on
//! opposite sides of the part, far apart.
//!
//! Winding is taken as the file gives it (orientation is fixed later, in `mesh`); an
//! inside-out model measures its gaps instead of its walls.

use glam::{DVec2, DVec3};
use platener_geom::Frame;

/// Normals are rounded to this (about 0.006°) to find faces of one plane direction.
const NORMAL_STEP: f64 = 1e-4;
/// Plane offsets are rounded to this (mm) to group triangles of one plane.
const OFFSET_STEP: f64 = 1e-3;
/// Faces closer than this (mm) are one surface stored twice, not a wall.
const MIN_WALL: f64 = 1e-3;
/// Projections must overlap by more than this (mm) across every separating direction.
const OVERLAP: f64 = 1e-4;

/// Triangles of one plane.
struct Plane {
    /// Rounded direction of the line of normals (the sign removed).
    line: [i64; 3],
    /// +1 when the faces look along the line's direction, −1 against it.
    side: i8,
    /// Position along the line's direction (mm).
    at: f64,
    /// The triangles, projected across the line's direction.
    tris: Vec<[DVec2; 3]>,
    lo: DVec2,
    hi: DVec2,
}

/// The thinnest wall of `triangles` in mm, or `None` when no two opposite faces overlap.
pub fn thinnest_wall(triangles: &[[DVec3; 3]]) -> Option<f64> {
    let planes = planes(triangles);
    let mut best = f64::INFINITY;
    let mut start = 0;
    while start < planes.len() {
        let line = planes[start].line;
        let end = start + planes[start..].iter().take_while(|p| p.line == line).count();
        best = best.min(thinnest_on_line(&planes[start..end], best));
        start = end;
    }
    best.is_finite().then_some(best)
}

/// Planes of one line of directions, sorted by position: the thinnest wall below `best`.
fn thinnest_on_line(planes: &[Plane], mut best: f64) -> f64 {
    for (i, front) in planes.iter().enumerate().filter(|(_, p)| p.side > 0) {
        for back in planes[..i].iter().rev() {
            let thickness = front.at - back.at;
            if thickness >= best {
                break;
            }
            if back.side < 0 && thickness > MIN_WALL && overlap(front, back) {
                best = thickness;
                break;
            }
        }
    }
    best
}

/// Groups `triangles` into planes, sorted by line, then position, then side.
fn planes(triangles: &[[DVec3; 3]]) -> Vec<Plane> {
    // (line, side, rounded position, position, triangle)
    let mut keyed: Vec<([i64; 3], i8, i64, f64, usize)> = Vec::with_capacity(triangles.len());
    for (i, t) in triangles.iter().enumerate() {
        let Some(n) = (t[1] - t[0]).cross(t[2] - t[0]).try_normalize() else {
            continue;
        };
        let q = n.to_array().map(|c| (c / NORMAL_STEP).round() as i64);
        let first = q.iter().copied().find(|&c| c != 0).unwrap_or(0);
        let side: i8 = if first < 0 { -1 } else { 1 };
        let line = q.map(|c| c * i64::from(side));
        let at = (n * f64::from(side)).dot((t[0] + t[1] + t[2]) / 3.0);
        keyed.push((line, side, (at / OFFSET_STEP).round() as i64, at, i));
    }
    keyed.sort_unstable_by_key(|a| (a.0, a.2, a.1, a.4));
    let mut planes: Vec<Plane> = Vec::new();
    for run in keyed.chunk_by(|a, b| (a.0, a.1, a.2) == (b.0, b.1, b.2)) {
        let line = run[0].0;
        let dir = DVec3::from_array(line.map(|c| c as f64)).normalize();
        let frame = Frame::on_plane(DVec3::ZERO, dir);
        let tris: Vec<[DVec2; 3]> = run.iter().map(|k| triangles[k.4].map(|p| frame.to_2d(p))).collect();
        let (lo, hi) = bounds(tris.iter().flatten());
        planes.push(Plane {
            line,
            side: run[0].1,
            at: run.iter().map(|k| k.3).sum::<f64>() / run.len() as f64,
            tris,
            lo,
            hi,
        });
    }
    planes
}

fn bounds<'a>(points: impl Iterator<Item = &'a DVec2>) -> (DVec2, DVec2) {
    platener_geom::boxes::bounds2(points.copied())
}

fn boxes_overlap(a: (DVec2, DVec2), b: (DVec2, DVec2)) -> bool {
    a.0.x + OVERLAP < b.1.x && b.0.x + OVERLAP < a.1.x && a.0.y + OVERLAP < b.1.y && b.0.y + OVERLAP < a.1.y
}

/// Whether some triangle of `a` and some triangle of `b` overlap in projection.
fn overlap(a: &Plane, b: &Plane) -> bool {
    if !boxes_overlap((a.lo, a.hi), (b.lo, b.hi)) {
        return false;
    }
    let near = |tris: &[[DVec2; 3]], other: &Plane| -> Vec<([DVec2; 3], (DVec2, DVec2))> {
        tris.iter()
            .map(|t| (*t, bounds(t.iter())))
            .filter(|(_, bx)| boxes_overlap(*bx, (other.lo, other.hi)))
            .collect()
    };
    let (ta, tb) = (near(&a.tris, b), near(&b.tris, a));
    ta.iter().any(|(s, sb)| {
        tb.iter()
            .any(|(t, tbx)| boxes_overlap(*sb, *tbx) && triangles_overlap(s, t))
    })
}

/// Separating-axis test of two triangles' interiors (overlap deeper than [`OVERLAP`]).
fn triangles_overlap(a: &[DVec2; 3], b: &[DVec2; 3]) -> bool {
    let separated_by = |tri: &[DVec2; 3]| {
        (0..3).any(|i| {
            let e = tri[(i + 1) % 3] - tri[i];
            let axis = DVec2::new(-e.y, e.x);
            let len = axis.length();
            if len == 0.0 {
                return false;
            }
            let proj = |t: &[DVec2; 3]| {
                let v = t.map(|p| axis.dot(p) / len);
                (v[0].min(v[1]).min(v[2]), v[0].max(v[1]).max(v[2]))
            };
            let ((a0, a1), (b0, b1)) = (proj(a), proj(b));
            a1 <= b0 + OVERLAP || b1 <= a0 + OVERLAP
        })
    };
    !separated_by(a) && !separated_by(b)
}
