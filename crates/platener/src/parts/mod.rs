//! Step `parts` of the plate method: plates become parts to cut.
//!
//! Each plate is one part, numbered from 1 in plate order, with the outline the `joints` step
//! gave it (fingers, tabs, slots) and its connections as plan.json joints; dovetail keys follow
//! as parts of their own. Plates no joint holds are named in warnings, and small ones left out
//! ([`loose`]). Outlines that joints left invalid are repaired ([`crate::repair`]); parts the joints
//! left smaller than the smallest part are left out ([`small`]); necks the joints left
//! narrower than twice the thickness are reported ([`necks`]). Raised details are glued on
//! from a thinner sheet ([`raised`]); standoffs taller than a sheet become stacked discs
//! ([`standoffs`]).

mod loose;
pub mod necks;
mod raised;
mod small;
mod standoffs;

use std::collections::BTreeMap;

use crate::bends::Bends;
use crate::context::{StepContext, WarningKind};
use crate::error::{Error, ModelProblem, Result};
use crate::joints::{Connection, ConnectionKind, JointStyle, Joints};
use platener_geom::Polygon;
use platener_geom::boolean::intersection;

use crate::plan::{
    BendStyle, EdgeLabel, Joint, JointKind, Mark, MarkSide, Method, Part, PlanInput, SettingValue, SourceInfo,
    score_rings,
};
use crate::plates::{Feature, Plates, Side};
use crate::read::Model;
use crate::settings::Settings;
use crate::weld::Welded;

/// Step `parts` of the plate method: the plates with their joints as parts to cut; with
/// `standoffs`, the bosses standing on them as stacked discs too.
pub fn run(
    model: &Model,
    plates: &Plates,
    (joints, bends): (Option<&Joints>, Option<&Bends>),
    (welded, standoffs): (&Welded, bool),
    settings: &Settings,
    cx: &mut StepContext<'_>,
) -> Result<PlanInput> {
    // The bent parts the `joints` step found to hold together.
    let held = bends.map(|b| joints.map_or_else(|| b.clone(), |j| b.keeping(&j.held_bends)));
    let bends = held.as_ref();
    // Raised details as tall as a thinner offered sheet are glued on (`raised`).
    let details = if settings.features == crate::settings::Features::Engrave {
        raised::details(
            plates,
            joints,
            &settings.offered_thicknesses(),
            settings.plates.min_area,
        )
    } else {
        Vec::new()
    };
    let ids = loose::part_ids(plates, (joints, bends), &raised::glued_plates(&details), cx);
    let mut parts = plate_parts(plates, joints, &ids);
    if let Some(b) = bends {
        bent_parts(plates, joints, b, &ids, &mut parts, cx)?;
    }
    let mut connections: Vec<Joint> =
        joints.map_or(Vec::new(), |j| j.connections.iter().map(|c| joint(c, &ids)).collect());
    if let Some(j) = joints {
        add_keys(plates, j, &ids, &mut parts, &mut connections);
    }
    let mut glued = Vec::new();
    let made = (&mut parts, &mut connections, &mut glued);
    for note in raised::glue(&details, plates, &ids, made) {
        cx.warn(WarningKind::Features, note);
    }
    // Bosses taller than a sheet are stacked discs on a peg or a screw (`standoffs`), unless
    // a later step builds them (the classifier's `layers`).
    if standoffs && settings.features != crate::settings::Features::Cut {
        let name = cx.model();
        let off_grid = |e| Error::model(name, ModelProblem::OffGrid(e));
        let found =
            standoffs::find(plates, &settings.offered_thicknesses(), settings.plates.min_area).map_err(off_grid)?;
        let made = standoffs::build(&found, plates, &ids, (&mut parts, &mut connections)).map_err(off_grid)?;
        for note in made {
            cx.warn(WarningKind::Features, note);
        }
    }
    if let Some(b) = bends {
        add_bends(b, &ids, &mut parts, &mut connections);
    }
    let mut method_settings = BTreeMap::new();
    method_settings.insert(
        "offered_thicknesses".to_string(),
        SettingValue::Numbers(settings.offered_thicknesses()),
    );
    method_settings.insert("weld".to_string(), SettingValue::Number(welded.distance));
    method_settings.insert(
        "features".to_string(),
        SettingValue::Text(format!("{:?}", settings.features).to_lowercase()),
    );
    method_settings.insert(
        "extruded_plates".to_string(),
        SettingValue::Flag(settings.plates.mode == crate::PlateMode::InherentAndExtruded),
    );
    let mut input = PlanInput::new(SourceInfo::from(model), Method::Plate, parts, connections);
    input.settings = settings.cut.clone();
    input.glued = glued;
    input.method_settings = method_settings;
    input.method_report = serde_json::to_value(serde_json::json!({
        "coverage": &plates.coverage,
        "contained_removed": plates.contained_removed,
        "trimmed": plates.trimmed,
        "rejoined": plates.rejoined,
        "features": &plates.features,
        "connections": joints.map(|j| &j.connections),
    }))
    .ok();
    crate::repair::clean_input(&mut input, cx);
    small::leave_out_small(&mut input, settings.plates.min_area, cx);
    let plate_of: BTreeMap<u32, usize> = ids.iter().enumerate().filter_map(|(i, id)| Some(((*id)?, i))).collect();
    necks::warn_necks(&input.parts, plates, &plate_of, cx);
    Ok(input)
}

/// Replaces the first plate of each bent part by the bent part (the other plates made no
/// part: they share its id).
fn bent_parts(
    plates: &Plates,
    joints: Option<&Joints>,
    bends: &Bends,
    ids: &[Option<u32>],
    parts: &mut [Part],
    cx: &mut StepContext<'_>,
) -> Result<()> {
    let Some(style) = bends.style else {
        return Ok(());
    };
    for b in &bends.parts {
        let first = b.members[0].plate as usize;
        let id = id_of(ids, first as u32);
        let outlines: Vec<&Polygon> = b
            .members
            .iter()
            .map(|m| {
                joints.map_or(&plates.plates[m.plate as usize].polygon, |j| {
                    &j.outlines[m.plate as usize]
                })
            })
            .collect();
        let labels: Vec<Vec<_>> = b
            .members
            .iter()
            .map(|m| joints.map_or(Vec::new(), |j| j.edges[m.plate as usize].clone()))
            .collect();
        let marks_of = |plate: u32, outline: &Polygon| feature_marks(&plates.features, plate, outline);
        let (part, notes) = crate::bends::flat::flat_part(id, b, plates, &outlines, &labels, &marks_of, style)
            .map_err(|e| Error::model(cx.model(), ModelProblem::OffGrid(e)))?;
        for note in notes {
            cx.warn_part(WarningKind::Joints, Some(id), note);
        }
        if let Some(slot) = parts.iter_mut().find(|p| p.id == id) {
            *slot = part;
        }
    }
    Ok(())
}

/// The bends as joints of kind `bend` between the merged plates, numbered after every part
/// (so a plate id never names a part), and each bent part's `merged`; a glued seam is a
/// `flap` joint naming its part twice. Their labels follow the connections'.
fn add_bends(bends: &Bends, ids: &[Option<u32>], parts: &mut [Part], connections: &mut Vec<Joint>) {
    let mut next_plate = parts.iter().map(|p| p.id).max().unwrap_or(0);
    let mut label = connections.iter().map(|c| c.label).max().unwrap_or(0);
    let flaps = matches!(bends.style, Some(BendStyle::Perforation | BendStyle::Score));
    for b in &bends.parts {
        let id = id_of(ids, b.members[0].plate);
        let merged: Vec<u32> = b
            .members
            .iter()
            .map(|_| {
                next_plate += 1;
                next_plate
            })
            .collect();
        for bend in &b.bends {
            label += 1;
            connections.push(Joint {
                parts: bend.members.map(|m| merged[m]),
                kind: JointKind::Bend,
                angle_deg: bend.enclosed_deg,
                label,
            });
        }
        if flaps {
            for seam in &b.seams {
                label += 1;
                connections.push(Joint {
                    parts: [id, id],
                    kind: JointKind::Flap,
                    angle_deg: seam.meeting.enclosed.to_degrees(),
                    label,
                });
            }
        }
        if let Some(part) = parts.iter_mut().find(|p| p.id == id) {
            part.merged = merged;
        }
    }
}

/// One part per plate kept (per bent part: its first plate, replaced later), numbered by `ids`, with its jointed outline and the connection
/// numbers of its edges.
fn plate_parts(plates: &Plates, joints: Option<&Joints>, ids: &[Option<u32>]) -> Vec<Part> {
    let mut seen = std::collections::BTreeSet::new();
    plates
        .plates
        .iter()
        .enumerate()
        .filter_map(|(i, p)| Some((i, p, ids[i]?)))
        // The plates of a bent part share an id: the first stands for the part.
        .filter(|&(_, _, id)| seen.insert(id))
        .map(|(i, p, id)| {
            let outline = joints.map_or(&p.polygon, |j| &j.outlines[i]);
            let mut part = Part::plate(id, p.thickness, outline.clone(), p.frame);
            part.marks = feature_marks(&plates.features, i as u32, outline);
            if let Some(j) = joints {
                part.edge_labels = j.edges[i]
                    .iter()
                    .map(|&(connection, segment)| EdgeLabel { connection, segment })
                    .collect();
            }
            part
        })
        .collect()
}

/// The part id of plate `p`: a joint's plates are never left out.
fn id_of(ids: &[Option<u32>], p: u32) -> u32 {
    ids[p as usize].expect("a plate with a joint is kept")
}

/// The `score` marks of plate `plate`'s one-sided features: every ring of their footprints,
/// closed, clipped to the part's outline (joints may have cut into it), with the face each is
/// on (the part lies with its local z = 0 face up).
fn feature_marks(features: &[Feature], plate: u32, outline: &Polygon) -> Vec<Mark> {
    let mut marks = Vec::new();
    for (side, mark_side) in [(Side::Up, MarkSide::Top), (Side::Down, MarkSide::Bottom)] {
        let regions: Vec<Polygon> = features
            .iter()
            .filter(|f| f.plate == plate && f.side == side)
            .map(|f| f.region.clone())
            .collect();
        if regions.is_empty() {
            continue;
        }
        // A region that the booleans cannot clip is drawn as found: it lay inside the plate.
        let clipped = intersection(&regions, std::slice::from_ref(outline)).unwrap_or(regions);
        marks.extend(score_rings(&clipped, mark_side));
    }
    marks
}

/// A connection as plan.json's joint.
fn joint(c: &Connection, ids: &[Option<u32>]) -> Joint {
    Joint {
        parts: [id_of(ids, c.plates[0]), id_of(ids, c.plates[1])],
        kind: match c.kind {
            _ if c.style == JointStyle::Jim => JointKind::Jim,
            _ if c.style == JointStyle::Dovetail => JointKind::Dovetail,
            ConnectionKind::Corner => JointKind::Finger,
            ConnectionKind::Tee => JointKind::Slot,
            ConnectionKind::Cross => JointKind::Halved,
        },
        angle_deg: c.angle_deg,
        label: c.label,
    }
}

/// Dovetail keys are parts of their own, numbered after the plates; each is a joint partner
/// of the plate whose notch it fills (so the assembly check sees it held).
fn add_keys(
    plates: &Plates,
    joints: &Joints,
    ids: &[Option<u32>],
    parts: &mut Vec<Part>,
    connections: &mut Vec<Joint>,
) {
    for key in &joints.keys {
        let id = parts.len() as u32 + 1;
        let plate = &plates.plates[key.plate as usize];
        parts.push(Part::plate(id, plate.thickness, key.outline.clone(), plate.frame));
        let angle_deg = joints
            .connections
            .get(key.label as usize - 1)
            .map_or(90.0, |c| c.angle_deg);
        connections.push(Joint {
            parts: [id_of(ids, key.notched), id],
            kind: JointKind::Dovetail,
            angle_deg,
            label: key.label,
        });
    }
}
