//! The stack as parts and joints for the cutting plan (the pipeline's `parts` snapshot).
//!
//! Every island is a part of kind `layer`, placed by its layer's frame (the stack frame moved
//! up to the layer's bottom face); every shaft a part of kind `shaft`, placed by its own frame
//! (x along its slots, y up the stack, z through its thickness). Each slot is one joint of kind
//! `shaft` between the shaft part and the layer part (in that order), at 90°.

use std::collections::BTreeMap;

use glam::DVec2;

use super::Stack;
use super::marks::tag;
use crate::error::{Error, ModelProblem, Result};
use crate::plan::{Joint, JointKind, Method, Part, PartKind, PlanInput, SettingValue, SourceInfo};
use crate::read::Model;
use crate::settings::{Settings, StackAxis};

/// The parts, joints and settings of `stack`, converted from `model`.
pub fn plan_input(stack: &Stack, model: &Model, settings: &Settings) -> Result<PlanInput> {
    let geometry = |e: platener_geom::GridError| Error::model(&model.name, ModelProblem::OffGrid(e));
    let mut parts = layer_parts(stack, &geometry)?;
    let joints = shaft_parts(stack, &mut parts, &geometry)?;
    let method_settings = method_settings(stack, settings);
    let mut input = PlanInput::new(SourceInfo::from(model), Method::Stacked, parts, joints);
    input.settings = settings.cut.clone();
    input.method_settings = method_settings;
    Ok(input)
}

/// Every island as a part of kind `layer`, tagged with its layer's number.
fn layer_parts(stack: &Stack, geometry: &dyn Fn(platener_geom::GridError) -> Error) -> Result<Vec<Part>> {
    let mut parts = Vec::new();
    for (k, layer) in stack.layers.iter().enumerate() {
        for island in &layer.islands {
            let text = format!("L{}", layer.number);
            let marks = tag(&island.polygon, &text, &[DVec2::X], DVec2::X, DVec2::ZERO)
                .map_err(geometry)?
                .unwrap_or_default();
            parts.push(Part {
                id: island.part,
                kind: PartKind::Layer,
                thickness: stack.layer_thickness(),
                polygon: island.polygon.clone(),
                frame: stack.layer_frame(k),
                marks,
                edge_labels: Vec::new(),
                merged: Vec::new(),
            });
        }
    }
    Ok(parts)
}

/// Every shaft as a part of kind `shaft` (added to `parts`), tagged with its number and the
/// layers it spans; returns one joint per slot.
fn shaft_parts(
    stack: &Stack,
    parts: &mut Vec<Part>,
    geometry: &dyn Fn(platener_geom::GridError) -> Error,
) -> Result<Vec<Joint>> {
    let mut joints = Vec::new();
    for (j, shaft) in stack.shafts.iter().enumerate() {
        let (lo, hi) = shaft.polygon.bounds();
        let center = (lo + hi) / 2.0;
        let (first, last) = (shaft.bands[0].layer + 1, shaft.bands[shaft.bands.len() - 1].layer + 1);
        let long = format!("S{} L{first}-{last}", j + 1);
        let short = format!("S{}", j + 1);
        let mut marks = None;
        for text in [&long, &short] {
            marks = tag(&shaft.polygon, text, &[DVec2::Y, DVec2::X], DVec2::Y, center).map_err(geometry)?;
            if marks.is_some() {
                break;
            }
        }
        parts.push(Part {
            id: shaft.part,
            kind: PartKind::Shaft,
            thickness: stack.shaft_thickness,
            polygon: shaft.polygon.clone(),
            frame: shaft.frame,
            marks: marks.unwrap_or_default(),
            edge_labels: Vec::new(),
            merged: Vec::new(),
        });
        for b in &shaft.bands {
            joints.push(Joint {
                // Shaft first: a sampled check (`platener verify`) starting from the shaft's
                // cells finds the slot's walls half a step away on every side, a notch included.
                parts: [shaft.part, stack.layers[b.layer].islands[b.island].part],
                kind: JointKind::Shaft,
                angle_deg: 90.0,
                label: joints.len() as u32 + 1,
            });
        }
    }
    Ok(joints)
}

/// The stacked method's settings as the plan records them.
fn method_settings(stack: &Stack, s: &Settings) -> BTreeMap<String, SettingValue> {
    let mut method_settings = BTreeMap::new();
    let axis = match s.stacked.axis {
        StackAxis::Auto => "auto",
        StackAxis::X => "x",
        StackAxis::Y => "y",
        StackAxis::Z => "z",
    };
    method_settings.insert("axis".to_string(), SettingValue::Text(axis.into()));
    let up = stack.up();
    method_settings.insert("up".to_string(), SettingValue::Numbers(vec![up.x, up.y, up.z]));
    method_settings.insert(
        "layer_thickness".to_string(),
        SettingValue::Number(stack.layer_thickness()),
    );
    method_settings.insert(
        "shaft_thickness".to_string(),
        SettingValue::Number(stack.shaft_thickness),
    );
    method_settings.insert("slot_margin".to_string(), SettingValue::Number(s.stacked.margin));
    method_settings.insert(
        "shaft_width".to_string(),
        SettingValue::Numbers(vec![s.stacked.shaft_min_width, s.stacked.shaft_max_width]),
    );
    method_settings.insert("weld".to_string(), SettingValue::Number(0.0));
    method_settings
}
