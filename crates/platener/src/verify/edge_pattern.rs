//! A finger joint's pattern along each of its two parts' edges, read back from the parts'
//! outlines and placements alone: what a finished plan (plan.json) has, so that `verify`
//! and the `joints` step read it the same way.
//!
//! The joint's line is where the two parts' mid-planes cross. On it, a part's material is its
//! tabs (at a corner the line runs through the middle of the square both plates reach into;
//! at a T, through the middle of the slots). The joint's stretch is where both parts reach
//! along it: each part's outline is read on two lines parallel to the joint's, just past the
//! partner's slab on either side (a part ending at the joint has material on one of them, a
//! part passing through on both), and the stretch is where both parts have some.

use glam::{DVec2, DVec3};
use platener_geom::Polygon;
use platener_geom::slab::Slab;

/// Patterns fit each other when every boundary between tab and notch lies within this (mm)
/// of the other's, once slid along by at most [`LENGTH_TOL`] (the tolerance).
pub const PATTERN_TOL: f64 = 0.2;
/// Edges whose lengths differ by more than this (mm) do not fit each other.
pub const LENGTH_TOL: f64 = 0.5;
/// Plates closer to parallel than this (the sine of the angle, about 3°) do not meet at an
/// edge: stacked layers, details glued face to face.
const MIN_SIN: f64 = 0.05;
/// Material or gaps along an edge shorter than this (mm) are grid noise.
const NOISE: f64 = 0.05;
/// How far past the partner's slab (mm) a part's outline is read for the joint's stretch.
const PAST_SLAB: f64 = 0.5;
/// Joints shorter than this (mm) are not read.
const MIN_LENGTH: f64 = 1.0;

/// A part's material along a joint's stretch: where it has material (its tabs), measured
/// from the stretch's start, ascending.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Pattern {
    /// The stretch's length, mm.
    pub length: f64,
    /// The tabs, `(from, to)` in mm from the stretch's start.
    pub tabs: Vec<(f64, f64)>,
}

/// One joint as its two parts' solids have it.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct JointEdges {
    /// Each part's pattern, in the order the parts were given.
    pub sides: [Pattern; 2],
    /// Each part's edge, in its own 2D frame: the stretch on the joint's line, from its
    /// start to its end.
    pub segments: [[DVec2; 2]; 2],
}

/// The joint's line seen in one part's plane: a point (the line's origin) and the direction.
struct PlaneLine {
    at: DVec2,
    along: DVec2,
}

impl PlaneLine {
    fn of(slab: &Slab, origin: DVec3, axis: DVec3) -> Self {
        let f = &slab.frame;
        Self {
            at: f.to_2d(origin),
            along: DVec2::new(axis.dot(f.u), axis.dot(f.v)).normalize_or_zero(),
        }
    }

    /// Where the line, moved `by` mm across itself, runs through `polygon`: intervals of the
    /// parameter along it.
    fn inside(&self, polygon: &Polygon, by: f64) -> Vec<(f64, f64)> {
        crossings(polygon, self.at + self.along.perp() * by, self.along)
    }

    fn point(&self, s: f64) -> DVec2 {
        self.at + self.along * s
    }
}

/// The joint between the parts `a` and `b` (one slab each), or `None` when they are (nearly)
/// parallel or reach along their common line for less than [`MIN_LENGTH`].
pub(crate) fn joint_edges(a: &Slab, b: &Slab) -> Option<JointEdges> {
    let (na, nb) = (a.frame.n, b.frame.n);
    let cross = na.cross(nb);
    let sin = cross.length();
    if sin < MIN_SIN {
        return None;
    }
    // The point of both mid-planes nearest the model's origin, and the line's direction.
    let ca = na.dot(a.frame.origin) + a.thickness / 2.0;
    let cb = nb.dot(b.frame.origin) + b.thickness / 2.0;
    let origin = (nb.cross(cross) * ca + cross.cross(na) * cb) / (sin * sin);
    let axis = cross / sin;
    let cos = na.dot(nb).abs();
    let lines = [PlaneLine::of(a, origin, axis), PlaneLine::of(b, origin, axis)];
    // Half the width of the partner's slab seen in each part's plane, and a little more.
    let past = [
        (b.thickness + cos * a.thickness) / (2.0 * sin) + PAST_SLAB,
        (a.thickness + cos * b.thickness) / (2.0 * sin) + PAST_SLAB,
    ];
    let slabs = [a, b];
    let reach = |i: usize| {
        let mut both = lines[i].inside(&slabs[i].polygon, past[i]);
        both.extend(lines[i].inside(&slabs[i].polygon, -past[i]));
        hull(&both)
    };
    let (ra, rb) = (reach(0)?, reach(1)?);
    let span = (ra.0.max(rb.0), ra.1.min(rb.1));
    if span.1 - span.0 < MIN_LENGTH {
        return None;
    }
    let side = |i: usize| Pattern::clipped(&lines[i].inside(&slabs[i].polygon, 0.0), span);
    Some(JointEdges {
        sides: [side(0), side(1)],
        segments: [0, 1].map(|i| [lines[i].point(span.0), lines[i].point(span.1)]),
    })
}

/// Where the line through `at` along the unit `along` runs inside `polygon` (outer ring
/// less holes): intervals of the parameter along it, ascending. A vertex on the line counts
/// on the side it lies on by the half-open rule, so each ring is crossed an even number of
/// times.
fn crossings(polygon: &Polygon, at: DVec2, along: DVec2) -> Vec<(f64, f64)> {
    let across = along.perp();
    let mut hits = Vec::new();
    for ring in std::iter::once(&polygon.outer).chain(&polygon.holes) {
        for (k, &p) in ring.iter().enumerate() {
            let q = ring[(k + 1) % ring.len()];
            let (dp, dq) = (across.dot(p - at), across.dot(q - at));
            if (dp >= 0.0) != (dq >= 0.0) {
                let hit = p + (q - p) * (dp / (dp - dq));
                hits.push(along.dot(hit - at));
            }
        }
    }
    hits.sort_by(f64::total_cmp);
    hits.chunks_exact(2).map(|c| (c[0], c[1])).collect()
}

/// The smallest interval holding all of `intervals`, if there are any.
fn hull(intervals: &[(f64, f64)]) -> Option<(f64, f64)> {
    intervals.iter().copied().reduce(|x, y| (x.0.min(y.0), x.1.max(y.1)))
}

impl Pattern {
    /// `intervals` (ascending) within `span`, from its start, without gaps or pieces of
    /// grid noise.
    fn clipped(intervals: &[(f64, f64)], span: (f64, f64)) -> Self {
        let mut tabs: Vec<(f64, f64)> = Vec::new();
        for &(s0, s1) in intervals {
            let (s0, s1) = (s0.max(span.0) - span.0, s1.min(span.1) - span.0);
            if s1 - s0 < NOISE {
                continue;
            }
            match tabs.last_mut() {
                Some(last) if s0 - last.1 < NOISE => last.1 = s1,
                _ => tabs.push((s0, s1)),
            }
        }
        Self {
            length: span.1 - span.0,
            tabs,
        }
    }

    /// The same tabs seen from the stretch's other end.
    pub fn reversed(&self) -> Self {
        Self {
            length: self.length,
            tabs: self
                .tabs
                .iter()
                .rev()
                .map(|&(s0, s1)| (self.length - s1, self.length - s0))
                .collect(),
        }
    }

    /// Whether this edge's tabs are `other`'s (within [`PATTERN_TOL`], slid by at most
    /// [`LENGTH_TOL`]; ends of the stretch match ends): a part with this edge goes where
    /// the part with `other` goes.
    pub fn matches(&self, other: &Pattern) -> bool {
        if (self.length - other.length).abs() > LENGTH_TOL || self.tabs.len() != other.tabs.len() {
            return false;
        }
        let mut shift = (f64::INFINITY, f64::NEG_INFINITY);
        for (mine, theirs) in self.tabs.iter().zip(&other.tabs) {
            for (x, y, lx, ly) in [
                (mine.0, theirs.0, 0.0, 0.0),
                (mine.1, theirs.1, self.length, other.length),
            ] {
                // A tab that reaches an end of one stretch reaches that end of the other.
                let (at_x, at_y) = ((x - lx).abs() < PATTERN_TOL, (y - ly).abs() < PATTERN_TOL);
                if at_x != at_y {
                    return false;
                }
                if !at_x {
                    shift = (shift.0.min(x - y), shift.1.max(x - y));
                }
            }
        }
        shift.0 > shift.1 || (shift.1 - shift.0 <= 2.0 * PATTERN_TOL && (shift.0 + shift.1).abs() <= 2.0 * LENGTH_TOL)
    }
}
