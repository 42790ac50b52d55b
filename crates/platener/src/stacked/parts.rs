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
use super::tabs::{add_keeping_number, number_fits, number_near, reference_marks, with_tab};
use crate::error::{Error, ModelProblem, Result};
use crate::plan::{CutSettings, Joint, JointKind, Method, Part, PartKind, PlanInput, SettingValue, SourceInfo};
use crate::read::Model;
use crate::settings::{Settings, StackAxis};

/// The parts, joints and settings of `stack`, converted from `model`, and where the numbers
/// of layers too thin for them went (`tabs.rs`).
pub fn plan_input(stack: &Stack, model: &Model, settings: &Settings) -> Result<(PlanInput, Numbers)> {
    let geometry = |e: platener_geom::GridError| Error::model(&model.name, ModelProblem::OffGrid(e));
    let (mut parts, mut numbers) = layer_parts(stack, &settings.cut, &geometry)?;
    let joints = shaft_parts(stack, &mut parts, &settings.cut, &mut numbers, &geometry)?;
    let method_settings = method_settings(stack, settings);
    let mut input = PlanInput::new(SourceInfo::from(model), Method::Stacked, parts, joints);
    input.settings = settings.cut.clone();
    input.method_settings = method_settings;
    input.glued = super::glued::glued(stack).0;
    input.method_report = Some(serde_json::json!({ "numbers": &numbers }));
    Ok((input, numbers))
}

/// Where the layers too thin for their numbers carry them (report.json's `method_report`).
#[derive(Debug, Clone, Default, serde::Serialize)]
pub struct Numbers {
    /// Parts numbered on a tab of their outline.
    pub on_tab: Vec<u32>,
    /// Parts whose footprint and number are engraved on a part of an adjacent layer:
    /// `[part, the part carrying it]`.
    pub on_neighbour: Vec<[u32; 2]>,
    /// Shafts too narrow for their numbers (a peg of a thin sheet), numbered beside their slot
    /// on a layer they pass through: `[shaft, the layer part carrying it]`.
    pub beside_slot: Vec<[u32; 2]>,
    /// Parts left without a number.
    pub none: Vec<u32>,
}

/// Every island as a part of kind `layer`, tagged with its layer's number and numbered (on a
/// tab, or on its neighbour, when it is too thin); returns the parts and where the numbers of
/// thin ones went.
fn layer_parts(
    stack: &Stack,
    cut: &CutSettings,
    geometry: &dyn Fn(platener_geom::GridError) -> Error,
) -> Result<(Vec<Part>, Numbers)> {
    let mut parts = Vec::new();
    let mut numbers = Numbers::default();
    let mut unnumbered = Vec::new();
    let glue = super::glued::glued(stack).0;
    let island_of = |id: u32| {
        stack
            .layers
            .iter()
            .enumerate()
            .find_map(|(k, l)| l.islands.iter().position(|i| i.part == id).map(|i| (k, i)))
    };
    for (k, layer) in stack.layers.iter().enumerate() {
        for (i, island) in layer.islands.iter().enumerate() {
            let text = format!("L{}", layer.number);
            let mut marks = tag(&island.polygon, &text, &[DVec2::X], DVec2::X, DVec2::ZERO)
                .map_err(geometry)?
                .unwrap_or_default();
            for r in stack.raised.iter().filter(|r| (r.layer, r.island) == (k, i)) {
                // Slots cut after the detail was found: the marks stay on the material.
                let on = boolean::intersection(&r.regions, std::slice::from_ref(&island.polygon)).map_err(geometry)?;
                marks.extend(crate::plan::score_rings(&on, r.side));
            }
            marks.extend(glue_marks(stack, &glue, island.part, &island_of).map_err(geometry)?);
            let mut part = Part {
                id: island.part,
                kind: PartKind::Layer,
                thickness: stack.layer_thickness(),
                polygon: island.polygon.clone(),
                frame: stack.layer_frame(k),
                marks,
                edge_labels: Vec::new(),
                merged: Vec::new(),
                segments: Vec::new(),
                bends: Vec::new(),
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
                let tab = with_tab(&island.polygon, &slots, &others, island.part, cut.kerf()).map_err(geometry)?;
                let numbered = tab.is_some_and(|p| {
                    part.polygon = p;
                    make_room_for_number(&mut part, cut)
                });
                if numbered {
                    numbers.on_tab.push(part.id);
                } else {
                    part.polygon = island.polygon.clone();
                    unnumbered.push((k, i));
                }
            }
            parts.push(part);
        }
    }
    for (k, i) in unnumbered {
        match on_neighbour(stack, k, i, &mut parts, cut).map_err(geometry)? {
            Some(on) => numbers.on_neighbour.push([stack.layers[k].islands[i].part, on]),
            None => numbers.none.push(stack.layers[k].islands[i].part),
        }
    }
    Ok((parts, numbers))
}

/// The glue marks of part `id`: for every part only glue holds to it, the outline of the area
/// they share, scored on the face that touches it (issue 31: where to glue, on both parts). A
/// layer's face down on the sheet is its upper face, so the lower part's mark is on its
/// `Bottom` side (engraved with the part turned over) and the upper part's on its `Top`.
fn glue_marks(
    stack: &Stack,
    glue: &[crate::plan::Glue],
    id: u32,
    island_of: &dyn Fn(u32) -> Option<(usize, usize)>,
) -> std::result::Result<Vec<crate::plan::Mark>, platener_geom::GridError> {
    let mut marks = Vec::new();
    for g in glue.iter().filter(|g| g.parts.contains(&id)) {
        let (Some(a), Some(b)) = (island_of(g.parts[0]), island_of(g.parts[1])) else {
            continue;
        };
        let (pa, pb) = (
            &stack.layers[a.0].islands[a.1].polygon,
            &stack.layers[b.0].islands[b.1].polygon,
        );
        let shared = boolean::intersection(std::slice::from_ref(pa), std::slice::from_ref(pb))?;
        let side = if g.parts[0] == id {
            crate::plan::MarkSide::Bottom
        } else {
            crate::plan::MarkSide::Top
        };
        marks.extend(crate::plan::score_rings(&shared, side));
    }
    Ok(marks)
}

/// Engraves the footprint and number of island `i` of layer `k` on the part of an adjacent
/// layer it overlaps most whose own number still fits; returns that part's id.
fn on_neighbour(
    stack: &Stack,
    k: usize,
    i: usize,
    parts: &mut [Part],
    cut: &CutSettings,
) -> std::result::Result<Option<u32>, platener_geom::GridError> {
    let island = &stack.layers[k].islands[i];
    let mut candidates = Vec::new();
    for n in [k.checked_sub(1), Some(k + 1)].into_iter().flatten() {
        for other in stack.layers.get(n).map_or(&[][..], |l| &l.islands[..]) {
            let o = boolean::intersection(
                std::slice::from_ref(&island.outline),
                std::slice::from_ref(&other.polygon),
            )?;
            let area = platener_geom::polygon::total_area(&o);
            if area > 0.0 {
                candidates.push((area, other.part));
            }
        }
    }
    candidates.sort_by(|a, b| b.0.total_cmp(&a.0).then(a.1.cmp(&b.1)));
    for (_, on) in candidates {
        let Some(at) = parts.iter().position(|p| p.id == on) else {
            continue;
        };
        let Some(marks) = reference_marks(&island.outline, island.part, &parts[at], cut.kerf())? else {
            continue;
        };
        if add_keeping_number(&mut parts[at], marks, cut) {
            return Ok(Some(on));
        }
    }
    Ok(None)
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
/// layers it spans (a shaft too narrow for its number has it beside its slot on a layer,
/// noted in `numbers`); returns one joint per slot.
fn shaft_parts(
    stack: &Stack,
    parts: &mut Vec<Part>,
    cut: &CutSettings,
    numbers: &mut Numbers,
    geometry: &dyn Fn(platener_geom::GridError) -> Error,
) -> Result<Vec<Joint>> {
    let mut joints = Vec::new();
    let mut narrow = Vec::new();
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
            segments: Vec::new(),
            bends: Vec::new(),
        };
        if !make_room_for_number(&mut part, cut) {
            narrow.push(shaft);
        }
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
    for shaft in narrow {
        match number_beside_slot(stack, shaft, parts, cut) {
            Some(on) => numbers.beside_slot.push([shaft.part, on]),
            None => numbers.none.push(shaft.part),
        }
    }
    Ok(joints)
}

/// Engraves `shaft`'s number beside its slot on the first layer part it passes through whose
/// own number still fits; returns that part's id.
fn number_beside_slot(stack: &Stack, shaft: &super::Shaft, parts: &mut [Part], cut: &CutSettings) -> Option<u32> {
    for b in &shaft.bands {
        let on = stack.layers[b.layer].islands[b.island].part;
        let Some(at) = parts.iter().position(|p| p.id == on) else {
            continue;
        };
        let slot = shaft.start + shaft.direction * ((b.from + b.to) / 2.0);
        let Some(marks) = number_near(&parts[at], shaft.part, slot, cut.kerf()) else {
            continue;
        };
        if add_keeping_number(&mut parts[at], marks, cut) {
            return Some(on);
        }
    }
    None
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
