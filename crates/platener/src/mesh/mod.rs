//! Step `mesh` (the thesis' MeshSetup): the indexed mesh with its topology and a health report.
//!
//! Later steps need to walk the surface: which edges a face has, which faces share an edge.
//! Building that also tells how healthy the model is (open and non-manifold edges, bodies), and
//! lets us make the winding consistent so every normal points out of the solid, which plate
//! finding depends on (two faces of a plate must face apart).

mod orient;
mod topology;
mod touching;

use glam::DVec3;
use serde::Serialize;

use crate::cleanup::Cleaned;
use crate::cleanup::is_degenerate;
use crate::context::{StepContext, WarningKind};
use crate::error::{Error, ModelProblem, Result};
use crate::weld::Welded;

pub use topology::Topology;

/// How healthy the surface is.
#[derive(Debug, Clone, Default, PartialEq, Serialize)]
pub struct Health {
    /// Edges used by exactly one triangle (holes in the surface).
    pub open_edges: usize,
    /// Edges used by three or more triangles.
    pub non_manifold_edges: usize,
    /// Connected bodies (faces connected through shared edges).
    pub components: usize,
    /// Separate solids: components not inside another (a hollow box's cavity is not one), bodies
    /// that touch or cross counted once (see `touching`).
    pub solids: usize,
    /// Triangles whose winding was turned round to agree with their neighbours / point out.
    pub flipped_faces: usize,
    /// Edges whose two triangles still disagree (a non-orientable surface, e.g. a Möbius strip).
    pub non_orientable_edges: usize,
    /// Triangles that welding left with no area, removed here.
    pub degenerate_after_weld: usize,
    /// Whether every edge has exactly two triangles (a closed, manifold surface).
    pub closed: bool,
    /// Enclosed volume in mm³ when the surface is closed.
    pub volume: Option<f64>,
}

/// The snapshot of step `mesh`.
#[derive(Debug, Clone, Serialize)]
pub struct Mesh {
    /// Vertex positions in mm.
    #[serde(skip)]
    pub vertices: Vec<DVec3>,
    /// Triangles, wound consistently (normals out where the surface allows).
    #[serde(skip)]
    pub triangles: Vec<[u32; 3]>,
    /// Each triangle as the model drew it before welding (the cleaned triangle it came from),
    /// wound like the triangle here. Welding moves vertices; these do not move, so planes are
    /// taken from them (`coplanar`).
    #[serde(skip)]
    pub original: Vec<[DVec3; 3]>,
    /// Unit normal of each triangle, from its winding.
    #[serde(skip)]
    pub normals: Vec<DVec3>,
    /// Area of each triangle in mm².
    #[serde(skip)]
    pub areas: Vec<f64>,
    /// Edges and their faces.
    #[serde(skip)]
    pub topology: Topology,
    /// Body index of each triangle.
    #[serde(skip)]
    pub component: Vec<u32>,
    /// The health report.
    pub health: Health,
    /// Total surface area in mm².
    pub surface_area: f64,
}

impl Mesh {
    /// Builds the mesh from an indexed triangle list that was not welded (each triangle is
    /// its own original); see [`Mesh::build_with_originals`].
    pub fn build(vertices: Vec<DVec3>, triangles: &[[u32; 3]], min_height: f64) -> Self {
        let original = triangles.iter().map(|t| t.map(|i| vertices[i as usize])).collect();
        Self::build_with_originals(vertices, triangles, original, min_height)
    }

    /// Builds the mesh from an indexed triangle list and each triangle's original corners
    /// (same winding): removes zero-area triangles, builds the topology, orients (turning the
    /// originals with their triangles), and reports health.
    pub fn build_with_originals(
        vertices: Vec<DVec3>,
        triangles: &[[u32; 3]],
        originals: Vec<[DVec3; 3]>,
        min_height: f64,
    ) -> Self {
        let mut kept: Vec<[u32; 3]> = Vec::with_capacity(triangles.len());
        let mut original: Vec<[DVec3; 3]> = Vec::with_capacity(triangles.len());
        let mut degenerate = 0;
        for (t, o) in triangles.iter().zip(originals) {
            let corners = t.map(|i| vertices[i as usize]);
            if is_degenerate(&corners, min_height) {
                degenerate += 1;
            } else {
                kept.push(*t);
                original.push(o);
            }
        }
        let mut topology = Topology::build(&kept);
        let oriented = orient::orient(&vertices, &kept, &topology);
        topology.reverse_faces(&oriented.reversed);
        for (o, &turned) in original.iter_mut().zip(&oriented.reversed) {
            if turned {
                o.swap(1, 2);
            }
        }
        let (normals, areas): (Vec<DVec3>, Vec<f64>) = oriented
            .triangles
            .iter()
            .map(|t| {
                let [a, b, c] = t.map(|i| vertices[i as usize]);
                let cross = (b - a).cross(c - a);
                let len = cross.length();
                (cross / len, 0.5 * len)
            })
            .unzip();
        let (open_edges, non_manifold_edges) = topology.edge_counts();
        let closed = open_edges == 0 && non_manifold_edges == 0 && !kept.is_empty();
        let volume = closed.then(|| orient::signed_volume(&vertices, &oriented.triangles, None));
        let health = Health {
            open_edges,
            non_manifold_edges,
            components: oriented.components,
            solids: oriented.solids,
            flipped_faces: oriented.flipped,
            non_orientable_edges: oriented.non_orientable_edges,
            degenerate_after_weld: degenerate,
            closed,
            volume,
        };
        Self {
            surface_area: areas.iter().sum(),
            vertices,
            triangles: oriented.triangles,
            original,
            normals,
            areas,
            topology,
            component: oriented.component,
            health,
        }
    }

    /// The three corners of triangle `f`.
    pub fn corners(&self, f: usize) -> [DVec3; 3] {
        self.triangles[f].map(|i| self.vertices[i as usize])
    }
}

/// Step `mesh`: the welded triangles as an indexed mesh with topology, consistent winding and
/// a health report.
pub fn run(welded: &Welded, cleaned: &Cleaned, cx: &mut StepContext<'_>) -> Result<Mesh> {
    let originals = welded.source.iter().map(|&s| cleaned.triangles[s as usize]).collect();
    let mesh = Mesh::build_with_originals(
        welded.vertices.clone(),
        &welded.triangles,
        originals,
        cleaned.tolerances.degenerate_height,
    );
    if mesh.triangles.is_empty() {
        return Err(Error::model(cx.model(), ModelProblem::EmptyAfterWeld));
    }
    // Open and non-manifold edges are reported by `weld` for the model as given; the
    // welded mesh's own counts (which welding can raise) are in the health report.
    let h = &mesh.health;
    if h.flipped_faces > 0 {
        cx.warn(
            WarningKind::FlippedFaces,
            format!(
                "{} flipped faces were turned round to agree with their neighbours",
                h.flipped_faces
            ),
        );
    }
    if h.degenerate_after_weld > 0 {
        cx.warn(
            WarningKind::DegenerateFaces,
            format!(
                "{} triangles lost their area in welding and were removed",
                h.degenerate_after_weld
            ),
        );
    }
    Ok(mesh)
}

#[cfg(test)]
mod tests;
