//! The stack as parts and joints for the cutting plan (the pipeline's `parts` snapshot).
//!
//! Every island is a part of kind `layer`, placed by its layer's frame (the stack frame moved
//! up to the layer's bottom face); every shaft a part of kind `shaft`, placed by its own frame
//! (x along its slots, y up the stack, z through its thickness). Each slot is one joint of kind
//! `shaft` between the shaft part and the layer part (in that order), at 90°.

use std::collections::BTreeMap;

use glam::DVec2;

use platener_geom::{Polygon, boolean};

use super::Stack;
use super::marks::tag;
use super::tabs::{number_fits, with_tab};
use crate::error::{Error, ModelProblem, Result};
use crate::plan::{CutSettings, Joint, JointKind, Method, Part, PartKind, PlanInput, SettingValue, SourceInfo};
use crate::read::Model;
use crate::settings::{Settings, StackAxis};

/// The parts, joints and settings of `stack`, converted from `model`, and the ids of the
/// layers that carry their number on a tab (`tabs.rs`).
pub fn plan_input(stack: &Stack, model: &Model, settings: &Settings) -> Result<(PlanInput, Vec<u32>)> {
    let geometry = |e: platener_geom::GridError| Error::model(&model.name, ModelProblem::OffGrid(e));
    let (mut parts, tabbed) = layer_parts(stack, &settings.cut, &geometry)?;
    let joints = shaft_parts(stack, &mut parts, &settings.cut, &geometry)?;
    let method_settings = method_settings(stack, settings);
    let mut input = PlanInput::new(SourceInfo::from(model), Method::Stacked, parts, joints);
    input.settings = settings.cut.clone();
    input.method_settings = method_settings;
    input.glued = super::glued::glued(stack).0;
    Ok((input, tabbed))
}

/// Every island as a part of kind `layer`, tagged with its layer's number and numbered (on a
/// tab when it is too thin); returns the parts and the ids of those with a tab.
fn layer_parts(
    stack: &Stack,
    cut: &CutSettings,
    geometry: &dyn Fn(platener_geom::GridError) -> Error,
) -> Result<(Vec<Part>, Vec<u32>)> {
    let mut parts = Vec::new();
    let mut tabbed = Vec::new();
    for (k, layer) in stack.layers.iter().enumerate() {
        for island in &layer.islands {
            let text = format!("L{}", layer.number);
            let marks = tag(&island.polygon, &text, &[DVec2::X], DVec2::X, DVec2::ZERO)
                .map_err(geometry)?
                .unwrap_or_default();
            let mut part = Part {
                id: island.part,
                kind: PartKind::Layer,
                thickness: stack.layer_thickness(),
                polygon: island.polygon.clone(),
                frame: stack.layer_frame(k),
                marks,
                edge_labels: Vec::new(),
                merged: Vec::new(),
            };
            if !make_room_for_number(&mut part, cut) {
                let slots = boolean::difference(
                    std::slice::from_ref(&island.outline),
                    std::slice::from_ref(&island.polygon),
                )
                .map_err(geometry)?;
                let others: Vec<&Polygon> = layer
                    .islands
                    .iter()
                    .filter(|o| o.part != island.part)
                    .map(|o| &o.outline)
                    .collect();
                if let Some(p) =
                    with_tab(&island.polygon, &slots, &others, island.part, cut.kerf()).map_err(geometry)?
                {
                    let marks = std::mem::take(&mut part.marks);
                    part.polygon = p;
                    part.marks = marks;
                    make_room_for_number(&mut part, cut);
                    tabbed.push(part.id);
                }
            }
            parts.push(part);
        }
    }
    Ok((parts, tabbed))
}

/// Whether `part`'s number fits, dropping its tag (the number matters more) when only that
/// makes it fit.
fn make_room_for_number(part: &mut Part, cut: &CutSettings) -> bool {
    if number_fits(part, cut) {
        return true;
    }
    if part.marks.is_empty() {
        return false;
    }
    let marks = std::mem::take(&mut part.marks);
    if number_fits(part, cut) {
        return true;
    }
    part.marks = marks;
    false
}

/// Every shaft as a part of kind `shaft` (added to `parts`), tagged with its number and the
/// layers it spans; returns one joint per slot.
fn shaft_parts(
    stack: &Stack,
    parts: &mut Vec<Part>,
    cut: &CutSettings,
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
        let mut part = Part {
            id: shaft.part,
            kind: PartKind::Shaft,
            thickness: stack.shaft_thickness,
            polygon: shaft.polygon.clone(),
            frame: shaft.frame,
            marks: marks.unwrap_or_default(),
            edge_labels: Vec::new(),
            merged: Vec::new(),
        };
        make_room_for_number(&mut part, cut);
        parts.push(part);
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
