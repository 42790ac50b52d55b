//! Where the slices lie, and their cross-sections.
//!
//! **Families.** A is cut by planes across the model's longer horizontal axis (so it has the
//! most slices), B across the other; both stand upright, each slice's 2D frame has x across
//! and y up (model z), which is the way the maker reads and assembles it.
//!
//! **Spacing.** One spacing for both families, planes centred on the model's extent like the
//! stacked method's layers. The default puts about [`SLICES_ALONG_LONGEST`] slices along the
//! longest horizontal extent, and never less than [`MIN_SPACING_PER_THICKNESS`] sheet
//! thicknesses apart, so that a slice's neighbouring slots leave material between them.

use glam::DVec3;
use platener_geom::polygon::interior_point;
use platener_geom::{Frame, GridError, Polygon, boolean};
use rayon::prelude::*;
use serde::Serialize;

use crate::assembly::Inside;
use crate::cuttable::Rule;
use crate::mesh::Mesh;
use crate::slicing::{AxisChoice, SlicePlan, Sliced, fill, slice};
use crate::stacked::keep_cuttable;

/// Slices along the longest horizontal extent by default.
pub const SLICES_ALONG_LONGEST: f64 = 10.0;
/// Slices are at least this many sheet thicknesses apart (the 3 t between slots).
pub const MIN_SPACING_PER_THICKNESS: f64 = 3.0;

/// How far inside a slab's faces its outer sections are taken, mm: a face exactly on a
/// model's flat side would take the section of the side itself.
pub const FACE_INSET: f64 = 0.01;

/// One family of parallel slices.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Family {
    /// `A` or `B`.
    pub letter: char,
    /// Where its planes are: `frame.n` is the family's normal (horizontal), x across, y up;
    /// plane `k` lies at local z = `plan.plane(k)`.
    pub plan: SlicePlan,
}

impl Family {
    /// Number of slices (planes).
    pub fn count(&self) -> usize {
        self.plan.count
    }

    /// Height of slice `k`'s plane along the family's normal, from the model's origin.
    pub fn offset(&self, k: usize) -> f64 {
        self.plan.frame.origin.dot(self.plan.frame.n) + self.plan.plane(k)
    }

    /// The part frame of slice `k` in sheets `thickness` thick: the slab from local z 0 to
    /// `thickness` is centred on the slice's plane.
    pub fn slab(&self, k: usize, thickness: f64) -> Frame {
        self.plan.frame.shifted(self.plan.plane(k) - thickness / 2.0)
    }
}

/// The default spacing for a model sliced from sheets `thickness` thick.
pub fn default_spacing(mesh: &Mesh, thickness: f64) -> f64 {
    let (lo, hi) = extent(mesh);
    let longest = (hi.x - lo.x).max(hi.y - lo.y);
    (longest / SLICES_ALONG_LONGEST).max(MIN_SPACING_PER_THICKNESS * thickness)
}

/// The two families, planes `spacing` apart; `None` for a model without triangles.
pub fn families(mesh: &Mesh, spacing: f64) -> Option<[Family; 2]> {
    if mesh.triangles.is_empty() || !(spacing.is_finite() && spacing > 0.0) {
        return None;
    }
    let (lo, hi) = extent(mesh);
    let (first, second) = if hi.x - lo.x >= hi.y - lo.y {
        (DVec3::X, DVec3::Y)
    } else {
        (DVec3::Y, DVec3::X)
    };
    let family = |letter, n: DVec3| {
        let (a, b) = (lo.dot(n), hi.dot(n));
        let count = (((b - a) / spacing).round() as usize).max(1);
        let base = a + (b - a - count as f64 * spacing) / 2.0;
        Family {
            letter,
            plan: SlicePlan {
                frame: Frame::on_plane(n * base, n),
                thickness: spacing,
                count,
                choice: AxisChoice::Given,
            },
        }
    };
    Some([family('A', first), family('B', second)])
}

/// `material` of slice `k` of `family` with the holes that are the model's hollows filled:
/// a hole whose middle has the model's surface on both sides along the family's normal is
/// enclosed (a hull below its deck, a box's inside), and a slice of a hollow model would
/// otherwise be a ring of walls too thin to cut. A hole open along the normal (a torus's
/// middle, a handle's loop) is the model's shape and stays.
fn fill_cavities(material: Vec<Polygon>, family: &Family, k: usize, inside: &Inside<'_>) -> Vec<Polygon> {
    let plane = family.plan.frame.shifted(family.plan.plane(k));
    let axis = if family.plan.frame.n.x.abs() > 0.5 { 0 } else { 1 };
    material
        .into_iter()
        .map(|mut p| {
            p.holes.retain(|hole| {
                interior_point(hole).is_none_or(|q| inside.crossings(plane.to_model_2d(q), axis).contains(&0))
            });
            p
        })
        .collect()
}

/// The bounds of the vertices triangles use.
fn extent(mesh: &Mesh) -> (DVec3, DVec3) {
    let (mut lo, mut hi) = (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY));
    for t in &mesh.triangles {
        for &v in t {
            let p = mesh.vertices[v as usize];
            lo = lo.min(p);
            hi = hi.max(p);
        }
    }
    (lo, hi)
}

/// Every slice's islands, and the pieces of sections too small to cut.
#[derive(Debug, Clone, Default)]
pub struct Sections {
    /// Per family, per slice, its islands (normalised, ordered by their lowest corner).
    pub islands: [Vec<Vec<Polygon>>; 2],
    /// `(family, slice, area)` of islands too small to cut.
    pub too_small: Vec<(usize, usize, f64)>,
}

/// The material of every slice of sheets `thickness` thick, split into islands `rule` keeps:
/// the model's cross-sections at the slab's mid-plane and at both its faces (a hair inside,
/// [`FACE_INSET`]), intersected, so a slice never stands out of the model where its surface
/// runs slanted to the slice (the hull's ends, the top of a dome).
pub fn sections(
    mesh: &Mesh,
    families: &[Family; 2],
    thickness: f64,
    tolerance: f64,
    rule: &Rule,
) -> Result<Sections, GridError> {
    let mut out = Sections::default();
    let face = (thickness / 2.0 - FACE_INSET).max(0.0);
    let inside = Inside::new(&mesh.vertices, &mesh.triangles);
    for (f, family) in families.iter().enumerate() {
        let planes: Vec<Sliced> = [0.0, -face, face]
            .into_iter()
            .map(|d| {
                let plan = SlicePlan {
                    frame: family.plan.frame.shifted(d),
                    ..family.plan
                };
                slice(mesh, &plan, tolerance)
            })
            .collect();
        let per: Vec<(Vec<Polygon>, Vec<Polygon>)> = (0..family.count())
            .into_par_iter()
            .map(|k| {
                let mut material = fill(&planes[0].loops[k])?;
                for other in &planes[1..] {
                    material = boolean::intersection(&material, &fill(&other.loops[k])?)?;
                }
                keep_cuttable(fill_cavities(material, family, k, &inside), rule)
            })
            .collect::<Result<_, _>>()?;
        for (k, (kept, small)) in per.into_iter().enumerate() {
            out.islands[f].push(kept);
            out.too_small.extend(small.iter().map(|p| (f, k, p.area())));
        }
    }
    Ok(out)
}
