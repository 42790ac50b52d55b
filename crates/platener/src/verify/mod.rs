//! `platener verify`: rebuilds the assembly from plan.json and checks it before anyone cuts.
//!
//! Each part is its outline extruded by its thickness and moved by its transform. Measured by
//! deterministic sampling (see [`sample`]; the accuracy follows the sampling step):
//! - pairwise interference volume (plates must not intersect; fingers must be exact complements),
//! - with the model: share of the model's surface within half a sheet plus 0.5 mm of a part
//!   ([`cover_distance`]), share of the parts'
//!   volume inside the model,
//! - groups of parts the joints hold together, against the model's separate solids,
//! - joints whose two parts do not actually meet.
//!
//! It fails when interference (other than the intended overlap of JimJoints' barbs) exceeds
//! 0.5 % of the parts' volume, when the parts fall apart into more groups than the model has
//! solids, when a joint's parts do not meet, or (with the model) when the parts cover less
//! than [`MIN_COVERAGE`] of the model's surface.

mod sample;
#[cfg(test)]
mod tests;

use serde::Serialize;

use crate::assembly::Solid;

use crate::mesh::Mesh;
use crate::plan::Plan;

/// Interference above this share of the parts' volume fails verification.
pub const MAX_INTERFERENCE: f64 = 0.005;
/// Model surface within half the thickest part's thickness plus this (mm) of a part counts as
/// covered: a wall cut from a sheet sits at most half a sheet from the face it stands for, and
/// the weld and the kerf move faces by less than half a millimetre.
pub const COVER_SLACK: f64 = 0.5;
/// A plan whose parts cover less than this share of the model's surface fails: it does not
/// reproduce the model (`--min-coverage`).
pub const MIN_COVERAGE: f64 = 0.8;

/// The distance within which a part covers the model's surface for `plan`.
pub fn cover_distance(plan: &Plan) -> f64 {
    plan.parts.iter().map(|p| p.thickness).fold(0.0, f64::max) / 2.0 + COVER_SLACK
}

/// Two parts that share volume.
#[derive(Debug, Clone, Serialize)]
pub struct Interference {
    /// The parts' ids.
    pub parts: [u32; 2],
    /// Shared volume, mm³.
    pub volume: f64,
}

/// What `platener verify` reports.
#[derive(Debug, Clone, Serialize)]
pub struct Verification {
    /// Parts rebuilt.
    pub parts: usize,
    /// Their total volume, mm³.
    pub parts_volume: f64,
    /// Pairs of parts that share volume, largest first.
    pub interference: Vec<Interference>,
    /// Total shared volume over the parts' volume.
    pub interference_share: f64,
    /// Groups of parts held together by joints.
    pub groups: usize,
    /// The model's separate solids, when the model was given.
    pub model_solids: Option<usize>,
    /// The distance within which a part covers the model's surface, mm.
    pub cover_distance: f64,
    /// Share of the model's surface within `cover_distance` of a part, when the model was given.
    pub surface_covered: Option<f64>,
    /// Share of the parts' volume inside the model, when the model was given.
    pub volume_inside: Option<f64>,
    /// Labels of joints whose parts do not meet.
    pub joints_not_meeting: Vec<u32>,
    /// The sampling step used, mm.
    pub step: f64,
    /// Why verification failed (empty when it passed).
    pub problems: Vec<String>,
    /// What the user should know but does not fail the plan (a model that does not look like
    /// the plan's source).
    pub warnings: Vec<String>,
}

impl Verification {
    /// Whether every check passed.
    pub fn passed(&self) -> bool {
        self.problems.is_empty()
    }
}

/// Why a file is not a cutting plan platener can verify (the file's fault).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum PlanFileError {
    /// Not a ZIP archive.
    #[error("not a ZIP: {0}")]
    NotZip(String),
    /// A ZIP without plan.json.
    #[error("the ZIP holds no plan.json: is it a platener cutting plan?")]
    NoPlan,
    /// plan.json is not UTF-8 or cannot be read.
    #[error("plan.json cannot be read: {0}")]
    Unreadable(String),
    /// plan.json does not parse as a plan.
    #[error("plan.json is not a platener plan: {0}")]
    NotAPlan(String),
}

/// Reads plan.json out of a conversion's ZIP.
pub fn plan_from_zip(bytes: &[u8]) -> Result<Plan, PlanFileError> {
    use std::io::Read;
    let mut zip =
        zip::ZipArchive::new(std::io::Cursor::new(bytes)).map_err(|e| PlanFileError::NotZip(e.to_string()))?;
    let mut text = String::new();
    zip.by_name("plan.json")
        .map_err(|_| PlanFileError::NoPlan)?
        .read_to_string(&mut text)
        .map_err(|e| PlanFileError::Unreadable(e.to_string()))?;
    serde_json::from_str(&text).map_err(|e| PlanFileError::NotAPlan(e.to_string()))
}

/// Verifies a plan, optionally against the model it was made from, with the default
/// [`MIN_COVERAGE`].
pub fn verify(plan: &Plan, model: Option<&Mesh>) -> Verification {
    verify_with(plan, model, MIN_COVERAGE)
}

/// Verifies a plan; against a model, it fails when the parts cover less than `min_coverage`
/// of the model's surface.
pub fn verify_with(plan: &Plan, model: Option<&Mesh>, min_coverage: f64) -> Verification {
    let solids: Vec<Solid> = plan.parts.iter().map(Solid::from_part).collect();
    let step = sample::step_for(&solids);
    let parts_volume: f64 = solids.iter().map(|s| s.volume).sum();
    let mut interference = sample::interference(&solids, step);
    interference.sort_by(|a, b| b.volume.total_cmp(&a.volume));
    // JimJoints overlap on purpose: their barbs squeeze through and snap behind the partner.
    let snapping = |pair: &[u32; 2]| {
        plan.joints
            .iter()
            .any(|j| j.kind == crate::plan::JointKind::Jim && (j.parts == *pair || j.parts == [pair[1], pair[0]]))
    };
    let shared: f64 = interference
        .iter()
        .filter(|i| !snapping(&i.parts))
        .map(|i| i.volume)
        .sum();
    let interference_share = if parts_volume > 0.0 {
        (shared / parts_volume).max(0.0) + 0.0 /* −0 → +0 */
    } else {
        0.0
    };
    let (groups, joints_not_meeting) = held_together(plan, &solids, step);
    let (model_solids, surface_covered, volume_inside) = match model {
        Some(m) => (
            Some(m.health.solids.max(1)),
            Some(sample::surface_covered(m, &solids, cover_distance(plan))),
            Some(sample::volume_inside(m, &solids, step.max(0.5))),
        ),
        None => (None, None, None),
    };
    let mut problems = Vec::new();
    if interference_share > MAX_INTERFERENCE {
        problems.push(format!(
            "parts intersect: {:.2} % of their volume is claimed twice (at most {:.1} %)",
            100.0 * interference_share,
            100.0 * MAX_INTERFERENCE
        ));
    }
    let allowed = model_solids.unwrap_or(1);
    if groups > allowed {
        problems.push(format!(
            "the parts fall apart into {groups} groups; the model has {allowed}"
        ));
    }
    if let Some(covered) = surface_covered.filter(|c| *c < min_coverage) {
        problems.push(format!(
            "the parts reproduce only {:.1} % of the model's surface (within {:.1} mm of a part); \
             at least {:.0} % is required (--min-coverage)",
            100.0 * covered,
            cover_distance(plan),
            100.0 * min_coverage
        ));
    }
    if !joints_not_meeting.is_empty() {
        problems.push(format!("joints whose parts do not meet: {joints_not_meeting:?}"));
    }
    Verification {
        parts: solids.len(),
        parts_volume,
        interference,
        interference_share,
        groups,
        model_solids,
        surface_covered,
        volume_inside,
        joints_not_meeting,
        step,
        cover_distance: cover_distance(plan),
        problems,
        warnings: Vec::new(),
    }
}

/// The groups of parts the joints hold together, and the joints whose parts do not meet.
fn held_together(plan: &Plan, solids: &[Solid], step: f64) -> (usize, Vec<u32>) {
    let index = |id: u32| solids.iter().position(|s| s.id == id);
    let mut group = crate::assembly::UnionFind::new(solids.len());
    let mut joints_not_meeting = Vec::new();
    for j in &plan.joints {
        let (Some(a), Some(b)) = (index(j.parts[0]), index(j.parts[1])) else {
            joints_not_meeting.push(j.label);
            continue;
        };
        // Sampled inside each part in turn: a slot opening onto one part's edge may only be
        // seen from the other.
        if sample::meet(&solids[a], &solids[b], step) || sample::meet(&solids[b], &solids[a], step) {
            group.join(a, b);
        } else {
            joints_not_meeting.push(j.label);
        }
    }
    (group.count(), joints_not_meeting)
}

/// Why `model` does not look like the model `plan` was made from (its bounding box differs by
/// more than 1 % of the plan's, or 0.01 mm), naming the units and scale the plan was made
/// with; `None` when it matches.
pub fn source_mismatch(plan: &Plan, model: &crate::read::Model) -> Option<String> {
    let (lo, hi) = (
        glam::DVec3::from(plan.source.bbox_min),
        glam::DVec3::from(plan.source.bbox_max),
    );
    let tolerance = 0.01 * (hi - lo).length() + 0.01;
    let off = (model.bounds.min - lo)
        .abs()
        .max_element()
        .max((model.bounds.max - hi).abs().max_element());
    (off > tolerance).then(|| {
        let size = |d: glam::DVec3| format!("{:.1} × {:.1} × {:.1} mm", d.x, d.y, d.z);
        format!(
            "the model is {} but the plan was made from one of {} (units {}, scale {}): \
             is it the same model, read with the same --units and --scale?",
            size(model.bounds.size()),
            size(hi - lo),
            format!("{:?}", plan.source.units).to_lowercase(),
            plan.source.scale
        )
    })
}
