//! Settings of the cutting plan: material and kerf, labels, sheets and nesting, laser speeds.
//!
//! Every default is here and documented in docs/cutting-plans.md; the CLI and the web service
//! only fill this struct.

use glam::DVec2;
use serde::{Deserialize, Serialize};

use super::error::PlanError;

/// The sheet material. It sets the default kerf, i.e. the width of material the laser burns
/// away along a cut (typical values for a 40–60 W CO₂ laser on 3 mm stock).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, Default)]
#[serde(rename_all = "lowercase")]
pub enum Material {
    /// Cast or extruded acrylic (PMMA): melts cleanly, kerf 0.15 mm.
    Acrylic,
    /// Plywood, MDF, solid wood: chars a little, kerf 0.2 mm (the default material).
    #[default]
    Wood,
    /// Corrugated or grey cardboard: burns wide, kerf 0.3 mm.
    Cardboard,
    /// Paper and thin card: kerf 0.1 mm.
    Paper,
}

impl Material {
    /// The default kerf in mm.
    pub fn default_kerf(self) -> f64 {
        match self {
            Material::Acrylic => 0.15,
            Material::Wood => 0.2,
            Material::Cardboard => 0.3,
            Material::Paper => 0.1,
        }
    }

    /// The lowercase name used in files and on the command line.
    pub fn name(self) -> &'static str {
        match self {
            Material::Acrylic => "acrylic",
            Material::Wood => "wood",
            Material::Cardboard => "cardboard",
            Material::Paper => "paper",
        }
    }
}

/// Which labels are engraved (engraving costs laser time, so the user chooses).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, Default)]
#[serde(rename_all = "lowercase")]
pub enum LabelMode {
    /// Part numbers and, next to every jointed edge, the connection number (default).
    #[default]
    Edges,
    /// Part numbers only.
    Parts,
    /// Nothing.
    None,
}

/// The stroke colours and widths the SVG sheets use for each operation, as one laser program
/// or service expects them (docs/cutting-plans.md has the table and its sources).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, Default)]
#[serde(rename_all = "lowercase")]
pub enum ColorProfile {
    /// Red cuts, blue engraving, hairlines: what most laser software reads as cut and engrave.
    #[default]
    Classic,
    /// Exact colours of LightBurn's palette, one layer per operation.
    LightBurn,
    /// One pure colour per operation, in ascending colour value in the order they should run.
    Glowforge,
    /// As Glowforge: xTool Creative Space makes one layer per colour.
    Xtool,
    /// Ponoko's convention: blue cuts, red vector engraving, 0.01 mm lines.
    Ponoko,
}

impl ColorProfile {
    /// Every profile, in the order the settings list them.
    pub const ALL: [ColorProfile; 5] = [
        ColorProfile::Classic,
        ColorProfile::LightBurn,
        ColorProfile::Glowforge,
        ColorProfile::Xtool,
        ColorProfile::Ponoko,
    ];

    /// The profile's name, as the setting takes it.
    pub fn name(self) -> &'static str {
        match self {
            ColorProfile::Classic => "classic",
            ColorProfile::LightBurn => "lightburn",
            ColorProfile::Glowforge => "glowforge",
            ColorProfile::Xtool => "xtool",
            ColorProfile::Ponoko => "ponoko",
        }
    }

    /// Whether this is the default profile (plan.json then leaves the key out).
    pub fn is_classic(&self) -> bool {
        *self == ColorProfile::Classic
    }
}

/// How long nesting searches (`nesting`): how many part orders it lays out side by side and
/// keeps the best of. More orders find denser layouts, linearly slower.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum NestEffort {
    /// One order, largest first: a plan at once, for previews and trials.
    Fast,
    /// Eight orders: the default, dense within a second or two on most plans.
    Good,
    /// Forty-eight orders: for the sheets you buy.
    Best,
}

impl NestEffort {
    /// Every level, in the order the settings list them.
    pub const ALL: [NestEffort; 3] = [NestEffort::Fast, NestEffort::Good, NestEffort::Best];

    /// The level's name, as the setting takes it.
    pub fn name(self) -> &'static str {
        match self {
            NestEffort::Fast => "fast",
            NestEffort::Good => "good",
            NestEffort::Best => "best",
        }
    }

    /// The part orders tried ([`CutSettings::nest_tries`]).
    pub fn tries(self) -> u32 {
        match self {
            NestEffort::Fast => 1,
            NestEffort::Good => 8,
            NestEffort::Best => 48,
        }
    }

    /// The level `tries` orders are, the nearest one at or below it.
    pub fn of(tries: u32) -> NestEffort {
        match tries {
            0..=7 => NestEffort::Fast,
            8..=47 => NestEffort::Good,
            _ => NestEffort::Best,
        }
    }
}

/// How tight joints fit (`fit`): a clearance across each finger and tab, both flanks together,
/// on top of the exact kerf compensation. Every cut path moves by a quarter of it (outward for
/// press), as a finger grows by two such moves and its notch shrinks by two.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, Default)]
#[serde(rename_all = "lowercase")]
pub enum Fit {
    /// 0.1 mm of interference: joints pressed home with a mallet hold without glue.
    Press,
    /// No clearance: the parts come out at their true size (the kerf compensated exactly).
    #[default]
    Snug,
    /// 0.15 mm of play: joints slide together by hand, for glued or knock-down builds.
    Loose,
}

impl Fit {
    /// Every fit, in the order the settings list them.
    pub const ALL: [Fit; 3] = [Fit::Press, Fit::Snug, Fit::Loose];

    /// The fit's name, as the setting takes it.
    pub fn name(self) -> &'static str {
        match self {
            Fit::Press => "press",
            Fit::Snug => "snug",
            Fit::Loose => "loose",
        }
    }

    /// The clearance across a finger or tab, both flanks together, mm; negative interferes.
    pub fn clearance(self) -> f64 {
        match self {
            Fit::Press => -0.1,
            Fit::Snug => 0.0,
            Fit::Loose => 0.15,
        }
    }

    /// How far every cut path moves outward for this fit, mm (a quarter of the interference).
    pub fn offset(self) -> f64 {
        -self.clearance() / 4.0
    }

    /// Whether this is the default fit (plan.json then leaves the key out).
    pub fn is_snug(&self) -> bool {
        *self == Fit::Snug
    }
}

/// A sheet sold as one thickness that measures another (`-t 3@2.85`): plywood sold as 3 mm
/// is 2.6–3.4 mm, and a finger joint's fit depends on that more than on the kerf. The parts
/// are made for the measured thickness (slots as wide as it, fingers as long); files and
/// captions name the sheet by its nominal thickness, as the maker buys and stores it.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct MeasuredThickness {
    /// What the sheet is sold as, mm.
    pub nominal: f64,
    /// What it measures, mm (the thickness every part of it is made for).
    pub measured: f64,
}

impl MeasuredThickness {
    /// The farthest a measured thickness may be from its nominal one, as a share of it;
    /// further is a typing error (`3@28.5`) rather than a real sheet.
    pub const MAX_DEVIATION: f64 = 0.25;

    /// Reads `nominal@measured` (`3@2.85`); `None` when `text` has no `@`.
    pub fn parse(text: &str) -> Option<Result<MeasuredThickness, String>> {
        let (nominal, measured) = text.split_once('@')?;
        let number = |t: &str| t.trim().parse::<f64>().ok().filter(|v| v.is_finite() && *v > 0.0);
        let (Some(nominal), Some(measured)) = (number(nominal), number(measured)) else {
            return Some(Err(
                "takes numbers, or a nominal and a measured thickness as 3@2.85".into()
            ));
        };
        if (measured / nominal - 1.0).abs() > Self::MAX_DEVIATION {
            return Some(Err(format!(
                "a measured thickness must be within {:.0} % of its sheet's nominal thickness (3@2.85)",
                100.0 * Self::MAX_DEVIATION
            )));
        }
        Some(Ok(MeasuredThickness { nominal, measured }))
    }

    /// As the setting takes it: `3@2.85`.
    pub fn text(&self) -> String {
        format!("{}@{}", self.nominal, self.measured)
    }
}

/// The sheets parts are nested on.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum SheetSize {
    /// Sheets of this size in mm, as many as needed.
    Fixed {
        /// Width (SVG x) in mm.
        width: f64,
        /// Height (SVG y) in mm.
        height: f64,
    },
    /// One sheet per thickness, just large enough for its parts.
    Fit,
}

impl Default for SheetSize {
    /// 600 × 400 mm: the bed of the common 60 W desktop CO₂ lasers.
    fn default() -> Self {
        SheetSize::Fixed {
            width: 600.0,
            height: 400.0,
        }
    }
}

impl std::str::FromStr for SheetSize {
    type Err = PlanError;

    /// `WxH` in mm (e.g. `600x400`, also with `×` or `*`) or `fit`, as `--sheet` takes it.
    fn from_str(s: &str) -> Result<Self, PlanError> {
        let s = s.trim();
        if s.eq_ignore_ascii_case("fit") {
            return Ok(SheetSize::Fit);
        }
        let bad = || PlanError::Setting {
            name: "sheet",
            message: format!("{s:?} is neither WxH in mm (e.g. 600x400) nor `fit`"),
        };
        let (w, h) = s.split_once(['x', 'X', '×', '*']).ok_or_else(bad)?;
        let (width, height) = (
            w.trim().parse().map_err(|_| bad())?,
            h.trim().parse().map_err(|_| bad())?,
        );
        Ok(SheetSize::Fixed { width, height })
    }
}

/// All settings of the cutting-plan steps (`kerf`, `labels`, `sheets`, `export`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct CutSettings {
    /// The sheet material (sets the default kerf).
    pub material: Material,
    /// Kerf in mm; `None` takes the material's default ([`Material::default_kerf`]).
    pub kerf: Option<f64>,
    /// Which labels to engrave.
    pub labels: LabelMode,
    /// Sheet size.
    pub sheet: SheetSize,
    /// Free border between the sheet edge and any cut path, mm (clamps, uneven edges).
    pub margin: f64,
    /// Least distance between the cut paths of two parts, mm; must exceed the kerf, or the
    /// laser would cut one part's edge while cutting its neighbour's.
    pub spacing: f64,
    /// Seed of the nesting search: the same seed gives the same layout.
    pub seed: u64,
    /// How many part orders the nesting tries (the first is largest-first); more is denser
    /// and slower, linearly.
    pub nest_tries: u32,
    /// Also try each part at the angle of its smallest bounding rectangle (plus 90° steps),
    /// not only at 0/90/180/270°.
    pub fine_rotations: bool,
    /// Let small parts go into the holes of large ones.
    pub fill_holes: bool,
    /// The laser: its kind and any speed the maker set (the time estimate's and the
    /// LightBurn project's speeds per material and thickness).
    #[serde(default)]
    pub laser: super::Laser,
    /// The SVG sheets' stroke colours per operation (plan.json leaves the default out).
    #[serde(default, skip_serializing_if = "ColorProfile::is_classic")]
    pub colors: ColorProfile,
    /// Score a 100 mm square with "100 MM" on each sheet where there is room, to check the
    /// scale after import (plan.json leaves the default, off, out).
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub reference_square: bool,
    /// The sheets the maker has (`stock`), nested onto in the order listed; a thickness with
    /// none listed goes on sheets of `sheet` (plan.json leaves an empty list out).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub stock: Vec<super::StockSheet>,
    /// Sheets whose measured thickness is not their nominal one (plan.json leaves an empty
    /// list out); the sheet thicknesses are the measured ones.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub measured: Vec<MeasuredThickness>,
    /// How tight joints fit (plan.json leaves the default, snug, out).
    #[serde(default, skip_serializing_if = "Fit::is_snug")]
    pub fit: Fit,
    /// Crush ribs on the long walls of the slots tabs pass through (`joints::ribs`; plan.json
    /// leaves the default, off, out).
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub crush_ribs: bool,
    /// Write step timings into report.json. Off by default, because timings differ from run to
    /// run and the ZIP must be byte-identical for the same input and settings.
    pub report_timings: bool,
}

impl Default for CutSettings {
    fn default() -> Self {
        Self {
            material: Material::Wood,
            kerf: None,
            labels: LabelMode::Edges,
            sheet: SheetSize::default(),
            margin: 5.0,
            spacing: 2.0,
            seed: 1,
            nest_tries: 8,
            fine_rotations: true,
            fill_holes: true,
            laser: super::Laser::default(),
            colors: ColorProfile::Classic,
            reference_square: false,
            crush_ribs: false,
            stock: Vec::new(),
            measured: Vec::new(),
            fit: Fit::Snug,
            report_timings: false,
        }
    }
}

/// Kerfs beyond this (mm) are refused: a CO₂ laser's kerf is 0.1–0.5 mm, and the nesting's
/// spacing between parts (2 mm) must exceed the kerf.
pub const MAX_KERF: f64 = 1.0;

/// The widest margin to the sheet's edge accepted, mm.
pub const MAX_MARGIN: f64 = 100.0;
/// The spacing between parts accepted, mm: at least half a millimetre (and more than the
/// kerf), at most 50 mm.
pub const SPACING_RANGE: (f64, f64) = (0.5, 50.0);

impl CutSettings {
    /// The stock listed for sheets `thickness` mm thick (a measured sheet by its nominal
    /// thickness), in the order listed.
    pub fn stock_of(&self, thickness: f64) -> Vec<super::StockSheet> {
        let nominal = self.nominal(thickness);
        self.stock
            .iter()
            .filter(|s| (s.thickness - nominal).abs() < 1e-9)
            .copied()
            .collect()
    }

    /// The nominal thickness of a sheet `thickness` mm thick: what a measured sheet is sold
    /// as, or the thickness itself.
    pub fn nominal(&self, thickness: f64) -> f64 {
        self.measured_as(thickness).map_or(thickness, |m| m.nominal)
    }

    /// The measured sheet `thickness` mm thick is, if it is one.
    pub fn measured_as(&self, thickness: f64) -> Option<&MeasuredThickness> {
        self.measured.iter().find(|m| m.measured.total_cmp(&thickness).is_eq())
    }

    /// Why an outline with the points `outline`, grown by `grow` mm on every side (less when
    /// negative), fits no sheet in any orientation (`what` names it in the message); `None`
    /// when it fits, or when sheets are sized to fit. Methods ask it as soon as they know
    /// their outlines, so a model no sheet holds is refused in a moment instead of after the
    /// joints and the nesting; the nesting refuses whatever this refuses (it tries 4 or 8 of
    /// the orientations this tries every degree of).
    pub fn oversize(&self, what: &str, outline: &[DVec2], grow: f64) -> Option<String> {
        let SheetSize::Fixed { width, height } = self.sheet else {
            return None;
        };
        let room = DVec2::new(width, height) - 2.0 * self.margin;
        let mut smallest: Option<DVec2> = None;
        for degree in 0..90 {
            let turn = DVec2::from_angle(f64::from(degree).to_radians());
            let (lo, hi) = platener_geom::polygon::bounds_of(outline.iter().map(|p| turn.rotate(*p)));
            let size = (hi - lo + DVec2::splat(2.0 * grow)).max(DVec2::ZERO);
            if !size.is_finite() || (size.x <= room.x && size.y <= room.y) || (size.y <= room.x && size.x <= room.y) {
                return None;
            }
            if smallest.is_none_or(|s| size.x * size.y < s.x * s.y) {
                smallest = Some(size);
            }
        }
        let size = smallest?;
        Some(self.oversize_message(what, "its outline", size.max_element(), size.min_element()))
    }

    /// The message for a part of `a × b` mm (measured as `measured` says) that fits no
    /// sheet: the same words from every method and step.
    pub fn oversize_message(&self, what: &str, measured: &str, a: f64, b: f64) -> String {
        let (width, height) = match self.sheet {
            SheetSize::Fixed { width, height } => (width, height),
            SheetSize::Fit => (a, b),
        };
        format!(
            "{what} is {a:.1} × {b:.1} mm ({measured}) and does not fit a {width:.0} × {height:.0} mm sheet \
             within its {} mm margins: set `sheet` to fit or a larger size, or scale the model down (`scale`)",
            self.margin
        )
    }

    /// The kerf in effect, mm.
    pub fn kerf(&self) -> f64 {
        self.kerf.unwrap_or_else(|| self.material.default_kerf())
    }

    /// Checks ranges; the error names the setting and what is allowed.
    pub fn validate(&self) -> Result<(), PlanError> {
        let bad = |name, message: String| Err(PlanError::Setting { name, message });
        let kerf = self.kerf();
        if !(kerf.is_finite() && (0.0..=MAX_KERF).contains(&kerf)) {
            return bad("kerf", format!("{kerf} mm must be from 0 to {MAX_KERF} mm"));
        }
        let (low, high) = SPACING_RANGE;
        if !(self.spacing.is_finite() && (low..=high).contains(&self.spacing)) {
            return bad(
                "spacing",
                format!("{} mm must be from {low} to {high} mm", self.spacing),
            );
        }
        if self.spacing <= kerf {
            return bad(
                "spacing",
                format!(
                    "{} mm must exceed the kerf ({kerf} mm), or cut paths would overlap",
                    self.spacing
                ),
            );
        }
        if !(self.margin.is_finite() && (0.0..=MAX_MARGIN).contains(&self.margin)) {
            return bad(
                "margin",
                format!("{} mm must be from 0 to {MAX_MARGIN} mm", self.margin),
            );
        }
        if let SheetSize::Fixed { width, height } = self.sheet
            && !(width.is_finite() && height.is_finite() && width > 2.0 * self.margin && height > 2.0 * self.margin)
        {
            return bad(
                "sheet",
                format!("{width} × {height} mm must be finite and larger than twice the margin"),
            );
        }
        if let Some(s) = self
            .stock
            .iter()
            .find(|s| !(s.width > 2.0 * self.margin && s.height > 2.0 * self.margin))
        {
            return bad(
                "stock",
                format!("{}: a sheet must be larger than twice the margin", s.text()),
            );
        }
        if self.nest_tries == 0 {
            return bad("nest tries", "must be at least 1".into());
        }
        Ok(())
    }
}

/// A method-specific setting recorded in plan.json's `settings` (joint kind, finger width…).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(untagged)]
pub enum SettingValue {
    /// A yes/no setting.
    Flag(bool),
    /// A number.
    Number(f64),
    /// Several numbers.
    Numbers(Vec<f64>),
    /// A word or phrase.
    Text(String),
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sheet_sizes_parse_like_the_command_line_writes_them() {
        assert_eq!("600x400".parse::<SheetSize>().ok(), Some(SheetSize::default()));
        assert_eq!(
            " 300 × 200 ".parse::<SheetSize>().ok(),
            Some(SheetSize::Fixed {
                width: 300.0,
                height: 200.0
            })
        );
        assert_eq!("FIT".parse::<SheetSize>().ok(), Some(SheetSize::Fit));
        assert!("600".parse::<SheetSize>().is_err());
    }

    #[test]
    fn spacing_must_exceed_the_kerf() {
        let s = CutSettings {
            kerf: Some(0.5),
            spacing: 0.4,
            ..CutSettings::default()
        };
        assert!(matches!(s.validate(), Err(PlanError::Setting { name: "spacing", .. })));
        assert!(CutSettings::default().validate().is_ok());
    }
}
