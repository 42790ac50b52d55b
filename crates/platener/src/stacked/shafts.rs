//! Where the shafts go: the seed's three phases.
//!
//! Two islands of adjacent layers *overlap* when their outlines intersect (by more than
//! [`MIN_OVERLAP`] mm²); every overlapping pair should end up joined by a shaft.
//!
//! 1. **Connect as many as possible.** Pairs are taken bottom up. For a pair not yet joined,
//!    the usable region is their overlap shrunk by the margin, minus every slot already in
//!    either layer grown by the margin. The shaft then grows up, then down, one layer at a time,
//!    into the island whose outline (shrunk by the margin, clear of its slots) keeps the most of
//!    the region, as long as a slot at least the minimum shaft width still fits; its slot is the
//!    longest one in what is left (at most the maximum width). So a shaft runs through as many
//!    consecutive layers as the overlap of their outlines allows, and every slot keeps the
//!    margin to the outline and to other slots.
//! 2. **Expand shafts to connect layers left unconnected.** For each pair still not joined, a
//!    shaft ending in one of the two islands is extended into the other: its slot there covers
//!    the stretch of its centre line whose columns lie inside the island (clear of other
//!    slots), within its previous slot, so the shaft is cut flush with the layer's outline where
//!    it comes out of it and narrows outwards (layers still slide on from its ends). A slot that
//!    would cut the island in two is shortened by the margin at one end or both, leaving a
//!    bridge; one shorter than a stub is refused. Failing that, a new shaft is placed as in
//!    phase 1 with half the margin and half the width.
//! 3. **Remove shafts joining fewer than two layers.**
//!
//! Phase 2's extension lives in `extend`. Before phase 3, pairs whose islands no shaft group
//! holds together yet get a peg, a short shaft with thinner walls (`peg`).
//!
//! A shaft only ever spans consecutive layers and has a slot in each of them, so it never
//! bridges a layer it does not pass through.

use std::collections::BTreeSet;

use platener_geom::polygon::total_area;
use platener_geom::{GridError, Polygon, boolean, offset};
use rayon::prelude::*;

use super::boss::Boss;
use super::extend::Extension;
use super::fit::{SlotLine, fit_slot};
use super::peg::{PEG_PHASE, fit_peg};
use super::{Band, Unjoined};
use crate::settings::StackedSettings;

/// Islands of adjacent layers overlapping by less than this (mm²) are not considered to touch.
pub const MIN_OVERLAP: f64 = 0.01;
/// Pieces of a boolean under this area (mm²) are grid rounding, not geometry.
pub(super) const SLIVER: f64 = 1e-4;

/// A shaft as placed: its centre line and the slots it has.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct PlacedShaft {
    pub line: SlotLine,
    pub bands: Vec<Band>,
    pub phase: u8,
    /// Layers whose slot the peg phase added by extending the shaft (their walls are a peg's).
    pub pegged: Vec<usize>,
}

/// The result of placement.
#[derive(Debug, Clone)]
pub(crate) struct Placed {
    pub shafts: Vec<PlacedShaft>,
    pub unjoined: Vec<Unjoined>,
    pub removed: usize,
    /// The narrowest material kept between a slot and the outline, mm ([`Planner::bridge`]).
    pub bridge: f64,
}

impl Placed {
    /// The narrowest material kept beside `shaft`'s slot in layer `k`, mm: a peg's wall, or
    /// [`Placed::bridge`].
    pub fn bridge_of(&self, shaft: &PlacedShaft, k: usize) -> f64 {
        if shaft.phase == PEG_PHASE || shaft.pegged.contains(&k) {
            super::peg::PEG_MIN_WALL
        } else {
            self.bridge
        }
    }
}

/// Two overlapping islands of layers `k` and `k + 1`.
pub(super) struct Pair {
    pub k: usize,
    pub lower: usize,
    pub upper: usize,
    pub overlap: Vec<Polygon>,
    pub area: f64,
}

/// How a new shaft is placed: the material kept to the outline (`wall`) and to other slots
/// (`clear`), mm, the shortest slot, and the phase it counts as.
#[derive(Debug, Clone, Copy)]
pub(super) struct Rule {
    pub wall: f64,
    pub clear: f64,
    pub min_width: f64,
    pub phase: u8,
}

impl Rule {
    /// Phases 1 and 2: the same margin to the outline and to other slots.
    fn margin(margin: f64, min_width: f64, phase: u8) -> Self {
        Rule {
            wall: margin,
            clear: margin,
            min_width,
            phase,
        }
    }
}

/// The state of placement: the islands, the slots cut so far and the pairs they join.
pub(super) struct Planner<'a> {
    pub islands: &'a [Vec<Polygon>],
    pub s: &'a StackedSettings,
    /// Half the shaft thickness.
    pub half: f64,
    /// Per layer, the slots cut so far: (island, rectangle).
    pub slots: Vec<Vec<(usize, Polygon)>>,
    pub shafts: Vec<PlacedShaft>,
    pub joined: BTreeSet<(usize, usize, usize)>,
    /// Bosses added for pegs (`boss`): the peg phase puts a boss's peg in it.
    pub bosses: &'a [Boss],
}

/// Places shafts `shaft_thickness` thick through the layers' `islands`.
pub(crate) fn place(islands: &[Vec<Polygon>], s: &StackedSettings, shaft_thickness: f64) -> Result<Placed, GridError> {
    place_bossed(islands, s, shaft_thickness, &[])
}

/// [`place`] through islands that carry `bosses` (already added to them).
pub(crate) fn place_bossed(
    islands: &[Vec<Polygon>],
    s: &StackedSettings,
    shaft_thickness: f64,
    bosses: &[Boss],
) -> Result<Placed, GridError> {
    let pairs = overlapping_pairs(islands)?;
    let mut p = Planner {
        islands,
        s,
        half: shaft_thickness / 2.0,
        slots: vec![Vec::new(); islands.len()],
        shafts: Vec::new(),
        joined: BTreeSet::new(),
        bosses,
    };
    // Phase 1.
    for pair in &pairs {
        if !p.is_joined(pair) {
            p.connect(pair, Rule::margin(s.margin, s.shaft_min_width, 1))?;
        }
    }
    // Phase 2.
    let relaxed_width = (s.shaft_min_width / 2.0).max(4.0 * p.half);
    for pair in &pairs {
        let ext = Extension {
            min_band: relaxed_width,
            wall: 0.0,
            clear: s.margin / 2.0,
            peg: false,
        };
        if !p.is_joined(pair) && !p.expand(pair, ext)? {
            p.connect(pair, Rule::margin(s.margin / 2.0, relaxed_width, 2))?;
        }
    }
    p.pegs(&pairs)?;
    // Phase 3.
    let before = p.shafts.len();
    p.shafts.retain(|sh| sh.bands.len() >= 2);
    let removed = before - p.shafts.len();
    let joined: BTreeSet<(usize, usize, usize)> = p
        .shafts
        .iter()
        .flat_map(|sh| sh.bands.windows(2).map(|w| (w[0].layer, w[0].island, w[1].island)))
        .collect();
    let unjoined = pairs
        .iter()
        .filter(|q| !joined.contains(&(q.k, q.lower, q.upper)))
        .map(|q| Unjoined {
            layer: q.k,
            lower: q.lower,
            upper: q.upper,
            overlap: q.area,
        })
        .collect();
    Ok(Placed {
        bridge: p.bridge(),
        shafts: p.shafts,
        unjoined,
        removed,
    })
}

/// Every overlapping pair of islands in adjacent layers, bottom up.
fn overlapping_pairs(islands: &[Vec<Polygon>]) -> Result<Vec<Pair>, GridError> {
    let per_layer: Vec<Vec<Pair>> = (0..islands.len().saturating_sub(1))
        .into_par_iter()
        .map(|k| {
            let mut out = Vec::new();
            for (i, a) in islands[k].iter().enumerate() {
                for (j, b) in islands[k + 1].iter().enumerate() {
                    if !boxes_meet(a, b) {
                        continue;
                    }
                    let overlap = boolean::intersection(std::slice::from_ref(a), std::slice::from_ref(b))?;
                    let area = total_area(&overlap);
                    if area > MIN_OVERLAP {
                        out.push(Pair {
                            k,
                            lower: i,
                            upper: j,
                            overlap,
                            area,
                        });
                    }
                }
            }
            Ok(out)
        })
        .collect::<Result<_, GridError>>()?;
    Ok(per_layer.into_iter().flatten().collect())
}

/// Whether the bounds of `a` and `b` meet (a cheap test before a boolean).
pub(super) fn boxes_meet(a: &Polygon, b: &Polygon) -> bool {
    let ((a0, a1), (b0, b1)) = (a.bounds(), b.bounds());
    a0.x <= b1.x && b0.x <= a1.x && a0.y <= b1.y && b0.y <= a1.y
}

fn region_box(region: &[Polygon]) -> Polygon {
    let (lo, hi) = region.iter().map(Polygon::bounds).fold(
        (glam::DVec2::splat(f64::INFINITY), glam::DVec2::splat(f64::NEG_INFINITY)),
        |(a, b), (c, d)| (a.min(c), b.max(d)),
    );
    Polygon::new(vec![lo, glam::DVec2::new(hi.x, lo.y), hi, glam::DVec2::new(lo.x, hi.y)])
}

impl Planner<'_> {
    /// The narrowest material kept between a slot and the layer's outline, mm: the relaxed
    /// margin, the least any phase keeps on purpose. Thinner material beside a slot is opened
    /// to the outside (`notch`), so no slot pinches its layer.
    pub(super) fn bridge(&self) -> f64 {
        self.s.margin / 2.0
    }

    fn is_joined(&self, pair: &Pair) -> bool {
        self.joined.contains(&(pair.k, pair.lower, pair.upper))
    }

    /// Layer `k`'s slots grown by `margin`: where no new slot may go.
    pub(super) fn keep_clear(&self, k: usize, margin: f64) -> Result<Vec<Polygon>, GridError> {
        let rects: Vec<Polygon> = self.slots[k].iter().map(|(_, r)| r.clone()).collect();
        if rects.is_empty() {
            return Ok(Vec::new());
        }
        offset::offset(&boolean::union_all(&rects)?, margin)
    }

    /// The slot `rule` fits in `region`: a peg's or a shaft's.
    fn fit(&self, region: &[Polygon], rule: Rule) -> Result<Option<SlotLine>, GridError> {
        if rule.phase == PEG_PHASE {
            fit_peg(region, self.half, rule.min_width, self.s.shaft_max_width)
        } else {
            fit_slot(region, self.half, rule.min_width, self.s.shaft_max_width)
        }
    }

    /// `region` within island `x` of layer `m` shrunk by the rule's wall, clear of its slots.
    fn narrow(&self, region: &[Polygon], m: usize, x: usize, rule: Rule) -> Result<Vec<Polygon>, GridError> {
        let inner = offset::offset(std::slice::from_ref(&self.islands[m][x]), -rule.wall)?;
        let within = boolean::intersection(region, &inner)?;
        let clear = self.keep_clear(m, rule.clear)?;
        if clear.is_empty() {
            Ok(within)
        } else {
            boolean::difference(&within, &clear)
        }
    }

    /// The island of layer `m` that keeps the most of `region` with a slot still fitting.
    fn grow_into(&self, region: &[Polygon], m: usize, rule: Rule) -> Result<Option<(usize, Vec<Polygon>)>, GridError> {
        let bbox = region_box(region);
        let mut best: Option<(usize, Vec<Polygon>, f64)> = None;
        for (x, island) in self.islands[m].iter().enumerate() {
            if !boxes_meet(&bbox, island) {
                continue;
            }
            let narrowed = self.narrow(region, m, x, rule)?;
            let area = total_area(&narrowed);
            if best.as_ref().is_some_and(|b| b.2 >= area) {
                continue;
            }
            if self.fit(&narrowed, rule)?.is_some() {
                best = Some((x, narrowed, area));
            }
        }
        Ok(best.map(|(x, r, _)| (x, r)))
    }

    /// Phase 1 (and phase 2's fallback, and pegs): a new shaft through `pair`, grown through
    /// as many layers as a slot of `rule` fits. Returns whether one was placed.
    pub(super) fn connect(&mut self, pair: &Pair, rule: Rule) -> Result<bool, GridError> {
        let mut region = offset::offset(&pair.overlap, -rule.wall)?;
        for k in [pair.k, pair.k + 1] {
            let clear = self.keep_clear(k, rule.clear)?;
            if !clear.is_empty() {
                region = boolean::difference(&region, &clear)?;
            }
        }
        if self.fit(&region, rule)?.is_none() {
            return Ok(false);
        }
        // Layers bottom up with their island.
        let mut chain = vec![(pair.k, pair.lower), (pair.k + 1, pair.upper)];
        while let Some(&(top, _)) = chain.last() {
            if top + 1 >= self.islands.len() {
                break;
            }
            let Some((x, r)) = self.grow_into(&region, top + 1, rule)? else {
                break;
            };
            chain.push((top + 1, x));
            region = r;
        }
        while chain[0].0 > 0 {
            let Some((x, r)) = self.grow_into(&region, chain[0].0 - 1, rule)? else {
                break;
            };
            chain.insert(0, (chain[0].0 - 1, x));
            region = r;
        }
        let Some(line) = self.fit(&region, rule)? else {
            return Ok(false);
        };
        let bands = chain
            .iter()
            .map(|&(layer, island)| Band {
                layer,
                island,
                from: 0.0,
                to: line.width,
            })
            .collect();
        self.add(PlacedShaft {
            line,
            bands,
            phase: rule.phase,
            pegged: Vec::new(),
        });
        Ok(true)
    }

    /// Registers a shaft: its slots and the pairs it joins.
    fn add(&mut self, shaft: PlacedShaft) {
        for b in &shaft.bands {
            self.slots[b.layer].push((b.island, shaft.line.rect(b.from, b.to, self.half)));
        }
        for w in shaft.bands.windows(2) {
            self.joined.insert((w[0].layer, w[0].island, w[1].island));
        }
        self.shafts.push(shaft);
    }
}
