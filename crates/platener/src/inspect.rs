//! `platener inspect`: runs the foundation steps and summarises what they found.

use std::sync::Arc;

use glam::DVec3;
use serde::Serialize;

use crate::error::Result;
use crate::mesh::Health;
use crate::pipeline::{self, Cancel, Source, State, StepRecord, Warning};
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
    settings.validate()?;
    let mut state = State::new(source, settings);
    let records = pipeline::run(&pipeline::foundation_steps(), &mut state, cancel)?;
    Ok((state, records))
}

/// Runs the foundation steps and summarises them.
pub fn inspect(source: Source, settings: Settings, cancel: &Cancel) -> Result<Inspection> {
    let (state, steps) = run_foundation(source, settings, cancel)?;
    let need = |name| crate::Error::MissingStep {
        step: "inspect",
        needs: name,
    };
    let model = state.read.as_ref().ok_or(need("read"))?;
    let cleaned = state.cleanup.as_ref().ok_or(need("cleanup"))?;
    let welded = state.weld.as_ref().ok_or(need("weld"))?;
    let mesh = state.mesh.as_ref().ok_or(need("mesh"))?;
    let groups = state.coplanar.as_ref().ok_or(need("coplanar"))?;
    let shapes: &Arc<_> = state.shapes.as_ref().ok_or(need("shapes"))?;
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
        steps,
    })
}
