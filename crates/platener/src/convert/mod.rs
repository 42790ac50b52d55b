//! One call converts a model with every method asked for: [`convert_all`].
//!
//! This is the product's one orchestration; the CLI and the web service only fill a
//! [`Request`], watch the [`Event`]s and render the [`Conversions`]. It runs the steps every
//! method shares (`read`, `cleanup`) once, and `weld` and `mesh` once per distinct weld
//! setting (the stacked method keeps every surface detail, so it welds exact duplicates only
//! and cannot share the plate method's welded mesh), forking the state for each method.
//! The methods run side by side, each on its own thread within its own time limit (one slow
//! method never starves the others), errors and panics are caught per method, every plan is
//! scored and verified (one analysis of its assembly for both) and the best of those that
//! finished is named.

mod panic;
#[cfg(test)]
mod tests;
mod work;

use std::sync::Arc;
use std::time::{Duration, Instant};

use serde::Serialize;

use crate::context::{Cancel, StepRecord, Warning};
use crate::error::{Error, Internal, Result};
use crate::export::Bundle;
use crate::method::MethodKind;
use crate::pipeline::{Source, State, StepEvent};
use crate::score::Score;
use crate::settings::Settings;
use crate::verify::Verification;

pub use panic::PanicHook;

/// What to convert and how.
#[derive(Debug, Clone)]
pub struct Request {
    /// The model: a path, a file's bytes with its name, or triangles.
    pub source: Source,
    /// The settings.
    pub settings: Settings,
    /// The methods to run, in order.
    pub methods: Vec<MethodKind>,
    /// Each method's time limit, counted from its start less the time the shared steps took
    /// (the methods run side by side, so with `parallel` at least the number of methods the
    /// model as a whole ends within it too); a method past it is cancelled and reported timed
    /// out alone. `None`: no limit.
    pub timeout: Option<Duration>,
    /// How many methods run at once (each on a thread of its own; the steps inside share
    /// rayon's pool); 0: all of them. Methods start in the order asked for.
    pub parallel: usize,
    /// Failures to inject, for tests of callers that must survive them.
    pub faults: Vec<Fault>,
}

impl Request {
    /// Every method, no time limit, no faults.
    pub fn new(source: Source, settings: Settings) -> Self {
        Self {
            source,
            settings,
            methods: MethodKind::ALL.to_vec(),
            timeout: None,
            parallel: 0,
            faults: Vec::new(),
        }
    }
}

/// A failure a caller's test asks a method to have, so it can show that it survives it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Fault {
    /// The method that fails.
    pub method: MethodKind,
    /// How.
    pub kind: FaultKind,
}

/// How an injected fault fails.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FaultKind {
    /// Returns an error.
    Error,
    /// Panics.
    Panic,
    /// Runs until cancelled (or the time limit).
    Hang,
}

/// How one method did.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Status {
    /// It made a plan.
    Converted,
    /// It stopped with an error.
    Failed,
    /// It panicked (a bug of ours; the error says where).
    Panicked,
    /// The model ran past the time limit before this method finished.
    TimedOut,
    /// The caller cancelled the run.
    Cancelled,
    /// The method had nothing to add for this model and stopped early (the error says why).
    Skipped,
}

impl Status {
    /// The status an error stands for.
    pub fn of(error: &Error) -> Self {
        match error {
            Error::Cancelled { .. } => Status::Cancelled,
            Error::TimedOut { .. } => Status::TimedOut,
            Error::Skipped { .. } => Status::Skipped,
            Error::Internal {
                problem: Internal::Panic { .. },
                ..
            } => Status::Panicked,
            _ => Status::Failed,
        }
    }
}

/// One method's result: its snapshots and records, its plan and score, or its error.
#[derive(Debug, Clone)]
pub struct MethodResult {
    /// The method.
    pub method: MethodKind,
    /// How it went.
    pub status: Status,
    /// Wall time, seconds (0 for a method the time limit stopped).
    pub seconds: f64,
    /// Every snapshot and step record it reached (`None` when it panicked or timed out).
    pub state: Option<State>,
    /// The score of its plan, when converted.
    pub score: Option<Score>,
    /// `verify`'s verdict on its plan against the method's mesh, when converted (from the same
    /// analysis of the assembly as the score).
    pub verification: Option<Verification>,
    /// Why it did not convert.
    pub error: Option<Error>,
}

impl MethodResult {
    /// The plan, report, files and ZIP, when converted.
    pub fn bundle(&self) -> Option<&Arc<Bundle>> {
        self.state.as_ref().and_then(|s| s.export.as_ref())
    }

    /// The records of every step it ran (shared steps included).
    pub fn steps(&self) -> &[StepRecord] {
        self.state.as_ref().map_or(&[], |s| &s.records)
    }

    /// Every warning of every step it ran.
    pub fn warnings(&self) -> impl Iterator<Item = &Warning> {
        self.steps().iter().flat_map(|r| r.warnings.iter())
    }
}

/// Everything one call made.
#[derive(Debug, Clone)]
pub struct Conversions {
    /// The model's name.
    pub name: String,
    /// The state after the shared steps (the model as read and cleaned), when they ran.
    pub shared: Option<State>,
    /// Per method asked for, in order.
    pub methods: Vec<MethodResult>,
    /// The best converted method: the highest score among the plans `verify` passes, or, when
    /// it passes none, among all (the first on a tie).
    pub best: Option<MethodKind>,
    /// Wall time, seconds.
    pub seconds: f64,
}

impl Conversions {
    /// The result of `method`, if it was asked for.
    pub fn method(&self, method: MethodKind) -> Option<&MethodResult> {
        self.methods.iter().find(|m| m.method == method)
    }

    /// The best method's result.
    pub fn best(&self) -> Option<&MethodResult> {
        self.best.and_then(|m| self.method(m))
    }
}

/// What a conversion tells its observer, as it happens.
#[derive(Debug, Clone, Copy)]
pub enum Event<'a> {
    /// A step started or finished; `method` is `None` for the shared steps.
    Step {
        /// The method it runs for.
        method: Option<MethodKind>,
        /// Started or finished, with its record.
        event: StepEvent<'a>,
    },
    /// The shared steps ended (`read` and `cleanup`, or as far as they got), before any
    /// method starts: the state holds the model as read when `read` succeeded, so a caller
    /// can show the model while the methods still run.
    Shared(&'a State),
    /// A method finished (converted, failed, panicked or timed out).
    Method(&'a MethodResult),
}

/// Receives [`Event`]s; called from the conversion's threads (one per method, at once).
pub trait Progress: Send + Sync {
    /// Handles one event.
    fn event(&self, event: Event<'_>);
}

impl<F: Fn(Event<'_>) + Send + Sync> Progress for F {
    fn event(&self, event: Event<'_>) {
        self(event)
    }
}

/// An observer that ignores everything.
pub fn no_progress() -> Arc<dyn Progress> {
    Arc::new(|_: Event<'_>| {})
}

/// Converts the request's model with each of its methods: see the module documentation.
///
/// Every method runs on a thread of its own with its own time limit, so a method past it is
/// cancelled (and, when a step does not notice within a grace period, left behind) while the
/// others finish; each method's [`Event::Method`] is sent the moment it ends. `cancel` stops
/// the run at the next check of any step. Never fails: every error is a method's (or, for the
/// shared steps, every method's).
pub fn convert_all(request: Request, cancel: &Cancel, progress: Arc<dyn Progress>) -> Conversions {
    let start = Instant::now();
    let name = request.source.name();
    let (shared, methods) = work::run(&request, cancel, progress);
    let best = best_of(&methods);
    Conversions {
        name,
        shared,
        methods,
        best,
        seconds: start.elapsed().as_secs_f64(),
    }
}

/// Converts with one method, no time limit: its snapshots, or its error.
pub fn convert(method: MethodKind, source: Source, settings: Settings, cancel: &Cancel) -> Result<State> {
    let request = Request {
        methods: vec![method],
        ..Request::new(source, settings)
    };
    let mut all = convert_all(request, cancel, no_progress());
    let result = all.methods.pop().ok_or(Error::Internal {
        step: "convert",
        problem: Internal::Thread {
            message: "no method result".into(),
        },
    })?;
    match (result.error, result.state) {
        (None, Some(state)) => Ok(state),
        (Some(e), _) => Err(e),
        (None, None) => Err(Error::missing("convert", "export")),
    }
}

/// Scores closer than this are a tie, decided by the volume the plans keep inside the model.
/// The score measures the surface a plan reproduces, not its volume (a wall cut thicker than
/// the model's loses volume by design), so a textured box's plates standing proud of its
/// walls scored as its true walls did (0.982 both, 67 % against 100 % of the volume inside).
pub const SCORE_TIE: f64 = 0.005;

/// The converted method with the highest score among those whose plan `verify` passes (a
/// plan that does not assemble into the model is never named best over one that does);
/// between scores within [`SCORE_TIE`], the one with more of its parts' volume inside the
/// model; the first on a tie of both.
fn best_of(methods: &[MethodResult]) -> Option<MethodKind> {
    let mut best: Option<(MethodKind, bool, f64, f64)> = None;
    for m in methods.iter().filter(|m| m.status == Status::Converted) {
        let passed = m.verification.as_ref().is_some_and(|v| v.passed());
        let score = m.score.as_ref().map_or(0.0, |s| s.total);
        let inside = m.verification.as_ref().and_then(|v| v.volume_inside).unwrap_or(0.0);
        let better = best.is_none_or(|(_, b_passed, b_score, b_inside)| {
            let tied = (score - b_score).abs() <= SCORE_TIE;
            (passed && !b_passed) || (passed == b_passed && ((!tied && score > b_score) || (tied && inside > b_inside)))
        });
        if better {
            best = Some((m.method, passed, score, inside));
        }
    }
    best.map(|(m, ..)| m)
}
