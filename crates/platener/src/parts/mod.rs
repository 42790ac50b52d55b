//! Step `parts` of the plate method: plates become parts to cut.
//!
//! Each plate is one part, numbered from 1 in plate order, with the outline the `joints` step
//! gave it (fingers, tabs, slots) and its connections as plan.json joints; dovetail keys follow
//! as parts of their own. Outlines that joints left invalid are repaired ([`clean`]).

pub mod clean;

use std::collections::BTreeMap;

use crate::context::StepContext;
use crate::joints::{Connection, ConnectionKind, JointStyle, Joints};
use crate::plan::{EdgeLabel, Joint, JointKind, Method, Part, PlanInput, SettingValue, SourceInfo};
use crate::plates::Plates;
use crate::read::Model;
use crate::settings::Settings;
use crate::weld::Welded;

/// Step `parts` of the plate method: the plates with their joints as parts to cut.
pub fn run(
    model: &Model,
    plates: &Plates,
    joints: Option<&Joints>,
    welded: &Welded,
    settings: &Settings,
    cx: &mut StepContext<'_>,
) -> PlanInput {
    let mut parts = plate_parts(plates, joints);
    let mut connections: Vec<Joint> = joints.map_or(Vec::new(), |j| j.connections.iter().map(joint).collect());
    if let Some(j) = joints {
        add_keys(plates, j, &mut parts, &mut connections);
    }
    let mut method_settings = BTreeMap::new();
    method_settings.insert(
        "offered_thicknesses".to_string(),
        SettingValue::Numbers(settings.offered_thicknesses()),
    );
    method_settings.insert("weld".to_string(), SettingValue::Number(welded.distance));
    method_settings.insert(
        "extruded_plates".to_string(),
        SettingValue::Flag(settings.plates.mode == crate::PlateMode::InherentAndExtruded),
    );
    let mut input = PlanInput::new(SourceInfo::from(model), Method::Plate, parts, connections);
    input.settings = settings.cut.clone();
    input.method_settings = method_settings;
    input.method_report = serde_json::to_value(serde_json::json!({
        "coverage": &plates.coverage,
        "contained_removed": plates.contained_removed,
        "trimmed": plates.trimmed,
        "rejoined": plates.rejoined,
        "connections": joints.map(|j| &j.connections),
    }))
    .ok();
    clean::clean_input(&mut input, cx);
    input
}

/// One part per plate, numbered from 1 in plate order, with its jointed outline and the
/// connection numbers of its edges.
fn plate_parts(plates: &Plates, joints: Option<&Joints>) -> Vec<Part> {
    plates
        .plates
        .iter()
        .enumerate()
        .map(|(i, p)| {
            let outline = joints.map_or(&p.polygon, |j| &j.outlines[i]);
            let mut part = Part::plate(i as u32 + 1, p.thickness, outline.clone(), p.frame);
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

/// A connection as plan.json's joint.
fn joint(c: &Connection) -> Joint {
    Joint {
        parts: [c.plates[0] + 1, c.plates[1] + 1],
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
fn add_keys(plates: &Plates, joints: &Joints, parts: &mut Vec<Part>, connections: &mut Vec<Joint>) {
    for key in &joints.keys {
        let id = parts.len() as u32 + 1;
        let plate = &plates.plates[key.plate as usize];
        parts.push(Part::plate(id, plate.thickness, key.outline.clone(), plate.frame));
        let angle_deg = joints
            .connections
            .get(key.label as usize - 1)
            .map_or(90.0, |c| c.angle_deg);
        connections.push(Joint {
            parts: [key.notched + 1, id],
            kind: JointKind::Dovetail,
            angle_deg,
            label: key.label,
        });
    }
}
