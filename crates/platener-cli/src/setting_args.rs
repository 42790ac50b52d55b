//! The library's settings as clap arguments: one flag per [`platener::options::Def`], with its
//! help, its values and its default taken from the definition, so the CLI never mirrors a
//! setting by hand. Each command takes the subset it uses ([`Subset`]).

use std::marker::PhantomData;

use clap::builder::{PossibleValue, PossibleValuesParser};
use clap::{Arg, ArgAction, ArgMatches, Command, FromArgMatches};
use platener::options::{self, Chosen, Def, Kind};

/// The settings a command takes.
pub trait Subset {
    /// Whether the command takes `def`.
    fn includes(def: &Def) -> bool;
}

/// `convert`: every setting.
#[derive(Debug, Clone, Copy)]
pub struct Every;
impl Subset for Every {
    fn includes(_: &Def) -> bool {
        true
    }
}

/// `scene`: every setting but those of the cutting plan alone (kerf, sheet, margin, spacing,
/// line colours, reference square, fit, labels, stock, nesting, laser).
#[derive(Debug, Clone, Copy)]
pub struct ForScene;
impl Subset for ForScene {
    fn includes(def: &Def) -> bool {
        !matches!(
            def.name,
            "kerf"
                | "laser"
                | "sheet"
                | "stock"
                | "nesting"
                | "margin"
                | "spacing"
                | "colors"
                | "reference-square"
                | "fit"
                | "labels"
        )
    }
}

/// `inspect`: how the model is read and welded, and the sheets its plates are measured against.
#[derive(Debug, Clone, Copy)]
pub struct ForModel;
impl Subset for ForModel {
    fn includes(def: &Def) -> bool {
        matches!(def.name, "thickness" | "units" | "scale" | "weld" | "features")
    }
}

/// `verify`: how the model is read (its unit and scale). The weld is the plan's own
/// (`verify::model_weld`), and the sheets and features are the plan's: flags for them would be
/// ignored, so the command does not take them.
#[derive(Debug, Clone, Copy)]
pub struct ForVerify;
impl Subset for ForVerify {
    fn includes(def: &Def) -> bool {
        matches!(def.name, "units" | "scale")
    }
}

/// `test-strip` and `hinge-test`: the material (they take one thickness of their own).
#[derive(Debug, Clone, Copy)]
pub struct ForMaterial;
impl Subset for ForMaterial {
    fn includes(def: &Def) -> bool {
        def.name == "material"
    }
}

/// The settings given on a command line (defaults included), applied in the definitions'
/// order to the library's defaults by [`SettingArgs::chosen`].
#[derive(Debug, Clone)]
pub struct SettingArgs<S> {
    given: Vec<(&'static str, Vec<String>)>,
    subset: PhantomData<S>,
}

impl<S: Subset> SettingArgs<S> {
    /// What the flags ask for, checked by the library's `validate`; errors name the flag.
    pub fn chosen(&self) -> anyhow::Result<Chosen> {
        let mut chosen = Chosen::default();
        for (name, values) in &self.given {
            let refs: Vec<&str> = values.iter().map(String::as_str).collect();
            chosen
                .set(name, &refs)
                .map_err(|e| anyhow::anyhow!(flags(&e.to_string())))?;
        }
        chosen.validate().map_err(|e| anyhow::anyhow!(flags(&e.to_string())))?;
        Ok(chosen)
    }
}

/// `message` with every setting it names written as its flag (`--scale`).
pub fn flags(message: &str) -> String {
    options::render(message, |d| format!("--{}", d.name))
}

fn defs_of<S: Subset>() -> impl Iterator<Item = &'static Def> {
    options::DEFS.iter().filter(|d| S::includes(d))
}

/// The flag of one setting.
fn arg_of(def: &'static Def) -> Arg {
    let defaults = def.default_texts();
    let mut arg = Arg::new(def.name)
        .long(def.name)
        .help(def.help)
        .long_help(format!("{} {}", def.help, def.doc))
        .help_heading(def.group.label())
        .default_values(defaults);
    if let Some(c) = def.short {
        arg = arg.short(c);
    }
    arg = match def.kind {
        Kind::Choice { choices } => arg
            .value_name(def.name.to_uppercase())
            .value_parser(PossibleValuesParser::new(
                choices.iter().map(|c| PossibleValue::new(c.value).help(c.help)),
            )),
        Kind::Number { unit, auto, .. } => arg.value_name(if auto.is_some() {
            format!("auto|{}", unit_word(unit))
        } else {
            unit_word(unit)
        }),
        Kind::Numbers { unit, .. } => arg.value_name(unit_word(unit)).action(ArgAction::Append),
        Kind::Sheet { .. } => arg.value_name("WxH|fit"),
        Kind::Text { shape, .. } => arg.value_name(shape),
    };
    arg
}

fn unit_word(unit: &str) -> String {
    match unit {
        "×" => "FACTOR".into(),
        u => u.to_uppercase(),
    }
}

impl<S: Subset> FromArgMatches for SettingArgs<S> {
    fn from_arg_matches(matches: &ArgMatches) -> Result<Self, clap::Error> {
        let given = defs_of::<S>()
            .filter_map(|def| {
                let values = matches.get_many::<String>(def.name)?;
                Some((def.name, values.cloned().collect()))
            })
            .collect();
        Ok(Self {
            given,
            subset: PhantomData,
        })
    }

    fn update_from_arg_matches(&mut self, matches: &ArgMatches) -> Result<(), clap::Error> {
        *self = Self::from_arg_matches(matches)?;
        Ok(())
    }
}

impl<S: Subset> clap::Args for SettingArgs<S> {
    fn augment_args(cmd: Command) -> Command {
        defs_of::<S>().fold(cmd, |cmd, def| cmd.arg(arg_of(def)))
    }

    fn augment_args_for_update(cmd: Command) -> Command {
        Self::augment_args(cmd)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn messages_name_flags() {
        assert_eq!(flags("`scale`: 0 must be a number"), "--scale: 0 must be a number");
    }
}
