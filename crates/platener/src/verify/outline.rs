//! A minimal validity check of a part's outline, as a laser needs it: every ring a simple
//! polygon (no crossing, no touching, no spike running back along itself), no ring crossing
//! another, every hole inside the outline and outside the other holes.
//!
//! Kept behind one function, [`outline_findings`], so that a full validity check of the kernel
//! can replace it without touching `verify`'s callers.

use glam::DVec2;
use platener_geom::polygon::ring_contains;

use crate::plan::PlanPart;

/// Cross products (mm²) at most this far from zero count as collinear: far below what two
/// points on the project's 1 µm grid make with any edge that does not pass through them.
const COLLINEAR: f64 = 1e-9;
/// Findings listed per part, at most.
const MOST: usize = 5;

/// One edge: its ring, its index in the ring, its ends.
#[derive(Clone, Copy)]
struct Edge {
    ring: usize,
    index: usize,
    a: DVec2,
    b: DVec2,
}

/// What is wrong with the part's outline and holes (empty when it is valid).
pub fn outline_findings(part: &PlanPart) -> Vec<String> {
    let rings: Vec<Vec<DVec2>> = std::iter::once(&part.outline)
        .chain(&part.holes)
        .map(|r| without_repeats(r))
        .collect();
    let name = |r: usize| {
        if r == 0 {
            "the outline".to_string()
        } else {
            format!("hole {r}")
        }
    };
    let mut found = Vec::new();
    for (r, ring) in rings.iter().enumerate() {
        if ring.len() < 3 || platener_geom::polygon::signed_area(ring).abs() <= COLLINEAR {
            found.push(format!("{} has no area", name(r)));
        }
    }
    if !found.is_empty() {
        return found;
    }
    found.extend(
        spikes(&rings)
            .into_iter()
            .map(|(r, p)| format!("{} runs back along itself at ({:.3}, {:.3})", name(r), p.x, p.y)),
    );
    found.extend(crossings(&rings).into_iter().map(|(r, s, p)| {
        let what = if r == s {
            format!("{} touches itself", name(r))
        } else {
            format!("{} and {} touch", name(r), name(s))
        };
        format!("{what} at ({:.3}, {:.3})", p.x, p.y)
    }));
    // Several edges through one pinch point report it once.
    found.dedup();
    if found.is_empty() {
        found.extend(misplaced_holes(&rings));
    }
    let more = found.len().saturating_sub(MOST);
    found.truncate(MOST);
    if more > 0 {
        found.push(format!("and {more} more such places"));
    }
    found
}

/// The ring without consecutive repeated points (and without a closing repeat).
fn without_repeats(ring: &[DVec2]) -> Vec<DVec2> {
    let mut out: Vec<DVec2> = Vec::with_capacity(ring.len());
    for &p in ring {
        if out.last() != Some(&p) {
            out.push(p);
        }
    }
    while out.len() > 1 && out.first() == out.last() {
        out.pop();
    }
    out
}

/// Corners where a ring turns straight back (a zero-width spike).
fn spikes(rings: &[Vec<DVec2>]) -> Vec<(usize, DVec2)> {
    let mut out = Vec::new();
    for (r, ring) in rings.iter().enumerate() {
        let n = ring.len();
        for i in 0..n {
            let (a, b, c) = (ring[(i + n - 1) % n], ring[i], ring[(i + 1) % n]);
            if (b - a).perp_dot(c - b).abs() <= COLLINEAR && (b - a).dot(c - b) < 0.0 {
                out.push((r, b));
            }
        }
    }
    out
}

/// Pairs of edges that are not neighbours in one ring yet cross or touch: the rings involved
/// and a point where they do.
fn crossings(rings: &[Vec<DVec2>]) -> Vec<(usize, usize, DVec2)> {
    let mut edges: Vec<Edge> = Vec::new();
    for (ring, points) in rings.iter().enumerate() {
        let n = points.len();
        edges.extend((0..n).map(|index| Edge {
            ring,
            index,
            a: points[index],
            b: points[(index + 1) % n],
        }));
    }
    // A sweep along x: only edges whose x ranges overlap are compared.
    edges.sort_by(|e, f| e.a.x.min(e.b.x).total_cmp(&f.a.x.min(f.b.x)));
    let mut out = Vec::new();
    for (i, e) in edges.iter().enumerate() {
        let right = e.a.x.max(e.b.x);
        for f in edges[i + 1..].iter().take_while(|f| f.a.x.min(f.b.x) <= right) {
            if neighbours(e, f, rings[e.ring].len()) {
                continue;
            }
            if let Some(p) = touch(e, f) {
                out.push((e.ring.min(f.ring), e.ring.max(f.ring), p));
            }
        }
    }
    out.sort_by(|a, b| {
        (a.0, a.1, a.2.x, a.2.y)
            .partial_cmp(&(b.0, b.1, b.2.x, b.2.y))
            .unwrap_or(std::cmp::Ordering::Equal)
    });
    out
}

/// Whether two edges follow each other in the same ring (they share a corner by design).
fn neighbours(e: &Edge, f: &Edge, n: usize) -> bool {
    e.ring == f.ring && ((e.index + 1) % n == f.index || (f.index + 1) % n == e.index)
}

/// Twice the signed area of the triangle `abc`, zero within [`COLLINEAR`].
fn orient(a: DVec2, b: DVec2, c: DVec2) -> f64 {
    let o = (b - a).perp_dot(c - a);
    if o.abs() <= COLLINEAR { 0.0 } else { o }
}

/// Whether `p`, collinear with the segment `ab`, lies on it.
fn on_segment(a: DVec2, b: DVec2, p: DVec2) -> bool {
    p.cmpge(a.min(b)).all() && p.cmple(a.max(b)).all()
}

/// A point the two edges share, if they cross or touch.
fn touch(e: &Edge, f: &Edge) -> Option<DVec2> {
    let (d1, d2) = (orient(e.a, e.b, f.a), orient(e.a, e.b, f.b));
    let (d3, d4) = (orient(f.a, f.b, e.a), orient(f.a, f.b, e.b));
    if d1 * d2 < 0.0 && d3 * d4 < 0.0 {
        // A proper crossing: where f meets the line of e.
        let t = d1 / (d1 - d2);
        return Some(f.a + (f.b - f.a) * t);
    }
    [(d1, e, f.a), (d2, e, f.b), (d3, f, e.a), (d4, f, e.b)]
        .into_iter()
        .find(|(d, edge, p)| *d == 0.0 && on_segment(edge.a, edge.b, *p))
        .map(|(_, _, p)| p)
}

/// Holes outside the outline or inside another hole (rings that neither cross nor touch, so
/// one corner tells where a whole ring lies).
fn misplaced_holes(rings: &[Vec<DVec2>]) -> Vec<String> {
    let mut out = Vec::new();
    for (h, hole) in rings.iter().enumerate().skip(1) {
        if !ring_contains(&rings[0], hole[0]) {
            out.push(format!("hole {h} lies outside the outline"));
            continue;
        }
        if let Some(k) = (1..rings.len()).find(|&k| k != h && ring_contains(&rings[k], hole[0])) {
            out.push(format!("hole {h} lies inside hole {k}"));
        }
    }
    out
}
