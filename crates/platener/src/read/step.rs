//! The `read` step: file → triangles in mm, with unit conversion and size sanity checks.

use std::sync::Arc;

use glam::DVec3;
use serde::Serialize;

use super::{Format, Source, Triangle, read_bytes, read_file};
use crate::context::{StepContext, WarningKind};
use crate::error::{Error, ModelProblem, Result};
use crate::settings::{Settings, Units};

/// Models smaller than this (largest extent, mm) are probably in cm, inches or metres: a
/// 4-unit Benchy, a 5-unit part.
pub const SUSPICIOUSLY_SMALL: f64 = 30.0;
/// Models fewer than this many sheet thicknesses across leave no room for a joint between
/// two walls; probably the wrong unit too.
pub const SHEETS_ACROSS: f64 = 8.0;
/// Models larger than this (largest extent, mm) are probably in microns or tenths of mm.
pub const SUSPICIOUSLY_LARGE: f64 = 5000.0;

/// An axis-aligned bounding box.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Bounds {
    /// Smallest corner.
    pub min: DVec3,
    /// Largest corner.
    pub max: DVec3,
}

impl Bounds {
    /// The bounds of some triangles (`None` when there are none).
    pub fn of(triangles: &[Triangle]) -> Option<Self> {
        let mut it = triangles.iter().flatten();
        let first = *it.next()?;
        let (min, max) = it.fold((first, first), |(lo, hi), p| (lo.min(*p), hi.max(*p)));
        Some(Self { min, max })
    }

    /// Extent along each axis.
    pub fn size(&self) -> DVec3 {
        self.max - self.min
    }

    /// Length of the diagonal.
    pub fn diagonal(&self) -> f64 {
        self.size().length()
    }

    /// The largest extent.
    pub fn largest_extent(&self) -> f64 {
        self.size().max_element()
    }
}

/// The snapshot of step `read`: the model as converted, in mm.
#[derive(Debug, Clone, Serialize)]
pub struct Model {
    /// The model's name (file stem).
    pub name: String,
    /// The file format, `None` for models made in code.
    pub format: Option<Format>,
    /// Triangles in mm, after units and scale.
    #[serde(skip)]
    pub triangles: Arc<Vec<Triangle>>,
    /// Objects / solids in the file.
    pub solids: usize,
    /// Bounding box in mm.
    pub bounds: Bounds,
    /// Facets whose stored normal disagreed with the winding.
    pub normals_against_winding: usize,
    /// The factor applied to the file's numbers.
    pub unit_factor: f64,
    /// The unit the file's numbers were taken in.
    pub units: Units,
    /// The extra scale applied.
    pub scale: f64,
    /// Printing it on an FDM printer instead (`fabrication::print`), estimated once here for
    /// every method's report.
    pub print: crate::plan::PrintEstimate,
}

/// Step `read`: the model's triangles in mm, with its bounds and what the reader noticed.
pub fn run(source: &Source, settings: &Settings, cx: &mut StepContext<'_>) -> Result<Model> {
    let name = source.name();
    let factor = settings.unit_factor();
    let scale = |mut tris: Vec<Triangle>| {
        if factor != 1.0 {
            tris.iter_mut().flatten().for_each(|p| *p *= factor);
        }
        tris
    };
    let (format, raw) = match source {
        Source::File(path) => read_file(path)?,
        Source::Bytes { name, bytes } => read_bytes(name, bytes)?,
        Source::Triangles { triangles, .. } => {
            let triangles = if factor == 1.0 {
                triangles.clone()
            } else {
                Arc::new(scale(triangles.to_vec()))
            };
            return model(name, None, (1, 0), triangles, settings, cx);
        }
    };
    for note in &raw.notes {
        cx.warn(WarningKind::Reader, note.clone());
    }
    let against = raw.normals_against_winding;
    if against > 0 {
        cx.warn(
            WarningKind::StoredNormals,
            format!("{against} stored facet normals point against the winding; the winding is used"),
        );
    }
    let triangles = Arc::new(scale(raw.triangles));
    model(name, Some(format), (raw.solids, against), triangles, settings, cx)
}

/// The snapshot, once the triangles are in mm: checked finite, bounded, sized.
fn model(
    name: String,
    format: Option<Format>,
    (solids, against): (usize, usize),
    triangles: Arc<Vec<Triangle>>,
    settings: &Settings,
    cx: &mut StepContext<'_>,
) -> Result<Model> {
    validate_finite(&name, &triangles)?;
    let bounds = Bounds::of(&triangles).ok_or_else(|| Error::model(&name, ModelProblem::NoTriangles))?;
    warn_units(bounds.largest_extent(), settings.thinnest(), cx);
    let print = crate::fabrication::print::estimate(&triangles);
    Ok(Model {
        name,
        format,
        triangles,
        solids,
        bounds,
        normals_against_winding: against,
        unit_factor: settings.unit_factor(),
        units: settings.units,
        scale: settings.scale,
        print,
    })
}

/// A model far too small (for millimetres, or for the sheets offered) or too large is
/// probably in other units.
fn warn_units(extent: f64, thinnest: f64, cx: &mut StepContext<'_>) {
    if extent < SUSPICIOUSLY_SMALL.max(SHEETS_ACROSS * thinnest) {
        cx.warn(
            WarningKind::Units,
            format!(
                "the model is only {extent:.4} mm across ({:.1} sheets of {thinnest} mm): if its numbers are not mm, \
                 set `units` to cm or in, or `scale` it up",
                extent / thinnest
            ),
        );
    } else if extent > SUSPICIOUSLY_LARGE {
        cx.warn(
            WarningKind::Units,
            format!(
                "the model is {:.1} m across: if its unit is not mm, set `units` or `scale` it down (e.g. 0.001 for µm)",
                extent / 1000.0
            ),
        );
    }
}

/// Refuses NaN/infinite coordinates (also those a huge `--scale` produces), naming the triangle.
fn validate_finite(name: &str, triangles: &[Triangle]) -> Result<()> {
    match triangles.iter().position(|t| !t.iter().all(|p| p.is_finite())) {
        None => Ok(()),
        Some(i) => Err(Error::model(name, ModelProblem::NonFinite { triangle: i })),
    }
}
