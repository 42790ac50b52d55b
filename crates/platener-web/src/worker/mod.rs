//! `platener worker`: a process that takes jobs from the database, converts them with
//! [`platener::convert_all`] and stores the results.
//!
//! A worker is a process of its own so that a model that crashes, loops or eats memory kills
//! only it: its lease runs out (or the server that started it notices at once), and the job
//! is retried once, then failed with a reason ([`Db::reap`]). It keeps its lease alive with
//! heartbeats while it converts, writes progress events as they happen, the model scene and
//! each method's results the moment they exist (`live.rs`), and the rest in one transaction
//! at the end.
//!
//! A conversion that does not end cleanly (a method ran past the time limit, the job was
//! cancelled or its lease lost, or the conversion thread would not stop) may leave a thread
//! running that nothing can stop; the worker then exits with [`Stop::Restart`] and the server
//! starts a fresh one at once (issue 29: such a worker used to hang on exit).

mod hooks;
mod job;
mod live;

use std::io::Read as _;
use std::time::Duration;

use platener::Cancel;

use crate::db::{Db, DbError};

/// A job is failed after this many attempts whose worker died.
pub const MAX_ATTEMPTS: i64 = 2;

/// The exit code of a worker that stopped to be replaced ([`Stop::Restart`]): `serve` starts
/// the next one at once, without the pause it leaves after a crash.
pub const EXIT_RESTART: u8 = 3;

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
    /// Honour the test-only model names (`platener-test-…`, see `hooks.rs`): never set in
    /// production; `serve` sets it only under `PLATENER_TEST_HOOKS=1`.
    pub test_hooks: bool,
}

/// The lease of a claim unless set: 30 s.
pub const DEFAULT_LEASE_MS: i64 = 30_000;

impl WorkerConfig {
    /// The defaults for a database: 2 GB, 60 s, 30 s leases, 200 ms polls.
    pub fn new(database: impl Into<String>) -> Self {
        Self {
            database: database.into(),
            memory_mb: 2048,
            timeout: Some(Duration::from_secs(60)),
            lease_ms: DEFAULT_LEASE_MS,
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

/// How a worker's run ended without an error.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Stop {
    /// The lifeline closed: the server is stopping.
    Lifeline,
    /// A conversion did not end cleanly and may have left a thread running: this process
    /// should end and another take its place (exit code [`EXIT_RESTART`]).
    Restart,
}

/// Runs a worker until its lifeline closes, a conversion does not end cleanly or the
/// database fails.
///
/// Whatever is still running when it returns (a conversion thread past its time limit, the
/// lifeline's read) is left behind: the runtime is shut down without waiting, and the lifeline
/// is read on a plain thread, so returning always lets the process exit.
pub fn run(config: &WorkerConfig) -> Result<Stop, WorkerError> {
    let _hook = platener::convert::PanicHook::install();
    if config.memory_mb > 0 {
        let bytes = config.memory_mb.saturating_mul(1 << 20);
        rlimit::setrlimit(rlimit::Resource::AS, bytes, bytes)?;
    }
    let cut = Cancel::default();
    if config.lifeline {
        watch_lifeline(cut.clone())?;
    }
    let runtime = tokio::runtime::Builder::new_current_thread().enable_all().build()?;
    let stop = runtime.block_on(work(config, &cut));
    runtime.shutdown_background();
    stop
}

/// This worker's name in the `worker` column: host, process id and a random suffix.
fn worker_name() -> String {
    let host = std::fs::read_to_string("/proc/sys/kernel/hostname").unwrap_or_default();
    let suffix = &crate::ids::token()[..8];
    format!("{}-{}-{suffix}", host.trim(), std::process::id())
}

async fn work(config: &WorkerConfig, cut: &Cancel) -> Result<Stop, WorkerError> {
    let db = Db::connect(&config.database, 2).await?;
    let me = config.name.clone().unwrap_or_else(worker_name);
    let mut last_reap = tokio::time::Instant::now() - Duration::from_secs(60);
    tracing::info!(worker = %me, "worker started");
    loop {
        if cut.is_cancelled() {
            return Ok(Stop::Lifeline);
        }
        if last_reap.elapsed() > Duration::from_secs(2) {
            db.reap(MAX_ATTEMPTS).await?;
            last_reap = tokio::time::Instant::now();
        }
        match db.claim(&me, config.lease_ms).await? {
            Some(claimed) => {
                if job::convert(&db, &me, claimed, config).await? == job::Ended::Unclean {
                    tracing::info!(worker = %me, "exiting to be replaced: the last conversion did not end cleanly");
                    return Ok(Stop::Restart);
                }
            }
            None => tokio::time::sleep(Duration::from_millis(config.poll_ms)).await,
        }
    }
}

/// Sets `cut` when standard input reaches its end (or fails). A plain thread, not tokio's
/// `stdin()`: tokio reads it on a blocking thread that a runtime's drop waits for, so a
/// worker that wanted to exit while its server lived hung forever (issue 29, bug 2).
fn watch_lifeline(cut: Cancel) -> std::io::Result<()> {
    std::thread::Builder::new().name("lifeline".into()).spawn(move || {
        let mut stdin = std::io::stdin();
        let mut buf = [0u8; 64];
        while matches!(stdin.read(&mut buf), Ok(n) if n > 0) {}
        cut.cancel();
    })?;
    Ok(())
}
