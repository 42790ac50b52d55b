//! The pipeline framework: named steps run in order over a [`State`].
//!
//! A step reads the snapshots of earlier steps and adds its own result as a new immutable
//! snapshot (`Arc`, shared, never deep-copied), so a viewer can show any step afterwards and a
//! later method can start from any earlier snapshot. Each step is timed, collects its own
//! warnings, and a running conversion can be cancelled between and inside steps.

use std::path::PathBuf;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Instant;

use serde::Serialize;

use crate::error::{Error, Result};
use crate::settings::Settings;
use crate::{cleanup, coplanar, mesh, plates, read, shapes, weld};

/// Where the model comes from.
#[derive(Debug, Clone)]
pub enum Source {
    /// A file on disk; the format follows the extension.
    File(PathBuf),
    /// Triangles made in code (tests, benchmarks, generated models), already in mm.
    Triangles {
        /// A name for reports.
        name: String,
        /// The triangles.
        triangles: Arc<Vec<read::Triangle>>,
    },
}

impl Source {
    /// The model's name for messages: the file stem, or the given name.
    pub fn name(&self) -> String {
        match self {
            Source::File(p) => p
                .file_stem()
                .map_or_else(|| p.display().to_string(), |s| s.to_string_lossy().into()),
            Source::Triangles { name, .. } => name.clone(),
        }
    }
}

/// The state of a conversion: the input, then one snapshot per step that has run.
#[derive(Debug, Clone)]
pub struct State {
    /// What is converted.
    pub source: Source,
    /// The settings of this run.
    pub settings: Arc<Settings>,
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
    /// Step `shapes`.
    pub shapes: Option<Arc<shapes::Shapes>>,
    /// Step `plates`.
    pub plates: Option<Arc<plates::Plates>>,
    /// Step `joints`.
    pub joints: Option<Arc<crate::joints::Joints>>,
    /// Step `stacked`: layers and shafts of the stacked method.
    pub stacked: Option<Arc<crate::stacked::Stack>>,
    /// Input of the cutting-plan steps: the parts a method made, with the cutting settings.
    pub parts: Option<Arc<crate::plan::PlanInput>>,
    /// Step `kerf`.
    pub kerf: Option<Arc<crate::kerf::CutPaths>>,
    /// Step `labels`.
    pub labels: Option<Arc<crate::labels::Labels>>,
    /// Step `sheets`.
    pub sheets: Option<Arc<crate::sheets::Nesting>>,
    /// Step `export`.
    pub export: Option<Arc<crate::export::Bundle>>,
}

impl State {
    /// A fresh state: nothing has run yet.
    pub fn new(source: Source, settings: Settings) -> Self {
        Self {
            source,
            settings: Arc::new(settings),
            read: None,
            cleanup: None,
            weld: None,
            mesh: None,
            coplanar: None,
            shapes: None,
            plates: None,
            joints: None,
            stacked: None,
            parts: None,
            kerf: None,
            labels: None,
            sheets: None,
            export: None,
        }
    }
}

/// Takes a snapshot out of the state or reports which step should have made it.
pub(crate) fn need<'a, T>(snapshot: &'a Option<Arc<T>>, step: &'static str, needs: &'static str) -> Result<&'a Arc<T>> {
    snapshot.as_ref().ok_or(Error::MissingStep { step, needs })
}

/// A cancellation flag shared between the caller and a running conversion.
#[derive(Debug, Clone, Default)]
pub struct Cancel(Arc<AtomicBool>);

impl Cancel {
    /// Asks the conversion to stop at its next check.
    pub fn cancel(&self) {
        self.0.store(true, Ordering::Relaxed);
    }

    /// Whether cancellation was asked for.
    pub fn is_cancelled(&self) -> bool {
        self.0.load(Ordering::Relaxed)
    }
}

/// What kind of thing a warning is about, for programs reading report.json.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum WarningKind {
    /// Something the reader noticed (e.g. bytes after the last facet).
    Reader,
    /// The model is suspiciously small or large: wrong units?
    Units,
    /// Zero-area triangles were removed.
    DegenerateFaces,
    /// Duplicate triangles were removed.
    DuplicateFaces,
    /// Welding would have emptied the model; the unwelded mesh was used.
    WeldFallback,
    /// Welding at the distance asked would have closed holes or fused parts; a smaller one
    /// was used.
    WeldReduced,
    /// Edges used by one triangle only (holes in the surface).
    OpenEdges,
    /// Edges shared by more than two triangles.
    NonManifoldEdges,
    /// Triangles wound against their neighbours, turned round.
    FlippedFaces,
    /// Stored normals disagree with the winding (we use the winding).
    StoredNormals,
    /// A joint could not be made as planned (a plate would fall apart…).
    Joints,
    /// Something the cutting-plan steps had to adapt (a label skipped, a part larger than the
    /// sheet, a hole closed by the kerf).
    CuttingPlan,
}

/// A warning raised by a step: the conversion goes on, the user should know.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Warning {
    /// The step that raised it.
    pub step: &'static str,
    /// Its kind.
    pub kind: WarningKind,
    /// The message, naming the defect and what to do.
    pub message: String,
}

/// What a step gets besides the state: settings, cancellation, a place for warnings.
pub struct StepContext<'a> {
    step: &'static str,
    cancel: &'a Cancel,
    warnings: Vec<Warning>,
}

impl StepContext<'_> {
    /// Records a warning of this step.
    pub fn warn(&mut self, kind: WarningKind, message: impl Into<String>) {
        self.warnings.push(Warning {
            step: self.step,
            kind,
            message: message.into(),
        });
    }

    /// Records the warnings a cutting-plan computation kept with its result.
    pub fn warn_all(&mut self, warnings: &[crate::plan::PlanWarning]) {
        for w in warnings {
            self.warn(WarningKind::CuttingPlan, w.message.clone());
        }
    }

    /// Returns `Err(Cancelled)` when the run was cancelled; call it in long loops.
    pub fn check_cancel(&self) -> Result<()> {
        if self.cancel.is_cancelled() {
            Err(Error::Cancelled { step: self.step })
        } else {
            Ok(())
        }
    }
}

/// One pipeline step.
pub trait Step: Sync {
    /// The step's name, as in report.json and the module it lives in.
    fn name(&self) -> &'static str;
    /// Reads earlier snapshots from `state` and stores its own snapshot in it.
    fn run(&self, state: &mut State, cx: &mut StepContext<'_>) -> Result<()>;
}

/// The record of one step that ran.
#[derive(Debug, Clone, Serialize)]
pub struct StepRecord {
    /// The step's name.
    pub name: &'static str,
    /// Wall time in milliseconds.
    pub millis: f64,
    /// Warnings it raised.
    pub warnings: Vec<Warning>,
}

/// The steps that turn a model into planar shapes (the foundation every method builds on).
pub fn foundation_steps() -> Vec<&'static dyn Step> {
    vec![
        &read::ReadStep,
        &cleanup::CleanupStep,
        &weld::WeldStep,
        &mesh::MeshStep,
        &coplanar::CoplanarStep,
        &shapes::ShapesStep,
    ]
}

/// The foundation steps, then plate finding and joints.
pub fn plate_steps() -> Vec<&'static dyn Step> {
    let mut steps = foundation_steps();
    steps.push(&plates::PlatesStep);
    steps.push(&crate::joints::JointsStep);
    steps
}

/// Runs `steps` in order on `state`, recording each. Stops at the first error.
pub fn run(steps: &[&dyn Step], state: &mut State, cancel: &Cancel) -> Result<Vec<StepRecord>> {
    let mut records = Vec::with_capacity(steps.len());
    for step in steps {
        let mut cx = StepContext {
            step: step.name(),
            cancel,
            warnings: Vec::new(),
        };
        cx.check_cancel()?;
        let span = tracing::info_span!("step", name = step.name());
        let _enter = span.enter();
        let start = Instant::now();
        step.run(state, &mut cx)?;
        records.push(StepRecord {
            name: step.name(),
            millis: start.elapsed().as_secs_f64() * 1e3,
            warnings: cx.warnings,
        });
    }
    Ok(records)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::samples::cuboid;
    use glam::DVec3;

    fn source(size: f64) -> Source {
        Source::Triangles {
            name: "cube".into(),
            triangles: Arc::new(cuboid(DVec3::ZERO, DVec3::splat(size))),
        }
    }

    #[test]
    fn a_cancelled_run_stops_with_the_step_it_reached() {
        let cancel = Cancel::default();
        cancel.cancel();
        let mut state = State::new(source(10.0), Settings::default());
        let err = run(&foundation_steps(), &mut state, &cancel).expect_err("cancelled");
        assert!(matches!(err, Error::Cancelled { step: "read" }));
        assert!(state.read.is_none());
    }

    #[test]
    fn a_step_without_its_input_says_which_step_is_missing() {
        let mut state = State::new(source(10.0), Settings::default());
        let err = run(&[&mesh::MeshStep], &mut state, &Cancel::default()).expect_err("no weld yet");
        assert!(matches!(
            err,
            Error::MissingStep {
                step: "mesh",
                needs: "weld"
            }
        ));
    }

    #[test]
    fn every_step_leaves_a_snapshot_and_a_record() {
        let mut state = State::new(source(10.0), Settings::default());
        let records = run(&foundation_steps(), &mut state, &Cancel::default()).expect("runs");
        let names: Vec<_> = records.iter().map(|r| r.name).collect();
        assert_eq!(names, ["read", "cleanup", "weld", "mesh", "coplanar", "shapes"]);
        let before = state.read.clone().expect("read");
        // Snapshots are shared, not copied: a later state holds the very same read result.
        let later = state.clone();
        assert!(Arc::ptr_eq(&before, later.read.as_ref().expect("read")));
        assert_eq!(state.shapes.expect("shapes").shapes.len(), 6);
    }

    #[test]
    fn tiny_and_huge_models_get_a_units_warning() {
        for (size, warned) in [(0.5, true), (50.0, false), (6000.0, true)] {
            let mut state = State::new(source(size), Settings::default());
            let records = run(&foundation_steps(), &mut state, &Cancel::default()).expect("runs");
            let units = records[0].warnings.iter().any(|w| w.kind == WarningKind::Units);
            assert_eq!(units, warned, "size {size}");
        }
    }

    #[test]
    fn scale_is_applied_in_the_read_step() {
        let settings = Settings {
            units: crate::Units::In,
            scale: 2.0,
            ..Settings::default()
        };
        let mut state = State::new(source(1.0), settings);
        run(&foundation_steps(), &mut state, &Cancel::default()).expect("runs");
        let b = state.read.expect("read").bounds;
        assert!((b.max - DVec3::splat(50.8)).length() < 1e-12);
    }
}
