//! Step `bends` of the plate method (the thesis' bent plates, chapter 10): neighbouring
//! plates that meet at a shallow enough angle become one part, cut flat and bent.
//!
//! 1. [`find`]: pairs of plates of one thickness that both end at the line where their
//!    mid-planes meet are candidates; the turn the sheet makes there must be one the bend
//!    style can make ([`zone`]: living hinges need room and round the corner a little, folds
//!    and heat bends are tight).
//! 2. [`grow`]: the easiest bends first, each joins two groups of plates into one flat layout
//!    by [`unfold`]ing one into the other's plane about the bend line (the bend deduction
//!    moves it back so the bent part closes to the model's size), unless the developed
//!    shapes would overlap or the part would not fit on a sheet. A candidate inside one group
//!    is a seam: the ring is cut open there and a joint closes it. Several orders are tried;
//!    the layout with fewer, larger parts wins.
//! 3. [`remove`]: where a plate already added blocks others from joining, the layout is grown
//!    again without it (a bounded number of times), and kept when it is better.
//!
//! The snapshot proposes which plates form each bent part, where each lies on the flat, its
//! bend lines and seams. The `joints` step leaves bends (and glued seams) without fingers
//! and decides which proposed parts hold together once jointed ([`flat`] lays one out); the
//! `parts` step merges the jointed plates of those into one part.

mod close;
mod fillet;
mod find;
pub mod flat;
mod grow;
mod remove;
#[cfg(test)]
mod remove_tests;
#[cfg(test)]
pub(crate) mod tests;
mod unfold;
pub mod zone;

use glam::DVec2;
use platener_geom::GridError;
use serde::Serialize;

use crate::context::{StepContext, WarningKind};
use crate::error::{Error, ModelProblem, Result};
use crate::mesh::Mesh;
use crate::plan::{BendStyle, Material, SheetSize};
use crate::plates::{Plate, Plates};
use crate::settings::{Bending, Settings};

pub use find::Candidate;
pub use grow::HalfPlane;
pub use unfold::Member;
pub use zone::BendZone;

/// Member `b` laid into `a`'s flat across `c` as a sharp fold (no bend zone): where a flap
/// on `a`'s edge at the seam `c` lands when folded onto `b`.
pub fn fold_sharp(a: &Member, b: &Member, c: &Candidate, thickness: f64) -> Member {
    unfold::develop(a, b, c, thickness, 0.0)
}

/// The largest turn bends are made at when the style is chosen by material (`bend` auto):
/// a ring of at most 8 facets per full turn (45° and more each) is a shape someone drew, a
/// hexagonal tube or an octagonal lamp, not a tessellated curve, and keeps its sharp,
/// jointed corners (a hinge there rounds them into the hollow: 1.5 mm at each corner of a
/// 2 mm hexagonal tube, 6 % of its volume outside the model). Finer rings bend; a style the
/// user asks for bends any turn it can make.
pub const AUTO_MAX_TURN_DEG: f64 = 44.5;

/// The snapshot of step `bends`.
#[derive(Debug, Clone, Serialize, Default)]
pub struct Bends {
    /// The style bends are made in; `None` when bending is off.
    pub style: Option<BendStyle>,
    /// The bent parts (two plates or more each), by their lowest plate.
    pub parts: Vec<BentPart>,
    /// Candidate connections considered.
    pub candidates: usize,
    /// Candidates that stayed joints, and why.
    pub refused: Vec<Refusal>,
    /// How many plates there were (the pairs [`Bends::unjointed`] names reach them all).
    #[serde(skip)]
    pub plate_count: usize,
}

/// A candidate that stayed a joint.
#[derive(Debug, Clone, Serialize)]
pub struct Refusal {
    /// The plates (indices into the plates snapshot).
    pub plates: [u32; 2],
    /// Why.
    pub reason: String,
}

/// Plates merged into one part, laid out flat.
#[derive(Debug, Clone, Serialize)]
pub struct BentPart {
    /// The plates, ascending; the first one's flat frame is the part's.
    pub members: Vec<Member>,
    /// Per member: where it is cut at its bend lines (its shape is the half-planes' common
    /// part of its plate).
    pub cuts: Vec<Vec<HalfPlane>>,
    /// The bends.
    pub bends: Vec<BendLine>,
    /// The seams: where a ring of plates is cut open; a joint closes them.
    pub seams: Vec<Seam>,
    /// Where a ring is cut open in the middle of a wall instead (its seam lay across a
    /// fillet, which no joint closes): that wall's plate is two members, each keeping a half.
    pub splits: Vec<Split>,
}

/// The half of its plate a member keeps where its wall is cut in two to open a ring.
#[derive(Debug, Clone, Serialize)]
pub struct Split {
    /// The member (index into [`BentPart::members`]).
    pub member: usize,
    /// The half it keeps.
    pub keep: HalfPlane,
}

impl BentPart {
    /// The halves member `i` keeps of its plate where its wall is cut in two (none, or one).
    pub fn splits_of(&self, i: usize) -> impl Iterator<Item = &HalfPlane> {
        self.splits.iter().filter(move |s| s.member == i).map(|s| &s.keep)
    }

    /// The plates it is made of, ascending, each once (a wall cut in two is one plate).
    pub fn plates(&self) -> Vec<u32> {
        let mut plates: Vec<u32> = self.members.iter().map(|m| m.plate).collect();
        plates.sort_unstable();
        plates.dedup();
        plates
    }
}

/// One bend of a bent part.
#[derive(Debug, Clone, Serialize)]
pub struct BendLine {
    /// The two members (indices into [`BentPart::members`]).
    pub members: [usize; 2],
    /// The angle the plates enclose, degrees.
    pub enclosed_deg: f64,
    /// The bend zone.
    pub zone: BendZone,
    /// The middle of the zone on the flat part, as far as either plate reaches along it.
    pub line: [DVec2; 2],
    /// Per member: where its flat segment begins (the zone's edge on its side), in the model.
    pub tangents: [HalfPlane; 2],
    /// The neutral radius of the model's fillet the zone replaces (an arc zone), mm.
    pub fillet: Option<f64>,
    /// The plates the fillet's facets were found as, which the zone replaces: they make no
    /// part and no joint.
    pub facets: Vec<u32>,
}

impl BendLine {
    /// How far the bent arc passes inside the model's own corner, mm: its sharp corner, or
    /// across a fillet the fillet's arc.
    pub fn rounding(&self) -> f64 {
        let own = self
            .fillet
            .map_or(0.0, |r| r * (1.0 / (self.zone.turn() / 2.0).cos() - 1.0));
        (self.zone.corner_gap() - own).max(0.0)
    }
}

/// A seam of a bent part.
#[derive(Debug, Clone, Serialize)]
pub struct Seam {
    /// The two members (indices into [`BentPart::members`]).
    pub members: [usize; 2],
    /// How the plates meet there.
    pub meeting: Candidate,
}

impl Bends {
    /// The bent part holding plate `p` and its member index there, if any.
    pub fn member_of(&self, p: usize) -> Option<(usize, usize)> {
        self.parts
            .iter()
            .enumerate()
            .find_map(|(k, part)| part.members.iter().position(|m| m.plate as usize == p).map(|i| (k, i)))
    }

    /// The plates that arc zones replace (a fillet's facets): they make no part.
    pub fn absorbed(&self) -> std::collections::BTreeSet<u32> {
        self.parts
            .iter()
            .flat_map(|p| p.bends.iter().flat_map(|b| b.facets.iter().copied()))
            .collect()
    }

    /// These bends with only the bent parts `held` names (indices into [`Bends::parts`], the
    /// ones the `joints` step found to hold together once jointed); the plates of the others
    /// are plates again.
    pub fn keeping(&self, held: &[usize]) -> Bends {
        Bends {
            parts: held.iter().filter_map(|&k| self.parts.get(k).cloned()).collect(),
            refused: Vec::new(),
            ..self.clone()
        }
    }

    /// The plate pairs (lower first) that need no joint: the bends, with paper and card
    /// the seams (a glue flap closes them), and every pair with a plate an arc zone replaced.
    pub fn unjointed(&self) -> std::collections::BTreeSet<(u32, u32)> {
        let flaps = matches!(self.style, Some(BendStyle::Perforation | BendStyle::Score));
        let mut pairs = std::collections::BTreeSet::new();
        for f in self.absorbed() {
            pairs.extend(
                (0..self.plate_count as u32)
                    .filter(|&j| j != f)
                    .map(|j| (f.min(j), f.max(j))),
            );
        }
        for part in &self.parts {
            let pair = |[i, j]: [usize; 2]| {
                let (a, b) = (part.members[i].plate, part.members[j].plate);
                (a.min(b), a.max(b))
            };
            pairs.extend(part.bends.iter().map(|b| pair(b.members)));
            if flaps {
                pairs.extend(part.seams.iter().map(|s| pair(s.members)));
            }
        }
        pairs
    }
}

/// Step `bends`: the bent parts of the plates, in the style `--bend` asks for.
pub fn run(plates: &Plates, mesh: &Mesh, settings: &Settings, cx: &mut StepContext<'_>) -> Result<Bends> {
    cx.check_cancel()?;
    let material = settings.cut.material;
    // A bent part's flat shape grows by its joints' fingers at its ends (a sheet's thickness
    // each) and by the nesting's spacing: a strip that fitted the margins alone was refused by
    // the nesting after every costly step (three 40-gon boxes, issue 29).
    let thickest = settings.thicknesses.iter().copied().fold(0.0, f64::max);
    let margin = 2.0 * settings.cut.margin + settings.cut.spacing + 2.0 * thickest;
    let sheet = match settings.cut.sheet {
        SheetSize::Fixed { width, height } => (width - margin, height - margin),
        SheetSize::Fit => (f64::INFINITY, f64::INFINITY),
    };
    if let (Some(style), Some(plate)) = (settings.bending.style(material), plates.plates.first())
        && crate::hinge::max_turn(style, material, plate.thickness) == 0.0
    {
        cx.warn(
            WarningKind::Joints,
            format!(
                "a {} bend does not work in {} mm {}: no plates are bent (try another `bend`)",
                style.name(),
                plate.thickness,
                material.name()
            ),
        );
    }
    let off_grid = |e| Error::model(cx.model(), ModelProblem::OffGrid(e));
    let bends = compute(&plates.plates, Some(mesh), settings.bending, material, sheet).map_err(off_grid)?;
    Ok(bends)
}

impl Bends {
    /// What the maker should know about these bent parts (the ones that hold, as the
    /// `joints` step keeps them): bends that round the model's corners by more than a
    /// thickness, and how many plates are merged into how many parts.
    pub fn notes(&self, plates: &Plates) -> Vec<String> {
        let mut notes = Vec::new();
        for (k, part) in self.parts.iter().enumerate() {
            let t = plates.plates[part.members[0].plate as usize].thickness;
            let round = part.bends.iter().map(BendLine::rounding).fold(0.0, f64::max);
            if round > t {
                notes.push(format!(
                    "bent part {} (of plates {}): its bends round the model's corners by up to {round:.1} mm",
                    k + 1,
                    plate_list(part)
                ));
            }
        }
        if !self.parts.is_empty() {
            let merged: usize = self.parts.iter().map(|p| p.plates().len()).sum();
            notes.push(format!(
                "{merged} plates are merged into {} bent part(s) ({}); `bend` none keeps them as jointed plates",
                self.parts.len(),
                self.style.map_or("", BendStyle::name)
            ));
        }
        notes
    }
}

/// The plates of a bent part, numbered as in the plates step, for messages.
pub fn plate_list(part: &BentPart) -> String {
    let ids: Vec<String> = part.plates().iter().map(|p| (p + 1).to_string()).collect();
    ids.join(", ")
}

/// The bent parts of `plates` made with `bending` in `material`, each fitting a sheet of
/// `sheet` (width, height) mm; with the `mesh` they were found in, also across its fillets
/// (runs of facets too narrow to be plates: one arc zone each).
pub fn compute(
    plates: &[Plate],
    mesh: Option<&Mesh>,
    bending: Bending,
    material: Material,
    sheet: (f64, f64),
) -> Result<Bends, GridError> {
    let Some(style) = bending.style(material) else {
        return Ok(Bends::default());
    };
    let t = plates.first().map_or(3.0, |p| p.thickness);
    let physical = crate::hinge::max_turn(style, material, t) + 0.5f64.to_radians();
    let max_turn = if bending == Bending::Auto {
        physical.min(AUTO_MAX_TURN_DEG.to_radians())
    } else {
        physical
    };
    let candidates = find::candidates(plates, (max_turn, physical), mesh);
    let zones: Vec<_> = candidates
        .iter()
        .map(|c| zone_of(c, plates, style, material, bending == Bending::Auto))
        .collect();
    let (candidates, zones) = fillet::prefer_arcs(candidates, zones);
    let grow = |order: &[usize]| grow::Layout::new(plates, &candidates, &zones, sheet).grow(order);
    let mut best: Option<(grow::Layout, Vec<usize>)> = None;
    for order in orders(&candidates, plates) {
        let layout = grow(&order)?;
        if best.as_ref().is_none_or(|(b, _)| layout.quality() < b.quality()) {
            best = Some((layout, order));
        }
    }
    let (layout, order) = best.expect("at least one order is tried");
    let layout = remove::improve(layout, order, &candidates, grow)?;
    let mut parts = parts_of(&layout, &candidates, &zones);
    let zone_of = |c: &Candidate| zone_of(c, plates, style, material, bending == Bending::Auto);
    for part in &mut parts {
        close::close_fillet_seams(part, plates, &zone_of, sheet)?;
    }
    Ok(Bends {
        style: Some(style),
        parts,
        candidates: candidates.len(),
        refused: layout
            .refused
            .iter()
            .map(|(ci, reason)| Refusal {
                plates: candidates[*ci].plates.map(|p| p as u32),
                reason: reason.clone(),
            })
            .collect(),
        plate_count: plates.len(),
    })
}

/// The zone of candidate `c`: it fits in each plate's half (a plate may bend on both sides)
/// with a fifth of it left flat; `strict` (the style chosen by material), it also keeps to
/// the model's corner (see [`zone::design`]).
fn zone_of(
    c: &Candidate,
    plates: &[Plate],
    style: BendStyle,
    material: Material,
    strict: bool,
) -> Result<BendZone, String> {
    let thickness = plates[c.plates[0]].thickness;
    let depth = c.depth[0].min(c.depth[1]);
    let room = zone::Room {
        thickness,
        depth,
        max_width: 0.8 * depth,
        fillet: (c.gap > 0.0).then(|| fillet::Arc::of(c, c.gap).radius),
    };
    zone::design(style, material, room, c.turn(), strict)
}

/// The orders in which candidates are tried: the easiest bends first (smallest turn, then
/// longest), the longest first, and outward from the largest plate.
fn orders(candidates: &[Candidate], plates: &[Plate]) -> Vec<Vec<usize>> {
    let easiest = easiest_first(&candidates.iter().map(|c| (c.turn(), c.length())).collect::<Vec<_>>());
    let mut longest: Vec<usize> = (0..candidates.len()).collect();
    longest.sort_by(|&i, &j| {
        candidates[j]
            .length()
            .total_cmp(&candidates[i].length())
            .then(i.cmp(&j))
    });
    vec![easiest.clone(), longest, outward(&easiest, candidates, plates)]
}

/// The indices of `(turn, length)` pairs, smallest turn first, then longest, then in order.
/// Turns equal to a µrad are one key: a tolerance inside a comparator is not transitive (a
/// cup beside its saucer made the sort panic), integer keys are.
fn easiest_first(keys: &[(f64, f64)]) -> Vec<usize> {
    let mut order: Vec<usize> = (0..keys.len()).collect();
    order.sort_by(|&i, &j| {
        let ((ta, la), (tb, lb)) = (keys[i], keys[j]);
        turn_key(ta).cmp(&turn_key(tb)).then(lb.total_cmp(&la)).then(i.cmp(&j))
    });
    order
}

/// A turn (radians) on a grid of 1 µrad, for sorting turns that differ by rounding alike.
fn turn_key(turn: f64) -> i64 {
    // Saturating float-to-int cast: a NaN turn sorts as 0, never panics.
    (turn * 1e6).round() as i64
}

/// The candidates in breadth-first order from the largest plate (then from the largest
/// plate not reached), each plate's candidates in `easiest` order.
fn outward(easiest: &[usize], candidates: &[Candidate], plates: &[Plate]) -> Vec<usize> {
    let mut by_area: Vec<usize> = (0..plates.len()).collect();
    by_area.sort_by(|&a, &b| plates[b].area.total_cmp(&plates[a].area).then(a.cmp(&b)));
    let mut reached = vec![false; plates.len()];
    let mut taken = vec![false; candidates.len()];
    let mut order = Vec::with_capacity(candidates.len());
    for seed in by_area {
        if reached[seed] {
            continue;
        }
        reached[seed] = true;
        let mut queue = std::collections::VecDeque::from([seed]);
        while let Some(p) = queue.pop_front() {
            for &ci in easiest {
                let c = &candidates[ci];
                if taken[ci] || !c.plates.contains(&p) {
                    continue;
                }
                taken[ci] = true;
                order.push(ci);
                let other = c.plates[1 - c.side_of(p)];
                if !reached[other] {
                    reached[other] = true;
                    queue.push_back(other);
                }
            }
        }
    }
    order
}

/// The bent parts of a grown layout: its groups of two plates or more.
fn parts_of(layout: &grow::Layout, candidates: &[Candidate], zones: &[Result<BendZone, String>]) -> Vec<BentPart> {
    let mut parts = Vec::new();
    let mut groups: Vec<Vec<usize>> = layout.groups.iter().filter(|g| g.len() > 1).cloned().collect();
    for g in &mut groups {
        g.sort_unstable();
    }
    groups.sort();
    for group in groups {
        let index = |p: usize| group.binary_search(&p).expect("a member of the group");
        let members: Vec<Member> = group.iter().map(|&p| layout.members[p].clone()).collect();
        let cuts = group.iter().map(|&p| layout.cuts[p].clone()).collect();
        let bends = layout
            .bends
            .iter()
            .filter(|(ci, _)| group.binary_search(&candidates[*ci].plates[0]).is_ok())
            .map(|&(ci, parent)| {
                let c = &candidates[ci];
                let zone = *zones[ci].as_ref().expect("a bend has a zone");
                bend_line(
                    c,
                    zone,
                    parent,
                    &layout.members[parent],
                    [index(c.plates[0]), index(c.plates[1])],
                )
            })
            .collect();
        let bent: std::collections::BTreeSet<usize> = layout.bends.iter().map(|(ci, _)| *ci).collect();
        let seams = candidates
            .iter()
            .enumerate()
            .filter(|(ci, c)| !bent.contains(ci) && c.plates.iter().all(|p| group.binary_search(p).is_ok()))
            .map(|(_, c)| Seam {
                members: c.plates.map(index),
                meeting: c.clone(),
            })
            .collect();
        parts.push(BentPart {
            members,
            cuts,
            bends,
            seams,
            splits: Vec::new(),
        });
    }
    parts
}

/// The bend of candidate `c` in the flat part: its middle line (the zone starts a setback
/// from the sharp corner on the `parent`'s side, which the deduction did not move) and where
/// each side's segment begins.
fn bend_line(c: &Candidate, zone: BendZone, parent: usize, pm: &Member, members: [usize; 2]) -> BendLine {
    let t_half = |side: usize| HalfPlane {
        point: c.point + c.into[side] * zone.setback(),
        axis: c.axis,
        into: c.into[side],
        gap: 0.0,
    };
    let into = c.into[c.side_of(parent)];
    let centre = c.point + into * (zone.setback() - zone.width() / 2.0);
    let flat = |along: f64| pm.place.apply(pm.frame.to_2d(centre + c.axis * along));
    BendLine {
        members,
        enclosed_deg: c.enclosed.to_degrees(),
        zone,
        line: [flat(c.reach.0), flat(c.reach.1)],
        tangents: [t_half(0), t_half(1)],
        fillet: (c.gap > 0.0).then(|| fillet::Arc::of(c, c.gap).radius),
        facets: c.facets.iter().map(|&p| p as u32).collect(),
    }
}
