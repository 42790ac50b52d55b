//! The event hub: one poller per server process feeds every event stream.
//!
//! Each stream polling the events table on its own cost one query per stream every 200 ms
//! (2500 queries/s for 500 clients). The hub keeps one *feed* per job being watched: the job's
//! events so far, in a `watch` channel every stream of that job subscribes to. One poller
//! reads the new events of every watched job in one query, on a timer (SQLite, and PostgreSQL
//! as a fallback), when a stream subscribes to a job, and on PostgreSQL the moment a worker's
//! `NOTIFY` says a job has a new event. A stream walks its feed by index, so a late client
//! gets every event so far, in order, and no stream sees a gap or a duplicate: the poller only
//! appends the event whose sequence number follows the feed's last one.

use std::collections::{HashMap, HashSet};
use std::sync::{Arc, Mutex, PoisonError};
use std::time::Duration;

use tokio::sync::{Notify, watch};

use crate::db::{Db, EventRow};

/// A job's events as far as the hub has read them.
#[derive(Debug, Default)]
pub(crate) struct Feed {
    events: Vec<EventRow>,
    /// The job was deleted: its stream ends after what it was sent.
    gone: bool,
}

impl Feed {
    /// The sequence number of the last event read (0: none).
    fn last_seq(&self) -> i64 {
        self.events.last().map_or(0, |e| e.seq)
    }

    /// Whether nothing can follow: the job's last event is here, or the job is gone.
    fn closed(&self) -> bool {
        self.gone || self.events.last().is_some_and(|e| is_last(&e.kind))
    }
}

/// The last events of a job.
pub(crate) fn is_last(kind: &str) -> bool {
    matches!(kind, "done" | "failed" | "cancelled")
}

/// The feeds of the jobs watched now, and the poller's wake-ups.
#[derive(Debug)]
pub(crate) struct Hub {
    db: Db,
    feeds: Mutex<HashMap<String, watch::Sender<Feed>>>,
    /// Jobs to read at the next wake-up without waiting for the timer.
    urgent: Mutex<HashSet<String>>,
    wake: Notify,
    poll_every: Duration,
    /// Whether a PostgreSQL listener is connected (then notifications wake the poller).
    pub(super) listening: watch::Sender<bool>,
}

impl Hub {
    /// A hub reading `db`, polling every watched job every `poll_every`.
    pub(crate) fn new(db: Db, poll_every: Duration) -> Arc<Hub> {
        Arc::new(Hub {
            db,
            feeds: Mutex::new(HashMap::new()),
            urgent: Mutex::new(HashSet::new()),
            wake: Notify::new(),
            poll_every,
            listening: watch::channel(false).0,
        })
    }

    /// Starts the poller (and on PostgreSQL the listener, given the database URL); both end
    /// when `stopping` becomes true.
    pub(crate) fn start(self: &Arc<Self>, database_url: Option<String>, stopping: watch::Receiver<bool>) {
        tokio::spawn(Arc::clone(self).poll_loop(stopping.clone()));
        if let Some(url) = database_url {
            tokio::spawn(super::listen::run(Arc::clone(self), url, stopping));
        }
    }

    /// A subscription to job `id`'s events from its first one.
    pub(crate) fn subscribe(&self, id: &str) -> watch::Receiver<Feed> {
        let rx = {
            let mut feeds = self.feeds.lock().unwrap_or_else(PoisonError::into_inner);
            match feeds.get(id) {
                Some(tx) => tx.subscribe(),
                None => {
                    let (tx, rx) = watch::channel(Feed::default());
                    feeds.insert(id.to_string(), tx);
                    rx
                }
            }
        };
        self.mark_urgent(id);
        rx
    }

    /// Asks the poller to read job `id` now (a new subscriber, or a notification).
    pub(crate) fn mark_urgent(&self, id: &str) {
        self.urgent
            .lock()
            .unwrap_or_else(PoisonError::into_inner)
            .insert(id.to_string());
        self.wake.notify_one();
    }

    /// Jobs being watched now.
    #[cfg(test)]
    pub(crate) fn watched(&self) -> usize {
        self.feeds.lock().unwrap_or_else(PoisonError::into_inner).len()
    }

    async fn poll_loop(self: Arc<Self>, mut stopping: watch::Receiver<bool>) {
        let mut tick = tokio::time::interval(self.poll_every);
        tick.set_missed_tick_behavior(tokio::time::MissedTickBehavior::Delay);
        loop {
            let full = tokio::select! {
                _ = tick.tick() => true,
                () = self.wake.notified() => false,
                _ = stopping.wait_for(|s| *s) => return,
            };
            if let Err(e) = self.poll(full).await {
                tracing::warn!("reading new events: {e}");
            }
        }
    }

    /// Reads new events: of every open feed when `full` (and finds deleted jobs and feeds
    /// nobody watches any more), else of the urgent ones.
    pub(super) async fn poll(&self, full: bool) -> crate::db::Result<()> {
        let urgent = std::mem::take(&mut *self.urgent.lock().unwrap_or_else(PoisonError::into_inner));
        let targets = self.targets(if full { None } else { Some(&urgent) });
        if targets.is_empty() {
            return Ok(());
        }
        let rows = self.db.events_of_jobs(&targets).await?;
        self.append(rows);
        if full {
            let ids: Vec<String> = targets.into_iter().map(|(id, _)| id).collect();
            let existing: HashSet<String> = self.db.existing_jobs(&ids).await?.into_iter().collect();
            self.close_missing(&ids, &existing);
        }
        Ok(())
    }

    /// `(job, last seq)` of the open feeds (those in `only`, when given); drops the feeds no
    /// stream holds any more.
    fn targets(&self, only: Option<&HashSet<String>>) -> Vec<(String, i64)> {
        let mut feeds = self.feeds.lock().unwrap_or_else(PoisonError::into_inner);
        if only.is_none() {
            feeds.retain(|_, tx| tx.receiver_count() > 0);
        }
        feeds
            .iter()
            .filter(|(id, _)| only.is_none_or(|o| o.contains(*id)))
            .filter_map(|(id, tx)| {
                let feed = tx.borrow();
                (!feed.closed()).then(|| (id.clone(), feed.last_seq()))
            })
            .collect()
    }

    /// Appends rows (by job and sequence number) to their feeds, each only if it follows the
    /// feed's last event: a row read twice, or after a gap, is left for the next poll.
    fn append(&self, rows: Vec<(String, EventRow)>) {
        let feeds = self.feeds.lock().unwrap_or_else(PoisonError::into_inner);
        let mut by_job: HashMap<String, Vec<EventRow>> = HashMap::new();
        for (id, row) in rows {
            by_job.entry(id).or_default().push(row);
        }
        for (id, rows) in by_job {
            let Some(tx) = feeds.get(&id) else { continue };
            tx.send_if_modified(|feed| {
                let before = feed.events.len();
                for row in rows {
                    if row.seq == feed.last_seq() + 1 && !feed.closed() {
                        feed.events.push(row);
                    }
                }
                feed.events.len() > before
            });
        }
    }

    /// Ends the feeds of jobs among `ids` that are not in `existing` (deleted).
    fn close_missing(&self, ids: &[String], existing: &HashSet<String>) {
        let feeds = self.feeds.lock().unwrap_or_else(PoisonError::into_inner);
        for id in ids.iter().filter(|id| !existing.contains(*id)) {
            if let Some(tx) = feeds.get(id) {
                tx.send_modify(|feed| feed.gone = true);
            }
        }
    }
}

/// One stream's place in its job's feed.
#[derive(Debug)]
pub(crate) struct Subscription {
    feed: watch::Receiver<Feed>,
    next: usize,
    stopping: watch::Receiver<bool>,
    /// A last event (done, failed, cancelled) was handed out: nothing may follow it, even
    /// if a stale writer ever appended something after it.
    ended: bool,
}

impl Subscription {
    /// Follows `feed` from its first event until it closes or `stopping` becomes true.
    pub(crate) fn new(feed: watch::Receiver<Feed>, stopping: watch::Receiver<bool>) -> Self {
        Self {
            feed,
            next: 0,
            stopping,
            ended: false,
        }
    }

    /// The next event, waiting for it; `None` once the job's last event was given, the job
    /// was deleted, or the server is stopping.
    pub(crate) async fn next(&mut self) -> Option<EventRow> {
        loop {
            if self.ended {
                return None;
            }
            {
                let feed = self.feed.borrow_and_update();
                if let Some(event) = feed.events.get(self.next) {
                    self.next += 1;
                    self.ended = is_last(&event.kind);
                    return Some(event.clone());
                }
                if feed.closed() || *self.stopping.borrow() {
                    return None;
                }
            }
            tokio::select! {
                changed = self.feed.changed() => changed.ok()?,
                _ = self.stopping.wait_for(|s| *s) => return None,
            }
        }
    }
}
