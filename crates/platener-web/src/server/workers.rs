//! The worker processes `serve` starts: `platener worker` children, restarted when they die.
//!
//! Each slot runs one child at a time under a name of its own (passed with `--name`), so
//! when a child dies the server ends that worker's leases at once instead of waiting for them
//! to run out: the job goes back to the queue (or fails after its second attempt) within a
//! second. A child's standard input is its lifeline: when the server closes it (shutdown) or
//! dies (even by `kill -9`), the worker finishes its job and exits.

use std::process::Stdio;
use std::sync::Arc;
use std::sync::atomic::Ordering;
use std::time::Duration;

use tokio::process::{Child, Command};
use tokio::sync::watch;
use tokio::task::JoinHandle;

use super::App;
use crate::worker::MAX_ATTEMPTS;

/// The running slots.
#[derive(Debug)]
pub struct Pool {
    drain: watch::Sender<Phase>,
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
pub fn start(app: Arc<App>, _stopping: watch::Receiver<bool>) -> Pool {
    let (drain, phase) = watch::channel(Phase::Run);
    let server = std::process::id();
    let slots = (0..app.config.workers)
        .map(|k| tokio::spawn(slot(app.clone(), format!("serve-{server}-{k}"), phase.clone())))
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
        .arg("--lifeline")
        .stdin(Stdio::piped())
        .stdout(Stdio::null())
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

/// One slot: runs a worker, and when it exits, ends its leases and starts another (after a
/// pause that grows while children keep dying at once).
async fn slot(app: Arc<App>, name: String, mut phase: watch::Receiver<Phase>) {
    let mut generation = 0u32;
    let mut pause = Duration::from_millis(200);
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
        app.live_workers.fetch_add(1, Ordering::SeqCst);
        let started = tokio::time::Instant::now();
        let status = supervise(&mut child, &mut phase).await;
        app.live_workers.fetch_sub(1, Ordering::SeqCst);
        let stopping = *phase.borrow() != Phase::Run;
        let ended = if stopping {
            app.db.requeue_worker(&worker).await.map(|_| ())
        } else {
            tracing::warn!(worker = %worker, "worker exited ({status}); restarting it");
            match app.db.expire_worker(&worker).await {
                Ok(()) => app.db.reap(MAX_ATTEMPTS).await.map(|_| ()),
                Err(e) => Err(e),
            }
        };
        if let Err(e) = ended {
            tracing::error!(worker = %worker, "cannot release its jobs: {e}");
        }
        if stopping {
            return;
        }
        pause = if started.elapsed() > Duration::from_secs(10) {
            Duration::from_millis(200)
        } else {
            (pause * 2).min(Duration::from_secs(10))
        };
        tokio::time::sleep(pause).await;
    }
}

/// Waits for the child to exit; on `Drain` closes its lifeline, on `Kill` kills it.
async fn supervise(child: &mut Child, phase: &mut watch::Receiver<Phase>) -> String {
    // Held here: `Child::wait` closes a stdin it still holds.
    let mut lifeline = child.stdin.take();
    loop {
        tokio::select! {
            status = child.wait() => {
                return status.map_or_else(|e| e.to_string(), |s| s.to_string());
            }
            changed = phase.changed() => {
                let now = if changed.is_ok() { *phase.borrow() } else { Phase::Kill };
                match now {
                    Phase::Run => {}
                    Phase::Drain => drop(lifeline.take()),
                    Phase::Kill => {
                        let _ = child.start_kill();
                        let status = child.wait().await;
                        return status.map_or_else(|e| e.to_string(), |s| s.to_string());
                    }
                }
            }
        }
    }
}
