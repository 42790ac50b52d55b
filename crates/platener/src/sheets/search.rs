//! Filling sheets: first fit over open sheets in a given part order, and the improvement phase
//! that tries several orders and keeps the best layout.
//!
//! Order 0 is largest area first (the classic first-fit-decreasing rule); order 1 is longest
//! box side first (long strips placed early leave fewer slivers); the others jitter the areas by
//! up to ±30 % with a seeded random generator. Tries run in parallel; the best is chosen by
//! (sheets used, length used on the last sheet, total length used, try number), so the result
//! depends only on the seed and the number of tries, never on thread timing.

use glam::DVec2;
use platener_geom::rng::SplitMix64;
use rayon::prelude::*;

use super::blf::{Bin, GAP, Placed};
use super::shape::NestShape;
use super::{compress, separate};

/// Keeps cut paths 1 µm inside the region so f32 rounding never puts them on the margin line.
const INSET: f64 = 1e-3;

/// The sheets of one layout: per sheet, what was placed.
#[derive(Debug, Clone)]
pub(crate) struct Layout {
    /// Per sheet, its placements (keys are shape indices).
    pub sheets: Vec<Vec<Placed>>,
    /// Per sheet, the right edge of its rightmost grown box.
    pub used_right: Vec<f64>,
}

impl Layout {
    /// Its last sheet replaced by `placed` (on a region whose left edge is `left`).
    fn replace_last(&mut self, placed: Vec<Placed>, left: f64) {
        if let (Some(sheet), Some(right)) = (self.sheets.last_mut(), self.used_right.last_mut()) {
            *right = super::blf::right_edge(&placed, left);
            *sheet = placed;
        }
    }

    fn score(&self) -> (usize, f64, f64) {
        let last = self.used_right.last().copied().unwrap_or(0.0);
        (self.sheets.len(), last, self.used_right.iter().sum())
    }
}

/// The free region of a `width` × `height` sheet for shapes grown by `spacing / 2`.
pub(crate) fn sheet_region(width: f64, height: f64, margin: f64, spacing: f64) -> (DVec2, DVec2) {
    // The bin keeps shapes `GAP` off its border; the cut paths then start `INSET` inside the margin.
    let lo = DVec2::splat(margin - spacing / 2.0 - GAP + INSET);
    let hi = DVec2::new(width, height) - lo;
    (lo, hi)
}

/// Whether `shape` fits an empty region of size `room` in some orientation.
pub(crate) fn fits_empty(shape: &NestShape, room: DVec2) -> bool {
    let room = room - DVec2::splat(2.0 * GAP);
    shape.templates.iter().any(|t| t.size.x <= room.x && t.size.y <= room.y)
}

/// First fit of `order` onto sheets with free region `lo..hi`; every item must fit an empty
/// sheet. Returns `None` if cancelled.
pub(crate) fn first_fit(
    shapes: &[NestShape],
    order: &[usize],
    lo: DVec2,
    hi: DVec2,
    cancelled: &(dyn Fn() -> bool + Sync),
) -> Option<Layout> {
    let mut bins: Vec<Bin> = Vec::new();
    for &item in order {
        if cancelled() {
            return None;
        }
        let shape = &shapes[item];
        if bins.iter_mut().any(|b| b.place(item, shape).is_some()) {
            continue;
        }
        let mut bin = Bin::rect(lo, hi)?;
        // Fits an empty sheet (checked by the caller), so this cannot fail; skip it if it does
        // rather than loop.
        bin.place(item, shape);
        bins.push(bin);
    }
    Some(Layout {
        used_right: bins.iter().map(Bin::used_right).collect(),
        sheets: bins.into_iter().map(|b| b.placed).collect(),
    })
}

/// The part order of try `t` (see the module docs).
pub(crate) fn order(shapes: &[NestShape], items: &[usize], t: u32, seed: u64) -> Vec<usize> {
    let longest = |i: usize| shapes[i].templates.first().map_or(0.0, |t| t.size.max_element());
    let mut keyed: Vec<(f64, usize)> = match t {
        0 => items.iter().map(|&i| (shapes[i].area, i)).collect(),
        1 => items.iter().map(|&i| (longest(i), i)).collect(),
        _ => {
            let mut rng = SplitMix64::new(seed ^ u64::from(t).wrapping_mul(0xA076_1D64_78BD_642F));
            items
                .iter()
                .map(|&i| (shapes[i].area * (0.7 + 0.6 * rng.unit()), i))
                .collect()
        }
    };
    keyed.sort_by(|a, b| b.0.total_cmp(&a.0).then(a.1.cmp(&b.1)));
    keyed.into_iter().map(|(_, i)| i).collect()
}

/// Runs `tries` orders in parallel and keeps the best layout (see the module docs).
pub(crate) fn best_layout(
    shapes: &[NestShape],
    items: &[usize],
    region: (DVec2, DVec2),
    tries: u32,
    seed: u64,
    cancelled: &(dyn Fn() -> bool + Sync),
) -> Option<Layout> {
    let mut layouts: Vec<(u32, Layout)> = (0..tries)
        .into_par_iter()
        .filter_map(|t| {
            let o = order(shapes, items, t, seed);
            first_fit(shapes, &o, region.0, region.1, cancelled).map(|l| (t, l))
        })
        .collect();
    // The last sheet's length is what the layouts were chosen by: shorten it further, from the
    // best few layouts (see `separate::Budget`), and keep the best result.
    let budget = separate::budget(tries);
    layouts.sort_by(|(ta, a), (tb, b)| compare(a, b).then(ta.cmp(tb)));
    let shrunk: Vec<Layout> = layouts
        .into_iter()
        .take(budget.starts)
        .enumerate()
        .collect::<Vec<_>>()
        .into_par_iter()
        .map(|(k, (_, layout))| shorten_last(shapes, layout, region, (budget, seed ^ k as u64), cancelled))
        .collect();
    shrunk.into_iter().min_by(compare)
}

/// Layouts by (sheets used, length used on the last sheet, total length used).
fn compare(a: &Layout, b: &Layout) -> std::cmp::Ordering {
    let (sa, sb) = (a.score(), b.score());
    sa.0.cmp(&sb.0).then(sa.1.total_cmp(&sb.1)).then(sa.2.total_cmp(&sb.2))
}

/// `layout` with its last sheet shortened by [`separate::shrink`] where it can be.
fn shorten_last(
    shapes: &[NestShape],
    mut layout: Layout,
    region: (DVec2, DVec2),
    (budget, seed): (separate::Budget, u64),
    cancelled: &(dyn Fn() -> bool + Sync),
) -> Layout {
    let compressed = layout
        .sheets
        .last()
        .and_then(|last| compress::compress(shapes, last, region, (budget.attempts, seed), cancelled));
    if let Some(shorter) = compressed {
        layout.replace_last(shorter, region.0.x);
    }
    let shrunk = layout
        .sheets
        .last()
        .and_then(|last| separate::shrink(shapes, last, region, (budget, seed), cancelled));
    if let Some(shorter) = shrunk {
        layout.replace_last(shorter, region.0.x);
    }
    layout
}

/// `--sheet fit`: the strip height that gives the smallest sheet. Heights around the square
/// root of the parts' box area (×0.7 … ×1.45) are tried with the largest-first order; the
/// height is never below the tallest part in its flattest orientation.
pub(crate) fn fit_height(
    shapes: &[NestShape],
    items: &[usize],
    margin: f64,
    spacing: f64,
    cancelled: &(dyn Fn() -> bool + Sync),
) -> f64 {
    let box_area: f64 = items
        .iter()
        .map(|&i| {
            shapes[i]
                .templates
                .iter()
                .map(|t| t.size.x * t.size.y)
                .fold(f64::INFINITY, f64::min)
        })
        .sum();
    let min_h = items
        .iter()
        .map(|&i| {
            shapes[i]
                .templates
                .iter()
                .map(|t| t.size.x.min(t.size.y))
                .fold(f64::INFINITY, f64::min)
        })
        .fold(0.0, f64::max);
    let frame = 2.0 * margin - spacing + 2.0 * INSET;
    let candidates: Vec<f64> = [0.7, 0.85, 1.0, 1.2, 1.45]
        .iter()
        .map(|f| (box_area.sqrt() * f).max(min_h) + frame)
        .collect();
    let o = order(shapes, items, 0, 0);
    let long = items
        .iter()
        .map(|&i| shapes[i].templates.first().map_or(0.0, |t| t.size.max_element()))
        .sum::<f64>()
        + frame;
    let areas: Vec<(f64, f64)> = candidates
        .par_iter()
        .filter_map(|&h| {
            let (lo, hi) = sheet_region(long, h, margin, spacing);
            let layout = first_fit(shapes, &o, lo, hi, cancelled)?;
            let right = layout.used_right.first().copied()?;
            (layout.sheets.len() == 1).then_some((h, (right + margin + spacing / 2.0) * h))
        })
        .collect();
    areas
        .into_iter()
        .min_by(|a, b| a.1.total_cmp(&b.1).then(a.0.total_cmp(&b.0)))
        .map_or(candidates[candidates.len() - 1], |(h, _)| h)
}
