//! `platener inspect`: runs the foundation steps and summarises what they found.

use glam::DVec3;
use serde::Serialize;

use crate::context::{Cancel, StepRecord, Warning};
use crate::error::Result;
use crate::mesh::Health;
use crate::pipeline::{self, FOUNDATION, PLATE, Source, State, StepId};
use crate::read::Bounds;
use crate::settings::Settings;

/// How many of the largest shapes the summary lists.
pub const LARGEST_SHAPES: usize = 10;

/// One of the largest planar shapes.
#[derive(Debug, Clone, Serialize)]
pub struct ShapeSummary {
    /// Area in mm².
    pub area: f64,
    /// Unit normal.
    pub normal: DVec3,
    /// Number of holes.
    pub holes: usize,
    /// Vertices over all rings.
    pub vertices: usize,
    /// A point of the shape's plane (its frame origin).
    pub at: DVec3,
}

/// One plate, as `platener inspect --plates` lists it.
#[derive(Debug, Clone, Serialize)]
pub struct PlateSummary {
    /// How it was found.
    pub kind: crate::plates::PlateKind,
    /// Sheet thickness in mm.
    pub thickness: f64,
    /// Outline area in mm².
    pub area: f64,
    /// Vertices of the outline and holes.
    pub vertices: usize,
    /// Holes.
    pub holes: usize,
    /// The plate's centre in the model (centre of its outline's box, mid-thickness).
    pub center: DVec3,
    /// The plate's normal.
    pub normal: DVec3,
    /// The 3×4 transform of plan.json (model point = R·(x, y, z) + t).
    pub transform: [[f64; 4]; 3],
}

/// Plates and coverage, for `platener inspect --plates`.
#[derive(Debug, Clone, Serialize)]
pub struct PlatesReport {
    /// The plates.
    pub plates: Vec<PlateSummary>,
    /// Which shapes became plates and why the others did not.
    pub coverage: crate::plates::Coverage,
    /// Plates removed as contained in another.
    pub contained_removed: usize,
    /// Plates trimmed where they overlapped another.
    pub trimmed: usize,
    /// Split plates joined again.
    pub rejoined: usize,
}

/// Everything `platener inspect` prints.
#[derive(Debug, Clone, Serialize)]
pub struct Inspection {
    /// Model name.
    pub model: String,
    /// File format label.
    pub format: Option<&'static str>,
    /// Triangles read.
    pub triangles_read: usize,
    /// Solids / objects in the file.
    pub solids: usize,
    /// Bounding box in mm.
    pub bounds: Bounds,
    /// Degenerate triangles removed by cleanup.
    pub degenerate_removed: usize,
    /// Duplicate triangles removed by cleanup.
    pub duplicates_removed: usize,
    /// Weld distance used (mm).
    pub weld_distance: f64,
    /// Vertices merged by welding.
    pub vertices_merged: usize,
    /// Triangles that welding collapsed or merged.
    pub triangles_welded_away: usize,
    /// Open edges of the model as given (before welding).
    pub input_open_edges: usize,
    /// Non-manifold edges of the model as given (before welding).
    pub input_non_manifold_edges: usize,
    /// Triangles in the final mesh.
    pub triangles: usize,
    /// Mesh health.
    pub health: Health,
    /// Surface area in mm².
    pub surface_area: f64,
    /// Planar groups.
    pub planar_groups: usize,
    /// Planar shapes.
    pub shapes: usize,
    /// The largest shapes.
    pub largest_shapes: Vec<ShapeSummary>,
    /// Printing the model instead, with the reference slicer profile (`fabrication::print`).
    pub print: crate::plan::PrintEstimate,
    /// Plates and coverage, when asked for.
    pub plates: Option<PlatesReport>,
    /// Steps with their times and warnings.
    pub steps: Vec<StepRecord>,
}

impl Inspection {
    /// All warnings of all steps.
    pub fn warnings(&self) -> impl Iterator<Item = &Warning> {
        self.steps.iter().flat_map(|s| s.warnings.iter())
    }
}

/// Runs the foundation steps on `source` and returns the final state and its records.
pub fn run_foundation(source: Source, settings: Settings, cancel: &Cancel) -> Result<(State, Vec<StepRecord>)> {
    run_steps(&FOUNDATION, source, settings, cancel)
}

fn run_steps(
    steps: &[StepId],
    source: Source,
    settings: Settings,
    cancel: &Cancel,
) -> Result<(State, Vec<StepRecord>)> {
    settings.validate()?;
    let mut state = State::new(source, settings);
    pipeline::run(steps, &mut state, cancel)?;
    let records = state.records.clone();
    Ok((state, records))
}

fn plates_report(plates: &crate::plates::Plates) -> PlatesReport {
    let summaries = plates
        .plates
        .iter()
        .map(|p| {
            let (lo, hi) = p.polygon.bounds();
            let c = (lo + hi) / 2.0;
            PlateSummary {
                kind: p.kind,
                thickness: p.thickness,
                area: p.area,
                vertices: p.polygon.vertex_count(),
                holes: p.polygon.holes.len(),
                center: p.frame.to_model(DVec3::new(c.x, c.y, p.thickness / 2.0)),
                normal: p.frame.n,
                transform: p.frame.matrix(),
            }
        })
        .collect();
    PlatesReport {
        plates: summaries,
        coverage: plates.coverage.clone(),
        contained_removed: plates.contained_removed,
        trimmed: plates.trimmed,
        rejoined: plates.rejoined,
    }
}

/// Runs the foundation steps (and plate finding when `with_plates`) and summarises them.
pub fn inspect(source: Source, settings: Settings, cancel: &Cancel, with_plates: bool) -> Result<Inspection> {
    let steps: &[StepId] = if with_plates { &PLATE } else { &FOUNDATION };
    let (state, steps) = run_steps(steps, source, settings, cancel)?;
    let model = pipeline::need(&state.read, "inspect", "read")?;
    let cleaned = pipeline::need(&state.cleanup, "inspect", "cleanup")?;
    let welded = pipeline::need(&state.weld, "inspect", "weld")?;
    let mesh = pipeline::need(&state.mesh, "inspect", "mesh")?;
    let groups = pipeline::need(&state.coplanar, "inspect", "coplanar")?;
    let shapes = pipeline::need(&state.shapes, "inspect", "shapes")?;
    Ok(Inspection {
        model: model.name.clone(),
        format: model.format.map(|f| f.label()),
        triangles_read: model.triangles.len(),
        solids: model.solids,
        bounds: model.bounds,
        degenerate_removed: cleaned.degenerate_removed,
        duplicates_removed: cleaned.duplicates_removed,
        weld_distance: welded.distance,
        vertices_merged: welded.vertices_merged,
        triangles_welded_away: welded.triangles_collapsed + welded.triangles_merged,
        input_open_edges: welded.input_open_edges,
        input_non_manifold_edges: welded.input_non_manifold_edges,
        triangles: mesh.triangles.len(),
        health: mesh.health.clone(),
        surface_area: mesh.surface_area,
        planar_groups: groups.groups.len(),
        shapes: shapes.shapes.len(),
        largest_shapes: shapes
            .shapes
            .iter()
            .take(LARGEST_SHAPES)
            .map(|s| ShapeSummary {
                area: s.area,
                normal: s.frame.n,
                holes: s.polygon.holes.len(),
                vertices: s.polygon.vertex_count(),
                at: s.frame.origin,
            })
            .collect(),
        print: model.print,
        plates: state.plates.as_deref().map(plates_report),
        steps,
    })
}
