//! Where a plate runs along a joint line: the stretches of the line (where two plates' middle
//! planes meet) that a plate passes through, or that one of its edges follows.
//!
//! Plates grown by a thickness share volume wherever they come within a thickness of each
//! other, also where they only touch at a vertex: on a low-poly ball each facet touches its
//! four diagonal neighbours so, and at shallow angles grown layers cross over many
//! millimetres. A joint needs more: both plates along the same stretch of the line, each
//! either passing through it or ending along it (an edge nearly parallel to it, near it).

use glam::{DVec2, DVec3};
use platener_geom::{GridError, Polygon};

use super::cap::middle_line;
use super::connect::{band, growth, into_plate};
use crate::plates::Plate;

/// Edges up to this many degrees off the line follow it (a trimmed plate's end follows its
/// neighbour's face exactly; a facet touching only at a vertex leaves at 30° or more).
const FOLLOW_DEG: f64 = 15.0;

/// Sorted, merged intervals.
pub(super) type Stretches = Vec<(f64, f64)>;

/// The stretches (positions along `axis`, in model coordinates) where `shape` (in `plate`'s
/// plane: its outline, or that with its other joints) runs along the line on which `plate`'s
/// and `other`'s middle planes meet, near the model point `near`. An edge follows the line
/// within [`growth`]: the width of `other`'s layer plus a thickness (plate finding trims a
/// plate back by up to about a thickness, a fillet leaves a gap, and where two plates were
/// laminated into one wall, the inner one ends a layer away).
pub(super) fn stretches(
    plate: &Plate,
    shape: &[Polygon],
    other: &Plate,
    axis: DVec3,
    near: DVec3,
) -> Result<Stretches, GridError> {
    let m = middle_line(plate, other, near);
    let f = &plate.frame;
    let at = |p: DVec2| axis.dot(f.to_model_2d(p));
    let line = f.to_2d(m);
    let across = {
        let d = DVec2::new(axis.dot(f.u), axis.dot(f.v)).normalize_or_zero();
        d.perp()
    };
    let mut out = Vec::new();
    // Through: the line inside the plate (a hairline strip along it).
    let into = into_plate(plate, axis, m);
    let c = into.dot(m);
    for polygon in shape {
        for piece in band(plate, polygon, into, c - 0.01, c + 0.01)? {
            out.push(span(piece.outer.iter().map(|p| at(*p))));
        }
    }
    // Along: edges nearly parallel to the line, within the other's layer.
    let reach = growth(plate, other);
    let follow = FOLLOW_DEG.to_radians().sin();
    for ring in shape.iter().flat_map(|p| std::iter::once(&p.outer).chain(&p.holes)) {
        for (i, &p) in ring.iter().enumerate() {
            let q = ring[(i + 1) % ring.len()];
            let len = p.distance(q);
            if len < 1e-9 || across.dot(q - p).abs() > follow * len {
                continue;
            }
            let (dp, dq) = (across.dot(p - line), across.dot(q - line));
            // The part of the edge within `reach` of the line.
            let (mut t0, mut t1) = (0.0_f64, 1.0_f64);
            if (dq - dp).abs() > 1e-12 {
                let (ta, tb) = ((-reach - dp) / (dq - dp), (reach - dp) / (dq - dp));
                t0 = t0.max(ta.min(tb));
                t1 = t1.min(ta.max(tb));
            } else if dp.abs() > reach {
                continue;
            }
            if t0 < t1 {
                out.push(span([at(p.lerp(q, t0)), at(p.lerp(q, t1))]));
            }
        }
    }
    Ok(merged(out))
}

/// The smallest interval holding all `values` (empty, lo > hi, when there are none).
pub(super) fn span(values: impl IntoIterator<Item = f64>) -> (f64, f64) {
    values
        .into_iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| (lo.min(v), hi.max(v)))
}

/// `intervals` sorted, with overlapping and touching ones merged.
fn merged(mut intervals: Vec<(f64, f64)>) -> Stretches {
    intervals.retain(|(lo, hi)| lo <= hi);
    intervals.sort_by(|x, y| x.0.total_cmp(&y.0));
    let mut out: Stretches = Vec::with_capacity(intervals.len());
    for (lo, hi) in intervals {
        match out.last_mut() {
            Some(last) if lo <= last.1 + 1e-6 => last.1 = last.1.max(hi),
            _ => out.push((lo, hi)),
        }
    }
    out
}

/// Where both `a` and `b` run: the overlaps of their stretches.
pub(super) fn common(a: &Stretches, b: &Stretches) -> Stretches {
    let mut out = Vec::new();
    for &(a0, a1) in a {
        for &(b0, b1) in b {
            let (lo, hi) = (a0.max(b0), a1.min(b1));
            if lo < hi {
                out.push((lo, hi));
            }
        }
    }
    merged(out)
}

/// The hull of the stretches that overlap `within`, clipped to it.
pub(super) fn hull_within(s: &Stretches, within: (f64, f64)) -> Option<(f64, f64)> {
    let (lo, hi) = s
        .iter()
        .map(|&(lo, hi)| (lo.max(within.0), hi.min(within.1)))
        .filter(|(lo, hi)| lo < hi)
        .fold((f64::INFINITY, f64::NEG_INFINITY), |acc, (lo, hi)| {
            (acc.0.min(lo), acc.1.max(hi))
        });
    (lo < hi).then_some((lo, hi))
}

#[cfg(test)]
mod tests {
    use super::*;

    use crate::joints::tests::plate;
    use platener_geom::Frame;
    use platener_geom::polygon::rect;

    /// Where a 10 × 10 floor (z 0–3) and a wall (x 10–13, 20 high) standing beside it over
    /// `y0`–`y1` both run along their line (which runs along y).
    fn floor_and_wall(y0: f64, y1: f64) -> Stretches {
        let floor = plate(
            Frame::on_plane(DVec3::ZERO, DVec3::Z),
            Polygon::new(rect(0.0, 0.0, 10.0, 10.0)),
        );
        let wall = plate(
            Frame::on_plane(DVec3::new(10.0, 0.0, 0.0), DVec3::X),
            Polygon::new(rect(y0, 0.0, y1, 20.0)),
        );
        let axis = floor.frame.n.cross(wall.frame.n);
        let near = DVec3::new(10.0, 5.0, 1.5);
        let of = |p: &Plate, q: &Plate| stretches(p, std::slice::from_ref(&p.polygon), q, axis, near).expect("grid");
        common(&of(&floor, &wall), &of(&wall, &floor))
    }

    #[test]
    fn plates_along_one_edge_meet_over_it_and_at_a_corner_not_at_all() {
        let edge = floor_and_wall(0.0, 10.0);
        assert_eq!(edge.len(), 1);
        assert!(
            (edge[0].0 - 0.0).abs() < 1e-3 && (edge[0].1 - 10.0).abs() < 1e-3,
            "{edge:?}"
        );
        let half = floor_and_wall(5.0, 30.0);
        assert!(
            (half[0].0 - 5.0).abs() < 1e-3 && (half[0].1 - 10.0).abs() < 1e-3,
            "{half:?}"
        );
        // Touching at the corner (10, 10) only.
        let corner = floor_and_wall(10.0, 20.0);
        assert!(corner.iter().all(|(lo, hi)| hi - lo < 1e-3), "{corner:?}");
    }

    #[test]
    fn overlapping_stretches_merge_and_common_keeps_overlaps() {
        let a = merged(vec![(3.0, 5.0), (0.0, 1.0), (0.5, 2.0)]);
        assert_eq!(a, vec![(0.0, 2.0), (3.0, 5.0)]);
        let b = vec![(1.5, 4.0)];
        assert_eq!(common(&a, &b), vec![(1.5, 2.0), (3.0, 4.0)]);
        assert_eq!(hull_within(&common(&a, &b), (1.8, 10.0)), Some((1.8, 4.0)));
        assert_eq!(hull_within(&a, (2.1, 2.9)), None);
    }
}
