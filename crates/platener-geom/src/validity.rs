//! Is a part outline something a laser can cut and a nester can place?
//!
//! A valid outline (issue 15, "every outline is valid") is a polygon whose rings are simple
//! (no edge crosses or touches another, no vertex repeats, no edge folds back onto the one
//! before it: a zero-width spike), whose outer ring is counter-clockwise and holes clockwise,
//! whose holes lie strictly inside the outer ring and outside each other, and with no material
//! narrower than a given width (the kerf). [`validate`] lists every way a polygon falls short
//! as typed [`Finding`]s naming the ring and the place; it never changes the polygon.
//!
//! Crossing, touching and folding are decided by exact orientation predicates
//! (`robust::orient2d`), so a slot corner lying exactly on a layer's edge is found whatever the
//! coordinates; width is measured as what a morphological opening (shrink by half the width,
//! grow back, [`crate::offset::opening`]) removes, on the 1 µm grid.
//!
//! The repair is [`crate::clean`]: it turns any polygon into valid pieces.

use glam::DVec2;
use robust::{Coord, orient2d};
use serde::Serialize;

use crate::grid::{GridError, STEP};
use crate::polygon::{Polygon, ring_contains, signed_area2};
use crate::{boolean, offset};

/// Which ring of a polygon a finding is about.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Serialize)]
pub enum RingId {
    /// The outer ring.
    Outer,
    /// Hole number `i` (index into `Polygon::holes`).
    Hole(usize),
}

/// What is wrong at a place of a polygon.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub enum Problem {
    /// A coordinate is NaN or infinite.
    NonFinite,
    /// The ring has fewer than three vertices.
    TooFewVertices,
    /// The ring encloses no area.
    NoArea,
    /// The outer ring is clockwise or a hole counter-clockwise (plan.json's convention).
    Orientation,
    /// Two consecutive vertices are equal (a zero-length edge).
    RepeatedVertex,
    /// An edge runs back along the one before it: a spike of zero width.
    Spike,
    /// An edge crosses an edge of ring `other` (which may be the same ring).
    Crossing {
        /// The other edge's ring.
        other: RingId,
    },
    /// A vertex lies on an edge or vertex of ring `other` (which may be the same ring), or
    /// two edges overlap along a line.
    Touching {
        /// The other ring.
        other: RingId,
    },
    /// A hole is not inside the outer ring.
    HoleOutside,
    /// A hole lies inside hole `other`.
    HoleInHole {
        /// The enclosing hole.
        other: usize,
    },
    /// Material here is narrower than the width asked for.
    Narrow,
}

/// One thing wrong with a polygon: the ring, the problem and a point where it is.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Finding {
    /// The ring it is about.
    pub ring: RingId,
    /// What is wrong.
    pub problem: Problem,
    /// Where (the polygon's own coordinates, mm).
    pub at: DVec2,
}

/// Lost pieces of the opening narrower than this (mm) are the grid's rounding, not material:
/// two booleans on the 1 µm grid move an edge by up to a step each.
const NOISE_WIDTH: f64 = 2.0 * STEP;

/// Everything wrong with `polygon` as a part outline; empty when it is valid.
///
/// `min_width` (mm) is the narrowest material allowed (the kerf), to within 4 µm (two grid
/// steps a side); 0 checks only the rings.
/// Findings come in a fixed order (rings, then containment, then width), so the same polygon
/// always gives the same list. Width is only measured when the rings are sound, since an
/// opening of a broken polygon says nothing about its material; an off-grid polygon (beyond
/// ±1000 m) is reported as [`Problem::NonFinite`].
pub fn validate(polygon: &Polygon, min_width: f64) -> Vec<Finding> {
    let mut findings = ring_findings(polygon);
    if findings.is_empty() {
        findings.extend(containment_findings(polygon));
    }
    if findings.is_empty() && min_width > 0.0 {
        match narrow_spots(polygon, min_width) {
            Ok(spots) => findings.extend(spots.into_iter().map(|at| Finding {
                ring: RingId::Outer,
                problem: Problem::Narrow,
                at,
            })),
            Err(_) => findings.push(Finding {
                ring: RingId::Outer,
                problem: Problem::NonFinite,
                at: polygon.outer.first().copied().unwrap_or_default(),
            }),
        }
    }
    findings
}

/// Whether `polygon` is a valid outline with no material narrower than `min_width`.
pub fn is_valid(polygon: &Polygon, min_width: f64) -> bool {
    validate(polygon, min_width).is_empty()
}

/// The rings of `polygon` with their ids, outer first.
fn rings(polygon: &Polygon) -> impl Iterator<Item = (RingId, &[DVec2])> {
    std::iter::once((RingId::Outer, polygon.outer.as_slice())).chain(
        polygon
            .holes
            .iter()
            .enumerate()
            .map(|(i, h)| (RingId::Hole(i), h.as_slice())),
    )
}

/// Per-ring problems (size, area, orientation, repeats, spikes) and then every crossing or
/// touching pair of edges.
fn ring_findings(polygon: &Polygon) -> Vec<Finding> {
    let mut out = Vec::new();
    for (id, ring) in rings(polygon) {
        let first = ring.first().copied().unwrap_or_default();
        let finding = |problem, at| Finding { ring: id, problem, at };
        if let Some(p) = ring.iter().find(|p| !p.is_finite()) {
            out.push(finding(Problem::NonFinite, *p));
            continue;
        }
        if ring.len() < 3 {
            out.push(finding(Problem::TooFewVertices, first));
            continue;
        }
        let area2 = signed_area2(ring);
        if area2 == 0.0 {
            out.push(finding(Problem::NoArea, first));
        } else if (area2 > 0.0) != (id == RingId::Outer) {
            out.push(finding(Problem::Orientation, first));
        }
        out.extend(
            corner_findings(ring)
                .into_iter()
                .map(|(problem, at)| finding(problem, at)),
        );
    }
    if out
        .iter()
        .any(|f| matches!(f.problem, Problem::NonFinite | Problem::TooFewVertices))
    {
        return out;
    }
    out.extend(edge_pair_findings(polygon));
    out
}

/// Repeated vertices and spikes of one ring, at each vertex in ring order.
fn corner_findings(ring: &[DVec2]) -> Vec<(Problem, DVec2)> {
    let n = ring.len();
    let mut out = Vec::new();
    for i in 0..n {
        let (a, b, c) = (ring[(i + n - 1) % n], ring[i], ring[(i + 1) % n]);
        if a == b {
            out.push((Problem::RepeatedVertex, b));
        } else if b != c && orient(a, b, c) == 0.0 && (b - a).dot(c - b) < 0.0 {
            out.push((Problem::Spike, b));
        }
    }
    out
}

/// Exact orientation of `c` relative to the line `a → b`: positive to the left, 0 on it.
fn orient(a: DVec2, b: DVec2, c: DVec2) -> f64 {
    let k = |p: DVec2| Coord { x: p.x, y: p.y };
    orient2d(k(a), k(b), k(c))
}

/// Whether `p`, known to be on the line through `a` and `b`, lies on the closed segment.
fn within(a: DVec2, b: DVec2, p: DVec2) -> bool {
    p.x >= a.x.min(b.x) && p.x <= a.x.max(b.x) && p.y >= a.y.min(b.y) && p.y <= a.y.max(b.y)
}

/// One edge of a ring, for the sweep.
struct Edge {
    ring: RingId,
    index: usize,
    len: usize,
    a: DVec2,
    b: DVec2,
}

impl Edge {
    fn min_x(&self) -> f64 {
        self.a.x.min(self.b.x)
    }

    /// Whether `other` is the edge before or after this one in the same ring (they share a
    /// vertex by construction; folding back there is a spike, found per corner).
    fn adjacent(&self, other: &Edge) -> bool {
        self.ring == other.ring
            && (other.index == (self.index + 1) % self.len || self.index == (other.index + 1) % self.len)
    }
}

/// Every pair of edges (of any rings) that cross or touch, found by a sweep along x: edges
/// sorted by their left end, each compared with those starting before it ends.
fn edge_pair_findings(polygon: &Polygon) -> Vec<Finding> {
    let mut edges: Vec<Edge> = rings(polygon)
        .flat_map(|(ring, r)| {
            let len = r.len();
            (0..len).map(move |index| Edge {
                ring,
                index,
                len,
                a: r[index],
                b: r[(index + 1) % len],
            })
        })
        .filter(|e| e.a != e.b)
        .collect();
    edges.sort_by(|e, f| {
        e.min_x()
            .total_cmp(&f.min_x())
            .then(e.ring.cmp(&f.ring))
            .then(e.index.cmp(&f.index))
    });
    let mut out = Vec::new();
    for (i, e) in edges.iter().enumerate() {
        let (max_x, lo_y, hi_y) = (e.a.x.max(e.b.x), e.a.y.min(e.b.y), e.a.y.max(e.b.y));
        for f in edges[i + 1..].iter().take_while(|f| f.min_x() <= max_x) {
            if f.a.y.max(f.b.y) < lo_y || f.a.y.min(f.b.y) > hi_y || e.adjacent(f) {
                continue;
            }
            if let Some((problem, at)) = meet(e, f) {
                let (first, second) = if e.ring <= f.ring { (e, f) } else { (f, e) };
                let problem = match problem {
                    Problem::Crossing { .. } => Problem::Crossing { other: second.ring },
                    _ => Problem::Touching { other: second.ring },
                };
                out.push(Finding {
                    ring: first.ring,
                    problem,
                    at,
                });
            }
        }
    }
    // Two rings meeting at a vertex meet there with up to four pairs of edges: one finding.
    out.sort_by(|f, g| {
        (f.ring.cmp(&g.ring))
            .then(f.at.x.total_cmp(&g.at.x))
            .then(f.at.y.total_cmp(&g.at.y))
    });
    out.dedup();
    out
}

/// How two non-adjacent edges meet, exactly: a proper crossing, a touch (an end on the other
/// edge, shared ends, collinear overlap), or not at all.
fn meet(e: &Edge, f: &Edge) -> Option<(Problem, DVec2)> {
    let (o1, o2) = (orient(e.a, e.b, f.a), orient(e.a, e.b, f.b));
    let (o3, o4) = (orient(f.a, f.b, e.a), orient(f.a, f.b, e.b));
    let touch = Problem::Touching { other: f.ring };
    if o1 * o2 < 0.0 && o3 * o4 < 0.0 {
        // Proper crossing; the point is only for reporting, so floats suffice.
        let d = e.b - e.a;
        let t = o3 / (o3 - o4);
        return Some((Problem::Crossing { other: f.ring }, e.a + d * t));
    }
    [(o1, e, f.a), (o2, e, f.b), (o3, f, e.a), (o4, f, e.b)]
        .into_iter()
        .find(|(o, edge, p)| *o == 0.0 && within(edge.a, edge.b, *p))
        .map(|(_, _, p)| (touch, p))
}

/// Holes strictly inside the outer ring and outside each other. Called only when no edges
/// cross or touch, so one vertex of a hole tells where the whole hole is.
fn containment_findings(polygon: &Polygon) -> Vec<Finding> {
    let mut out = Vec::new();
    for (i, hole) in polygon.holes.iter().enumerate() {
        let p = hole[0];
        let ring = RingId::Hole(i);
        if !ring_contains(&polygon.outer, p) {
            out.push(Finding {
                ring,
                problem: Problem::HoleOutside,
                at: p,
            });
            continue;
        }
        if let Some(g) = (0..polygon.holes.len()).find(|&g| g != i && ring_contains(&polygon.holes[g], p)) {
            out.push(Finding {
                ring,
                problem: Problem::HoleInHole { other: g },
                at: p,
            });
        }
    }
    out
}

/// Points of `polygon`'s material narrower than `min_width`: one point per piece of
/// [`narrow_material`].
fn narrow_spots(polygon: &Polygon, min_width: f64) -> Result<Vec<DVec2>, GridError> {
    Ok(narrow_material(polygon, min_width)?
        .iter()
        .filter_map(|p| p.outer.first().copied())
        .collect())
}

/// The pieces of `polygon`'s material narrower than `min_width`, each shrunk by
/// [`NOISE_WIDTH`]: what an opening removes, ignoring grid-rounding crumbs. The repair
/// ([`crate::clean`]) uses them to find what to cut away or widen.
///
/// The opening is by half the width less [`NOISE_WIDTH`]: an opening on the grid moves miter
/// corners by a step or two, so material the cleaner opened at exactly half the width would
/// otherwise be found narrow again. Widths are thus checked to within 4 µm.
pub fn narrow_material(polygon: &Polygon, min_width: f64) -> Result<Vec<Polygon>, GridError> {
    let r = (min_width / 2.0 - NOISE_WIDTH).max(0.0);
    if r == 0.0 {
        return Ok(Vec::new());
    }
    let opened = offset::opening(std::slice::from_ref(polygon), r)?;
    let lost = boolean::difference(std::slice::from_ref(polygon), &opened)?;
    if lost.is_empty() {
        return Ok(Vec::new());
    }
    let cores = offset::offset(&lost, -NOISE_WIDTH)?;
    // Miter joins are not a true structuring element: where the shrink removes an edge shorter
    // than the width (a small chamfer, a finger's notch), growing back leaves a crumb at the
    // corner, at most about the width across. Narrow material runs longer than that.
    Ok(cores
        .into_iter()
        .filter(|p| {
            let (lo, hi) = p.bounds();
            (hi - lo).max_element() > 2.0 * min_width
        })
        .collect())
}

#[cfg(test)]
mod tests;
