//! The bend zone of one bend: how wide the strip that curves is on the flat part, and what
//! that does to the flat length (the bend allowance of sheet-metal practice).
//!
//! The zone bends as an arc of the neutral (mid-thickness) surface of radius R tangent to both
//! plates' mid-planes. Its flat width is the arc's length R·φ (φ the turn), while the sharp
//! corner of the model's plates would have 2·R·tan(φ/2) of mid-plane between the two
//! tangent lines: developing the sharp corner and then moving the far plate back by the
//! difference (the bend deduction) gives a flat part that closes to the model's size.
//! The zone's width and pattern come from [`crate::hinge`] (living-hinge physics, folds).

use serde::Serialize;

use crate::hinge::{BendDesign, HingeError, design as hinge_design, design_lattice};
use crate::plan::{BendStyle, Material};

/// The zone of one bend: its hinge or fold design, the one source of its width and radius.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[serde(transparent)]
pub struct BendZone {
    /// The hinge or fold that makes it (links, slits, dashes).
    pub design: BendDesign,
}

impl BendZone {
    /// How the material is made to bend.
    pub fn style(&self) -> BendStyle {
        self.design.style
    }

    /// The turn, radians.
    pub fn turn(&self) -> f64 {
        self.design.turn
    }

    /// Width of the zone on the flat part, mm (the neutral arc's length).
    pub fn width(&self) -> f64 {
        self.design.zone_width
    }

    /// Radius of the neutral arc, mm.
    pub fn radius(&self) -> f64 {
        self.design.neutral_radius
    }

    /// How far each tangent line lies from the sharp corner of the mid-planes: R·tan(φ/2).
    pub fn setback(&self) -> f64 {
        self.radius() * (self.turn() / 2.0).tan()
    }

    /// How much shorter the flat part is than the sharp corner's development: 2·setback − width.
    pub fn deduction(&self) -> f64 {
        2.0 * self.setback() - self.width()
    }

    /// How far inside the model's sharp corner the bent arc passes, mm (see
    /// [`BendDesign::corner_gap`]).
    pub fn corner_gap(&self) -> f64 {
        self.design.corner_gap()
    }
}

/// The largest turn the straight flex makes when the style is chosen by material: 16 facets
/// or more per full turn, a tessellated curve (a cylinder of 20 mm radius in 16 facets), not a
/// faceted design. Its limit is reported practice, not designed margin (docs/bending.md).
const FLEX_MAX_TURN_DEG: f64 = 22.6;

/// The widest zone of a turn whose arc passes at most `gap` inside the sharp corner.
fn width_for_gap(turn: f64, gap: f64) -> f64 {
    let sec = 1.0 / (turn / 2.0).cos() - 1.0;
    if sec <= 0.0 { f64::INFINITY } else { gap * turn / sec }
}

/// The widest zone of a turn whose material bulging out of the model stays under 4 % of the
/// neighbouring plates' (`t` thick, `depth` deep): at the inner face the arc of radius
/// ρ = R − t/2 leaves the sharp corner by a crescent of area ρ²·(tan(φ/2) − φ/2), which is
/// material where the model has none.
fn width_for_bulge(turn: f64, t: f64, depth: f64) -> f64 {
    let lune = (turn / 2.0).tan() - turn / 2.0;
    if lune <= 0.0 {
        return f64::INFINITY;
    }
    turn * (t / 2.0 + (0.04 * t * depth / lune).sqrt())
}

/// The room a bend has: the sheet, how deep its plates are and how wide its zone may be.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Room {
    /// Sheet thickness, mm.
    pub thickness: f64,
    /// How far the shallower plate reaches from the line where the mid-planes meet, mm.
    pub depth: f64,
    /// The widest zone that leaves each plate a flat segment, mm.
    pub max_width: f64,
    /// The neutral radius of the model's own rounding when the plates stop short of their
    /// corner by a run of narrow facets (an arc zone replaces them), mm.
    pub fillet: Option<f64>,
}

/// The zone of a bend of `turn` radians in `style` with `room`, or why there is none. The
/// widest hinge (strongest links) whose bulge out of the model stays small is taken; else
/// the narrowest hinge there is, if it rounds the model's corner by at most a thickness, or
/// (`strict` off: a style the user asked for) if it fits at all. All of this with the
/// lattice first, so every bend it made stays as it was; only where it makes none is the
/// straight flex tried, and with the style chosen by material (`strict`) only on a
/// tessellated curve ([`FLEX_MAX_TURN_DEG`], or a fillet: a run of narrow facets): a
/// coarser corner (the low-poly lamp's 25–40°) is a design and stays jointed.
///
/// Across a fillet the zone spans the whole run of facets: a hinge that could bend tighter
/// is widened to the fillet's own arc, and one that needs a larger radius may pass at most
/// a thickness inside the fillet (strict) instead of inside the sharp corner.
pub(crate) fn design(
    style: BendStyle,
    material: Material,
    room: Room,
    turn: f64,
    strict: bool,
) -> Result<BendZone, String> {
    let Some(fillet) = room.fillet else {
        return design_corner(style, material, room, turn, strict);
    };
    let own = fillet * turn;
    let sec = 1.0 / (turn / 2.0).cos() - 1.0;
    let rounding = width_for_gap(turn, fillet * sec + room.thickness);
    let allowed = if strict {
        room.max_width.min(rounding)
    } else {
        room.max_width
    };
    if own > room.max_width {
        return Err(format!(
            "the fillet's arc is {own:.1} mm long, only {:.1} mm of its walls could bend",
            room.max_width
        ));
    }
    let design = match hinge_design(style, material, room.thickness, turn, allowed) {
        Ok(design) => design,
        Err(HingeError::TooWide { needed, .. }) => {
            let why = if strict && needed <= room.max_width {
                " without rounding the model's fillet by more than a thickness"
            } else {
                ""
            };
            return Err(format!(
                "the bend zone would be {needed:.1} mm wide, only {allowed:.1} mm fit{why}"
            ));
        }
        Err(e) => return Err(e.to_string()),
    };
    let design = design.widened(own);
    // A fold is one crease: it makes a sharp corner where the model is round.
    let off = (design.neutral_radius - fillet).abs() * sec;
    if strict && off > room.thickness {
        return Err(format!(
            "a {} would leave the model's {fillet:.1} mm fillet by {off:.1} mm",
            style.name()
        ));
    }
    Ok(BendZone { design })
}

/// [`design`] at a sharp corner (plates that reach their line).
fn design_corner(
    style: BendStyle,
    material: Material,
    room: Room,
    turn: f64,
    strict: bool,
) -> Result<BendZone, String> {
    let (thickness, depth, max_width) = (room.thickness, room.depth, room.max_width);
    let lattice = |limit: f64| design_lattice(style, material, thickness, turn, limit);
    let why = match fit(lattice, (thickness, depth), turn, max_width, strict) {
        Ok(zone) => return Ok(zone),
        Err(why) => why,
    };
    if strict && turn > FLEX_MAX_TURN_DEG.to_radians() {
        return Err(why);
    }
    let either = |limit: f64| hinge_design(style, material, thickness, turn, limit);
    fit(either, (thickness, depth), turn, max_width, strict).map_err(|_| why)
}

/// [`design`] with the hinges `attempt` gives for a width limit.
fn fit(
    attempt: impl Fn(f64) -> Result<BendDesign, HingeError>,
    (thickness, depth): (f64, f64),
    turn: f64,
    max_width: f64,
    strict: bool,
) -> Result<BendZone, String> {
    let zone = |design: BendDesign| BendZone { design };
    let narrowest = match attempt(max_width.min(width_for_bulge(turn, thickness, depth))) {
        Ok(design) => return Ok(zone(design)),
        Err(HingeError::TooWide { needed, .. }) => needed,
        Err(e) => return Err(e.to_string()),
    };
    let allowed = if strict {
        max_width.min(width_for_gap(turn, thickness))
    } else {
        max_width
    };
    if narrowest > allowed {
        let why = if strict && narrowest <= max_width {
            " without rounding the model's corner by more than a thickness"
        } else {
            ""
        };
        return Err(format!(
            "the bend zone would be {narrowest:.1} mm wide, only {allowed:.1} mm fit{why}"
        ));
    }
    attempt(narrowest + 1e-9).map(zone).map_err(|e| e.to_string())
}
