//! Test-only behaviours chosen by the model's name, so tests can show what a hostile model
//! does to the service. Honoured only when the worker's `test_hooks` is set (`serve` sets it
//! under `PLATENER_TEST_HOOKS=1`); otherwise these are ordinary names.

use std::path::PathBuf;
use std::time::{Duration, Instant};

use platener::Cancel;
use platener::convert::Event;
use platener::pipeline::{StepEvent, StepId};

/// The folder of [`Hook::Hold`]'s gates, from the worker's environment (a test sets it for
/// its server, whose workers inherit it).
pub const GATE_ENV: &str = "PLATENER_TEST_GATE";

/// The longest a held method waits for its gate: a test that never opens it is not hung.
const HOLD_LIMIT: Duration = Duration::from_secs(30);

/// How long a method is held when no gate folder is set.
const HOLD_UNGATED: Duration = Duration::from_secs(3);

/// What a `platener-test-…` model does.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Hook {
    /// `platener-test-abort…`: aborts the worker process (a crash).
    Abort,
    /// `platener-test-slow…`: waits 3 s before converting (time for a test to kill the worker
    /// or cancel the job mid-way).
    Slow,
    /// `platener-test-hang…`: the conversion's first step never returns and ignores
    /// cancellation (a step stuck in a loop): the library's time limit gives up on it and its
    /// thread stays behind.
    Hang,
    /// `platener-test-alloc…`: allocates address space until the memory limit (RLIMIT_AS)
    /// refuses, which aborts the process with the allocator's message.
    Alloc,
    /// `platener-test-freeze…`: stops the whole worker process (SIGSTOP), heartbeats and all,
    /// as a machine thrashing or a deadlock would: only the server can end it.
    Freeze,
    /// `platener-test-hold…`: each method waits as its `sheets` step starts until its gate,
    /// the file `{PLATENER_TEST_GATE}/{model name}.{method}`, exists (at most 30 s, 3 s
    /// without the folder), or the job is cancelled; so a test decides when each method may
    /// end and sees the model, and the methods that ended, while the others still run.
    Hold {
        /// The gates' path without the method (`None`: no gate folder).
        gate: Option<PathBuf>,
    },
}

/// The allocations of [`Hook::Alloc`]: address space only (never written, so no memory is
/// used), 64 MB at a time, at most 1 TB when no limit stops it first.
const ALLOC_BLOCK: usize = 64 << 20;
const ALLOC_BLOCKS: usize = 16_384;

impl Hook {
    /// The hook a model name asks for, if any.
    pub fn of(name: &str) -> Option<Hook> {
        let rest = name.strip_prefix("platener-test-")?;
        let gate = std::env::var_os(GATE_ENV).map(|dir| PathBuf::from(dir).join(name));
        [
            ("abort", Hook::Abort),
            ("slow", Hook::Slow),
            ("hang", Hook::Hang),
            ("alloc", Hook::Alloc),
            ("freeze", Hook::Freeze),
            ("hold", Hook::Hold { gate }),
        ]
        .into_iter()
        .find(|(prefix, _)| rest.starts_with(prefix))
        .map(|(_, hook)| hook)
    }

    /// Runs on the conversion thread before `convert_all`.
    pub fn before_converting(&self) {
        match self {
            Hook::Abort => std::process::abort(),
            Hook::Slow => std::thread::sleep(Duration::from_secs(3)),
            Hook::Alloc => {
                let mut blocks: Vec<Vec<u8>> = Vec::new();
                for _ in 0..ALLOC_BLOCKS {
                    blocks.push(Vec::with_capacity(ALLOC_BLOCK));
                }
                std::hint::black_box(&blocks);
            }
            Hook::Freeze => {
                // No unsafe code in the workspace: `kill` sends the signal.
                let _ = std::process::Command::new("kill")
                    .arg("-STOP")
                    .arg(std::process::id().to_string())
                    .status();
            }
            Hook::Hang | Hook::Hold { .. } => {}
        }
    }

    /// Runs at every progress event, on the thread that sent it: a step's comes from the
    /// library's own work thread (a method's end may come from the caller's). `cancel` is the
    /// job's.
    pub fn on_progress(&self, event: &Event<'_>, cancel: &Cancel) {
        match (self, event) {
            (Hook::Hang, Event::Step { .. }) => loop {
                std::thread::sleep(Duration::from_secs(1));
            },
            (
                Hook::Hold { gate },
                Event::Step {
                    method: Some(method),
                    event: StepEvent::Started(step),
                },
            ) if *step == StepId::Sheets.name() => {
                let gate = gate.as_ref().map(|g| {
                    let mut path = g.clone().into_os_string();
                    path.push(format!(".{}", method.name()));
                    PathBuf::from(path)
                });
                hold(gate, cancel);
            }
            _ => {}
        }
    }
}

/// Waits until `gate` exists or `cancel` is set, bounded ([`HOLD_LIMIT`], or
/// [`HOLD_UNGATED`] without a gate).
fn hold(gate: Option<PathBuf>, cancel: &Cancel) {
    let start = Instant::now();
    let limit = if gate.is_some() { HOLD_LIMIT } else { HOLD_UNGATED };
    while !gate.as_ref().is_some_and(|g| g.exists()) && !cancel.is_cancelled() && start.elapsed() < limit {
        std::thread::sleep(Duration::from_millis(20));
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_choose_hooks() {
        assert_eq!(Hook::of("platener-test-hang-3.stl"), Some(Hook::Hang));
        assert_eq!(Hook::of("platener-test-alloc.stl"), Some(Hook::Alloc));
        assert_eq!(Hook::of("platener-test-slowly.stl"), Some(Hook::Slow));
        assert!(matches!(Hook::of("platener-test-hold-a.stl"), Some(Hook::Hold { .. })));
        assert_eq!(Hook::of("box.stl"), None);
        assert_eq!(Hook::of("platener-test-other.stl"), None);
    }
}
