//! The score of a conversion: one number in [0, 1] ranking cutting plans as a maker would
//! (`--method all` picks the best by it, among the plans `verify` passes).
//!
//! ```text
//! total    = surface × (0.4 + 0.3·assembly + 0.2·quality + 0.1·effort)
//! assembly = connectivity × max(0, 1 − interference / 0.05) × (1 − glued parts / parts)
//! quality  = fidelity × slender × fit × details
//! effort   = 1 / (1 + work_minutes / 60)
//! ```
//!
//! - **surface**: share of the model's surface within half a sheet plus 0.5 mm of a part
//!   (the [`Analysis`]'s `surface_covered`): what the plan reproduces. Not the parts' volume
//!   inside the model, which a wall cut from a sheet thicker than the model's wall always
//!   loses: that is the quality's `fit`, a tenth of the total at most.
//! - **connectivity**: (parts − groups) / (parts − solids), groups counted through the joints
//!   whose parts really meet (the [`Analysis`]); 1 when there are no more parts than solids.
//! - **interference**: shared volume over the parts' volume (JimJoints' barbs left out); 5 %
//!   leaves nothing of the assembly term.
//! - **fidelity** ([`quality`]): how true the joints' angles are to the model's: per joint
//!   between plates, 1 / (1 + (Δ/2°)²) with Δ the difference between the angle of the two
//!   parts and the angle of the model faces they stand for; the mean over the joints.
//! - **slender**: how far the parts are from slivers: per part min(1, w / 2t) with w = 2·area /
//!   perimeter (the width of a strip), weighted by area; shafts left out.
//! - **fit**: 1 − ½·(1 − min(1, inside / 0.9)), inside the share of the parts' volume inside
//!   the model (issue 32): stock thicker than the model's walls stands out of it.
//! - **details**: 1 − ½·(1 − kept), kept the share of the model's sharp edges (faces turning
//!   by more than 30°) within the cover distance of a part's outline or a score mark (issue
//!   32: raised letters a blank part drops).
//! - **work_minutes**: report.json's `fabrication` total: laser time, sheets handled, parts
//!   taken out and joints closed ([`crate::fabrication::handwork`]), one estimate for both.
//!
//! The surface is a factor, not a term: a plan that reproduces nothing is worth nothing,
//! however cheap. Everything is measured on plan.json (outline, holes, transform) by the one
//! assembly analysis, deterministically: the same conversion always gets the same score.
//! docs/score.md explains the choices.

pub mod details;
pub mod quality;
#[cfg(test)]
mod tests;

use serde::Serialize;

use crate::assembly::{Analysis, analyse};
use crate::export::Bundle;
use crate::export::report::Report;
use crate::mesh::Mesh;
use crate::plan::Plan;
use crate::plates::Plates;

pub use quality::QualityScore;

/// Share of the total for the surface alone (of a plan that reproduces the whole surface).
pub const SURFACE_WEIGHT: f64 = 0.4;
/// Share of the total for holding together.
pub const ASSEMBLY_WEIGHT: f64 = 0.3;
/// Share of the total for the joints' quality.
pub const QUALITY_WEIGHT: f64 = 0.2;
/// Share of the total for little work.
pub const EFFORT_WEIGHT: f64 = 0.1;
/// Interference (shared volume over the parts' volume) that leaves nothing of the assembly.
pub const INTERFERENCE_LIMIT: f64 = 0.05;
/// Work that halves the effort score, minutes.
pub const EFFORT_HALF_MINUTES: f64 = 60.0;

/// How much of the model's surface the parts reproduce.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SurfaceScore {
    /// Share of the model's surface within `cover_distance` of a part.
    pub value: f64,
    /// The distance, mm: half the thickest part plus 0.5 mm.
    pub cover_distance: f64,
    /// For the plate method: the share of the surface the plates were detected on (the
    /// coverage report's figure), for comparison.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub plates_surface_share: Option<f64>,
}

/// Whether the assembly holds together.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct AssemblyScore {
    /// `connectivity × max(0, 1 − interference / 0.05) × (1 − glued parts / parts)`.
    pub value: f64,
    /// (parts − groups) / (parts − solids); 1 when every part is joined into one group per
    /// solid of the model, 0 without joints.
    pub connectivity: f64,
    /// Shared volume over the parts' volume (JimJoints' barbs left out).
    pub interference: f64,
    /// Number of joints in the plan.
    pub joints: usize,
    /// Labels of the joints whose parts do not meet (they hold nothing).
    pub joints_not_meeting: Vec<u32>,
    /// Groups of parts connected through joints that meet (a part alone is a group).
    pub groups: usize,
    /// Separate solids of the model: the fewest groups its parts can form.
    pub solids: usize,
    /// Parts only glue holds (plan.json's `glued`): the assembly keeps `1 − glued / parts`.
    pub glued_parts: usize,
}

/// How much work the plan is.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct EffortScore {
    /// `1 / (1 + work_minutes / 60)`.
    pub value: f64,
    /// Parts to cut and assemble.
    pub parts: usize,
    /// Sheets to cut.
    pub sheets: usize,
    /// Length of all cut paths, mm.
    pub cut_length: f64,
    /// Estimated laser time (cutting and engraving), minutes.
    pub laser_minutes: f64,
    /// Laser time plus handling parts and sheets, minutes.
    pub work_minutes: f64,
}

/// The score of one conversion, with its components.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Score {
    /// The score in [0, 1]: `surface × (0.4 + 0.3·assembly + 0.2·quality + 0.1·effort)`.
    pub total: f64,
    /// How much of the model's surface the parts reproduce.
    pub surface: SurfaceScore,
    /// Whether the parts hold together.
    pub assembly: AssemblyScore,
    /// Whether the joints are true to the model and the parts are no slivers.
    pub quality: QualityScore,
    /// How much work it is.
    pub effort: EffortScore,
}

/// Scores a finished conversion: its model's `mesh` against its plan, analysing the assembly;
/// `plates` (the plate method's) adds the coverage report's surface share.
pub fn score(mesh: &Mesh, bundle: &Bundle, plates: Option<&Plates>) -> Score {
    let analysis = analyse(&bundle.plan, Some(mesh));
    score_analysed(mesh, bundle, plates, &analysis)
}

/// [`score`] from an analysis of the plan against `mesh` already made (as `convert` makes it
/// once for the score, the report and `verify`).
pub fn score_analysed(mesh: &Mesh, bundle: &Bundle, plates: Option<&Plates>, analysis: &Analysis) -> Score {
    let mut s = evaluate(mesh, &bundle.plan, &bundle.report, analysis);
    s.surface.plates_surface_share = plates.map(|p| p.coverage.surface_share);
    s
}

/// The score of `plan` as a reproduction of `mesh`; effort figures come from `report`.
fn evaluate(mesh: &Mesh, plan: &Plan, report: &Report, analysis: &Analysis) -> Score {
    let surface = analysis.surface_covered.unwrap_or(0.0);
    let connectivity = analysis.connectivity();
    let interference = analysis.interference_share;
    let glued_parts = plan.glued_parts().len();
    let assembly = connectivity * (1.0 - interference / INTERFERENCE_LIMIT).max(0.0) * glue_free(glued_parts, plan);
    let quality = quality::measure(mesh, plan, analysis.cover_distance, analysis.volume_inside);
    let effort = effort(plan, report);
    let total = surface
        * (SURFACE_WEIGHT + ASSEMBLY_WEIGHT * assembly + QUALITY_WEIGHT * quality.value + EFFORT_WEIGHT * effort.value);
    Score {
        total: total.clamp(0.0, 1.0),
        surface: SurfaceScore {
            value: surface,
            cover_distance: analysis.cover_distance,
            plates_surface_share: None,
        },
        assembly: AssemblyScore {
            value: assembly,
            connectivity,
            interference,
            joints: plan.joints.len(),
            joints_not_meeting: analysis.joints_not_meeting.clone(),
            groups: analysis.group_count(),
            solids: analysis.allowed_groups(),
            glued_parts,
        },
        quality,
        effort,
    }
}

/// The share of `plan`'s parts that need no glue: a plan that glue must hold together ranks
/// below a glue-free one of the same surface, in proportion to the parts glue holds (issue 31).
/// Groups alone do not say it: glued parts of a separate solid of the model (the teapot's
/// spout foot) make no more groups than the model has solids.
fn glue_free(glued_parts: usize, plan: &Plan) -> f64 {
    let parts = plan.parts.len();
    if parts == 0 {
        1.0
    } else {
        1.0 - glued_parts.min(parts) as f64 / parts as f64
    }
}

/// The effort of cutting and assembling the plan.
fn effort(plan: &Plan, report: &Report) -> EffortScore {
    let parts = plan.parts.len();
    let sheets = plan.sheets.len();
    let laser_minutes = report.estimated_cutting_seconds.max(0.0) / 60.0;
    let work_minutes = report.fabrication.total_seconds.max(0.0) / 60.0;
    EffortScore {
        value: 1.0 / (1.0 + work_minutes / EFFORT_HALF_MINUTES),
        parts,
        sheets,
        cut_length: report.cut_length,
        laser_minutes,
        work_minutes,
    }
}
