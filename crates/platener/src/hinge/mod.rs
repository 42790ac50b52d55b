//! Bend zones of bent parts (issue 19): how wide a bend is, and the marks that make it bend.
//!
//! Not a pipeline step but a helper the `bends` step calls: [`design`] turns a bend (style,
//! material, thickness, turn) into a [`BendDesign`] from the physics of the style (the torsion
//! of lattice-hinge links, or a fold's radius), [`marks`] draws that design along a bend line
//! of a part's flat shape, and [`swatch`] lays out the `platener hinge-test` strip so a user can
//! check a hinge before cutting a whole part. docs/bending.md gives the formulas and the
//! material values with their sources.

mod pattern;
mod physics;

#[cfg(test)]
mod tests;

pub use pattern::marks;
pub use physics::{BendDesign, MaterialData, design, design_lattice, design_pattern, max_turn, torsion_ratio};

use crate::plan::{BendStyle, Material};

/// Why a bend cannot be designed or drawn.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum HingeError {
    /// A number that must be positive and finite is not.
    #[error("{name} must be a positive finite number, got {value}")]
    Invalid {
        /// Which input.
        name: &'static str,
        /// What was given.
        value: f64,
    },
    /// The style does not work in this material at this thickness.
    #[error("a {} bend does not work in {} mm {}", .style.name(), .thickness, .material.name())]
    Unsuitable {
        /// The style asked for.
        style: BendStyle,
        /// The material.
        material: Material,
        /// The sheet thickness, mm.
        thickness: f64,
    },
    /// The turn is more than the style can make.
    #[error("a {} bend turns at most {max_deg:.1}°, asked {turn_deg:.1}°", .style.name())]
    TooSharp {
        /// The style.
        style: BendStyle,
        /// The turn asked for, degrees.
        turn_deg: f64,
        /// The most it can turn, degrees.
        max_deg: f64,
    },
    /// Even the narrowest links make a zone wider than there is room for.
    #[error("the bend zone would be {needed:.1} mm wide, only {max_width:.1} mm fit")]
    TooWide {
        /// The narrowest zone the style can make, mm.
        needed: f64,
        /// The room there is, mm.
        max_width: f64,
    },
    /// The clip polygon could not be eroded on the grid.
    #[error("cannot erode the bend's clip outline: {0}")]
    Grid(#[from] platener_geom::GridError),
}
