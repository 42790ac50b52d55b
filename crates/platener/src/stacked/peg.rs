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
use super::fit::{SlotLine, best_slot};
use super::shafts::{Pair, PlacedShaft, Planner, Rule, SLIVER};
use crate::assembly::UnionFind;

pub use crate::cuttable::PEG_MIN_WALL;
/// Grid slack, mm: walls are kept `PEG_MIN_WALL` less this, and a peg's ends stop this short
/// of the region's, so a strip exactly a peg and two walls wide (the bracket's 5 mm strip for
/// a 3 mm peg) still takes one despite the 1 µm grid's rounding.
const PEG_SLACK: f64 = 0.01;
/// The phase number of pegs ([`super::Shaft::phase`]).
pub(crate) const PEG_PHASE: u8 = 3;

/// The longest slot `2·half` thick, `min_width..=max_width` long, whose full rectangle lies
/// inside `region`: a candidate centre line of [`best_slot`] extended by `half` (less the
/// slack) at each end, kept when its rectangle still lies inside (a diagonal in a square does
/// not; the square's side does).
pub(crate) fn fit_peg(
    region: &[Polygon],
    half: f64,
    min_width: f64,
    max_width: f64,
) -> Result<Option<SlotLine>, GridError> {
    let end = half - PEG_SLACK;
    best_slot(region, half, (max_width - 2.0 * end).max(0.0), |line| {
        let peg = SlotLine {
            start: line.start - line.dir * end,
            dir: line.dir,
            width: line.width + 2.0 * end,
        };
        if peg.width < min_width {
            return Ok(None);
        }
        let rect = peg.rect(0.0, peg.width, half);
        let outside = boolean::difference(std::slice::from_ref(&rect), region)?;
        Ok((total_area(&outside) < SLIVER).then_some(peg))
    })
}

impl Planner<'_> {
    /// The peg phase: for every overlapping pair whose islands are in different shaft groups,
    /// bottom up, a shaft ending in one of them extended into the other with a peg's wall (a
    /// shaft through the lid under the knob's neck), or else a new peg.
    pub(super) fn pegs(&mut self, pairs: &[Pair]) -> Result<(), GridError> {
        let rule = Rule {
            wall: PEG_MIN_WALL - PEG_SLACK,
            clear: self.bridge(),
            min_width: 2.0 * self.half,
            phase: PEG_PHASE,
        };
        // An extended shaft narrows to its slot in the neck: as narrow as an island may be.
        let ext = Extension {
            min_band: self.s.min_width,
            wall: PEG_MIN_WALL - PEG_SLACK,
            clear: rule.clear,
            peg: true,
        };
        for pair in pairs {
            if self.held_together(pair) {
                continue;
            }
            if let Some(bossed) = self.in_boss(pair)?
                && self.connect(&bossed, rule)?
            {
                continue;
            }
            if !self.expand(pair, ext)? {
                self.connect(pair, rule)?;
            }
        }
        Ok(())
    }

    /// `pair` with its overlap cut down to the boss added for it, if there is one: the peg
    /// goes there (in the whole overlap the longest chord, looked for first, may lie where no
    /// peg fits).
    fn in_boss(&self, pair: &Pair) -> Result<Option<Pair>, GridError> {
        let Some(boss) = self
            .bosses
            .iter()
            .find(|b| (b.layer, b.lower, b.upper) == (pair.k, pair.lower, pair.upper))
        else {
            return Ok(None);
        };
        let overlap = boolean::intersection(&pair.overlap, std::slice::from_ref(&boss.square))?;
        Ok(Some(Pair {
            k: pair.k,
            lower: pair.lower,
            upper: pair.upper,
            area: total_area(&overlap),
            overlap,
        }))
    }

    /// Whether the two islands of `pair` are in one group of the shafts placed so far (a shaft
    /// with one slot holds nothing).
    fn held_together(&self, pair: &Pair) -> bool {
        IslandGroups::of(self.islands, &self.shafts).same(pair.k, pair.lower, pair.upper)
    }
}

/// The groups of islands the shafts hold together (a shaft with one slot holds nothing).
pub(super) struct IslandGroups {
    /// Per layer, the index of its first island among all.
    offsets: Vec<usize>,
    groups: UnionFind,
}

impl IslandGroups {
    pub(super) fn of(islands: &[Vec<Polygon>], shafts: &[PlacedShaft]) -> Self {
        let offsets: Vec<usize> = islands
            .iter()
            .scan(0, |n, l| {
                let at = *n;
                *n += l.len();
                Some(at)
            })
            .collect();
        let total = islands.iter().map(Vec::len).sum();
        let mut g = IslandGroups {
            offsets,
            groups: UnionFind::new(total),
        };
        for sh in shafts.iter().filter(|s| s.bands.len() >= 2) {
            for w in sh.bands.windows(2) {
                g.join(w[0].layer, w[0].island, w[1].island);
            }
        }
        g
    }

    fn index(&self, layer: usize, island: usize) -> usize {
        self.offsets[layer] + island
    }

    /// Whether island `lower` of layer `k` and island `upper` of layer `k + 1` are held together.
    pub(super) fn same(&mut self, k: usize, lower: usize, upper: usize) -> bool {
        let (a, b) = (self.index(k, lower), self.index(k + 1, upper));
        self.groups.root(a) == self.groups.root(b)
    }

    /// Counts island `lower` of layer `k` and island `upper` of layer `k + 1` as held together.
    pub(super) fn join(&mut self, k: usize, lower: usize, upper: usize) {
        let (a, b) = (self.index(k, lower), self.index(k + 1, upper));
        self.groups.join(a, b);
    }
}

#[cfg(test)]
pub(super) mod tests {
    use super::*;
    use crate::stacked::fit::fit_slot;

    /// The rectangle `x0..x1` × `y0..y1`, counter-clockwise.
    pub(in crate::stacked) fn rect(x0: f64, y0: f64, x1: f64, y1: f64) -> Polygon {
        let mut p = Polygon::new(platener_geom::polygon::rect(x0, y0, x1, y1));
        p.normalize_orientation();
        p
    }

    #[test]
    fn a_peg_gets_back_the_ends_fit_slot_shortens() {
        // A 3.7 mm square (a 5.7 mm neck minus 1 mm walls): fit_slot finds under 1 mm of centre
        // line for a 3 mm slot (the 0.7 mm square's diagonal); the peg is the full 3.7 mm along
        // a side (less the slack at each end).
        let region = [rect(0.0, 0.0, 3.7, 3.7)];
        let slot = fit_slot(&region, 1.5, 0.1, 60.0).expect("grid").expect("a chord");
        assert!(slot.width < 1.0, "{}", slot.width);
        let peg = fit_peg(&region, 1.5, 3.0, 60.0).expect("grid").expect("a peg");
        assert!((peg.width - (3.7 - 2.0 * PEG_SLACK)).abs() < 0.01, "{}", peg.width);
        let r = peg.rect(0.0, peg.width, 1.5);
        let out = boolean::difference(std::slice::from_ref(&r), &region).expect("grid");
        assert!(total_area(&out) < SLIVER);
        // Too short for the minimum, or no room across: none.
        assert!(fit_peg(&region, 1.5, 4.0, 60.0).expect("grid").is_none());
        assert!(
            fit_peg(&[rect(0.0, 0.0, 2.9, 20.0)], 1.5, 3.0, 60.0)
                .expect("grid")
                .is_none()
        );
    }
}
