//! The last resort of shaft placement: a *peg* for layers that would otherwise only be glued.
//!
//! A narrow neck (the teapot's lid knob, 5.7 mm across; a bracket's 5 mm strip) leaves no room
//! for a phase 1 or 2 shaft: a slot one shaft thickness wide keeps walls under the relaxed
//! margin, and those phases want slots at least several millimetres long. A peg relaxes both:
//! after phase 2, for each overlapping pair whose islands no shaft group holds together yet, a
//! short shaft is placed as in phase 1 (grown through consecutive layers while it fits) with
//! only [`PEG_MIN_WALL`] of material kept to the outline, and a slot at least as long as the
//! shaft is thick. Its slot keeps the relaxed margin's clearance from other slots, whose
//! bridges are that wide. The notch bridge beside a peg's slot is the wall itself
//! ([`PEG_MIN_WALL`]), so the wall is kept whole (`notch`).
//!
//! `fit_slot` searches the region shrunk by half the thickness on every side, which also
//! shortens the slot by half the thickness at each end: in a 3.7 mm square it finds 0.7 mm.
//! [`fit_peg`] gives those ends back and keeps the slot only if the full rectangle still lies
//! inside the region.

use platener_geom::polygon::total_area;
use platener_geom::{GridError, Polygon, boolean};

use super::extend::Extension;
use super::fit::{SlotLine, fit_slot};
use super::shafts::{Pair, Planner, Rule, SLIVER};
use crate::assembly::UnionFind;

/// The least material kept between a peg's slot and the layer's outline, mm.
pub const PEG_MIN_WALL: f64 = 1.0;
/// The phase number of pegs ([`super::Shaft::phase`]).
pub(crate) const PEG_PHASE: u8 = 3;

/// The longest slot `2·half` thick, `min_width..=max_width` long, whose full rectangle lies
/// inside `region`: [`fit_slot`]'s centre line extended by `half` at each end.
pub(crate) fn fit_peg(
    region: &[Polygon],
    half: f64,
    min_width: f64,
    max_width: f64,
) -> Result<Option<SlotLine>, GridError> {
    let inner_min = (min_width - 2.0 * half).max(SLIVER);
    let Some(line) = fit_slot(region, half, inner_min, (max_width - 2.0 * half).max(inner_min))? else {
        return Ok(None);
    };
    let peg = SlotLine {
        start: line.start - line.dir * half,
        dir: line.dir,
        width: line.width + 2.0 * half,
    };
    let rect = peg.rect(0.0, peg.width, half);
    let outside = boolean::difference(std::slice::from_ref(&rect), region)?;
    Ok((total_area(&outside) < SLIVER).then_some(peg))
}

impl Planner<'_> {
    /// The peg phase: for every overlapping pair whose islands are in different shaft groups,
    /// bottom up, a shaft ending in one of them extended into the other with a peg's wall (a
    /// shaft through the lid under the knob's neck), or else a new peg.
    pub(super) fn pegs(&mut self, pairs: &[Pair]) -> Result<(), GridError> {
        let rule = Rule {
            wall: PEG_MIN_WALL,
            clear: self.bridge(),
            min_width: 2.0 * self.half,
            phase: PEG_PHASE,
        };
        // An extended shaft narrows to its slot in the neck: as narrow as an island may be.
        let ext = Extension {
            min_band: self.s.min_width,
            wall: PEG_MIN_WALL,
            clear: rule.clear,
            peg: true,
        };
        for pair in pairs {
            if !self.held_together(pair) && !self.expand(pair, ext)? {
                self.connect(pair, rule)?;
            }
        }
        Ok(())
    }

    /// Whether the two islands of `pair` are in one group of the shafts placed so far (a shaft
    /// with one slot holds nothing).
    fn held_together(&self, pair: &Pair) -> bool {
        let offsets: Vec<usize> = self
            .islands
            .iter()
            .scan(0, |n, l| {
                let at = *n;
                *n += l.len();
                Some(at)
            })
            .collect();
        let index = |layer: usize, island: usize| offsets[layer] + island;
        let total = self.islands.iter().map(Vec::len).sum();
        let mut groups = UnionFind::new(total);
        for sh in self.shafts.iter().filter(|s| s.bands.len() >= 2) {
            for w in sh.bands.windows(2) {
                groups.join(index(w[0].layer, w[0].island), index(w[1].layer, w[1].island));
            }
        }
        let lower = groups.root(index(pair.k, pair.lower));
        lower == groups.root(index(pair.k + 1, pair.upper))
    }
}
