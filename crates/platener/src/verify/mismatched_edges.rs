//! Edges that fit where they do not belong: for every two finger joints of a plan, whether an
//! edge of one accepts an edge of the other, so that a maker could put a part in the wrong
//! place or the wrong way round and it would still go together (Kyub's FoolProofJoint).
//!
//! Edge X (joint j1, part P, partner Q) accepts edge Y (joint j2 ≠ j1, part R ≠ P, partner
//! S) when X's tabs are S's tabs along j2 ([`Pattern::matches`], either way round): X's tabs
//! fill Y's notches. The thicknesses must match too (P as thick as S, Q as R). Such a pair is
//! harmless, *interchangeable*, when P is S's twin: the same outline up to a rigid motion
//! (turning over allowed) that carries X onto S's edge along j2, so putting P there builds
//! the same thing (a shelf of identical shelves; a symmetric wall turned round). Likewise
//! when R is Q's twin. Only the other pairs are counted as accepting.

use glam::DVec2;
use platener_geom::Polygon;
use platener_geom::rigid::Rigid2;
use platener_geom::slab::Slab;
use serde::Serialize;

use super::edge_pattern::{JointEdges, PATTERN_TOL, joint_edges};
use crate::plan::{JointKind, PartKind, Plan};

/// Parts whose thicknesses differ by more than this (mm) do not take each other's place.
const THICKNESS_TOL: f64 = 0.1;

/// How many edges of a plan fit where they do not belong.
#[derive(Debug, Clone, Default, PartialEq, Serialize)]
pub struct MismatchReport {
    /// Joints whose edges were read (finger, JimJoint, dovetail, tab and slot; not bent parts).
    pub joints_read: usize,
    /// Pairs of non-partner edges that accept each other: a wrong assembly that goes together.
    pub accepting_pairs: usize,
    /// Pairs that accept each other between interchangeable parts: harmless.
    pub interchangeable_pairs: usize,
    /// The accepting pairs (not the interchangeable ones), by joint labels.
    pub pairs: Vec<EdgePair>,
    /// Parts that take each other's places harmlessly, in groups of twins (ids ascending, the
    /// groups by their first id): what the instructions tell the maker may be swapped.
    pub interchangeable_parts: Vec<Vec<u32>>,
}

/// Two edges of different joints that accept each other.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Serialize)]
pub struct EdgePair {
    /// The joints' labels, lower first.
    pub joints: [u32; 2],
    /// The parts whose edges these are (the first on the first joint).
    pub parts: [u32; 2],
    /// Whether they fit only with one turned end for end.
    pub reversed: bool,
}

/// A joint as the check reads it: its two parts (indices into the parts given).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct EdgeJoint {
    /// The parts, indices into the slabs given to [`acceptances`].
    pub parts: [usize; 2],
    /// Dovetails fit only dovetails; the other finger-like joints fit each other.
    pub dovetail: bool,
}

/// Edge `sides[0]` of joint `joints[0]` accepts edge `sides[1]` of joint `joints[1]`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct Acceptance {
    /// Indices into the joints given, lower first.
    pub joints: [usize; 2],
    /// Which side (0 or 1, the joint's part order) of each joint.
    pub sides: [usize; 2],
    /// Whether they fit only with one turned end for end.
    pub reversed: bool,
    /// The parts that would swap when they are twins (indices into the slabs given): the pair
    /// is harmless.
    pub twins: Option<[usize; 2]>,
}

impl Acceptance {
    /// Whether the parts that would swap are twins, so the wrong fit builds the same thing.
    pub fn interchangeable(&self) -> bool {
        self.twins.is_some()
    }
}

/// The check on a plan: its finger-like joints between flat parts (the first joint of each
/// label: a dovetail's keys are joints of the same label).
pub fn mismatched_edges(plan: &Plan) -> MismatchReport {
    let slabs: Vec<Option<Slab>> = plan
        .parts
        .iter()
        .map(|p| {
            let flat = p.kind != PartKind::Bent || p.segments.is_empty();
            flat.then(|| p.pieces().ok()?.into_iter().next()).flatten()
        })
        .collect();
    let index = |id: u32| plan.parts.iter().position(|p| p.id == id);
    let mut seen = std::collections::BTreeSet::new();
    let mut joints = Vec::new();
    let mut labels = Vec::new();
    for j in &plan.joints {
        let finger_like = matches!(
            j.kind,
            JointKind::Finger | JointKind::Jim | JointKind::Dovetail | JointKind::Slot
        );
        let (Some(a), Some(b)) = (index(j.parts[0]), index(j.parts[1])) else {
            continue;
        };
        if finger_like && seen.insert(j.label) && a != b {
            joints.push(EdgeJoint {
                parts: [a, b],
                dovetail: j.kind == JointKind::Dovetail,
            });
            labels.push(j.label);
        }
    }
    let (read, found) = acceptances(&slabs, &joints);
    let mut report = MismatchReport {
        joints_read: read,
        ..MismatchReport::default()
    };
    let mut twins = Vec::new();
    for a in found {
        if let Some(pair) = a.twins {
            report.interchangeable_pairs += 1;
            twins.push(pair);
            continue;
        }
        report.accepting_pairs += 1;
        let part = |k: usize| plan.parts[joints[a.joints[k]].parts[a.sides[k]]].id;
        report.pairs.push(EdgePair {
            joints: [labels[a.joints[0]], labels[a.joints[1]]],
            parts: [part(0), part(1)],
            reversed: a.reversed,
        });
    }
    report.pairs.sort_unstable();
    report.interchangeable_parts = groups(plan, &twins);
    report
}

/// The groups of parts that `pairs` (indices into `plan.parts`) join, by id: each group
/// ascending, the groups by their first id; a part paired only with itself (turned round in
/// its own place) is no group.
fn groups(plan: &Plan, pairs: &[[usize; 2]]) -> Vec<Vec<u32>> {
    let mut uf = crate::assembly::UnionFind::new(plan.parts.len());
    for &[a, b] in pairs {
        uf.join(a, b);
    }
    let mut by_root: std::collections::BTreeMap<usize, Vec<u32>> = std::collections::BTreeMap::new();
    for &i in pairs.iter().flatten().collect::<std::collections::BTreeSet<_>>() {
        by_root.entry(uf.root(i)).or_default().push(plan.parts[i].id);
    }
    let mut out: Vec<Vec<u32>> = by_root
        .into_values()
        .filter(|g| g.len() > 1)
        .map(|mut g| {
            g.sort_unstable();
            g
        })
        .collect();
    out.sort();
    out
}

/// One side of a read joint: the joint, the side, and the part's index.
#[derive(Clone, Copy)]
struct Side {
    joint: usize,
    side: usize,
    part: usize,
}

/// How many of `joints` could be read, and every pair of their edges that accept each other
/// (`slabs`: each part as one slab, `None` for parts not read). Pairs are sought only among
/// edges of about the same length, so the cost grows with the look-alikes, not the square of
/// the joints.
pub(crate) fn acceptances(slabs: &[Option<Slab>], joints: &[EdgeJoint]) -> (usize, Vec<Acceptance>) {
    let read: Vec<Option<JointEdges>> = joints
        .iter()
        .map(|j| joint_edges(slabs[j.parts[0]].as_ref()?, slabs[j.parts[1]].as_ref()?))
        .collect();
    let mut sides: Vec<(f64, Side)> = Vec::new();
    for (k, edges) in read.iter().enumerate() {
        if let Some(e) = edges {
            for side in 0..2 {
                let part = joints[k].parts[side];
                sides.push((e.sides[side].length, Side { joint: k, side, part }));
            }
        }
    }
    sides.sort_by(|x, y| {
        x.0.total_cmp(&y.0)
            .then((x.1.joint, x.1.side).cmp(&(y.1.joint, y.1.side)))
    });
    let reading = Reading {
        slabs,
        joints,
        read: &read,
    };
    let mut found = Vec::new();
    for (i, &(length, x)) in sides.iter().enumerate() {
        for &(other, y) in &sides[i + 1..] {
            if other - length > super::edge_pattern::LENGTH_TOL {
                break;
            }
            if x.joint != y.joint && x.part != y.part {
                found.extend(reading.accepts(x, y));
            }
        }
    }
    found.sort_by_key(|a| (a.joints, a.sides));
    (read.iter().flatten().count(), found)
}

/// What [`acceptances`] reads from.
struct Reading<'a> {
    slabs: &'a [Option<Slab>],
    joints: &'a [EdgeJoint],
    read: &'a [Option<JointEdges>],
}

impl Reading<'_> {
    fn edges(&self, s: Side) -> &JointEdges {
        self.read[s.joint].as_ref().expect("only read joints have sides")
    }

    fn partner(&self, s: Side) -> Side {
        let side = 1 - s.side;
        Side {
            side,
            part: self.joints[s.joint].parts[side],
            ..s
        }
    }

    fn thickness(&self, s: Side) -> f64 {
        self.slabs[s.part].as_ref().map_or(0.0, |p| p.thickness)
    }

    /// Whether `x` takes the place of `y`'s partner: it has that partner's tabs (either
    /// way round) and thickness, and its own partner is as thick as `y`'s part. Returns
    /// whether reversed.
    fn takes_place(&self, x: Side, y: Side) -> Option<bool> {
        let (xp, yp) = (self.partner(x), self.partner(y));
        let alike = |a: f64, b: f64| (a - b).abs() <= THICKNESS_TOL;
        if self.joints[x.joint].dovetail != self.joints[y.joint].dovetail
            || !alike(self.thickness(x), self.thickness(yp))
            || !alike(self.thickness(xp), self.thickness(y))
        {
            return None;
        }
        let (mine, theirs) = (&self.edges(x).sides[x.side], &self.edges(yp).sides[yp.side]);
        if mine.matches(theirs) {
            Some(false)
        } else {
            mine.matches(&theirs.reversed()).then_some(true)
        }
    }

    /// Whether edges `x` and `y` accept each other, and if so how.
    fn accepts(&self, x: Side, y: Side) -> Option<Acceptance> {
        let forth = self.takes_place(x, y);
        let back = self.takes_place(y, x);
        let reversed = forth.or(back)?;
        let pair = |a: Side, b: Side| [a.part.min(b.part), a.part.max(b.part)];
        let twins = match (forth, back) {
            (Some(r), _) if self.twins(x, self.partner(y), r) => Some(pair(x, self.partner(y))),
            (_, Some(r)) if self.twins(y, self.partner(x), r) => Some(pair(y, self.partner(x))),
            _ => None,
        };
        let (x, y) = if x.joint < y.joint { (x, y) } else { (y, x) };
        Some(Acceptance {
            joints: [x.joint, y.joint],
            sides: [x.side, y.side],
            reversed,
            twins,
        })
    }

    /// Whether `x`'s part is the twin of `s`'s part by a rigid motion of the plane (or one
    /// turning it over) that carries edge `x` onto edge `s` (start to end if `reversed`).
    fn twins(&self, x: Side, s: Side, reversed: bool) -> bool {
        let (Some(p), Some(q)) = (&self.slabs[x.part], &self.slabs[s.part]) else {
            return false;
        };
        let from = self.edges(x).segments[x.side];
        let mut to = self.edges(s).segments[s.side];
        if reversed {
            to.reverse();
        }
        let area = |s: &Slab| s.polygon.area();
        if (area(p) - area(q)).abs() > 0.01 * area(q).max(1.0) {
            return false;
        }
        [false, true]
            .into_iter()
            .any(|over| congruent(&p.polygon, &q.polygon, motion(from, to, over)))
    }
}

/// The motion carrying the segment `from` onto `to` (middle to middle), turning the plane
/// over across `from` first if `over`.
fn motion(from: [DVec2; 2], to: [DVec2; 2], over: bool) -> impl Fn(DVec2) -> DVec2 {
    let (m0, m1) = ((from[0] + from[1]) / 2.0, (to[0] + to[1]) / 2.0);
    let (d0, d1) = ((from[1] - from[0]).normalize(), (to[1] - to[0]).normalize());
    let rigid = Rigid2::from_points(m0, m0 + d0, m1, m1 + d1);
    move |p: DVec2| {
        let p = if over {
            let r = p - m0;
            m0 + d0 * d0.dot(r) - d0.perp() * d0.perp().dot(r)
        } else {
            p
        };
        rigid.apply(p)
    }
}

/// Whether `map` carries outline `p` onto `q`: every vertex of each within [`PATTERN_TOL`]
/// of one of the other's when they have as many (drawn alike), else of the other's boundary.
fn congruent(p: &Polygon, q: &Polygon, map: impl Fn(DVec2) -> DVec2) -> bool {
    let moved = Polygon {
        outer: p.outer.iter().map(|v| map(*v)).collect(),
        holes: p.holes.iter().map(|h| h.iter().map(|v| map(*v)).collect()).collect(),
    };
    if moved.vertex_count() == q.vertex_count() {
        return near_vertices(&moved, q) && near_vertices(q, &moved);
    }
    let near = |v: &DVec2, s: &Polygon| s.boundary_distance_squared(*v) <= PATTERN_TOL * PATTERN_TOL;
    vertices(&moved).all(|v| near(v, q)) && vertices(q).all(|v| near(v, &moved))
}

fn vertices(s: &Polygon) -> impl Iterator<Item = &DVec2> {
    s.outer.iter().chain(s.holes.iter().flatten())
}

/// Whether each of `a`'s vertices lies within [`PATTERN_TOL`] of one of `b`'s: `b`'s sorted
/// by x once, each of `a`'s looked up among those within the tolerance in x.
fn near_vertices(a: &Polygon, b: &Polygon) -> bool {
    let mut sorted: Vec<DVec2> = vertices(b).copied().collect();
    sorted.sort_by(|u, w| u.x.total_cmp(&w.x));
    vertices(a).all(|v| {
        let from = sorted.partition_point(|w| w.x < v.x - PATTERN_TOL);
        sorted[from..]
            .iter()
            .take_while(|w| w.x <= v.x + PATTERN_TOL)
            .any(|w| w.distance_squared(*v) <= PATTERN_TOL * PATTERN_TOL)
    })
}
