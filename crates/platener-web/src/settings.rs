//! The settings of a conversion as the API takes them (form fields, recut JSON), stored with
//! the job as JSON and turned into the library's [`Settings`] by the worker.
//!
//! The server checks them with [`JobSettings::to_library`] before accepting an upload (cheap:
//! no model is read), so a bad value is refused rather than a failed job: a `400` for a value
//! the API does not understand, a `422` with the library's own message
//! ([`Settings::validate`]) for one out of range.

use platener::joints::JointStyle;
use platener::method::MethodKind;
use platener::plan::{Material, SheetSize};
use platener::{Bending, Features, PlateMode, Settings, Units, Weld};
use serde::{Deserialize, Serialize};

/// The settings of one conversion, as in the conversion's `settings` field.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct JobSettings {
    /// Sheet thicknesses, mm (the form field `thickness`, repeatable).
    #[serde(alias = "thickness")]
    pub thicknesses: Vec<f64>,
    /// wood, acrylic, cardboard, paper.
    pub material: String,
    /// Kerf in mm; `None`: the material's.
    pub kerf: Option<f64>,
    /// plate, stacked, classifier or all.
    pub method: String,
    /// `WxH` in mm or `fit`.
    pub sheet: String,
    /// auto, finger, jim, dovetail.
    pub joint: String,
    /// mm, cm, in.
    pub units: String,
    /// Scale factor after the unit.
    pub scale: f64,
    /// Weld distance in mm; `None`: automatic, 0: exact duplicates only (the debug view's
    /// slider).
    pub weld: Option<f64>,
    /// `all` (inherent and extruded plates) or `inherent` (inherent plates only).
    pub plates: String,
    /// One-sided features of plates: engrave, cut or ignore.
    pub features: String,
    /// Store every step's snapshot for the debug view (`/#/debug`).
    pub debug: bool,
    /// Bent parts: auto, none, living-hinge, perforation, score, heat (`--bend`).
    pub bend: String,
}

impl Default for JobSettings {
    fn default() -> Self {
        Self {
            thicknesses: vec![3.0],
            material: "wood".into(),
            kerf: None,
            method: "all".into(),
            sheet: "600x400".into(),
            joint: "auto".into(),
            units: "mm".into(),
            scale: 1.0,
            weld: None,
            plates: "all".into(),
            features: "engrave".into(),
            debug: false,
            bend: "auto".into(),
        }
    }
}

/// Why a conversion's settings are refused; each is a sentence that names the setting and
/// never echoes the value sent.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum SettingsError {
    /// A value the API does not understand (an unknown material, a sheet that is not `WxH`):
    /// the request is malformed, `400`.
    #[error("{0}")]
    Unknown(String),
    /// A value of the right kind out of the library's range ([`Settings::validate`]): the
    /// request is understood but cannot be converted, `422`.
    #[error("{0}")]
    OutOfRange(String),
}

impl From<&str> for SettingsError {
    fn from(message: &str) -> Self {
        SettingsError::Unknown(message.to_string())
    }
}

impl From<String> for SettingsError {
    fn from(message: String) -> Self {
        SettingsError::Unknown(message)
    }
}

impl JobSettings {
    /// Sets one form field; the error is a sentence for a `400`.
    pub fn set_field(&mut self, field: &str, value: &str, thicknesses_seen: &mut bool) -> Result<(), String> {
        let number = |v: &str| {
            v.trim()
                .parse::<f64>()
                .map_err(|_| format!("the field {field} takes a number"))
        };
        match field {
            "thickness" | "thicknesses" => {
                if !*thicknesses_seen {
                    self.thicknesses.clear();
                    *thicknesses_seen = true;
                }
                self.thicknesses.push(number(value)?);
            }
            "material" => self.material = value.trim().to_string(),
            "kerf" => self.kerf = Some(number(value)?),
            "method" => self.method = value.trim().to_string(),
            "sheet" => self.sheet = value.trim().to_string(),
            "joint" => self.joint = value.trim().to_string(),
            "units" => self.units = value.trim().to_string(),
            "scale" => self.scale = number(value)?,
            "weld" => self.weld = Some(number(value)?),
            "plates" => self.plates = value.trim().to_string(),
            "features" => self.features = value.trim().to_string(),
            "debug" => self.debug = matches!(value.trim(), "true" | "1" | "on"),
            "bend" => self.bend = value.trim().to_string(),
            _ => return Err("unknown form field (expected model, thickness, material, method, kerf, sheet, joint, units, scale, weld, plates, features, bend, debug or name)".into()),
        }
        Ok(())
    }

    /// The library's settings and the methods to run, checked by the library's own
    /// [`Settings::validate`] (the same check the CLI and the worker make).
    pub fn to_library(&self) -> Result<(Settings, Vec<MethodKind>), SettingsError> {
        let mut settings = Settings::default();
        settings.thicknesses.clone_from(&self.thicknesses);
        settings.cut.material = match self.material.as_str() {
            "wood" => Material::Wood,
            "acrylic" => Material::Acrylic,
            "cardboard" => Material::Cardboard,
            "paper" => Material::Paper,
            _ => return Err("material must be wood, acrylic, cardboard or paper".into()),
        };
        settings.cut.kerf = self.kerf;
        settings.cut.sheet = self
            .sheet
            .parse::<SheetSize>()
            .map_err(|_| "sheet must be WxH in mm (e.g. 600x400) or fit".to_string())?;
        settings.joints.style = match self.joint.as_str() {
            "auto" => None,
            "finger" => Some(JointStyle::Finger),
            "jim" => Some(JointStyle::Jim),
            "dovetail" => Some(JointStyle::Dovetail),
            _ => return Err("joint must be auto, finger, jim or dovetail".into()),
        };
        settings.units = match self.units.as_str() {
            "mm" => Units::Mm,
            "cm" => Units::Cm,
            "in" => Units::In,
            _ => return Err("units must be mm, cm or in".into()),
        };
        settings.scale = self.scale;
        settings.bending = self
            .bend
            .parse::<Bending>()
            .map_err(|_| "bend must be auto, none, living-hinge, perforation, score or heat".to_string())?;
        self.debug_options(&mut settings)?;
        let methods = match self.method.as_str() {
            "all" => MethodKind::ALL.to_vec(),
            name => vec![
                name.parse::<MethodKind>()
                    .map_err(|_| "method must be plate, stacked, classifier or all".to_string())?,
            ],
        };
        settings
            .validate()
            .map_err(|e| SettingsError::OutOfRange(e.to_string()))?;
        Ok((settings, methods))
    }

    /// The options the debug view re-runs with: weld distance, plate mode, features.
    fn debug_options(&self, settings: &mut Settings) -> Result<(), SettingsError> {
        settings.weld = match self.weld {
            None => Weld::Auto,
            Some(0.0) => Weld::Off,
            Some(d) if d.is_finite() && (0.0..=10.0).contains(&d) => Weld::Distance(d),
            Some(_) => {
                return Err(SettingsError::OutOfRange(
                    "weld must be a number of mm from 0 to 10".into(),
                ));
            }
        };
        settings.plates.mode = match self.plates.as_str() {
            "all" => PlateMode::InherentAndExtruded,
            "inherent" => PlateMode::InherentOnly,
            _ => return Err(SettingsError::Unknown("plates must be all or inherent".into())),
        };
        settings.features = self
            .features
            .parse::<Features>()
            .map_err(|_| "features must be engrave, cut or ignore".to_string())?;
        Ok(())
    }

    /// These settings with the fields of a recut's JSON body applied over them.
    pub fn with_changes(&self, changes: &serde_json::Value) -> Result<Self, String> {
        let serde_json::Value::Object(changes) = changes else {
            return Err("the body must be a JSON object of settings, e.g. {\"kerf\": 0.15}".into());
        };
        let mut merged = serde_json::to_value(self).map_err(|e| e.to_string())?;
        for (k, v) in changes {
            let key = if k == "thickness" { "thicknesses" } else { k.as_str() };
            let v = match (key, v) {
                ("thicknesses", serde_json::Value::Number(_)) => serde_json::Value::Array(vec![v.clone()]),
                _ => v.clone(),
            };
            merged[key] = v;
        }
        serde_json::from_value(merged).map_err(|_| {
            "unknown setting or wrong type (settings: thicknesses, material, kerf, method, sheet, joint, units, scale, weld, plates, features, bend, debug)"
                .to_string()
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn defaults_are_the_libraries() {
        let (settings, methods) = JobSettings::default().to_library().expect("valid");
        assert_eq!(settings, Settings::default());
        assert_eq!(methods, MethodKind::ALL.to_vec());
    }

    #[test]
    fn form_fields_and_recut_changes_apply() {
        let mut s = JobSettings::default();
        let mut seen = false;
        s.set_field("thickness", "4", &mut seen).expect("number");
        s.set_field("thickness", "6", &mut seen).expect("number");
        s.set_field("material", "acrylic", &mut seen).expect("text");
        assert_eq!(s.thicknesses, vec![4.0, 6.0]);
        let (lib, _) = s.to_library().expect("valid");
        assert_eq!(lib.cut.material, Material::Acrylic);
        let r = s
            .with_changes(&serde_json::json!({"kerf": 0.15, "thickness": 5}))
            .expect("valid");
        assert_eq!(r.kerf, Some(0.15));
        assert_eq!(r.thicknesses, vec![5.0]);
        assert!(s.with_changes(&serde_json::json!({"colour": "red"})).is_err());
        assert!(s.set_field("kerf", "<script>", &mut seen).is_err());
    }

    #[test]
    fn debug_options_reach_the_library() {
        let mut s = JobSettings::default();
        for (field, value) in [
            ("weld", "0.05"),
            ("plates", "inherent"),
            ("features", "cut"),
            ("debug", "true"),
        ] {
            s.set_field(field, value, &mut false).expect("a debug option");
        }
        assert!(s.debug);
        let (lib, _) = s.to_library().expect("valid");
        assert_eq!(lib.weld, Weld::Distance(0.05));
        assert_eq!(lib.plates.mode, PlateMode::InherentOnly);
        assert_eq!(lib.features, Features::Cut);
        let off = s.with_changes(&serde_json::json!({"weld": 0.0})).expect("valid");
        assert_eq!(off.to_library().expect("valid").0.weld, Weld::Off);
        for bad in [
            json_of("weld", "11"),
            json_of("plates", "\"<i>\""),
            json_of("features", "\"etch\""),
        ] {
            let e = s
                .with_changes(&bad)
                .expect("well typed")
                .to_library()
                .expect_err("refused")
                .to_string();
            assert!(!e.contains('<'), "{e}");
        }
    }

    #[test]
    fn bend_reaches_the_library_and_bad_styles_are_refused() {
        use platener::plan::BendStyle;
        let mut s = JobSettings::default();
        s.set_field("bend", "living-hinge", &mut false).expect("a form field");
        assert_eq!(
            s.to_library().expect("valid").0.bending,
            Bending::Style(BendStyle::LivingHinge)
        );
        let r = s.with_changes(&serde_json::json!({"bend": "none"})).expect("valid");
        assert_eq!(r.to_library().expect("valid").0.bending, Bending::None);
        let heat = s.with_changes(&serde_json::json!({"bend": "heat"})).expect("valid");
        assert_eq!(
            heat.to_library().expect("valid").0.bending,
            Bending::Style(BendStyle::Heat)
        );
        for bad in [json_of("bend", "\"<fold>\""), json_of("bend", "\"\"")] {
            let e = s
                .with_changes(&bad)
                .expect("well typed")
                .to_library()
                .expect_err("refused")
                .to_string();
            assert!(e.starts_with("bend must be") && !e.contains('<'), "{e}");
        }
        assert!(s.with_changes(&json_of("bend", "3")).is_err(), "bend is text");
        let mut form = JobSettings::default();
        form.set_field("bend", "<b>crease</b>", &mut false).expect("text");
        assert!(
            form.to_library()
                .expect_err("refused")
                .to_string()
                .starts_with("bend must be")
        );
    }

    fn json_of(key: &str, value: &str) -> serde_json::Value {
        serde_json::from_str(&format!("{{\"{key}\": {value}}}")).expect("json")
    }

    #[test]
    fn bad_values_are_refused_without_echo() {
        for (field, value) in [
            ("material", "<b>gold</b>"),
            ("sheet", "<b>"),
            ("method", "<x>"),
            ("joint", "<y>"),
        ] {
            let mut s = JobSettings::default();
            s.set_field(field, value, &mut false)
                .expect("text fields take any text");
            let e = s.to_library().expect_err("refused");
            assert!(matches!(e, SettingsError::Unknown(_)), "{e}");
            assert!(!e.to_string().contains('<'), "{e}");
        }
        let s = JobSettings {
            thicknesses: vec![-1.0],
            ..JobSettings::default()
        };
        assert!(s.to_library().is_err());
    }

    /// The page's custom thickness field says min="0.1", but a form may send anything: 0.05 mm
    /// hung a conversion (issue 29). The library's range check refuses it, by the page's name.
    #[test]
    fn out_of_range_values_are_the_librarys_refusals() {
        for (field, value, named) in [
            ("thickness", "0.05", "sheet thickness"),
            ("thickness", "60", "sheet thickness"),
            ("scale", "0", "scale"),
            ("kerf", "7", "kerf"),
            ("sheet", "20000x400", "sheet size"),
        ] {
            let mut s = JobSettings::default();
            s.set_field(field, value, &mut false).expect("a number or text");
            match s.to_library() {
                Err(SettingsError::OutOfRange(m)) => assert!(m.contains(named), "{field}={value}: {m}"),
                other => panic!("{field}={value}: {other:?}"),
            }
        }
    }
}
