//! 2D booleans on the project grid, through i_overlay's exact integer engine.
//!
//! This file and [`crate::offset`] are the only places that call i_overlay. Inputs are snapped
//! to the [`crate::grid`] (so non-finite or huge coordinates are refused before i_overlay, which
//! would panic on them); outputs are polygons with outer rings counter-clockwise and holes
//! clockwise, collinear vertices removed.

use i_overlay::core::fill_rule::FillRule;
use i_overlay::core::overlay::Overlay;
use i_overlay::core::overlay_rule::OverlayRule;
use i_overlay::i_float::int::point::IntPoint;

use crate::grid::{self, GridError};
use crate::polygon::{Polygon, Ring};

pub(crate) type IntContour = Vec<IntPoint<i32>>;
pub(crate) type IntShape = Vec<IntContour>;

/// The boolean operations.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Op {
    /// Points in either.
    Union,
    /// Points in both.
    Intersection,
    /// Points in the first and not the second.
    Difference,
    /// Points in exactly one.
    Xor,
}

pub(crate) fn ring_to_grid(ring: &[glam::DVec2]) -> Result<IntContour, GridError> {
    ring.iter()
        .map(|p| grid::point_to_grid(*p).map(|[x, y]| IntPoint::new(x, y)))
        .collect()
}

pub(crate) fn polygons_to_grid(polygons: &[Polygon]) -> Result<Vec<IntShape>, GridError> {
    polygons
        .iter()
        .map(|p| {
            std::iter::once(&p.outer)
                .chain(p.holes.iter())
                .map(|r| ring_to_grid(r))
                .collect()
        })
        .collect()
}

pub(crate) fn shapes_from_grid(shapes: Vec<IntShape>) -> Vec<Polygon> {
    shapes
        .into_iter()
        .filter_map(|shape| {
            let mut rings = shape
                .into_iter()
                .map(|c| c.into_iter().map(|p| grid::from_grid([p.x, p.y])).collect::<Ring>());
            let outer = rings.next()?;
            Some(Polygon {
                outer,
                holes: rings.collect(),
            })
        })
        .collect()
}

/// Applies `op` to two sets of polygons (each set's own overlaps are unioned first).
pub fn apply(op: Op, a: &[Polygon], b: &[Polygon]) -> Result<Vec<Polygon>, GridError> {
    let subj = polygons_to_grid(a)?;
    let clip = polygons_to_grid(b)?;
    let rule = match op {
        Op::Union => OverlayRule::Union,
        Op::Intersection => OverlayRule::Intersect,
        Op::Difference => OverlayRule::Difference,
        Op::Xor => OverlayRule::Xor,
    };
    let shapes = Overlay::from_subj_and_clip(&subj, &clip).overlay(rule, FillRule::NonZero);
    Ok(shapes_from_grid(shapes))
}

/// Union of two sets of polygons.
pub fn union(a: &[Polygon], b: &[Polygon]) -> Result<Vec<Polygon>, GridError> {
    apply(Op::Union, a, b)
}

/// Intersection of two sets of polygons.
pub fn intersection(a: &[Polygon], b: &[Polygon]) -> Result<Vec<Polygon>, GridError> {
    apply(Op::Intersection, a, b)
}

/// `a` minus `b`.
pub fn difference(a: &[Polygon], b: &[Polygon]) -> Result<Vec<Polygon>, GridError> {
    apply(Op::Difference, a, b)
}

/// Merges overlapping polygons of one set into disjoint polygons.
pub fn union_all(a: &[Polygon]) -> Result<Vec<Polygon>, GridError> {
    apply(Op::Union, a, &[])
}

/// Hole detection: turns closed rings (any orientation, any nesting) into polygons by the
/// even-odd rule. A ring inside one other ring is a hole; a ring inside a hole is an island,
/// returned as a polygon of its own.
pub fn from_rings_even_odd(rings: &[Ring]) -> Result<Vec<Polygon>, GridError> {
    let contours = rings.iter().map(|r| ring_to_grid(r)).collect::<Result<Vec<_>, _>>()?;
    let shapes = Overlay::from_subj(&contours).overlay(OverlayRule::Subject, FillRule::EvenOdd);
    Ok(shapes_from_grid(shapes))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::polygon::{signed_area, total_area};
    use glam::DVec2;

    use crate::polygon::rect;

    #[test]
    fn overlapping_squares() {
        let a = [Polygon::new(rect(0.0, 0.0, 10.0, 10.0))];
        let b = [Polygon::new(rect(5.0, 5.0, 15.0, 15.0))];
        assert!((total_area(&union(&a, &b).expect("grid")) - 175.0).abs() < 1e-9);
        assert!((total_area(&intersection(&a, &b).expect("grid")) - 25.0).abs() < 1e-9);
        assert!((total_area(&difference(&a, &b).expect("grid")) - 75.0).abs() < 1e-9);
    }

    #[test]
    fn even_odd_nesting_makes_holes_and_islands() {
        // Outer 100², hole 60², island 20² inside the hole; orientations deliberately mixed.
        let rings = vec![
            rect(0.0, 0.0, 100.0, 100.0),
            rect(20.0, 20.0, 80.0, 80.0),
            rect(40.0, 40.0, 60.0, 60.0),
        ];
        let mut polys = from_rings_even_odd(&rings).expect("grid");
        polys.sort_by(|a, b| b.area().total_cmp(&a.area()));
        assert_eq!(polys.len(), 2);
        assert_eq!(polys[0].holes.len(), 1);
        assert!((polys[0].area() - (10000.0 - 3600.0)).abs() < 1e-9);
        assert!(signed_area(&polys[0].outer) > 0.0);
        assert!(signed_area(&polys[0].holes[0]) < 0.0);
        assert!((polys[1].area() - 400.0).abs() < 1e-9);
    }

    #[test]
    fn refuses_non_finite() {
        let a = [Polygon::new(vec![DVec2::ZERO, DVec2::new(f64::NAN, 0.0), DVec2::ONE])];
        assert_eq!(union_all(&a), Err(GridError::NonFinite));
    }
}
