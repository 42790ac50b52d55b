//! One claimed job: its conversion on a thread of its own, watched with bounded waits, its
//! progress events, heartbeats and results (stored as they come by [`super::live`], the rest
//! at the end).

use std::sync::{Arc, Mutex};
use std::time::Duration;

use platener::convert::{Conversions, Event, Request, Status, convert_all};
use platener::{Cancel, Source};
use serde_json::{Value, json};
use tokio::sync::{mpsc, oneshot};

use super::live::{self, Note, Partial, Writer};
use super::{WorkerConfig, WorkerError, hooks};
use crate::db::{Claimed, Db, Finished, Hold};
use crate::results;
use crate::settings::JobSettings;
use crate::summary::Summary;

/// How long past the time limit the worker waits for `convert_all` to return before it gives
/// the thread up: `convert_all` itself returns about 2 s after the limit (its cancel grace),
/// so this only fires when something outside the library's watch hangs.
pub const OVERRUN_GRACE: Duration = Duration::from_secs(10);

/// How long a cancelled conversion (the job was cancelled, deleted or its lease lost) may take
/// to stop before the worker gives its thread up: steps check for cancellation between their
/// loops, so a live conversion stops well within this.
pub const CANCEL_GRACE: Duration = Duration::from_secs(3);

/// How a job's conversion ended for the worker.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Ended {
    /// Every thread it started has ended: the worker may take the next job.
    Clean,
    /// It ran past its time limit, was cancelled or lost, or its thread was given up: a thread
    /// may still run, so the worker exits and is replaced.
    Unclean,
}

/// What waiting for a conversion thread gave.
enum Ran {
    /// `convert_all` returned.
    Returned(Box<Conversions>),
    /// It did not return within the time limit and [`OVERRUN_GRACE`].
    Overran,
    /// The job was cancelled or lost and the thread did not stop within [`CANCEL_GRACE`], or
    /// the thread ended without a result.
    GivenUp,
}

/// Converts one claimed job and records it.
pub async fn convert(db: &Db, me: &str, job: Claimed, config: &WorkerConfig) -> Result<Ended, WorkerError> {
    tracing::info!(job = %job.id, attempt = job.attempts, "converting");
    let hold = Hold {
        id: job.id.clone(),
        worker: me.to_string(),
        attempt: job.attempts,
    };
    let partial = Arc::new(Mutex::new(Partial::default()));
    let cancel = Cancel::default();
    let heartbeat = tokio::spawn(heartbeat(
        db.clone(),
        job.id.clone(),
        me.to_string(),
        config.lease_ms,
        cancel.clone(),
    ));
    let (outcome, ended) = match parse_settings(&job) {
        Ok((mut request, debug)) => {
            request.timeout = config.timeout;
            let observed = Observed {
                hold: &hold,
                name: &job.name,
                partial: &partial,
            };
            match run_observed(db, observed, request, &cancel, config).await? {
                Ran::Returned(all) => {
                    let timed_out = all.methods.iter().any(|m| m.status == Status::TimedOut);
                    let landed = live::lock(&partial).landed.clone();
                    let finished = tokio::task::spawn_blocking(move || results::finished(&all, debug, &landed))
                        .await
                        .map_err(|e| std::io::Error::other(e.to_string()))?;
                    let clean = !timed_out && !cancel.is_cancelled();
                    (Some(finished), if clean { Ended::Clean } else { Ended::Unclean })
                }
                Ran::Overran => {
                    let summary = live::lock(&partial).summary();
                    (Some(overran(config.timeout, summary)), Ended::Unclean)
                }
                Ran::GivenUp => (None, Ended::Unclean),
            }
        }
        Err(message) => (Some(bad_settings(&message)), Ended::Clean),
    };
    heartbeat.abort();
    if let Some(outcome) = outcome
        && !db.finish(&job.id, me, &outcome).await?
    {
        tracing::warn!(job = %job.id, "the job was cancelled, deleted or taken from this worker; the results not landed yet are dropped");
    }
    Ok(ended)
}

/// The library request of a job and whether it stores debug snapshots, or why its stored
/// settings are unusable.
fn parse_settings(job: &Claimed) -> Result<(Request, bool), String> {
    let job_settings: JobSettings = serde_json::from_str(&job.settings).map_err(|e| e.to_string())?;
    let (settings, methods) = job_settings.to_library().map_err(|e| e.to_string())?;
    let source = Source::Bytes {
        name: job.name.clone(),
        bytes: Arc::from(job.model.as_slice()),
    };
    let request = Request {
        methods,
        ..Request::new(source, settings)
    };
    Ok((request, job_settings.debug))
}

/// A job failed with `error` and no results but those its `summary` lists (landed while it
/// ran), as [`Db::finish`] stores it.
fn failed(error: &Value, summary: Summary) -> Finished {
    Finished {
        status: "failed".into(),
        error: Some(error.to_string()),
        summary: summary.to_json(),
        files: Vec::new(),
        event: json!({"status": "failed", "error": error}).to_string(),
    }
}

fn bad_settings(message: &str) -> Finished {
    failed(
        &json!({"code": "bad_request", "message": format!("the stored settings are invalid: {message}")}),
        Partial::default().summary(),
    )
}

/// The failure of a conversion whose thread did not return after its time limit; the
/// methods that landed before stay.
fn overran(timeout: Option<Duration>, summary: Summary) -> Finished {
    let limit = timeout.map_or(0.0, |t| t.as_secs_f64());
    let error = json!({
        "code": "timed_out",
        "message": format!("the conversion ran past the time limit of {limit} s and did not stop; the model was not converted"),
    });
    failed(&error, summary)
}

/// The attempt a conversion is observed for.
struct Observed<'a> {
    hold: &'a Hold,
    /// The model's name (test hooks go by it).
    name: &'a str,
    /// What landed so far ([`Writer::partial`]).
    partial: &'a Arc<Mutex<Partial>>,
}

/// Runs `convert_all` on a thread of its own while its events, the model scene and each
/// method's results are stored in order as they come ([`Writer`]). A write that finds the
/// job no longer this attempt's (cancelled, deleted, taken by another worker) cancels the
/// conversion. Every wait is bounded ([`Ran`]): the thread is given up past the time limit or
/// after a cancel, never waited for forever.
async fn run_observed(
    db: &Db,
    observed: Observed<'_>,
    request: Request,
    cancel: &Cancel,
    config: &WorkerConfig,
) -> Result<Ran, WorkerError> {
    let (tx, rx) = mpsc::unbounded_channel::<Option<Note>>();
    let sender = tx.clone();
    let hook = config.test_hooks.then(|| hooks::Hook::of(observed.name)).flatten();
    let (pool, hook_cancel, progress_hook) = (tokio::runtime::Handle::current(), cancel.clone(), hook.clone());
    let progress = Arc::new(move |event: Event<'_>| {
        if let Some(note) = Note::of(event, &pool) {
            let _ = sender.send(Some(note));
        }
        // After the note: a step a hook holds has been seen to start.
        if let Some(hook) = &progress_hook {
            hook.on_progress(&event, &hook_cancel);
        }
    });
    let writer = Writer {
        db: db.clone(),
        hold: observed.hold.clone(),
        order: request.methods.clone(),
        partial: observed.partial.clone(),
        lost: cancel.clone(),
    };
    let appender = tokio::spawn(writer.run(rx));
    let (done, result) = oneshot::channel();
    let thread_cancel = cancel.clone();
    std::thread::Builder::new()
        .name(format!("job {}", observed.hold.id))
        .spawn(move || {
            if let Some(hook) = hook {
                hook.before_converting();
            }
            let _ = done.send(convert_all(request, &thread_cancel, progress));
        })?;
    let ran = wait_bounded(result, config.timeout.map(|t| t + OVERRUN_GRACE), cancel).await;
    if matches!(ran, Ran::Returned(_)) {
        // A thread left behind after a time limit keeps its sender; `None` ends the appender.
        let _ = tx.send(None);
        appender.await.map_err(|e| std::io::Error::other(e.to_string()))??;
    } else {
        appender.abort();
    }
    Ok(ran)
}

/// Waits for the conversion's result, at most `limit` in all and [`CANCEL_GRACE`] after
/// `cancel` is set.
async fn wait_bounded(mut result: oneshot::Receiver<Conversions>, limit: Option<Duration>, cancel: &Cancel) -> Ran {
    let start = tokio::time::Instant::now();
    let mut cancelled_at = None;
    loop {
        tokio::select! {
            all = &mut result => return all.map_or(Ran::GivenUp, |all| Ran::Returned(Box::new(all))),
            () = tokio::time::sleep(Duration::from_millis(100)) => {}
        }
        if limit.is_some_and(|l| start.elapsed() >= l) {
            return Ran::Overran;
        }
        if cancel.is_cancelled() && cancelled_at.get_or_insert_with(tokio::time::Instant::now).elapsed() >= CANCEL_GRACE
        {
            return Ran::GivenUp;
        }
    }
}

/// Extends the job's lease every quarter lease; cancels the conversion when the lease was
/// lost (the job was cancelled, deleted or given to another worker).
async fn heartbeat(db: Db, id: String, me: String, lease_ms: i64, cancel: Cancel) {
    let period = Duration::from_millis(u64::try_from(lease_ms / 4).unwrap_or(1000).max(100));
    loop {
        tokio::time::sleep(period).await;
        match db.heartbeat(&id, &me, lease_ms).await {
            Ok(true) => {}
            Ok(false) => {
                cancel.cancel();
                return;
            }
            Err(e) => tracing::warn!(job = %id, "heartbeat failed: {e}"),
        }
    }
}
