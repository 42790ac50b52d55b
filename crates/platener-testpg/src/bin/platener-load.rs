//! `platener-load`: the load benchmark client for `platener serve` (issue 17).
//!
//! Runs N concurrent users against a server on this machine and prints a JSON summary
//! (throughput, status-read latency p50/p99, failed requests, the server's peak memory when
//! `--server-pid` is given). Exits 1 when any request or conversion failed, 2 when it could not
//! run, so scripts can require a clean run.

use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Duration;

use clap::Parser;
use platener_testpg::load::{Config, run};

/// The example box shipped with platener: the model the benchmark uploads.
const EXAMPLE_BOX: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples/box-3mm.stl");

/// Load benchmark client for `platener serve` (loopback only).
#[derive(Debug, Parser)]
#[command(name = "platener-load", version)]
struct Args {
    /// The server's base URL.
    #[arg(long, default_value = "http://127.0.0.1:3000")]
    url: String,
    /// Concurrent clients.
    #[arg(long, default_value_t = 10)]
    clients: usize,
    /// Conversions per client, one after the other.
    #[arg(long, default_value_t = 1)]
    per_client: usize,
    /// The model to upload (default: the example box).
    #[arg(long)]
    model: Option<PathBuf>,
    /// Milliseconds between status reads while a conversion runs.
    #[arg(long, default_value_t = 250)]
    status_interval_ms: u64,
    /// Seconds one conversion may take before it counts as failed.
    #[arg(long, default_value_t = 600)]
    timeout_s: u64,
    /// The server's process id: its memory and its workers' is sampled during the run.
    #[arg(long)]
    server_pid: Option<u32>,
}

fn main() -> ExitCode {
    let args = Args::parse();
    let path = args.model.clone().unwrap_or_else(|| PathBuf::from(EXAMPLE_BOX));
    let model = match std::fs::read(&path) {
        Ok(bytes) => bytes,
        Err(e) => return fail(&format!("cannot read the model {}: {e}", path.display())),
    };
    let config = Config {
        base_url: args.url,
        clients: args.clients,
        conversions_per_client: args.per_client,
        model,
        model_name: path
            .file_name()
            .map_or_else(|| "model.stl".into(), |n| n.to_string_lossy().into_owned()),
        status_interval: Duration::from_millis(args.status_interval_ms.max(1)),
        timeout: Duration::from_secs(args.timeout_s.max(1)),
        server_pid: args.server_pid,
    };
    let runtime = match tokio::runtime::Runtime::new() {
        Ok(runtime) => runtime,
        Err(e) => return fail(&format!("cannot start the async runtime: {e}")),
    };
    let summary = match runtime.block_on(run(config)) {
        Ok(summary) => summary,
        Err(e) => return fail(&e.to_string()),
    };
    match serde_json::to_string_pretty(&summary) {
        Ok(json) => println!("{json}"),
        Err(e) => return fail(&format!("cannot write the summary: {e}")),
    }
    let clean = summary.requests.failed == 0 && summary.conversions.failed == 0;
    if clean { ExitCode::SUCCESS } else { ExitCode::from(1) }
}

fn fail(message: &str) -> ExitCode {
    eprintln!("platener-load: {message}");
    ExitCode::from(2)
}
