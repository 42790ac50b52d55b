//! Step `joints` (the thesis' PlateGraph and JointComputation): where plates meet, and the
//! fingers, tabs and slots that make them hold without glue.
//!
//! One volumetric scheme covers every case, at any angle:
//! 1. [`connect`]: each plate grows across every neighbour's slab (by the width of the
//!    neighbour's slab seen in its plane); where two grown plates share volume they are
//!    connected. That shared prism is the joint region (the thesis' parallelogram, so finger
//!    length follows the enclosed angle by construction); disjoint stretches are separate
//!    connections. A plate whose original outline already covers the region passes through.
//!    Only where both plates run along the line is it a joint ([`along`]), and not across a
//!    chamfer plate between them ([`bridge`]).
//! 2. [`fingers`]: the region is cut into segments along the joint line; each segment belongs to
//!    one plate and is removed from the other, so the two sides are exact negatives. Corners
//!    (neither passes through): an odd number of fingers, the ends to the higher-ranked plate, so
//!    every corner volume where three plates meet has exactly one owner. T-junctions (one passes
//!    through): tabs on the ending plate, slots (holes) in the through plate, whose ends it keeps.
//!    Crossings (both pass through): a halved joint, one slot from each side to half depth.
//! 3. [`junction`]: three or more plates on one line (a "Y") reach past it only as far as the
//!    model goes and share one row of fingers in which they take turns.

mod along;
#[cfg(test)]
mod assembly_tests;
mod bent;
mod bridge;
mod cap;
mod claims;
mod connect;
mod distinct;
#[cfg(test)]
mod distinct_tests;
mod fingers;
mod junction;
mod ribs;
#[cfg(test)]
mod ribs_tests;
#[cfg(test)]
mod tests;

use glam::{DVec2, DVec3};
use platener_geom::{GridError, Polygon};
use serde::Serialize;

use crate::context::{StepContext, WarningKind};
use crate::error::{Error, ModelProblem, Result};
use crate::plates::{Plate, Plates};
use crate::settings::Settings;
// The joints' settings are kernel data, below every step (docs/architecture.md).
pub use crate::settings::{JointSettings, JointStyle};

/// How two plates meet.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum ConnectionKind {
    /// Both plates end at the joint: finger joint.
    Corner,
    /// One plate ends against the other's face: tabs and slots.
    Tee,
    /// Both pass through each other: halved (cross-lap) joint.
    Cross,
}

/// A connection between two plates (an edge of the plate graph).
#[derive(Debug, Clone, Serialize)]
pub struct Connection {
    /// The plates (indices into the plates snapshot), lower first.
    pub plates: [u32; 2],
    /// How they meet.
    pub kind: ConnectionKind,
    /// The shape of its fingers or tabs (chosen per connection, recorded here).
    pub style: JointStyle,
    /// The angle enclosed by the plates, degrees (90 for a box corner).
    pub angle_deg: f64,
    /// Start and end of the joint along the line where the plates meet, in the model.
    pub line: [DVec3; 2],
    /// Number of segments (fingers of both plates; 2 for a halved joint).
    pub segments: usize,
    /// The connection's number, engraved next to it on both plates (1-based).
    pub label: u32,
}

/// The snapshot of step `joints`: the plates' outlines with their joints, and the graph.
#[derive(Debug, Clone, Serialize)]
pub struct Joints {
    /// Each plate's outline with fingers, tabs and slots (one polygon per plate).
    pub outlines: Vec<Polygon>,
    /// The connections.
    pub connections: Vec<Connection>,
    /// Per plate: the jointed edges (segments in the plate's frame) and their labels.
    pub edges: Vec<Vec<(u32, [DVec2; 2])>>,
    /// Extra parts: the keys of dovetail joints.
    pub keys: Vec<Key>,
    /// Per labelled connection, where its joint lies on each plate and who kept the ends: a
    /// record for the debug view only (the plan and its report do not read it).
    pub regions: Vec<JointRegion>,
    /// The bent parts of the `bends` step that hold together once jointed (indices into its
    /// parts): the `parts` step merges these; the plates of the others are jointed plates.
    pub held_bends: Vec<usize>,
    /// The bent parts that would not hold together, and why.
    pub refused_bends: Vec<crate::bends::Refusal>,
}

/// Where one connection's fingers, tabs or slots go on its two plates, and which plate
/// claimed the material at its ends (the corner volume both plates reach into).
#[derive(Debug, Clone, Serialize)]
pub struct JointRegion {
    /// The connection's label.
    pub label: u32,
    /// The plates, as in [`Connection::plates`].
    pub plates: [u32; 2],
    /// The joint region in each plate's frame (the same order as `plates`).
    pub polygons: [Polygon; 2],
    /// The plate that owns the joint's end segments (a corner's outer fingers, the through
    /// plate of a T, the plate that keeps the whole region at a butt joint).
    pub claimed_by: u32,
}

/// A key of a dovetail joint: a small part cut from the dovetailed plate's sheet that fills
/// the notch beside a dovetail. It lies in that plate's layer, so it shares its frame.
#[derive(Debug, Clone, Serialize)]
pub struct Key {
    /// The dovetailed plate (its frame and thickness place the key).
    pub plate: u32,
    /// The plate whose notch the key fills.
    pub notched: u32,
    /// The key's outline, in the dovetailed plate's frame.
    pub outline: Polygon,
    /// The connection's label.
    pub label: u32,
}

impl Joints {
    /// The parts as solids: each plate's outline with its joints, then each dovetail key, as
    /// slabs in the model (for checks such as interference and volume).
    pub fn parts(&self, plates: &[Plate]) -> Vec<platener_geom::slab::Slab> {
        let outlines = plates.iter().zip(&self.outlines).map(|(p, o)| p.slab_of(o.clone()));
        let keys = self
            .keys
            .iter()
            .map(|k| plates[k.plate as usize].slab_of(k.outline.clone()));
        outlines.chain(keys).collect()
    }
}

/// Computes the joints of `plates` (straight fingers where the settings name no style), with
/// what the user should know (a joint that had to adapt, a plate that would fall apart…).
pub fn compute(plates: &[Plate], settings: &JointSettings) -> Result<(Joints, Vec<String>), GridError> {
    compute_except(plates, settings, &std::collections::BTreeSet::new())
}

/// [`compute`], leaving the plate pairs in `unjointed` (lower index first) without a joint:
/// the bends of bent parts, which are one sheet there.
pub fn compute_except(
    plates: &[Plate],
    settings: &JointSettings,
    unjointed: &std::collections::BTreeSet<(u32, u32)>,
) -> Result<(Joints, Vec<String>), GridError> {
    let mut regions = connect::find(plates, settings)?;
    regions.retain(|r| !unjointed.contains(&(r.a.min(r.b) as u32, r.a.max(r.b) as u32)));
    let (mut joints, mut warnings) =
        fingers::apply(plates, regions, settings, settings.style.unwrap_or(JointStyle::Finger))?;
    warnings.extend(drop_unmet(plates, &mut joints));
    Ok((joints, warnings))
}

/// Whether plates `a` and `b`, cut as `joints` has them, meet as the assembly analysis
/// (verify) counts it: touching along a line is not holding.
fn meet(plates: &[Plate], joints: &Joints, a: usize, b: usize) -> bool {
    crate::assembly::slabs_meet(
        &plates[a].slab_of(joints.outlines[a].clone()),
        &plates[b].slab_of(joints.outlines[b].clone()),
    )
}

/// Drops the connections whose plates do not meet once cut (shortened fingers or a butt at an
/// obtuse corner can leave the two apart): a joint that holds nothing is not listed as one,
/// so the plan's groups are the ones it really has. The rest are numbered again from 1.
fn drop_unmet(plates: &[Plate], joints: &mut Joints) -> Vec<String> {
    let mut warnings = Vec::new();
    let mut dropped = std::collections::BTreeSet::new();
    for c in &joints.connections {
        let [a, b] = c.plates.map(|p| p as usize);
        if !meet(plates, joints, a, b) {
            warnings.push(format!(
                "connection {}: plates {} and {} do not meet once cut; it is left out (they need glue or another joint)",
                c.label,
                a + 1,
                b + 1
            ));
            dropped.insert(c.label);
        }
    }
    if dropped.is_empty() {
        return warnings;
    }
    joints.connections.retain(|c| !dropped.contains(&c.label));
    joints.keys.retain(|k| !dropped.contains(&k.label));
    joints.regions.retain(|r| !dropped.contains(&r.label));
    for e in &mut joints.edges {
        e.retain(|(label, _)| !dropped.contains(label));
    }
    let renumber = |label: u32| label - dropped.range(..label).count() as u32;
    for c in &mut joints.connections {
        c.label = renumber(c.label);
    }
    for k in &mut joints.keys {
        k.label = renumber(k.label);
    }
    for r in &mut joints.regions {
        r.label = renumber(r.label);
    }
    for e in &mut joints.edges {
        for (label, _) in e.iter_mut() {
            *label = renumber(*label);
        }
    }
    warnings
}

/// The joint settings of a conversion: the user's, with the style that holds in the material
/// where they chose none.
pub(crate) fn settings_for(settings: &Settings) -> JointSettings {
    let chosen = &settings.joints;
    JointSettings {
        style: Some(chosen.style.unwrap_or(JointStyle::for_material(settings.cut.material))),
        crush_ribs: settings.cut.crush_ribs,
        ..chosen.clone()
    }
}

/// Step `joints`: the plate graph and the joints along it, in the style the user chose or
/// the one that holds in the material; bends of bent parts get none. It decides which of
/// the bent parts the `bends` step proposed hold together once their plates carry their
/// joints; the plates of any that do not are joined as plates.
pub fn run(
    plates: &Plates,
    bends: Option<&crate::bends::Bends>,
    settings: &Settings,
    cx: &mut StepContext<'_>,
) -> Result<Joints> {
    cx.check_cancel()?;
    let joint_settings = settings_for(settings);
    let off_grid = |e| Error::model(cx.model(), ModelProblem::OffGrid(e));
    let unjointed = bends.map(crate::bends::Bends::unjointed).unwrap_or_default();
    let (mut joints, mut warnings) = compute_except(&plates.plates, &joint_settings, &unjointed).map_err(off_grid)?;
    let (mut held, mut refused) = (Vec::new(), Vec::new());
    if let Some(b) = bends
        && let Some(style) = b.style
    {
        for (k, part) in b.parts.iter().enumerate() {
            if bent::holds_together(part, plates, &joints, style) {
                held.push(k);
            } else {
                refused.push(bent::refusal(part));
            }
        }
        let kept = b.keeping(&held);
        if !refused.is_empty() {
            (joints, warnings) =
                compute_except(&plates.plates, &joint_settings, &kept.unjointed()).map_err(off_grid)?;
        }
        // What was bent is said once it is decided (the refused parts are in the snapshot).
        warnings.extend(kept.notes(plates));
    }
    for w in warnings {
        cx.warn(WarningKind::Joints, w);
    }
    joints.held_bends = held;
    joints.refused_bends = refused;
    Ok(joints)
}
