//! Step `weld` (the thesis' Simplification): merges vertices closer than the weld distance.
//!
//! Editors add small bevels and fillets to printable models; welding at about 2 mm collapses
//! them so the flat faces meet in sharp edges again and plates are found. Triangles that lose
//! a distinct corner disappear; triangles that become equal are merged. The clustering itself
//! is [`platener_geom::weld`] (near-linear, deterministic). If welding would leave nothing,
//! the unwelded mesh is used and a warning says so.

use std::sync::Arc;

use glam::DVec3;
use platener_geom::dedup::first_equal;
use platener_geom::weld::weld;
use rayon::slice::ParallelSliceMut;
use serde::Serialize;

use crate::error::{Error, Result};
use crate::pipeline::{State, Step, StepContext, WarningKind, need};

/// The snapshot of step `weld`: an indexed triangle list.
#[derive(Debug, Clone, Serialize)]
pub struct Welded {
    /// Vertex positions in mm.
    #[serde(skip)]
    pub vertices: Vec<DVec3>,
    /// Triangles as vertex indices, winding as in the file.
    #[serde(skip)]
    pub triangles: Vec<[u32; 3]>,
    /// The distance used (0 = exact duplicates only).
    pub distance: f64,
    /// Distinct input positions before welding.
    pub vertices_before: usize,
    /// Vertices merged away by welding (`vertices_before - vertices.len()`).
    pub vertices_merged: usize,
    /// Triangles removed because two corners merged.
    pub triangles_collapsed: usize,
    /// Triangles removed because they became equal to another.
    pub triangles_merged: usize,
    /// Whether welding emptied the model and the unwelded mesh was used instead.
    pub fell_back: bool,
    /// Open edges of the model as given (exact duplicates merged, before welding).
    pub input_open_edges: usize,
    /// Non-manifold edges of the model as given (before welding).
    pub input_non_manifold_edges: usize,
}

/// Welds a triangle soup at `distance` (0 merges exact duplicates only).
pub fn weld_soup(soup: &[[DVec3; 3]], distance: f64) -> Welded {
    let corners: Vec<[f64; 3]> = soup.iter().flatten().map(|p| p.to_array()).collect();
    let exact = weld(&corners, &vec![1.0; corners.len()], 0.0);
    let before = exact.points.len();
    let (input_open_edges, input_non_manifold_edges) = input_edge_defects(&exact.map);
    let clustered = (distance > 0.0).then(|| weld(&exact.points, &exact.weights, distance));
    let (vertices, corner_id): (Vec<DVec3>, Box<dyn Fn(usize) -> u32>) = match &clustered {
        Some(c) => (
            c.points.iter().map(|p| DVec3::from_array(*p)).collect(),
            Box::new(|i| c.map[exact.map[i] as usize]),
        ),
        None => (
            exact.points.iter().map(|p| DVec3::from_array(*p)).collect(),
            Box::new(|i| exact.map[i]),
        ),
    };
    let mut collapsed = 0;
    let mut triangles: Vec<[u32; 3]> = Vec::with_capacity(soup.len());
    for t in 0..soup.len() {
        let tri = [corner_id(3 * t), corner_id(3 * t + 1), corner_id(3 * t + 2)];
        if tri[0] == tri[1] || tri[1] == tri[2] || tri[0] == tri[2] {
            collapsed += 1;
        } else {
            triangles.push(tri);
        }
    }
    // Cleanup removed exact duplicates already; welding can make new ones.
    let mut merged = 0;
    if clustered.is_some() {
        let keys: Vec<[u32; 3]> = triangles
            .iter()
            .map(|t| {
                let mut k = *t;
                k.sort_unstable();
                k
            })
            .collect();
        let first = first_equal(&keys);
        let before_merge = triangles.len();
        triangles = triangles
            .into_iter()
            .enumerate()
            .filter(|&(i, _)| first[i] as usize == i)
            .map(|(_, t)| t)
            .collect();
        merged = before_merge - triangles.len();
    }
    Welded {
        vertices_merged: before - vertices.len(),
        vertices,
        triangles,
        distance,
        vertices_before: before,
        triangles_collapsed: collapsed,
        triangles_merged: merged,
        fell_back: false,
        input_open_edges,
        input_non_manifold_edges,
    }
}

/// Open and non-manifold edges of the unwelded model, from each corner's exact vertex id:
/// these are the model's own defects, not artefacts of welding. Counted from sorted edge keys
/// alone (no incidence lists needed).
fn input_edge_defects(corner_vertex: &[u32]) -> (usize, usize) {
    let mut keys: Vec<u64> = Vec::with_capacity(corner_vertex.len());
    for c in corner_vertex.chunks_exact(3) {
        if c[0] == c[1] || c[1] == c[2] || c[0] == c[2] {
            continue;
        }
        for i in 0..3 {
            let (a, b) = (c[i], c[(i + 1) % 3]);
            keys.push((u64::from(a.min(b)) << 32) | u64::from(a.max(b)));
        }
    }
    keys.par_sort_unstable();
    let (mut open, mut non_manifold) = (0, 0);
    for run in keys.chunk_by(|a, b| a == b) {
        match run.len() {
            1 => open += 1,
            2 => {}
            _ => non_manifold += 1,
        }
    }
    (open, non_manifold)
}

/// Step `weld`.
pub struct WeldStep;

impl Step for WeldStep {
    fn name(&self) -> &'static str {
        "weld"
    }

    fn run(&self, state: &mut State, cx: &mut StepContext<'_>) -> Result<()> {
        let model = need(&state.read, self.name(), "read")?;
        let cleaned = need(&state.cleanup, self.name(), "cleanup")?;
        let distance = state.settings.weld_distance(model.bounds.largest_extent());
        let mut welded = weld_soup(&cleaned.triangles, distance);
        if welded.triangles.is_empty() && distance > 0.0 {
            cx.warn(
                WarningKind::WeldFallback,
                format!(
                    "welding at {distance:.3} mm would remove every triangle; the unwelded mesh is used (try --weld 0)"
                ),
            );
            welded = Welded {
                fell_back: true,
                ..weld_soup(&cleaned.triangles, 0.0)
            };
        }
        cx.check_cancel()?;
        if welded.input_open_edges > 0 {
            cx.warn(
                WarningKind::OpenEdges,
                format!(
                    "{} open edges: the model's surface has holes (not watertight)",
                    welded.input_open_edges
                ),
            );
        }
        if welded.input_non_manifold_edges > 0 {
            cx.warn(
                WarningKind::NonManifoldEdges,
                format!(
                    "{} non-manifold edges: some edges of the model are shared by more than two triangles",
                    welded.input_non_manifold_edges
                ),
            );
        }
        if welded.triangles.is_empty() {
            return Err(Error::Model {
                model: model.name.clone(),
                message: "no triangle with an area is left after cleanup".into(),
            });
        }
        state.weld = Some(Arc::new(welded));
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bevel_collapses_into_a_sharp_edge() {
        // Two 20 mm squares meeting at a right angle through a 0.5 mm 45° bevel strip.
        let p = |x: f64, y: f64, z: f64| DVec3::new(x, y, z);
        let top = [
            p(0.0, 0.0, 10.0),
            p(20.0, 0.0, 10.0),
            p(20.0, 19.5, 10.0),
            p(0.0, 19.5, 10.0),
        ];
        let bevel_lo = [p(0.0, 20.0, 9.5), p(20.0, 20.0, 9.5)];
        let side_lo = [p(0.0, 20.0, -10.0), p(20.0, 20.0, -10.0)];
        let soup = vec![
            [top[0], top[1], top[2]],
            [top[0], top[2], top[3]],
            [top[3], top[2], bevel_lo[1]],
            [top[3], bevel_lo[1], bevel_lo[0]],
            [bevel_lo[0], bevel_lo[1], side_lo[1]],
            [bevel_lo[0], side_lo[1], side_lo[0]],
        ];
        let w = weld_soup(&soup, 1.0);
        let v = &w.vertices;
        assert_eq!(w.vertices_before, 8);
        assert_eq!(v.len(), 6);
        assert_eq!(w.triangles_collapsed, 2, "both bevel triangles collapse");
        assert_eq!(w.triangles.len(), 4);
        // The merged corner lies at the mean of (y 19.5, z 10) and (y 20, z 9.5).
        let corner = v
            .iter()
            .find(|q| q.x == 0.0 && q.y > 19.0 && q.z > 9.0)
            .expect("merged corner");
        assert!((corner.y - 19.75).abs() < 1e-9 && (corner.z - 9.75).abs() < 1e-9);
    }
}
