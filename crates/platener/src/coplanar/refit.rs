//! Welded vertices put back onto the model's planes.
//!
//! Welding averages positions: a bevelled box's corner ends up inside the bevel, off all
//! three faces, and outlines drawn through it tilt and taper. Each vertex is moved to the
//! least-squares point of the planes of the groups around it ([`Qef`], one plane per group,
//! truncated so near-parallel planes fix one direction, not two): the exact corner where
//! three faces meet, the nearest point of the edge where two meet, the projection onto one.
//! A vertex welding did not move stays where it is, and no vertex moves further than twice
//! the distance welding moved it (from the farthest of its original corners): the planes
//! around it then do not describe a corner near it, and the welded position is safer.
//! Groups the classifier fixed carry a snap distance: their vertices move onto the planes
//! by up to that much whether welding moved them or not (flattening a texture).

use glam::DVec3;
use platener_geom::plane_fit::Qef;

use super::PlanarGroup;
use crate::mesh::Mesh;

/// Every mesh vertex refitted to its groups' planes (see the module doc); `snap[g]` is how
/// far group g's vertices may move regardless of welding.
pub(super) fn refit_vertices(mesh: &Mesh, groups: &[PlanarGroup], face_group: &[u32], snap: &[f64]) -> Vec<DVec3> {
    let n = mesh.vertices.len();
    // (vertex, group, distance welding moved it from this corner's original), sorted:
    // each vertex's groups are then one run, deduplicated in order (deterministic).
    let mut incident: Vec<(u32, u32, f64)> = Vec::with_capacity(3 * mesh.triangles.len());
    for (f, t) in mesh.triangles.iter().enumerate() {
        for (k, &v) in t.iter().enumerate() {
            let moved = (mesh.vertices[v as usize] - mesh.original[f][k]).length();
            incident.push((v, face_group[f], moved));
        }
    }
    incident.sort_unstable_by(|a, b| (a.0, a.1).cmp(&(b.0, b.1)).then(a.2.total_cmp(&b.2)));
    let mut out = mesh.vertices.clone();
    for run in incident.chunk_by(|a, b| a.0 == b.0) {
        let v = run[0].0 as usize;
        let moved = run.iter().map(|r| r.2).fold(0.0, f64::max);
        let allowed = run.iter().map(|r| snap[r.1 as usize]).fold(2.0 * moved, f64::max);
        if allowed == 0.0 || v >= n {
            continue;
        }
        let mut qef = Qef::default();
        for g in run.chunk_by(|a, b| a.1 == b.1) {
            let plane = &groups[g[0].1 as usize];
            qef.add(plane.normal, plane.offset, 1.0);
        }
        let p = mesh.vertices[v];
        let x = qef.solve(p);
        if (x - p).length() <= allowed {
            out[v] = x;
        }
    }
    out
}
