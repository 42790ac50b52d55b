//! Test-only behaviours chosen by the model's name, so tests can show what a hostile model
//! does to the service. Honoured only when the worker's `test_hooks` is set (`serve` sets it
//! under `PLATENER_TEST_HOOKS=1`); otherwise these are ordinary names.

use std::time::Duration;

/// What a `platener-test-…` model does.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
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
}

/// The allocations of [`Hook::Alloc`]: address space only (never written, so no memory is
/// used), 64 MB at a time, at most 1 TB when no limit stops it first.
const ALLOC_BLOCK: usize = 64 << 20;
const ALLOC_BLOCKS: usize = 16_384;

impl Hook {
    /// The hook a model name asks for, if any.
    pub fn of(name: &str) -> Option<Hook> {
        let rest = name.strip_prefix("platener-test-")?;
        [
            ("abort", Hook::Abort),
            ("slow", Hook::Slow),
            ("hang", Hook::Hang),
            ("alloc", Hook::Alloc),
            ("freeze", Hook::Freeze),
        ]
        .into_iter()
        .find(|(prefix, _)| rest.starts_with(prefix))
        .map(|(_, hook)| hook)
    }

    /// Runs on the conversion thread before `convert_all`.
    pub fn before_converting(self) {
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
            Hook::Hang => {}
        }
    }

    /// Runs at every progress event; `step` for a step's event, which comes from the
    /// library's own work thread (a method's may come from the caller's).
    pub fn on_progress(self, step: bool) {
        if self == Hook::Hang && step {
            loop {
                std::thread::sleep(Duration::from_secs(1));
            }
        }
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
        assert_eq!(Hook::of("box.stl"), None);
        assert_eq!(Hook::of("platener-test-other.stl"), None);
    }
}
