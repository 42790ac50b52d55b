//! Standoffs and bosses taller than a sheet, cut as stacked discs (issue 32).
//!
//! A boss standing on a plate (an enclosure's standoffs, a knob's base) is higher than the
//! plate's sheet, so it is neither the plate nor a detail engraved on it; before, the plan
//! left it out and said so. A maker builds it as the stacked method builds everything: discs
//! of its footprint cut from the sheet, stacked on the plate, held in line by
//!
//! - a **peg** when the footprint has room for a slot one sheet wide with
//!   [`PEG_MIN_WALL`] of material around it: the peg (a strip of the sheet, a shaft part)
//!   goes through a slot in every disc and in the plate, flush with the plate's far face and
//!   the stack's top, glue-free as the stacked method's pegs;
//! - else a **screw** through the standoff's own hole (a footprint with a hole at least
//!   [`MIN_SCREW`] across): the hole is cut through the plate too, and a screw with a nut
//!   under the plate holds the discs, as makers mount a board on a laser-cut base.
//!
//! The discs are cut from the offered sheet whose whole number of thicknesses comes closest
//! to the height (5 mm from 2.5 mm sheet as 2 discs, from 3 mm sheet as 2 discs, 1 mm
//! taller); a footprint the smallest-part rule refuses at every sheet (an Arduino's 5.2 mm
//! standoff with a 3.2 mm hole: 1 mm walls) is listed, not cut, and its screw hole is cut
//! through the plate so bought spacers and screws can stand in for it. So is a boss with
//! neither room for a peg nor a hole, and one on a bent part.

use std::collections::BTreeMap;

use glam::{DVec2, DVec3};
use platener_geom::boolean::difference;
use platener_geom::offset::offset;
use platener_geom::polygon::{interior_point, rect, total_area};
use platener_geom::{Frame, GridError, Polygon};

use crate::cuttable::{PEG_MIN_WALL, Rule};
use crate::plan::{Joint, JointKind, Part, PartKind};
use crate::plates::{Elevation, Feature, Plates, Side};

/// The narrowest screw hole a stack is held by, mm across (an M1.6 screw's clearance).
pub const MIN_SCREW: f64 = 1.5;
/// The most discs in one stack: a taller boss is a plate's work, or a bought part's.
pub const MAX_DISCS: usize = 16;
/// Grid slack, mm: a peg's walls may be this much thinner than [`PEG_MIN_WALL`], so a 5 mm
/// boss takes a 3 mm peg exactly.
const SLACK: f64 = 0.01;
/// Step between the peg widths tried, mm (from two sheets wide down to one: wider pegs
/// leave the discs' walls at their ends a millimetre thin).
const WIDTH_STEP: f64 = 0.5;

/// A boss taller than its plate's sheet, and what becomes of it.
pub(super) struct Standoff {
    /// The plate it stands on.
    base: usize,
    /// Its footprint on that plate, in the plate's frame.
    region: Polygon,
    /// The face it stands on.
    side: Side,
    /// How tall it stands, mm, when measured.
    height: Option<f64>,
    /// Its size and place, for the report.
    size: [f64; 2],
    center: DVec3,
    /// What is made of it.
    make: Make,
}

/// What a standoff becomes.
enum Make {
    /// `discs` discs `sheet` thick, held by `hold`.
    Stack { sheet: f64, discs: usize, hold: Hold },
    /// Nothing cut: why, and the screw hole (in the plate's frame) to cut through the plate.
    Listed { why: String, hole: Option<Polygon> },
}

/// What holds a stack of discs on its plate.
enum Hold {
    /// A peg through `slot` (a rectangle in the plate's frame, `width` along `along`).
    Peg { slot: Polygon, along: DVec2, width: f64 },
    /// A screw through `hole` (the footprint's own hole, in the plate's frame).
    Screw { hole: Polygon },
}

/// The standoffs of `plates`: raised features taller than their plate's sheet that no other
/// plate builds, with the stack each becomes from the `offered` sheets (parts at least
/// `min_area` big), or why none.
///
/// # Errors
/// When a footprint does not fit the 1 µm grid.
pub(super) fn find(plates: &Plates, offered: &[f64], min_area: f64) -> Result<Vec<Standoff>, GridError> {
    let slabs: Vec<_> = plates.plates.iter().map(crate::plates::Plate::slab).collect();
    let mut out = Vec::new();
    for f in &plates.features {
        let base = &plates.plates[f.plate as usize];
        let tall = f.height.is_none_or(|h| h > base.thickness + 1e-6);
        if f.relief != Elevation::Raised || !tall || crate::plates::builder(f, &slabs).is_some() {
            continue;
        }
        let make = match f.height {
            None => Make::Listed {
                why: "their height was not measured".into(),
                hole: None,
            },
            // A dome or a cone is no stack of equal discs: the stacked method slices it.
            Some(_) if !f.prism => Make::Listed {
                why: "they do not stand straight up (the stacked method slices such shapes)".into(),
                hole: None,
            },
            Some(h) => plan_stack(&f.region, reach(f, base.thickness, h), offered, min_area)?,
        };
        out.push(Standoff {
            base: f.plate as usize,
            region: f.region.clone(),
            side: f.side,
            height: f.height,
            size: f.size,
            center: f.center,
            make,
        });
    }
    Ok(out)
}

/// How far the stack must reach from the plate's face: the feature's height from the model's
/// face, plus the model's face's distance outside the plate (a 4 mm floor cut from 3 mm sheet).
fn reach(f: &Feature, thickness: f64, height: f64) -> f64 {
    let face = f.frame.to_local(f.center).z;
    let gap = match f.side {
        Side::Up => -face,
        Side::Down => face - thickness,
    };
    (height + gap).max(0.0)
}

/// The stack a footprint `region` makes reaching `reach` mm: from the offered sheet the rule
/// keeps it at whose whole thicknesses come closest (the thicker on a tie), held by a peg or
/// a screw; else why it is listed.
fn plan_stack(region: &Polygon, reach: f64, offered: &[f64], min_area: f64) -> Result<Make, GridError> {
    let hole = screw_hole(region);
    let count = |s: f64| ((reach / s).round() as usize).max(1);
    let kept: Vec<f64> = offered
        .iter()
        .copied()
        .filter(|&s| Rule::for_sheet(s, 0.0, min_area).keeps(region))
        .collect();
    let Some(sheet) = kept.iter().copied().min_by(|&a, &b| {
        let err = |s: f64| (count(s) as f64 * s - reach).abs();
        err(a).total_cmp(&err(b)).then(b.total_cmp(&a))
    }) else {
        let thinnest = offered.iter().copied().fold(f64::INFINITY, f64::min);
        let rule = Rule::for_sheet(thinnest, 0.0, min_area);
        let why = rule.check(region)?.err().map_or("too small to cut".to_string(), |w| {
            format!("too small to cut from {thinnest} mm sheet ({})", w.describe(&rule))
        });
        return Ok(Make::Listed { why, hole });
    };
    let discs = count(sheet);
    if discs > MAX_DISCS {
        let why = format!("taller than {MAX_DISCS} sheets of {sheet} mm");
        return Ok(Make::Listed { why, hole });
    }
    // A disc must pass the rule with its peg's slot cut too.
    let rule = Rule::for_sheet(sheet, 0.0, min_area);
    let peg = fit_peg(region, sheet)?.filter(|(slot, ..)| {
        let mut disc = region.clone();
        disc.holes.push(slot.outer.clone());
        disc.normalize_orientation();
        rule.keeps(&disc)
    });
    let hold = match (peg, hole) {
        (Some((slot, along, width)), _) => Hold::Peg { slot, along, width },
        (None, Some(hole)) => Hold::Screw { hole },
        (None, None) => {
            let why = format!("no room for a peg of {sheet} mm sheet and no screw hole");
            return Ok(Make::Listed { why, hole: None });
        }
    };
    Ok(Make::Stack { sheet, discs, hold })
}

/// The footprint's widest hole at least [`MIN_SCREW`] across (four times its area over its
/// perimeter: a circle's diameter), as a polygon.
fn screw_hole(region: &Polygon) -> Option<Polygon> {
    region
        .holes
        .iter()
        .map(|ring| {
            let mut hole = Polygon::new(ring.clone());
            hole.normalize_orientation();
            hole
        })
        .filter(|h| across(h) >= MIN_SCREW)
        .max_by(|a, b| across(a).total_cmp(&across(b)))
}

/// A slot `sheet` wide and one to two sheets long with [`PEG_MIN_WALL`] of `region` all
/// around, at the middle of the region's deepest part, along its longer side first: the
/// slot, its direction and its length.
fn fit_peg(region: &Polygon, sheet: f64) -> Result<Option<(Polygon, DVec2, f64)>, GridError> {
    let core = offset(std::slice::from_ref(region), -(PEG_MIN_WALL + sheet / 2.0 - SLACK))?;
    let Some(piece) = core.iter().max_by(|a, b| a.area().total_cmp(&b.area())) else {
        return Ok(None);
    };
    let (lo, hi) = piece.bounds();
    let mut centre = (lo + hi) / 2.0;
    if !piece.contains(centre) {
        let Some(p) = interior_point(&piece.outer) else {
            return Ok(None);
        };
        centre = p;
    }
    let (lo, hi) = region.bounds();
    let dirs = if hi.x - lo.x >= hi.y - lo.y {
        [DVec2::X, DVec2::Y]
    } else {
        [DVec2::Y, DVec2::X]
    };
    let steps = (sheet / WIDTH_STEP).floor() as usize;
    for k in (0..=steps).rev() {
        let width = sheet + k as f64 * WIDTH_STEP;
        for along in dirs {
            let slot = slot_at(centre, along, width, sheet);
            let walls = offset(std::slice::from_ref(&slot), PEG_MIN_WALL - SLACK)?;
            if total_area(&difference(&walls, std::slice::from_ref(region))?) < 1e-6 {
                return Ok(Some((slot, along, width)));
            }
        }
    }
    Ok(None)
}

/// A `width` × `sheet` rectangle centred on `centre`, `width` along `along` (an axis).
fn slot_at(centre: DVec2, along: DVec2, width: f64, sheet: f64) -> Polygon {
    let half = along.abs() * width / 2.0 + along.perp().abs() * sheet / 2.0;
    let (a, b) = (centre - half, centre + half);
    let mut p = Polygon::new(rect(a.x, a.y, b.x, b.y));
    p.normalize_orientation();
    p
}

/// Cuts the standoffs of `standoffs` on their plates' parts (`ids`): the discs and pegs as
/// parts numbered after `parts`, their joints numbered after `connections`, slots and screw
/// holes cut through the plates; says what became of them, per plate part.
pub(super) fn build(
    standoffs: &[Standoff],
    plates: &Plates,
    ids: &[Option<u32>],
    (parts, connections): (&mut Vec<Part>, &mut Vec<Joint>),
) -> Result<Vec<String>, GridError> {
    let mut next_id = parts.iter().map(|p| p.id).max().unwrap_or(0);
    let mut label = connections.iter().map(|c| c.label).max().unwrap_or(0);
    let mut said: BTreeMap<u32, Said> = BTreeMap::new();
    for st in standoffs {
        let Some(base_id) = ids[st.base] else {
            continue;
        };
        let Some(at) = parts.iter().position(|p| p.id == base_id) else {
            continue;
        };
        let entry = said.entry(base_id).or_default();
        let (sheet, discs, hold) = match &st.make {
            Make::Stack { sheet, discs, hold } if parts[at].kind == PartKind::Plate => (*sheet, *discs, hold),
            Make::Stack { .. } => {
                entry.list("it stands on a bent part", st, None);
                continue;
            }
            Make::Listed { why, hole } => {
                let through = hole.as_ref().filter(|h| cut_through(&mut parts[at], h));
                entry.list(why, st, through.map(across));
                continue;
            }
        };
        let plate = &plates.plates[st.base];
        let through = match hold {
            Hold::Peg { slot, .. } => slot,
            Hold::Screw { hole } => hole,
        };
        if !cut_through(&mut parts[at], through) {
            entry.list("its slot would not leave the part whole", st, None);
            continue;
        }
        let first = next_id + 1;
        let mut below = base_id;
        for k in 0..discs {
            next_id += 1;
            let mut region = st.region.clone();
            if let Hold::Peg { slot, .. } = hold {
                region.holes.push(slot.outer.clone());
                region.normalize_orientation();
            }
            let frame = disc_frame(&plate.frame, st.side, plate.thickness, sheet, k);
            parts.push(Part::plate(next_id, sheet, region, frame));
            if matches!(hold, Hold::Screw { .. }) {
                label += 1;
                connections.push(joint([below, next_id], JointKind::Screw, 0.0, label));
            }
            below = next_id;
        }
        let ids_made = format!("parts {first}–{next_id}");
        let how = match hold {
            Hold::Peg { slot, along, width } => {
                next_id += 1;
                parts.push(peg_part(next_id, plate, st.side, (slot, *along, *width), sheet, discs));
                for part in std::iter::once(base_id).chain(first..first + discs as u32) {
                    label += 1;
                    connections.push(joint([next_id, part], JointKind::Shaft, 90.0, label));
                }
                format!("on a peg (part {next_id}) through a slot in part {base_id}")
            }
            Hold::Screw { hole } => format!(
                "held by a screw through their {:.1} mm hole, cut through part {base_id} too (a nut under it)",
                across(hole)
            ),
        };
        entry.built.push(format!(
            "{}: {discs} disc(s) of {sheet} mm ({ids_made}) {how}",
            describe(st)
        ));
    }
    Ok(said.into_iter().flat_map(|(base, said)| said.lines(base)).collect())
}

/// What became of the standoffs on one part, for the report.
#[derive(Default)]
struct Said {
    /// One entry per standoff cut.
    built: Vec<String>,
    /// Per reason: the standoffs left out, and the diameters of the screw holes cut for them.
    listed: BTreeMap<String, (Vec<String>, Vec<f64>)>,
}

impl Said {
    /// Lists `st`, left out for `why`, its screw hole `across` mm cut through if any.
    fn list(&mut self, why: &str, st: &Standoff, across: Option<f64>) {
        let entry = self.listed.entry(why.to_string()).or_default();
        entry.0.push(describe(st));
        entry.1.extend(across);
    }

    /// The report's lines for the standoffs on part `base`.
    fn lines(self, base: u32) -> Vec<String> {
        let mut out = Vec::new();
        if !self.built.is_empty() {
            out.push(format!(
                "part {base}: {} standoff(s) standing on it are cut as stacked discs: {}",
                self.built.len(),
                self.built.join("; ")
            ));
        }
        for (why, (which, holes)) in self.listed {
            let holes = match holes.iter().copied().reduce(f64::max) {
                Some(d) => format!(
                    ". Their screw holes ({d:.1} mm) are cut through part {base}: bought spacers and screws stand \
                     in for them"
                ),
                None => String::new(),
            };
            out.push(format!(
                "part {base}: {} boss(es) standing on it left out, {why}; only their footprints are engraved: {}{holes}",
                which.len(),
                which.join("; ")
            ));
        }
        out
    }
}

/// How wide a hole is across: four times its area over its perimeter (a circle's diameter).
fn across(hole: &Polygon) -> f64 {
    4.0 * hole.area() / platener_geom::polygon::perimeter(&hole.outer).max(f64::MIN_POSITIVE)
}

/// A standoff's size, height and place, for the report.
fn describe(st: &Standoff) -> String {
    let tall = st
        .height
        .map_or_else(|| "height not measured".to_string(), |h| format!("{h:.1} mm tall"));
    let c = st.center;
    format!(
        "{:.1} × {:.1} mm, {tall}, at ({:.1}, {:.1}, {:.1})",
        st.size[0], st.size[1], c.x, c.y, c.z
    )
}

/// Cuts `hole` through `part` (nothing when the part has it already); false when the cut
/// would not leave one part.
fn cut_through(part: &mut Part, hole: &Polygon) -> bool {
    match difference(std::slice::from_ref(&part.polygon), std::slice::from_ref(hole)) {
        Ok(mut cut) if cut.len() == 1 => {
            part.polygon = cut.remove(0);
            true
        }
        _ => false,
    }
}

/// A joint of a standoff's stack.
fn joint(parts: [u32; 2], kind: JointKind, angle_deg: f64, label: u32) -> Joint {
    Joint {
        parts,
        kind,
        angle_deg,
        label,
    }
}

/// Where disc `k` (0 on the plate) of a stack of `sheet` lies on the `side` face of a plate
/// `thickness` thick in `frame`.
fn disc_frame(frame: &Frame, side: Side, thickness: f64, sheet: f64, k: usize) -> Frame {
    match side {
        Side::Up => frame.shifted(-sheet * (k + 1) as f64),
        Side::Down => frame.shifted(thickness + sheet * k as f64),
    }
}

/// The peg through a stack of `discs` discs of `sheet` on `plate`'s `side` face: a strip
/// `width` wide from the plate's far face to the stack's top, standing in `slot` (along
/// `along`), `sheet` thick across it.
fn peg_part(
    id: u32,
    plate: &crate::plates::Plate,
    side: Side,
    (slot, along, width): (&Polygon, DVec2, f64),
    sheet: f64,
    discs: usize,
) -> Part {
    let f = &plate.frame;
    let (lo, hi) = slot.bounds();
    let centre = (lo + hi) / 2.0;
    let across = along.perp();
    let u = f.u * along.x + f.v * along.y;
    let n = f.u * across.x + f.v * across.y;
    // The peg's v runs against the plate's normal, so (u, v, n) stays right-handed.
    let frame = Frame {
        origin: f.to_model((centre - across * sheet / 2.0).extend(0.0)),
        u,
        v: -f.n,
        n,
    };
    let stack = sheet * discs as f64;
    // Local y is minus the plate's z: the Up face is at z = 0, the Down face at z = thickness.
    let (y0, y1) = match side {
        Side::Up => (-plate.thickness, stack),
        Side::Down => (-(plate.thickness + stack), 0.0),
    };
    let mut polygon = Polygon::new(rect(-width / 2.0, y0, width / 2.0, y1));
    polygon.normalize_orientation();
    let mut part = Part::plate(id, sheet, polygon, frame);
    part.kind = PartKind::Shaft;
    part
}

#[cfg(test)]
mod tests {
    use super::*;

    fn square(side: f64) -> Polygon {
        let mut p = Polygon::new(rect(0.0, 0.0, side, side));
        p.normalize_orientation();
        p
    }

    #[test]
    fn a_peg_keeps_a_millimetre_of_wall_and_is_at_most_two_sheets_long() {
        let (slot, along, width) = fit_peg(&square(10.0), 3.0).expect("on the grid").expect("fits");
        assert_eq!((along, width), (DVec2::X, 6.0));
        let (lo, hi) = slot.bounds();
        assert!((lo - DVec2::new(2.0, 3.5)).length() < 1e-9 && (hi - DVec2::new(8.0, 6.5)).length() < 1e-9);
        // Exactly a peg and two walls: 3 × 3 mm in a 5 mm square.
        let (_, _, width) = fit_peg(&square(5.0), 3.0).expect("on the grid").expect("fits");
        assert_eq!(width, 3.0);
        assert!(fit_peg(&square(4.9), 3.0).expect("on the grid").is_none());
    }

    #[test]
    fn a_ring_takes_a_screw_not_a_peg() {
        let mut ring = square(10.0);
        ring.holes.push(rect(3.4, 3.4, 6.6, 6.6));
        ring.normalize_orientation();
        assert!(fit_peg(&ring, 3.0).expect("on the grid").is_none());
        let hole = screw_hole(&ring).expect("a 3.2 mm hole");
        assert!((across(&hole) - 3.2).abs() < 1e-9);
        let Make::Stack { sheet, discs, hold } = plan_stack(&ring, 5.0, &[2.5, 3.0], 25.0).expect("on the grid") else {
            panic!("cut as discs");
        };
        // 5 mm: two 2.5 mm discs exactly, rather than two 3 mm ones.
        assert_eq!((sheet, discs), (2.5, 2));
        assert!(matches!(hold, Hold::Screw { .. }));
        let mut pin = square(10.0);
        pin.holes.push(rect(4.5, 4.5, 5.5, 5.5));
        pin.normalize_orientation();
        assert!(screw_hole(&pin).is_none(), "1 mm is no screw hole");
    }

    #[test]
    fn a_standoff_too_small_to_cut_is_listed_with_its_screw_hole() {
        let mut ring = Polygon::new(rect(0.0, 0.0, 5.2, 5.2));
        ring.holes.push(rect(1.0, 1.0, 4.2, 4.2));
        ring.normalize_orientation();
        let Make::Listed { why, hole } = plan_stack(&ring, 5.0, &[3.0], 25.0).expect("on the grid") else {
            panic!("listed");
        };
        assert!(why.contains("too small to cut from 3 mm sheet"), "{why}");
        assert!(hole.is_some());
    }
}
