//! Step `stacked`: the model sliced into layers joined by shafts (issue: stacked-plates method).

use crate::error::{Error, Result};
use crate::pipeline::{State, Step, StepContext};

/// Step `stacked`.
pub struct StackedStep;

impl Step for StackedStep {
    fn name(&self) -> &'static str {
        "stacked"
    }

    fn run(&self, state: &mut State, _cx: &mut StepContext<'_>) -> Result<()> {
        Err(Error::Model {
            model: state.source.name(),
            message: "the stacked method is not built yet".into(),
        })
    }
}
