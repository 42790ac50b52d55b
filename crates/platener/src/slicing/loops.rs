//! Chaining a plane's segments into loops through shared mesh edges.
//!
//! A segment ends on the mesh edge where the next triangle's segment starts, so loops are
//! found by matching edge ids, not coordinates: they close exactly whatever the float noise,
//! and in linear time after the sort (a binary search per step). Where the surface has holes
//! a chain stops at an open edge; such chains are joined end to start across gaps up to a
//! given width, nearest first, so a loop closes even on a mesh with small defects. Chains
//! that cannot be closed are dropped and counted.

use std::ops::AddAssign;

use platener_geom::Ring;
use serde::Serialize;

use super::Segment;

/// How the loops of a slice closed.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize)]
pub struct LoopStats {
    /// Loops closed through shared edges alone.
    pub closed: usize,
    /// Loops closed by joining open chains across small gaps.
    pub bridged: usize,
    /// Open chains that could not be closed, ignored.
    pub dropped: usize,
}

impl AddAssign for LoopStats {
    fn add_assign(&mut self, o: Self) {
        self.closed += o.closed;
        self.bridged += o.bridged;
        self.dropped += o.dropped;
    }
}

/// A chain of crossed mesh edges, in order.
#[derive(Debug, Clone, PartialEq, Eq)]
pub(crate) struct Chain {
    /// The crossed edges; for an open chain the last one is where it stops.
    pub edges: Vec<u32>,
    /// Whether the last segment ends where the first starts.
    pub closed: bool,
    /// Each segment's triangle, in order (segment i runs from edge i to edge i + 1; never
    /// empty).
    pub faces: Vec<u32>,
}

/// An open chain's crossing points and the body it belongs to.
#[derive(Debug, Clone)]
pub(crate) struct OpenChain {
    /// The points, first to last.
    pub points: Ring,
    /// The mesh component of its first triangle.
    pub component: u32,
    /// Its length, mm, and the part of it cut from marked triangles (see [`Marked`]).
    pub marked: Marked,
}

/// How much of a loop's length was cut from marked triangles (the classifier's layers mark
/// the triangles no plate builds): lengths in mm, gaps bridged across not counted.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub(crate) struct Marked {
    /// Length cut from marked triangles.
    pub marked: f64,
    /// Whole length.
    pub length: f64,
}

impl Marked {
    /// The marked share of the length, 0 for a loop of no length.
    pub fn share(self) -> f64 {
        if self.length > 0.0 {
            self.marked / self.length
        } else {
            0.0
        }
    }
}

impl AddAssign for Marked {
    fn add_assign(&mut self, o: Self) {
        self.marked += o.marked;
        self.length += o.length;
    }
}

/// Chains `segments` (sorted by start edge) through their shared edges. On a non-manifold edge
/// (several segments start there) the first unused one is taken.
pub(crate) fn chain(segments: &[Segment]) -> Vec<Chain> {
    let n = segments.len();
    let mut used = vec![false; n];
    // Segments ordered by end edge: a segment whose start edge no segment ends on begins an
    // open chain.
    let mut by_end: Vec<u32> = (0..n as u32).collect();
    by_end.sort_unstable_by_key(|&i| (segments[i as usize].to, i));
    let ends_on = |e: u32| {
        let i = by_end.partition_point(|&j| segments[j as usize].to < e);
        i < n && segments[by_end[i] as usize].to == e
    };
    let next = |used: &[bool], e: u32| {
        let i = segments.partition_point(|s| s.from < e);
        (i..n).take_while(|&j| segments[j].from == e).find(|&j| !used[j])
    };
    let mut out = Vec::new();
    let walk = |start: usize, used: &mut Vec<bool>| {
        let mut edges = vec![segments[start].from];
        let mut faces = vec![segments[start].face];
        used[start] = true;
        let mut at = start;
        while let Some(j) = next(used, segments[at].to) {
            used[j] = true;
            edges.push(segments[j].from);
            faces.push(segments[j].face);
            at = j;
        }
        let closed = segments[at].to == segments[start].from;
        if !closed {
            edges.push(segments[at].to);
        }
        Chain { edges, closed, faces }
    };
    // Open chains first, from their true starts, so they are not cut in two.
    for i in 0..n {
        if !used[i] && !ends_on(segments[i].from) {
            out.push(walk(i, &mut used));
        }
    }
    for i in 0..n {
        if !used[i] {
            out.push(walk(i, &mut used));
        }
    }
    out
}

/// Joins open chains end to start across gaps no wider than `gap`, nearest pairs first.
/// Returns the loops so closed (with the component of their first chain and their marked
/// length) and the counts.
pub(crate) fn close_gaps(open: Vec<OpenChain>, gap: f64) -> (Vec<(Ring, u32, Marked)>, LoopStats) {
    let m = open.len();
    let mut stats = LoopStats::default();
    if m == 0 {
        return (Vec::new(), stats);
    }
    let head = |i: usize| open[i].points[0];
    let tail = |i: usize| open[i].points[open[i].points.len() - 1];
    // Heads sorted by x: each tail looks only at heads within `gap` in x.
    let mut by_x: Vec<usize> = (0..m).collect();
    by_x.sort_by(|&a, &b| head(a).x.total_cmp(&head(b).x).then(a.cmp(&b)));
    let mut pairs: Vec<(f64, usize, usize)> = Vec::new();
    for i in 0..m {
        let t = tail(i);
        let first = by_x.partition_point(|&j| head(j).x < t.x - gap);
        for &j in by_x[first..].iter().take_while(|&&j| head(j).x <= t.x + gap) {
            let d = t.distance(head(j));
            if d <= gap {
                pairs.push((d, i, j));
            }
        }
    }
    pairs.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)).then(a.2.cmp(&b.2)));
    let mut next: Vec<Option<usize>> = vec![None; m];
    let mut has_prev = vec![false; m];
    for (_, i, j) in pairs {
        if next[i].is_none() && !has_prev[j] {
            next[i] = Some(j);
            has_prev[j] = true;
        }
    }
    let mut seen = vec![false; m];
    // Paths (a chain without a predecessor starts one) cannot close: dropped.
    for (i, _) in has_prev.iter().enumerate().filter(|(_, p)| !**p) {
        let mut at = Some(i);
        while let Some(a) = at {
            seen[a] = true;
            at = next[a];
        }
        stats.dropped += 1;
    }
    // What is left are cycles.
    let mut out = Vec::new();
    for i in 0..m {
        if seen[i] {
            continue;
        }
        let mut ring: Ring = Vec::new();
        let mut marked = Marked::default();
        let mut at = i;
        while !seen[at] {
            seen[at] = true;
            ring.extend(open[at].points.iter().copied());
            marked += open[at].marked;
            at = next[at].expect("every chain in a cycle has a successor");
        }
        stats.bridged += 1;
        out.push((ring, open[i].component, marked));
    }
    (out, stats)
}
