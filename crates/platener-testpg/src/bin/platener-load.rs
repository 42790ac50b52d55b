//! `platener-load`: the load benchmark client for `platener serve` (issue 17).
//!
//! Without a subcommand it runs N concurrent users against a server on this machine and
//! prints a JSON summary (throughput, latencies p50/p99, failed requests, the server's peak
//! memory when `--server-pid` is given). `platener-load bench` starts the real server itself,
//! on SQLite and on a throwaway PostgreSQL cluster, once per client count, and prints the
//! runs as JSON and as a Markdown table (docs/performance.md). Exits 1 when any request or
//! conversion failed, 2 when it could not run, so scripts can require a clean run.

use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Duration;

use clap::{Args, Parser, Subcommand};
use platener_testpg::load::bench::{self, BenchConfig, Database};
use platener_testpg::load::{Config, Summary, run};

/// The example box shipped with platener: the model the benchmark uploads.
const EXAMPLE_BOX: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples/box-3mm.stl");

/// Load benchmark client for `platener serve` (loopback only).
#[derive(Debug, Parser)]
#[command(name = "platener-load", version, args_conflicts_with_subcommands = true)]
struct Cli {
    #[command(subcommand)]
    command: Option<Command>,
    #[command(flatten)]
    run: RunArgs,
}

#[derive(Debug, Subcommand)]
enum Command {
    /// Start `platener serve` per database and client count, and load it.
    Bench(BenchArgs),
}

/// Loading a server that runs already.
#[derive(Debug, Args)]
struct RunArgs {
    /// The server's base URL.
    #[arg(long, default_value = "http://127.0.0.1:3000")]
    url: String,
    /// Concurrent clients.
    #[arg(long, default_value_t = 10)]
    clients: usize,
    /// The server's process id: its memory and its workers' is sampled during the run.
    #[arg(long)]
    server_pid: Option<u32>,
    #[command(flatten)]
    client: ClientArgs,
}

/// `bench`: the whole benchmark.
#[derive(Debug, Args)]
struct BenchArgs {
    /// Client counts, one run each.
    #[arg(long, value_delimiter = ',', default_value = "10,100,500")]
    clients: Vec<usize>,
    /// Databases: sqlite, postgres.
    #[arg(long, value_delimiter = ',', default_value = "sqlite,postgres")]
    database: Vec<String>,
    /// Worker processes per server (default: one per core).
    #[arg(long)]
    workers: Option<usize>,
    /// The `platener` binary (default: beside this program, as `cargo build --release` puts it).
    #[arg(long)]
    platener: Option<PathBuf>,
    #[command(flatten)]
    client: ClientArgs,
}

/// What every client does.
#[derive(Debug, Args)]
struct ClientArgs {
    /// Conversions per client, one after the other.
    #[arg(long, default_value_t = 1)]
    per_client: usize,
    /// The model to upload (default: the example box).
    #[arg(long)]
    model: Option<PathBuf>,
    /// Milliseconds between status reads while a conversion runs.
    #[arg(long, default_value_t = 1000)]
    status_interval_ms: u64,
    /// Status reads at most while a conversion runs (0: no limit), besides one before and one after.
    #[arg(long, default_value_t = 5)]
    status_reads: usize,
    /// Seconds one conversion may take before it counts as failed.
    #[arg(long, default_value_t = 600)]
    timeout_s: u64,
}

impl ClientArgs {
    /// The client configuration, without a server yet.
    fn config(&self) -> Result<Config, String> {
        let path = self.model.clone().unwrap_or_else(|| PathBuf::from(EXAMPLE_BOX));
        let model = std::fs::read(&path).map_err(|e| format!("cannot read the model {}: {e}", path.display()))?;
        Ok(Config {
            base_url: String::new(),
            clients: 0,
            conversions_per_client: self.per_client,
            model,
            model_name: path
                .file_name()
                .map_or_else(|| "model.stl".into(), |n| n.to_string_lossy().into_owned()),
            status_interval: Duration::from_millis(self.status_interval_ms.max(1)),
            status_reads_while_streaming: self.status_reads,
            timeout: Duration::from_secs(self.timeout_s.max(1)),
            server_pid: None,
        })
    }
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    let result = match cli.command {
        Some(Command::Bench(args)) => run_bench(&args),
        None => run_once(cli.run),
    };
    result.unwrap_or_else(|message| {
        eprintln!("platener-load: {message}");
        ExitCode::from(2)
    })
}

fn run_once(args: RunArgs) -> Result<ExitCode, String> {
    let config = Config {
        base_url: args.url,
        clients: args.clients,
        server_pid: args.server_pid,
        ..args.client.config()?
    };
    let runtime = tokio::runtime::Runtime::new().map_err(|e| format!("cannot start the async runtime: {e}"))?;
    let summary = runtime.block_on(run(config)).map_err(|e| e.to_string())?;
    let json = serde_json::to_string_pretty(&summary).map_err(|e| format!("cannot write the summary: {e}"))?;
    println!("{json}");
    Ok(exit_code([&summary]))
}

fn run_bench(args: &BenchArgs) -> Result<ExitCode, String> {
    let databases = args
        .database
        .iter()
        .map(|d| Database::of_name(d).ok_or_else(|| format!("unknown database {d:?} (sqlite, postgres)")))
        .collect::<Result<Vec<_>, _>>()?;
    let platener = match &args.platener {
        Some(p) => p.clone(),
        None => std::env::current_exe()
            .map_err(|e| e.to_string())?
            .with_file_name("platener"),
    };
    let config = BenchConfig {
        platener,
        databases,
        clients: args.clients.clone(),
        workers: args
            .workers
            .unwrap_or_else(|| std::thread::available_parallelism().map_or(1, |n| n.get())),
        client: args.client.config()?,
    };
    let runs = bench::bench(&config, |r| {
        eprintln!(
            "{}",
            bench::markdown(std::slice::from_ref(r)).lines().last().unwrap_or("")
        );
    })
    .map_err(|e| e.to_string())?;
    let json = serde_json::to_string_pretty(&runs).map_err(|e| format!("cannot write the runs: {e}"))?;
    println!("{json}");
    eprintln!("\n{}", bench::markdown(&runs));
    Ok(exit_code(runs.iter().map(|r| &r.summary)))
}

/// 0 when every request and conversion succeeded, else 1.
fn exit_code<'a>(summaries: impl IntoIterator<Item = &'a Summary>) -> ExitCode {
    let clean = summaries
        .into_iter()
        .all(|s| s.requests.failed == 0 && s.conversions.failed == 0);
    if clean { ExitCode::SUCCESS } else { ExitCode::from(1) }
}
