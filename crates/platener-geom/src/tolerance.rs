//! One bundle of tolerances, derived from the model's size, passed explicitly everywhere.
//!
//! No step uses a bare epsilon: every "is this zero / equal / straight" question reads one of
//! these fields, so tuning happens in one place and tests can state what they assume.

use serde::Serialize;

/// Pieces of a boolean or offset result smaller than this (mm²) are rounding noise of the
/// [1 µm grid](crate::grid::STEP), not material: a sliver one grid step wide and 0.1 mm long.
/// Slivers a laser cannot cut are found by width (an opening), not by this area; this only
/// tells an empty result from a real one.
pub const GRID_NOISE_AREA: f64 = 1e-4;

/// Overlaps between two plates' volumes smaller than this (mm²) are grid noise: ten times
/// [`GRID_NOISE_AREA`], because such an overlap comes from two booleans computed through two
/// different plates' frames, each rounding by up to a grid step.
pub const OVERLAP_NOISE_AREA: f64 = 1e-3;

/// Islands of a stacked layer under this area (mm²) are crumbs of the slicing booleans (a
/// 0.1 × 0.1 mm speck), not material: dropped without a report. Islands above it but too small
/// to cut are dropped by the minimum area and width settings, and reported.
pub const CRUMB_AREA: f64 = 0.01;

/// Tolerances of a conversion. Lengths in mm, angles in radians.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Tolerances {
    /// Two points closer than this are the same point (exact duplicates after float noise).
    pub identical: f64,
    /// A triangle whose area is below `identical · longest edge` is degenerate (zero height).
    pub degenerate_height: f64,
    /// A vertex whose distance from the line through its neighbours is below this lies on a
    /// straight run and is removed from outlines.
    pub straight: f64,
    /// Connected faces whose normals differ by less than this angle are one planar group.
    pub coplanar_angle: f64,
}

impl Tolerances {
    /// Tolerances for a model whose bounding-box diagonal is `diagonal` mm.
    ///
    /// `identical` is 1e-9 of the size (float noise of f32 coordinates is ~1e-7 relative, but
    /// exact duplicates are what we remove here), at least one grid step below the 2D grid.
    pub fn for_model(diagonal: f64) -> Self {
        let size = if diagonal.is_finite() && diagonal > 0.0 {
            diagonal
        } else {
            1.0
        };
        Self {
            identical: (size * 1e-9).max(1e-9),
            degenerate_height: (size * 1e-7).max(1e-9),
            straight: (size * 1e-4).clamp(1e-6, 0.01),
            coplanar_angle: 1.0_f64.to_radians(),
        }
    }
}

impl Default for Tolerances {
    fn default() -> Self {
        Self::for_model(100.0)
    }
}
