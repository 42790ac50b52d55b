//! The score of a conversion: one number in [0, 1] saying how good a cutting plan is, built
//! from what users care about (the seed's Scorer; `--method all` picks the best by it).
//!
//! ```text
//! total    = shape × (0.5 + 0.3·assembly + 0.2·effort)
//! shape    = surface_covered × volume_inside
//! assembly = connectivity × (1 − interference)
//! effort   = 1 / (1 + work_minutes / 60)
//! ```
//!
//! - **surface_covered**: share of the model's surface (area-weighted sample points) within
//!   [`ScoreSettings::reach`] (2 mm) of some part's volume.
//! - **volume_inside**: share of the parts' volume (sample points) inside the model (ray
//!   parity, voted over three axes: [`inside`]).
//! - **connectivity**: how much of the assembly hangs together through plan.json's `joints`:
//!   (parts − groups) / (parts − solids), the share of the connections needed to make as many
//!   groups as the model has separate solids; 1 when there are no more parts than solids, 0
//!   when there are no joints.
//! - **interference**: share of the parts' volume (sample points) inside another part.
//! - **work_minutes**: laser time (report.json's estimate) + 1 minute per part to assemble
//!   + 2 minutes per sheet to handle.
//!
//! The shape is a factor, not a term: a plan that reproduces nothing is worth nothing, however
//! cheap. The parts are read from plan.json (outline, holes, transform), so the score judges
//! what a reader of the plan would assemble, whichever method made it. Shares are estimated
//! from [`ScoreSettings::surface_samples`] and [`ScoreSettings::volume_samples`] seeded
//! samples: ±1 percentage point (one standard error at 4000 samples is at most 0.8), and the
//! same conversion always gets the same score. docs/score.md explains the choices.

mod sample;
#[cfg(test)]
mod tests;

use std::collections::BTreeMap;

use platener_geom::rng::SplitMix64;
use serde::Serialize;

use crate::assembly::{Inside, Solid};
use crate::export::Bundle;
use crate::export::report::Report;
use crate::mesh::Mesh;
use crate::plan::{Plan, PlanJoint};
use crate::plates::Plates;

/// Weight of the assembly inside the shape factor.
pub const ASSEMBLY_WEIGHT: f64 = 0.3;
/// Weight of the effort inside the shape factor (the rest, 0.5, is the shape alone).
pub const EFFORT_WEIGHT: f64 = 0.2;
/// Minutes to take a part off the sheet, sand it and put it in place.
pub const MINUTES_PER_PART: f64 = 1.0;
/// Minutes to put a sheet in the laser, focus and take it out.
pub const MINUTES_PER_SHEET: f64 = 2.0;
/// Work that halves the effort score, minutes.
pub const EFFORT_HALF_MINUTES: f64 = 60.0;

/// How the score is estimated.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ScoreSettings {
    /// Points on the model's surface (area-weighted, stratified).
    pub surface_samples: usize,
    /// Points in the parts' volume (volume-weighted, stratified).
    pub volume_samples: usize,
    /// A surface point within this distance (mm) of a part counts as covered. 2 mm: less
    /// than any sheet's thickness, more than a weld or a kerf moves a face.
    pub reach: f64,
    /// Seed of the sampling.
    pub seed: u64,
}

impl Default for ScoreSettings {
    fn default() -> Self {
        Self {
            surface_samples: 4000,
            volume_samples: 4000,
            reach: 2.0,
            seed: 1,
        }
    }
}

/// How much of the model's shape the parts reproduce.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ShapeScore {
    /// `surface_covered × volume_inside`.
    pub value: f64,
    /// Share of the model's surface within reach of a part.
    pub surface_covered: f64,
    /// Share of the parts' volume inside the model.
    pub volume_inside: f64,
    /// For the plate method: the share of the surface the plates were detected on (the
    /// coverage report's figure), for comparison with `surface_covered`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub plates_surface_share: Option<f64>,
}

/// Whether the assembly holds together.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct AssemblyScore {
    /// `connectivity × (1 − interference)`.
    pub value: f64,
    /// (parts − groups) / (parts − solids); 1 when every part is joined into one group per
    /// solid of the model, 0 without joints.
    pub connectivity: f64,
    /// Share of the parts' volume inside another part.
    pub interference: f64,
    /// Number of joints in the plan.
    pub joints: usize,
    /// Groups of parts connected through joints (a part alone is a group).
    pub groups: usize,
    /// Separate solids of the model: the fewest groups its parts can form.
    pub solids: usize,
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
    /// The score in [0, 1]: `shape × (0.5 + 0.3·assembly + 0.2·effort)`.
    pub total: f64,
    /// How much of the model the parts reproduce.
    pub shape: ShapeScore,
    /// Whether the parts hold together.
    pub assembly: AssemblyScore,
    /// How much work it is.
    pub effort: EffortScore,
}

/// Scores a finished conversion with the default settings: its model's `mesh` against its
/// plan; `plates` (the plate method's) adds the coverage report's surface share.
pub fn score(mesh: &Mesh, bundle: &Bundle, plates: Option<&Plates>) -> Score {
    score_with(mesh, bundle, plates, &ScoreSettings::default())
}

/// [`score`] with the given sampling settings.
pub fn score_with(mesh: &Mesh, bundle: &Bundle, plates: Option<&Plates>, settings: &ScoreSettings) -> Score {
    let mut s = evaluate(mesh, &bundle.plan, &bundle.report, settings);
    s.shape.plates_surface_share = plates.map(|p| p.coverage.surface_share);
    s
}

/// The score of `plan` as a reproduction of `mesh`; effort figures come from `report`.
fn evaluate(mesh: &Mesh, plan: &Plan, report: &Report, settings: &ScoreSettings) -> Score {
    let prisms: Vec<Solid> = plan.parts.iter().map(Solid::from_part).collect();
    let mut rng = SplitMix64::new(settings.seed);
    let surface_covered = surface_covered(mesh, &prisms, settings, &mut rng);
    let (volume_inside, interference) = volume_shares(mesh, &prisms, settings, &mut rng);
    let shape = surface_covered * volume_inside;
    let solids = mesh.health.solids.max(1);
    let (connectivity, groups) = connectivity(&prisms, &plan.joints, solids);
    let assembly = connectivity * (1.0 - interference);
    let effort = effort(plan, report);
    let total =
        shape * (1.0 - ASSEMBLY_WEIGHT - EFFORT_WEIGHT + ASSEMBLY_WEIGHT * assembly + EFFORT_WEIGHT * effort.value);
    Score {
        total: total.clamp(0.0, 1.0),
        shape: ShapeScore {
            value: shape,
            surface_covered,
            volume_inside,
            plates_surface_share: None,
        },
        assembly: AssemblyScore {
            value: assembly,
            connectivity,
            interference,
            joints: plan.joints.len(),
            groups,
            solids,
        },
        effort,
    }
}

/// Share of area-weighted surface samples within reach of a part.
fn surface_covered(mesh: &Mesh, prisms: &[Solid], settings: &ScoreSettings, rng: &mut SplitMix64) -> f64 {
    let picks = sample::stratified(&mesh.areas, settings.surface_samples, rng);
    if picks.is_empty() || prisms.is_empty() {
        return 0.0;
    }
    let covered = picks
        .iter()
        .filter(|&&t| {
            let [a, b, c] = mesh.triangles[t].map(|i| mesh.vertices[i as usize]);
            let p = sample::in_triangle(a, b, c, rng);
            prisms.iter().any(|prism| prism.within(p, settings.reach))
        })
        .count();
    covered as f64 / picks.len() as f64
}

/// Shares of volume-weighted part samples inside the model, and inside another part.
fn volume_shares(mesh: &Mesh, prisms: &[Solid], settings: &ScoreSettings, rng: &mut SplitMix64) -> (f64, f64) {
    let volumes: Vec<f64> = prisms.iter().map(|p| p.volume).collect();
    let picks = sample::stratified(&volumes, settings.volume_samples, rng);
    let inside = Inside::new(&mesh.vertices, &mesh.triangles);
    let (mut counted, mut in_model, mut in_other) = (0usize, 0usize, 0usize);
    for i in picks {
        let Some(p) = sample::in_prism(&prisms[i], rng) else {
            continue;
        };
        counted += 1;
        if inside.contains(p) {
            in_model += 1;
        }
        let me = prisms[i].id;
        if prisms.iter().any(|o| o.id != me && o.near_box(p, 0.0) && o.contains(p)) {
            in_other += 1;
        }
    }
    if counted == 0 {
        return (0.0, 0.0);
    }
    (in_model as f64 / counted as f64, in_other as f64 / counted as f64)
}

/// Connectivity through the joints for a model of `solids` separate solids, and the number of
/// connected groups.
fn connectivity(prisms: &[Solid], joints: &[PlanJoint], solids: usize) -> (f64, usize) {
    let n = prisms.len();
    if n == 0 {
        return (0.0, 0);
    }
    let index: BTreeMap<u32, usize> = prisms.iter().enumerate().map(|(i, p)| (p.id, i)).collect();
    let mut group = crate::assembly::UnionFind::new(n);
    for j in joints {
        if let (Some(&a), Some(&b)) = (index.get(&j.parts[0]), index.get(&j.parts[1])) {
            group.join(a, b);
        }
    }
    let groups = group.count();
    // A spanning forest of `groups` trees over n parts has n − groups connections; one tree
    // per solid would need n − solids.
    let share = if n <= solids {
        1.0
    } else {
        ((n - groups) as f64 / (n - solids) as f64).min(1.0)
    };
    (share, groups)
}

/// The effort of cutting and assembling the plan.
fn effort(plan: &Plan, report: &Report) -> EffortScore {
    let parts = plan.parts.len();
    let sheets = plan.sheets.len();
    let laser_minutes = report.estimated_cutting_seconds.max(0.0) / 60.0;
    let work_minutes = laser_minutes + MINUTES_PER_PART * parts as f64 + MINUTES_PER_SHEET * sheets as f64;
    EffortScore {
        value: 1.0 / (1.0 + work_minutes / EFFORT_HALF_MINUTES),
        parts,
        sheets,
        cut_length: report.cut_length,
        laser_minutes,
        work_minutes,
    }
}
