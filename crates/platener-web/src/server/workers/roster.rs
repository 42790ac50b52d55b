//! What each slot's worker is doing, for `/api/health` and `/metrics`: alive or not, busy
//! with a job or idle, and since when idle.

use std::sync::Mutex;
use std::time::Duration;

use tokio::time::Instant;

/// The slots' workers as their supervisors last saw them.
#[derive(Debug, Default)]
pub struct Roster {
    slots: Mutex<Vec<SlotView>>,
}

#[derive(Debug, Clone, Copy, Default)]
struct SlotView {
    live: bool,
    busy: bool,
    idle_since: Option<Instant>,
}

/// The roster summed up.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Census {
    /// Worker processes alive now.
    pub live: usize,
    /// Of those, how many held a job at their supervisor's last look.
    pub busy: usize,
    /// The longest a live worker has been seen idle without a break.
    pub longest_idle: Option<Duration>,
}

impl Roster {
    /// Slot `k`'s worker: `None` when none is running, else whether it holds a job.
    pub fn set(&self, k: usize, holding: Option<bool>) {
        let mut slots = self.slots.lock().unwrap_or_else(std::sync::PoisonError::into_inner);
        if slots.len() <= k {
            slots.resize(k + 1, SlotView::default());
        }
        let view = &mut slots[k];
        let idle = holding == Some(false);
        *view = SlotView {
            live: holding.is_some(),
            busy: holding == Some(true),
            idle_since: if idle {
                view.idle_since.or_else(|| Some(Instant::now()))
            } else {
                None
            },
        };
    }

    /// The live, busy and idle workers now.
    pub fn census(&self) -> Census {
        let slots = self.slots.lock().unwrap_or_else(std::sync::PoisonError::into_inner);
        Census {
            live: slots.iter().filter(|s| s.live).count(),
            busy: slots.iter().filter(|s| s.busy).count(),
            longest_idle: slots.iter().filter_map(|s| s.idle_since).min().map(|t| t.elapsed()),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn idle_time_runs_while_idle_and_stops_when_busy_or_gone() {
        let r = Roster::default();
        r.set(1, Some(false));
        r.set(0, Some(true));
        let c = r.census();
        assert_eq!((c.live, c.busy, c.longest_idle.is_some()), (2, 1, true));
        r.set(1, None);
        assert_eq!(r.census().longest_idle, None);
        assert_eq!(r.census().live, 1);
    }
}
