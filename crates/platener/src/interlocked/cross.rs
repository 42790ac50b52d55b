//! Crossings and their halved slots.
//!
//! Slice A at one plane and slice B at the other cross in a vertical column, a sheet thick
//! each way. At height z the column holds A's material where A's section meets the column's
//! strip, and B's likewise: their *column extents*. They share volume where those overlap. A
//! split height h removes that: A loses its strip below h (a slot open at the bottom), B its
//! strip above h (a slot open at the top). Then A's material in the column lies above every
//! bit of B's, in place and all the way down as A is lowered from above: the slots are both
//! what holds the slices and what lets them be put together.
//!
//! h is the middle of the shared range (each slot half the crossing, as a halved joint is),
//! unless that cuts a slice apart; then a quarter or three quarters, then the ends (one slice
//! unslotted, the other slotted over the whole range). Only when every height splits a slice
//! does the middle stand and the slice fall into pieces, each held by its own slots.

use glam::DVec2;
use platener_geom::polygon::rect;
use platener_geom::tolerance::CRUMB_AREA;
use platener_geom::{GridError, Polygon, boolean, offset};
use serde::Serialize;

use super::place::{Family, Sections};
use crate::cuttable::Rule;

/// Two z ranges closer than this (mm) neither overlap nor need a slot.
pub(super) const TOUCH: f64 = 1e-3;
/// A column is measured this much narrower on each side (mm) than the slot: material along a
/// slot's wall within a few steps of the booleans' 1 µm grid is rounding, not material in the
/// column (5 µm, far inside any laser's fit).
pub const WALL_SLACK: f64 = 0.005;

/// One crossing of an A slice and a B slice.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Crossing {
    /// The A slice's index and the B slice's index.
    pub slices: [usize; 2],
    /// The column's x in the A family's 2D frame, and in the B family's.
    pub at: [f64; 2],
    /// The split height: A keeps the column above it, B below.
    pub split: f64,
    /// The heights over which both slices had material in the column (empty: none; the slots
    /// then only let A pass B's material on its way down).
    pub shared: Option<[f64; 2]>,
    /// The A piece and the B piece the crossing holds (part ids), once the pieces are known.
    pub parts: [u32; 2],
}

/// The z ranges `[bottom, top]` of `material` within the vertical strip of half-width
/// `half` (less [`WALL_SLACK`]) around x = `x`: where a crossing column there has material.
/// Sorted, merged.
pub fn column_extent(material: &[Polygon], x: f64, half: f64) -> Result<Vec<[f64; 2]>, GridError> {
    let Some((lo, hi)) = bounds(material) else {
        return Ok(Vec::new());
    };
    if x + half <= lo.x || x - half >= hi.x {
        return Ok(Vec::new());
    }
    let half = half - WALL_SLACK;
    let strip = Polygon::new(rect(x - half, lo.y - 1.0, x + half, hi.y + 1.0));
    let mut ranges: Vec<[f64; 2]> = boolean::intersection(material, &[strip])?
        .iter()
        .filter(|p| p.area() >= CRUMB_AREA)
        .map(|p| {
            let (a, b) = p.bounds();
            [a.y, b.y]
        })
        .collect();
    ranges.sort_by(|a, b| a[0].total_cmp(&b[0]).then(a[1].total_cmp(&b[1])));
    let mut merged: Vec<[f64; 2]> = Vec::new();
    for r in ranges {
        match merged.last_mut() {
            Some(last) if r[0] <= last[1] => last[1] = last[1].max(r[1]),
            _ => merged.push(r),
        }
    }
    Ok(merged)
}

/// The hull of the heights where two extents overlap by more than [`TOUCH`].
pub(super) fn shared(a: &[[f64; 2]], b: &[[f64; 2]]) -> Option<[f64; 2]> {
    let mut hull: Option<[f64; 2]> = None;
    for p in a {
        for q in b {
            let (lo, hi) = (p[0].max(q[0]), p[1].min(q[1]));
            if hi - lo > TOUCH {
                hull = Some(hull.map_or([lo, hi], |h| [h[0].min(lo), h[1].max(hi)]));
            }
        }
    }
    hull
}

fn bounds(material: &[Polygon]) -> Option<(DVec2, DVec2)> {
    platener_geom::boxes::enclosing2(material.iter().map(Polygon::bounds))
}

/// Every slice's material after its slots, and the crossings.
#[derive(Debug, Clone)]
pub struct Crossed {
    /// Per family, per slice, its material (every island) minus its slots.
    pub material: [Vec<Vec<Polygon>>; 2],
    /// The crossings, by A slice then B slice.
    pub crossings: Vec<Crossing>,
    /// Islands too small to cut, from the sections.
    pub too_small: Vec<(usize, usize, f64)>,
}

/// Cuts the slots of every crossing of `sections` (slot width `thickness`), never leaving
/// material narrower than `min_width` (the kerf: a slot wall on a section's edge leaves a
/// sliver no laser cuts).
pub fn cut(
    families: &[Family; 2],
    sections: &Sections,
    thickness: f64,
    min_width: f64,
    rule: &Rule,
) -> Result<Crossed, GridError> {
    let trim = Trim { min_width, rule };
    let mut material = sections.islands.clone();
    for slices in &mut material {
        for m in slices.iter_mut() {
            *m = trim.apply(m)?;
        }
    }
    let mut crossings = Vec::new();
    let half = thickness / 2.0;
    for i in 0..families[0].count() {
        for j in 0..families[1].count() {
            let at = column(families, i, j);
            let (a, b) = (&material[0][i], &material[1][j]);
            let (za, zb) = (column_extent(a, at[0], half)?, column_extent(b, at[1], half)?);
            let (Some(a_lo), Some(b_hi)) = (za.first().map(|r| r[0]), zb.last().map(|r| r[1])) else {
                continue;
            };
            if a_lo >= b_hi - TOUCH {
                // A's material lies above B's already: nothing to cut.
                continue;
            }
            let both = shared(&za, &zb);
            let range = both.unwrap_or([a_lo, b_hi]);
            let (new_a, new_b, split) = best_split(a, b, at, half, range, &trim)?;
            material[0][i] = new_a;
            material[1][j] = new_b;
            crossings.push(Crossing {
                slices: [i, j],
                at,
                split,
                shared: both,
                parts: [0, 0],
            });
        }
    }
    Ok(Crossed {
        material,
        crossings,
        too_small: sections.too_small.clone(),
    })
}

/// Where slice `i` of A and slice `j` of B cross: the column's x in each family's frame.
pub(super) fn column(families: &[Family; 2], i: usize, j: usize) -> [f64; 2] {
    let (fa, fb) = (&families[0].plan.frame, &families[1].plan.frame);
    // The column is the vertical line at offset(i) along A's normal and offset(j) along B's.
    let p = fa.n * families[0].offset(i) + fb.n * families[1].offset(j);
    [fa.to_2d(p).x, fb.to_2d(p).x]
}

/// The first split height in the shared `range` (middle, quarters, ends) whose slots leave
/// both slices in as many pieces worth cutting as before, and the slotted slices; the middle
/// when none does.
fn best_split(
    a: &[Polygon],
    b: &[Polygon],
    at: [f64; 2],
    half: f64,
    range: [f64; 2],
    trim: &Trim<'_>,
) -> Result<(Vec<Polygon>, Vec<Polygon>, f64), GridError> {
    let rule = trim.rule;
    let before = [pieces(a, rule), pieces(b, rule)];
    let [lo, hi] = range;
    let mut first = None;
    for share in [0.5, 0.25, 0.75, 0.0, 1.0] {
        let h = lo + share * (hi - lo);
        let new_a = trim.apply(&slot(a, at[0], half, h, true)?)?;
        let new_b = trim.apply(&slot(b, at[1], half, h, false)?)?;
        if pieces(&new_a, rule) == before[0] && pieces(&new_b, rule) == before[1] {
            return Ok((new_a, new_b, h));
        }
        first.get_or_insert((new_a, new_b, h));
    }
    Ok(first.expect("five heights were tried"))
}

/// `material` minus the strip of half-width `half` around x = `x`, below `h` (`below`) or
/// above it.
fn slot(material: &[Polygon], x: f64, half: f64, h: f64, below: bool) -> Result<Vec<Polygon>, GridError> {
    let Some((lo, hi)) = bounds(material) else {
        return Ok(Vec::new());
    };
    let (y0, y1) = if below { (lo.y - 1.0, h) } else { (h, hi.y + 1.0) };
    if y1 <= y0 {
        return Ok(material.to_vec());
    }
    let mut cut = boolean::difference(material, &[Polygon::new(rect(x - half, y0, x + half, y1))])?;
    cut.retain(|p| p.area() >= CRUMB_AREA);
    Ok(cut)
}

/// What slotting keeps of a slice: nothing narrower than `min_width`, judged by `rule`.
struct Trim<'a> {
    min_width: f64,
    rule: &'a Rule,
}

impl Trim<'_> {
    /// `material` without its parts narrower than the kerf (an opening a grid step wider, kept
    /// within `material`: mitred corners of the opening may reach past a slot's wall).
    fn apply(&self, material: &[Polygon]) -> Result<Vec<Polygon>, GridError> {
        if self.min_width <= 0.0 || material.is_empty() {
            return Ok(material.to_vec());
        }
        let opened = offset::opening(material, self.min_width / 2.0 + WALL_SLACK)?;
        let mut kept = boolean::intersection(&opened, material)?;
        kept.retain(|p| p.area() >= CRUMB_AREA);
        Ok(kept)
    }
}

/// `(pieces worth cutting, all pieces)` of `material`.
fn pieces(material: &[Polygon], rule: &Rule) -> (usize, usize) {
    (material.iter().filter(|p| rule.keeps(p)).count(), material.len())
}
