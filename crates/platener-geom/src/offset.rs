//! Offsetting polygons (kerf compensation, margins) on the project grid with sharp corners.
//!
//! Positive distances grow the solid (outer ring outwards, holes shrink), negative ones shrink
//! it. Joins are miters, so a square stays a square: laser parts must keep their corners for
//! joints to fit. Very sharp spikes (turns under 5°) are bevelled by i_overlay to stay finite.

use i_overlay::i_float::int::angle::Angle;
use i_overlay::mesh::int::outline::offset::IntOutlineOffset;
use i_overlay::mesh::int::style::{IntLineJoin, IntOutlineStyle};

use crate::boolean::{polygons_to_grid, shapes_from_grid};
use crate::grid::{self, GridError};
use crate::polygon::Polygon;

/// Offsets `polygons` by `distance` mm (positive grows), with miter joins.
pub fn offset(polygons: &[Polygon], distance: f64) -> Result<Vec<Polygon>, GridError> {
    // Interior angles under 5° are bevelled instead of growing a spike to infinity.
    let join = Angle::from_radians(5f64.to_radians()).map_or(IntLineJoin::Bevel, IntLineJoin::Miter);
    offset_joined(polygons, distance, join)
}

/// Offsets `polygons` by `distance` mm with `join` at the corners that grow.
fn offset_joined(polygons: &[Polygon], distance: f64, join: IntLineJoin) -> Result<Vec<Polygon>, GridError> {
    let mut normalized = polygons.to_vec();
    normalized.iter_mut().for_each(Polygon::normalize_orientation);
    let shapes = polygons_to_grid(&normalized)?;
    let d = grid::to_grid(distance)?;
    let style = IntOutlineStyle::new(d).line_join(join);
    shapes
        .validate_outline(&style)
        .map_err(|_| GridError::OutOfRange(distance))?;
    let out = shapes.outline(&style).map_err(|_| GridError::OutOfRange(distance))?;
    Ok(shapes_from_grid(out))
}

/// Morphological opening (shrink by `r`, then grow back): removes every piece and spike of
/// `polygons` narrower than `2r` and keeps everything wider exactly (miter joins restore the
/// corners).
pub fn opening(polygons: &[Polygon], r: f64) -> Result<Vec<Polygon>, GridError> {
    offset(&offset(polygons, -r)?, r)
}

/// Offsets `polygons` by `distance` mm with bevelled corners: growing a thin sliver never
/// makes miter spikes at its sharp ends (used to widen necks, where only the width matters).
pub fn offset_bevelled(polygons: &[Polygon], distance: f64) -> Result<Vec<Polygon>, GridError> {
    offset_joined(polygons, distance, IntLineJoin::Bevel)
}

/// An opening whose growth bevels corners instead of mitring them: it never grows a sharp
/// wedge back, so every part of a wedge narrower than `2r` is gone (the miter [`opening`]
/// rebuilds a thin wedge's tip from its wider base). Convex corners lose a small triangle,
/// so it only serves to find narrow material, never as an outline.
pub fn opening_bevelled(polygons: &[Polygon], r: f64) -> Result<Vec<Polygon>, GridError> {
    offset_joined(&offset_joined(polygons, -r, IntLineJoin::Bevel)?, r, IntLineJoin::Bevel)
}

/// Morphological closing (grow by `r`, then shrink back): fills every gap and notch of
/// `polygons` narrower than `2r` and keeps everything else exactly.
pub fn closing(polygons: &[Polygon], r: f64) -> Result<Vec<Polygon>, GridError> {
    offset(&offset(polygons, r)?, -r)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::polygon::total_area;
    use glam::DVec2;

    #[test]
    fn square_grows_with_sharp_corners() {
        let sq = Polygon::new(vec![
            DVec2::new(0.0, 0.0),
            DVec2::new(10.0, 0.0),
            DVec2::new(10.0, 10.0),
            DVec2::new(0.0, 10.0),
        ]);
        let out = offset(std::slice::from_ref(&sq), 0.5).expect("grid");
        assert!((total_area(&out) - 121.0).abs() < 1e-6, "{}", total_area(&out));
        assert_eq!(out[0].outer.len(), 4);
        let inner = offset(&[sq], -0.5).expect("grid");
        assert!((total_area(&inner) - 81.0).abs() < 1e-6);
    }

    #[test]
    fn opening_removes_slivers_and_keeps_the_rest_exactly() {
        // A 10 × 10 square with a 0.2 mm wide, 5 mm long sliver hanging off its right side.
        let p = Polygon::new(vec![
            DVec2::new(0.0, 0.0),
            DVec2::new(10.0, 0.0),
            DVec2::new(10.0, 4.0),
            DVec2::new(15.0, 4.0),
            DVec2::new(15.0, 4.2),
            DVec2::new(10.0, 4.2),
            DVec2::new(10.0, 10.0),
            DVec2::new(0.0, 10.0),
        ]);
        let open = opening(std::slice::from_ref(&p), 0.5).expect("grid");
        assert_eq!(open.len(), 1);
        assert!((total_area(&open) - 100.0).abs() < 1e-6, "{}", total_area(&open));
        // Features wider than 2r stay as they are: a 3 mm finger survives a 1 mm opening.
        let finger = Polygon::new(vec![
            DVec2::new(0.0, 0.0),
            DVec2::new(10.0, 0.0),
            DVec2::new(10.0, 4.0),
            DVec2::new(13.0, 4.0),
            DVec2::new(13.0, 7.0),
            DVec2::new(10.0, 7.0),
            DVec2::new(10.0, 10.0),
            DVec2::new(0.0, 10.0),
        ]);
        let open = opening(std::slice::from_ref(&finger), 1.0).expect("grid");
        assert!((total_area(&open) - 109.0).abs() < 1e-6, "{}", total_area(&open));
        let closed = closing(&[finger], 1.0).expect("grid");
        assert!((total_area(&closed) - 109.0).abs() < 1e-6, "{}", total_area(&closed));
    }

    #[test]
    fn holes_shrink_when_growing() {
        let p = Polygon {
            outer: vec![
                DVec2::new(0.0, 0.0),
                DVec2::new(20.0, 0.0),
                DVec2::new(20.0, 20.0),
                DVec2::new(0.0, 20.0),
            ],
            holes: vec![vec![
                DVec2::new(5.0, 5.0),
                DVec2::new(15.0, 5.0),
                DVec2::new(15.0, 15.0),
                DVec2::new(5.0, 15.0),
            ]],
        };
        let out = offset(&[p], 1.0).expect("grid");
        // 22² − 8²
        assert!((total_area(&out) - (484.0 - 64.0)).abs() < 1e-6, "{}", total_area(&out));
    }
}
