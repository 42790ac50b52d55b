//! The settings of a conversion as the API takes them (form fields, recut JSON), stored with
//! the job as JSON and turned into the library's [`Settings`] by the worker.
//!
//! Every setting is the library's ([`platener::options`]): its parsing, its range check and
//! its message are the library's, and messages name settings by the page's labels. The only
//! field of the web's own is `debug` (store every step's snapshot for the debug view).
//!
//! The server checks settings with [`JobSettings::to_library`] before accepting an upload
//! (cheap: no model is read), so a bad value is refused rather than a failed job: a `400` for
//! a value the API does not understand, a `422` for one out of range.

use platener::method::MethodKind;
use platener::options::{self, Chosen};
use platener::{Error, Settings};
use serde_json::{Map, Value};

/// The settings of one conversion, as in the conversion's `settings` field: every setting
/// of [`options::DEFS`] by its API key, and `debug`.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct JobSettings {
    /// What the maker chose.
    pub chosen: Chosen,
    /// Store every step's snapshot for the debug view (`/#/debug`).
    pub debug: bool,
    /// The values of the repeatable form fields seen so far (a form sends `thickness` once
    /// per ticked box).
    repeated: Vec<(&'static str, Vec<String>)>,
}

/// Why a conversion's settings are refused; each is a sentence that names the setting by the
/// page's label and never echoes the value sent.
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

/// A library message with every setting named by its label on the page ("Sheet thickness").
pub fn labelled(message: &str) -> String {
    options::render(message, |d| d.label.to_string())
}

fn unknown(e: &Error) -> String {
    labelled(&e.to_string())
}

/// `true`, `1` or `on` (a checkbox sends `on`).
fn truthy(value: &str) -> bool {
    matches!(value.trim(), "true" | "1" | "on")
}

impl JobSettings {
    /// Sets one form field; the error is a sentence for a `400`.
    pub fn set_field(&mut self, field: &str, value: &str) -> Result<(), String> {
        if field == "debug" {
            self.debug = truthy(value);
            return Ok(());
        }
        let def = options::find(field).ok_or_else(|| {
            let names: Vec<&str> = options::DEFS.iter().map(|d| d.name).collect();
            format!(
                "unknown form field (expected model, name, debug or a setting: {})",
                names.join(", ")
            )
        })?;
        let values: Vec<String> = if def.repeatable() {
            let slot = match self.repeated.iter().position(|(n, _)| *n == def.name) {
                Some(i) => i,
                None => {
                    self.repeated.push((def.name, Vec::new()));
                    self.repeated.len() - 1
                }
            };
            self.repeated[slot].1.push(value.to_string());
            self.repeated[slot].1.clone()
        } else {
            vec![value.to_string()]
        };
        let refs: Vec<&str> = values.iter().map(String::as_str).collect();
        self.chosen.set(def.name, &refs).map_err(|e| unknown(&e))
    }

    /// The library's settings and the methods to run, checked by the library's own
    /// [`Chosen::validate`] (the same check the CLI and the worker make).
    pub fn to_library(&self) -> Result<(Settings, Vec<MethodKind>), SettingsError> {
        self.chosen
            .validate()
            .map_err(|e| SettingsError::OutOfRange(labelled(&e.to_string())))?;
        Ok((self.chosen.settings.clone(), self.chosen.methods.clone()))
    }

    /// These settings with the fields of a recut's JSON body applied over them.
    pub fn with_changes(&self, changes: &Value) -> Result<Self, String> {
        let Value::Object(changes) = changes else {
            return Err("the body must be a JSON object of settings, e.g. {\"kerf\": 0.15}".into());
        };
        let mut next = Self {
            repeated: Vec::new(),
            ..self.clone()
        };
        next.apply(changes)?;
        Ok(next)
    }

    /// Applies `key: value` pairs of the API's JSON.
    fn apply(&mut self, values: &Map<String, Value>) -> Result<(), String> {
        for (key, value) in values {
            if key == "debug" {
                self.debug = value.as_bool().ok_or("debug takes true or false")?;
            } else {
                self.chosen.set_json(key, value).map_err(|e| unknown(&e))?;
            }
        }
        Ok(())
    }
}

impl serde::Serialize for JobSettings {
    fn serialize<S: serde::Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        let mut map = self.chosen.to_json();
        map.insert("debug".into(), Value::Bool(self.debug));
        map.serialize(serializer)
    }
}

impl<'de> serde::Deserialize<'de> for JobSettings {
    fn deserialize<D: serde::Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        let map = Map::<String, Value>::deserialize(deserializer)?;
        let mut settings = JobSettings::default();
        settings.apply(&map).map_err(serde::de::Error::custom)?;
        Ok(settings)
    }
}

#[cfg(test)]
mod tests {
    use platener::plan::{BendStyle, Material};
    use platener::{Bending, Features, PlateMode, Weld};

    use super::*;

    #[test]
    fn defaults_are_the_libraries() {
        let (settings, methods) = JobSettings::default().to_library().expect("valid");
        assert_eq!(settings, Settings::default());
        assert_eq!(methods, MethodKind::ALL.to_vec());
    }

    /// Jobs stored before the settings vocabulary keep their meaning.
    #[test]
    fn stored_settings_read_back() {
        let old = r#"{"thicknesses":[4.0,6.0],"material":"acrylic","kerf":null,"method":"all","sheet":"600x400",
            "joint":"auto","units":"mm","scale":1.0,"weld":null,"plates":"all","features":"engrave","debug":false,"bend":"auto"}"#;
        let s: JobSettings = serde_json::from_str(old).expect("old settings");
        assert_eq!(s.chosen.settings.thicknesses, vec![4.0, 6.0]);
        assert_eq!(s.chosen.settings.cut.material, Material::Acrylic);
        let again: JobSettings = serde_json::from_str(&serde_json::to_string(&s).expect("json")).expect("new");
        assert_eq!(again, s);
    }

    #[test]
    fn form_fields_and_recut_changes_apply() {
        let mut s = JobSettings::default();
        s.set_field("thickness", "4").expect("number");
        s.set_field("thickness", "6").expect("number");
        s.set_field("material", "acrylic").expect("text");
        assert_eq!(s.chosen.settings.thicknesses, vec![4.0, 6.0]);
        let (lib, _) = s.to_library().expect("valid");
        assert_eq!(lib.cut.material, Material::Acrylic);
        let r = s
            .with_changes(&serde_json::json!({"kerf": 0.15, "thickness": 5}))
            .expect("valid");
        assert_eq!(r.chosen.settings.cut.kerf, Some(0.15));
        assert_eq!(r.chosen.settings.thicknesses, vec![5.0]);
        assert!(s.with_changes(&serde_json::json!({"colour": "red"})).is_err());
        assert!(s.set_field("kerf", "<script>").is_err());
    }

    #[test]
    fn every_setting_reaches_the_library() {
        let mut s = JobSettings::default();
        for (field, value) in [
            ("weld", "0.05"),
            ("plates", "inherent"),
            ("features", "cut"),
            ("debug", "true"),
            ("bend", "living-hinge"),
            ("labels", "parts"),
            ("axis", "z"),
        ] {
            s.set_field(field, value).expect("a setting");
        }
        assert!(s.debug);
        let (lib, _) = s.to_library().expect("valid");
        assert_eq!(lib.weld, Weld::Distance(0.05));
        assert_eq!(lib.plates.mode, PlateMode::InherentOnly);
        assert_eq!(lib.features, Features::Cut);
        assert_eq!(lib.bending, Bending::Style(BendStyle::LivingHinge));
        let off = s.with_changes(&serde_json::json!({"weld": 0.0})).expect("valid");
        assert_eq!(off.to_library().expect("valid").0.weld, Weld::Off);
    }

    #[test]
    fn bad_values_are_refused_without_echo() {
        for (field, value) in [
            ("material", "<b>gold</b>"),
            ("sheet", "<b>"),
            ("method", "<x>"),
            ("joint", "<y>"),
            ("bend", "<fold>"),
            ("features", "etch"),
        ] {
            let mut s = JobSettings::default();
            let e = s.set_field(field, value).expect_err("refused");
            assert!(!e.contains('<'), "{e}");
        }
        let e = JobSettings::default()
            .with_changes(&serde_json::json!({"<i>": 1}))
            .expect_err("no such setting");
        assert!(!e.contains('<'), "{e}");
    }

    /// The page's custom thickness field says min="0.1", but a form may send anything: 0.05 mm
    /// hung a conversion (issue 29). The library's range check refuses it, by the page's label.
    #[test]
    fn out_of_range_values_are_the_librarys_refusals() {
        for (field, value, named) in [
            ("thickness", "0.05", "Sheet thickness"),
            ("thickness", "60", "Sheet thickness"),
            ("scale", "0", "Scale"),
            ("kerf", "7", "Kerf"),
            ("weld", "11", "Weld distance"),
            ("sheet", "20000x400", "Sheet size"),
        ] {
            let mut s = JobSettings::default();
            s.set_field(field, value).expect("a number or text");
            match s.to_library() {
                Err(SettingsError::OutOfRange(m)) => assert!(m.starts_with(named), "{field}={value}: {m}"),
                other => panic!("{field}={value}: {other:?}"),
            }
        }
    }
}
