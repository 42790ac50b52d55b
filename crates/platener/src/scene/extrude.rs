//! A flat part as a closed solid: its polygon extruded from local z = 0 to its thickness.
//!
//! Plates and final parts are drawn this way in their own frame; the node's transform puts
//! them in the model. The caps come from [`platener_geom::triangulate`], the side walls follow
//! the triangulation's boundary edges, so every edge is shared by exactly two triangles of
//! opposite direction (watertight) and every triangle faces outward.

use glam::DVec3;
use platener_geom::Polygon;
use platener_geom::triangulate::triangulate;

use super::SceneError;
use super::glb::MeshData;

/// The solid of `polygon` (outer ring and holes in the local xy plane) between z = 0 and
/// z = `thickness`: positions and counter-clockwise-from-outside triangles.
pub(crate) fn extrude(polygon: &Polygon, thickness: f64) -> Result<(Vec<DVec3>, Vec<[u32; 3]>), SceneError> {
    let t = triangulate(polygon).map_err(|error| SceneError::Geometry {
        what: "an outline".into(),
        error,
    })?;
    let n = u32::try_from(t.points.len()).map_err(|_| SceneError::TooLarge { what: "a part".into() })?;
    let positions: Vec<DVec3> = [0.0, thickness]
        .iter()
        .flat_map(|&z| t.points.iter().map(move |p| p.extend(z)))
        .collect();
    let mut triangles = Vec::with_capacity(2 * t.triangles.len() + 2 * t.points.len());
    for &[a, b, c] in &t.triangles {
        // The bottom cap faces -z: its triangles turned round.
        triangles.push([a, c, b]);
        triangles.push([a + n, b + n, c + n]);
    }
    // Boundary edge a → b has the solid on its left: the wall a0 b0 b1 a1 faces right, out.
    for [a, b] in t.boundary_edges() {
        triangles.push([a, b, b + n]);
        triangles.push([a, b + n, a + n]);
    }
    Ok((positions, triangles))
}

/// [`extrude`] as mesh data for the GLB writer.
pub(crate) fn slab_mesh(polygon: &Polygon, thickness: f64) -> Result<MeshData, SceneError> {
    let (positions, triangles) = extrude(polygon, thickness)?;
    Ok(MeshData {
        positions,
        indices: triangles.into_iter().flatten().collect(),
    })
}
