//! The classifier's conversion: primitives become the planar groups the plate method builds
//! on (issue 20, "Conversion").
//!
//! - A plane primitive is one group at its fitted plane, holding every triangle it explains:
//!   a textured wall becomes one flat group, its texture flattened onto the plane.
//! - A cylinder or cone becomes `n` facet groups, one per angular sector, each at the plane
//!   of a polygon with the circle's area ([`facet_distance`]): the plate method then finds
//!   them as narrow plates and the `bends` step wraps them into one bent part. Coaxial
//!   cylinders (a tube's outer and inner wall) share their sectors, so facets pair into
//!   plates of the wall's thickness.
//! - Spheres and what no primitive explains are grouped as the plate method groups them, and
//!   so is a solid cylinder too narrow to wrap ([`stacked_instead`]): step `layers` stacks
//!   them.
//! - So is a primitive whose triangles are mostly one exact planar group ([`fragmented`]):
//!   on a clean CAD model the exact faces are better than any fit, and RANSAC may lay a
//!   huge, nearly flat cylinder over a plate.
//!
//! Vertices of these groups are then moved onto their planes (by at most [`snap_distance`])
//! where the planes around them meet, so a sector's ragged triangle border becomes the
//! polygon's straight edge and a texture's corners the box's corners.

use std::f64::consts::{PI, TAU};

use glam::DVec3;
use platener_geom::plane_fit::PlaneFit;

use super::surface::{Surface, basis};
use super::{Classification, Primitive};
use crate::coplanar::{Fixed, PlanarGroup, PlanarGroups};
use crate::mesh::Mesh;
use crate::settings::Settings;

/// Fewest and most facets a curved primitive is cut into.
const FACETS: (usize, usize) = (8, 48);

/// One curved primitive's sectors: the frame they are measured in and their count.
#[derive(Debug, Clone, Copy)]
struct Sectors {
    axis: DVec3,
    /// A point on the axis (a cylinder's) or the apex (a cone's).
    origin: DVec3,
    u: DVec3,
    v: DVec3,
    n: usize,
}

impl Sectors {
    /// These sectors' frame made square to a nearly parallel `axis` (Gram–Schmidt, keeping
    /// u and v's senses, so the sectors keep their angles whichever way the axis points).
    fn turned_to(self, axis: DVec3) -> Self {
        let u = (self.u - axis * axis.dot(self.u)).normalize();
        let v = (self.v - axis * axis.dot(self.v) - u * u.dot(self.v)).normalize();
        Self { u, v, ..self }
    }

    fn of(&self, p: DVec3) -> usize {
        let d = p - self.origin;
        let a = d.dot(self.v).atan2(d.dot(self.u)).rem_euclid(TAU);
        ((a / TAU * self.n as f64) as usize).min(self.n - 1)
    }

    /// The unit radial direction through the middle of sector `k`.
    fn radial(&self, k: usize) -> DVec3 {
        let a = (k as f64 + 0.5) * TAU / self.n as f64;
        self.u * a.cos() + self.v * a.sin()
    }
}

/// The distance from the axis of the facets of an `n`-gon with the area of a circle of
/// `radius`: the facets then cut as much off the circle as they add, so volumes and plate
/// thicknesses stay the circle's.
pub fn facet_distance(radius: f64, n: usize) -> f64 {
    let half = PI / n as f64;
    radius * (PI / (n as f64 * half.tan())).sqrt()
}

/// How many facets a circle of `radius` needs so that no facet lies further than `tolerance`
/// from it, within [`FACETS`].
pub fn facet_count(radius: f64, tolerance: f64) -> usize {
    let c = (1.0 - tolerance / radius).clamp(-1.0, 1.0);
    let n = if c <= 0.0 {
        FACETS.0 as f64
    } else {
        (PI / c.acos()).ceil()
    };
    (n as usize).clamp(FACETS.0, FACETS.1)
}

/// How far a vertex of a classified group may move onto its plane: twice the classifier's ε
/// (the most a texture or noise strays from its primitive, and the plane's own fitting
/// error) plus the facets' deviation from a curve, `tolerance`.
pub fn snap_distance(c: &Classification, tolerance: f64) -> f64 {
    2.0 * c.thresholds.eps + tolerance
}

/// Whether `p` is a small solid cylinder the classifier stacks as discs (step `layers`)
/// instead of wrapping it: the material fills it, and a bend of the material's style
/// (`--bend`) turning from one of its facets to the next needs a zone wider than a facet
/// (3 mm plywood: a radius under about 26 mm), or a radius larger than the wall's own. With
/// bending off, never: its facets are
/// jointed plates as before.
pub fn stacked_instead(p: &Primitive, settings: &Settings) -> bool {
    let Surface::Cylinder { radius, .. } = p.shape else {
        return false;
    };
    let material = settings.cut.material;
    let Some(style) = settings.bending.style(material) else {
        return false;
    };
    let t = settings.thinnest();
    let n = facet_count(radius, t / 2.0);
    let facet = 2.0 * facet_distance(radius, n) * (PI / n as f64).tan();
    // A wall wrapped round it curves at its own neutral radius, r − t/2: a hinge that needs
    // more (the straight flex's 5 t) cannot make it, though its zone fits a facet.
    let wraps = crate::hinge::design(style, material, t, TAU / n as f64, facet)
        .is_ok_and(|d| d.neutral_radius <= radius - t / 2.0 + 1e-9);
    p.outward && !wraps
}

/// The fixed groups of a classification (see the module doc), for [`crate::coplanar::group_rest`],
/// and the primitives they replace the exact groups of.
pub fn fixed_groups(mesh: &Mesh, c: &Classification, exact: &PlanarGroups, settings: &Settings) -> (Fixed, Vec<u32>) {
    let tolerance = settings.thinnest() / 2.0;
    let sectors = curved_sectors(mesh, &c.primitives, tolerance, c.thresholds.eps);
    let mut groups = Vec::new();
    let mut replaced = Vec::new();
    for (k, p) in c.primitives.iter().enumerate() {
        let pieces = sectors[k].map_or(1, |s| s.n);
        if !fragmented(mesh, p, exact, pieces) || stacked_instead(p, settings) {
            continue;
        }
        match (&p.shape, sectors[k]) {
            (Surface::Plane { normal, offset }, _) => groups.push(plane_group(mesh, p, *normal, *offset)),
            (shape @ (Surface::Cylinder { .. } | Surface::Cone { .. }), Some(s)) => {
                groups.extend(facet_groups(mesh, p, shape, &s));
            }
            _ => continue,
        }
        replaced.push(k as u32);
    }
    groups.retain(|g| !g.faces.is_empty());
    let snap = vec![snap_distance(c, tolerance); groups.len()];
    (Fixed { groups, snap }, replaced)
}

/// Why the classifier would change nothing on this model, decided before sampling and
/// RANSAC (issue 29: it cost every model a second or more and won on 1 of 53 real ones).
/// Primitives replace exact groups only where at least [`FINE_GROUPS`] of them split one
/// primitive finely ([`fragmented`]): a texture, noise or a fine tessellation, whose faces
/// are fragments: smaller than a sheet's thickness squared, or narrower than a sheet and
/// turning by less than [`SMOOTH_TURN_DEG`] into a neighbouring face (a facet strip of a
/// tessellated cylinder or sphere, not the rim of a plate, which turns by 90°). Drawn faces of
/// a CAD model or a low-poly figure are larger. With fewer than [`FINE_GROUPS`] fragments, or
/// fragments covering under [`FRAGMENT_SHARE`] of the surface, the exact faces stay exact and
/// the classifier's plan would be the plate method's: `Some(reason)`.
pub fn nothing_to_replace(mesh: &Mesh, exact: &PlanarGroups, thickness: f64) -> Option<String> {
    let smooth = smooth_neighbours(mesh, exact);
    let (mut count, mut area) = (0usize, 0.0);
    for (k, g) in exact.groups.iter().enumerate() {
        let (lo, hi) = platener_geom::boxes::bounds3(g.faces.iter().flat_map(|&f| mesh.corners(f as usize)));
        let width = g.area / (hi - lo).length().max(f64::MIN_POSITIVE);
        if g.area < thickness * thickness || (width < thickness && smooth[k]) {
            count += 1;
            area += g.area;
        }
    }
    let total: f64 = exact.groups.iter().map(|g| g.area).sum();
    let share = if total > 0.0 { area / total } else { 0.0 };
    (count < FINE_GROUPS || share < FRAGMENT_SHARE).then(|| {
        format!(
            "the model's faces are exact ({count} faces smaller than the sheet's thickness squared or narrower than \
             a sheet, {:.1} % of its surface): there is no texture, noise or fine tessellation for the classifier to \
             replace, so its plan would be the plate method's",
            100.0 * share
        )
    })
}

/// Two faces meeting at a turn below this (degrees) are one smooth surface tessellated.
pub const SMOOTH_TURN_DEG: f64 = 30.0;

/// Per exact group, whether it meets another group along an edge at a turn below
/// [`SMOOTH_TURN_DEG`].
fn smooth_neighbours(mesh: &Mesh, exact: &PlanarGroups) -> Vec<bool> {
    let mut smooth = vec![false; exact.groups.len()];
    let cos = SMOOTH_TURN_DEG.to_radians().cos();
    let topology = &mesh.topology;
    for e in 0..topology.edges.len() as u32 {
        let corners = topology.edge_corners(e);
        let [a, b] = match corners {
            [a, b] => [a / 3, b / 3].map(|f| exact.face_group[f as usize] as usize),
            _ => continue,
        };
        if a != b
            && let (Some(ga), Some(gb)) = (exact.groups.get(a), exact.groups.get(b))
            && ga.normal.dot(gb.normal) > cos
        {
            smooth[a] = true;
            smooth[b] = true;
        }
    }
    smooth
}

/// The least share of the surface in fragments (see [`nothing_to_replace`]) for which the
/// classifier runs: a 96-sided peg of radius 15 mm on a 120 × 90 × 50 mm box is 4.5 % (the
/// classifier stacks it as discs); the CAD plates of the corpus that it cannot improve are
/// mostly below 3 %.
pub const FRAGMENT_SHARE: f64 = 0.03;

/// Whether the exact planar groups (those the plate method uses) split `p`'s triangles
/// finely: at least [`FINE_GROUPS`] of them, none holding [`FRAGMENTED`] of its area, on
/// average (weighted by area) smaller than a quarter of the pieces the primitive would be
/// cut into (`pieces`: 1 for a plane, its sectors for a curve). That is a texture, noise or
/// a fine tessellation, which the primitive should replace. A primitive that is mostly one
/// exact face (a CAD plate, or a nearly flat "cylinder" RANSAC laid over one), or a few
/// facets someone drew (a low-poly lamp shade), is left to the exact groups, which keep the
/// model's own edges.
fn fragmented(mesh: &Mesh, p: &Primitive, exact: &PlanarGroups, pieces: usize) -> bool {
    let mut by_group: Vec<(u32, f64)> = p
        .triangles
        .iter()
        .map(|&f| (exact.face_group[f as usize], mesh.areas[f as usize]))
        .collect();
    by_group.sort_unstable_by_key(|x| x.0);
    let areas: Vec<f64> = by_group
        .chunk_by(|a, b| a.0 == b.0)
        .map(|run| run.iter().map(|x| x.1).sum())
        .collect();
    let total: f64 = areas.iter().sum();
    let largest = areas.iter().copied().fold(0.0, f64::max);
    let typical = areas.iter().map(|a| a * a).sum::<f64>() / total.max(f64::MIN_POSITIVE);
    largest < FRAGMENTED * p.area && typical < p.area / (4.0 * pieces as f64) && areas.len() >= FINE_GROUPS
}

/// The fewest exact groups a primitive must span to replace them: fewer are facets someone
/// chose (a low-poly lamp's triangles, a 12-sided tube), not a texture or a fine tessellation.
pub const FINE_GROUPS: usize = 16;

/// A primitive whose largest exact group holds less than this share of its area replaces
/// the exact groups (see [`fragmented`]).
pub const FRAGMENTED: f64 = 0.5;

/// A plane primitive's group at the plane of its own triangles (area-weighted least
/// squares, [`PlaneFit`]): RANSAC's refit takes in samples near the plane's border whose
/// normals lean towards it, and may sit a fraction of ε off a face that is exactly flat. The
/// normal faces the way the triangles face.
fn plane_group(mesh: &Mesh, p: &Primitive, normal: DVec3, offset: f64) -> PlanarGroup {
    let mut fit = PlaneFit::default();
    p.triangles.iter().for_each(|&f| fit.add(mesh.corners(f as usize)));
    let (normal, offset) = fit.plane().unwrap_or((normal, offset));
    let facing: DVec3 = p
        .triangles
        .iter()
        .map(|&f| mesh.normals[f as usize] * mesh.areas[f as usize])
        .sum();
    let sign = if facing.dot(normal) < 0.0 { -1.0 } else { 1.0 };
    PlanarGroup {
        faces: p.triangles.clone(),
        normal: normal * sign,
        offset: offset * sign,
        area: p.area,
    }
}

/// A curved primitive's triangles split by sector, each sector at its facet's plane.
fn facet_groups(mesh: &Mesh, p: &Primitive, shape: &Surface, s: &Sectors) -> Vec<PlanarGroup> {
    let mut faces: Vec<Vec<u32>> = vec![Vec::new(); s.n];
    let mut areas = vec![0.0; s.n];
    for &f in &p.triangles {
        let [a, b, c] = mesh.corners(f as usize);
        let k = s.of((a + b + c) / 3.0);
        faces[k].push(f);
        areas[k] += mesh.areas[f as usize];
    }
    let mut out = Vec::with_capacity(s.n);
    for (k, (faces, area)) in faces.into_iter().zip(areas).enumerate() {
        let (normal, offset) = facet_plane(shape, s, k, p.outward);
        out.push(PlanarGroup {
            faces,
            normal,
            offset,
            area,
        });
    }
    out
}

/// The plane of facet `k` of a cylinder or cone, its normal out of the solid.
fn facet_plane(shape: &Surface, s: &Sectors, k: usize, outward: bool) -> (DVec3, f64) {
    let d = s.radial(k);
    let side = if outward { 1.0 } else { -1.0 };
    match *shape {
        Surface::Cylinder { radius, .. } => {
            let at = s.origin + d * facet_distance(radius, s.n);
            (d * side, (d * side).dot(at))
        }
        Surface::Cone { half_angle, .. } => {
            // The facet holds the apex, the tangent across the sector, and the line up the
            // cone at the facet's distance from the axis.
            let scale = facet_distance(1.0, s.n);
            let along = s.axis + d * half_angle.tan() * scale;
            let normal = along.cross(s.axis.cross(d)).normalize();
            let normal = if normal.dot(d) * side < 0.0 { -normal } else { normal };
            (normal, normal.dot(s.origin))
        }
        _ => (d, d.dot(s.origin)),
    }
}

/// The sectors of every cylinder and cone (`None` for planes and spheres). Coaxial ones (a
/// tube's two walls, a shade's two cones) share the angular frame and the facet count of the
/// first found, counted for the widest of them, so their facets pair up into plates.
fn curved_sectors(mesh: &Mesh, prims: &[Primitive], tolerance: f64, eps: f64) -> Vec<Option<Sectors>> {
    let axes: Vec<Option<(DVec3, DVec3, f64)>> = prims.iter().map(|p| axis_of(mesh, p)).collect();
    let mut out: Vec<Option<Sectors>> = vec![None; prims.len()];
    for k in 0..prims.len() {
        let Some((axis, origin, _)) = axes[k] else {
            continue;
        };
        let on_axis = |j: usize| axes[j].filter(|&(a, o, _)| coaxial(axis, origin, a, o, eps));
        let widest = (0..prims.len()).filter_map(on_axis).map(|x| x.2).fold(0.0, f64::max);
        let shared = (0..k).find_map(|j| out[j].filter(|_| on_axis(j).is_some()));
        out[k] = Some(match shared {
            Some(s) => Sectors {
                axis,
                origin,
                ..s.turned_to(axis)
            },
            None => frame(axis, origin, facet_count(widest, tolerance)),
        });
    }
    out
}

/// A curved primitive's axis, a point on it (a cone's apex) and its widest radius: a
/// cylinder's radius, a cone's at the furthest corner of its triangles.
fn axis_of(mesh: &Mesh, p: &Primitive) -> Option<(DVec3, DVec3, f64)> {
    match p.shape {
        Surface::Cylinder { axis, point, radius } => Some((axis, point, radius)),
        Surface::Cone { apex, axis, .. } => {
            let corners = p.triangles.iter().flat_map(|&f| mesh.corners(f as usize));
            let widest = corners
                .map(|x| {
                    let d = x - apex;
                    (d - axis * d.dot(axis)).length()
                })
                .fold(0.0, f64::max);
            Some((axis, apex, widest))
        }
        _ => None,
    }
}

/// Whether two axes are one line: parallel within 1° and within ε of each other.
fn coaxial(a: DVec3, p: DVec3, b: DVec3, q: DVec3, eps: f64) -> bool {
    let parallel = a.cross(b).length() <= 1f64.to_radians().sin();
    let d = q - p;
    parallel && (d - a * d.dot(a)).length() <= eps
}

/// Sectors around `axis` through `origin`.
fn frame(axis: DVec3, origin: DVec3, n: usize) -> Sectors {
    let (u, v) = basis(axis);
    Sectors { axis, origin, u, v, n }
}
