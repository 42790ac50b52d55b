//! Step `coplanar` (the thesis' CoplanarFaces): groups connected faces that lie in one plane.
//!
//! Faces are grown into groups breadth-first across shared edges, starting from the largest
//! face not yet grouped. A face joins when its normal is within the coplanar angle of the
//! *seed's* normal (not its neighbour's): comparing with the neighbour would let a finely
//! faceted cylinder drift all the way round into one "plane".
//!
//! Welding decides which faces belong together; it does not decide where the plane is. A
//! group's normal and offset are fitted to the faces' *original* (unwelded) triangles
//! ([`PlaneFit`]: exact when they are coplanar, an area-weighted least-squares plane
//! otherwise), leaving out originals turned away from the group (what is left of a welded
//! bevel). Then each welded vertex is put back where the planes of the groups around it meet
//! ([`refit`]), so a bevelled box's corner returns to the exact corner of its three faces.

mod refit;

use std::collections::VecDeque;

use glam::DVec3;
use platener_geom::plane_fit::PlaneFit;
use rayon::slice::ParallelSliceMut;
use serde::Serialize;

use crate::mesh::Mesh;
use crate::settings::Settings;

/// Connected faces in one plane.
#[derive(Debug, Clone, Serialize)]
pub struct PlanarGroup {
    /// The faces (mesh triangle indices), in the order they were reached.
    #[serde(skip)]
    pub faces: Vec<u32>,
    /// Unit normal (pointing out of the solid), fitted to the faces' original triangles.
    pub normal: DVec3,
    /// Plane offset: `normal · x` for points x on the plane (fitted like the normal).
    pub offset: f64,
    /// Total area in mm².
    pub area: f64,
}

/// The snapshot of step `coplanar`.
#[derive(Debug, Clone, Serialize)]
pub struct PlanarGroups {
    /// Groups, largest area first.
    pub groups: Vec<PlanarGroup>,
    /// The group of each mesh triangle.
    #[serde(skip)]
    pub face_group: Vec<u32>,
    /// Each mesh vertex moved onto the planes of the groups around it (see [`refit`]);
    /// outlines are drawn through these.
    #[serde(skip)]
    pub vertices: Vec<DVec3>,
    /// The angle used, in degrees.
    pub angle_deg: f64,
}

/// Groups the faces of `mesh` whose normals are within `angle` (radians) of their seed's.
pub fn group_faces(mesh: &Mesh, angle: f64) -> PlanarGroups {
    group_rest(mesh, angle, Fixed::default())
}

/// Groups decided before growth (the classifier's primitives): their faces and planes, and
/// how far a vertex on one of them may move onto its plane even where welding did not move
/// it (a texture's depth; 0 keeps the welding rule of [`refit`]).
#[derive(Debug, Clone, Default)]
pub struct Fixed {
    /// The groups, each with its faces, plane and area.
    pub groups: Vec<PlanarGroup>,
    /// How far each group's vertices may be moved onto its plane, mm.
    pub snap: Vec<f64>,
}

/// Groups the faces no group of `fixed` holds as [`group_faces`] does, then ranks every
/// group (fixed or grown) largest first and refits the vertices.
pub fn group_rest(mesh: &Mesh, angle: f64, fixed: Fixed) -> PlanarGroups {
    let n = mesh.triangles.len();
    let cos_max = angle.cos();
    let mut face_group = vec![u32::MAX; n];
    for (id, g) in fixed.groups.iter().enumerate() {
        g.faces.iter().for_each(|&f| face_group[f as usize] = id as u32);
    }
    let mut snap = fixed.snap;
    let mut groups = fixed.groups;
    snap.resize(groups.len(), 0.0);
    grow(mesh, cos_max, &mut face_group, &mut groups);
    snap.resize(groups.len(), 0.0);
    // Largest first; ties by smallest face index, so the order is deterministic.
    let mut ranked: Vec<usize> = (0..groups.len()).collect();
    let key = |g: &PlanarGroup| g.faces.iter().copied().min().unwrap_or(u32::MAX);
    ranked.sort_by(|&a, &b| {
        groups[b]
            .area
            .total_cmp(&groups[a].area)
            .then(key(&groups[a]).cmp(&key(&groups[b])))
    });
    let mut rank_of = vec![0u32; groups.len()];
    for (rank, &g) in ranked.iter().enumerate() {
        rank_of[g] = rank as u32;
    }
    face_group.iter_mut().for_each(|g| *g = rank_of[*g as usize]);
    let snap: Vec<f64> = ranked.iter().map(|&g| snap[g]).collect();
    let mut slots: Vec<Option<PlanarGroup>> = groups.into_iter().map(Some).collect();
    let groups: Vec<PlanarGroup> = ranked.iter().filter_map(|&g| slots[g].take()).collect();
    PlanarGroups {
        vertices: refit::refit_vertices(mesh, &groups, &face_group, &snap),
        groups,
        face_group,
        angle_deg: angle.to_degrees(),
    }
}

/// Grows a group from each face not yet grouped (largest first) across shared edges.
fn grow(mesh: &Mesh, cos_max: f64, face_group: &mut [u32], groups: &mut Vec<PlanarGroup>) {
    let mut order: Vec<u32> = (0..face_group.len() as u32)
        .filter(|&f| face_group[f as usize] == u32::MAX)
        .collect();
    order.par_sort_unstable_by(|&a, &b| {
        mesh.areas[b as usize]
            .total_cmp(&mesh.areas[a as usize])
            .then(a.cmp(&b))
    });
    let mut queue = VecDeque::new();
    for &seed in &order {
        if face_group[seed as usize] != u32::MAX {
            continue;
        }
        let id = groups.len() as u32;
        let seed_normal = mesh.normals[seed as usize];
        face_group[seed as usize] = id;
        let mut faces = vec![seed];
        queue.push_back(seed);
        while let Some(f) = queue.pop_front() {
            for &e in &mesh.topology.face_edges[f as usize] {
                for &fc in mesh.topology.edge_corners(e) {
                    let g = fc / 3;
                    if face_group[g as usize] == u32::MAX && mesh.normals[g as usize].dot(seed_normal) >= cos_max {
                        face_group[g as usize] = id;
                        faces.push(g);
                        queue.push_back(g);
                    }
                }
            }
        }
        groups.push(summarise(mesh, faces, cos_max));
    }
}

/// A group's area (of its welded faces) and plane (of its original faces). Originals whose
/// normal is more than twice the coplanar angle (`cos_max` its cosine) from the welded faces'
/// mean normal (at least 0.5°) are left out of the fit: welding joined them to the group, but their plane is
/// another one (a collapsed bevel's remnant).
fn summarise(mesh: &Mesh, faces: Vec<u32>, cos_max: f64) -> PlanarGroup {
    let (mut welded, mut area) = (PlaneFit::default(), 0.0);
    for &f in &faces {
        welded.add(mesh.corners(f as usize));
        area += mesh.areas[f as usize];
    }
    let fallback = mesh.normals[faces[0] as usize];
    let welded_plane = welded.plane();
    let mean = welded_plane.map_or(fallback, |(n, _)| n);
    let cos_keep = (2.0 * cos_max.clamp(-1.0, 1.0).acos()).max(0.5f64.to_radians()).cos();
    let mut original = PlaneFit::default();
    for &f in &faces {
        let o = mesh.original[f as usize];
        let n = (o[1] - o[0]).cross(o[2] - o[0]).normalize_or_zero();
        if n.dot(mean) >= cos_keep {
            original.add(o);
        }
    }
    let corners = mesh.corners(faces[0] as usize);
    let (normal, offset) = original
        .plane()
        .or(welded_plane)
        .unwrap_or((fallback, fallback.dot(corners[0])));
    PlanarGroup {
        faces,
        normal,
        offset,
        area,
    }
}

/// Step `coplanar`: the mesh's faces grouped into connected planar groups.
pub fn run(mesh: &Mesh, settings: &Settings) -> PlanarGroups {
    group_faces(mesh, settings.coplanar_angle_deg.to_radians())
}
