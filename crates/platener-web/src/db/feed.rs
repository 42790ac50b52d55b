//! What the server's event hub reads: the new events of many jobs in one query, which of them
//! still exist, and PostgreSQL's notification that a job has a new event.
//!
//! One query per poll for every job watched, instead of one per stream, is what lets a server
//! stream to hundreds of clients (docs/decisions.md, "Events that scale").

use sqlx::Row;

use super::{Db, EventRow, Result};

/// Jobs per query: well below SQLite's and PostgreSQL's limits on parameters.
const JOBS_PER_QUERY: usize = 200;

impl Db {
    /// The events of each `(job, after)` with a sequence number above `after`, by job and
    /// sequence number.
    pub async fn events_of_jobs(&self, jobs: &[(String, i64)]) -> Result<Vec<(String, EventRow)>> {
        let mut out = Vec::new();
        for chunk in jobs.chunks(JOBS_PER_QUERY) {
            let terms: Vec<String> = (0..chunk.len())
                .map(|i| format!("(job_id = ${} AND seq > ${})", 2 * i + 1, 2 * i + 2))
                .collect();
            let sql = format!(
                "SELECT job_id, seq, kind, data FROM events WHERE {} ORDER BY job_id, seq",
                terms.join(" OR ")
            );
            let mut query = sqlx::query(sqlx::AssertSqlSafe(sql));
            for (id, after) in chunk {
                query = query.bind(id.clone()).bind(*after);
            }
            for row in query.fetch_all(&self.pool).await? {
                out.push((row.try_get("job_id")?, EventRow::from_row(&row)?));
            }
        }
        Ok(out)
    }

    /// Which of `ids` are jobs (not deleted), in no particular order.
    pub async fn existing_jobs(&self, ids: &[String]) -> Result<Vec<String>> {
        let mut out = Vec::new();
        for chunk in ids.chunks(JOBS_PER_QUERY * 2) {
            let params: Vec<String> = (1..=chunk.len()).map(|i| format!("${i}")).collect();
            let sql = format!("SELECT id FROM jobs WHERE id IN ({})", params.join(", "));
            let mut query = sqlx::query(sqlx::AssertSqlSafe(sql));
            for id in chunk {
                query = query.bind(id.clone());
            }
            for row in query.fetch_all(&self.pool).await? {
                out.push(row.try_get("id")?);
            }
        }
        Ok(out)
    }

    /// Tells listening servers (PostgreSQL only) that job `id` has a new event; inside a
    /// transaction, PostgreSQL delivers it when the transaction commits.
    pub(super) async fn notify_event<'c, E>(&self, executor: E, id: &str) -> Result<()>
    where
        E: sqlx::Executor<'c, Database = sqlx::Any>,
    {
        if let Some(sql) = self.dialect.notify_sql() {
            sqlx::query(sql).bind(id).execute(executor).await?;
        }
        Ok(())
    }
}
