//! The coverage report: for every planar shape, the plates that use it, or why none does.
//! Users ask this more than anything: "which walls became plates, and why not the others".

use serde::Serialize;

use super::inherent::{Nearest, matching_thickness};
use super::{Plate, PlateKind};
use crate::settings::Settings;
use crate::shapes::Shapes;

/// Why a shape (or a piece of it) did not become a plate.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[serde(rename_all = "kebab-case", tag = "reason")]
pub enum Rejection {
    /// No parallel face facing away from it overlaps it within the search distance.
    NoOppositeFace,
    /// The opposite face is at a distance no offered thickness fits.
    ThicknessMismatch {
        /// Distance to the nearest opposite face in mm.
        distance: f64,
    },
    /// The nearest parallel face faces it across empty space: a slot or gap, not material.
    FacingEachOther {
        /// Width of the gap in mm.
        distance: f64,
    },
    /// Under the minimum plate area.
    TooSmall {
        /// Area in mm².
        area: f64,
    },
    /// Narrower on average than the sheet is thick (e.g. a facet of a thin curved wall).
    Sliver {
        /// Mean width 2·area/perimeter in mm.
        width: f64,
    },
    /// Its plate lay inside another plate's volume and was removed.
    Contained,
}

impl Rejection {
    /// A sentence for people, naming the offered thicknesses where that helps.
    pub fn explain(&self, offered: &[f64]) -> String {
        let list = offered.iter().map(|t| format!("{t}")).collect::<Vec<_>>().join("/");
        match self {
            Rejection::NoOppositeFace => "no opposite face: nothing parallel behind it".into(),
            Rejection::ThicknessMismatch { distance } => {
                format!("opposite face at {distance:.2} mm but offered {list} mm")
            }
            Rejection::FacingEachOther { distance } => {
                format!("faces another face across a {distance:.2} mm gap (a slot)")
            }
            Rejection::TooSmall { area } => format!("too small ({area:.1} mm²)"),
            Rejection::Sliver { width } => format!("a sliver ({width:.2} mm wide on average), too thin to cut"),
            Rejection::Contained => "its plate lay inside another plate".into(),
        }
    }
}

/// Why no plate was found, for people: how many faces were rejected for each reason, the
/// largest area first. `None` when some shape became a plate.
pub fn why_no_plates(coverage: &Coverage, min_area: f64, offered: &[f64]) -> Option<String> {
    if coverage.shapes.iter().any(|s| !s.plates.is_empty()) {
        return None;
    }
    if coverage.shapes.is_empty() {
        return Some("no plate found: the model has no planar faces (try the stacked method)".into());
    }
    let list = offered.iter().map(|t| format!("{t}")).collect::<Vec<_>>().join("/");
    let mut by_reason: Vec<(&str, usize, f64)> = Vec::new();
    for s in &coverage.shapes {
        let reason = match s.rejected {
            Some(Rejection::NoOppositeFace) => "have no opposite face within a few sheets behind them",
            Some(Rejection::ThicknessMismatch { .. }) => "have their opposite face at a distance no offered sheet fits",
            Some(Rejection::FacingEachOther { .. }) => "face another face across a gap",
            Some(Rejection::TooSmall { .. }) => "are under the minimum plate area",
            Some(Rejection::Sliver { .. }) => "are slivers thinner than the sheet",
            Some(Rejection::Contained) | None => "lay inside other plates",
        };
        match by_reason.iter_mut().find(|(r, ..)| *r == reason) {
            Some((_, n, area)) => {
                *n += 1;
                *area += s.area;
            }
            None => by_reason.push((reason, 1, s.area)),
        }
    }
    by_reason.sort_by(|a, b| b.2.total_cmp(&a.2).then(a.0.cmp(b.0)));
    let parts: Vec<String> = by_reason
        .iter()
        .map(|(reason, n, area)| format!("{n} ({area:.0} mm²) {reason}"))
        .collect();
    Some(format!(
        "no plate found for sheets of {list} mm among {} planar faces: {}; plates need two opposite faces a \
         sheet's thickness apart (or a face of at least {min_area} mm² to extrude): try other sheet thicknesses (`thickness`), \
         check the units, or the stacked method",
        coverage.shapes.len(),
        parts.join(", ")
    ))
}

/// How one shape was used.
#[derive(Debug, Clone, Serialize)]
pub struct ShapeUse {
    /// Index into the `shapes` snapshot.
    pub shape: u32,
    /// Its area in mm².
    pub area: f64,
    /// Its outward normal.
    pub normal: glam::DVec3,
    /// The plates (indices into `plates`) made from it.
    pub plates: Vec<u32>,
    /// Area of the shape covered by plates, mm² (as detected, before overlaps were trimmed).
    pub used_area: f64,
    /// Why it is not (or not wholly) part of an inherent plate.
    pub why_not_inherent: Option<Rejection>,
    /// Set when no plate uses it at all: the reason.
    pub rejected: Option<Rejection>,
}

/// Surface area turned into plates of one thickness.
#[derive(Debug, Clone, Serialize)]
pub struct ThicknessShare {
    /// Sheet thickness in mm.
    pub thickness: f64,
    /// Plates of that thickness.
    pub plates: usize,
    /// Share of the model's surface area they use, 0–1.
    pub surface_share: f64,
}

/// The coverage report.
#[derive(Debug, Clone, Serialize)]
pub struct Coverage {
    /// One entry per shape, in shape order.
    pub shapes: Vec<ShapeUse>,
    /// Share of the model's surface area used by plates, 0–1.
    pub surface_share: f64,
    /// The same per thickness.
    pub per_thickness: Vec<ThicknessShare>,
    /// Share used by inherent plates alone.
    pub inherent_share: f64,
}

pub(super) fn report(
    shapes: &Shapes,
    detail: &[Nearest],
    detected_use: &[f64],
    plates: &[Plate],
    surface: f64,
    settings: &Settings,
) -> Coverage {
    let mut uses: Vec<Vec<u32>> = vec![Vec::new(); shapes.shapes.len()];
    for (k, p) in plates.iter().enumerate() {
        for &s in &p.shapes {
            uses[s as usize].push(k as u32);
        }
    }
    let mut entries = Vec::with_capacity(shapes.shapes.len());
    let (mut used_total, mut inherent_total) = (0.0, 0.0);
    let mut by_thickness: Vec<(f64, usize, f64)> = Vec::new();
    for (i, shape) in shapes.shapes.iter().enumerate() {
        let d = &detail[i];
        let plates_of: Vec<u32> = uses[i].clone();
        let inherent = plates_of
            .iter()
            .any(|&k| plates[k as usize].kind == PlateKind::Inherent);
        let why_not = if inherent {
            None
        } else {
            Some(match (d.apart, d.facing) {
                (Some(distance), _) if matching_thickness(distance, settings).is_none() => {
                    Rejection::ThicknessMismatch { distance }
                }
                (Some(_), _) => d.refused.unwrap_or(Rejection::Contained),
                (None, Some(distance)) => Rejection::FacingEachOther { distance },
                (None, None) => Rejection::NoOppositeFace,
            })
        };
        let rejected = plates_of
            .is_empty()
            .then(|| d.refused.or(why_not).unwrap_or(Rejection::Contained));
        let used_area = if plates_of.is_empty() { 0.0 } else { detected_use[i] };
        used_total += used_area;
        if inherent {
            inherent_total += used_area;
        }
        if let Some(&k) = plates_of.first() {
            let t = plates[k as usize].thickness;
            match by_thickness.iter_mut().find(|e| e.0 == t) {
                Some(e) => e.2 += used_area,
                None => by_thickness.push((t, 0, used_area)),
            }
        }
        entries.push(ShapeUse {
            shape: i as u32,
            area: shape.area,
            normal: shape.frame.n,
            plates: plates_of,
            used_area,
            why_not_inherent: why_not,
            rejected,
        });
    }
    for p in plates {
        match by_thickness.iter_mut().find(|e| e.0 == p.thickness) {
            Some(e) => e.1 += 1,
            None => by_thickness.push((p.thickness, 1, 0.0)),
        }
    }
    by_thickness.sort_by(|a, b| a.0.total_cmp(&b.0));
    let share = |a: f64| if surface > 0.0 { (a / surface).min(1.0) } else { 0.0 };
    Coverage {
        shapes: entries,
        surface_share: share(used_total),
        per_thickness: by_thickness
            .into_iter()
            .map(|(thickness, plates, a)| ThicknessShare {
                thickness,
                plates,
                surface_share: share(a),
            })
            .collect(),
        inherent_share: share(inherent_total),
    }
}
