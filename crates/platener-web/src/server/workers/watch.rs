//! When the server kills one of its workers as stuck: a rule on what the database says the
//! worker holds, kept apart from the processes so it can be tested without them.
//!
//! A worker's own bounds (the library's time limit, its overrun and cancel graces) end every
//! conversion whose worker still runs its event loop. These rules catch the worker that does
//! not: one whose whole process stopped (no heartbeat), or one that holds a job far past the
//! time limit anyway.

use std::time::Duration;

use tokio::time::Instant;

use crate::db::Held;

/// How often a slot looks at what its worker holds.
pub const WATCH_PERIOD: Duration = Duration::from_millis(500);

/// The least a worker may run past the time limit on one job before the server kills it: the
/// worker gives a conversion up 10 s past the limit (`worker::job::OVERRUN_GRACE`), then
/// renders and stores what it has, which can take a while for a large plan.
pub const OVERTIME_GRACE_MIN: Duration = Duration::from_secs(30);

/// Why the server killed a worker.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Stuck {
    /// It held one job past the time limit plus the grace.
    Overtime {
        /// The time limit, seconds.
        timeout_s: f64,
    },
    /// It held a job without a heartbeat for half its lease (two heartbeats missed).
    Silent {
        /// Milliseconds since its last heartbeat.
        quiet_ms: i64,
    },
}

/// The bounds a slot holds its worker to.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Limits {
    /// The time limit per model; `None`: none, and no overtime rule.
    pub timeout: Option<Duration>,
    /// The workers' lease, ms (they heartbeat every quarter of it).
    pub lease_ms: i64,
}

impl Limits {
    /// How long one job may be held before the worker is killed: the time limit plus the
    /// larger of itself and [`OVERTIME_GRACE_MIN`].
    pub fn overtime(&self) -> Option<Duration> {
        self.timeout.map(|t| t + t.max(OVERTIME_GRACE_MIN))
    }
}

/// What a slot remembers between looks: the job (and attempt) its worker holds and since when.
#[derive(Debug, Default)]
pub struct Watch {
    job: Option<(String, i64, Instant)>,
}

impl Watch {
    /// Takes one look (`held` now, at `now` and `now_ms`); `Some` when the worker is stuck.
    pub fn look(&mut self, held: Option<&Held>, now: Instant, now_ms: i64, limits: &Limits) -> Option<Stuck> {
        let Some(held) = held else {
            self.job = None;
            return None;
        };
        let same = self
            .job
            .as_ref()
            .is_some_and(|(id, attempts, _)| *id == held.id && *attempts == held.attempts);
        if !same {
            self.job = Some((held.id.clone(), held.attempts, now));
        }
        if let Some(lease_until) = held.lease_until
            && lease_until - now_ms < limits.lease_ms / 2
        {
            return Some(Stuck::Silent {
                quiet_ms: now_ms - (lease_until - limits.lease_ms),
            });
        }
        let since = self.job.as_ref().map_or(now, |(_, _, since)| *since);
        match (limits.overtime(), limits.timeout) {
            (Some(over), Some(t)) if now.duration_since(since) > over => Some(Stuck::Overtime {
                timeout_s: t.as_secs_f64(),
            }),
            _ => None,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const LIMITS: Limits = Limits {
        timeout: Some(Duration::from_secs(60)),
        lease_ms: 30_000,
    };

    fn held(id: &str, attempts: i64, lease_until: i64) -> Held {
        Held {
            id: id.into(),
            attempts,
            lease_until: Some(lease_until),
        }
    }

    #[test]
    fn a_worker_without_heartbeats_for_half_its_lease_is_silent() {
        let (mut w, t0) = (Watch::default(), Instant::now());
        // Claimed at 0 (lease until 30 s): fine at 14 s, silent at 16 s.
        assert_eq!(w.look(Some(&held("a", 1, 30_000)), t0, 14_000, &LIMITS), None);
        let stuck = w.look(Some(&held("a", 1, 30_000)), t0, 16_000, &LIMITS);
        assert_eq!(stuck, Some(Stuck::Silent { quiet_ms: 16_000 }));
        // A heartbeat at 10 s renews it.
        assert_eq!(w.look(Some(&held("a", 1, 40_000)), t0, 16_000, &LIMITS), None);
    }

    #[test]
    fn one_job_held_past_the_limit_and_grace_is_overtime() {
        let (mut w, t0) = (Watch::default(), Instant::now());
        let at = |s: u64| t0 + Duration::from_secs(s);
        // Heartbeats keep coming: only the time on one job counts. 60 s + 60 s grace.
        assert_eq!(w.look(Some(&held("a", 1, 1 << 40)), at(0), 0, &LIMITS), None);
        assert_eq!(w.look(Some(&held("a", 1, 1 << 40)), at(119), 0, &LIMITS), None);
        assert_eq!(
            w.look(Some(&held("a", 1, 1 << 40)), at(121), 0, &LIMITS),
            Some(Stuck::Overtime { timeout_s: 60.0 })
        );
        // Another job, or the same one's next attempt, starts the clock again.
        assert_eq!(w.look(Some(&held("a", 2, 1 << 40)), at(122), 0, &LIMITS), None);
        assert_eq!(w.look(Some(&held("b", 1, 1 << 40)), at(300), 0, &LIMITS), None);
        assert_eq!(w.look(None, at(301), 0, &LIMITS), None);
        // No time limit, no overtime.
        let none = Limits {
            timeout: None,
            ..LIMITS
        };
        assert_eq!(w.look(Some(&held("b", 1, 1 << 40)), at(10_000), 0, &none), None);
    }

    #[test]
    fn short_limits_still_get_the_minimum_grace() {
        let limits = Limits {
            timeout: Some(Duration::from_secs(2)),
            lease_ms: 6_000,
        };
        assert_eq!(limits.overtime(), Some(Duration::from_secs(32)));
    }
}
