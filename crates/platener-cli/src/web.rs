//! `platener serve` and `platener worker`: flags in, the web crate does the rest.

use std::net::SocketAddr;
use std::path::PathBuf;
use std::time::Duration;

use clap::Args;
use platener_web::{ServeConfig, WorkerConfig};

/// Examples shown under `platener serve --help`.
pub const SERVE_EXAMPLES: &str = "Examples:
  platener serve
      the API and page on http://127.0.0.1:3000, data in ./platener-data
  platener serve --addr 0.0.0.0:8080 --workers 4 --max-upload-mb 20
  platener serve --database postgres://user@db/platener --workers 0
      a server whose workers run on other machines (`platener worker --database …`)";

/// `platener serve`.
#[derive(Debug, Args)]
pub struct ServeArgs {
    /// Address to listen on (port 0: any free port; the address is printed).
    #[arg(long, default_value = "127.0.0.1:3000")]
    pub addr: SocketAddr,
    /// Folder of the SQLite database.
    #[arg(long, value_name = "DIR", default_value = "platener-data")]
    pub data: PathBuf,
    /// Database URL (sqlite://FILE or postgres://…); default: SQLite in --data.
    #[arg(long, value_name = "URL")]
    pub database: Option<String>,
    /// Worker processes to start (default: one per core; 0: none).
    #[arg(long, value_name = "N")]
    pub workers: Option<usize>,
    /// Largest upload in MB.
    #[arg(long, value_name = "MB", default_value_t = 50)]
    pub max_upload_mb: u64,
    /// Largest model in triangles (a binary STL from its header, other formats once read).
    #[arg(long, value_name = "N", default_value_t = 5_000_000)]
    pub max_triangles: u64,
    /// Give up a model after this many seconds (0: never).
    #[arg(long, value_name = "S", default_value_t = 60.0)]
    pub timeout: f64,
    /// Queued conversions beyond which uploads are refused (503 busy).
    #[arg(long, value_name = "N", default_value_t = 100)]
    pub max_queue: i64,
    /// Uploads per minute from one address (429 beyond; 0: no limit).
    #[arg(long, value_name = "N", default_value_t = 30)]
    pub rate_limit: u32,
    /// Memory limit per worker in MB (0: none).
    #[arg(long, value_name = "MB", default_value_t = 2048)]
    pub worker_memory_mb: u64,
    /// Seconds a SIGTERM waits for running conversions before re-queuing them.
    #[arg(long, value_name = "S", default_value_t = 20)]
    pub grace: u64,
    /// Seconds a worker's claim lasts without a heartbeat; one silent for half of it while
    /// converting is killed and replaced.
    #[arg(long, value_name = "S", default_value_t = 30, value_parser = clap::value_parser!(u64).range(1..=3600))]
    pub worker_lease: u64,
    /// Do not queue and publish the shipped examples on the first start.
    #[arg(long)]
    pub no_examples: bool,
}

/// `platener worker`.
#[derive(Debug, Args)]
pub struct WorkerArgs {
    /// Database URL (sqlite://FILE or postgres://…), the same as the server's.
    #[arg(long, value_name = "URL")]
    pub database: String,
    /// Memory limit in MB (0: none).
    #[arg(long, value_name = "MB", default_value_t = 2048)]
    pub memory_mb: u64,
    /// Give up a model after this many seconds (0: never).
    #[arg(long, value_name = "S", default_value_t = 60.0)]
    pub timeout: f64,
    /// This worker's name in the database (default: host, process id, random suffix).
    #[arg(long)]
    pub name: Option<String>,
    /// Exit when standard input closes (how `serve` keeps its workers from outliving it).
    #[arg(long)]
    pub lifeline: bool,
    /// Seconds a claimed job stays this worker's without a heartbeat (one every quarter).
    #[arg(long, value_name = "S", default_value_t = 30, value_parser = clap::value_parser!(u64).range(1..=3600))]
    pub lease: u64,
}

/// Logs at info level on stderr, coloured only on a terminal (so log files stay plain text).
fn init_logs() {
    use std::io::IsTerminal as _;
    let _ = tracing_subscriber::fmt()
        .with_max_level(tracing::Level::INFO)
        .with_ansi(std::io::stderr().is_terminal())
        .with_writer(std::io::stderr)
        .try_init();
}

/// Whether the test-only model names are honoured (`PLATENER_TEST_HOOKS=1`; never in use).
fn test_hooks() -> bool {
    std::env::var("PLATENER_TEST_HOOKS").is_ok_and(|v| v == "1")
}

/// Runs the server until SIGTERM or Ctrl-C.
pub fn serve(args: &ServeArgs) -> anyhow::Result<()> {
    init_logs();
    let exe = std::env::current_exe()?;
    let mut config = ServeConfig::new(exe);
    config.addr = args.addr;
    config.data.clone_from(&args.data);
    config.database.clone_from(&args.database);
    if let Some(n) = args.workers {
        config.workers = n;
    }
    config.max_upload_mb = args.max_upload_mb;
    config.max_triangles = args.max_triangles;
    config.timeout = args.timeout;
    config.max_queue = args.max_queue;
    config.rate_limit = args.rate_limit;
    config.worker_memory_mb = args.worker_memory_mb;
    config.grace = Duration::from_secs(args.grace);
    config.worker_lease = Duration::from_secs(args.worker_lease);
    config.examples = !args.no_examples;
    config.test_hooks = test_hooks();
    platener_web::serve(config, |addr| {
        // The one line on stdout: scripts and tests read the address from it.
        println!("platener: serving on http://{addr}");
    })?;
    Ok(())
}

/// Runs a worker until its lifeline closes, a conversion leaves a thread behind (exit code
/// [`platener_web::worker::EXIT_RESTART`]: replace me) or the database fails.
pub fn worker(args: &WorkerArgs) -> anyhow::Result<u8> {
    init_logs();
    let mut config = WorkerConfig::new(args.database.clone());
    config.memory_mb = args.memory_mb;
    config.timeout = (args.timeout > 0.0).then(|| Duration::from_secs_f64(args.timeout));
    config.name.clone_from(&args.name);
    config.lifeline = args.lifeline;
    config.test_hooks = test_hooks();
    config.lease_ms = i64::try_from(args.lease.saturating_mul(1000)).unwrap_or(i64::MAX);
    match platener_web::worker::run(&config)? {
        platener_web::worker::Stop::Lifeline => Ok(0),
        platener_web::worker::Stop::Restart => Ok(platener_web::worker::EXIT_RESTART),
    }
}
