//! The worker processes `serve` starts: `platener worker` children, watched, killed when
//! stuck, and replaced when they end.
//!
//! Each slot runs one child at a time under a name of its own (passed with `--name`), so
//! when a child ends the server ends that worker's jobs at once, with the reason it saw
//! ([`death`]: crashed, out of memory, killed as stuck) instead of waiting for the lease to
//! run out: the job goes back to the queue (or fails after its second attempt) within a
//! second. While a child runs, its slot looks at the job it holds every half second
//! ([`watch`]) and kills a worker that stopped heartbeating or holds one job far past the
//! time limit (issue 29: no model can stall the service). A child's standard input is its
//! lifeline: when the server closes it (shutdown) or dies (even by `kill -9`), the worker
//! finishes its job and exits.

mod death;
mod roster;
mod stderr;
mod watch;

use std::process::{ExitStatus, Stdio};
use std::sync::Arc;
use std::time::Duration;

use tokio::process::{Child, Command};
use tokio::sync::watch as channel;
use tokio::task::JoinHandle;

pub use roster::{Census, Roster};

use self::death::Death;
use self::watch::{Limits, Stuck, WATCH_PERIOD, Watch};
use super::App;
use crate::db::now_ms;
use crate::worker::MAX_ATTEMPTS;

/// The first pause before restarting a crashed worker; it doubles while workers keep crashing
/// within [`STEADY`] of their start, up to [`MAX_PAUSE`].
const FIRST_PAUSE: Duration = Duration::from_millis(200);
const MAX_PAUSE: Duration = Duration::from_secs(10);
const STEADY: Duration = Duration::from_secs(10);

/// The running slots.
#[derive(Debug)]
pub struct Pool {
    drain: channel::Sender<Phase>,
    slots: Vec<JoinHandle<()>>,
}

/// What the slots should do.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Phase {
    Run,
    /// Close the lifelines: finish the job at hand, take no other.
    Drain,
    /// Kill the children now.
    Kill,
}

/// Starts `app.config.workers` slots.
pub fn start(app: Arc<App>, _stopping: channel::Receiver<bool>) -> Pool {
    let (drain, phase) = channel::channel(Phase::Run);
    let server = std::process::id();
    let slots = (0..app.config.workers)
        .map(|k| tokio::spawn(slot(app.clone(), k, format!("serve-{server}-{k}"), phase.clone())))
        .collect();
    Pool { drain, slots }
}

impl Pool {
    /// Lets running jobs finish within `grace`, then kills the rest and re-queues their jobs.
    pub async fn drain(self, grace: Duration) {
        let _ = self.drain.send(Phase::Drain);
        let all = futures_util::future::join_all(self.slots);
        let mut all = std::pin::pin!(all);
        if tokio::time::timeout(grace, &mut all).await.is_err() {
            let _ = self.drain.send(Phase::Kill);
            let _ = all.await;
        }
    }
}

/// The workers' lease in whole seconds (at least 1), as `worker --lease` takes it: the
/// watch holds them to the same value they were given.
fn lease_s(config: &super::ServeConfig) -> u64 {
    config.worker_lease.as_secs().max(1)
}

fn spawn_worker(app: &App, name: &str) -> std::io::Result<Child> {
    let c = &app.config;
    let mut cmd = Command::new(&c.worker_exe);
    cmd.arg("worker")
        .arg("--database")
        .arg(c.database_url())
        .arg("--name")
        .arg(name)
        .arg("--memory-mb")
        .arg(c.worker_memory_mb.to_string())
        .arg("--timeout")
        .arg(c.timeout.to_string())
        .arg("--lease")
        .arg(lease_s(c).to_string())
        .arg("--lifeline")
        .stdin(Stdio::piped())
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .kill_on_drop(true)
        // Few malloc arenas: each reserves 64 MB of address space, which the memory limit counts.
        .env("MALLOC_ARENA_MAX", "2");
    if c.test_hooks {
        cmd.env("PLATENER_TEST_HOOKS", "1");
    } else {
        cmd.env_remove("PLATENER_TEST_HOOKS");
    }
    cmd.spawn()
}

/// How a child's supervision ended.
struct End {
    status: Option<ExitStatus>,
    /// Why the server killed it, if it did because it was stuck.
    killed: Option<Stuck>,
}

/// One slot: runs a worker, and when it ends, ends its jobs with the reason and starts
/// another: at once when the worker left on purpose or was killed as stuck, after a pause that
/// grows while children keep crashing at once otherwise.
async fn slot(app: Arc<App>, k: usize, name: String, mut phase: channel::Receiver<Phase>) {
    let mut generation = 0u32;
    let mut pause = FIRST_PAUSE;
    loop {
        if *phase.borrow() != Phase::Run {
            return;
        }
        let worker = format!("{name}-{generation}");
        generation += 1;
        let mut child = match spawn_worker(&app, &worker) {
            Ok(c) => c,
            Err(e) => {
                tracing::error!("cannot start a worker ({}): {e}", app.config.worker_exe.display());
                tokio::time::sleep(Duration::from_secs(5)).await;
                continue;
            }
        };
        app.roster.set(k, Some(false));
        let log = child.stderr.take().map(|e| tokio::spawn(stderr::forward(e)));
        let started = tokio::time::Instant::now();
        let end = supervise(&app, k, &worker, &mut child, &mut phase).await;
        app.roster.set(k, None);
        // The pipe ends when the process does; the bound only guards against a lost descendant.
        let out_of_memory = match log {
            Some(log) => matches!(tokio::time::timeout(Duration::from_secs(2), log).await, Ok(Ok(true))),
            None => false,
        };
        if *phase.borrow() != Phase::Run {
            if let Err(e) = app.db.requeue_worker(&worker).await {
                tracing::error!(worker = %worker, "cannot release its jobs: {e}");
            }
            return;
        }
        let death = Death::of(end.status, end.killed, out_of_memory);
        // A worker that held a job died of its model, not of a broken setup: replace it now.
        if release(&app, &worker, &death).await || death.replace_at_once() {
            pause = FIRST_PAUSE;
            continue;
        }
        pause = if started.elapsed() > STEADY {
            FIRST_PAUSE
        } else {
            (pause * 2).min(MAX_PAUSE)
        };
        tokio::time::sleep(pause).await;
    }
}

/// Ends the jobs a gone worker held, with the reason; whether it held any.
async fn release(app: &App, worker: &str, death: &Death) -> bool {
    if *death != Death::Exited {
        tracing::warn!(worker = %worker, "worker ended ({death:?}); replacing it");
    }
    let ending = death.ending(MAX_ATTEMPTS, app.config.worker_memory_mb);
    let released = app.db.release_worker(worker, &ending, MAX_ATTEMPTS).await;
    let reaped = app.db.reap(MAX_ATTEMPTS).await;
    match (released, reaped) {
        (Ok((requeued, failed)), Ok(_)) => !(requeued.is_empty() && failed.is_empty()),
        (Err(e), _) | (_, Err(e)) => {
            tracing::error!(worker = %worker, "cannot release its jobs: {e}");
            false
        }
    }
}

/// Waits for the child to exit, looking at what it holds every [`WATCH_PERIOD`] and killing
/// it when it is stuck; on `Drain` closes its lifeline, on `Kill` kills it.
async fn supervise(app: &App, k: usize, worker: &str, child: &mut Child, phase: &mut channel::Receiver<Phase>) -> End {
    // Held here: `Child::wait` closes a stdin it still holds.
    let mut lifeline = child.stdin.take();
    let limits = Limits {
        timeout: (app.config.timeout > 0.0).then(|| Duration::from_secs_f64(app.config.timeout)),
        lease_ms: i64::try_from(lease_s(&app.config).saturating_mul(1000)).unwrap_or(i64::MAX),
    };
    let mut watch = Watch::default();
    let mut tick = tokio::time::interval(WATCH_PERIOD);
    loop {
        tokio::select! {
            status = child.wait() => return End { status: status.ok(), killed: None },
            changed = phase.changed() => {
                let now = if changed.is_ok() { *phase.borrow() } else { Phase::Kill };
                match now {
                    Phase::Run => {}
                    Phase::Drain => drop(lifeline.take()),
                    Phase::Kill => return kill(child, None).await,
                }
            }
            _ = tick.tick() => {
                let held = match app.db.held_by(worker).await {
                    Ok(held) => held,
                    Err(e) => {
                        tracing::warn!(worker = %worker, "cannot look at its job: {e}");
                        continue;
                    }
                };
                app.roster.set(k, Some(held.is_some()));
                let now = tokio::time::Instant::now();
                if let Some(stuck) = watch.look(held.as_ref(), now, now_ms(), &limits) {
                    tracing::warn!(worker = %worker, "killing a stuck worker: {stuck:?}");
                    return kill(child, Some(stuck)).await;
                }
            }
        }
    }
}

/// Kills the child and waits for it.
async fn kill(child: &mut Child, stuck: Option<Stuck>) -> End {
    let _ = child.start_kill();
    End {
        status: child.wait().await.ok(),
        killed: stuck,
    }
}
