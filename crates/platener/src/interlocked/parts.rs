//! The pieces as parts and joints for the cutting plan.
//!
//! Every piece is a part of kind `plate` placed by its slice's slab frame (x across, y up, z
//! through the sheet). It carries its name (A3) after an arrow pointing up, so it is stood
//! the right way up, and beside each slot the name of the piece that slot takes, so the
//! maker finds each crossing without the plan. The part number comes first: marks give way to
//! it, and a piece too thin for it gets a tab (as a stacked layer does). Each crossing is one joint of kind `halved`
//! between its A piece and its B piece (in that order), at 90°.

use std::collections::BTreeMap;

use glam::DVec2;
use platener_geom::{GridError, Polygon, boolean, offset};
use serde_json::json;

use super::{Interlocked, Piece};
use crate::plan::{CutSettings, Joint, JointKind, Mark, Method, Part, PartKind, PlanInput, SettingValue, SourceInfo};
use crate::read::Model;
use crate::settings::Settings;
use crate::stacked::{number_fits, tag, text_near, with_tab};

/// Room kept around a name or slot label, mm.
const CLEARANCE: f64 = 1.0;
/// A tab on a piece's free edge reaches this far into it, with its clearance (mm): the
/// columns that keep tabs off stop this short of that edge.
const TAB_CLEAR: f64 = 2.0;
/// How far from the slot's end its label is wanted, mm.
const LABEL_OFFSET: f64 = 6.0;

/// The parts, joints and settings of `interlocked`, converted from `model`.
pub fn plan_input(i: &Interlocked, model: &Model, settings: &Settings) -> Result<PlanInput, GridError> {
    let mut parts = Vec::with_capacity(i.pieces.len());
    for piece in &i.pieces {
        let (tag, labels) = marks(i, piece)?;
        let mut part = Part {
            id: piece.part,
            kind: PartKind::Plate,
            thickness: i.thickness,
            polygon: piece.polygon.clone(),
            frame: i.families[piece.family].slab(piece.slice, i.thickness),
            marks: Vec::new(),
            edge_labels: Vec::new(),
            merged: Vec::new(),
            segments: Vec::new(),
            bends: Vec::new(),
        };
        number(&mut part, tag, labels, &columns(i, piece), &settings.cut)?;
        parts.push(part);
    }
    let joints = i
        .crossings
        .iter()
        .enumerate()
        .map(|(n, c)| Joint {
            parts: c.parts,
            kind: JointKind::Halved,
            angle_deg: 90.0,
            label: n as u32 + 1,
        })
        .collect();
    let mut input = PlanInput::new(SourceInfo::from(model), Method::Interlocked, parts, joints);
    input.settings = settings.cut.clone();
    input.method_settings = method_settings(i);
    input.method_report = Some(json!({
        "order": &i.order,
        "lower": [Interlocked::LOWER.x, Interlocked::LOWER.y, Interlocked::LOWER.z],
        "left_out": &i.left_out,
    }));
    Ok(input)
}

/// Gives `part` its marks so that its number still fits (the `labels` step engraves it): the
/// name `tag` and the slot `labels` when there is room for all, else the tag alone, else
/// neither; a piece too thin for its number gets a tab on its outline for it, clear of every
/// crossing `column` (a tab there would meet the other slice), as stacked layers do.
fn number(
    part: &mut Part,
    tag: Vec<Mark>,
    labels: Vec<Mark>,
    columns: &[Polygon],
    cut: &CutSettings,
) -> Result<(), GridError> {
    let all: Vec<Mark> = tag.iter().chain(&labels).cloned().collect();
    for marks in [all.clone(), tag.clone(), Vec::new()] {
        part.marks = marks;
        if number_fits(part, cut) {
            return Ok(());
        }
    }
    let others: Vec<&Polygon> = columns.iter().collect();
    if let Some(with) = with_tab(&part.polygon, &[], &others, part.id, cut.kerf())? {
        let plain = std::mem::replace(&mut part.polygon, with);
        for marks in [tag, Vec::new()] {
            part.marks = marks;
            if number_fits(part, cut) {
                return Ok(());
            }
        }
        part.polygon = plain;
    }
    part.marks = all;
    Ok(())
}

/// Where a tab on `piece` would meet a slice of the other family: the crossing columns
/// through its slice, as strips a sheet wide in its slice's 2D frame, except above an A
/// piece's top and below a B piece's bottom. There the other slice has no material in the
/// column (B keeps its column below the split, A above it), so a tab on an A piece's top edge
/// or a B piece's bottom edge is clear of every crossing.
fn columns(i: &Interlocked, piece: &Piece) -> Vec<Polygon> {
    let (lo, hi) = piece.polygon.bounds();
    let (f, other) = (piece.family, 1 - piece.family);
    let half = i.thickness / 2.0;
    let (bottom, top) = if f == 0 {
        (lo.y - 10.0, hi.y - TAB_CLEAR)
    } else {
        (lo.y + TAB_CLEAR, hi.y + 10.0)
    };
    (0..i.families[other].count())
        .map(|k| {
            let slices = if f == 0 { [piece.slice, k] } else { [k, piece.slice] };
            let x = super::cross::column(&i.families, slices[0], slices[1])[f];
            Polygon::new(platener_geom::polygon::rect(x - half, bottom, x + half, top))
        })
        .collect()
}

/// The piece's name with an arrow pointing up, and beside each slot its partner's name.
fn marks(i: &Interlocked, piece: &Piece) -> Result<(Vec<Mark>, Vec<Mark>), GridError> {
    let (lo, hi) = piece.polygon.bounds();
    let tag = tag(&piece.polygon, &piece.name, &[DVec2::X], DVec2::Y, (lo + hi) / 2.0)?.unwrap_or_default();
    let mut marks = Vec::new();
    let mut free = vec![piece.polygon.clone()];
    if let Some(taken) = box_of(&tag) {
        free = boolean::difference(&free, &[taken])?;
    }
    let f = piece.family;
    for c in i.crossings.iter().filter(|c| c.parts[f] == piece.part) {
        let Some(partner) = i.pieces.iter().find(|p| p.part == c.parts[1 - f]) else {
            continue;
        };
        // A's slot opens downward and ends at the split; B's opens upward from it.
        let beside = if f == 0 { LABEL_OFFSET } else { -LABEL_OFFSET };
        let reference = DVec2::new(c.at[f], c.split + beside);
        if let Some((label, taken)) = text_near(&free, &partner.name, reference)? {
            marks.extend(label);
            free = boolean::difference(&free, &[taken])?;
        }
    }
    Ok((tag, marks))
}

/// The box around `marks`, grown by [`CLEARANCE`]; `None` without marks.
fn box_of(marks: &[Mark]) -> Option<Polygon> {
    let points = marks.iter().flat_map(|m| m.path.iter().copied());
    let (lo, hi) = platener_geom::polygon::bounds_of(points);
    (lo.x <= hi.x).then(|| {
        let r = platener_geom::polygon::rect(lo.x, lo.y, hi.x, hi.y);
        let grown = offset::offset(&[Polygon::new(r.clone())], CLEARANCE).ok();
        grown
            .and_then(|g| g.into_iter().next())
            .unwrap_or_else(|| Polygon::new(r))
    })
}

/// The method's settings as the plan records them.
fn method_settings(i: &Interlocked) -> BTreeMap<String, SettingValue> {
    let mut s = BTreeMap::new();
    s.insert("slice_spacing".to_string(), SettingValue::Number(i.spacing));
    s.insert(
        "slices".to_string(),
        SettingValue::Numbers(i.families.iter().map(|f| f.count() as f64).collect()),
    );
    let normals = i
        .families
        .iter()
        .flat_map(|f| [f.plan.frame.n.x, f.plan.frame.n.y, f.plan.frame.n.z]);
    s.insert("normals".to_string(), SettingValue::Numbers(normals.collect()));
    s.insert("weld".to_string(), SettingValue::Number(0.0));
    s
}
