//! The bend zone of one bend: how wide the strip that curves is on the flat part, and what
//! that does to the flat length (the bend allowance of sheet-metal practice).
//!
//! The zone bends as an arc of the neutral (mid-thickness) surface of radius R tangent to both
//! plates' mid-planes. Its flat width is the arc's length R·φ (φ the turn), while the sharp
//! corner of the model's plates would have 2·R·tan(φ/2) of mid-plane between the two
//! tangent lines: developing the sharp corner and then moving the far plate back by the
//! difference (the bend deduction) gives a flat part that closes to the model's size.

use serde::Serialize;

use crate::plan::{BendStyle, Material};

/// The zone of one bend.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Zone {
    /// How the material is made to bend.
    pub style: BendStyle,
    /// The turn, radians.
    pub turn: f64,
    /// Width of the zone on the flat part, mm (the neutral arc's length).
    pub width: f64,
    /// Radius of the neutral arc, mm.
    pub radius: f64,
}

impl Zone {
    /// How far each tangent line lies from the sharp corner of the mid-planes: R·tan(φ/2).
    pub fn setback(&self) -> f64 {
        self.radius * (self.turn / 2.0).tan()
    }

    /// How much shorter the flat part is than the sharp corner's development: 2·setback − width.
    pub fn deduction(&self) -> f64 {
        2.0 * self.setback() - self.width
    }

    /// How far inside the model's sharp corner the bent arc passes, mm: R·(1/cos(φ/2) − 1).
    pub fn corner_gap(&self) -> f64 {
        self.radius * (1.0 / (self.turn / 2.0).cos() - 1.0)
    }
}

/// The zone of a bend of `turn` radians in `style`, at most `max_width` wide on the flat, or
/// why there is none.
pub(crate) fn design(
    style: BendStyle,
    material: Material,
    thickness: f64,
    turn: f64,
    max_width: f64,
) -> Result<Zone, String> {
    let _ = material;
    let radius = match style {
        BendStyle::LivingHinge => {
            let square = (0.676 * turn * 86.6 / 4.0).ceil() * (thickness + 0.2);
            let narrow = (0.676 * turn * 86.6 / 4.0 / 1.45).ceil() * (thickness / 2.0 + 0.2);
            let width = if square <= max_width { square } else { narrow };
            if width > max_width {
                return Err(format!("a living hinge needs {width:.1} mm, {max_width:.1} mm fit"));
            }
            width / turn
        }
        BendStyle::Perforation | BendStyle::Score => thickness / 2.0,
        BendStyle::Heat => 1.5 * thickness,
    };
    Ok(Zone {
        style,
        turn,
        width: radius * turn,
        radius,
    })
}
