//! `GET /api/health`: whether the service can take work, and whether work queued is being
//! done (issue 29: a health check that answered "ok" while every worker was stuck and every
//! upload stayed queued hid the outage).

use std::sync::Arc;
use std::sync::atomic::Ordering;
use std::time::Duration;

use axum::Json;
use axum::extract::State;
use axum::http::StatusCode;
use axum::response::{IntoResponse, Response};
use serde::Serialize;

use super::App;
use super::error::{ApiError, ApiResult};
use super::workers::Census;
use crate::db::{QueueStats, now_ms};

/// A queued job that has waited this long while a worker sat idle as long (or, for a server
/// without workers of its own, while no job ran anywhere) is not being served: a worker takes
/// a job within a poll (200 ms) of being free.
pub const STALL_AFTER: Duration = Duration::from_secs(10);

/// The answer, `200` with status `ok` or `503` with status `stalled`.
#[derive(Debug, Serialize)]
pub struct Health {
    /// `ok` or `stalled`.
    pub status: &'static str,
    /// Jobs queued.
    pub queue: i64,
    /// This server's worker processes alive now.
    pub workers: usize,
    /// Of those, how many hold a job.
    pub busy_workers: usize,
    /// Jobs running (on any server's workers).
    pub running: i64,
    /// How long the oldest queued job has waited, seconds (0.1 s); `null` with none queued.
    pub oldest_queued_s: Option<f64>,
    /// Why the service is stalled; only with status `stalled`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub reason: Option<String>,
}

/// `GET /api/health`: `200 ok` when the service can take work and does the work queued;
/// `503 busy` (an error) while stopping or with a full queue; `503 stalled` (this body) while
/// jobs wait and no worker takes them.
pub async fn health(State(app): State<Arc<App>>) -> ApiResult<Response> {
    let stats = app.db.queue_stats().await?;
    if app.draining.load(Ordering::SeqCst) {
        return Err(ApiError::busy("the server is stopping", 60));
    }
    if stats.queued >= app.config.max_queue {
        return Err(ApiError::busy("the conversion queue is full", 30));
    }
    let census = app.roster.census();
    let waited = stats
        .oldest_created
        .map(|c| Duration::from_millis(u64::try_from(now_ms() - c).unwrap_or(0)));
    let reason = stalled(app.config.workers, &census, &stats, waited);
    let body = Health {
        status: if reason.is_some() { "stalled" } else { "ok" },
        queue: stats.queued,
        workers: census.live,
        busy_workers: census.busy,
        running: stats.running,
        oldest_queued_s: waited.map(|w| (w.as_secs_f64() * 10.0).round() / 10.0),
        reason,
    };
    let status = if body.reason.is_some() {
        StatusCode::SERVICE_UNAVAILABLE
    } else {
        StatusCode::OK
    };
    Ok((status, Json(body)).into_response())
}

/// Why queued work is not being done, if it is not: jobs wait and this server (which runs
/// `workers`) has no worker alive; or the oldest job waited [`STALL_AFTER`] while a worker
/// sat idle as long, or, without workers of our own, while no job ran anywhere.
fn stalled(workers: usize, census: &Census, stats: &QueueStats, waited: Option<Duration>) -> Option<String> {
    if stats.queued == 0 {
        return None;
    }
    if workers > 0 && census.live == 0 {
        return Some("jobs are waiting and no worker is running".into());
    }
    let waited = waited.filter(|w| *w >= STALL_AFTER)?;
    let secs = waited.as_secs();
    if workers > 0 && census.longest_idle.is_some_and(|i| i >= STALL_AFTER) {
        return Some(format!("the oldest job has waited {secs} s while a worker is idle"));
    }
    (workers == 0 && stats.running == 0)
        .then(|| format!("the oldest job has waited {secs} s and no worker is converting anything"))
}

/// The routes of the service's own state: health and the settings it takes.
pub fn routes() -> axum::Router<std::sync::Arc<super::App>> {
    use axum::routing::get;
    axum::Router::new()
        .route("/api/health", get(health))
        .route("/api/settings", get(super::settings::schema))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn census(live: usize, busy: usize, idle_s: Option<u64>) -> Census {
        Census {
            live,
            busy,
            longest_idle: idle_s.map(Duration::from_secs),
        }
    }

    fn stats(queued: i64, running: i64) -> QueueStats {
        QueueStats {
            queued,
            running,
            oldest_created: Some(0),
        }
    }

    #[test]
    fn waiting_jobs_without_a_live_or_busy_worker_are_a_stall() {
        let long = Some(Duration::from_secs(60));
        let short = Some(Duration::from_secs(1));
        assert!(stalled(4, &census(0, 0, None), &stats(1, 0), short).is_some());
        assert!(stalled(4, &census(0, 0, None), &stats(0, 0), None).is_none());
        // All busy: a backlog, not a stall.
        assert!(stalled(4, &census(4, 4, None), &stats(30, 4), long).is_none());
        // A worker idle as long as the oldest job waited: nobody takes it.
        assert!(stalled(4, &census(4, 3, Some(20)), &stats(3, 3), long).is_some());
        assert!(stalled(4, &census(4, 3, Some(1)), &stats(3, 3), long).is_none());
        // Workers elsewhere: a stall only when nothing runs anywhere.
        assert!(stalled(0, &census(0, 0, None), &stats(3, 0), long).is_some());
        assert!(stalled(0, &census(0, 0, None), &stats(3, 1), long).is_none());
        assert!(stalled(0, &census(0, 0, None), &stats(3, 0), short).is_none());
    }
}
