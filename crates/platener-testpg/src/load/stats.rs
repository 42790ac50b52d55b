//! What the load run counts and measures, and its JSON summary.

use std::collections::BTreeMap;

use serde::Serialize;

/// Counts and timings of one client, merged into the run's at the end.
#[derive(Debug, Default)]
pub(crate) struct Recorder {
    pub(crate) requests: u64,
    pub(crate) failed_requests: u64,
    /// Failure descriptions (`upload: HTTP 500`) and how often each happened.
    pub(crate) errors: BTreeMap<String, u64>,
    pub(crate) submitted: u64,
    pub(crate) done: u64,
    pub(crate) failed: u64,
    pub(crate) status_ms: Vec<f64>,
    pub(crate) upload_ms: Vec<f64>,
    pub(crate) plan_ms: Vec<f64>,
    pub(crate) conversion_ms: Vec<f64>,
    pub(crate) plan_bytes: u64,
}

impl Recorder {
    /// Records a failed request (or a broken promise of the API) under `what`.
    pub(crate) fn error(&mut self, what: String) {
        self.failed_requests += 1;
        *self.errors.entry(what).or_default() += 1;
    }

    /// Adds another client's figures.
    pub(crate) fn merge(&mut self, other: Recorder) {
        self.requests += other.requests;
        self.failed_requests += other.failed_requests;
        for (what, n) in other.errors {
            *self.errors.entry(what).or_default() += n;
        }
        self.submitted += other.submitted;
        self.done += other.done;
        self.failed += other.failed;
        self.status_ms.extend(other.status_ms);
        self.upload_ms.extend(other.upload_ms);
        self.plan_ms.extend(other.plan_ms);
        self.conversion_ms.extend(other.conversion_ms);
        self.plan_bytes += other.plan_bytes;
    }
}

/// The JSON the benchmark prints.
#[derive(Debug, Clone, PartialEq, Serialize, serde::Deserialize)]
pub struct Summary {
    /// Concurrent clients.
    pub clients: usize,
    /// Conversions submitted, done (plan downloaded) and failed (by the server, or timed out).
    pub conversions: Conversions,
    /// HTTP requests made and how many failed (transport error, unexpected status or body).
    pub requests: Requests,
    /// What failed, and how often.
    pub errors: BTreeMap<String, u64>,
    /// Wall-clock length of the run.
    pub seconds: f64,
    /// Finished conversions (done or failed) per second of the run.
    pub conversions_per_second: f64,
    /// Latency of `GET /api/conversions/{id}`.
    pub status_reads: Latency,
    /// Latency of accepted uploads (`POST /api/conversions`, to the `202` and its body).
    pub uploads: Latency,
    /// Latency of plan downloads (`GET …/plan.zip`, to the last byte).
    pub downloads: Latency,
    /// Upload to downloaded plan, per conversion that ended done.
    pub conversion: Latency,
    /// Bytes of plan ZIPs downloaded.
    pub plan_bytes: u64,
    /// Peak resident memory of the server process and its descendants (MB), when its pid was given.
    pub server_peak_rss_mb: Option<f64>,
    /// Peak resident memory of the server process alone (MB).
    pub server_process_peak_rss_mb: Option<f64>,
    /// Peak resident memory of its descendants together, the worker processes (MB).
    pub workers_peak_rss_mb: Option<f64>,
}

/// See [`Summary::conversions`].
#[derive(Debug, Clone, PartialEq, Eq, Serialize, serde::Deserialize)]
pub struct Conversions {
    /// Accepted with `202`.
    pub submitted: u64,
    /// Ended with `done` and a plan downloaded.
    pub done: u64,
    /// Ended with `failed`, or not in time, or broken off by a failed request.
    pub failed: u64,
}

/// See [`Summary::requests`].
#[derive(Debug, Clone, PartialEq, Eq, Serialize, serde::Deserialize)]
pub struct Requests {
    /// Requests sent.
    pub total: u64,
    /// Requests that failed.
    pub failed: u64,
}

/// A latency distribution in milliseconds (nearest-rank percentiles; zeros when empty).
#[derive(Debug, Clone, PartialEq, Serialize, serde::Deserialize)]
pub struct Latency {
    /// Samples.
    pub count: usize,
    /// Median.
    pub p50_ms: f64,
    /// 99th percentile.
    pub p99_ms: f64,
    /// Largest.
    pub max_ms: f64,
}

impl Latency {
    /// The distribution of `samples`.
    pub(crate) fn of(mut samples: Vec<f64>) -> Latency {
        samples.sort_by(f64::total_cmp);
        let rank = |p: f64| {
            let i = ((p * samples.len() as f64).ceil() as usize).clamp(1, samples.len().max(1)) - 1;
            samples.get(i).copied().map_or(0.0, round3)
        };
        Latency {
            count: samples.len(),
            p50_ms: rank(0.5),
            p99_ms: rank(0.99),
            max_ms: rank(1.0),
        }
    }
}

/// Milliseconds to the microsecond, so the JSON stays readable.
pub(crate) fn round3(x: f64) -> f64 {
    (x * 1000.0).round() / 1000.0
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn nearest_rank_percentiles() {
        let l = Latency::of((1..=100).rev().map(f64::from).collect());
        assert_eq!((l.count, l.p50_ms, l.p99_ms, l.max_ms), (100, 50.0, 99.0, 100.0));
        let one = Latency::of(vec![7.0]);
        assert_eq!((one.p50_ms, one.p99_ms, one.max_ms), (7.0, 7.0, 7.0));
        let none = Latency::of(Vec::new());
        assert_eq!((none.count, none.p50_ms, none.p99_ms), (0, 0.0, 0.0));
    }
}
