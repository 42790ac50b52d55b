//! What every pipeline step gets besides its inputs: cancellation and a place for warnings.
//!
//! This module imports nothing else of the crate, so that every step module can use it
//! without depending on the pipeline that runs it (docs/architecture.md).

use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};

use serde::Serialize;

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

/// A step noticed that its run was cancelled.
#[derive(Debug, Clone, Copy, PartialEq, Eq, thiserror::Error)]
#[error("cancelled during step {step}")]
pub struct Cancelled {
    /// The step that noticed.
    pub step: &'static str,
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
    /// The weld distance was cut back below the model's thinnest wall, or a weld distance set
    /// by the user reaches it (both figures in the message).
    WeldThinWall,
    /// Edges used by one triangle only (holes in the surface).
    OpenEdges,
    /// Edges shared by more than two triangles.
    NonManifoldEdges,
    /// Triangles wound against their neighbours, turned round.
    FlippedFaces,
    /// Stored normals disagree with the winding (we use the winding).
    StoredNormals,
    /// Plate finding found nothing (the message says why for each kind of face).
    Plates,
    /// One-sided features of plates engraved as marks, or bosses standing on plates left out.
    Features,
    /// A joint could not be made as planned (a plate would fall apart…).
    Joints,
    /// Something the cutting-plan steps had to adapt (a label skipped, a part larger than the
    /// sheet, a hole closed by the kerf).
    CuttingPlan,
}

/// A warning raised by a step: the conversion goes on, the user should know. The one warning
/// type of the library: steps raise it, step records keep it, reports render it.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Warning {
    /// The step that raised it.
    pub step: &'static str,
    /// Its kind.
    pub kind: WarningKind,
    /// The part it concerns, if one (cutting-plan steps).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub part: Option<u32>,
    /// The message, naming the defect and what to do.
    pub message: String,
}

/// The record of one step that ran: the one place its time and warnings are kept
/// (report.json and every report of the callers are built from these).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct StepRecord {
    /// The step's name.
    pub name: &'static str,
    /// Wall time in milliseconds.
    pub millis: f64,
    /// Warnings it raised.
    pub warnings: Vec<Warning>,
}

/// What a step gets besides its inputs: cancellation and a place for warnings.
#[derive(Debug)]
pub struct StepContext<'a> {
    step: &'static str,
    model: &'a str,
    cancel: &'a Cancel,
    warnings: Vec<Warning>,
}

impl<'a> StepContext<'a> {
    /// A context for running `step` on the model named `model`, stopped by `cancel`.
    pub fn new(step: &'static str, model: &'a str, cancel: &'a Cancel) -> Self {
        Self {
            step,
            model,
            cancel,
            warnings: Vec::new(),
        }
    }

    /// The step this context belongs to.
    pub fn step(&self) -> &'static str {
        self.step
    }

    /// The name of the model being converted, for error messages.
    pub fn model(&self) -> &'a str {
        self.model
    }

    /// Records a warning of this step.
    pub fn warn(&mut self, kind: WarningKind, message: impl Into<String>) {
        self.warnings.push(self.warning(kind, None, message));
    }

    /// Records a warning of this step about one part.
    pub fn warn_part(&mut self, kind: WarningKind, part: Option<u32>, message: impl Into<String>) {
        self.warnings.push(self.warning(kind, part, message));
    }

    /// A warning of this step, not yet recorded (for work that runs in parallel and hands
    /// its warnings back).
    pub fn warning(&self, kind: WarningKind, part: Option<u32>, message: impl Into<String>) -> Warning {
        Warning {
            step: self.step,
            kind,
            part,
            message: message.into(),
        }
    }

    /// Records warnings made with [`StepContext::warning`].
    pub fn extend(&mut self, warnings: impl IntoIterator<Item = Warning>) {
        self.warnings.extend(warnings);
    }

    /// Whether the run was cancelled (for callbacks that poll).
    pub fn is_cancelled(&self) -> bool {
        self.cancel.is_cancelled()
    }

    /// Returns `Err(Cancelled)` when the run was cancelled; call it in long loops.
    pub fn check_cancel(&self) -> Result<(), Cancelled> {
        if self.cancel.is_cancelled() {
            Err(Cancelled { step: self.step })
        } else {
            Ok(())
        }
    }

    /// The warnings recorded so far, ending the context.
    pub fn into_warnings(self) -> Vec<Warning> {
        self.warnings
    }
}
