//! The one definition of every setting a maker chooses (the way ripgrep's `flags/defs.rs`
//! defines each flag once): its name, label, group, kind with allowed values or range and
//! unit, a one-line help and a longer doc, and how it reads and writes [`Chosen`].
//!
//! Everything a front end shows of a setting comes from here: the CLI's arguments and
//! `--help`, the web API's parsing and error messages, `GET /api/settings` (the page builds
//! its form from it) and the table in docs/settings.md. The defaults are not written here: a
//! setting's default is what it reads from [`Chosen::default`], i.e. [`Settings::default`],
//! so a default cannot differ between the library and a front end.
//!
//! Library messages refer to a setting by its name in backticks (`` `scale` ``);
//! [`render`] lets each front end name it its own way (`--scale` in the CLI, "Scale" on the
//! page).

mod defs;
mod schema;
#[cfg(test)]
mod tests;

use serde_json::Value;

use crate::error::{Error, Result};
use crate::method::MethodKind;
use crate::settings::Settings;

pub use defs::DEFS;
pub use schema::{markdown, schema};

/// What a maker chose: the settings of a conversion and the methods to run.
#[derive(Debug, Clone, PartialEq)]
pub struct Chosen {
    /// The library's settings.
    pub settings: Settings,
    /// The methods to run (the `method` setting: one, or every method for `all`).
    pub methods: Vec<MethodKind>,
}

impl Default for Chosen {
    fn default() -> Self {
        Self {
            settings: Settings::default(),
            methods: MethodKind::ALL.to_vec(),
        }
    }
}

/// The groups a form shows the settings in, in this order.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Group {
    /// What the sheets are: material, thicknesses, kerf.
    Material,
    /// How the file's numbers become millimetres.
    Model,
    /// The sheets parts are nested on.
    Sheets,
    /// Joints, labels, bends and features.
    Joints,
    /// Which methods run and their own settings.
    Method,
    /// Settings most makers never change.
    Advanced,
}

impl Group {
    /// Every group, in the order a form shows them.
    pub const ALL: [Group; 6] = [
        Group::Material,
        Group::Model,
        Group::Sheets,
        Group::Joints,
        Group::Method,
        Group::Advanced,
    ];

    /// The group's heading.
    pub fn label(self) -> &'static str {
        match self {
            Group::Material => "Material",
            Group::Model => "Model",
            Group::Sheets => "Sheets",
            Group::Joints => "Joints and labels",
            Group::Method => "Method",
            Group::Advanced => "Advanced",
        }
    }

    /// Folded away until opened: the settings a maker rarely needs. The method stays open:
    /// its select also switches the page between the methods' plans.
    pub fn folded(self) -> bool {
        matches!(self, Group::Joints | Group::Advanced)
    }
}

/// One allowed value of a choice (or a preset of a free value).
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct Choice {
    /// The value as written (`living-hinge`, `600x400`).
    pub value: &'static str,
    /// How a form names it.
    pub label: &'static str,
    /// One line on what it does.
    pub help: &'static str,
}

/// What kind of value a setting takes.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
#[serde(tag = "type", rename_all = "lowercase")]
pub enum Kind {
    /// One of a list of words.
    Choice {
        /// The allowed values, the default among them.
        choices: &'static [Choice],
    },
    /// A number from `min` to `max` (both allowed).
    Number {
        /// The unit (`mm`, `×`).
        unit: &'static str,
        /// The least value allowed.
        min: f64,
        /// The greatest value allowed.
        max: f64,
        /// The word for "chosen by platener" (`auto`) and what it means, when the setting may
        /// be left to platener; `None` when a number is always needed.
        auto: Option<&'static str>,
    },
    /// One or more numbers, each from `min` to `max`.
    Numbers {
        /// The unit.
        unit: &'static str,
        /// The least value allowed.
        min: f64,
        /// The greatest value allowed.
        max: f64,
        /// At most this many.
        max_count: usize,
        /// Common values a form offers as boxes to tick.
        common: &'static [f64],
    },
    /// Free text in a format of its own (the stock list), empty for none.
    Text {
        /// What it looks like, for a form's placeholder.
        example: &'static str,
        /// Its shape, for the CLI's value name (`T:WxH[xN],...`).
        shape: &'static str,
        /// The format in words.
        format: &'static str,
    },
    /// A sheet size, `WxH` in mm or `fit`, with presets for common beds.
    Sheet {
        /// Common sizes.
        presets: &'static [Choice],
        /// The longest side allowed, mm.
        max: f64,
    },
}

/// One setting.
#[derive(Debug, Clone, Copy)]
pub struct Def {
    /// The name: the CLI's long flag, the form field and how messages name it.
    pub name: &'static str,
    /// The key in the web API's `settings` object (the name, but `thicknesses` for the
    /// repeatable `thickness`, as the API has always called it).
    pub key: &'static str,
    /// The CLI's short flag, if any.
    pub short: Option<char>,
    /// How a form labels it.
    pub label: &'static str,
    /// The form group it is shown in.
    pub group: Group,
    /// The values it takes.
    pub kind: Kind,
    /// One line: what it does.
    pub help: &'static str,
    /// More: when to change it and what the values mean.
    pub doc: &'static str,
    /// Sets it from its values as text (one, or several for [`Kind::Numbers`]); the error is
    /// a phrase that never repeats the value (the page shows it).
    set: fn(&mut Chosen, &[&str]) -> std::result::Result<(), String>,
    /// Its current value, as the web API writes it (`null` for "auto").
    get: fn(&Chosen) -> Value,
}

impl Def {
    /// This setting's value in `chosen`, as JSON.
    pub fn value(&self, chosen: &Chosen) -> Value {
        (self.get)(chosen)
    }

    /// Its default, as JSON.
    pub fn default_value(&self) -> Value {
        self.value(&Chosen::default())
    }

    /// A value as the text a command line or a form field gives (`auto` for null).
    pub fn texts(value: &Value) -> Vec<String> {
        match value {
            Value::Null => vec!["auto".into()],
            Value::Array(items) => items.iter().flat_map(Def::texts).collect(),
            Value::String(s) => vec![s.clone()],
            // `3`, not serde_json's `3.0`: as a person writes it on a command line.
            Value::Number(n) => vec![n.as_f64().map_or_else(|| n.to_string(), |f| f.to_string())],
            other => vec![other.to_string()],
        }
    }

    /// Its default as text, once per value.
    pub fn default_texts(&self) -> Vec<String> {
        Def::texts(&self.default_value())
    }

    /// Whether it takes several values (a repeatable flag, a repeatable form field).
    pub fn repeatable(&self) -> bool {
        matches!(self.kind, Kind::Numbers { .. })
    }

    /// The allowed values of a choice, in order.
    pub fn choices(&self) -> &'static [Choice] {
        match self.kind {
            Kind::Choice { choices } => choices,
            _ => &[],
        }
    }
}

/// The setting named `name` (or with that API key).
pub fn find(name: &str) -> Option<&'static Def> {
    DEFS.iter().find(|d| d.name == name || d.key == name)
}

impl Chosen {
    /// Sets the setting `name` from text values; the error names the setting.
    pub fn set(&mut self, name: &str, values: &[&str]) -> Result<()> {
        let def = find(name).ok_or_else(|| unknown(name))?;
        (def.set)(self, values).map_err(|message| Error::Setting {
            name: def.name,
            message,
        })
    }

    /// Sets the setting `key` from a JSON value (`null` is `auto`, an array several values).
    pub fn set_json(&mut self, key: &str, value: &Value) -> Result<()> {
        let def = find(key).ok_or_else(|| unknown(key))?;
        if matches!(value, Value::Object(_)) || matches!(value, Value::Array(_)) && !def.repeatable() {
            return Err(Error::Setting {
                name: def.name,
                message: "takes one value, not a list or an object".into(),
            });
        }
        let texts = Def::texts(value);
        let refs: Vec<&str> = texts.iter().map(String::as_str).collect();
        self.set(def.name, &refs)
    }

    /// Every setting's value, by API key, in [`DEFS`]' order.
    pub fn to_json(&self) -> serde_json::Map<String, Value> {
        DEFS.iter().map(|d| (d.key.to_string(), d.value(self))).collect()
    }

    /// Checks every range ([`Settings::validate`]) and that a method is chosen.
    pub fn validate(&self) -> Result<()> {
        if self.methods.is_empty() {
            return Err(Error::Setting {
                name: "method",
                message: "choose at least one method".into(),
            });
        }
        self.settings.validate()
    }
}

/// The refusal of a name that is no setting; the list is the names a caller may send.
fn unknown(name: &str) -> Error {
    let names: Vec<&str> = DEFS.iter().map(|d| d.name).collect();
    let shown = if name.chars().all(|c| c.is_ascii_alphanumeric() || c == '-' || c == '_') && name.len() <= 32 {
        name
    } else {
        "that"
    };
    Error::Setting {
        name: "settings",
        message: format!("{shown} is no setting; the settings are {}", names.join(", ")),
    }
}

/// `message` with every setting named in backticks (`` `scale` ``) written as `name` says:
/// `--scale` for the CLI, the form's label for the page. Backticked words that are no
/// setting stay as they are.
pub fn render(message: &str, name: impl Fn(&Def) -> String) -> String {
    let mut out = String::with_capacity(message.len());
    let mut rest = message;
    while let Some(open) = rest.find('`') {
        let Some(close) = rest[open + 1..].find('`') else {
            break;
        };
        let word = &rest[open + 1..open + 1 + close];
        out.push_str(&rest[..open]);
        match find(word) {
            Some(def) => out.push_str(&name(def)),
            None => out.push_str(&rest[open..=open + 1 + close]),
        }
        rest = &rest[open + close + 2..];
    }
    out.push_str(rest);
    out
}
