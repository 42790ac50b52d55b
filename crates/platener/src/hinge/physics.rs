//! How wide a bend zone is and what its hinge looks like, from the physics of each style.
//!
//! A **living hinge** (lattice hinge) is rows of staggered slits parallel to the bend line; the
//! material between two rows forms torsion links of length `l` (the overlap of staggered slits)
//! and width `b`. The turn Θ is shared by the `n` links in series, and a rectangular bar of
//! sides `b`, `t` twisted by θ over its length `l` sees the shear stress
//! `τ = c · G · b_min · θ / l` (`c = k1/k2` of the torsion table, `b_min = min(b, t)`), so each
//! link may twist at most `θ_max = τ · l / (c · G · b_min)` and `n ≥ Θ / θ_max`. The flat zone
//! is `n` pitches wide and curves on the neutral axis (bend allowance), so its radius is
//! `R = w / Θ`. Folds (perforation, score) and heat bends are a radius and a line.
//! docs/bending.md derives these and cites the material values.

use std::f64::consts::{FRAC_PI_2, PI};

use super::HingeError;
use crate::plan::{BendStyle, HingePattern, Material};

/// Thickest sheet accepted, mm (as the kerf strip).
const MAX_THICKNESS: f64 = 50.0;
/// Longest link, in thicknesses: longer links let the sheet splay instead of twisting cleanly
/// (lattice-hinge tests, docs/bending.md).
const MAX_LINK_LENGTH: f64 = 4.0;
/// Narrowest link, in thicknesses: narrower links burn through or snap when cut.
const MIN_LINK_WIDTH: f64 = 0.5;
/// Link widths tried from square (b = t) down to [`MIN_LINK_WIDTH`].
const WIDTH_STEPS: u32 = 10;

/// The straight-cut flex (boxes.py's flex pattern, whose parameters are in thicknesses: cut
/// lines 0.5 t apart, t bridges, a slit every 5 t) bends in plywood to about 5 t: makers bend
/// it around 15 mm in 3 mm plywood, boxes.py's FlexBox default. An empirical limit, not the
/// torsion model (which gives 36 mm for it at 3 mm); `platener hinge-test` draws it so the stock can
/// be checked. docs/bending.md has the sources.
const FLEX_MIN_RADIUS: f64 = 5.0;
/// Distance between the flex's cut lines, in thicknesses.
const FLEX_PITCH: f64 = 0.5;
/// The flex's bridges, in thicknesses.
const FLEX_BRIDGE: f64 = 1.0;
/// The flex's period along the line (a slit and a bridge), in thicknesses.
const FLEX_PERIOD: f64 = 5.0;

/// The largest turn of one crease of a fold spread over a fillet's arc, degrees: six creases
/// round a right angle, as a fillet of six facets does.
pub const MAX_CREASE_TURN_DEG: f64 = 15.0;

/// Torsion table of a rectangular section (Timoshenko & Goodier, Theory of Elasticity, §109;
/// Roark's Formulas, table of torsion constants): `(short/long side, k1, k2)` with the torque
/// `T = k1 · G · θ' · a · b³` and the largest stress `τ = T / (k2 · a · b²)`, `b` the short side.
const TORSION_TABLE: [(f64, f64, f64); 9] = [
    (0.0, 1.0 / 3.0, 1.0 / 3.0),
    (0.1, 0.312, 0.312),
    (0.2, 0.291, 0.291),
    (0.25, 0.281, 0.282),
    (1.0 / 3.0, 0.263, 0.267),
    (0.4, 0.249, 0.258),
    (0.5, 0.229, 0.246),
    (1.0 / 1.5, 0.196, 0.231),
    (1.0, 0.1406, 0.208),
];

/// `c = k1 / k2` of a rectangular section with sides `b` and `t`, interpolated linearly in the
/// ratio short/long side (0.676 for a square, → 1 for a thin strip).
pub fn torsion_ratio(b: f64, t: f64) -> f64 {
    let r = (b.min(t) / b.max(t)).clamp(0.0, 1.0);
    let c = |(_, k1, k2): (f64, f64, f64)| k1 / k2;
    for w in TORSION_TABLE.windows(2) {
        let (lo, hi) = (w[0], w[1]);
        if r <= hi.0 {
            let f = (r - lo.0) / (hi.0 - lo.0);
            return c(lo) + f * (c(hi) - c(lo));
        }
    }
    c(TORSION_TABLE[TORSION_TABLE.len() - 1])
}

/// The values of a sheet material the hinge physics needs.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MaterialData {
    /// Name, for docs and errors.
    pub name: &'static str,
    /// Shear modulus G, MPa.
    pub shear_modulus: f64,
    /// Shear stress a link may take, MPa (the shear strength, or a safe fraction of it for a
    /// brittle material).
    pub shear_strength: f64,
    /// Width of a slit (the laser's kerf), mm.
    pub kerf: f64,
}

impl MaterialData {
    /// Birch plywood (docs/bending.md: G 620 MPa, panel shear strength 7.2 MPa).
    pub const PLYWOOD: MaterialData = MaterialData {
        name: "plywood",
        shear_modulus: 620.0,
        shear_strength: 7.2,
        kerf: 0.2,
    };
    /// MDF (docs/bending.md: G 1100 MPa, shear strength 6 MPa); not a `plan::Material` yet.
    pub const MDF: MaterialData = MaterialData {
        name: "mdf",
        shear_modulus: 1100.0,
        shear_strength: 6.0,
        kerf: 0.2,
    };
    /// Cast acrylic (docs/bending.md: G 1150 MPa; a third of its 60 MPa shear strength, since
    /// it is brittle).
    pub const ACRYLIC: MaterialData = MaterialData {
        name: "acrylic",
        shear_modulus: 1150.0,
        shear_strength: 20.0,
        kerf: 0.15,
    };

    /// The values for `material` if links of it can twist at all (wood is taken as plywood;
    /// card and paper tear instead of twisting).
    pub fn of(material: Material) -> Option<MaterialData> {
        match material {
            Material::Wood => Some(Self::PLYWOOD),
            Material::Acrylic => Some(Self::ACRYLIC),
            Material::Cardboard | Material::Paper => None,
        }
    }

    /// The largest twist of one link `b` wide and `l` long in a sheet `t` thick, radians.
    pub fn max_link_twist(&self, b: f64, t: f64, l: f64) -> f64 {
        self.shear_strength * l / (torsion_ratio(b, t) * self.shear_modulus * b.min(t))
    }
}

/// One designed bend zone: its width on the flat part and, for a living hinge, its slits.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct BendDesign {
    /// How it bends.
    pub style: BendStyle,
    /// A living hinge's slit pattern (the lattice for every other style).
    pub pattern: HingePattern,
    /// Sheet thickness, mm.
    pub thickness: f64,
    /// The turn, radians (π − the enclosed angle).
    pub turn: f64,
    /// Width of the zone on the flat part (the neutral axis' arc length), mm.
    pub zone_width: f64,
    /// Radius of the neutral (mid-thickness) surface once bent, mm.
    pub neutral_radius: f64,
    /// Torsion links in series across the zone (0 for folds and heat bends).
    pub links: u32,
    /// Link width b (across the zone), mm.
    pub link_width: f64,
    /// Link length l (the overlap of staggered slits, along the bend line), mm.
    pub link_length: f64,
    /// Length of one slit (living hinge) or cut dash (perforation), mm.
    pub slit_length: f64,
    /// Uncut material between two slits of a row (living hinge) or two dashes (perforation), mm.
    pub bridge: f64,
    /// Rows of slits (living hinge), or the creases of a fold (1, or several when it spans a
    /// fillet's arc), or 1: the one line of a heat bend.
    pub rows: u32,
    /// Row pitch (link width + kerf), or the spacing of a fold's creases, mm; 0 for a single
    /// line.
    pub pitch: f64,
}

impl BendDesign {
    /// How far the bent arc stays inside the sharp corner of the model, mm:
    /// `R · (1 / cos(Θ/2) − 1)`, the distance from the arc's middle to where the two flat
    /// sides' mid-planes meet. Infinite for a U-turn (180°): its sides are parallel and meet
    /// nowhere.
    pub fn corner_gap(&self) -> f64 {
        if self.turn >= PI - 1e-9 {
            return f64::INFINITY;
        }
        self.neutral_radius * (1.0 / (self.turn / 2.0).cos() - 1.0)
    }

    /// The same hinge spread over a zone at least `width` wide, to span a fillet's whole arc:
    /// more rows at the same pitch, so each link twists less (a wider zone only eases a
    /// hinge). A fold becomes evenly spaced creases over exactly `width`, each turning at
    /// most [`MAX_CREASE_TURN_DEG`], so the card follows the arc; a heat bend (one guide line
    /// over the heater) stays as it is.
    #[must_use]
    pub fn widened(self, width: f64) -> Self {
        if width.is_nan() || width <= self.zone_width {
            return self;
        }
        if matches!(self.style, BendStyle::Perforation | BendStyle::Score) {
            let creases = (self.turn / MAX_CREASE_TURN_DEG.to_radians() - 1e-9).ceil().max(2.0);
            return Self {
                rows: creases as u32,
                pitch: width / creases,
                zone_width: width,
                neutral_radius: width / self.turn,
                ..self
            };
        }
        if self.style != BendStyle::LivingHinge || self.pitch <= 0.0 {
            return self;
        }
        let links = (width / self.pitch - 1e-9).ceil().max(f64::from(self.links));
        let zone_width = links * self.pitch;
        Self {
            links: links as u32,
            rows: links as u32 + 1,
            zone_width,
            neutral_radius: zone_width / self.turn,
            ..self
        }
    }

    /// How far one slit pattern repeats along the bend line, mm (slit + bridge).
    pub fn period(&self) -> f64 {
        self.slit_length + self.bridge
    }
}

/// The largest turn (radians) `style` can make in `thickness` mm of `material`; 0 when the style
/// does not work there. Heat bends and folds make 90° (sharper folds crack card's facing and
/// acrylic crazes); a living hinge in wood makes a U-turn (180°, e.g. a phone stand), in
/// brittle acrylic 90°.
pub fn max_turn(style: BendStyle, material: Material, thickness: f64) -> f64 {
    use Material::{Acrylic, Cardboard, Paper, Wood};
    match (style, material) {
        (BendStyle::LivingHinge, Wood) => PI,
        (BendStyle::LivingHinge, Acrylic)
        | (BendStyle::Perforation, Cardboard | Paper)
        | (BendStyle::Score, Paper)
        | (BendStyle::Heat, Acrylic) => FRAC_PI_2,
        // Only thin card folds along a score without cracking.
        (BendStyle::Score, Cardboard) if thickness <= 1.0 => FRAC_PI_2,
        _ => 0.0,
    }
}

/// Checks that `value` is positive and finite.
fn positive(name: &'static str, value: f64) -> Result<f64, HingeError> {
    if value.is_finite() && value > 0.0 {
        Ok(value)
    } else {
        Err(HingeError::Invalid { name, value })
    }
}

/// Designs a bend turning by `turn` radians in `thickness` mm of `material`, whose zone is at
/// most `max_width` mm wide (`f64::INFINITY` for no limit). A living hinge takes square links
/// if they fit, else narrower ones (each twists more, so fewer are needed) down to half the
/// thickness; a zone that still does not fit is [`HingeError::TooWide`].
pub fn design(
    style: BendStyle,
    material: Material,
    thickness: f64,
    turn: f64,
    max_width: f64,
) -> Result<BendDesign, HingeError> {
    design_with(style, material, (thickness, turn), max_width, true)
}

/// [`design`] without the straight flex: a living hinge is always the lattice (the `bends`
/// step tries it first, so the bends it made before the flex stay as they were).
pub fn design_lattice(
    style: BendStyle,
    material: Material,
    thickness: f64,
    turn: f64,
    max_width: f64,
) -> Result<BendDesign, HingeError> {
    design_with(style, material, (thickness, turn), max_width, false)
}

/// [`design`], with the straight flex as the living hinge's fallback when `flex`.
fn design_with(
    style: BendStyle,
    material: Material,
    (thickness, turn): (f64, f64),
    max_width: f64,
    flex: bool,
) -> Result<BendDesign, HingeError> {
    let t = positive("thickness", thickness)?;
    if t > MAX_THICKNESS {
        return Err(HingeError::Invalid {
            name: "thickness",
            value: t,
        });
    }
    positive("turn", turn)?;
    if max_width.is_nan() || max_width <= 0.0 {
        return Err(HingeError::Invalid {
            name: "max_width",
            value: max_width,
        });
    }
    let max = max_turn(style, material, t);
    if max == 0.0 {
        return Err(HingeError::Unsuitable {
            style,
            material,
            thickness: t,
        });
    }
    if turn > max + 1e-9 {
        return Err(HingeError::TooSharp {
            style,
            turn_deg: turn.to_degrees(),
            max_deg: max.to_degrees(),
        });
    }
    let design = match (style, MaterialData::of(material)) {
        (BendStyle::LivingHinge, Some(data)) if flex => return either_pattern(&data, material, t, turn, max_width),
        (BendStyle::LivingHinge, Some(data)) => return living_hinge(&data, t, turn, max_width),
        _ => fold(style, t, turn),
    };
    if design.zone_width > max_width {
        return Err(HingeError::TooWide {
            needed: design.zone_width,
            max_width,
        });
    }
    Ok(design)
}

/// The lattice when it fits `max_width` (its links are designed from their torsion, with the
/// margin that gives), else the straight flex where the material takes it (wood) and its
/// tighter radius fits.
fn either_pattern(
    data: &MaterialData,
    material: Material,
    t: f64,
    turn: f64,
    max_width: f64,
) -> Result<BendDesign, HingeError> {
    let lattice = living_hinge(data, t, turn, max_width);
    let Err(HingeError::TooWide { needed, .. }) = lattice else {
        return lattice;
    };
    match straight_flex(data, material, t, turn) {
        Some(d) if d.zone_width <= max_width => Ok(d),
        Some(d) => Err(HingeError::TooWide {
            needed: needed.min(d.zone_width),
            max_width,
        }),
        None => lattice,
    }
}

/// A living hinge of `pattern` turning by `turn` in `thickness` mm of `material` (the swatch
/// draws each pattern); `None` when the pattern does not suit the material or sheet.
pub fn design_pattern(pattern: HingePattern, material: Material, thickness: f64, turn: f64) -> Option<BendDesign> {
    if turn > max_turn(BendStyle::LivingHinge, material, thickness) + 1e-9 || turn.is_nan() || turn <= 0.0 {
        return None;
    }
    let data = MaterialData::of(material)?;
    match pattern {
        HingePattern::Lattice => living_hinge(&data, thickness, turn, f64::INFINITY).ok(),
        HingePattern::Straight => straight_flex(&data, material, thickness, turn),
    }
}

/// The straight-cut flex turning by `turn` at its tightest radius ([`FLEX_MIN_RADIUS`]): rows
/// [`FLEX_PITCH`] apart across a zone of that radius' arc. Wood only (acrylic's links crack
/// at such radii); `None` for a sheet so thin that its links would be under half the pitch.
fn straight_flex(data: &MaterialData, material: Material, t: f64, turn: f64) -> Option<BendDesign> {
    let pitch = FLEX_PITCH * t;
    let link_width = pitch - data.kerf;
    if material != Material::Wood || link_width < pitch / 2.0 {
        return None;
    }
    let links = (FLEX_MIN_RADIUS * t * turn / pitch).ceil().max(1.0);
    let zone_width = links * pitch;
    let bridge = FLEX_BRIDGE * t;
    let slit_length = FLEX_PERIOD * t - bridge;
    Some(BendDesign {
        style: BendStyle::LivingHinge,
        pattern: HingePattern::Straight,
        thickness: t,
        turn,
        zone_width,
        neutral_radius: zone_width / turn,
        links: links as u32,
        link_width,
        link_length: (slit_length - bridge) / 2.0,
        slit_length,
        bridge,
        rows: links as u32 + 1,
        pitch,
    })
}

/// The living hinge of the widest links, from square down to half the thickness, whose zone
/// fits `max_width`.
pub(super) fn living_hinge(data: &MaterialData, t: f64, turn: f64, max_width: f64) -> Result<BendDesign, HingeError> {
    let mut narrowest = None;
    for k in 0..=WIDTH_STEPS {
        let b = t * (1.0 - (1.0 - MIN_LINK_WIDTH) * f64::from(k) / f64::from(WIDTH_STEPS));
        let d = lattice(data, t, turn, b);
        if d.zone_width <= max_width {
            return Ok(d);
        }
        narrowest = Some(d);
    }
    Err(HingeError::TooWide {
        needed: narrowest.map_or(f64::INFINITY, |d| d.zone_width),
        max_width,
    })
}

/// The lattice of links `b` wide and `4t` long that turns by `turn`: enough links that none
/// is over-stressed and that neighbours, twisting, do not close the kerf between them.
fn lattice(data: &MaterialData, t: f64, turn: f64, b: f64) -> BendDesign {
    let l = MAX_LINK_LENGTH * t;
    let theta_max = data.max_link_twist(b, t, l);
    let mut n = (turn / theta_max).ceil().max(1.0);
    // A twisted b × t section is b·cos φ + t·sin φ wide: the slit must leave it room.
    while b * (turn / n).cos() + t * (turn / n).sin() - b > data.kerf {
        n += 1.0;
    }
    let pitch = b + data.kerf;
    let zone_width = n * pitch;
    // A bridge as long as the sheet is thick is at least as stiff as the link it holds, so
    // only the links twist.
    let bridge = t;
    BendDesign {
        style: BendStyle::LivingHinge,
        pattern: HingePattern::Lattice,
        thickness: t,
        turn,
        zone_width,
        neutral_radius: zone_width / turn,
        links: n as u32,
        link_width: b,
        link_length: l,
        slit_length: 2.0 * l + bridge,
        bridge,
        rows: n as u32 + 1,
        pitch,
    }
}

/// A fold or heat bend: a zone of the neutral arc's length around one line. Folds crease with
/// no inner radius (neutral radius t/2); acrylic is bent over a heater to an inner radius of
/// about t (neutral 1.5 t). A perforation's dashes are 3t long with t-long ties (at least
/// 0.5 mm) so the card folds along them but does not tear.
fn fold(style: BendStyle, t: f64, turn: f64) -> BendDesign {
    let neutral_radius = match style {
        BendStyle::Heat => 1.5 * t,
        _ => 0.5 * t,
    };
    let (slit_length, bridge) = match style {
        BendStyle::Perforation => ((3.0 * t).max(1.0), t.max(0.5)),
        _ => (0.0, 0.0),
    };
    BendDesign {
        style,
        pattern: HingePattern::Lattice,
        thickness: t,
        turn,
        zone_width: neutral_radius * turn,
        neutral_radius,
        links: 0,
        link_width: 0.0,
        link_length: 0.0,
        slit_length,
        bridge,
        rows: 1,
        pitch: 0.0,
    }
}
