//! Phase 2 of shaft placement: a shaft ending in one island of an unjoined pair is extended
//! into the other, cut flush with that island's outline (see `shafts` for the three phases).
//!
//! The extension's slot covers the longest stretch of the shaft's previous slot whose columns
//! (the shaft's thickness across) lie inside the island, clear of other slots by half the
//! margin: where the island ends, the shaft ends, so it is flush with the layer's outline, and
//! since each slot lies within the one before, the shaft only narrows towards its ends and
//! layers still slide on from there. A slot that would cut the island in two is shortened by
//! the margin at one end, the other, or both, leaving a bridge.

use platener_geom::{GridError, Polygon, boolean, offset};

use super::Band;
use super::fit::SlotLine;
use super::notch::cut_slots;
use super::peg::PEG_MIN_WALL;
use super::shafts::{Pair, Planner, SLIVER};

/// How a shaft is extended: its shortest slot, the wall kept to the island's outline and the
/// clearance to other slots (mm), and whether it is a peg's (whose bridge is the wall).
#[derive(Debug, Clone, Copy)]
pub(super) struct Extension {
    pub min_band: f64,
    pub wall: f64,
    pub clear: f64,
    pub peg: bool,
}

impl Planner<'_> {
    /// Phase 2 (and pegs): extends a shaft ending in one island of `pair` into the other.
    pub(super) fn expand(&mut self, pair: &Pair, ext: Extension) -> Result<bool, GridError> {
        for i in 0..self.shafts.len() {
            let sh = &self.shafts[i];
            let (first, last) = (sh.bands[0], sh.bands[sh.bands.len() - 1]);
            let target = if last.layer == pair.k && last.island == pair.lower {
                Some((last, pair.k + 1, pair.upper, true))
            } else if first.layer == pair.k + 1 && first.island == pair.upper {
                Some((first, pair.k, pair.lower, false))
            } else {
                None
            };
            let Some((prev, m, x, up)) = target else {
                continue;
            };
            if let Some(band) = self.band_in(&sh.line, prev, m, x, ext)? {
                let line = sh.line;
                self.slots[m].push((x, line.rect(band.from, band.to, self.half)));
                let sh = &mut self.shafts[i];
                if ext.peg {
                    sh.pegged.push(m);
                }
                if up {
                    sh.bands.push(band);
                } else {
                    sh.bands.insert(0, band);
                }
                self.joined.insert((pair.k, pair.lower, pair.upper));
                return Ok(true);
            }
        }
        Ok(false)
    }

    /// The slot a shaft along `line` gets in island `x` of layer `m`, next to its slot `prev`:
    /// the longest stretch of `prev`'s whose columns lie in the island clear of other slots.
    fn band_in(
        &self,
        line: &SlotLine,
        prev: Band,
        m: usize,
        x: usize,
        ext: Extension,
    ) -> Result<Option<Band>, GridError> {
        let rect = line.rect(prev.from, prev.to, self.half);
        let clear = self.keep_clear(m, ext.clear)?;
        let island = std::slice::from_ref(&self.islands[m][x]);
        let mut allowed = if ext.wall > 0.0 {
            offset::offset(island, -ext.wall)?
        } else {
            island.to_vec()
        };
        if !clear.is_empty() {
            allowed = boolean::difference(&allowed, &clear)?;
        }
        let outside = boolean::difference(std::slice::from_ref(&rect), &allowed)?;
        // Stretches of the centre line whose columns leave the island.
        let mut forbidden: Vec<(f64, f64)> = outside
            .iter()
            .filter(|p| p.area() > SLIVER)
            .map(|p| {
                p.outer
                    .iter()
                    .map(|q| line.dir.dot(*q - line.start))
                    .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), s| (a.min(s), b.max(s)))
            })
            .collect();
        forbidden.sort_by(|a, b| a.0.total_cmp(&b.0));
        let mut best: Option<(f64, f64)> = None;
        let mut at = prev.from;
        for (a, b) in forbidden.iter().copied().chain([(prev.to, prev.to)]) {
            let (lo, hi) = (at, a.min(prev.to));
            if hi - lo > best.map_or(0.0, |(l, h)| h - l) {
                best = Some((lo, hi));
            }
            at = at.max(b);
        }
        let Some((from, to)) = best else {
            return Ok(None);
        };
        // The island must stay in one piece with all its slots: a slot running out of the
        // island at both ends would cut it in two (or pinch it, which `cut_slots` opens into a
        // cut), so it is shortened by the margin at one end, then at the other, then at both,
        // leaving a bridge.
        let shorten = self.s.margin;
        let others: Vec<(Polygon, f64)> = self.slots[m]
            .iter()
            .filter(|(i, _)| *i == x)
            .map(|(_, r)| (r.clone(), self.bridge()))
            .collect();
        let bridge = if ext.peg { PEG_MIN_WALL } else { self.bridge() };
        for (a, b) in [
            (from, to),
            (from, to - shorten),
            (from + shorten, to),
            (from + shorten, to - shorten),
        ] {
            if b - a < ext.min_band {
                continue;
            }
            let mut cuts = others.clone();
            cuts.push((line.rect(a, b, self.half), bridge));
            // Cut as `assemble` will cut it: a pinch beside the slot is opened, so a slot
            // that nearly crosses the island splits it here and is shortened instead.
            if cut_slots(&self.islands[m][x], &cuts)?.len() == 1 {
                return Ok(Some(Band {
                    layer: m,
                    island: x,
                    from: a,
                    to: b,
                }));
            }
        }
        Ok(None)
    }
}
