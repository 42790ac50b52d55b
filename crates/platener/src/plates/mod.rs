//! Step `plates` (the thesis' InherentPlates, ExtrudedPlates and RemoveContainedPlates): the
//! flat plates the model can be rebuilt from, and a report of which faces became plates and why
//! the others did not.
//!
//! 1. [`inherent`]: pairs of parallel shapes facing apart, a sheet thickness apart, give a plate
//!    where they overlap; what is left of each shape may still pair with another.
//! 2. Leftover shapes are extruded inwards by the extrusion thickness (a solid block becomes a
//!    hollow hull), unless the mode is inherent-only.
//! 3. [`overlap`]: plates inside another plate's volume are removed, overlapping ones trimmed so
//!    no volume is claimed twice; [`rejoin`]: coplanar pieces split by a plate passing through
//!    them become one plate again.
//! 4. [`corners`]: plates that end short of a wall they meet through a rounded or chamfered
//!    corner grow up to it.
//! 5. [`coverage`]: per shape, which plates use it or why none does.

mod corners;
mod coverage;
mod features;
mod inherent;
mod overlap;
mod pairs;
mod rejoin;
pub mod stock;
#[cfg(test)]
mod tests;

use glam::DVec3;
use platener_geom::slab::Slab;
use platener_geom::{Frame, GridError, Polygon, polygon};
use serde::Serialize;

use crate::context::{StepContext, WarningKind};
use crate::error::{Error, ModelProblem, Result};
use crate::mesh::Mesh;
use crate::read::Model;
use crate::settings::{PlateMode, Settings};
use crate::shapes::Shapes;

pub use coverage::{Coverage, Rejection, ShapeUse, ThicknessShare};
pub(crate) use features::builder;
pub use features::{Elevation, Feature, Side};

/// How a plate was found.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum PlateKind {
    /// Between two opposite faces of the model.
    Inherent,
    /// A face extruded inwards by the extrusion thickness.
    Extruded,
}

/// A flat plate: an outline in a frame's plane, extruded from local z = 0 to the thickness.
#[derive(Debug, Clone, Serialize)]
pub struct Plate {
    /// How it was found.
    pub kind: PlateKind,
    /// Sheet thickness in mm (one of the offered ones, or the extrusion thickness).
    pub thickness: f64,
    /// Where the plate sits: `frame.to_model((x, y, z))` for z in [0, thickness].
    pub frame: Frame,
    /// Outline and holes in the frame's plane.
    pub polygon: Polygon,
    /// Area of the outline in mm².
    pub area: f64,
    /// The planar shapes (indices into the `shapes` snapshot) it was made from.
    pub shapes: Vec<u32>,
}

impl Plate {
    /// The plate as a slab, for volume questions.
    pub fn slab(&self) -> Slab {
        self.slab_of(self.polygon.clone())
    }

    /// Another outline in the plate's plane (its part with joints, a joint region) as a slab
    /// of its thickness.
    pub fn slab_of(&self, polygon: Polygon) -> Slab {
        Slab {
            frame: self.frame,
            polygon,
            thickness: self.thickness,
        }
    }

    /// Axis-aligned bounds of the plate's volume in the model.
    pub fn bounds(&self) -> (DVec3, DVec3) {
        self.bounds_of(&self.polygon)
    }

    /// The model-space box of another outline in the plate's plane (its part with joints),
    /// as a slab of its thickness.
    pub fn bounds_of(&self, outline: &Polygon) -> (DVec3, DVec3) {
        platener_geom::slab::extruded_bounds(&self.frame, &outline.outer, self.thickness)
    }

    /// The plate's volume in mm³.
    pub fn volume(&self) -> f64 {
        self.area * self.thickness
    }
}

/// The snapshot of step `plates`.
#[derive(Debug, Clone, Serialize)]
pub struct Plates {
    /// The plates: inherent first, then extruded, each largest first.
    pub plates: Vec<Plate>,
    /// Which shapes became plates and why the others did not.
    pub coverage: Coverage,
    /// Plates removed because another plate's volume contained them.
    pub contained_removed: usize,
    /// Plates trimmed because they overlapped a plate found earlier.
    pub trimmed: usize,
    /// Plates made whole again after a plate passing through had split them.
    pub rejoined: usize,
    /// Plates grown across a rounded or chamfered corner to the plate they meet there.
    pub corners_closed: usize,
    /// Features on one face of a plate (engraved or embossed text, pockets, standoffs), plate
    /// by plate; empty unless `--features engrave`.
    pub features: Vec<Feature>,
    /// Each overlap trimming resolved, in the order it did: a record for the debug view only
    /// (the plan and its report do not read it).
    pub overlaps: Vec<Overlap>,
}

impl Plates {
    /// Refuses plates no sheet holds, right after plate finding: a 1.5 m workbench frame
    /// spent minutes in joints and nesting to say what its plates already show (issue 29).
    /// Conservative: a plate shrunk by its thickness on every side (the most a joint trims)
    /// must still fit no sheet.
    pub fn fit_sheets(&self, cut: &crate::plan::CutSettings) -> Result<()> {
        for (k, p) in self.plates.iter().enumerate() {
            let what = format!("plate {} of the model", k + 1);
            if let Some(message) = cut.oversize(&what, &p.polygon.outer, -p.thickness) {
                return Err(Error::Setting { name: "sheet", message });
            }
        }
        Ok(())
    }
}

/// One overlap between two plates and how it was resolved: the lower-ranked plate gave up
/// the columns of its outline that meet the higher-ranked plate's volume. Plates are named
/// by the shapes they were made from, since trimming and rejoining renumber them after.
#[derive(Debug, Clone, Serialize)]
pub struct Overlap {
    /// The shapes of the plate that gave way.
    pub trimmed: Vec<u32>,
    /// The shapes of the plate that kept the shared volume.
    pub by: Vec<u32>,
    /// The area the trimmed plate lost to it, mm².
    pub area: f64,
    /// What it gave up, in the trimmed plate's frame.
    pub claimed: Vec<Polygon>,
}

/// Whether a laser can sensibly cut this outline at this thickness: at least the area of the
/// smallest part ([`crate::cuttable::Rule`], or `min_area` when that is more), and on average
/// at least as wide as the sheet is thick (2·area / perimeter), so thin curved walls do not
/// turn into hundreds of slivers. A cheap first sieve: the part's width is checked against the
/// rule once its joints are cut (`parts`).
pub(crate) fn cuttable(p: &Polygon, thickness: f64, min_area: f64) -> std::result::Result<(), Rejection> {
    let area = p.area();
    if area < crate::cuttable::Rule::for_sheet(thickness, 0.0, min_area).min_area {
        return Err(Rejection::TooSmall { area });
    }
    let perimeter = polygon::perimeter(&p.outer) + p.holes.iter().map(|h| polygon::perimeter(h)).sum::<f64>();
    let width = 2.0 * area / perimeter;
    if width < thickness {
        return Err(Rejection::Sliver { width });
    }
    Ok(())
}

/// Maps a polygon from one frame's plane to another's (through the model), keeping plan.json's
/// orientation (outer counter-clockwise).
pub(crate) fn map_polygon(p: &Polygon, from: &Frame, to: &Frame) -> Polygon {
    let map = |r: &Vec<glam::DVec2>| r.iter().map(|q| to.to_2d(from.to_model_2d(*q))).collect();
    let mut out = Polygon {
        outer: map(&p.outer),
        holes: p.holes.iter().map(map).collect(),
    };
    out.normalize_orientation();
    out
}

/// Finds the plates of a model's shapes; the mesh gives the cross-sections that tell holes
/// from one-sided features, and its surface area the coverage share.
pub fn find_plates(shapes: &Shapes, mesh: &Mesh, center: DVec3, settings: &Settings) -> Result<Plates, GridError> {
    let ps = &settings.plates;
    let sections = features::Sections::new(mesh, settings.features);
    let mut found = inherent::find(shapes, &sections, center, settings)?;
    if ps.mode == PlateMode::InherentAndExtruded {
        inherent::extrude_leftovers(shapes, &sections, &mut found, settings)?;
    }
    let detected_use: Vec<f64> = shapes
        .shapes
        .iter()
        .zip(&found.remaining)
        .map(|(s, rest)| (s.area - polygon::total_area(rest)).max(0.0))
        .collect();
    let clearance = 1e-3;
    let resolved = overlap::resolve(found.plates, ps.min_area, clearance)?;
    let (contained, trimmed) = (resolved.contained, resolved.trimmed);
    let (mut plates, rejoined) = rejoin::rejoin(resolved.plates, ps.parallel_angle_deg.to_radians(), clearance)?;
    plates.sort_by(|a, b| {
        (a.kind == PlateKind::Extruded)
            .cmp(&(b.kind == PlateKind::Extruded))
            .then(b.area.total_cmp(&a.area))
    });
    let coverage = coverage::report(
        shapes,
        &found.detail,
        &detected_use,
        &plates,
        mesh.surface_area,
        settings,
    );
    let features = features::assign(&found.features, &plates)?;
    Ok(Plates {
        plates,
        coverage,
        contained_removed: contained,
        trimmed,
        rejoined,
        corners_closed: 0,
        features,
        overlaps: resolved.overlaps,
    })
}

/// Step `plates`: the plates the model's shapes make, with the coverage report.
pub fn run(
    shapes: &Shapes,
    mesh: &Mesh,
    model: &Model,
    settings: &Settings,
    cx: &mut StepContext<'_>,
) -> Result<Plates> {
    cx.check_cancel()?;
    let center = (model.bounds.min + model.bounds.max) / 2.0;
    let off_grid = |e| Error::model(&model.name, ModelProblem::OffGrid(e));
    let mut plates = find_plates(shapes, mesh, center, settings).map_err(off_grid)?;
    let inside = crate::assembly::Inside::new(&mesh.vertices, &mesh.triangles);
    plates.corners_closed = corners::close(&mut plates.plates, &inside, 1e-3).map_err(off_grid)?;
    let offered = settings.offered_thicknesses();
    if let Some(why) = coverage::why_no_plates(&plates.coverage, settings.plates.min_area, &offered) {
        cx.warn(WarningKind::Plates, why);
    }
    for why in features::warnings(&plates.features, &plates.plates) {
        cx.warn(WarningKind::Features, why);
    }
    if let Some(thick) = stock::thick_stock(&plates.plates, &inside) {
        cx.warn(WarningKind::Plates, thick.message());
    }
    Ok(plates)
}
