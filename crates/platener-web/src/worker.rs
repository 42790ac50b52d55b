//! `platener worker`: a process that takes jobs from the database, converts them with
//! [`convert_all`] and stores the results.
//!
//! A worker is a process of its own so that a model that crashes, loops or eats memory kills
//! only it: its lease runs out (or the server that started it notices at once), and the job
//! is retried once, then failed with a reason ([`Db::reap`]). It keeps its lease alive with
//! heartbeats while it converts, writes progress events as they happen and the results in one
//! transaction at the end.

use std::sync::Arc;
use std::time::Duration;

use platener::convert::{Event, Request, convert_all};
use platener::pipeline::StepEvent;
use platener::{Cancel, Source};
use serde_json::json;
use tokio::sync::mpsc;

use crate::db::{Claimed, Db, DbError, Finished};
use crate::results;
use crate::settings::JobSettings;

/// A job is failed after this many attempts whose worker died.
pub const MAX_ATTEMPTS: i64 = 2;

/// How a worker runs.
#[derive(Debug, Clone)]
pub struct WorkerConfig {
    /// The database URL.
    pub database: String,
    /// Address-space limit in MB (RLIMIT_AS); 0: none.
    pub memory_mb: u64,
    /// Time limit per model (all methods together); `None`: none.
    pub timeout: Option<Duration>,
    /// How long a claim lasts without a heartbeat, ms.
    pub lease_ms: i64,
    /// How long to wait when the queue is empty, ms.
    pub poll_ms: u64,
    /// The name in the jobs' `worker` column; `None`: host, process id and a random suffix.
    pub name: Option<String>,
    /// Standard input is a lifeline (workers started by `serve`): when it closes, finish the
    /// job at hand and exit, so a stopped or killed server leaves no worker behind.
    pub lifeline: bool,
    /// Honour the test-only model names (`platener-test-abort…`, `platener-test-slow…`): never
    /// set in production; `serve` sets it only under `PLATENER_TEST_HOOKS=1`.
    pub test_hooks: bool,
}

impl WorkerConfig {
    /// The defaults for a database: 2 GB, 60 s, 30 s leases, 200 ms polls.
    pub fn new(database: impl Into<String>) -> Self {
        Self {
            database: database.into(),
            memory_mb: 2048,
            timeout: Some(Duration::from_secs(60)),
            lease_ms: 30_000,
            poll_ms: 200,
            name: None,
            lifeline: false,
            test_hooks: false,
        }
    }
}

/// Why a worker stopped.
#[derive(Debug, thiserror::Error)]
pub enum WorkerError {
    /// The database failed.
    #[error(transparent)]
    Db(#[from] DbError),
    /// The runtime or the memory limit could not be set up.
    #[error("worker setup: {0}")]
    Setup(#[from] std::io::Error),
}

/// Runs a worker until its lifeline closes, a model ran past its time
/// limit (its thread cannot be stopped, so the process ends and is restarted fresh) or the
/// database fails.
pub fn run(config: &WorkerConfig) -> Result<(), WorkerError> {
    let _hook = platener::convert::PanicHook::install();
    if config.memory_mb > 0 {
        let bytes = config.memory_mb.saturating_mul(1 << 20);
        rlimit::setrlimit(rlimit::Resource::AS, bytes, bytes)?;
    }
    let runtime = tokio::runtime::Builder::new_current_thread().enable_all().build()?;
    runtime.block_on(work(config))
}

/// This worker's name in the `worker` column: host, process id and a random suffix.
fn worker_name() -> String {
    let host = std::fs::read_to_string("/proc/sys/kernel/hostname").unwrap_or_default();
    let suffix = &crate::ids::token()[..8];
    format!("{}-{}-{suffix}", host.trim(), std::process::id())
}

async fn work(config: &WorkerConfig) -> Result<(), WorkerError> {
    let db = Db::connect(&config.database, 2).await?;
    let me = config.name.clone().unwrap_or_else(worker_name);
    let cut = Cancel::default();
    if config.lifeline {
        tokio::spawn(watch_lifeline(cut.clone()));
    }
    let mut last_reap = tokio::time::Instant::now() - Duration::from_secs(60);
    tracing::info!(worker = %me, "worker started");
    loop {
        if cut.is_cancelled() {
            return Ok(());
        }
        if last_reap.elapsed() > Duration::from_secs(2) {
            db.reap(MAX_ATTEMPTS).await?;
            last_reap = tokio::time::Instant::now();
        }
        match db.claim(&me, config.lease_ms).await? {
            Some(job) => {
                if !convert_job(&db, &me, job, config).await? {
                    return Ok(());
                }
            }
            None => tokio::time::sleep(Duration::from_millis(config.poll_ms)).await,
        }
    }
}

/// Sets `cut` when standard input reaches its end (or fails).
async fn watch_lifeline(cut: Cancel) {
    use tokio::io::AsyncReadExt as _;
    let mut stdin = tokio::io::stdin();
    let mut buf = [0u8; 64];
    while matches!(stdin.read(&mut buf).await, Ok(n) if n > 0) {}
    cut.cancel();
}

/// Converts one claimed job and records it; `false` when the worker must exit afterwards (a
/// method ran past the time limit and its thread may still run).
async fn convert_job(db: &Db, me: &str, job: Claimed, config: &WorkerConfig) -> Result<bool, WorkerError> {
    tracing::info!(job = %job.id, attempt = job.attempts, "converting");
    let cancel = Cancel::default();
    let heartbeat = tokio::spawn(heartbeat(
        db.clone(),
        job.id.clone(),
        me.to_string(),
        config.lease_ms,
        cancel.clone(),
    ));
    let outcome = match parse_settings(&job) {
        Ok((request, debug)) => {
            let (request, restart) = (request_with_limits(request, config), config.timeout.is_some());
            let all = run_observed(db, me, &job, request, &cancel, config.test_hooks).await?;
            let timed_out = all
                .methods
                .iter()
                .any(|m| m.status == platener::convert::Status::TimedOut);
            let finished = tokio::task::spawn_blocking(move || results::finished(&all, debug))
                .await
                .map_err(|e| std::io::Error::other(e.to_string()))?;
            (finished, restart && timed_out)
        }
        Err(message) => (bad_settings(&message), false),
    };
    heartbeat.abort();
    let stored = db.finish(&job.id, me, &outcome.0).await?;
    if !stored {
        tracing::warn!(job = %job.id, "the job was cancelled, deleted or taken from this worker; its results are dropped");
    }
    Ok(!outcome.1)
}

fn request_with_limits(mut request: Request, config: &WorkerConfig) -> Request {
    request.timeout = config.timeout;
    request
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

fn bad_settings(message: &str) -> Finished {
    let error = json!({"code": "bad_request", "message": format!("the stored settings are invalid: {message}")});
    Finished {
        status: "failed".into(),
        error: Some(error.to_string()),
        summary: json!({"model": null, "steps": [], "methods": [], "best": null}).to_string(),
        files: Vec::new(),
        event: json!({"status": "failed", "error": error}).to_string(),
    }
}

/// Runs `convert_all` on a blocking thread while its events are appended to the database in
/// order; returns when both are done. A progress write that finds the job no longer `me`'s
/// (cancelled, deleted, taken by another worker) cancels the conversion.
async fn run_observed(
    db: &Db,
    me: &str,
    job: &Claimed,
    request: Request,
    cancel: &Cancel,
    test_hooks: bool,
) -> Result<platener::Conversions, WorkerError> {
    let (tx, mut rx) = mpsc::unbounded_channel::<Option<(&'static str, String)>>();
    let sender = tx.clone();
    let progress = Arc::new(move |event: Event<'_>| {
        let _ = sender.send(Some(event_json(event)));
    });
    let appender = {
        let (db, id, me, lost) = (db.clone(), job.id.clone(), me.to_string(), cancel.clone());
        tokio::spawn(async move {
            let mut held = true;
            while let Some(Some((kind, data))) = rx.recv().await {
                if held && !db.append_progress(&id, &me, kind, &data).await? {
                    // Cancelled, deleted or given to another worker: stop converting.
                    held = false;
                    lost.cancel();
                }
            }
            Ok::<(), DbError>(())
        })
    };
    let name = job.name.clone();
    let cancel = cancel.clone();
    let all = tokio::task::spawn_blocking(move || {
        if test_hooks {
            test_hook(&name);
        }
        convert_all(request, &cancel, progress)
    })
    .await
    .map_err(|e| std::io::Error::other(e.to_string()))?;
    // A thread left behind after a time limit keeps its sender; `None` ends the appender.
    let _ = tx.send(None);
    appender.await.map_err(|e| std::io::Error::other(e.to_string()))??;
    Ok(all)
}

/// Test-only behaviours chosen by the model's name, so tests can show what a hostile model
/// does to the service: `platener-test-abort…` aborts the worker process, `platener-test-slow…`
/// waits 3 s before converting (time for a test to kill the worker mid-job).
fn test_hook(name: &str) {
    if name.starts_with("platener-test-abort") {
        std::process::abort();
    }
    if name.starts_with("platener-test-slow") {
        std::thread::sleep(Duration::from_secs(3));
    }
}

/// An SSE event's name and JSON for a library event.
fn event_json(event: Event<'_>) -> (&'static str, String) {
    match event {
        Event::Step { method, event } => {
            let method = method.map(|m| m.name());
            let data = match event {
                StepEvent::Started(step) => json!({"method": method, "step": step, "state": "started"}),
                StepEvent::Finished(record) => json!({
                    "method": method, "step": record.name, "state": "finished",
                    "ms": record.millis, "warnings": record.warnings.len(),
                }),
            };
            ("step", data.to_string())
        }
        Event::Method(m) => {
            let data = json!({
                "method": m.method.name(),
                "status": results::status_name(m.status),
                "score": m.score.as_ref().map(|s| s.total),
                "seconds": m.seconds,
                "error": m.error.as_ref().map(ToString::to_string),
            });
            ("method", data.to_string())
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
