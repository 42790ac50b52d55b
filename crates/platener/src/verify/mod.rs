//! `platener verify`: rebuilds the assembly from plan.json and checks it before anyone cuts.
//!
//! Each part is its outline extruded by its thickness and moved by its transform; a bent
//! part is the union of its segments and its bend zones' slices ([`crate::plan::bent`]). The
//! measuring is the one [`analyse`] of the assembly that `convert` and the score read too
//! (deterministic sampling; the accuracy follows the sampling step). A plan fails
//! ([`Check`]) when
//! - parts share more than [`MAX_INTERFERENCE`] of their volume (JimJoints' barbs, which
//!   overlap on purpose, left out),
//! - the joints that meet leave more groups than the model has solids,
//! - a joint's parts do not meet,
//! - (with the model) the parts cover less than [`MIN_COVERAGE`] of the model's surface
//!   (not for interlocked slices, which stand for the model's shape a spacing apart by design:
//!   their coverage is measured and scored, not required),
//! - an outline is invalid ([`outline_findings`]),
//! - a part lies outside its sheet or is larger than it,
//! - a bent part's segments and bends disagree ([`crate::plan::bent`]).
//!
//! Each failure names the parts it concerns. Reported, never failed: [`mismatched_edges`],
//! the pairs of finger-joint edges that fit where they do not belong (a maker could build
//! the plan wrongly; not a flaw of the parts, and a shelf of identical shelves has such pairs
//! by design, counted apart as interchangeable). [`check`] turns an analysis already made (as
//! `convert` makes it for every plan) into a verdict without measuring again.

mod edge_pattern;
#[cfg(test)]
mod edge_tests;
mod mismatched_edges;
mod outline;
mod sheet;
#[cfg(test)]
mod tests;

use serde::Serialize;

use crate::assembly::{Analysis, analyse};
pub use crate::assembly::{COVER_SLACK, Interference, cover_distance};
use crate::mesh::Mesh;
use crate::plan::Plan;
pub use edge_pattern::{LENGTH_TOL, PATTERN_TOL};
pub(crate) use mismatched_edges::{Acceptance, EdgeJoint, acceptances};
pub use mismatched_edges::{EdgePair, MismatchReport, mismatched_edges};
pub use outline::outline_findings;

/// Interference above this share of the parts' volume fails verification.
pub const MAX_INTERFERENCE: f64 = 0.005;
/// A plan whose parts cover less than this share of the model's surface fails: it does not
/// reproduce the model (`--min-coverage`).
pub const MIN_COVERAGE: f64 = 0.8;

/// Which check a plan failed.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Check {
    /// Parts share volume.
    Interference,
    /// More groups of parts than the model has solids.
    Groups,
    /// A joint whose parts do not meet.
    JointsNotMeeting,
    /// Too little of the model's surface reproduced.
    Coverage,
    /// An outline that cannot be cut as drawn.
    Outline,
    /// A part outside its sheet or larger than it.
    Sheet,
    /// A bent part whose segments and bends disagree (it cannot be bent as drawn).
    Bends,
}

/// One reason a plan fails, with the parts it concerns.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Failure {
    /// The check.
    pub check: Check,
    /// The parts concerned, ascending (empty for the surface coverage).
    pub parts: Vec<u32>,
    /// What is wrong, for people, naming the parts.
    pub message: String,
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
    /// Total shared volume over the parts' volume (JimJoints' barbs left out).
    pub interference_share: f64,
    /// Groups of parts held together by joints.
    pub groups: usize,
    /// The groups' part ids.
    pub group_parts: Vec<Vec<u32>>,
    /// The model's separate solids, when the model was given.
    pub model_solids: Option<usize>,
    /// The distance within which a part covers the model's surface, mm.
    pub cover_distance: f64,
    /// Share of the model's surface within `cover_distance` of a part, when the model was given.
    pub surface_covered: Option<f64>,
    /// Share of the parts' volume inside the model, when the model was given to `verify`
    /// (not measured by [`check`]).
    pub volume_inside: Option<f64>,
    /// Labels of joints whose parts do not meet.
    pub joints_not_meeting: Vec<u32>,
    /// Finger-joint edges that fit where they do not belong ([`mismatched_edges`]):
    /// reported, not failed.
    pub mismatched_edges: MismatchReport,
    /// The sampling step used, mm.
    pub step: f64,
    /// Why verification failed, with the parts (empty when it passed).
    pub failures: Vec<Failure>,
    /// The failures' messages (empty when it passed).
    pub problems: Vec<String>,
    /// What the user should know but does not fail the plan (a model that does not look like
    /// the plan's source).
    pub warnings: Vec<String>,
}

impl Verification {
    /// Whether every check passed.
    pub fn passed(&self) -> bool {
        self.failures.is_empty()
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
/// of the model's surface, and measures the share of the parts' volume inside the model.
pub fn verify_with(plan: &Plan, model: Option<&Mesh>, min_coverage: f64) -> Verification {
    check(plan, &analyse(plan, model), min_coverage)
}

/// The verdict on `plan` from its `analysis` (made by [`analyse`], with the model when the
/// coverage is to be checked), without measuring the assembly again.
pub fn check(plan: &Plan, analysis: &Analysis, min_coverage: f64) -> Verification {
    let mut failures = Vec::new();
    failures.extend(interference_failure(analysis));
    failures.extend(groups_failure(analysis));
    failures.extend(joints_failure(plan, analysis));
    let sketch = plan.method == crate::plan::Method::Interlocked;
    if let Some(covered) = analysis.surface_covered.filter(|c| *c < min_coverage && !sketch) {
        failures.push(Failure {
            check: Check::Coverage,
            parts: Vec::new(),
            message: format!(
                "the parts reproduce only {:.1} % of the model's surface (within {:.1} mm of a part); \
                 at least {:.0} % is required (the minimum coverage)",
                100.0 * covered,
                analysis.cover_distance,
                100.0 * min_coverage
            ),
        });
    }
    let kerf = plan.settings.cut.kerf();
    for part in &plan.parts {
        for finding in outline_findings(part, kerf) {
            failures.push(Failure {
                check: Check::Outline,
                parts: vec![part.id],
                message: format!("part {}: invalid outline: {finding}", part.id),
            });
        }
    }
    failures.extend(sheet::findings(plan));
    failures.extend(bend_failures(plan));
    Verification {
        parts: analysis.parts,
        parts_volume: analysis.parts_volume,
        interference: analysis.interference.clone(),
        interference_share: analysis.interference_share,
        groups: analysis.group_count(),
        group_parts: analysis.groups.clone(),
        model_solids: analysis.model_solids,
        cover_distance: analysis.cover_distance,
        surface_covered: analysis.surface_covered,
        volume_inside: analysis.volume_inside,
        joints_not_meeting: analysis.joints_not_meeting.clone(),
        mismatched_edges: mismatched_edges(plan),
        step: analysis.step,
        problems: failures.iter().map(|f| f.message.clone()).collect(),
        failures,
        warnings: Vec::new(),
    }
}

/// Pairs named in a failure message, at most.
const NAMED_PAIRS: usize = 8;

/// Parts that share more than [`MAX_INTERFERENCE`] of their volume, naming the pairs.
fn interference_failure(analysis: &Analysis) -> Option<Failure> {
    if analysis.interference_share <= MAX_INTERFERENCE {
        return None;
    }
    let pairs: Vec<&Interference> = analysis.interference.iter().filter(|i| !i.intended).collect();
    let mut parts: Vec<u32> = pairs.iter().flat_map(|i| i.parts).collect();
    parts.sort_unstable();
    parts.dedup();
    let named: Vec<String> = pairs
        .iter()
        .take(NAMED_PAIRS)
        .map(|i| format!("parts {} and {} ({:.1} mm³)", i.parts[0], i.parts[1], i.volume))
        .collect();
    let more = pairs.len().saturating_sub(NAMED_PAIRS);
    Some(Failure {
        check: Check::Interference,
        parts,
        message: format!(
            "parts intersect: {:.2} % of their volume is claimed twice (at most {:.1} %): {}{}",
            100.0 * analysis.interference_share,
            100.0 * MAX_INTERFERENCE,
            named.join(", "),
            if more > 0 {
                format!(" and {more} more pairs")
            } else {
                String::new()
            }
        ),
    })
}

/// More groups than the model has solids, naming the parts of the groups beyond them.
fn groups_failure(analysis: &Analysis) -> Option<Failure> {
    let extra = analysis.extra_groups();
    if extra.is_empty() {
        return None;
    }
    let mut parts: Vec<u32> = extra.iter().flat_map(|g| g.iter().copied()).collect();
    parts.sort_unstable();
    let named: Vec<String> = extra.iter().map(|g| format!("{g:?}")).collect();
    Some(Failure {
        check: Check::Groups,
        parts,
        message: format!(
            "the parts fall apart into {} groups; the model has {}: no joint holds parts {} to the rest",
            analysis.group_count(),
            analysis.allowed_groups(),
            named.join(", ")
        ),
    })
}

/// Joints whose parts do not meet, naming the joints and their parts.
/// Bent parts whose segments and bends cannot be rebuilt in 3D (the analysis then measured
/// them flat).
fn bend_failures(plan: &Plan) -> Vec<Failure> {
    plan.parts
        .iter()
        .filter_map(|part| {
            part.pieces().err().map(|e| Failure {
                check: Check::Bends,
                parts: vec![part.id],
                message: e.to_string(),
            })
        })
        .collect()
}

fn joints_failure(plan: &Plan, analysis: &Analysis) -> Option<Failure> {
    if analysis.joints_not_meeting.is_empty() {
        return None;
    }
    let joints: Vec<_> = plan
        .joints
        .iter()
        .filter(|j| analysis.joints_not_meeting.contains(&j.label))
        .collect();
    let mut parts: Vec<u32> = joints.iter().flat_map(|j| j.parts).collect();
    parts.sort_unstable();
    parts.dedup();
    let named: Vec<String> = joints
        .iter()
        .map(|j| format!("{} (parts {} and {})", j.label, j.parts[0], j.parts[1]))
        .collect();
    Some(Failure {
        check: Check::JointsNotMeeting,
        parts,
        message: format!("joints whose parts do not meet: {}", named.join(", ")),
    })
}

/// The weld `plan` was made with (recorded as `settings.weld`, mm), so that `verify --model`
/// measures the same mesh convert judged the plan against: coverage on another weld of the
/// model could differ from convert's report. Plans without the setting were made unwelded.
pub fn model_weld(plan: &Plan) -> crate::Weld {
    match plan.settings.method.get("weld") {
        Some(crate::plan::SettingValue::Number(d)) if *d > 0.0 => crate::Weld::Distance(*d),
        _ => crate::Weld::Off,
    }
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
             is it the same model, read with the same `units` and `scale`?",
            size(model.bounds.size()),
            size(hi - lo),
            format!("{:?}", plan.source.units).to_lowercase(),
            plan.source.scale
        )
    })
}
