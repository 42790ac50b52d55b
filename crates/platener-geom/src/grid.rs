//! The project-wide fixed grid for 2D booleans and offsets.
//!
//! i_overlay's integer API is exact: every 2D point is snapped to a grid of [`STEP`] mm
//! (1 µm, far below what a laser resolves) and stored as `i32`. One grid for the whole project
//! means results of different steps combine without re-snapping slivers. The i32 engine takes
//! coordinates up to ±2^30 steps, i.e. ±1073 m; we refuse anything beyond [`LIMIT`].

use glam::DVec2;

/// Grid step in mm.
pub const STEP: f64 = 1e-3;
/// Largest absolute 2D coordinate (mm) accepted: 1000 m, inside i_overlay's i32 range.
pub const LIMIT: f64 = 1.0e6;

/// A 2D coordinate that cannot go on the grid.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum GridError {
    /// NaN or infinite.
    NonFinite,
    /// Larger than [`LIMIT`] in absolute value.
    OutOfRange(f64),
}

impl core::fmt::Display for GridError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            GridError::NonFinite => f.write_str("coordinate is not a finite number"),
            GridError::OutOfRange(v) => {
                write!(f, "coordinate {v} mm is beyond the ±{LIMIT} mm the 2D grid holds")
            }
        }
    }
}

impl core::error::Error for GridError {}

/// Snaps one coordinate (mm) to grid units.
pub fn to_grid(v: f64) -> Result<i32, GridError> {
    if !v.is_finite() {
        return Err(GridError::NonFinite);
    }
    if v.abs() > LIMIT {
        return Err(GridError::OutOfRange(v));
    }
    // In range by the check above: |v / STEP| <= 1e9 < 2^30.
    Ok((v / STEP).round() as i32)
}

/// Snaps a point to grid units.
pub fn point_to_grid(p: DVec2) -> Result<[i32; 2], GridError> {
    Ok([to_grid(p.x)?, to_grid(p.y)?])
}

/// Back from grid units to mm.
pub fn from_grid(p: [i32; 2]) -> DVec2 {
    DVec2::new(p[0] as f64 * STEP, p[1] as f64 * STEP)
}

/// Rounds a point to the nearest grid point, in mm (what a boolean would output for it).
pub fn snap(p: DVec2) -> Result<DVec2, GridError> {
    point_to_grid(p).map(from_grid)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn round_trip_is_within_half_a_step() {
        for v in [0.0, 1.2345678, -987.6543, 123456.789] {
            let g = to_grid(v).expect("in range");
            assert!((g as f64 * STEP - v).abs() <= STEP / 2.0 + 1e-12);
        }
    }

    #[test]
    fn rejects_bad_coordinates() {
        assert_eq!(to_grid(f64::NAN), Err(GridError::NonFinite));
        assert_eq!(to_grid(f64::INFINITY), Err(GridError::NonFinite));
        assert!(matches!(to_grid(2.0e6), Err(GridError::OutOfRange(_))));
    }
}
