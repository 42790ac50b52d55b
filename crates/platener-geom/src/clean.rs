//! Repairing part outlines into valid ones ([`crate::validity`]).
//!
//! Joints and slots are cut into outlines by booleans, and a slot corner may land exactly on an
//! outline's edge, a finger may leave a sliver, a ring may run back along itself. Before such an
//! outline reaches the kerf offset or the nester it is repaired here:
//!
//! 1. *Regularise*: a union of the polygon with itself (non-zero rule, on the 1 µm grid) turns
//!    crossing rings, zero-width spikes and repeated vertices into proper rings.
//! 2. *Open* by half the minimum width: material narrower than it (slivers, thin spikes, necks)
//!    goes; everything wider comes back exactly (miter joins keep corners).
//! 3. *Separate touches*: where two rings (or one ring with itself) still meet in a point, a
//!    small square of the minimum width is cut out there, then step 2 runs again. Cutting, not
//!    filling, so a slot whose corner touched the edge stays large enough for its shaft.
//! 4. Pieces and holes with no area to speak of ([`GRID_NOISE_AREA`]) are dropped.
//!
//! A polygon that is already valid is returned unchanged (same vertices), so clean outlines are
//! never moved by a grid round trip.

use glam::DVec2;

use crate::grid::{GridError, STEP};
use crate::polygon::{Polygon, rect};
use crate::tolerance::GRID_NOISE_AREA;
use crate::validity::{Problem, validate};
use crate::{boolean, offset};

/// Rounds of "separate touches, open again" before giving up: each round removes the touches
/// it finds; new ones only come from the cut squares meeting other rings, which a second round
/// separates.
const ROUNDS: usize = 4;

/// The smallest square (mm) cut out at a touching point, when the minimum width is smaller:
/// ten grid steps, so the rings end up clearly apart.
const MIN_SEPARATION: f64 = 10.0 * STEP;

/// `polygon` repaired into valid pieces with no material narrower than `min_width` (mm),
/// largest first; empty when nothing of it is wider. Outer rings come counter-clockwise and
/// holes clockwise. Pieces that remain invalid after the repair rounds (which no test has
/// produced) are still returned; callers check them with [`validate`].
pub fn clean(polygon: &Polygon, min_width: f64) -> Result<Vec<Polygon>, GridError> {
    if validate(polygon, min_width).is_empty() {
        return Ok(vec![polygon.clone()]);
    }
    let mut normalized = polygon.clone();
    normalized.normalize_orientation();
    let mut pieces = open(&boolean::union_all(&[normalized])?, min_width)?;
    for _ in 0..ROUNDS {
        let touches: Vec<DVec2> = pieces
            .iter()
            .flat_map(|p| validate(p, 0.0))
            .filter(|f| matches!(f.problem, Problem::Touching { .. } | Problem::Crossing { .. }))
            .map(|f| f.at)
            .collect();
        if touches.is_empty() {
            break;
        }
        let h = min_width.max(MIN_SEPARATION) / 2.0;
        let squares: Vec<Polygon> = touches
            .iter()
            .map(|p| Polygon::new(rect(p.x - h, p.y - h, p.x + h, p.y + h)))
            .collect();
        pieces = open(&boolean::difference(&pieces, &squares)?, min_width)?;
    }
    // An opening on the grid is not quite idempotent (miter corners move by a step): open
    // again what is still found narrow.
    for _ in 0..ROUNDS {
        if !pieces
            .iter()
            .any(|p| validate(p, min_width).iter().any(|f| f.problem == Problem::Narrow))
        {
            break;
        }
        pieces = open(&pieces, min_width)?;
    }
    Ok(pieces)
}

/// The opening of `pieces` by half of `min_width` (none for 0), within `pieces`, without
/// crumbs, largest first.
fn open(pieces: &[Polygon], min_width: f64) -> Result<Vec<Polygon>, GridError> {
    // Miter joins make an opening grow back sharp corners where the shrink removed short
    // edges (a chamfer comes back square): intersected with the input, it never adds material.
    let opened = if min_width > 0.0 {
        boolean::intersection(&offset::opening(pieces, min_width / 2.0)?, pieces)?
    } else {
        pieces.to_vec()
    };
    let mut out: Vec<Polygon> = opened
        .into_iter()
        .filter(|p| p.area() >= GRID_NOISE_AREA)
        .map(|mut p| {
            p.holes
                .retain(|h| crate::polygon::signed_area(h).abs() >= GRID_NOISE_AREA);
            p.normalize_orientation();
            p
        })
        .collect();
    // Largest first; equal areas by their lowest corner, so the order never depends on the
    // boolean engine's output order.
    out.sort_by(|a, b| {
        let (la, lb) = (a.bounds().0, b.bounds().0);
        b.area()
            .total_cmp(&a.area())
            .then(la.x.total_cmp(&lb.x))
            .then(la.y.total_cmp(&lb.y))
    });
    Ok(out)
}

#[cfg(test)]
mod tests;
