//! `GET /metrics` (Prometheus text) and the in-memory counters behind it.

use std::collections::BTreeMap;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::{Arc, Mutex};

use axum::Router;
use axum::extract::{Request, State};
use axum::http::{StatusCode, header};
use axum::middleware::Next;
use axum::response::{IntoResponse, Response};
use axum::routing::get;

use super::App;
use super::error::ApiResult;

/// The routes of this resource.
pub fn routes() -> Router<Arc<App>> {
    Router::new().route("/metrics", get(metrics))
}

/// Counters the server keeps in memory (the rest of /metrics comes from the database).
#[derive(Debug, Default)]
pub struct Metrics {
    /// Responses by status code.
    pub responses: Mutex<BTreeMap<u16, u64>>,
    /// Uploads and recuts accepted.
    pub accepted: AtomicU64,
}

/// Counts every response by status.
pub async fn count_requests(State(app): State<Arc<App>>, request: Request, next: Next) -> Response {
    let response = next.run(request).await;
    let mut counts = app
        .metrics
        .responses
        .lock()
        .unwrap_or_else(std::sync::PoisonError::into_inner);
    *counts.entry(response.status().as_u16()).or_insert(0) += 1;
    response
}

/// Upper bounds of the conversion time histogram, ms.
const BUCKETS_MS: [i64; 8] = [500, 1000, 2000, 5000, 10_000, 30_000, 60_000, 120_000];

/// `GET /metrics`: Prometheus text.
pub async fn metrics(State(app): State<Arc<App>>) -> ApiResult<Response> {
    use std::fmt::Write as _;
    let mut s = String::new();
    let _ = writeln!(s, "# HELP platener_http_responses_total Responses by status code.");
    let _ = writeln!(s, "# TYPE platener_http_responses_total counter");
    let responses = app
        .metrics
        .responses
        .lock()
        .unwrap_or_else(std::sync::PoisonError::into_inner)
        .clone();
    for (code, n) in responses {
        let _ = writeln!(s, "platener_http_responses_total{{status=\"{code}\"}} {n}");
    }
    let _ = writeln!(s, "# TYPE platener_uploads_accepted_total counter");
    let _ = writeln!(
        s,
        "platener_uploads_accepted_total {}",
        app.metrics.accepted.load(Ordering::Relaxed)
    );
    let _ = writeln!(s, "# HELP platener_conversions Conversions in the database by status.");
    let _ = writeln!(s, "# TYPE platener_conversions gauge");
    for (status, n) in app.db.counts().await? {
        let _ = writeln!(s, "platener_conversions{{status=\"{status}\"}} {n}");
    }
    let _ = writeln!(s, "# TYPE platener_queue_length gauge");
    let _ = writeln!(s, "platener_queue_length {}", app.db.queue_len().await?);
    let _ = writeln!(s, "# TYPE platener_workers gauge");
    let _ = writeln!(s, "platener_workers {}", app.roster.census().live);
    let (counts, n, total) = app.db.durations(&BUCKETS_MS).await?;
    let _ = writeln!(
        s,
        "# HELP platener_conversion_seconds Time from a worker's first claim to the result."
    );
    let _ = writeln!(s, "# TYPE platener_conversion_seconds histogram");
    for (b, c) in BUCKETS_MS.iter().zip(&counts) {
        let _ = writeln!(
            s,
            "platener_conversion_seconds_bucket{{le=\"{}\"}} {c}",
            *b as f64 / 1000.0
        );
    }
    let _ = writeln!(s, "platener_conversion_seconds_bucket{{le=\"+Inf\"}} {n}");
    let _ = writeln!(s, "platener_conversion_seconds_sum {}", total as f64 / 1000.0);
    let _ = writeln!(s, "platener_conversion_seconds_count {n}");
    Ok((
        StatusCode::OK,
        [(header::CONTENT_TYPE, "text/plain; version=0.0.4; charset=utf-8")],
        s,
    )
        .into_response())
}
