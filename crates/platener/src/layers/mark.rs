//! Which triangles the layers build, and which plate face they rest on.
//!
//! A triangle is *marked* when no plate builds it (its planar group became no plate) and it
//! is a sphere's, a small solid cylinder's (too narrow to wrap: stacked discs,
//! [`crate::classify::groups::stacked_instead`]) or nothing's (a freeform). Planes, cones and
//! other cylinders left without a plate are details the plates leave out (a small boss, a
//! rounded edge), not volumes to rebuild in layers.

use glam::DVec3;

use crate::classify::SurfaceKind;
use crate::classify::groups::stacked_instead;
use crate::coplanar::PlanarGroups;
use crate::mesh::Mesh;
use crate::plates::Plates;
use crate::settings::Settings;
use crate::shapes::Shapes;

/// What decides which triangles are marked: the classified mesh and the plates made of it.
#[derive(Clone, Copy)]
pub struct Surface<'a> {
    /// Step `mesh`.
    pub mesh: &'a Mesh,
    /// Step `classify`.
    pub found: &'a crate::classify::Classification,
    /// The planar groups `classify` made.
    pub groups: &'a PlanarGroups,
    /// Step `shapes`.
    pub shapes: &'a Shapes,
    /// Step `plates`.
    pub plates: &'a Plates,
}

/// The marked triangles and their area.
#[derive(Debug, Clone)]
pub(crate) struct Marked {
    /// Per mesh triangle, whether the layers build it.
    pub faces: Vec<bool>,
    /// Their area, mm².
    pub area: f64,
}

/// The triangles of `mesh` no plate builds that a sphere, a small solid cylinder or nothing
/// explains.
pub(crate) fn marked(on: &Surface<'_>, settings: &Settings) -> Marked {
    let (mesh, found, groups) = (on.mesh, on.found, on.groups);
    let built = built_groups(groups, on.shapes, on.plates);
    let stacked: Vec<bool> = found
        .primitives
        .iter()
        .map(|p| p.shape.kind() == SurfaceKind::Sphere || stacked_instead(p, settings))
        .collect();
    let faces: Vec<bool> = (0..mesh.triangles.len())
        .map(|f| {
            let primitive = found.labels.get(f).copied().flatten();
            let in_plate = groups.face_group.get(f).is_some_and(|&g| built[g as usize]);
            !in_plate && primitive.is_none_or(|p| stacked.get(p as usize).copied().unwrap_or(false))
        })
        .collect();
    let area = faces.iter().zip(&mesh.areas).filter(|(m, _)| **m).map(|(_, a)| a).sum();
    Marked { faces, area }
}

/// Per planar group, whether a plate was made from it.
pub(crate) fn built_groups(groups: &PlanarGroups, shapes: &Shapes, plates: &Plates) -> Vec<bool> {
    let mut built = vec![false; groups.groups.len()];
    for used in &plates.coverage.shapes {
        if !used.plates.is_empty()
            && let Some(shape) = shapes.shapes.get(used.shape as usize)
            && let Some(b) = built.get_mut(shape.group as usize)
        {
            *b = true;
        }
    }
    built
}

/// The plate face the marked surface meets along the longest boundary: its planar group and
/// that length, mm. A dome on a lid meets the lid's top face all round, so the layers are laid
/// parallel to it and start on it.
pub(crate) fn resting_face(mesh: &Mesh, marked: &[bool], groups: &PlanarGroups, built: &[bool]) -> Option<(u32, f64)> {
    let mut shared = vec![0.0; groups.groups.len()];
    let topology = &mesh.topology;
    for (e, [a, b]) in topology.edges.iter().enumerate() {
        let &[c, d] = topology.edge_corners(e as u32) else {
            continue;
        };
        let (f, g) = ((c / 3) as usize, (d / 3) as usize);
        let other = match (marked[f], marked[g]) {
            (true, false) => g,
            (false, true) => f,
            _ => continue,
        };
        let group = groups.face_group[other] as usize;
        if built[group] {
            shared[group] += mesh.vertices[*a as usize].distance(mesh.vertices[*b as usize]);
        }
    }
    shared
        .iter()
        .enumerate()
        .filter(|(_, l)| **l > 0.0)
        .max_by(|a, b| a.1.total_cmp(b.1).then(b.0.cmp(&a.0)))
        .map(|(g, l)| (g as u32, *l))
}

/// The corners of the marked triangles (shared corners once per triangle).
fn corners<'a>(mesh: &'a Mesh, marked: &'a [bool]) -> impl Iterator<Item = DVec3> + 'a {
    mesh.triangles
        .iter()
        .zip(marked)
        .filter(|(_, m)| **m)
        .flat_map(|(t, _)| t.iter().map(|&v| mesh.vertices[v as usize]))
}

/// The extent of the marked triangles' vertices along `up`, from `origin`: (lowest, highest).
pub(crate) fn extent(mesh: &Mesh, marked: &[bool], origin: DVec3, up: DVec3) -> Option<(f64, f64)> {
    corners(mesh, marked)
        .map(|p| (p - origin).dot(up))
        .fold(None, |range, h| {
            Some(range.map_or((h, h), |(lo, hi): (f64, f64)| (lo.min(h), hi.max(h))))
        })
}

/// The centre of the marked triangles' bounding box.
pub(crate) fn centre(mesh: &Mesh, marked: &[bool]) -> Option<DVec3> {
    corners(mesh, marked)
        .fold(None, |b, p| {
            Some(b.map_or((p, p), |(lo, hi): (DVec3, DVec3)| (lo.min(p), hi.max(p))))
        })
        .map(|(lo, hi)| (lo + hi) / 2.0)
}
