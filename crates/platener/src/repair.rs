//! Every part outline valid before it is offset or nested (issue 15).
//!
//! Both methods make outlines by booleans: joints cut fingers and slots into plates, shafts cut
//! slots into layers. A slot corner can land exactly on an outline's edge, a finger can leave a
//! sliver narrower than the laser's kerf, a ring can run back along itself. Such an outline
//! breaks the kerf offset and the nester (jagua-rs refuses or panics on zero-width shapes), and
//! the plan is not what the laser can cut. So where the parts are made, after every slot and
//! joint is cut, each outline is checked ([`platener_geom::validity`]) and, only when it is
//! not valid, repaired ([`platener_geom::clean`]): valid outlines keep their exact vertices.
//!
//! A repair keeps a part's largest piece. Pieces cut off (narrower than the kerf, or split
//! off where a slot touched the edge) are reported with the part's id when they held material
//! ([`CRUMB_AREA`]); a part with nothing wider than the kerf is left out with its joints.
//! Where cutting would lose more than [`MAX_LOSS`] of a part (a neck narrower than the kerf
//! holding a large piece), the narrow material is widened to the kerf instead
//! ([`platener_geom::clean::widen`]) when that keeps the part's area within [`MAX_LOSS`];
//! otherwise the outline stays as it was and a warning names the part.

use std::collections::BTreeMap;

use platener_geom::Polygon;
use platener_geom::boolean::difference;
use platener_geom::clean::{clean, widen};
use platener_geom::polygon::total_area;
use platener_geom::tolerance::CRUMB_AREA;
use platener_geom::validity::is_valid;
use rayon::prelude::*;

use crate::context::{StepContext, WarningKind};
use crate::plan::{Joint, Part, PlanInput};

/// A repair may cut off at most this share of a part's area; beyond it the outline is left
/// as it was, with a warning (see [`clean_part`]).
const MAX_LOSS: f64 = 0.02;

/// What cleaning did to one part: a warning for it, and whether it is gone.
#[derive(Debug, Clone, PartialEq)]
pub struct Repair {
    /// The part's id.
    pub part: u32,
    /// What the user should know, when anything of substance was lost.
    pub message: Option<String>,
    /// The part had no material wider than the kerf and was removed (with its joints).
    pub removed: bool,
}

/// Repairs the outline of every part in `parts` so that it is valid with no material narrower
/// than `min_width` (mm, the kerf); removes parts left with nothing, and `joints` naming them.
/// Returns one [`Repair`] per part that changed, in part order. An outline that cannot go on
/// the 1 µm grid is left as it is: the `kerf` step refuses it with the part's id.
pub fn clean_parts(parts: &mut Vec<Part>, joints: &mut Vec<Joint>, min_width: f64) -> Vec<Repair> {
    clean_parts_within(parts, joints, min_width, &BTreeMap::new())
}

/// [`clean_parts`], where a part whose id `uncut` maps to its outline before joints were cut
/// may have a neck narrower than `min_width` widened ([`widen_part`]) instead of left invalid,
/// never into its slots and notches (the uncut outline less the part).
pub fn clean_parts_within(
    parts: &mut Vec<Part>,
    joints: &mut Vec<Joint>,
    min_width: f64,
    uncut: &BTreeMap<u32, Polygon>,
) -> Vec<Repair> {
    let repairs: Vec<Option<Repair>> = parts
        .par_iter_mut()
        .map(|p| clean_part(p, min_width, uncut.get(&p.id)))
        .collect();
    let repairs: Vec<Repair> = repairs.into_iter().flatten().collect();
    let gone: Vec<u32> = repairs.iter().filter(|r| r.removed).map(|r| r.part).collect();
    if !gone.is_empty() {
        parts.retain(|p| !gone.contains(&p.id));
        joints.retain(|j| !j.parts.iter().any(|id| gone.contains(id)));
    }
    repairs
}

/// Repairs one part in place; `None` when its outline was already valid. `uncut`: its outline
/// before joints, when a neck may be widened.
fn clean_part(part: &mut Part, min_width: f64, uncut: Option<&Polygon>) -> Option<Repair> {
    let pieces = clean(&part.polygon, min_width).ok()?;
    if pieces.len() == 1 && pieces[0] == part.polygon {
        return None;
    }
    let id = part.id;
    let Some(kept) = pieces.first().cloned() else {
        return Some(Repair {
            part: id,
            message: Some(format!(
                "part {id} has no material wider than the kerf ({min_width} mm) and is left out"
            )),
            removed: true,
        });
    };
    let cut_off: Vec<f64> = pieces[1..]
        .iter()
        .map(|p| p.area())
        .filter(|a| *a >= CRUMB_AREA)
        .collect();
    let lost = part.polygon.area() - total_area(&pieces);
    let whole = part.polygon.area();
    let gone = lost.max(0.0) + cut_off.iter().sum::<f64>();
    if gone > MAX_LOSS * whole {
        return Some(widen_part(part, min_width, gone, uncut));
    }
    part.polygon = kept;
    let message = (!cut_off.is_empty() || lost >= 1.0).then(|| {
        format!(
            "part {id}: its outline was repaired (slivers narrower than the kerf, {min_width} mm, or rings \
             touching themselves): {} piece(s) of {:.1} mm² cut off, {:.1} mm² lost",
            cut_off.len(),
            cut_off.iter().sum::<f64>(),
            lost.max(0.0) + cut_off.iter().sum::<f64>()
        )
    });
    Some(Repair {
        part: id,
        message,
        removed: false,
    })
}

/// The repair of a part whose cleaning would cut off `gone` mm² (more than [`MAX_LOSS`]):
/// its narrow material widened to `min_width`, never into the slots and notches its joints cut
/// (`uncut` less the part), when that leaves one valid piece within [`MAX_LOSS`] of the part's
/// area; else (or without `uncut`: stacked layers, whose shaft notches the lead found bridged)
/// the outline as it was. A warning names the part either way.
fn widen_part(part: &mut Part, min_width: f64, gone: f64, uncut: Option<&Polygon>) -> Repair {
    let (id, whole) = (part.id, part.polygon.area());
    let slots = |u: &Polygon| difference(std::slice::from_ref(u), std::slice::from_ref(&part.polygon)).ok();
    let widened: Option<Polygon> = uncut
        .and_then(slots)
        .and_then(|keep_out| widen(&part.polygon, min_width, &keep_out).ok())
        .filter(|pieces| pieces.len() == 1 && pieces[0].area() > 0.0)
        .map(|mut pieces| pieces.remove(0))
        .filter(|p| (p.area() - whole).abs() <= MAX_LOSS * whole && is_valid(p, min_width));
    let message = match widened {
        Some(p) => {
            let added = p.area() - whole;
            part.polygon = p;
            format!(
                "part {id}: material narrower than the kerf ({min_width} mm) held {gone:.1} mm² of it; \
                 widened to the kerf instead of cutting that off ({added:+.2} mm²)"
            )
        }
        // Separating a touch split the part (a slot notch pinching a layer's neck): losing a
        // piece this large is worse than an outline that touches itself; leave it and say so.
        None => format!(
            "part {id}: its outline touches itself or is narrower than the kerf ({min_width} mm) somewhere, \
             and repairing it would cut off {gone:.1} mm² of {whole:.1}; left as it is"
        ),
    };
    Repair {
        part: id,
        message: Some(message),
        removed: false,
    }
}

/// Cleans the outlines of `input`'s parts for its kerf ([`clean_parts`]) and warns, naming the
/// part, where material was cut off or a part left out. Both methods call it where they make
/// their parts.
pub fn clean_input(input: &mut PlanInput, cx: &mut StepContext<'_>) {
    clean_input_within(input, &BTreeMap::new(), cx);
}

/// [`clean_input`] with the parts' outlines before joints ([`clean_parts_within`]): the plate
/// method's, whose necks may be widened.
pub fn clean_input_within(input: &mut PlanInput, uncut: &BTreeMap<u32, Polygon>, cx: &mut StepContext<'_>) {
    let kerf = input.settings.kerf();
    for r in clean_parts_within(&mut input.parts, &mut input.joints, kerf, uncut) {
        if let Some(message) = r.message {
            cx.warn_part(WarningKind::CuttingPlan, Some(r.part), message);
        }
    }
}
