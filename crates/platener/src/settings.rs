//! Conversion settings: what the user chooses, with documented defaults.
//!
//! The CLI and the web service only fill this struct; every default lives here.

use serde::Serialize;

use crate::error::{Error, Result};

/// The unit a model file's numbers are in. STL has no unit; we take millimetres.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, serde::Deserialize, Default)]
#[serde(rename_all = "lowercase")]
pub enum Units {
    /// Millimetres (the default).
    #[default]
    Mm,
    /// Centimetres.
    Cm,
    /// Inches.
    In,
}

impl Units {
    /// How many millimetres one file unit is.
    pub fn to_mm(self) -> f64 {
        match self {
            Units::Mm => 1.0,
            Units::Cm => 10.0,
            Units::In => 25.4,
        }
    }
}

/// How vertices are welded (the thesis' Simplification step).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Default)]
#[serde(rename_all = "lowercase", tag = "mode", content = "distance")]
pub enum Weld {
    /// Chosen from the model's size and the thinnest sheet (see [`Settings::weld_distance`]).
    #[default]
    Auto,
    /// Merge exact duplicates only (keeps every surface detail; the stacked method uses this).
    Off,
    /// Merge vertices closer than this many mm.
    Distance(f64),
}

/// Which plates the plate method looks for (the thesis' debug view offered both).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Default)]
#[serde(rename_all = "kebab-case")]
pub enum PlateMode {
    /// Only pairs of opposite faces a sheet thickness apart.
    InherentOnly,
    /// Inherent plates, then leftover faces extruded inwards (a solid block becomes a hull).
    #[default]
    InherentAndExtruded,
}

/// Settings of plate finding.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PlateSettings {
    /// Which plates to find.
    pub mode: PlateMode,
    /// Two faces `d` apart make a plate of thickness `t` when `min_factor·t < d`…
    pub min_factor: f64,
    /// …and `d < max_factor·t`. 0.75 and 1.35 accept a 3 mm sheet for walls 2.25–4.05 mm.
    pub max_factor: f64,
    /// Faces whose normals are within this many degrees of opposite are parallel.
    pub parallel_angle_deg: f64,
    /// Thickness of extruded plates; `None` takes the thinnest offered sheet.
    pub extrusion_thickness: Option<f64>,
    /// Plates (and leftover faces) under this area in mm² are too small to cut: the smallest
    /// part's area ([`crate::cuttable::Rule`]), or 2t × 2t when that is more.
    pub min_area: f64,
}

impl Default for PlateSettings {
    fn default() -> Self {
        Self {
            mode: PlateMode::InherentAndExtruded,
            min_factor: 0.75,
            max_factor: 1.35,
            parallel_angle_deg: 2.0,
            extrusion_thickness: None,
            min_area: crate::cuttable::MIN_AREA,
        }
    }
}

/// The direction the stacked method slices along (`--axis`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Default)]
#[serde(rename_all = "lowercase")]
pub enum StackAxis {
    /// The model's largest planar face is laid flat (the seed's rule: fewer, better connected
    /// layers); a model without a planar face of note keeps its own z axis up.
    #[default]
    Auto,
    /// Layers stacked along the model's x axis.
    X,
    /// Layers stacked along the model's y axis.
    Y,
    /// Layers stacked along the model's z axis (as it would be 3D-printed).
    Z,
}

impl std::str::FromStr for StackAxis {
    type Err = Error;

    /// `x`, `y`, `z` or `auto`, as `--axis` takes it.
    fn from_str(s: &str) -> Result<Self> {
        match s.trim().to_ascii_lowercase().as_str() {
            "auto" => Ok(StackAxis::Auto),
            "x" => Ok(StackAxis::X),
            "y" => Ok(StackAxis::Y),
            "z" => Ok(StackAxis::Z),
            _ => Err(Error::Setting {
                name: "axis",
                message: format!("{s:?} is none of x, y, z, auto"),
            }),
        }
    }
}

/// What the plate method makes of features on one face of a plate that do not go through it
/// (engraved or embossed text, pockets, standoff footprints): `--features`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, serde::Deserialize, Default)]
#[serde(rename_all = "lowercase")]
pub enum Features {
    /// The plate is the model's material at its mid-plane; the features are engraved as score
    /// marks on the face where they are (the default).
    #[default]
    Engrave,
    /// Every hole of the plate's faces is cut through (the behaviour before issue 15).
    Cut,
    /// The plate is the model's material at its mid-plane, without marks.
    Ignore,
}

impl std::str::FromStr for Features {
    type Err = Error;

    /// `engrave`, `cut` or `ignore`, as `--features` takes it.
    fn from_str(s: &str) -> Result<Self> {
        match s.trim().to_ascii_lowercase().as_str() {
            "engrave" => Ok(Features::Engrave),
            "cut" => Ok(Features::Cut),
            "ignore" => Ok(Features::Ignore),
            _ => Err(Error::Setting {
                name: "features",
                message: format!("{s:?} is none of engrave, cut, ignore"),
            }),
        }
    }
}

/// Whether and how the plate method merges neighbouring plates into bent parts: `--bend`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Default)]
#[serde(rename_all = "kebab-case")]
pub enum Bending {
    /// The style that suits the material (living hinges in wood, perforations in cardboard,
    /// scores in paper, heat lines in acrylic), at the angles it can bend (the default).
    #[default]
    Auto,
    /// No bent parts: finger joints everywhere.
    None,
    /// This style for every bend the style can make.
    Style(crate::plan::BendStyle),
}

impl Bending {
    /// The style bends are made in for `material`, or `None` when bending is off.
    pub fn style(self, material: crate::plan::Material) -> Option<crate::plan::BendStyle> {
        use crate::plan::{BendStyle, Material};
        match self {
            Bending::None => None,
            Bending::Style(style) => Some(style),
            Bending::Auto => Some(match material {
                Material::Wood => BendStyle::LivingHinge,
                Material::Cardboard => BendStyle::Perforation,
                Material::Paper => BendStyle::Score,
                Material::Acrylic => BendStyle::Heat,
            }),
        }
    }
}

impl std::str::FromStr for Bending {
    type Err = Error;

    /// `auto`, `none`, `living-hinge`, `perforation`, `score` or `heat`, as `--bend` takes it.
    fn from_str(s: &str) -> Result<Self> {
        use crate::plan::BendStyle;
        let styles = [
            BendStyle::LivingHinge,
            BendStyle::Perforation,
            BendStyle::Score,
            BendStyle::Heat,
        ];
        match s.trim().to_ascii_lowercase().as_str() {
            "auto" => Ok(Bending::Auto),
            "none" => Ok(Bending::None),
            other => styles
                .into_iter()
                .find(|st| st.name() == other)
                .map(Bending::Style)
                .ok_or_else(|| Error::Setting {
                    name: "bend",
                    message: format!("{s:?} is none of auto, none, living-hinge, perforation, score, heat"),
                }),
        }
    }
}

/// Settings of the stacked method (layers joined by shafts); docs/stacked.md explains them.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct StackedSettings {
    /// The slicing direction.
    pub axis: StackAxis,
    /// Layer (sheet) thickness in mm; `None` takes the thinnest offered sheet.
    pub layer_thickness: Option<f64>,
    /// Shaft thickness in mm; `None` takes the layer thickness (one kind of sheet).
    pub shaft_thickness: Option<f64>,
    /// Material kept around every slot, mm: between a slot and the layer's outline and between
    /// two slots. 3 mm keeps a plywood or acrylic bridge from snapping.
    pub margin: f64,
    /// A shaft is at least this wide (along its slots), mm.
    pub shaft_min_width: f64,
    /// A shaft is at most this wide, mm: wider slots weaken the layers for no gain in register.
    pub shaft_max_width: f64,
    /// Islands of a layer with less area than this (mm²) are too small to cut; they are dropped
    /// and reported: the smallest part's area ([`crate::cuttable::Rule`]), or 2t × 2t when
    /// that is more.
    pub min_area: f64,
    /// Islands nowhere wider than this (mm) are too thin to cut; they are dropped and reported.
    /// The smallest-part rule (t) applies whatever this says. Also the narrowest band a
    /// shaft extended into a neck may keep.
    pub min_width: f64,
}

impl Default for StackedSettings {
    fn default() -> Self {
        Self {
            axis: StackAxis::Auto,
            layer_thickness: None,
            shaft_thickness: None,
            margin: 3.0,
            shaft_min_width: 10.0,
            shaft_max_width: 60.0,
            min_area: crate::cuttable::MIN_AREA,
            min_width: 1.5,
        }
    }
}

/// The interlocked method (two families of upright slices in halved slots).
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize)]
pub struct InterlockedSettings {
    /// Distance between neighbouring slices of a family, mm; `None` for about ten slices
    /// along the longest horizontal extent, at least three sheet thicknesses apart.
    pub spacing: Option<f64>,
}

/// The range of the slice spacing, mm.
pub const SLICE_SPACING_RANGE: (f64, f64) = (2.0, 1000.0);

/// All settings of a conversion.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Settings {
    /// The unit of the model file's numbers.
    pub units: Units,
    /// Extra scale factor applied after the unit conversion.
    pub scale: f64,
    /// Vertex welding.
    pub weld: Weld,
    /// Sheet thicknesses the user has, in mm (the thinnest bounds the automatic weld distance).
    pub thicknesses: Vec<f64>,
    /// Connected faces whose normals differ by less than this many degrees form one planar
    /// group. 1° keeps a 200-sided cylinder (1.8° per facet) from becoming one "plane".
    pub coplanar_angle_deg: f64,
    /// Vertices closer than this (mm) to the line through their neighbours are removed from
    /// outlines; `None` derives it from the model size (1e-4 of the diagonal, 1 µm–10 µm).
    pub straight_tolerance: Option<f64>,
    /// Plate finding.
    pub plates: PlateSettings,
    /// One-sided features of plates: engraved, cut through or ignored.
    pub features: Features,
    /// The stacked method (layers and shafts).
    pub stacked: StackedSettings,
    /// The interlocked method (slice spacing).
    pub interlocked: InterlockedSettings,
    /// Joints of the plate method (finger width, style; the style defaults by material).
    pub joints: JointSettings,
    /// Bent parts of the plate method (`--bend`).
    pub bending: Bending,
    /// Run the classifier even on a model whose faces are exact, where it skips by default
    /// (its plan is then the plate method's, made more slowly): for comparing and for tests.
    pub classify_exact_faces: bool,
    /// Kerf, labels, sheets and export of the cutting plan.
    pub cut: crate::plan::CutSettings,
}

impl Default for Settings {
    fn default() -> Self {
        Self {
            units: Units::Mm,
            scale: 1.0,
            weld: Weld::Auto,
            thicknesses: vec![3.0],
            coplanar_angle_deg: 1.0,
            straight_tolerance: None,
            plates: PlateSettings::default(),
            features: Features::Engrave,
            stacked: StackedSettings::default(),
            interlocked: InterlockedSettings::default(),
            joints: JointSettings::default(),
            bending: Bending::Auto,
            classify_exact_faces: false,
            cut: crate::plan::CutSettings::default(),
        }
    }
}

impl StackedSettings {
    /// Checks ranges; the error names the setting and what is allowed.
    pub fn validate(&self) -> Result<()> {
        let bad = |name, message: String| Err(Error::Setting { name, message });
        for (name, t) in [
            ("layer thickness", self.layer_thickness),
            ("shaft thickness", self.shaft_thickness),
        ] {
            if let Some(t) = t
                && !(t.is_finite() && t > 0.0)
            {
                return bad(name, format!("{t} is not a positive number of mm"));
            }
        }
        for (name, v) in [
            ("slot margin", self.margin),
            ("minimum island area", self.min_area),
            ("minimum island width", self.min_width),
        ] {
            if !(v.is_finite() && v >= 0.0) {
                return bad(name, format!("{v} must be a finite number ≥ 0"));
            }
        }
        if !(self.shaft_min_width.is_finite()
            && self.shaft_min_width > 0.0
            && self.shaft_max_width.is_finite()
            && self.shaft_max_width >= self.shaft_min_width)
        {
            return bad(
                "shaft width",
                format!(
                    "need 0 < minimum ({}) ≤ maximum ({}) mm",
                    self.shaft_min_width, self.shaft_max_width
                ),
            );
        }
        Ok(())
    }
}

/// Models whose largest extent is below this (mm) are not welded automatically: their
/// details are all smaller than any bevel we would want to remove.
pub const AUTO_WELD_MIN_EXTENT: f64 = 20.0;
/// The automatic weld distance never exceeds this (mm): bevels editors add are ≤ 2 mm.
pub const AUTO_WELD_MAX: f64 = 2.0;
/// The automatic weld distance stays at or below this share of the model's thinnest wall
/// (measured by `weld`): under half, so a wall's two faces are never merged, with 10 % to
/// spare for the averaging that moves welded vertices (see docs/decisions.md).
pub const AUTO_WELD_WALL_SHARE: f64 = 0.45;

/// The thinnest sheet a conversion takes, mm: thinner sheets make every tolerance derived from
/// the thickness (weld distance, plate pairing, finger width) so small that a model's steps
/// multiply without bound (a 0.05 mm sheet hung a conversion, issue 29); 0.1 mm is the page's
/// own minimum and thinner than any paper a laser cuts.
pub const MIN_THICKNESS: f64 = 0.1;
/// The thickest sheet, mm: the page's maximum, beyond any desktop laser's cutting depth.
pub const MAX_THICKNESS: f64 = 50.0;
/// At most this many sheet thicknesses: each is a candidate for every plate (the page offers 8).
pub const MAX_THICKNESSES: usize = 10;
/// The scale factor's range: a model 1000 times smaller or larger than its file says is a
/// mistake, and the geometry kernel's 1 µm grid cannot hold what lies beyond.
pub const SCALE_RANGE: (f64, f64) = (0.001, 1000.0);
/// The longest sheet side, mm (10 m): beyond it nesting searches a bed no laser has.
pub const MAX_SHEET_SIDE: f64 = 10_000.0;
/// The largest weld distance, mm: welding merges vertices this close, and beyond a
/// centimetre it would merge the walls of any model a laser cuts.
pub const MAX_WELD: f64 = 10.0;

impl Settings {
    /// Checks ranges; the error names the setting as the web page and `--help` show it, and
    /// what is allowed. Every caller (CLI, web upload, worker) runs this before converting,
    /// so a value that would make a conversion hang is refused before any work is queued.
    pub fn validate(&self) -> Result<()> {
        let bad = |name, message: String| Err(Error::Setting { name, message });
        let (low, high) = SCALE_RANGE;
        if !(self.scale.is_finite() && (low..=high).contains(&self.scale)) {
            return bad("scale", format!("{} must be a number from {low} to {high}", self.scale));
        }
        if let Weld::Distance(d) = self.weld
            && !(d.is_finite() && (0.0..=MAX_WELD).contains(&d))
        {
            return bad("weld", format!("{d} mm must be from 0 to {MAX_WELD} mm"));
        }
        self.validate_thicknesses()?;
        if !(self.coplanar_angle_deg.is_finite() && (0.0..45.0).contains(&self.coplanar_angle_deg)) {
            return bad(
                "coplanar angle",
                format!("{}° must be in [0, 45)", self.coplanar_angle_deg),
            );
        }
        if let Some(t) = self.straight_tolerance
            && !(t.is_finite() && t >= 0.0)
        {
            return bad("straight tolerance", format!("{t} is not a distance ≥ 0 mm"));
        }
        self.cut.validate()?;
        if let Some(s) = self.interlocked.spacing {
            let (low, high) = SLICE_SPACING_RANGE;
            if !(s.is_finite() && (low..=high).contains(&s)) {
                return bad("slice-spacing", format!("{s} mm must be from {low} to {high} mm"));
            }
        }
        let p = &self.plates;
        if !(p.min_factor.is_finite() && p.min_factor > 0.0 && p.max_factor.is_finite() && p.max_factor > p.min_factor)
        {
            return bad(
                "plate factors",
                format!("need 0 < min ({}) < max ({})", p.min_factor, p.max_factor),
            );
        }
        if !(p.parallel_angle_deg.is_finite() && (0.0..30.0).contains(&p.parallel_angle_deg)) {
            return bad(
                "parallel angle",
                format!("{}° must be in [0, 30)", p.parallel_angle_deg),
            );
        }
        if let Some(t) = p.extrusion_thickness
            && !(t.is_finite() && t > 0.0)
        {
            return bad("extrusion thickness", format!("{t} is not a positive number of mm"));
        }
        if !(p.min_area.is_finite() && p.min_area >= 0.0) {
            return bad("minimum plate area", format!("{} is not an area ≥ 0 mm²", p.min_area));
        }
        self.stacked.validate()?;
        self.joints.validate()?;
        self.validate_sheet()
    }

    /// The sheet thicknesses: one to [`MAX_THICKNESSES`], each from [`MIN_THICKNESS`] to
    /// [`MAX_THICKNESS`] mm.
    fn validate_thicknesses(&self) -> Result<()> {
        let name = "thickness";
        let range = format!("each must be from {MIN_THICKNESS} to {MAX_THICKNESS} mm");
        if self.thicknesses.is_empty() || self.thicknesses.len() > MAX_THICKNESSES {
            return Err(Error::Setting {
                name,
                message: format!("give 1 to {MAX_THICKNESSES} thicknesses; {range}"),
            });
        }
        match self
            .thicknesses
            .iter()
            .find(|t| !(t.is_finite() && (MIN_THICKNESS..=MAX_THICKNESS).contains(*t)))
        {
            Some(t) => Err(Error::Setting {
                name,
                message: format!("{t} mm is out of range; {range}"),
            }),
            None => Ok(()),
        }
    }

    /// A fixed sheet's sides are at most [`MAX_SHEET_SIDE`] (their lower bound, twice the
    /// margin, is the cutting plan's own check).
    fn validate_sheet(&self) -> Result<()> {
        if let crate::plan::SheetSize::Fixed { width, height } = self.cut.sheet
            && !(width <= MAX_SHEET_SIDE && height <= MAX_SHEET_SIDE)
        {
            return Err(Error::Setting {
                name: "sheet",
                message: format!("{width} × {height} mm: each side must be at most {MAX_SHEET_SIDE} mm"),
            });
        }
        Ok(())
    }

    /// The sheet thicknesses offered, thinnest first, each once: the order the user named
    /// them in never changes a result.
    pub fn offered_thicknesses(&self) -> Vec<f64> {
        let mut t = self.thicknesses.clone();
        t.sort_by(f64::total_cmp);
        t.dedup();
        t
    }

    /// The thinnest sheet offered (finer layers, lighter hulls; docs/decisions.md).
    pub fn thinnest(&self) -> f64 {
        self.thicknesses.iter().copied().fold(f64::INFINITY, f64::min)
    }

    /// The thickness of the stacked method's layers: the thinnest sheet unless set.
    pub fn layer_thickness(&self) -> f64 {
        self.stacked.layer_thickness.unwrap_or_else(|| self.thinnest())
    }

    /// The thickness of the stacked method's shafts.
    pub fn shaft_thickness(&self) -> f64 {
        self.stacked.shaft_thickness.unwrap_or_else(|| self.layer_thickness())
    }

    /// The thickness extruded plates get: the thinnest sheet unless set.
    pub fn extrusion_thickness(&self) -> f64 {
        self.plates.extrusion_thickness.unwrap_or_else(|| self.thinnest())
    }

    /// The factor from file units to mm.
    pub fn unit_factor(&self) -> f64 {
        self.units.to_mm() * self.scale
    }

    /// The weld distance for a model whose largest bounding-box extent is `extent` mm.
    ///
    /// Automatic rule: none below [`AUTO_WELD_MIN_EXTENT`]; otherwise `extent / 50`, at most
    /// [`AUTO_WELD_MAX`] and at most 0.6 × the thinnest sheet, so the two faces of a plate we
    /// are looking for are never welded together. A 100 mm model with 3 mm sheets gets 1.8 mm.
    /// Step `weld` halves it further until it is at most [`AUTO_WELD_WALL_SHARE`] × the
    /// model's thinnest wall.
    pub fn weld_distance(&self, extent: f64) -> f64 {
        match self.weld {
            Weld::Off => 0.0,
            Weld::Distance(d) => d,
            Weld::Auto if extent.is_nan() || extent < AUTO_WELD_MIN_EXTENT => 0.0,
            Weld::Auto => {
                let thinnest = self.thicknesses.iter().copied().fold(f64::INFINITY, f64::min);
                (extent / 50.0).min(AUTO_WELD_MAX).min(0.6 * thinnest)
            }
        }
    }
}

/// The shape of fingers and tabs.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum JointStyle {
    /// Straight fingers, exact negatives of each other (wood, acrylic).
    Finger,
    /// The thesis' JimJoint: fingers and tabs widen towards the tip, so they squeeze through
    /// and snap behind the other part (paper, card, foam, which give way).
    Jim,
    /// Laser-cut dovetails: the fingers (or tabs) of one plate widen towards their tip; the
    /// other plate's notches (or slots) are as wide as the tips so they go in, and two keys
    /// per dovetail (small extra parts cut from the dovetailed plate's sheet) fill the rest
    /// of each notch and wedge the dovetail tight (docs/decisions.md).
    Dovetail,
}

impl JointStyle {
    /// The style that holds in `material`: straight fingers for rigid sheets, snapping ones for
    /// materials that give way.
    pub fn for_material(material: crate::plan::Material) -> Self {
        match material {
            crate::plan::Material::Acrylic | crate::plan::Material::Wood => JointStyle::Finger,
            crate::plan::Material::Cardboard | crate::plan::Material::Paper => JointStyle::Jim,
        }
    }
}

/// Settings of the joints.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct JointSettings {
    /// Finger style; `None` chooses by material ([`JointStyle::for_material`]).
    pub style: Option<JointStyle>,
    /// Finger width as a multiple of the thicker plate's thickness.
    pub finger_factor: f64,
    /// Plates closer to parallel than this many degrees are not joined. Fingers are capped
    /// at shallow angles whatever this is (`cap`); below a few degrees two plates are one
    /// bent sheet rather than a corner.
    pub min_angle_deg: f64,
    /// Crush ribs in the slots tabs pass through (the cutting plan's `crush_ribs`, which the
    /// joints step copies here).
    pub crush_ribs: bool,
}

impl Default for JointSettings {
    fn default() -> Self {
        Self {
            style: None,
            finger_factor: 3.0,
            min_angle_deg: 5.0,
            crush_ribs: false,
        }
    }
}

impl JointSettings {
    /// Checks ranges; the error names the setting and what is allowed.
    pub fn validate(&self) -> Result<()> {
        let bad = |name, message: String| Err(Error::Setting { name, message });
        if !(self.finger_factor.is_finite() && (0.5..=20.0).contains(&self.finger_factor)) {
            return bad(
                "finger width",
                format!("{} sheet thicknesses must be from 0.5 to 20", self.finger_factor),
            );
        }
        if !(self.min_angle_deg.is_finite() && (0.0..90.0).contains(&self.min_angle_deg)) {
            return bad(
                "least joint angle",
                format!("{}° must be from 0° to under 90°", self.min_angle_deg),
            );
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The setting's name in the refusal, or `None` when the settings pass.
    fn refused(change: impl FnOnce(&mut Settings)) -> Option<&'static str> {
        let mut s = Settings::default();
        change(&mut s);
        match s.validate() {
            Ok(()) => None,
            Err(Error::Setting { name, .. }) => Some(name),
            Err(e) => panic!("not a setting error: {e}"),
        }
    }

    #[test]
    fn out_of_range_settings_are_refused_by_name() {
        assert_eq!(refused(|_| {}), None);
        assert_eq!(refused(|s| s.thicknesses = vec![0.05]), Some("thickness"));
        assert_eq!(refused(|s| s.thicknesses = vec![3.0, 51.0]), Some("thickness"));
        assert_eq!(refused(|s| s.thicknesses = vec![f64::NAN]), Some("thickness"));
        assert_eq!(refused(|s| s.thicknesses = vec![3.0; 11]), Some("thickness"));
        assert_eq!(refused(|s| s.thicknesses = Vec::new()), Some("thickness"));
        assert_eq!(refused(|s| s.thicknesses = vec![0.1, 50.0]), None);
        assert_eq!(refused(|s| s.scale = 0.0001), Some("scale"));
        assert_eq!(refused(|s| s.scale = 1001.0), Some("scale"));
        assert_eq!(refused(|s| s.scale = 0.001), None);
        assert_eq!(refused(|s| s.cut.kerf = Some(2.5)), Some("kerf"));
        let sheet = |width, height| crate::plan::SheetSize::Fixed { width, height };
        assert_eq!(refused(|s| s.cut.sheet = sheet(20_000.0, 400.0)), Some("sheet"));
        assert_eq!(refused(|s| s.cut.sheet = sheet(600.0, f64::INFINITY)), Some("sheet"));
        assert_eq!(refused(|s| s.cut.sheet = sheet(10_000.0, 10_000.0)), None);
    }

    #[test]
    fn the_refusal_names_the_setting_and_the_range() {
        let s = Settings {
            thicknesses: vec![0.05],
            ..Settings::default()
        };
        let message = s.validate().expect_err("refused").to_string();
        assert!(
            message.contains("`thickness`") && message.contains("0.1 to 50 mm"),
            "{message}"
        );
    }
}
