//! Why a worker process ended, as the server saw it, and what that means for the job it held.

use std::process::ExitStatus;

use super::watch::Stuck;
use crate::db::Ending;
use crate::worker::EXIT_RESTART;

/// Why a worker ended.
#[derive(Debug, Clone, PartialEq)]
pub enum Death {
    /// It exited on its own to be replaced (a conversion left a thread behind), or exited 0.
    Exited,
    /// Its allocator reported memory it could not get (the address-space limit) before it
    /// died.
    OutOfMemory,
    /// It died otherwise: a signal or an error exit; the status as text.
    Crashed(String),
    /// The server killed it.
    Killed(Stuck),
}

impl Death {
    /// The death of a worker that ended with `status` (`None`: its status could not be read),
    /// after the server killed it (`killed`), and whether its standard error reported an
    /// allocation failure.
    pub fn of(status: Option<ExitStatus>, killed: Option<Stuck>, out_of_memory: bool) -> Death {
        if let Some(stuck) = killed {
            return Death::Killed(stuck);
        }
        match status {
            Some(s) if s.success() || s.code() == Some(i32::from(EXIT_RESTART)) => Death::Exited,
            _ if out_of_memory => Death::OutOfMemory,
            Some(s) => Death::Crashed(s.to_string()),
            None => Death::Crashed("its exit status is unknown".into()),
        }
    }

    /// Whether the next worker should start at once: it left on purpose or the server ended
    /// it. A crash waits (a pause that grows), in case the setup is broken rather than a model.
    pub fn replace_at_once(&self) -> bool {
        matches!(self, Death::Exited | Death::Killed(_))
    }

    /// How the jobs it still held end (`memory_mb`: the workers' limit, for the message).
    pub fn ending(&self, max_attempts: i64, memory_mb: u64) -> Ending {
        let after = format!("after {max_attempts} attempts the model was not converted");
        let (code, message, retry) = match self {
            Death::Exited => (
                "worker_died",
                format!("the worker converting this model stopped; {after}"),
                "the worker stopped",
            ),
            Death::OutOfMemory => (
                "out_of_memory",
                format!("converting this model ran out of memory (the limit is {memory_mb} MB per worker); {after}"),
                "the worker ran out of memory",
            ),
            Death::Crashed(status) => (
                "worker_died",
                format!("the worker converting this model crashed ({status}); {after}"),
                "the worker crashed",
            ),
            Death::Killed(Stuck::Silent { quiet_ms }) => (
                "worker_stalled",
                format!(
                    "the worker converting this model stopped answering (no heartbeat for {:.1} s) and was killed; {after}",
                    *quiet_ms as f64 / 1000.0
                ),
                "the worker stopped answering and was killed",
            ),
            Death::Killed(Stuck::Overtime { timeout_s }) => {
                let message = format!(
                    "the conversion ran past the time limit of {timeout_s} s and its worker did not stop; \
                     the server killed it and the model was not converted"
                );
                return Ending {
                    code: "timed_out",
                    message,
                    retry: None,
                };
            }
        };
        Ending {
            code,
            message,
            retry: Some(format!("{retry}; the job is queued again")),
        }
    }
}

#[cfg(test)]
mod tests {
    use std::os::unix::process::ExitStatusExt as _;

    use super::*;

    #[test]
    fn deaths_are_told_apart() {
        let abort = ExitStatus::from_raw(6);
        assert_eq!(Death::of(Some(abort), None, false), Death::Crashed(abort.to_string()));
        assert_eq!(Death::of(Some(abort), None, true), Death::OutOfMemory);
        let restart = ExitStatus::from_raw(i32::from(EXIT_RESTART) << 8);
        assert_eq!(Death::of(Some(restart), None, false), Death::Exited);
        let stuck = Stuck::Silent { quiet_ms: 4000 };
        assert_eq!(Death::of(Some(abort), Some(stuck), true), Death::Killed(stuck));
        assert!(Death::Killed(stuck).replace_at_once() && !Death::OutOfMemory.replace_at_once());
    }

    #[test]
    fn only_overtime_fails_at_once() {
        let over = Death::Killed(Stuck::Overtime { timeout_s: 3.0 }).ending(2, 2048);
        assert_eq!((over.code, over.retry), ("timed_out", None));
        let oom = Death::OutOfMemory.ending(2, 2048);
        assert_eq!(oom.code, "out_of_memory");
        assert!(oom.message.contains("2048 MB") && oom.retry.is_some(), "{oom:?}");
    }
}
