//! Better development by removing plates already added (issue 19, "when adding a plate would
//! overlap, try the alternatives"): a plate that joined a bent part early can block, laid
//! flat, the plates that would join after it. The layout is grown again with the blocking
//! plates taken out until the blocked candidate has been tried, and kept when it has fewer
//! or larger parts (the rule [`Layout::quality`] compares orders by).
//!
//! Growing is Kruskal's algorithm over an order of candidates, so removing plates is
//! reordering: every candidate of a blocking plate (but the blocked one) moves to just after
//! the blocked candidate. The newcomer then joins where the blocking plates were, and they
//! try again afterwards, joining elsewhere or staying plates.

use std::collections::BTreeSet;

use platener_geom::GridError;

use super::find::Candidate;
use super::grow::{Blocked, Layout};

/// At most this many layouts are grown again with plates removed, each costing one growth
/// (as much as one of the orders tried): the search is linear in it, never exponential.
pub(crate) const MAX_REGROWTHS: usize = 8;

/// `layout`, grown by `order`, or a layout grown with blocking plates removed that is
/// better. Each blocked candidate of the best layout so far is tried in the order it was
/// refused, when removing its blockers takes out no more plates than it lets in; the first
/// better layout becomes the best, and its own blocked candidates are tried next. At most
/// [`MAX_REGROWTHS`] growths; deterministic (no order is grown twice).
pub(crate) fn improve<'a>(
    layout: Layout<'a>,
    order: Vec<usize>,
    candidates: &[Candidate],
    grow: impl Fn(&[usize]) -> Result<Layout<'a>, GridError>,
) -> Result<Layout<'a>, GridError> {
    let (mut best, mut order) = (layout, order);
    let mut tried = BTreeSet::from([order.clone()]);
    'better: while tried.len() <= MAX_REGROWTHS {
        let blocked: Vec<Blocked> = best
            .blocked
            .iter()
            .filter(|b| b.by.len() <= b.moving)
            .cloned()
            .collect();
        for b in &blocked {
            let alternative = removing(&order, b, candidates);
            if !tried.insert(alternative.clone()) {
                continue;
            }
            let grown = grow(&alternative)?;
            if grown.quality() < best.quality() {
                (best, order) = (grown, alternative);
                continue 'better;
            }
            if tried.len() > MAX_REGROWTHS {
                break;
            }
        }
        break;
    }
    Ok(best)
}

/// `order` with the candidates of the plates blocking `blocked` (but the blocked candidate
/// itself) moved to just after it, in their order.
fn removing(order: &[usize], blocked: &Blocked, candidates: &[Candidate]) -> Vec<usize> {
    let of_blocker = |ci: usize| {
        ci != blocked.candidate
            && candidates[ci]
                .plates
                .iter()
                .any(|p| blocked.by.binary_search(p).is_ok())
    };
    let (moved, kept): (Vec<usize>, Vec<usize>) = order.iter().partition(|&&ci| of_blocker(ci));
    let mut result = Vec::with_capacity(order.len());
    for ci in kept {
        result.push(ci);
        if ci == blocked.candidate {
            result.extend(&moved);
        }
    }
    result
}
