//! The database: jobs, their progress events and their results, for SQLite and PostgreSQL.
//!
//! One code path serves both (sqlx's `Any` driver); what differs is in [`dialect`]. The
//! server and the workers share nothing but this database, so every state change of a job
//! is one statement or one transaction here.

pub mod dialect;
mod feed;
mod live;
mod rows;
mod transitions;

use std::time::{SystemTime, UNIX_EPOCH};

use sqlx::any::AnyPoolOptions;
use sqlx::{AnyPool, Row};

pub use dialect::Dialect;
pub use live::Hold;
pub use rows::{Claimed, EventRow, Finished, GalleryRow, JobRow, NewJob, ResultFile};
pub use transitions::{Cancelled, Ending};

/// The queue at one moment ([`Db::queue_stats`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct QueueStats {
    /// Jobs waiting for a worker.
    pub queued: i64,
    /// Jobs a worker holds.
    pub running: i64,
    /// When the oldest queued job was created, ms since 1970.
    pub oldest_created: Option<i64>,
}

/// The job a worker holds ([`Db::held_by`]).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Held {
    /// The job.
    pub id: String,
    /// Its attempts so far, this one included.
    pub attempts: i64,
    /// When its lease runs out unless the worker heartbeats, ms since 1970.
    pub lease_until: Option<i64>,
}

/// What went wrong with the database.
#[derive(Debug, thiserror::Error)]
pub enum DbError {
    /// The URL names no database this build supports.
    #[error("unsupported database URL (expected sqlite:… or postgres://…)")]
    UnsupportedUrl,
    /// A query or the connection failed.
    #[error("database: {0}")]
    Sql(#[from] sqlx::Error),
    /// The migrations failed.
    #[error("database migration: {0}")]
    Migrate(#[from] sqlx::migrate::MigrateError),
    /// A stored JSON value could not be read back.
    #[error("stored data is damaged: {0}")]
    Damaged(String),
}

/// A database result.
pub type Result<T> = std::result::Result<T, DbError>;

/// Milliseconds since 1970: every time the crate stores.
pub fn now_ms() -> i64 {
    SystemTime::now()
        .duration_since(UNIX_EPOCH)
        .map_or(0, |d| i64::try_from(d.as_millis()).unwrap_or(i64::MAX))
}

/// A pool of connections to the job database.
#[derive(Debug, Clone)]
pub struct Db {
    pool: AnyPool,
    dialect: Dialect,
}

/// The columns of `jobs` that [`JobRow`] reads (never the model's bytes).
const JOB_COLUMNS: &str = "id, status, name, model_bytes, triangles, settings, created, started, finished, \
     attempts, worker, error, summary, delete_token, published, parent";

impl Db {
    /// Connects (creating an SQLite file if missing) and brings the tables up to date.
    pub async fn connect(url: &str, max_connections: u32) -> Result<Self> {
        let dialect = Dialect::of_url(url).ok_or(DbError::UnsupportedUrl)?;
        sqlx::any::install_default_drivers();
        let pool = AnyPoolOptions::new()
            .max_connections(max_connections.max(1))
            .connect(url)
            .await?;
        for statement in dialect.setup() {
            sqlx::query(*statement).execute(&pool).await?;
        }
        dialect.migrator().run(&pool).await?;
        Ok(Self { pool, dialect })
    }

    /// The database's dialect.
    pub fn dialect(&self) -> Dialect {
        self.dialect
    }

    /// Closes every connection.
    pub async fn close(&self) {
        self.pool.close().await;
    }

    /// Stores a new queued job; it exists before the upload is answered.
    pub async fn insert_job(&self, job: &NewJob) -> Result<()> {
        sqlx::query(
            "INSERT INTO jobs (id, status, name, model, model_bytes, triangles, settings, created, \
             attempts, delete_token, published, parent) VALUES ($1, 'queued', $2, $3, $4, $5, $6, $7, 0, $8, $9, $10)",
        )
        .bind(&job.id)
        .bind(&job.name)
        .bind(job.model.clone())
        .bind(i64::try_from(job.model.len()).unwrap_or(i64::MAX))
        .bind(job.triangles)
        .bind(&job.settings)
        .bind(job.created)
        .bind(&job.delete_token_hash)
        .bind(job.published)
        .bind(job.parent.clone())
        .execute(&self.pool)
        .await?;
        Ok(())
    }

    /// A job without its model bytes.
    pub async fn job(&self, id: &str) -> Result<Option<JobRow>> {
        let sql = format!("SELECT {JOB_COLUMNS} FROM jobs WHERE id = $1");
        let row = sqlx::query(sqlx::AssertSqlSafe(sql))
            .bind(id)
            .fetch_optional(&self.pool)
            .await?;
        row.as_ref().map(JobRow::from_row).transpose()
    }

    /// A job's model bytes (for a recut).
    pub async fn model(&self, id: &str) -> Result<Option<Vec<u8>>> {
        let row = sqlx::query("SELECT model FROM jobs WHERE id = $1")
            .bind(id)
            .fetch_optional(&self.pool)
            .await?;
        Ok(row.map(|r| r.try_get("model")).transpose()?)
    }

    /// Takes the oldest queued job for `worker`, leased until `lease_ms` from now.
    pub async fn claim(&self, worker: &str, lease_ms: i64) -> Result<Option<Claimed>> {
        let now = now_ms();
        let row = sqlx::query(self.dialect.claim_sql())
            .bind(worker)
            .bind(now + lease_ms)
            .bind(now)
            .fetch_optional(&self.pool)
            .await?;
        row.as_ref().map(Claimed::from_row).transpose()
    }

    /// Extends the lease of a job `worker` still holds; `false` when it no longer does (the
    /// job was given to another worker or deleted), and the worker should drop it.
    pub async fn heartbeat(&self, id: &str, worker: &str, lease_ms: i64) -> Result<bool> {
        let done = sqlx::query("UPDATE jobs SET lease_until = $1 WHERE id = $2 AND worker = $3 AND status = 'running'")
            .bind(now_ms() + lease_ms)
            .bind(id)
            .bind(worker)
            .execute(&self.pool)
            .await?;
        Ok(done.rows_affected() == 1)
    }

    /// Ends the lease of every job `worker` holds now (it died): the next [`Db::reap`] returns
    /// them to the queue or fails them.
    pub async fn expire_worker(&self, worker: &str) -> Result<()> {
        sqlx::query("UPDATE jobs SET lease_until = 0 WHERE worker = $1 AND status = 'running'")
            .bind(worker)
            .execute(&self.pool)
            .await?;
        Ok(())
    }

    /// Puts the jobs `worker` holds back in the queue without counting the attempt (a graceful
    /// shutdown stopped it, not the model), without what they stored so far.
    pub async fn requeue_worker(&self, worker: &str) -> Result<u64> {
        let mut tx = self.pool.begin().await?;
        let rows = sqlx::query(
            "UPDATE jobs SET status = 'queued', worker = NULL, lease_until = NULL, attempts = attempts - 1 \
             WHERE worker = $1 AND status = 'running' RETURNING id",
        )
        .bind(worker)
        .fetch_all(&mut *tx)
        .await?;
        let ids: Vec<String> = rows
            .iter()
            .map(|r| r.try_get("id"))
            .collect::<std::result::Result<_, _>>()?;
        live::clear_partial(&mut tx, &ids).await?;
        tx.commit().await?;
        Ok(u64::try_from(ids.len()).unwrap_or(u64::MAX))
    }

    /// Appends an event to a job's list without checking who holds the job (workers use
    /// [`Db::append_progress`]); returns its sequence number (from 1).
    pub async fn append_event(&self, id: &str, kind: &str, data: &str) -> Result<i64> {
        let mut conn = self.pool.acquire().await?;
        self.insert_event(&mut conn, id, kind, data).await
    }

    /// A job's events after sequence number `after`, in order (at most `limit`).
    pub async fn events_after(&self, id: &str, after: i64, limit: i64) -> Result<Vec<EventRow>> {
        let rows =
            sqlx::query("SELECT seq, kind, data FROM events WHERE job_id = $1 AND seq > $2 ORDER BY seq LIMIT $3")
                .bind(id)
                .bind(after)
                .bind(limit)
                .fetch_all(&self.pool)
                .await?;
        rows.iter().map(EventRow::from_row).collect()
    }

    /// Records a finished job in one transaction: its status and summary, the result files not
    /// landed while it ran ([`Db::land`]; those stay) and the last event; nothing is written
    /// unless `worker` still holds the job. Returns whether it did.
    pub async fn finish(&self, id: &str, worker: &str, outcome: &Finished) -> Result<bool> {
        let mut tx = self.pool.begin().await?;
        let updated = sqlx::query(
            "UPDATE jobs SET status = $1, finished = $2, error = $3, summary = $4, lease_until = NULL \
             WHERE id = $5 AND worker = $6 AND status = 'running'",
        )
        .bind(&outcome.status)
        .bind(now_ms())
        .bind(outcome.error.clone())
        .bind(&outcome.summary)
        .bind(id)
        .bind(worker)
        .execute(&mut *tx)
        .await?;
        if updated.rows_affected() != 1 {
            tx.rollback().await?;
            // A job deleted while it ran leaves no events behind.
            sqlx::query("DELETE FROM events WHERE job_id = $1 AND NOT EXISTS (SELECT 1 FROM jobs WHERE id = $1)")
                .bind(id)
                .execute(&self.pool)
                .await?;
            return Ok(false);
        }
        live::insert_files(&mut tx, id, &outcome.files).await?;
        self.insert_event(&mut tx, id, &outcome.status, &outcome.event).await?;
        tx.commit().await?;
        Ok(true)
    }

    /// One stored result file: its content type and bytes.
    pub async fn result_file(&self, id: &str, method: &str, file: &str) -> Result<Option<(String, Vec<u8>)>> {
        let row = sqlx::query("SELECT content_type, data FROM results WHERE job_id = $1 AND method = $2 AND file = $3")
            .bind(id)
            .bind(method)
            .bind(file)
            .fetch_optional(&self.pool)
            .await?;
        row.map(|r| Ok((r.try_get("content_type")?, r.try_get("data")?)))
            .transpose()
    }

    /// Removes a job, its events and results, in one transaction. The job's row goes first:
    /// on PostgreSQL that waits for a worker's write in progress (which locked the row) to
    /// commit, so the results and events it added are deleted too, not left behind.
    pub async fn delete(&self, id: &str) -> Result<bool> {
        let mut tx = self.pool.begin().await?;
        let done = sqlx::query("DELETE FROM jobs WHERE id = $1")
            .bind(id)
            .execute(&mut *tx)
            .await?;
        sqlx::query("DELETE FROM results WHERE job_id = $1")
            .bind(id)
            .execute(&mut *tx)
            .await?;
        sqlx::query("DELETE FROM events WHERE job_id = $1")
            .bind(id)
            .execute(&mut *tx)
            .await?;
        tx.commit().await?;
        Ok(done.rows_affected() == 1)
    }

    /// Shows a job in the gallery (keeps the first publication time).
    pub async fn publish(&self, id: &str) -> Result<()> {
        sqlx::query("UPDATE jobs SET published = COALESCE(published, $1) WHERE id = $2")
            .bind(now_ms())
            .bind(id)
            .execute(&self.pool)
            .await?;
        Ok(())
    }

    /// Takes a job out of the gallery again (it stays reachable by its id, as before it was
    /// published); nothing changes for a job that was not published.
    pub async fn unpublish(&self, id: &str) -> Result<()> {
        sqlx::query("UPDATE jobs SET published = NULL WHERE id = $1")
            .bind(id)
            .execute(&self.pool)
            .await?;
        Ok(())
    }

    /// Published jobs, newest first, `per_page` from page `page` (from 1).
    pub async fn gallery(&self, page: i64, per_page: i64) -> Result<Vec<GalleryRow>> {
        let rows = sqlx::query(
            "SELECT id, name, status, summary, published FROM jobs WHERE published IS NOT NULL \
             ORDER BY published DESC, id LIMIT $1 OFFSET $2",
        )
        .bind(per_page)
        .bind((page - 1).max(0) * per_page)
        .fetch_all(&self.pool)
        .await?;
        rows.iter().map(GalleryRow::from_row).collect()
    }

    /// How many jobs are in each status, by status name.
    pub async fn counts(&self) -> Result<Vec<(String, i64)>> {
        let rows = sqlx::query("SELECT status, COUNT(*) AS n FROM jobs GROUP BY status ORDER BY status")
            .fetch_all(&self.pool)
            .await?;
        rows.iter()
            .map(|r| Ok((r.try_get("status")?, r.try_get("n")?)))
            .collect()
    }

    /// Jobs waiting for a worker.
    pub async fn queue_len(&self) -> Result<i64> {
        let row = sqlx::query("SELECT COUNT(*) AS n FROM jobs WHERE status = 'queued'")
            .fetch_one(&self.pool)
            .await?;
        Ok(row.try_get("n")?)
    }

    /// The queue as `/api/health` reports it: jobs queued, jobs running, and when the oldest
    /// queued job was created (ms), in two statements.
    pub async fn queue_stats(&self) -> Result<QueueStats> {
        let queued = sqlx::query(
            "SELECT COUNT(*) AS n, CAST(MIN(created) AS BIGINT) AS oldest FROM jobs WHERE status = 'queued'",
        )
        .fetch_one(&self.pool)
        .await?;
        let running = sqlx::query("SELECT COUNT(*) AS n FROM jobs WHERE status = 'running'")
            .fetch_one(&self.pool)
            .await?;
        Ok(QueueStats {
            queued: queued.try_get("n")?,
            oldest_created: queued.try_get("oldest")?,
            running: running.try_get("n")?,
        })
    }

    /// The job `worker` holds now (running, leased to it), if any: what the server watches
    /// its workers by.
    pub async fn held_by(&self, worker: &str) -> Result<Option<Held>> {
        let row = sqlx::query(
            "SELECT id, attempts, lease_until FROM jobs WHERE worker = $1 AND status = 'running' ORDER BY id LIMIT 1",
        )
        .bind(worker)
        .fetch_optional(&self.pool)
        .await?;
        row.map(|r| {
            Ok(Held {
                id: r.try_get("id")?,
                attempts: r.try_get("attempts")?,
                lease_until: r.try_get("lease_until")?,
            })
        })
        .transpose()
    }

    /// Jobs held by one of `workers`.
    pub async fn running_of(&self, workers: &[String]) -> Result<i64> {
        let mut n = 0;
        for w in workers {
            let row = sqlx::query("SELECT COUNT(*) AS n FROM jobs WHERE worker = $1 AND status = 'running'")
                .bind(w)
                .fetch_one(&self.pool)
                .await?;
            n += row.try_get::<i64, _>("n")?;
        }
        Ok(n)
    }

    /// How many finished conversions took at most each of `bounds_ms` (cumulative, for a
    /// Prometheus histogram), their count and their total time.
    pub async fn durations(&self, bounds_ms: &[i64]) -> Result<(Vec<i64>, i64, i64)> {
        let mut counts = Vec::with_capacity(bounds_ms.len());
        for b in bounds_ms {
            let row = sqlx::query(
                "SELECT COUNT(*) AS n FROM jobs WHERE finished IS NOT NULL AND started IS NOT NULL \
                 AND finished - started <= $1",
            )
            .bind(*b)
            .fetch_one(&self.pool)
            .await?;
            counts.push(row.try_get("n")?);
        }
        let row = sqlx::query(
            "SELECT COUNT(*) AS n, CAST(COALESCE(SUM(finished - started), 0) AS BIGINT) AS total FROM jobs \
             WHERE finished IS NOT NULL AND started IS NOT NULL",
        )
        .fetch_one(&self.pool)
        .await?;
        Ok((counts, row.try_get("n")?, row.try_get("total")?))
    }

    /// A value of the `meta` table.
    pub async fn meta(&self, key: &str) -> Result<Option<String>> {
        let row = sqlx::query("SELECT value FROM meta WHERE key = $1")
            .bind(key)
            .fetch_optional(&self.pool)
            .await?;
        Ok(row.map(|r| r.try_get("value")).transpose()?)
    }

    /// Sets a value of the `meta` table once; `false` when it was set already (another
    /// server got there first).
    pub async fn set_meta_once(&self, key: &str, value: &str) -> Result<bool> {
        let done = sqlx::query("INSERT INTO meta (key, value) VALUES ($1, $2) ON CONFLICT (key) DO NOTHING")
            .bind(key)
            .bind(value)
            .execute(&self.pool)
            .await?;
        Ok(done.rows_affected() == 1)
    }
}

impl Db {
    /// The (method, file) names of a job's results, in order.
    pub async fn result_index(&self, id: &str) -> Result<Vec<(String, String)>> {
        let rows = sqlx::query("SELECT method, file FROM results WHERE job_id = $1 ORDER BY method, file")
            .bind(id)
            .fetch_all(&self.pool)
            .await?;
        rows.iter()
            .map(|r| Ok((r.try_get("method")?, r.try_get("file")?)))
            .collect()
    }
}
