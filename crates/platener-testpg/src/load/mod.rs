//! The load benchmark client: N concurrent simulated users of `platener serve`.
//!
//! Each user uploads a model (`POST /api/conversions`), follows its server-sent events until
//! `done` or `failed`, reads `GET /api/conversions/{id}` meanwhile (the latency measured),
//! checks the status agrees with the last event and downloads `plan.zip`. The run's figures
//! (throughput, status-read latency, failed requests, the server's peak memory) come back as a
//! [`Summary`]. Only loopback addresses are accepted: this measures a server on this machine.

pub mod bench;
mod client;
pub mod memory;
pub mod sse;
mod stats;
pub mod zipdir;

use std::sync::Arc;
use std::time::{Duration, Instant};

pub use stats::{Conversions, Latency, Requests, Summary};

use stats::{Recorder, round3};

/// What to run.
#[derive(Debug, Clone)]
pub struct Config {
    /// The server, e.g. `http://127.0.0.1:3000` (loopback only).
    pub base_url: String,
    /// Concurrent users.
    pub clients: usize,
    /// Conversions each user runs, one after the other.
    pub conversions_per_client: usize,
    /// The model's bytes.
    pub model: Vec<u8>,
    /// The model's file name in the upload.
    pub model_name: String,
    /// How often a user reads the status while following events.
    pub status_interval: Duration,
    /// At most this many status reads while following events (0: no limit), besides the one
    /// before and the one after: "a few", so that 500 clients load the server like 500 users
    /// with a page open, not like a status-polling storm.
    pub status_reads_while_streaming: usize,
    /// How long one conversion may take, upload to plan, before it counts as failed.
    pub timeout: Duration,
    /// The server's process id, to sample its (and its workers') memory.
    pub server_pid: Option<u32>,
}

/// Why a run could not start.
#[derive(Debug, thiserror::Error)]
pub enum LoadError {
    /// The URL is not `http://` on a loopback address.
    #[error("{0}: the load client only targets http:// on a loopback address (127.0.0.0/8, localhost, [::1])")]
    NotLoopback(String),
    /// Zero clients or conversions.
    #[error("nothing to do: clients and conversions per client must be at least 1")]
    NothingToDo,
    /// The HTTP client could not be built.
    #[error("could not build the HTTP client: {0}")]
    Client(#[from] reqwest::Error),
}

/// Runs the load and summarises it.
pub async fn run(mut config: Config) -> Result<Summary, LoadError> {
    check_loopback(&config.base_url)?;
    if config.clients == 0 || config.conversions_per_client == 0 {
        return Err(LoadError::NothingToDo);
    }
    config.base_url = config.base_url.trim_end_matches('/').to_string();
    // No proxy: an HTTP_PROXY of the environment must not take loopback traffic elsewhere.
    let http = reqwest::Client::builder().no_proxy().build()?;
    let config = Arc::new(config);
    let sampler = config.server_pid.map(memory::Sampler::start);
    let started = Instant::now();
    let tasks: Vec<_> = (0..config.clients)
        .map(|_| tokio::spawn(client::run_client(http.clone(), Arc::clone(&config))))
        .collect();
    let mut total = Recorder::default();
    for task in tasks {
        match task.await {
            Ok(rec) => total.merge(rec),
            Err(e) => total.error(format!("client task: {e}")),
        }
    }
    let seconds = started.elapsed().as_secs_f64();
    let peaks = sampler.map(memory::Sampler::finish);
    Ok(summarise(&config, total, seconds, peaks))
}

fn summarise(config: &Config, total: Recorder, seconds: f64, peaks: Option<memory::Peaks>) -> Summary {
    let finished = (total.done + total.failed) as f64;
    Summary {
        clients: config.clients,
        conversions: Conversions {
            submitted: total.submitted,
            done: total.done,
            failed: total.failed,
        },
        requests: Requests {
            total: total.requests,
            failed: total.failed_requests,
        },
        errors: total.errors,
        seconds: round3(seconds),
        conversions_per_second: if seconds > 0.0 { round3(finished / seconds) } else { 0.0 },
        status_reads: Latency::of(total.status_ms),
        uploads: Latency::of(total.upload_ms),
        downloads: Latency::of(total.plan_ms),
        conversion: Latency::of(total.conversion_ms),
        plan_bytes: total.plan_bytes,
        server_peak_rss_mb: peaks.map(|p| p.tree_mb),
        server_process_peak_rss_mb: peaks.map(|p| p.root_mb),
        workers_peak_rss_mb: peaks.map(|p| p.descendants_mb),
    }
}

/// Accepts only `http://` URLs whose host is a loopback address or `localhost`.
pub fn check_loopback(url: &str) -> Result<(), LoadError> {
    let refuse = || LoadError::NotLoopback(url.to_string());
    let parsed = reqwest::Url::parse(url).map_err(|_| refuse())?;
    let loopback = match parsed.host() {
        Some(url::Host::Domain(d)) => d.eq_ignore_ascii_case("localhost"),
        Some(url::Host::Ipv4(ip)) => ip.is_loopback(),
        Some(url::Host::Ipv6(ip)) => ip.is_loopback(),
        None => false,
    };
    if parsed.scheme() == "http" && loopback {
        Ok(())
    } else {
        Err(refuse())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn only_loopback_http_is_accepted() {
        for ok in [
            "http://127.0.0.1:3000",
            "http://127.1.2.3/",
            "http://localhost:8080",
            "http://[::1]:3000",
        ] {
            assert!(check_loopback(ok).is_ok(), "{ok}");
        }
        for bad in [
            "http://10.0.0.1:3000",
            "https://127.0.0.1",
            "http://example.com",
            "127.0.0.1:3000",
            "",
        ] {
            let err = check_loopback(bad).expect_err(bad);
            assert!(err.to_string().contains("loopback"), "{err}");
        }
    }
}
