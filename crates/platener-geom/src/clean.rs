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
//! 4. *Trim wedges*: a thin wedge (a spike tapering to a point) survives a miter opening,
//!    which grows its tip back from the wider base; what a bevelled opening removes there
//!    ([`offset::opening_bevelled`]) is cut away where the check still finds narrow material.
//! 5. Pieces and holes with no area to speak of ([`GRID_NOISE_AREA`]) are dropped.
//!
//! Cutting narrow material away is right for slivers and spikes, but where a neck narrower
//! than the width holds a large piece it would cut that piece off: [`widen`] instead grows the
//! narrow material to the width, for callers that refuse a repair that loses too much.
//!
//! A polygon that is already valid is returned unchanged (same vertices), so clean outlines are
//! never moved by a grid round trip.

use glam::DVec2;

use crate::grid::{GridError, STEP};
use crate::polygon::{Polygon, rect};
use crate::tolerance::GRID_NOISE_AREA;
use crate::validity::{Problem, narrow_material, validate};
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
    // again what is still found narrow; then cut away thin wedges the opening grows back.
    for round in 0..ROUNDS {
        if !pieces.iter().any(|p| is_narrow(p, min_width)) {
            break;
        }
        if round > 0 {
            pieces = trim_wedges(&pieces, min_width)?;
        }
        pieces = open(&pieces, min_width)?;
    }
    Ok(pieces)
}

/// Whether the check finds material of `polygon` narrower than `min_width`.
fn is_narrow(polygon: &Polygon, min_width: f64) -> bool {
    validate(polygon, min_width)
        .iter()
        .any(|f| f.problem == Problem::Narrow)
}

/// `pieces` without the narrow wedges the check finds: for each piece with narrow material
/// ([`narrow_material`]), what a bevelled opening by half the width removes is cut away where
/// it holds that material (the rest of what it removes is corner crumbs, which stay).
fn trim_wedges(pieces: &[Polygon], min_width: f64) -> Result<Vec<Polygon>, GridError> {
    let mut out = Vec::with_capacity(pieces.len());
    for piece in pieces {
        let cores = narrow_material(piece, min_width)?;
        if cores.is_empty() {
            out.push(piece.clone());
            continue;
        }
        let one = std::slice::from_ref(piece);
        let lost = boolean::difference(one, &offset::opening_bevelled(one, min_width / 2.0)?)?;
        let wedges: Vec<Polygon> = lost
            .into_iter()
            .filter(|l| cores.iter().any(|c| overlaps(l.bounds(), c.bounds())))
            .collect();
        out.extend(boolean::difference(one, &wedges)?);
    }
    Ok(out)
}

/// Whether two bounding boxes (lower, upper corner) overlap.
fn overlaps(a: (DVec2, DVec2), b: (DVec2, DVec2)) -> bool {
    a.0.x <= b.1.x && b.0.x <= a.1.x && a.0.y <= b.1.y && b.0.y <= a.1.y
}

/// `polygon` with its necks narrower than `min_width` grown to at least that, never into
/// `keep_out` (slots and notches a mating part fills), then [`clean`]ed: the repair for a
/// neck that holds a large piece, which cutting would lose.
/// The necks are the strips an opening removes that the opened polygon meets in two places
/// ([`crate::necks`]), short pinches included. They grow by the whole width on every side, so
/// a neck of width `d` becomes at least `d + min_width` wide even where `keep_out` lets it grow
/// on one side only; the material added is about the neck's length times twice the width. Long narrow material the check finds ([`narrow_material`]) is grown too:
/// a neck the opening meets on one side only (a lobe whose own opening vanishes) is no strip.
pub fn widen(polygon: &Polygon, min_width: f64, keep_out: &[Polygon]) -> Result<Vec<Polygon>, GridError> {
    let mut normalized = polygon.clone();
    normalized.normalize_orientation();
    let regular = boolean::union_all(&[normalized])?;
    let mut cores = Vec::new();
    for piece in &regular {
        cores.extend(crate::necks::strips(piece, min_width / 2.0, GRID_NOISE_AREA)?);
        cores.extend(narrow_material(piece, min_width)?);
    }
    if cores.is_empty() {
        return clean(polygon, min_width);
    }
    // Bevelled: a sliver's sharp ends would otherwise grow miter spikes millimetres long.
    let mut grown = offset::offset_bevelled(&cores, min_width + MIN_SEPARATION)?;
    if !keep_out.is_empty() {
        grown = boolean::difference(&grown, keep_out)?;
    }
    let widened = boolean::union(&regular, &grown)?;
    let mut out = Vec::new();
    for piece in &widened {
        out.extend(clean(piece, min_width)?);
    }
    out.sort_by(|a, b| b.area().total_cmp(&a.area()));
    Ok(out)
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
