//! The load benchmark of issue 17: for each database and each client count, a fresh
//! `platener serve` (the real binary, with its worker processes) and one [`run`](super::run)
//! against it.
//!
//! All clients come from 127.0.0.1, so the server runs with the per-address upload limit off
//! and a queue bound above the client count: the benchmark measures the service, not its
//! abuse limits. PostgreSQL runs use one throwaway cluster ([`Cluster`]) and a fresh database
//! per run; SQLite runs a fresh data folder per run.

use std::io::{BufRead as _, BufReader};
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

use serde::Serialize;

use super::{Config, LoadError, Summary};
use crate::Cluster;

/// How long a server may take to print its address.
const START_LIMIT: Duration = Duration::from_secs(60);
/// How long a stopped server may take to exit before it is killed.
const STOP_LIMIT: Duration = Duration::from_secs(30);

/// A database the benchmark runs on.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Database {
    /// A fresh SQLite file per run (the default of `platener serve`).
    Sqlite,
    /// A fresh database per run in a throwaway PostgreSQL cluster.
    Postgres,
}

impl Database {
    /// The database of a name (`sqlite`, `postgres`).
    pub fn of_name(name: &str) -> Option<Self> {
        match name.trim() {
            "sqlite" => Some(Database::Sqlite),
            "postgres" | "postgresql" => Some(Database::Postgres),
            _ => None,
        }
    }
}

/// What to benchmark.
#[derive(Debug, Clone)]
pub struct BenchConfig {
    /// The `platener` binary.
    pub platener: PathBuf,
    /// Databases, in order.
    pub databases: Vec<Database>,
    /// Concurrent clients of each run, in order.
    pub clients: Vec<usize>,
    /// Worker processes per server.
    pub workers: usize,
    /// The client settings of every run (its `base_url`, `clients` and `server_pid` are set
    /// per run).
    pub client: Config,
}

/// One run's figures.
#[derive(Debug, Clone, Serialize)]
pub struct BenchRun {
    /// The database.
    pub database: Database,
    /// Worker processes.
    pub workers: usize,
    /// The load average (1 minute) before and after the run.
    pub load_average: (f64, f64),
    /// The client's figures.
    pub summary: Summary,
}

/// Why the benchmark could not run.
#[derive(Debug, thiserror::Error)]
pub enum BenchError {
    /// The server program is missing.
    #[error("{0}: no such program; build it first (`cargo build --release -p platener-cli`) or pass --platener")]
    NoServer(PathBuf),
    /// The server did not start.
    #[error("platener serve did not start: {0}")]
    Server(String),
    /// The throwaway PostgreSQL cluster failed.
    #[error("PostgreSQL: {0}")]
    Postgres(#[from] crate::Error),
    /// The client could not run.
    #[error(transparent)]
    Load(#[from] LoadError),
    /// A temp dir, process or runtime failed.
    #[error("{0}")]
    Io(#[from] std::io::Error),
}

/// Runs every (database, clients) pair, calling `each` with each run as it ends.
pub fn bench(config: &BenchConfig, mut each: impl FnMut(&BenchRun)) -> Result<Vec<BenchRun>, BenchError> {
    if !config.platener.is_file() {
        return Err(BenchError::NoServer(config.platener.clone()));
    }
    let runtime = tokio::runtime::Runtime::new()?;
    let mut runs = Vec::new();
    for &database in &config.databases {
        let cluster = match database {
            Database::Postgres => Some(Cluster::start()?),
            Database::Sqlite => None,
        };
        for &clients in &config.clients {
            let data = tempfile::tempdir()?;
            let url = match &cluster {
                Some(c) => Some(c.fresh_database()?.url),
                None => None,
            };
            let before = load_average();
            let server = Server::start(config, data.path(), url.as_deref())?;
            let client = Config {
                base_url: server.url.clone(),
                clients,
                server_pid: Some(server.child.id()),
                ..config.client.clone()
            };
            let summary = runtime.block_on(super::run(client));
            server.stop(data.path());
            let run = BenchRun {
                database,
                workers: config.workers,
                load_average: (before, load_average()),
                summary: summary?,
            };
            each(&run);
            runs.push(run);
        }
    }
    Ok(runs)
}

/// A running `platener serve` and its address.
struct Server {
    child: Child,
    url: String,
}

impl Server {
    /// Starts the server on a free loopback port with its log in `data/serve.log`.
    fn start(config: &BenchConfig, data: &Path, database: Option<&str>) -> Result<Server, BenchError> {
        let log = std::fs::File::create(data.join("serve.log"))?;
        let mut command = Command::new(&config.platener);
        command
            .args(["serve", "--addr", "127.0.0.1:0", "--no-examples", "--rate-limit", "0"])
            .args(["--max-queue", "1000000", "--workers", &config.workers.to_string()])
            .arg("--data")
            .arg(data)
            .stdin(Stdio::null())
            .stdout(Stdio::piped())
            .stderr(log);
        if let Some(url) = database {
            command.args(["--database", url]);
        }
        let mut child = command.spawn()?;
        let Some(stdout) = child.stdout.take() else {
            return Err(BenchError::Server("no standard output".into()));
        };
        // The first line names the address; read it on a thread so a silent server is bounded.
        let (tx, rx) = std::sync::mpsc::channel();
        std::thread::spawn(move || {
            let mut line = String::new();
            let _ = BufReader::new(stdout).read_line(&mut line);
            let _ = tx.send(line);
        });
        let line = rx.recv_timeout(START_LIMIT).unwrap_or_default();
        match line.trim().strip_prefix("platener: serving on ") {
            Some(url) => Ok(Server {
                child,
                url: url.to_string(),
            }),
            None => {
                let _ = child.kill();
                let _ = child.wait();
                let log = std::fs::read_to_string(data.join("serve.log")).unwrap_or_default();
                Err(BenchError::Server(format!("its output: {line:?}; its log: {log}")))
            }
        }
    }

    /// SIGTERM, then waits (bounded) for the exit; a server that does not exit is killed.
    fn stop(mut self, data: &Path) {
        let pid = nix::unistd::Pid::from_raw(i32::try_from(self.child.id()).unwrap_or(i32::MAX));
        let _ = nix::sys::signal::kill(pid, nix::sys::signal::Signal::SIGTERM);
        let started = Instant::now();
        while started.elapsed() < STOP_LIMIT {
            if matches!(self.child.try_wait(), Ok(Some(_))) {
                return;
            }
            std::thread::sleep(Duration::from_millis(50));
        }
        eprintln!(
            "platener-load: the server did not stop within {} s; killed (log: {})",
            STOP_LIMIT.as_secs(),
            data.join("serve.log").display()
        );
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

/// The 1-minute load average (0 when /proc/loadavg cannot be read).
fn load_average() -> f64 {
    std::fs::read_to_string("/proc/loadavg")
        .ok()
        .and_then(|s| s.split_whitespace().next()?.parse().ok())
        .unwrap_or(0.0)
}

/// A Markdown table of runs, for docs/performance.md.
pub fn markdown(runs: &[BenchRun]) -> String {
    let mut out = String::from(
        "| database | clients | done | conv/s | failed req | status p50 / p99 ms | upload p50 / p99 ms | \
         download p50 / p99 ms | conversion p50 / p99 s | server RSS MB | workers RSS MB | load avg |\n\
         |---|---|---|---|---|---|---|---|---|---|---|---|\n",
    );
    for r in runs {
        let s = &r.summary;
        let mb = |v: Option<f64>| v.map_or_else(|| "–".to_string(), |v| format!("{v:.0}"));
        out.push_str(&format!(
            "| {:?} | {} | {}/{} | {:.2} | {} | {:.1} / {:.1} | {:.1} / {:.1} | {:.1} / {:.1} | {:.1} / {:.1} | {} | {} | {:.2} → {:.2} |\n",
            r.database,
            s.clients,
            s.conversions.done,
            s.conversions.submitted,
            s.conversions_per_second,
            s.requests.failed,
            s.status_reads.p50_ms,
            s.status_reads.p99_ms,
            s.uploads.p50_ms,
            s.uploads.p99_ms,
            s.downloads.p50_ms,
            s.downloads.p99_ms,
            s.conversion.p50_ms / 1000.0,
            s.conversion.p99_ms / 1000.0,
            mb(s.server_process_peak_rss_mb),
            mb(s.workers_peak_rss_mb),
            r.load_average.0,
            r.load_average.1,
        ));
    }
    out
}
