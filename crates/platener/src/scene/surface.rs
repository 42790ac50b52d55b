//! The views of the model's surface: `model` (triangles as read), `wireframe` (their edges)
//! and `coplanar` (each planar group in its own colour). Positions are in model coordinates;
//! the surfaces are drawn double-sided because a model as read may be open or mis-wound.

use std::collections::HashMap;

use glam::DVec3;

use super::decimate::{Indexed, TRIANGLE_LIMIT, compact, under_limit};
use super::glb::{GlbBuilder, MeshData, Mode};
use super::palette::Colour;
use super::{Scene, SceneError};
use crate::coplanar::PlanarGroups;
use crate::mesh::Mesh;
use crate::read;

/// At most this many planar groups get their own node; the rest (the smallest: groups are
/// sorted largest first) are drawn together in grey, so an organic model with one group per
/// triangle does not turn into a JSON of a hundred thousand nodes.
pub const GROUP_NODE_LIMIT: usize = 1024;

/// The `model` view: the triangles as read, as one grey mesh (decimated above
/// [`TRIANGLE_LIMIT`]).
pub fn model(model: &read::Model) -> Result<Scene, SceneError> {
    let (mesh, note) = under_limit(index_soup(&model.triangles), TRIANGLE_LIMIT);
    let mut glb = GlbBuilder::default();
    let m = glb.mesh("model", &triangles(mesh), Mode::Triangles, Colour::GREY, true)?;
    glb.node("model", m, None);
    Scene::finish(glb, &model.name, note.into_iter().collect())
}

/// The `wireframe` view: every edge of the mesh once, as lines (decimated like `model`).
pub fn wireframe(mesh: &Mesh) -> Result<Scene, SceneError> {
    let (indexed, note) = under_limit((mesh.vertices.clone(), mesh.triangles.clone()), TRIANGLE_LIMIT);
    let (positions, tris) = indexed;
    let mut edges: Vec<[u32; 2]> = tris
        .iter()
        .flat_map(|&[a, b, c]| [[a, b], [b, c], [c, a]])
        .map(|[a, b]| [a.min(b), a.max(b)])
        .collect();
    edges.sort_unstable();
    edges.dedup();
    let data = MeshData {
        positions,
        indices: edges.into_iter().flatten().collect(),
    };
    let mut glb = GlbBuilder::default();
    let m = glb.mesh("wireframe", &data, Mode::Lines, Colour::GREY, false)?;
    glb.node("wireframe", m, None);
    Scene::finish(glb, "wireframe", note.into_iter().collect())
}

/// The `coplanar` view: one node `group-N` (N from 1, largest group first) per planar group
/// in its own colour; groups past [`GROUP_NODE_LIMIT`] and faces in no group go to one grey
/// node `group-rest`.
pub fn coplanar(mesh: &Mesh, groups: &PlanarGroups) -> Result<Scene, SceneError> {
    let mut glb = GlbBuilder::default();
    for (i, g) in groups.groups.iter().take(GROUP_NODE_LIMIT).enumerate() {
        let name = format!("group-{}", i + 1);
        let m = glb.mesh(&name, &faces_of(mesh, &g.faces), Mode::Triangles, Colour::nth(i), true)?;
        glb.node(&name, m, None);
    }
    let rest: Vec<u32> = (0..mesh.triangles.len() as u32)
        .filter(|&f| {
            let g = groups.face_group.get(f as usize).copied().unwrap_or(u32::MAX);
            g as usize >= GROUP_NODE_LIMIT.min(groups.groups.len())
        })
        .collect();
    let mut notes = Vec::new();
    if !rest.is_empty() {
        let m = glb.mesh(
            "group-rest",
            &faces_of(mesh, &rest),
            Mode::Triangles,
            Colour::GREY,
            true,
        )?;
        glb.node("group-rest", m, None);
        notes.push(format!(
            "{} faces of the smaller planar groups (past the first {GROUP_NODE_LIMIT}) drawn as one grey node",
            rest.len()
        ));
    }
    Scene::finish(glb, "coplanar", notes)
}

/// A triangle soup indexed by exact position (first seen, first numbered).
fn index_soup(soup: &[read::Triangle]) -> Indexed {
    let mut index: HashMap<[u64; 3], u32> = HashMap::new();
    let mut points = Vec::new();
    let triangles = soup
        .iter()
        .map(|t| {
            t.map(|p| {
                let next = points.len() as u32;
                *index.entry(p.to_array().map(f64::to_bits)).or_insert_with(|| {
                    points.push(p);
                    next
                })
            })
        })
        .collect();
    (points, triangles)
}

/// Some faces of the mesh with only the vertices they use.
fn faces_of(mesh: &Mesh, faces: &[u32]) -> MeshData {
    faces_under(mesh, faces, usize::MAX).0
}

/// Some faces of the mesh with only the vertices they use, clustered down to at most `limit`
/// triangles when there are more (with the note [`under_limit`] writes).
pub(super) fn faces_under(mesh: &Mesh, faces: &[u32], limit: usize) -> (MeshData, Option<String>) {
    let picked: Vec<[u32; 3]> = faces.iter().map(|&f| mesh.triangles[f as usize]).collect();
    let (indexed, note) = under_limit(compact(&mesh.vertices, picked), limit);
    (triangles(indexed), note)
}

fn triangles((positions, tris): (Vec<DVec3>, Vec<[u32; 3]>)) -> MeshData {
    MeshData {
        positions,
        indices: tris.into_iter().flatten().collect(),
    }
}
