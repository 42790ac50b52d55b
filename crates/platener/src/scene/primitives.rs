//! The `primitives` view (issue 20, "Debug view"): what the classifier found, drawn on the
//! mesh. Each primitive is one node `KIND-N` (`plane-1`, `cylinder-2`, N from 1 in the
//! classification's order) in its own palette colour, holding the triangles it explains and,
//! as points in the same colour, its inlier samples; the node's `extras` carry the fitted
//! shape. What no primitive explains is one grey node `unexplained`. Seeing the inliers next
//! to the triangles shows whether a primitive is wrong (points off its triangles) or only
//! labelled wrong (points right, triangles missing).

use serde_json::{Value, json};

use super::glb::{GlbBuilder, MeshData, Mode};
use super::palette::Colour;
use super::surface::{GROUP_NODE_LIMIT, faces_under};
use super::{Scene, SceneError, TRIANGLE_LIMIT};
use crate::classify::{Classification, Primitive};
use crate::mesh::Mesh;

/// At most this many inlier samples are drawn, over all primitives: 20 000 points keep the
/// GLB under a quarter of a megabyte of positions and are plenty to see a primitive's extent
/// (the classifier takes 40 000 samples by default).
pub const POINT_LIMIT: usize = 20_000;

/// The name of the node of what no primitive explains.
const UNEXPLAINED: &str = "unexplained";

/// The `primitives` view of `classification`, made on `mesh`. Primitives past
/// [`GROUP_NODE_LIMIT`] are drawn grey with the unexplained triangles. Above
/// [`TRIANGLE_LIMIT`] triangles each node is decimated to its share of the limit; every k-th
/// inlier is drawn (k the same for all, in sample order) so at most [`POINT_LIMIT`] are.
pub fn primitives(mesh: &Mesh, classification: &Classification) -> Result<Scene, SceneError> {
    let shown = &classification.primitives[..classification.primitives.len().min(GROUP_NODE_LIMIT)];
    let total = mesh.triangles.len();
    let mut points = PointPicker::new(shown.iter().map(|p| p.samples.len()).sum());
    let mut glb = GlbBuilder::default();
    let mut decimated = false;
    for (i, p) in shown.iter().enumerate() {
        let name = format!("{}-{}", p.shape.kind().name(), i + 1);
        let (surface, note) = faces_under(mesh, &p.triangles, triangle_limit(total, p.triangles.len()));
        decimated |= note.is_some();
        let samples = points.pick(classification, p);
        let parts = [(&surface, Mode::Triangles), (&samples, Mode::Points)];
        let m = glb.mesh_of(&name, &parts, Colour::nth(i), true)?;
        glb.node_with(&name, m, None, Some(extras(p, samples.positions.len())));
    }
    let rest = unexplained(classification, shown.len());
    let (surface, note) = faces_under(mesh, &rest, triangle_limit(total, rest.len()));
    decimated |= note.is_some();
    let m = glb.mesh(UNEXPLAINED, &surface, Mode::Triangles, Colour::GREY, true)?;
    if m.is_some() {
        glb.node(UNEXPLAINED, m, None);
    }
    let hidden = classification.primitives.len() - shown.len();
    let notes = notes(decimated.then_some((total, glb.triangles)), &points, hidden);
    Scene::finish(glb, "primitives", notes)
}

/// What the viewer should know: triangles decimated (from, to), inliers thinned, primitives
/// drawn grey.
fn notes(decimated: Option<(usize, usize)>, points: &PointPicker, hidden: usize) -> Vec<String> {
    let mut notes = Vec::new();
    if let Some((from, to)) = decimated {
        notes.push(format!("decimated from {from} to {to} triangles for viewing"));
    }
    if points.stride > 1 {
        notes.push(format!(
            "1 in {} of the {} inlier samples drawn as points",
            points.stride, points.seen
        ));
    }
    if hidden > 0 {
        notes.push(format!(
            "{hidden} later primitives (past the first {GROUP_NODE_LIMIT}) drawn grey with the unexplained faces"
        ));
    }
    notes
}

/// What a viewer can list about a primitive: its kind, fitted shape (the classification's
/// JSON form), side, area and counts.
fn extras(p: &Primitive, points: usize) -> Value {
    json!({
        "kind": p.shape.kind().name(),
        "shape": p.shape,
        "outward": p.outward,
        "area": p.area,
        "triangles": p.triangles.len(),
        "samples": p.samples.len(),
        "points": points,
    })
}

/// The triangles no shown primitive explains, ascending.
fn unexplained(c: &Classification, shown: usize) -> Vec<u32> {
    (0..c.labels.len() as u32)
        .filter(|&f| c.labels[f as usize].is_none_or(|k| k as usize >= shown))
        .collect()
}

/// A node's share of [`TRIANGLE_LIMIT`] when the mesh has `total` triangles and the node
/// `triangles`: all of them under the limit, else its part of the limit in proportion (at
/// least one).
fn triangle_limit(total: usize, triangles: usize) -> usize {
    if total <= TRIANGLE_LIMIT {
        return usize::MAX;
    }
    (TRIANGLE_LIMIT as u128 * triangles as u128 / total as u128).max(1) as usize
}

/// Picks every `stride`-th inlier over all primitives in turn, so the drawn points are spread
/// like the samples and the same input draws the same points.
#[derive(Debug)]
struct PointPicker {
    stride: usize,
    seen: usize,
}

impl PointPicker {
    /// A picker for `total` inliers: the smallest stride that draws at most [`POINT_LIMIT`].
    fn new(total: usize) -> Self {
        Self {
            stride: total.div_ceil(POINT_LIMIT).max(1),
            seen: 0,
        }
    }

    /// The picked inliers of `p`, as points.
    fn pick(&mut self, c: &Classification, p: &Primitive) -> MeshData {
        let start = self.seen;
        self.seen += p.samples.len();
        let first = (self.stride - start % self.stride) % self.stride;
        let positions = p
            .samples
            .iter()
            .skip(first)
            .step_by(self.stride)
            .map(|&s| c.samples[s as usize].at.p)
            .collect();
        MeshData {
            positions,
            indices: Vec::new(),
        }
    }
}
