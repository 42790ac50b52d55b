//! Step `kerf`: cut paths offset by half the kerf, and the calibration test strip.
//!
//! The laser burns away a line `kerf` wide centred on its path. Cutting along the nominal
//! outline would make every part `kerf` too small and every hole and slot `kerf` too large, so
//! joints would rattle. The cut path is therefore the nominal shape grown by `kerf / 2`: the
//! outline moves out, holes and slots shrink, and the part comes out at nominal size. Corners
//! stay sharp (miter joins, [`platener_geom::offset`]) so fingers keep their square shoulders.
//! The kerf itself is measured with the [`strip`] (`platener test-strip`).
//!
//! Growing can make a valid outline's cut path touch itself: a hole or a notch whose waist is
//! exactly the kerf wide closes to a point, two holes end up meeting in one. The laser burns
//! the material between them anyway, so the cut path is repaired the way the cut comes out
//! ([`separate_touches`]): a tiny square of material (10 µm) is removed at each touch, which
//! merges the touching holes into one hole and opens a pinched notch, and a warning names the
//! part.

use glam::DVec2;
use platener_geom::clean::clean;
use platener_geom::validity::Problem;
use platener_geom::{Polygon, Ring, offset, validate};
use rayon::prelude::*;
use serde::Serialize;

use crate::context::{StepContext, Warning, WarningKind};
use crate::plan::{Fit, MarkKind, Part, PlanError, PlanInput};

/// One part's cut path.
#[derive(Debug, Clone, Serialize)]
pub struct CutPart {
    /// The part's id.
    pub id: u32,
    /// The nominal shape, outer ring counter-clockwise and holes clockwise (plan.json's form).
    pub nominal: Polygon,
    /// The cut path: `nominal` offset outward by `kerf / 2`, same orientations.
    pub cut: Polygon,
    /// The part's `cut` marks (hinge slits, perforation dashes), open paths exactly as drawn:
    /// a slit removes no material, so there is no edge to move by half the kerf, and it is no
    /// hole (it encloses nothing), so it is neither offset nor dropped as narrower than the
    /// kerf. Empty for parts without cut marks.
    pub slits: Vec<Vec<DVec2>>,
}

/// The snapshot of step `kerf`: one cut path per part, in the input's part order.
#[derive(Debug, Clone, Serialize)]
pub struct CutPaths {
    /// The kerf used, mm.
    pub kerf: f64,
    /// Per part, in the order of the input.
    pub parts: Vec<CutPart>,
}

/// The cut path of one nominal polygon: offset outward by `kerf / 2` with miter joins.
///
/// Returns the offset polygon; holes narrower than the kerf disappear (the laser would burn
/// them away entirely). Exact to the 1 µm grid of [`platener_geom::grid`].
pub fn cut_polygon(nominal: &Polygon, kerf: f64) -> Result<Polygon, platener_geom::GridError> {
    let grown = offset::offset(std::slice::from_ref(nominal), kerf / 2.0)?;
    // An outward offset of one connected polygon is one polygon; keep the largest piece should
    // grid snapping ever split off a sliver.
    let mut best = grown
        .into_iter()
        .max_by(|a, b| a.area().total_cmp(&b.area()))
        .unwrap_or_default();
    best.normalize_orientation();
    Ok(best)
}

/// `cut` with its rings made simple where they touch or cross, and how many such places
/// there were (0: `cut` is returned as it is).
///
/// The kernel's [`clean`] at width 0 regularises the rings and cuts a square of ten grid steps
/// out of the material at each touch: a cut path is the edge of what the laser removes, so
/// removing a speck more where two cuts meet is what the laser does anyway, whereas filling
/// it would leave a hole or notch uncut. The largest piece is kept (the squares never split a
/// part wider than them).
pub fn separate_touches(cut: &Polygon) -> Result<(Polygon, usize), platener_geom::GridError> {
    let touches = validate(cut, 0.0)
        .iter()
        .filter(|f| matches!(f.problem, Problem::Touching { .. } | Problem::Crossing { .. }))
        .count();
    if touches == 0 {
        return Ok((cut.clone(), 0));
    }
    let repaired = clean(cut, 0.0)?.into_iter().next().unwrap_or_else(|| cut.clone());
    Ok((repaired, touches))
}

/// `ring` without consecutive repeated points and without a closing copy of its first point
/// (plan.json's rings are not closed).
pub fn open_ring(ring: &[DVec2]) -> Ring {
    let mut out: Ring = Vec::with_capacity(ring.len());
    for p in ring {
        if out.last() != Some(p) {
            out.push(*p);
        }
    }
    while out.len() > 1 && out.first() == out.last() {
        out.pop();
    }
    out
}

/// The paths of `part`'s `cut` marks, in mark order, as they are ([`CutPart::slits`]).
pub fn slits(part: &Part) -> Vec<Vec<DVec2>> {
    part.marks
        .iter()
        .filter(|m| m.kind == MarkKind::Cut)
        .map(|m| m.path.clone())
        .collect()
}

/// Cut paths of all `parts` for `kerf` mm, with a warning for each part whose holes are too
/// narrow to cut ([`min_hole_width`]: left out of the nominal shape too, so plan.json, the
/// sheets and the score agree) or close when offset.
pub fn cut_paths(parts: &[Part], kerf: f64) -> Result<(CutPaths, Vec<Warning>), PlanError> {
    fitted_cut_paths(parts, kerf, Fit::Snug)
}

/// [`cut_paths`] for joints that fit as `fit` says: every path moves out by a further
/// [`Fit::offset`] (in for a loose fit), so each finger and its notch differ by the fit's
/// clearance. Holes too narrow to cut are judged by the kerf alone.
pub fn fitted_cut_paths(parts: &[Part], kerf: f64, fit: Fit) -> Result<(CutPaths, Vec<Warning>), PlanError> {
    // The width the cut path is grown by on both sides together, as a kerf would be.
    let grown = kerf + 2.0 * fit.offset();
    let results: Vec<Result<(CutPart, Option<Warning>), PlanError>> = parts
        .par_iter()
        .map(|part| {
            let grid_error = |e: platener_geom::GridError| PlanError::Part {
                part: part.id,
                message: e.to_string(),
            };
            let width = min_hole_width(kerf);
            let mut holes = Vec::with_capacity(part.polygon.holes.len());
            let mut dropped = 0;
            for hole in &part.polygon.holes {
                if too_narrow(hole, width).map_err(grid_error)? {
                    dropped += 1;
                } else {
                    holes.push(open_ring(hole));
                }
            }
            let mut nominal = Polygon {
                outer: open_ring(&part.polygon.outer),
                holes,
            };
            nominal.normalize_orientation();
            let (cut, touches) =
                separate_touches(&cut_polygon(&nominal, grown).map_err(grid_error)?).map_err(grid_error)?;
            if cut.outer.len() < 3 {
                return Err(PlanError::Part {
                    part: part.id,
                    message: "the outline vanished when offset by half the kerf".into(),
                });
            }
            let warning = kerf_warning(part.id, (dropped, nominal.holes.len()), &cut, touches, kerf);
            Ok((
                CutPart {
                    id: part.id,
                    nominal,
                    cut,
                    slits: slits(part),
                },
                warning,
            ))
        })
        .collect();
    let mut out = CutPaths {
        kerf,
        parts: Vec::with_capacity(parts.len()),
    };
    let mut warnings = Vec::new();
    for r in results {
        let (part, warning) = r?;
        out.parts.push(part);
        warnings.extend(warning);
    }
    Ok((out, warnings))
}

/// Holes narrower than this many kerfs are not cut: what the laser leaves of them is a slit
/// at most a kerf wide, or nothing (issue 32: an OpenSCAD box kept triangular holes of
/// 0.0003–0.09 mm² in plan.json, which an outside checker crashed on).
pub const MIN_HOLE_KERFS: f64 = 2.0;

/// Holes narrower than this (mm) are not cut whatever the kerf (0 included): no laser's beam
/// is finer.
pub const MIN_HOLE_WIDTH: f64 = 0.1;

/// The narrowest hole cut with `kerf`, mm.
pub fn min_hole_width(kerf: f64) -> f64 {
    (MIN_HOLE_KERFS * kerf).max(MIN_HOLE_WIDTH)
}

/// Whether `hole` is narrower than `width` everywhere: shrunk by half of it, nothing is left.
fn too_narrow(hole: &[DVec2], width: f64) -> Result<bool, platener_geom::GridError> {
    let mut p = Polygon::new(open_ring(hole));
    p.normalize_orientation();
    Ok(offset::offset(&[p], -width / 2.0)?.iter().all(|q| q.area() <= 0.0))
}

/// The warning for one part's cut path, if any: holes left out as too narrow (`dropped`, of
/// `(dropped, kept)`) or that closed when offset, and places where the cut path touched itself
/// and was separated ([`separate_touches`]).
fn kerf_warning(
    part: u32,
    (dropped, kept): (usize, usize),
    cut: &Polygon,
    touches: usize,
    kerf: f64,
) -> Option<Warning> {
    let closed = dropped + kept.saturating_sub(cut.holes.len());
    let mut said = Vec::new();
    if closed > 0 {
        said.push(format!(
            "{closed} hole(s) of part {part} are narrower than {:.2} mm (twice the kerf, {kerf} mm) and are not cut",
            min_hole_width(kerf)
        ));
    }
    if touches > 0 {
        said.push(format!(
            "the cut path of part {part} touched itself at {touches} place(s) once grown by half the kerf \
             ({kerf} mm): holes or notches meeting there are cut as one"
        ));
    }
    (!said.is_empty()).then(|| Warning {
        step: "kerf",
        kind: WarningKind::CuttingPlan,
        part: Some(part),
        message: said.join("; "),
    })
}

/// Step `kerf`: the cut path of every part, offset by half the kerf.
pub fn run(input: &PlanInput, cx: &mut StepContext<'_>) -> Result<CutPaths, PlanError> {
    input.validate()?;
    let (cut, warnings) = fitted_cut_paths(&input.parts, input.settings.kerf(), input.settings.fit)?;
    cx.extend(warnings);
    Ok(cut)
}

#[cfg(test)]
mod tests;
