//! The pipeline: named steps run in order over a [`State`].
//!
//! Each step is a function of its inputs in its own module (`read::run`, `plates::run`…) that
//! returns its snapshot; it knows nothing of the pipeline. This module knows the steps: it
//! takes each step's inputs out of the state, runs it with a [`StepContext`], and stores the
//! snapshot (`Arc`, shared, never deep-copied) and a [`StepRecord`] in the state. Only the
//! runner writes the state, so a viewer can show any step afterwards and a later method can
//! start from any earlier snapshot. docs/architecture.md describes the layers.

mod steps;
#[cfg(test)]
mod tests;
mod view;

use std::sync::Arc;
use std::time::Instant;

use crate::error::{Error, Result};
use crate::settings::Settings;
use crate::{
    bends, classify, cleanup, coplanar, export, joints, kerf, labels, layers, mesh, plan, plates, read, relief, shapes,
    sheets, stacked, weld,
};

pub use crate::context::{Cancel, StepContext, StepRecord, Warning, WarningKind};
pub use crate::read::Source;
pub use steps::{CUTTING_PLAN, FOUNDATION, PLATE, StepId};

/// The state of a conversion: the input, then one snapshot per step that has run, and the
/// record of every step that ran.
#[derive(Debug, Clone)]
pub struct State {
    /// What is converted.
    pub source: Source,
    /// The settings of this run.
    pub settings: Arc<Settings>,
    /// Every step that ran, in order, with its time and warnings.
    pub records: Vec<StepRecord>,
    /// Step `read`.
    pub read: Option<Arc<read::Model>>,
    /// Step `cleanup`.
    pub cleanup: Option<Arc<cleanup::Cleaned>>,
    /// Step `weld`.
    pub weld: Option<Arc<weld::Welded>>,
    /// Step `mesh`.
    pub mesh: Option<Arc<mesh::Mesh>>,
    /// Step `coplanar`.
    pub coplanar: Option<Arc<coplanar::PlanarGroups>>,
    /// Step `classify` (classifier method; it also fills `coplanar`).
    pub classify: Option<Arc<classify::Classification>>,
    /// Step `shapes`.
    pub shapes: Option<Arc<shapes::Shapes>>,
    /// Step `plates`.
    pub plates: Option<Arc<plates::Plates>>,
    /// Step `bends`.
    pub bends: Option<Arc<bends::Bends>>,
    /// Step `joints`.
    pub joints: Option<Arc<joints::Joints>>,
    /// Step `stacked`: layers and shafts of the stacked method.
    pub stacked: Option<Arc<stacked::Stack>>,
    /// Step `interlocked`: the slices and crossings of the interlocked method.
    pub interlocked: Option<Arc<crate::interlocked::Interlocked>>,
    /// Step `relief`: the classifier's flattened textures engraved on their plates.
    pub relief: Option<Arc<relief::Relief>>,
    /// Step `layers`: the classifier's spheres and freeforms as layers among its plates.
    pub layers: Option<Arc<layers::Layers>>,
    /// Step `parts`: the plate method's parts with the cutting settings (the classifier's
    /// plates, before `relief` and `layers` add to them). The cutting-plan steps read
    /// [`State::final_parts`].
    pub parts: Option<Arc<plan::PlanInput>>,
    /// Step `stacked`'s parts: its layers and shafts.
    pub stacked_parts: Option<Arc<plan::PlanInput>>,
    /// Step `interlocked`'s parts: its slices.
    pub interlocked_parts: Option<Arc<plan::PlanInput>>,
    /// Step `relief`'s parts: `parts` with the textures engraved, when it engraved any.
    pub relief_parts: Option<Arc<plan::PlanInput>>,
    /// Step `layers`' parts: the parts before it with the layers added, when it cut any.
    pub layers_parts: Option<Arc<plan::PlanInput>>,
    /// Step `kerf`.
    pub kerf: Option<Arc<kerf::CutPaths>>,
    /// Step `labels`.
    pub labels: Option<Arc<labels::Labels>>,
    /// Step `sheets`.
    pub sheets: Option<Arc<sheets::Nesting>>,
    /// Step `export`.
    pub export: Option<Arc<export::Bundle>>,
}

impl State {
    /// A fresh state: nothing has run yet.
    pub fn new(source: Source, settings: Settings) -> Self {
        Self {
            source,
            settings: Arc::new(settings),
            records: Vec::new(),
            read: None,
            cleanup: None,
            weld: None,
            mesh: None,
            coplanar: None,
            classify: None,
            shapes: None,
            plates: None,
            bends: None,
            joints: None,
            stacked: None,
            interlocked: None,
            relief: None,
            layers: None,
            parts: None,
            stacked_parts: None,
            interlocked_parts: None,
            relief_parts: None,
            layers_parts: None,
            kerf: None,
            labels: None,
            sheets: None,
            export: None,
        }
    }

    /// The method's parts as the cutting-plan steps take them: those of the last step that
    /// made or changed parts (`layers`, `relief`, `stacked`, `interlocked`, else `parts`).
    /// Each step writes only its own snapshot; this is the one choice among them.
    pub fn final_parts(&self) -> &Option<Arc<plan::PlanInput>> {
        [
            &self.layers_parts,
            &self.relief_parts,
            &self.stacked_parts,
            &self.interlocked_parts,
        ]
        .into_iter()
        .find(|p| p.is_some())
        .unwrap_or(&self.parts)
    }

    /// A state that starts from parts made elsewhere (tests, benchmarks, programs with their
    /// own parts): ready for the cutting-plan steps.
    pub fn of_parts(input: plan::PlanInput) -> Self {
        let source = Source::Triangles {
            name: input.source.name.clone(),
            triangles: Arc::new(Vec::new()),
        };
        let mut state = Self::new(source, Settings::default());
        state.parts = Some(Arc::new(input));
        state
    }

    /// This state without the snapshots and records of the steps not in `keep`: what a
    /// method that shares only part of another's foundation starts from.
    pub fn keeping(mut self, keep: &[StepId]) -> Self {
        for step in StepId::ALL.into_iter().filter(|s| !keep.contains(s)) {
            self.forget(step);
        }
        self.records.retain(|r| keep.iter().any(|s| s.name() == r.name));
        self
    }

    /// Drops `step`'s snapshot.
    fn forget(&mut self, step: StepId) {
        match step {
            StepId::Read => self.read = None,
            StepId::Cleanup => self.cleanup = None,
            StepId::Weld => self.weld = None,
            StepId::Mesh => self.mesh = None,
            StepId::Coplanar => self.coplanar = None,
            StepId::Classify => self.classify = None,
            StepId::Shapes => self.shapes = None,
            StepId::Plates => self.plates = None,
            StepId::Bends => self.bends = None,
            StepId::Joints => self.joints = None,
            StepId::Parts => self.parts = None,
            StepId::Stacked => {
                self.stacked = None;
                self.stacked_parts = None;
            }
            StepId::Interlocked => {
                self.interlocked = None;
                self.interlocked_parts = None;
            }
            StepId::Relief => {
                self.relief = None;
                self.relief_parts = None;
            }
            StepId::Layers => {
                self.layers = None;
                self.layers_parts = None;
            }
            StepId::Kerf => self.kerf = None,
            StepId::Labels => self.labels = None,
            StepId::Sheets => self.sheets = None,
            StepId::Export => self.export = None,
        }
    }

    /// The model's name, for messages.
    pub fn model_name(&self) -> String {
        self.read
            .as_ref()
            .map_or_else(|| self.source.name(), |m| m.name.clone())
    }

    /// The cutting plan, once `export` ran.
    pub fn bundle(&self) -> Result<&Arc<export::Bundle>> {
        need(&self.export, "convert", "export")
    }

    /// Every warning of every step that ran.
    pub fn warnings(&self) -> impl Iterator<Item = &Warning> {
        self.records.iter().flat_map(|r| r.warnings.iter())
    }
}

/// Takes a snapshot out of the state or reports which step should have made it.
pub fn need<'a, T>(snapshot: &'a Option<Arc<T>>, step: &'static str, needs: &'static str) -> Result<&'a Arc<T>> {
    snapshot.as_ref().ok_or(Error::missing(step, needs))
}

/// What the runner tells an observer.
#[derive(Debug, Clone, Copy)]
pub enum StepEvent<'a> {
    /// A step is about to run.
    Started(&'static str),
    /// A step finished; its record.
    Finished(&'a StepRecord),
}

/// Runs `steps` in order on `state`, recording each in `state.records`. Stops at the first
/// error; the records of the steps that ran (and their warnings) stay in the state.
pub fn run(steps: &[StepId], state: &mut State, cancel: &Cancel) -> Result<()> {
    run_observed(steps, state, cancel, &|_| {})
}

/// [`run`], telling `observe` when each step starts and finishes.
pub fn run_observed(
    steps: &[StepId],
    state: &mut State,
    cancel: &Cancel,
    observe: &(dyn Fn(StepEvent<'_>) + Sync),
) -> Result<()> {
    let model = state.model_name();
    for &step in steps {
        let name = step.name();
        let mut cx = StepContext::new(name, &model, cancel);
        cx.check_cancel()?;
        observe(StepEvent::Started(name));
        let span = tracing::info_span!("step", name);
        let _enter = span.enter();
        let start = Instant::now();
        let result = steps::apply(step, state, &mut cx);
        state.records.push(StepRecord {
            name,
            millis: start.elapsed().as_secs_f64() * 1e3,
            warnings: cx.into_warnings(),
        });
        result?;
        if let Some(record) = state.records.last() {
            observe(StepEvent::Finished(record));
        }
    }
    Ok(())
}

/// The cutting plan of parts made elsewhere: runs kerf → labels → sheets → export.
pub fn cutting_plan(input: plan::PlanInput, cancel: &Cancel) -> Result<State> {
    let mut state = State::of_parts(input);
    run(&CUTTING_PLAN, &mut state, cancel)?;
    Ok(state)
}

/// The plates of a model made in code (`name` for messages), for sheets of the given
/// `thicknesses`: every step up to `plates` with default settings otherwise.
pub fn plates_of_triangles(
    name: &str,
    triangles: Vec<read::Triangle>,
    thicknesses: &[f64],
) -> Result<Arc<plates::Plates>> {
    let source = Source::triangles(name, triangles);
    let settings = Settings {
        thicknesses: thicknesses.to_vec(),
        ..Settings::default()
    };
    let mut state = State::new(source, settings);
    run(&PLATE, &mut state, &Cancel::default())?;
    need(&state.plates, "plates", "plates").cloned()
}
