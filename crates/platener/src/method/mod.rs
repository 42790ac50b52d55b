//! Fabrication methods: the whole chain of steps from a model to a cutting plan.
//!
//! A method is a list of pipeline steps ending in a `parts` snapshot (the parts to cut and how
//! they connect), followed by the cutting-plan steps (`kerf`, `labels`, `sheets`, `export`),
//! which never need to know which method made the parts.
//!
//! | method | steps |
//! |---|---|
//! | plate | foundation, `plates`, `joints`, `parts` (plates with joints → parts) |
//! | stacked | foundation without welding, `stacked` (layers and shafts → parts) |

mod plate_parts;

use std::sync::Arc;

use serde::Serialize;

use crate::error::{Error, Result};
use crate::export::{Bundle, cutting_plan_steps};
use crate::pipeline::{self, Cancel, Source, State, Step, StepRecord};
use crate::settings::{Settings, Weld};

pub use plate_parts::PlatePartsStep;

/// The fabrication methods.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, PartialOrd, Ord)]
#[serde(rename_all = "lowercase")]
pub enum MethodKind {
    /// Flat plates joined by joints (the default).
    Plate,
    /// The model sliced into stacked layers joined by shafts.
    Stacked,
}

impl MethodKind {
    /// Every method, in the order `--method all` runs them.
    pub const ALL: [MethodKind; 2] = [MethodKind::Plate, MethodKind::Stacked];

    /// The name used in file names and reports.
    pub fn name(self) -> &'static str {
        match self {
            MethodKind::Plate => "plate",
            MethodKind::Stacked => "stacked",
        }
    }

    /// The steps up to and including the `parts` snapshot.
    pub fn steps(self) -> Vec<&'static dyn Step> {
        match self {
            MethodKind::Plate => {
                let mut steps = pipeline::plate_steps();
                steps.push(&PlatePartsStep);
                steps
            }
            MethodKind::Stacked => {
                let mut steps = pipeline::foundation_steps();
                steps.push(&crate::stacked::StackedStep);
                steps
            }
        }
    }

    /// The settings this method runs with: the stacked method keeps every surface detail, so
    /// it merges exact duplicates only.
    pub fn adjust(self, mut settings: Settings) -> Settings {
        if self == MethodKind::Stacked {
            settings.weld = Weld::Off;
        }
        settings
    }
}

/// A finished conversion: every snapshot, the step records, and the cutting plan.
#[derive(Debug, Clone)]
pub struct Conversion {
    /// The method that ran.
    pub method: MethodKind,
    /// Every step's snapshot.
    pub state: State,
    /// Every step that ran, with times and warnings.
    pub steps: Vec<StepRecord>,
}

impl Conversion {
    /// The cutting plan: plan.json, report.json, sheets and the ZIP.
    pub fn bundle(&self) -> Result<&Arc<Bundle>> {
        pipeline::need(&self.state.export, "convert", "export")
    }
}

/// Converts `source` with one method, all the way to the ZIP.
pub fn convert(method: MethodKind, source: Source, settings: Settings, cancel: &Cancel) -> Result<Conversion> {
    let settings = method.adjust(settings);
    settings.validate()?;
    let mut state = State::new(source, settings);
    let mut steps = pipeline::run(&method.steps(), &mut state, cancel)?;
    // report.json lists the steps that made the parts, too.
    let parts = state.parts.as_ref().ok_or(Error::MissingStep {
        step: "convert",
        needs: "parts",
    })?;
    let mut input = (**parts).clone();
    input.earlier_steps = steps.iter().map(Into::into).collect();
    state.parts = Some(Arc::new(input));
    steps.extend(pipeline::run(&cutting_plan_steps(), &mut state, cancel)?);
    Ok(Conversion { method, state, steps })
}

#[cfg(test)]
mod tests;
