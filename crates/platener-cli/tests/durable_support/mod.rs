//! The job database as the durability tests see it: read directly, beside the server, so a
//! test can look at the queue while the server is dead and check that no job is ever
//! half-written. Each look is one SQL statement, hence one consistent snapshot on both
//! databases (PostgreSQL's READ COMMITTED gives each statement its own).

use std::collections::BTreeMap;

use serde_json::Value;
use sqlx::Row;

/// One job as one statement saw it.
#[derive(Debug, Clone)]
pub struct JobSnap {
    pub id: String,
    pub status: String,
    pub attempts: i64,
    pub worker: Option<String>,
    pub summary: Option<String>,
    /// The kind of its last event, if any.
    pub last_kind: Option<String>,
    /// Its result files as `method/file`.
    pub files: Vec<String>,
}

/// A connection pool to the server's database and a runtime to drive it.
pub struct JobDb {
    pool: sqlx::AnyPool,
    runtime: tokio::runtime::Runtime,
}

impl JobDb {
    /// Opens the database at `url` (the server must have created it).
    pub fn open(url: &str) -> JobDb {
        sqlx::any::install_default_drivers();
        let runtime = tokio::runtime::Builder::new_current_thread()
            .enable_all()
            .build()
            .expect("runtime");
        let pool = runtime
            .block_on(sqlx::any::AnyPoolOptions::new().max_connections(1).connect(url))
            .expect("the job database opens");
        JobDb { pool, runtime }
    }

    /// Every job with its last event's kind and its result files, in one statement.
    pub fn snapshot(&self) -> Vec<JobSnap> {
        let rows = self
            .runtime
            .block_on(
                sqlx::query(
                    "SELECT j.id, j.status, j.attempts, j.worker, j.summary, \
                     (SELECT e.kind FROM events e WHERE e.job_id = j.id ORDER BY e.seq DESC LIMIT 1) AS last_kind, \
                     r.method, r.file FROM jobs j LEFT JOIN results r ON r.job_id = j.id ORDER BY j.id",
                )
                .fetch_all(&self.pool),
            )
            .expect("a snapshot of the jobs");
        let mut jobs: Vec<JobSnap> = Vec::new();
        for r in &rows {
            let id: String = r.get("id");
            if jobs.last().is_none_or(|j| j.id != id) {
                jobs.push(JobSnap {
                    id,
                    status: r.get("status"),
                    attempts: r.get("attempts"),
                    worker: r.get("worker"),
                    summary: r.get("summary"),
                    last_kind: r.get("last_kind"),
                    files: Vec::new(),
                });
            }
            let (method, file): (Option<String>, Option<String>) = (r.get("method"), r.get("file"));
            if let (Some(m), Some(f), Some(job)) = (method, file, jobs.last_mut()) {
                job.files.push(format!("{m}/{f}"));
            }
        }
        jobs
    }

    /// A job's events as (sequence number, kind, data), in the order stored.
    pub fn events(&self, id: &str) -> Vec<(i64, String, Value)> {
        let rows = self
            .runtime
            .block_on(
                sqlx::query("SELECT seq, kind, data FROM events WHERE job_id = $1 ORDER BY seq")
                    .bind(id)
                    .fetch_all(&self.pool),
            )
            .expect("a job's events");
        rows.iter()
            .map(|r| {
                let data: String = r.get("data");
                let data = serde_json::from_str(&data).unwrap_or_else(|e| panic!("event data {data:?}: {e}"));
                (r.get("seq"), r.get("kind"), data)
            })
            .collect()
    }
}

impl Drop for JobDb {
    fn drop(&mut self) {
        self.runtime.block_on(self.pool.close());
    }
}

/// The files a finished method must have: its ZIP, plan.json, report.json, and the SVG and
/// PNG of each sheet.
fn method_files(method: &Value) -> Vec<String> {
    let name = method["method"].as_str().unwrap_or_default();
    let mut files: Vec<String> = ["plan.zip", "plan.json", "report.json"]
        .iter()
        .map(|f| format!("{name}/{f}"))
        .collect();
    for n in 1..=method["sheets"].as_u64().unwrap_or(0) {
        files.push(format!("{name}/sheets/{n}.svg"));
        files.push(format!("{name}/sheets/{n}.png"));
    }
    files
}

/// What is wrong with a job as seen: a `done` job must have its last event `done` and a best
/// plan; a queued job has no files (a retry starts from nothing); every job's files belong to
/// methods its summary lists (or to none: the shared model scene), and each listed method that
/// made a plan has every file (a method lands whole, while the job runs or at its end); an
/// ended job's last event matches its status, and a running or queued job has no ending.
pub fn half_written(job: &JobSnap) -> Option<String> {
    let last = job.last_kind.as_deref();
    let ended = matches!(last, Some("done" | "failed" | "cancelled"));
    let summary: Value = job
        .summary
        .as_deref()
        .and_then(|s| serde_json::from_str(s).ok())
        .unwrap_or_default();
    let methods = summary["methods"].as_array().cloned().unwrap_or_default();
    let missing: Vec<String> = methods
        .iter()
        .filter(|m| m["status"] == "done")
        .flat_map(method_files)
        .filter(|f| !job.files.contains(f))
        .collect();
    let listed = |f: &&String| {
        let method = f.split('/').next().unwrap_or_default();
        method == "shared" || methods.iter().any(|m| m["method"] == method)
    };
    let stray: Vec<&String> = job.files.iter().filter(|f| !listed(f)).collect();
    let problem = match job.status.as_str() {
        "done" if last != Some("done") => Some(format!("done but its last event is {last:?}")),
        "done" if summary["best"].is_null() => Some("done without a best plan".to_string()),
        "queued" if !job.files.is_empty() => Some(format!("queued with {} files", job.files.len())),
        _ if !missing.is_empty() || !stray.is_empty() => Some(format!(
            "without {missing:?}, or with files of methods its summary does not list: {stray:?}"
        )),
        "failed" | "cancelled" if last != Some(job.status.as_str()) => Some(format!("last event {last:?}")),
        "queued" | "running" if ended => Some(format!("last event {last:?}")),
        _ => None,
    };
    problem.map(|p| format!("job {} ({}): {p}", job.id, job.status))
}

/// How many jobs are in each status.
pub fn counts(jobs: &[JobSnap]) -> BTreeMap<String, usize> {
    let mut counts = BTreeMap::new();
    for j in jobs {
        *counts.entry(j.status.clone()).or_insert(0) += 1;
    }
    counts
}
