//! Results as they come (issue 30): one job's writer stores, in the order the conversion told
//! them, step events at once, the model scene once the shared steps have read the model, and
//! each method's files the moment it ends, while the other methods still run.
//!
//! The files are made on tokio's blocking pool, started from the conversion's own thread as
//! its event arrives, so the conversion never waits for them: a scene that takes a while only
//! delays the events queued behind it. Every write is checked against the attempt's hold
//! ([`Db::land`], [`Db::append_progress`]): after a cancel, a lost lease or a requeue nothing
//! more is stored, and the conversion is told to stop.

use std::sync::{Arc, Mutex, MutexGuard, PoisonError};

use platener::convert::{Event, MethodResult};
use platener::method::MethodKind;
use platener::pipeline::{StepEvent, StepId};
use platener::{Cancel, State};
use serde_json::{Value, json};
use tokio::runtime::Handle;
use tokio::sync::mpsc::UnboundedReceiver;
use tokio::task::JoinHandle;

use crate::db::{Db, DbError, Hold, ResultFile};
use crate::results::{self, Landed};
use crate::summary::{MethodLine, ModelLine, StepLine, Summary};

/// What the conversion's observer hands the writer, in the order it happened.
pub(super) enum Note {
    /// A step's event: its SSE data.
    Step(String),
    /// Files being made, to be stored with the event saying they are there.
    Landing(JoinHandle<Landing>),
}

impl Note {
    /// The note of a library event, its files started on `pool` at once; none for shared
    /// steps that did not read the model (nothing to show: the job fails at once).
    pub(super) fn of(event: Event<'_>, pool: &Handle) -> Option<Note> {
        match event {
            Event::Step { method, event } => Some(Note::Step(step_json(method, event).to_string())),
            Event::Shared(state) if state.read.is_some() => {
                let state = state.clone();
                Some(Note::Landing(pool.spawn_blocking(move || Landing::model(&state))))
            }
            Event::Shared(_) => None,
            Event::Method(m) => {
                let m = m.clone();
                Some(Note::Landing(pool.spawn_blocking(move || Landing::method(&m))))
            }
        }
    }
}

/// A `step` event's data: the step's name and, for people, what it does (`label`, the
/// library's one table of them); for a method's step also its place among the method's steps
/// (`index` from 0, of `of`), which progress bars count by, since a foundation another method
/// made first sends no events of its own.
pub(super) fn step_json(method: Option<MethodKind>, event: StepEvent<'_>) -> Value {
    let name = method.map(MethodKind::name);
    let (step, mut data) = match event {
        StepEvent::Started(step) => (step, json!({"method": name, "step": step, "state": "started"})),
        StepEvent::Finished(record) => (
            record.name,
            json!({
                "method": name, "step": record.name, "state": "finished",
                "ms": record.millis, "warnings": record.warnings.len(),
            }),
        ),
    };
    let id = StepId::named(step);
    data["label"] = json!(id.map(StepId::label));
    if let (Some(method), Some(id)) = (method, id) {
        let steps = StepId::of_method(method);
        data["index"] = json!(steps.iter().position(|s| *s == id));
        data["of"] = json!(steps.len());
    }
    data
}

/// What one landing stores: files, its part of the summary and its event.
pub(super) struct Landing {
    /// Its part of the summary.
    part: Part,
    files: Vec<ResultFile>,
    /// The SSE event's kind and data.
    event: (&'static str, Value),
}

impl Landing {
    /// The model scene and a `model` event with the model's size.
    fn model(state: &State) -> Landing {
        let files = results::model_files(state);
        let model = results::model_line(state);
        let event = json!({
            "triangles": model.map(|m| m.triangles),
            "bbox_mm": model.map(|m| m.bbox_mm),
            "scene": !files.is_empty(),
        });
        Landing {
            part: Part::Model(model, results::step_lines(state)),
            files,
            event: ("model", event),
        }
    }

    /// A method's files and its `method` event.
    fn method(m: &MethodResult) -> Landing {
        Landing {
            part: Part::Method(m.method, results::method_line(m)),
            files: results::method_files(m),
            event: ("method", json!(results::method_event(m))),
        }
    }
}

/// A landing's part of the summary.
pub(super) enum Part {
    /// The model as read and the shared steps.
    Model(Option<ModelLine>, Vec<StepLine>),
    /// A method and its line.
    Method(MethodKind, MethodLine),
}

/// The summary of a running job: the model and shared steps once read, the methods landed
/// so far in the order asked for, and no best yet (chosen at the end, as before).
#[derive(Debug, Clone, Default)]
pub(super) struct Partial {
    model: Option<ModelLine>,
    steps: Vec<StepLine>,
    methods: Vec<(MethodKind, MethodLine)>,
    /// What is stored, so the end stores only the rest.
    pub(super) landed: Landed,
}

impl Partial {
    /// This summary with `landing` in it.
    fn with(&self, landing: &Landing, order: &[MethodKind]) -> Partial {
        let mut next = self.clone();
        match &landing.part {
            Part::Model(model, steps) => {
                next.model = *model;
                next.steps.clone_from(steps);
                next.landed.model = !landing.files.is_empty();
            }
            Part::Method(method, line) => {
                let method = *method;
                next.methods.retain(|(m, _)| *m != method);
                next.methods.push((method, line.clone()));
                next.methods.sort_by_key(|(m, _)| order.iter().position(|o| o == m));
                next.landed.methods.push(method);
            }
        }
        next
    }

    /// The summary as the conversion JSON reads it.
    pub(super) fn summary(&self) -> Summary {
        Summary {
            model: self.model,
            steps: self.steps.clone(),
            methods: self.methods.iter().map(|(_, line)| line.clone()).collect(),
            best: None,
            seconds: None,
        }
    }
}

/// Locks a partial summary (a panic elsewhere leaves it usable: it is only data).
pub(super) fn lock(partial: &Mutex<Partial>) -> MutexGuard<'_, Partial> {
    partial.lock().unwrap_or_else(PoisonError::into_inner)
}

/// Stores one attempt's notes in order while it holds the job.
pub(super) struct Writer {
    pub(super) db: Db,
    pub(super) hold: Hold,
    /// The methods asked for, in order (the summary lists them so).
    pub(super) order: Vec<MethodKind>,
    /// What landed so far; the job reads it when the writer is gone.
    pub(super) partial: Arc<Mutex<Partial>>,
    /// Set when the job is no longer this attempt's: the conversion stops.
    pub(super) lost: Cancel,
}

impl Writer {
    /// Writes notes until `None` (the conversion returned) or the channel closes. Once a write
    /// finds the job gone it reads on without writing, so the conversion's thread never waits.
    pub(super) async fn run(self, mut rx: UnboundedReceiver<Option<Note>>) -> Result<(), DbError> {
        let mut held = true;
        while let Some(Some(note)) = rx.recv().await {
            if !held {
                continue;
            }
            held = match note {
                Note::Step(data) => {
                    let hold = &self.hold;
                    self.db.append_progress(&hold.id, &hold.worker, "step", &data).await?
                }
                Note::Landing(made) => self.land(made).await?,
            };
            if !held {
                // Cancelled, deleted, requeued or given to another worker: stop converting.
                self.lost.cancel();
            }
        }
        Ok(())
    }

    /// Stores one landing with the summary that includes it; whether the job is still held.
    async fn land(&self, made: JoinHandle<Landing>) -> Result<bool, DbError> {
        let landing = match made.await {
            Ok(landing) => landing,
            Err(e) => {
                tracing::warn!(job = %self.hold.id, "results could not be made as they came ({e}); the end stores them");
                return Ok(true);
            }
        };
        let next = lock(&self.partial).with(&landing, &self.order);
        // Library messages name settings in backticks; the page shows them by their labels.
        let summary = crate::settings::labelled(&next.summary().to_json());
        let (kind, data) = (landing.event.0, crate::settings::labelled(&landing.event.1.to_string()));
        let held = self
            .db
            .land(&self.hold, &summary, &landing.files, (kind, &data))
            .await?;
        if held {
            *lock(&self.partial) = next;
        }
        Ok(held)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn step_events_carry_their_words_and_their_place_in_the_method() {
        let data = step_json(Some(MethodKind::Plate), StepEvent::Started("joints"));
        assert_eq!(data["label"], StepId::Joints.label());
        let steps = StepId::of_method(MethodKind::Plate);
        let place = steps.iter().position(|s| *s == StepId::Joints);
        assert_eq!(data["index"], json!(place));
        assert_eq!(data["of"], json!(steps.len()));
        let shared = step_json(None, StepEvent::Started("read"));
        assert_eq!(shared["label"], StepId::Read.label());
        assert!(shared.get("index").is_none(), "{shared}");
    }

    #[test]
    fn the_partial_summary_lists_landed_methods_in_the_order_asked() {
        let order = [MethodKind::Plate, MethodKind::Stacked, MethodKind::Classifier];
        let line = |m: MethodKind| MethodLine {
            method: m.name().to_string(),
            status: "done".into(),
            score: None,
            parts: None,
            sheets: None,
            glue: None,
            verified: None,
            seconds: 0.0,
            warnings: Some(Vec::new()),
            error: None,
        };
        let landing = |m: MethodKind| Landing {
            part: Part::Method(m, line(m)),
            files: Vec::new(),
            event: ("method", json!({})),
        };
        let partial = Partial::default()
            .with(&landing(MethodKind::Stacked), &order)
            .with(&landing(MethodKind::Plate), &order);
        let summary = partial.summary();
        let names: Vec<&str> = summary.methods.iter().map(|m| m.method.as_str()).collect();
        assert_eq!(names, ["plate", "stacked"]);
        assert_eq!(summary.best, None, "the best is chosen at the end");
        assert_eq!(partial.landed.methods, [MethodKind::Stacked, MethodKind::Plate]);
        assert!(!partial.landed.model);
    }
}
