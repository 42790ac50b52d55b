//! The pieces as parts and joints for the cutting plan.
//!
//! Every piece is a part of kind `plate` placed by its slice's slab frame (x across, y up, z
//! through the sheet). It carries its name (A3) after an arrow pointing up, so it is stood
//! the right way up, and beside each slot the name of the piece that slot takes, so the
//! maker finds each crossing without the plan. The part number comes first: marks give way to
//! it, a piece too thin for it gets a tab (as a stacked layer does), and one with room for
//! neither has `#id` engraved beside its slot on a piece it crosses. Each crossing is one joint of kind `halved`
//! between its A piece and its B piece (in that order), at 90°.

use std::collections::BTreeMap;

use glam::DVec2;
use platener_geom::{GridError, Polygon, boolean, offset};
use serde_json::json;

use super::column_extent;
use super::cross::{column, shared};
use super::held::GRIP;
use super::{Interlocked, Piece};
use crate::plan::{CutSettings, Joint, JointKind, Mark, Method, Part, PartKind, PlanInput, SettingValue, SourceInfo};
use crate::read::Model;
use crate::settings::Settings;
use crate::stacked::{Numbers, add_keeping_number, number_fits, tag, text_near, with_tab_where};

/// Room kept around a name or slot label, mm.
const CLEARANCE: f64 = 1.0;
/// How far from the slot's end its label is wanted, mm.
const LABEL_OFFSET: f64 = 6.0;

/// The parts, joints and settings of `interlocked`, converted from `model`, and the pieces left
/// out because their number fits nowhere (not on them, on a tab or on a piece they touch: a
/// part nobody can find is not cut).
pub fn plan_input(i: &Interlocked, model: &Model, settings: &Settings) -> Result<(PlanInput, Vec<u32>), GridError> {
    let mut parts = Vec::with_capacity(i.pieces.len());
    let mut unnumbered = Vec::new();
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
        if !number(&mut part, tag, labels, i, piece, &settings.cut)? {
            unnumbered.push(piece);
        }
        parts.push(part);
    }
    let mut numbers = Numbers::default();
    for piece in unnumbered {
        match on_partner(i, piece, &mut parts, &settings.cut)? {
            Some(on) => numbers.on_neighbour.push([piece.part, on]),
            None => numbers.none.push(piece.part),
        }
    }
    let unnumbered = std::mem::take(&mut numbers.none);
    parts.retain(|p| !unnumbered.contains(&p.id));
    let joints = i
        .crossings
        .iter()
        .filter(|c| !c.parts.iter().any(|p| unnumbered.contains(p)))
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
        "numbers": &numbers,
        "unnumbered_left_out": &unnumbered,
    }));
    Ok((input, unnumbered))
}

/// Gives `part` (of `piece`) its marks so that its number still fits (the `labels` step
/// engraves it): the name `tag` and the slot `labels` when there is room for all, else the tag
/// alone, else neither; a piece too thin for its number gets a tab on its outline for it, as
/// stacked layers do, clear of its slice's other pieces and of every slice of the other family.
fn number(
    part: &mut Part,
    tag: Vec<Mark>,
    labels: Vec<Mark>,
    i: &Interlocked,
    piece: &Piece,
    cut: &CutSettings,
) -> Result<bool, GridError> {
    let all: Vec<Mark> = tag.iter().chain(&labels).cloned().collect();
    for marks in [all.clone(), tag.clone(), Vec::new()] {
        part.marks = marks;
        if number_fits(part, cut) {
            return Ok(true);
        }
    }
    let siblings: Vec<&Polygon> = i
        .pieces
        .iter()
        .filter(|p| (p.family, p.slice) == (piece.family, piece.slice) && p.part != piece.part)
        .map(|p| &p.polygon)
        .collect();
    let clear = |tab: &[Polygon]| clear_of_crossings(i, piece, tab);
    if let Some(with) = with_tab_where(&part.polygon, &[], &siblings, part.id, cut.kerf(), clear)? {
        let plain = std::mem::replace(&mut part.polygon, with);
        for marks in [tag, Vec::new()] {
            part.marks = marks;
            if number_fits(part, cut) {
                return Ok(true);
            }
        }
        part.polygon = plain;
    }
    part.marks = all;
    Ok(false)
}

/// The last resort for a piece with room neither for its number nor for a tab: `#id` engraved
/// on a piece it crosses, beside the slot that takes it, or else on another piece of its own
/// slice, where that piece's own number still fits; returns that piece's part id.
fn on_partner(i: &Interlocked, piece: &Piece, parts: &mut [Part], cut: &CutSettings) -> Result<Option<u32>, GridError> {
    let f = piece.family;
    let beside = if f == 0 { -LABEL_OFFSET } else { LABEL_OFFSET };
    let partners = i
        .crossings
        .iter()
        .filter(|c| c.parts[f] == piece.part)
        .map(|c| (c.parts[1 - f], Some(DVec2::new(c.at[1 - f], c.split + beside))));
    let siblings = i
        .pieces
        .iter()
        .filter(|p| (p.family, p.slice) == (f, piece.slice) && p.part != piece.part)
        .map(|p| (p.part, None));
    for (on, near) in partners.chain(siblings).collect::<Vec<_>>() {
        let Some(at) = parts.iter().position(|p| p.id == on) else {
            continue;
        };
        let taken: Vec<Polygon> = parts[at]
            .marks
            .iter()
            .filter_map(|m| box_of(std::slice::from_ref(m)))
            .collect();
        let free = boolean::difference(std::slice::from_ref(&parts[at].polygon), &taken)?;
        let (lo, hi) = parts[at].polygon.bounds();
        let reference = near.unwrap_or((lo + hi) / 2.0);
        let Some((label, _)) = text_near(&free, &format!("#{}", piece.part), reference)? else {
            continue;
        };
        if add_keeping_number(&mut parts[at], label, cut) {
            return Ok(Some(on));
        }
    }
    Ok(None)
}

/// Whether material `added` to `piece` (a tab, in its slice's 2D frame) keeps clear of every
/// slice of the other family: in each crossing column through it, the added material and the
/// other slice's pieces share no height.
fn clear_of_crossings(i: &Interlocked, piece: &Piece, added: &[Polygon]) -> Result<bool, GridError> {
    let (f, other) = (piece.family, 1 - piece.family);
    let half = i.thickness / 2.0;
    for k in 0..i.families[other].count() {
        let slices = if f == 0 { [piece.slice, k] } else { [k, piece.slice] };
        let at = column(&i.families, slices[0], slices[1]);
        let mine = column_extent(added, at[f], half + GRIP)?;
        if mine.is_empty() {
            continue;
        }
        let theirs: Vec<Polygon> = i
            .pieces
            .iter()
            .filter(|p| p.family == other && p.slice == k)
            .map(|p| p.polygon.clone())
            .collect();
        if shared(&mine, &column_extent(&theirs, at[other], half + GRIP)?).is_some() {
            return Ok(false);
        }
    }
    Ok(true)
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
