//! Three or more plates meeting on one line (a "Y", a wall under a roof ridge).
//!
//! Pair by pair, each plate grows across the whole of its partner's slab. Where only two
//! plates meet that is the corner; on a shared line it reaches past the line, out of the model
//! and through the third plate, and the partners it beats give up columns nobody fills. And
//! fingers cut pair by pair can leave one plate winning no finger (it only butts against the
//! others) or three plates each beating the next (all three give way, leaving a hole).
//!
//! So here each plate's reach past the line ends where its thickness leaves the other plates'
//! arms (the model near the line, seen as the union of the arms' half slabs), and
//! [`fingers`](super::fingers) cuts all connections of a line in one row of fingers in which
//! the plates take turns: in each finger one plate takes the whole junction.

use glam::{DVec2, DVec3};
use platener_geom::Polygon;

use super::connect::{Overlap, at, extent, into_plate};
use crate::assembly::UnionFind;
use crate::plates::Plate;

/// The plates meeting on one line and their connections' shared extent along it.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct Junction {
    /// The plates, in the order they take turns, ascending.
    pub plates: Vec<usize>,
    /// The line's direction (a connection's own axis may point the other way).
    pub axis: DVec3,
    /// Extent along `axis` covered by the line's connections.
    pub range: (f64, f64),
}

impl Junction {
    /// Which of `a` and `b` owns finger `s`: the one whose turn comes first.
    pub fn owner(&self, s: usize, a: usize, b: usize) -> usize {
        let k = self.plates.len();
        let rank = |p: usize| {
            let i = self.plates.iter().position(|&q| q == p).unwrap_or(0);
            (i + k - s % k) % k
        };
        if rank(a) <= rank(b) { a } else { b }
    }
}

/// Shared stretches (indices into the raw list) that lie on one line with three or more plates.
pub(super) struct Line {
    pub plates: Vec<usize>,
    pub members: Vec<usize>,
    /// A point on the line: the mean of the stretches' centres.
    pub center: DVec3,
    pub axis: DVec3,
    /// Extent along `axis` of all members.
    pub range: (f64, f64),
}

/// Groups the raw stretches that run along one line (parallel axes, less than `near` apart,
/// overlapping extents) and keeps the groups of three or more plates that all meet each other.
pub(super) fn lines(plates: &[Plate], raw: &[Overlap], near: f64) -> Vec<Line> {
    let cos_max = 1f64.to_radians().cos();
    let centres: Vec<DVec3> = raw.iter().map(|r| r.centre(plates)).collect();
    let ranges: Vec<(f64, f64)> = raw.iter().map(|r| extent(&plates[r.a], &r.in_a, r.axis)).collect();
    let mut groups_of = UnionFind::new(raw.len());
    for i in 0..raw.len() {
        for j in i + 1..raw.len() {
            let (ri, rj) = (&raw[i], &raw[j]);
            let dot = ri.axis.dot(rj.axis);
            if dot.abs() < cos_max {
                continue;
            }
            let off = centres[j] - centres[i];
            if (off - ri.axis * off.dot(ri.axis)).length() > near {
                continue;
            }
            // rj's extent measured along ri's axis.
            let rj_range = flipped_unless(ranges[j], dot > 0.0);
            if rj_range.0 < ranges[i].1 && ranges[i].0 < rj_range.1 {
                groups_of.join(i, j);
            }
        }
    }
    let mut groups: std::collections::BTreeMap<usize, Vec<usize>> = std::collections::BTreeMap::new();
    for i in 0..raw.len() {
        groups.entry(groups_of.root(i)).or_default().push(i);
    }
    groups
        .into_values()
        .filter_map(|members| {
            let mut ps: Vec<usize> = members.iter().flat_map(|&i| [raw[i].a, raw[i].b]).collect();
            ps.sort_unstable();
            ps.dedup();
            // Every two of the plates meet here. Otherwise it is not one line of plates but,
            // say, a laminated wall (parallel plates a layer apart, never connected) meeting a
            // neighbour, or a board split in two that the plates step could not rejoin.
            let meet = |p: usize, q: usize| members.iter().any(|&i| (raw[i].a, raw[i].b) == (p.min(q), p.max(q)));
            let all_meet = ps
                .iter()
                .enumerate()
                .all(|(i, &p)| ps[i + 1..].iter().all(|&q| meet(p, q)));
            if ps.len() < 3 || !all_meet {
                return None;
            }
            let axis = raw[members[0]].axis;
            let center = members.iter().map(|&i| centres[i]).sum::<DVec3>() / members.len() as f64;
            let range = members.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |r, &i| {
                let (lo, hi) = flipped_unless(ranges[i], raw[i].axis.dot(axis) > 0.0);
                (r.0.min(lo), r.1.max(hi))
            });
            Some(Line {
                plates: ps,
                members,
                center,
                axis,
                range,
            })
        })
        .collect()
}

/// The point of `plate`'s middle plane nearest `p`.
fn on_middle(plate: &Plate, p: DVec3) -> DVec3 {
    p - plate.frame.n * plate.frame.n.dot(p - at(plate, DVec2::ZERO))
}

/// An extent `range` measured along an axis, measured along a parallel one instead (`same_way`
/// when they point the same way).
pub(super) fn flipped_unless(range: (f64, f64), same_way: bool) -> (f64, f64) {
    if same_way { range } else { (-range.1, -range.0) }
}

/// Whether `plate` goes on past the line (it passes through, as at a T) instead of ending there.
pub(super) fn passes(plate: &Plate, line: &Line) -> bool {
    let d = into_plate(plate, line.axis, line.center);
    let behind = plate
        .polygon
        .outer
        .iter()
        .map(|p| d.dot(at(plate, *p) - line.center))
        .fold(f64::INFINITY, f64::min);
    behind < -plate.thickness
}

/// The values of `s` (an interval, possibly empty) for which `lo <= p + s·q <= hi`.
fn solve(p: f64, q: f64, lo: f64, hi: f64) -> (f64, f64) {
    if q.abs() < 1e-12 {
        return if p >= lo && p <= hi {
            (f64::NEG_INFINITY, f64::INFINITY)
        } else {
            (f64::INFINITY, f64::NEG_INFINITY)
        };
    }
    let (a, b) = ((lo - p) / q, (hi - p) / q);
    (a.min(b), a.max(b))
}

/// How far past the line plate `w` can reach with its whole thickness inside the model: inside
/// the union of the other plates' half slabs (each plate's layer on its own side of the line).
/// Checked along nine lines through w's thickness; at most `cap`. Where w meets a neighbour at
/// a shallow angle its middle would run on far inside that neighbour while its faces leave the
/// model: the faces decide.
pub(super) fn exit(plates: &[Plate], line: &Line, w: usize, cap: f64) -> f64 {
    let pw = &plates[w];
    let out = -into_plate(pw, line.axis, line.center);
    // The line's point on w's middle plane.
    let x0 = on_middle(pw, line.center);
    (0..=8)
        .map(|i| {
            let start = x0 + pw.frame.n * (pw.thickness * (i as f64 / 8.0 - 0.5));
            inside_from(plates, line, w, start, out, cap)
        })
        .fold(cap, f64::min)
}

/// How far from `start` along `out` the union of the half slabs of `line`'s plates other than
/// `w` holds without a break, at most `cap`.
fn inside_from(plates: &[Plate], line: &Line, w: usize, start: DVec3, out: DVec3, cap: f64) -> f64 {
    let mut spans: Vec<(f64, f64)> = Vec::new();
    for &p in line.plates.iter().filter(|&&p| p != w) {
        let pp = &plates[p];
        let (n, d) = (pp.frame.n, into_plate(pp, line.axis, line.center));
        let h = pp.thickness / 2.0;
        let layer = solve(n.dot(start - at(pp, DVec2::ZERO)), n.dot(out), -h, h);
        let side = if passes(pp, line) {
            (f64::NEG_INFINITY, f64::INFINITY)
        } else {
            solve(d.dot(start - line.center), d.dot(out), 0.0, f64::INFINITY)
        };
        spans.push((layer.0.max(side.0), layer.1.min(side.1)));
    }
    let mut reached = 0.0f64;
    loop {
        let next = spans
            .iter()
            .filter(|s| s.0 <= reached + 1e-6 && s.1 > reached)
            .fold(reached, |r, s| r.max(s.1));
        if next <= reached || next >= cap {
            return next.min(cap);
        }
        reached = next;
    }
}

/// The part of `plate`'s plane more than `exit` past the line, over the line's `range` (widened
/// by `margin` at both ends), as a polygon in the plate's frame: what its reach must not enter.
pub(super) fn beyond(plate: &Plate, line: &Line, exit: f64, margin: f64) -> Polygon {
    let out = -into_plate(plate, line.axis, line.center);
    let x0 = on_middle(plate, line.center);
    let base = x0 - line.axis * line.axis.dot(x0);
    let far = exit + 1e3;
    let corner = |s: f64, l: f64| plate.frame.to_2d(base + out * s + line.axis * l);
    let (l0, l1) = (line.range.0 - margin, line.range.1 + margin);
    let mut p = Polygon::new(vec![
        corner(exit, l0),
        corner(far, l0),
        corner(far, l1),
        corner(exit, l1),
    ]);
    p.normalize_orientation();
    p
}
