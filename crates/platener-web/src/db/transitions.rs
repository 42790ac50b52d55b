//! The state changes of a job that more than one process may attempt at once: a worker's
//! progress write, a cancel, the reaping of dead workers' jobs.
//!
//! Each is one transaction that first updates the job's row, so on PostgreSQL the row lock
//! orders them (the second re-reads the row and finds it changed) and on SQLite the single
//! writer does. Every event of a job is appended inside the transaction that changes (or
//! checks) its state, so a job never ends without its last event, no event follows the last
//! one, and a worker that lost its job writes nothing more.

use sqlx::AnyConnection;
use sqlx::Row;
use sqlx::any::AnyRow;

use super::{Db, Result, now_ms};

/// How a cancel request ended.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Cancelled {
    /// The job was queued or running and is now `cancelled`, with its last event.
    Now,
    /// The job had already ended with this status (done, failed, cancelled): nothing changed.
    AlreadyEnded(String),
    /// No such job.
    Missing,
}

impl Db {
    /// Appends an event after the job's last one and tells listening servers (PostgreSQL
    /// delivers the notification when the transaction commits); its sequence number. Inside a
    /// transaction that updated the job's row first, the row lock keeps two appenders from
    /// taking the same number.
    pub(super) async fn insert_event(&self, conn: &mut AnyConnection, id: &str, kind: &str, data: &str) -> Result<i64> {
        let row = sqlx::query(
            "INSERT INTO events (job_id, seq, kind, data) \
             SELECT $1, COALESCE(MAX(seq), 0) + 1, $2, $3 FROM events WHERE job_id = $1 RETURNING seq",
        )
        .bind(id)
        .bind(kind)
        .bind(data)
        .fetch_one(&mut *conn)
        .await?;
        self.notify_event(&mut *conn, id).await?;
        Ok(row.try_get("seq")?)
    }
}

impl Db {
    /// A worker's progress event, appended only while `worker` still holds the running job;
    /// `false` when it does not (the job was cancelled, deleted or given to another worker)
    /// and the worker should stop: so no event of a stale attempt lands after a retry's or
    /// after the last event.
    pub async fn append_progress(&self, id: &str, worker: &str, kind: &str, data: &str) -> Result<bool> {
        let mut tx = self.pool.begin().await?;
        let held = sqlx::query(
            "UPDATE jobs SET lease_until = lease_until WHERE id = $1 AND worker = $2 AND status = 'running'",
        )
        .bind(id)
        .bind(worker)
        .execute(&mut *tx)
        .await?;
        if held.rows_affected() != 1 {
            tx.rollback().await?;
            return Ok(false);
        }
        self.insert_event(&mut tx, id, kind, data).await?;
        tx.commit().await?;
        Ok(true)
    }

    /// Cancels a queued or running job at once: status `cancelled`, its lease ended and its
    /// last event, in one transaction. A running job's worker learns it at its next progress
    /// write or heartbeat, stops, and its results are refused by [`Db::finish`]; the methods
    /// it landed before ([`Db::land`]) stay.
    pub async fn cancel(&self, id: &str) -> Result<Cancelled> {
        let mut tx = self.pool.begin().await?;
        let updated = sqlx::query(
            "UPDATE jobs SET status = 'cancelled', finished = $1, lease_until = NULL \
             WHERE id = $2 AND status IN ('queued', 'running')",
        )
        .bind(now_ms())
        .bind(id)
        .execute(&mut *tx)
        .await?;
        if updated.rows_affected() != 1 {
            tx.rollback().await?;
            return Ok(match self.job(id).await? {
                Some(row) => Cancelled::AlreadyEnded(row.status),
                None => Cancelled::Missing,
            });
        }
        self.insert_event(&mut tx, id, "cancelled", r#"{"status":"cancelled"}"#)
            .await?;
        tx.commit().await?;
        Ok(Cancelled::Now)
    }

    /// Jobs whose lease ran out: their worker died or hung. After `max_attempts` attempts a
    /// job fails with a message saying so; before, it returns to the queue. The states and
    /// their `failed` or `retry` events are one transaction, so a reaper killed half-way
    /// leaves no job failed without its last event. Returns the ids requeued and failed.
    pub async fn reap(&self, max_attempts: i64) -> Result<(Vec<String>, Vec<String>)> {
        let now = now_ms();
        let message = format!(
            "the worker converting this model stopped {max_attempts} times (it crashed, ran out of memory or \
             was killed); the model was not converted"
        );
        let error = serde_json::json!({"code": "worker_died", "message": message}).to_string();
        let mut tx = self.pool.begin().await?;
        let failed: Vec<AnyRow> = sqlx::query(
            "UPDATE jobs SET status = 'failed', finished = $1, error = $2, lease_until = NULL \
             WHERE status = 'running' AND lease_until < $1 AND attempts >= $3 RETURNING id",
        )
        .bind(now)
        .bind(&error)
        .bind(max_attempts)
        .fetch_all(&mut *tx)
        .await?;
        let requeued: Vec<AnyRow> = sqlx::query(
            "UPDATE jobs SET status = 'queued', worker = NULL, lease_until = NULL \
             WHERE status = 'running' AND lease_until < $1 RETURNING id",
        )
        .bind(now)
        .fetch_all(&mut *tx)
        .await?;
        let (requeued, failed) = (sorted_ids(&requeued)?, sorted_ids(&failed)?);
        super::live::clear_partial(&mut tx, &requeued).await?;
        for id in &failed {
            self.insert_event(&mut tx, id, "failed", &error).await?;
        }
        for id in &requeued {
            let retry = r#"{"reason":"the worker stopped; the job is queued again"}"#;
            self.insert_event(&mut tx, id, "retry", retry).await?;
        }
        tx.commit().await?;
        Ok((requeued, failed))
    }
}

/// How the jobs of a worker that is gone end ([`Db::release_worker`]): the server knows why
/// it went (crashed, out of memory, killed as stuck), so the job's `failed` error or `retry`
/// event says so instead of the reaper's guess.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Ending {
    /// The error code of a job failed now.
    pub code: &'static str,
    /// The sentence of a job failed now.
    pub message: String,
    /// The reason in a `retry` event; `None`: fail at once whatever the attempts (retrying a
    /// model that ran past its time limit would only spend the limit again).
    pub retry: Option<String>,
}

impl Db {
    /// Ends the running jobs `worker` holds, whose process is gone: back to the queue with a
    /// `retry` event while attempts remain and `ending` allows it, else `failed` with its
    /// error; states and events in one transaction, like [`Db::reap`]. Returns the ids
    /// requeued and failed.
    pub async fn release_worker(
        &self,
        worker: &str,
        ending: &Ending,
        max_attempts: i64,
    ) -> Result<(Vec<String>, Vec<String>)> {
        let now = now_ms();
        let error = serde_json::json!({"code": ending.code, "message": ending.message}).to_string();
        let attempts_left_below = if ending.retry.is_some() { max_attempts } else { 0 };
        let mut tx = self.pool.begin().await?;
        let failed: Vec<AnyRow> = sqlx::query(
            "UPDATE jobs SET status = 'failed', finished = $1, error = $2, lease_until = NULL \
             WHERE status = 'running' AND worker = $3 AND attempts >= $4 RETURNING id",
        )
        .bind(now)
        .bind(&error)
        .bind(worker)
        .bind(attempts_left_below)
        .fetch_all(&mut *tx)
        .await?;
        let requeued: Vec<AnyRow> = sqlx::query(
            "UPDATE jobs SET status = 'queued', worker = NULL, lease_until = NULL \
             WHERE status = 'running' AND worker = $1 RETURNING id",
        )
        .bind(worker)
        .fetch_all(&mut *tx)
        .await?;
        let (requeued, failed) = (sorted_ids(&requeued)?, sorted_ids(&failed)?);
        super::live::clear_partial(&mut tx, &requeued).await?;
        for id in &failed {
            self.insert_event(&mut tx, id, "failed", &error).await?;
        }
        let retry = serde_json::json!({"reason": ending.retry}).to_string();
        for id in &requeued {
            self.insert_event(&mut tx, id, "retry", &retry).await?;
        }
        tx.commit().await?;
        Ok((requeued, failed))
    }
}

/// The `id` column of rows, sorted.
fn sorted_ids(rows: &[AnyRow]) -> Result<Vec<String>> {
    let mut ids: Vec<String> = rows
        .iter()
        .map(|r| r.try_get("id"))
        .collect::<std::result::Result<_, _>>()?;
    ids.sort();
    Ok(ids)
}
