//! Results as they come (issue 30): a running job's model scene and each method's files are
//! stored the moment the worker has them, not only at the end, and the queue position of a
//! waiting job.
//!
//! Every such write is one transaction that first updates the job's row where this *attempt*
//! (worker and attempt number) still holds it running, like [`Db::append_progress`]: a worker
//! that lost its job, or the attempt a retry replaced, writes nothing. A job going back to
//! the queue loses its partial results in the transaction that requeues it
//! ([`clear_partial`]), so a retry's results are never mixed with its predecessor's, while a
//! cancelled or failed job keeps the methods that landed.

use sqlx::{AnyConnection, Row};

use super::{Db, Result, ResultFile};

/// One attempt of a job as its worker holds it: what its writes are checked against.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Hold {
    /// The job.
    pub id: String,
    /// The worker's name in the `worker` column.
    pub worker: String,
    /// The attempt's number (`attempts` when it was claimed).
    pub attempt: i64,
}

impl Db {
    /// Stores part of a running job's results: its summary so far, `files` (replacing any of
    /// the same names) and the event saying they are there, in one transaction, only while
    /// `hold` still holds the job. `false` when it does not (cancelled, deleted, requeued or
    /// given to another worker): nothing was written and the worker should stop.
    pub async fn land(&self, hold: &Hold, summary: &str, files: &[ResultFile], event: (&str, &str)) -> Result<bool> {
        let mut tx = self.pool.begin().await?;
        let held = sqlx::query(
            "UPDATE jobs SET summary = $1 WHERE id = $2 AND worker = $3 AND attempts = $4 AND status = 'running'",
        )
        .bind(summary)
        .bind(&hold.id)
        .bind(&hold.worker)
        .bind(hold.attempt)
        .execute(&mut *tx)
        .await?;
        if held.rows_affected() != 1 {
            tx.rollback().await?;
            return Ok(false);
        }
        insert_files(&mut tx, &hold.id, files).await?;
        self.insert_event(&mut tx, &hold.id, event.0, event.1).await?;
        tx.commit().await?;
        Ok(true)
    }

    /// How many queued jobs a worker takes before a queued job created at `created` with id
    /// `id` (claims go by creation time, then id): its place in the queue.
    pub async fn queue_ahead(&self, id: &str, created: i64) -> Result<i64> {
        let row = sqlx::query(
            "SELECT COUNT(*) AS n FROM jobs WHERE status = 'queued' AND (created < $1 OR (created = $1 AND id < $2))",
        )
        .bind(created)
        .bind(id)
        .fetch_one(&self.pool)
        .await?;
        Ok(row.try_get("n")?)
    }
}

/// Inserts result files, replacing stored ones of the same (job, method, file): a method's
/// files landed while the job ran are never an error when the end writes again.
pub(super) async fn insert_files(conn: &mut AnyConnection, id: &str, files: &[ResultFile]) -> Result<()> {
    for f in files {
        sqlx::query(
            "INSERT INTO results (job_id, method, file, content_type, data) VALUES ($1, $2, $3, $4, $5) \
             ON CONFLICT (job_id, method, file) DO UPDATE SET content_type = excluded.content_type, data = excluded.data",
        )
        .bind(id)
        .bind(&f.method)
        .bind(&f.file)
        .bind(&f.content_type)
        .bind(f.data.clone())
        .execute(&mut *conn)
        .await?;
    }
    Ok(())
}

/// Removes what the attempts of requeued jobs stored while they ran (files and summary so
/// far), inside the transaction that requeues them, so each retry starts from nothing.
pub(super) async fn clear_partial(conn: &mut AnyConnection, ids: &[String]) -> Result<()> {
    for id in ids {
        sqlx::query("DELETE FROM results WHERE job_id = $1")
            .bind(id)
            .execute(&mut *conn)
            .await?;
        sqlx::query("UPDATE jobs SET summary = NULL WHERE id = $1")
            .bind(id)
            .execute(&mut *conn)
            .await?;
    }
    Ok(())
}
