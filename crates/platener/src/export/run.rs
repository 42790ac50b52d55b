//! From parts to a ZIP in one call: the four cutting-plan steps as plain functions, for the
//! methods' callers, tests and benchmarks that have parts but no pipeline state.

use crate::kerf::{self, CutPaths};
use crate::labels::{self, Labels};
use crate::pipeline::Step;
use crate::plan::{PlanError, PlanInput};
use crate::sheets::{self, Nesting};

use super::{Bundle, ExportStep, export};

/// Everything the cutting-plan steps made.
#[derive(Debug, Clone)]
pub struct CuttingPlan {
    /// Step `kerf`.
    pub cut: CutPaths,
    /// Step `labels`.
    pub labels: Labels,
    /// Step `sheets`.
    pub nesting: Nesting,
    /// Step `export`: plan.json, report.json, every file and the ZIP.
    pub bundle: Bundle,
}

/// Runs kerf → labels → sheets → export on `input`. `cancelled` is polled between steps and
/// while nesting.
pub fn cutting_plan(input: &PlanInput, cancelled: &(dyn Fn() -> bool + Sync)) -> Result<CuttingPlan, PlanError> {
    input.validate()?;
    let check = |step| {
        if cancelled() {
            Err(PlanError::Cancelled { step })
        } else {
            Ok(())
        }
    };
    check("kerf")?;
    let cut = kerf::cut_paths(&input.parts, input.settings.kerf())?;
    check("labels")?;
    let labels = labels::label_parts(&input.parts, input.settings.labels, input.settings.kerf());
    check("sheets")?;
    let nesting = sheets::nest(&input.parts, &cut, &input.settings, cancelled)?;
    check("export")?;
    let bundle = export(input, &cut, &labels, &nesting)?;
    Ok(CuttingPlan {
        cut,
        labels,
        nesting,
        bundle,
    })
}

/// The cutting-plan steps in pipeline order; they start from the state's `parts` snapshot.
pub fn cutting_plan_steps() -> Vec<&'static dyn Step> {
    vec![&kerf::KerfStep, &labels::LabelsStep, &sheets::SheetsStep, &ExportStep]
}
