//! The classifier method's detection (issue 20; the thesis' chapter 12, GeometryClassification):
//! which primitives a model is made of, even when its surfaces carry a texture or noise.
//!
//! 1. [`sample`]: points with normals spread over the surface by area, each keeping its
//!    triangle (the thesis' LabelledShapes);
//! 2. [`ransac`]: planes, cylinders, spheres and cones by efficient RANSAC (Schnabel, Wahl
//!    and Klein 2007), each refitted by least squares;
//! 3. [`label`]: every triangle mapped to the primitive that explains it;
//! 4. [`volumes`]: the thesis' prism and box classifiers (parallel congruent planes, a lateral
//!    surface between them), solid cylinders with their caps, spheres;
//! 5. [`graph`]: volumes, connectors and freeforms with their adjacency.
//!
//! Every threshold follows from the model's size, the sampling density and the sheet
//! thickness ([`Thresholds::derive`]; docs/classifier.md gives the formulas and the measured
//! accuracy and speed). A seed makes the run reproducible to the bit.

pub mod bitmap;
pub mod fit;
pub mod graph;
pub mod groups;
pub mod label;
pub mod ransac;
pub mod sample;
pub mod surface;
pub mod volumes;

#[cfg(test)]
mod tests;

use serde::Serialize;

use crate::mesh::Mesh;
pub use graph::{Graph, Node, NodeKind};
pub use surface::{Surface, SurfaceKind};
pub use volumes::{Volume, VolumeKind};

/// What the classifier needs to know besides the mesh.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ClassifySettings {
    /// The seed of every random choice (sampling, RANSAC draws).
    pub seed: u64,
    /// Sheet thickness in mm: surface detail finer than half a sheet is not worth a part.
    pub thickness: f64,
    /// How many surface samples to take; the spacing follows from the surface area.
    pub samples: usize,
}

impl Default for ClassifySettings {
    fn default() -> Self {
        Self {
            seed: 0x5EED_C1A5_5F1E_u64,
            thickness: 3.0,
            samples: 40_000,
        }
    }
}

impl ClassifySettings {
    /// The classifier's settings for a conversion: the thinnest sheet offered.
    pub fn from_settings(s: &crate::Settings) -> Self {
        Self {
            thickness: s.thinnest(),
            ..Self::default()
        }
    }
}

pub use crate::error::ClassifyError;

/// The tolerances of one run, derived from the model and the settings.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Thresholds {
    /// Mean distance between samples, mm: √(area / samples).
    pub spacing: f64,
    /// Distance tolerance ε, mm: min(thickness / 2, diagonal / 50).
    pub eps: f64,
    /// Radius of the neighbourhood a sample's normal is fitted to, mm: max(3·spacing, 4ε).
    /// At 2ε, α would be 45° wherever samples are dense, and cylinders rounding a small
    /// textured box's edges took strips of its faces.
    pub normal_radius: f64,
    /// Normal tolerance α, degrees: atan(2ε / normal_radius), the most noise within ±ε can
    /// tilt a normal fitted over that neighbourhood.
    pub alpha_deg: f64,
    /// cos α.
    pub cos_alpha: f64,
    /// Side of the connectivity bitmap's cells, mm: 2·spacing (about four samples a cell).
    pub cell: f64,
    /// Fewest samples of a primitive: those on a square four sheets wide, at least 10.
    pub min_points: usize,
    /// Bounding-box diagonal, mm.
    pub diagonal: f64,
    /// Largest radius of a curved primitive, mm: diagonal² / (8ε); a larger one deviates
    /// from a plane by less than ε across the whole model.
    pub max_radius: f64,
    /// Octree levels used for localized draws: down to cells four spacings wide.
    pub octree_levels: usize,
    /// Two planes are parallel within this angle, degrees: atan(2ε / diagonal).
    pub parallel_deg: f64,
}

impl Thresholds {
    /// The tolerances for a surface of `area` mm² whose bounding box has `diagonal`.
    pub fn derive(area: f64, diagonal: f64, s: &ClassifySettings) -> Self {
        let spacing = (area / s.samples as f64).sqrt();
        let eps = (s.thickness / 2.0).min(diagonal / 50.0);
        let normal_radius = (3.0 * spacing).max(4.0 * eps);
        let alpha = (2.0 * eps / normal_radius).atan();
        let side = 4.0 * s.thickness;
        let min_points = ((side * side / (spacing * spacing)) as usize).max(10);
        let levels = (diagonal / (4.0 * spacing)).log2().floor().max(1.0) as usize;
        Self {
            spacing,
            eps,
            normal_radius,
            alpha_deg: alpha.to_degrees(),
            cos_alpha: alpha.cos(),
            cell: 2.0 * spacing,
            min_points,
            diagonal,
            max_radius: diagonal * diagonal / (8.0 * eps),
            octree_levels: levels.min(10),
            parallel_deg: (2.0 * eps / diagonal).atan().to_degrees(),
        }
    }

    /// Whether a candidate is a shape this model can hold and no simpler shape explains:
    /// radii between ε and [`Thresholds::max_radius`]; cones whose radius changes by more
    /// than ε across the model (else a cylinder) and that bend by more than ε (else a plane).
    pub fn plausible(&self, s: &Surface) -> bool {
        let d = self.diagonal;
        match *s {
            Surface::Plane { .. } => true,
            Surface::Cylinder { radius, .. } | Surface::Sphere { radius, .. } => {
                radius >= self.eps && radius <= self.max_radius
            }
            Surface::Cone { half_angle, .. } => {
                let lo = (self.eps / d).min(1.0).asin();
                half_angle > lo && half_angle < std::f64::consts::FRAC_PI_2 - lo
            }
        }
    }
}

/// One detected primitive.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Primitive {
    /// The fitted surface.
    pub shape: Surface,
    /// Whether the solid lies inside it (a cylinder's or sphere's normals point away from
    /// the axis / centre); `false` for bores and cavities. Planes face out by their normal.
    pub outward: bool,
    /// Its inlier samples (indices into [`Classification::samples`]), ascending.
    #[serde(skip)]
    pub samples: Vec<u32>,
    /// The mesh triangles it explains, ascending.
    #[serde(skip)]
    pub triangles: Vec<u32>,
    /// Area of those triangles, mm².
    pub area: f64,
}

/// The snapshot of a classification.
#[derive(Debug, Clone, Serialize)]
pub struct Classification {
    /// The tolerances used.
    pub thresholds: Thresholds,
    /// The surface samples.
    #[serde(skip)]
    pub samples: Vec<sample::Sample>,
    /// The primitives, in the order they were found (largest first, roughly).
    pub primitives: Vec<Primitive>,
    /// Each triangle's primitive, if one explains it.
    #[serde(skip)]
    pub labels: Vec<Option<u32>>,
    /// Volumes made of primitives.
    pub volumes: Vec<Volume>,
    /// Volumes, connectors, surfaces and freeforms with their adjacency.
    pub graph: Graph,
    /// Total surface area, mm².
    pub surface_area: f64,
    /// The primitives whose triangles the classifier's planar groups replaced (a texture, a
    /// knurl, noise over exact faces): set by step `classify`, empty from [`run`].
    pub replaced: Vec<u32>,
}

/// Classifies `mesh`: samples, primitives, triangle labels, volumes and the graph.
pub fn run(mesh: &Mesh, settings: &ClassifySettings) -> Result<Classification, ClassifyError> {
    validate(settings)?;
    let area: f64 = mesh.areas.iter().sum();
    if mesh.triangles.is_empty() || area.is_nan() || area <= 0.0 {
        return Err(ClassifyError::NoSurface);
    }
    let (lo, hi) = platener_geom::boxes::bounds3(mesh.vertices.iter().copied());
    let th = Thresholds::derive(area, (hi - lo).length(), settings);
    let points = sample::sample_surface(mesh, settings.samples, settings.seed);
    let fit = sample::NormalFit {
        spacing: th.spacing,
        radius: th.normal_radius,
        flat: th.eps / 2.0,
        cos_alpha: th.cos_alpha,
    };
    let samples = sample::with_normals(mesh, &points, fit);
    let mut primitives = ransac::detect(&samples, &th, settings.seed ^ 0xA5A5_5A5A);
    let labels = label::label_triangles(mesh, &samples, &primitives, &th);
    label::attach(&mut primitives, &labels, mesh);
    let adjacency = graph::primitive_adjacency(mesh, &labels);
    let volumes = volumes::find(mesh, &samples, &primitives, &labels, &adjacency, &th);
    let graph = graph::build(mesh, &primitives, &labels, &volumes);
    Ok(Classification {
        thresholds: th,
        samples,
        primitives,
        labels,
        volumes,
        graph,
        surface_area: area,
        replaced: Vec::new(),
    })
}

/// Step `classify` of the classifier method: the classification of `mesh`, and the planar
/// groups its primitives stand for ([`groups`]), grown further over what they leave.
pub fn step(
    mesh: &Mesh,
    settings: &crate::Settings,
    cx: &mut crate::context::StepContext<'_>,
) -> crate::error::Result<(Classification, crate::coplanar::PlanarGroups)> {
    cx.check_cancel()?;
    let angle = settings.coplanar_angle_deg.to_radians();
    let exact = crate::coplanar::group_faces(mesh, angle);
    if !settings.classify_exact_faces
        && let Some(reason) = groups::nothing_to_replace(mesh, &exact, settings.thinnest())
    {
        return Err(crate::error::Error::Skipped { reason });
    }
    let found = run(mesh, &ClassifySettings::from_settings(settings))
        .map_err(|e| crate::error::Error::model(cx.model(), crate::error::ModelProblem::Classify(e)))?;
    let mut found = found;
    let (fixed, replaced) = groups::fixed_groups(mesh, &found, &exact, settings);
    found.replaced = replaced;
    let planar = crate::coplanar::group_rest(mesh, angle, fixed);
    Ok((found, planar))
}

/// Rejects settings no classification can use.
fn validate(s: &ClassifySettings) -> Result<(), ClassifyError> {
    if !(s.thickness.is_finite() && s.thickness > 0.0) {
        return Err(ClassifyError::Setting {
            name: "thickness",
            message: format!("{} is not a positive number of mm", s.thickness),
        });
    }
    if !(100..=10_000_000).contains(&s.samples) {
        return Err(ClassifyError::Setting {
            name: "samples",
            message: format!("{} is not between 100 and 10 000 000", s.samples),
        });
    }
    Ok(())
}
