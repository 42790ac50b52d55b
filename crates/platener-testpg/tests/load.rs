//! The load client against a tiny fake server that implements the four endpoints it uses
//! trivially, so the client is known to count and measure right before the real server exists.

use std::convert::Infallible;
use std::sync::Arc;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::Duration;

use axum::extract::{Multipart, Path, State};
use axum::http::{StatusCode, header};
use axum::response::sse::{Event, Sse};
use axum::response::{IntoResponse, Response};
use axum::routing::{get, post};
use axum::{Json, Router};
use futures_util::Stream;
use platener_testpg::load::{Config, Conversions, Summary, run};
use serde_json::json;

/// What the fake plan download returns: a stored ZIP holding `plan.json` (`{"parts":[]}`),
/// written by Python's zipfile, since the client checks the ZIP's directory.
const FAKE_ZIP: &[u8] = b"\x50\x4b\x03\x04\x14\x00\x00\x00\x00\x00\x00\x00\x78\x5d\x2e\x53\
    \x97\x53\x0c\x00\x00\x00\x0c\x00\x00\x00\x09\x00\x00\x00\x70\x6c\
    \x61\x6e\x2e\x6a\x73\x6f\x6e\x7b\x22\x70\x61\x72\x74\x73\x22\x3a\
    \x5b\x5d\x7d\x50\x4b\x01\x02\x14\x03\x14\x00\x00\x00\x00\x00\x00\
    \x00\x78\x5d\x2e\x53\x97\x53\x0c\x00\x00\x00\x0c\x00\x00\x00\x09\
    \x00\x00\x00\x00\x00\x00\x00\x00\x00\x00\x00\x80\x01\x00\x00\x00\
    \x00\x70\x6c\x61\x6e\x2e\x6a\x73\x6f\x6e\x50\x4b\x05\x06\x00\x00\
    \x00\x00\x01\x00\x01\x00\x37\x00\x00\x00\x33\x00\x00\x00\x00\x00";
/// The example box the binary uploads by default.
const EXAMPLE_BOX: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples/box-3mm.stl");

/// The fake server's behaviour and what it saw.
#[derive(Default)]
struct Fake {
    /// The size every upload's `model` must have.
    model_len: usize,
    /// Conversions whose number is a multiple of this end `failed` (0: none).
    fail_every: usize,
    /// The conversion whose status reads answer 500.
    broken_status: Option<usize>,
    uploads: AtomicUsize,
    bad_uploads: AtomicUsize,
    status_reads: AtomicUsize,
    event_streams: AtomicUsize,
    plans: AtomicUsize,
}

impl Fake {
    fn number(id: &str) -> usize {
        id.strip_prefix("c_").and_then(|n| n.parse().ok()).unwrap_or(0)
    }

    fn ending(&self, id: &str) -> &'static str {
        let n = Fake::number(id);
        if self.fail_every > 0 && n.is_multiple_of(self.fail_every) {
            "failed"
        } else {
            "done"
        }
    }
}

async fn upload(State(fake): State<Arc<Fake>>, mut form: Multipart) -> Response {
    let mut model = None;
    while let Ok(Some(field)) = form.next_field().await {
        if field.name() == Some("model") {
            model = field.bytes().await.ok();
        }
    }
    if model.map(|m| m.len()) != Some(fake.model_len) {
        fake.bad_uploads.fetch_add(1, Ordering::SeqCst);
        return (StatusCode::BAD_REQUEST, "no model").into_response();
    }
    let id = format!("c_{}", fake.uploads.fetch_add(1, Ordering::SeqCst) + 1);
    let location = format!("/api/conversions/{id}");
    let body = json!({ "id": id, "status": "queued", "delete_token": "secret" });
    (StatusCode::ACCEPTED, [(header::LOCATION, location)], Json(body)).into_response()
}

async fn status(State(fake): State<Arc<Fake>>, Path(id): Path<String>) -> Response {
    fake.status_reads.fetch_add(1, Ordering::SeqCst);
    if fake.broken_status == Some(Fake::number(&id)) {
        return (StatusCode::INTERNAL_SERVER_ERROR, "broken").into_response();
    }
    Json(json!({ "id": id, "status": fake.ending(&id) })).into_response()
}

/// A step, a method, then the last event, 20 ms apart (so status reads happen meanwhile).
async fn events(
    State(fake): State<Arc<Fake>>,
    Path(id): Path<String>,
) -> Sse<impl Stream<Item = Result<Event, Infallible>>> {
    fake.event_streams.fetch_add(1, Ordering::SeqCst);
    let last = fake.ending(&id);
    let events = vec![
        Event::default().event("step").data(r#"{"name":"read","ms":1.0}"#),
        Event::default()
            .event("method")
            .data(r#"{"method":"plate","status":"done","score":0.9}"#),
        Event::default().event(last).data("{}"),
    ];
    Sse::new(futures_util::stream::unfold(
        events.into_iter(),
        |mut rest| async move {
            tokio::time::sleep(Duration::from_millis(20)).await;
            rest.next().map(|event| (Ok(event), rest))
        },
    ))
}

async fn plan(State(fake): State<Arc<Fake>>, Path(id): Path<String>) -> Response {
    fake.plans.fetch_add(1, Ordering::SeqCst);
    if fake.ending(&id) != "done" {
        return StatusCode::NOT_FOUND.into_response();
    }
    ([(header::CONTENT_TYPE, "application/zip")], FAKE_ZIP).into_response()
}

/// Serves the fake on a free port of 127.0.0.1; its base URL.
async fn serve(fake: Arc<Fake>) -> String {
    let app = Router::new()
        .route("/api/conversions", post(upload))
        .route("/api/conversions/{id}", get(status))
        .route("/api/conversions/{id}/events", get(events))
        .route("/api/conversions/{id}/plan.zip", get(plan))
        .with_state(fake);
    let listener = tokio::net::TcpListener::bind("127.0.0.1:0").await.expect("bind");
    let addr = listener.local_addr().expect("addr");
    tokio::spawn(async move { axum::serve(listener, app).await.expect("serve") });
    format!("http://{addr}")
}

fn config(base_url: String, clients: usize, per_client: usize) -> Config {
    Config {
        base_url,
        clients,
        conversions_per_client: per_client,
        model: b"solid fake\nendsolid fake\n".to_vec(),
        model_name: "fake.stl".into(),
        status_interval: Duration::from_millis(5),
        status_reads_while_streaming: 0,
        timeout: Duration::from_secs(60),
        server_pid: Some(std::process::id()),
    }
}

fn runtime() -> tokio::runtime::Runtime {
    tokio::runtime::Builder::new_multi_thread()
        .worker_threads(2)
        .enable_all()
        .build()
        .expect("runtime")
}

#[test]
fn ten_clients_two_conversions_each_all_done() {
    let fake = Arc::new(Fake {
        model_len: 25,
        ..Fake::default()
    });
    let summary = runtime().block_on(async {
        let url = serve(Arc::clone(&fake)).await;
        run(config(url, 10, 2)).await.expect("run")
    });
    assert_eq!(
        summary.conversions,
        Conversions {
            submitted: 20,
            done: 20,
            failed: 0
        }
    );
    assert_eq!(summary.requests.failed, 0, "{:?}", summary.errors);
    assert!(summary.errors.is_empty());
    let (uploads, streams, plans) = (
        fake.uploads.load(Ordering::SeqCst),
        fake.event_streams.load(Ordering::SeqCst),
        fake.plans.load(Ordering::SeqCst),
    );
    let reads = fake.status_reads.load(Ordering::SeqCst);
    assert_eq!(
        (uploads, streams, plans, fake.bad_uploads.load(Ordering::SeqCst)),
        (20, 20, 20, 0)
    );
    // Every request the client counted reached the server, and every status read was timed.
    assert_eq!(summary.requests.total as usize, uploads + streams + plans + reads);
    assert_eq!(summary.status_reads.count, reads);
    assert_eq!((summary.uploads.count, summary.downloads.count), (20, 20));
    for l in [&summary.uploads, &summary.downloads] {
        assert!(0.0 < l.p50_ms && l.p50_ms <= l.p99_ms && l.p99_ms <= l.max_ms, "{l:?}");
    }
    assert!(
        reads >= 40,
        "one read before the events and one after, per conversion: {reads}"
    );
    let l = &summary.status_reads;
    assert!(0.0 < l.p50_ms && l.p50_ms <= l.p99_ms && l.p99_ms <= l.max_ms, "{l:?}");
    // A conversion spans at least the fake's three 20 ms event gaps.
    assert_eq!(summary.conversion.count, 20);
    assert!(summary.conversion.p50_ms >= 60.0, "{:?}", summary.conversion);
    assert_eq!(summary.plan_bytes, 20 * FAKE_ZIP.len() as u64);
    assert!(summary.conversions_per_second > 0.0);
    assert!(
        summary.server_peak_rss_mb.is_some_and(|mb| mb > 1.0),
        "{:?}",
        summary.server_peak_rss_mb
    );
    // The "server" is this test process: all of it is the process, none is workers.
    assert!(summary.server_process_peak_rss_mb.is_some_and(|mb| mb > 1.0));
    assert!(summary.workers_peak_rss_mb.is_some());
}

#[test]
fn failed_conversions_and_failed_requests_are_counted_apart() {
    let fake = Arc::new(Fake {
        model_len: 25,
        fail_every: 5,
        broken_status: Some(3),
        ..Fake::default()
    });
    let summary = runtime().block_on(async {
        let url = serve(Arc::clone(&fake)).await;
        run(Config {
            server_pid: None,
            ..config(url, 10, 1)
        })
        .await
        .expect("run")
    });
    // c_5 and c_10 end failed; c_3's status reads fail but its events and plan work.
    assert_eq!(
        summary.conversions,
        Conversions {
            submitted: 10,
            done: 8,
            failed: 2
        }
    );
    assert_eq!(
        fake.plans.load(Ordering::SeqCst),
        8,
        "no plan is asked for a failed conversion"
    );
    let broken = summary.errors.get("status: HTTP 500").copied().unwrap_or(0);
    assert!(broken >= 2, "{:?}", summary.errors);
    assert_eq!(summary.errors.len(), 1, "{:?}", summary.errors);
    assert_eq!(summary.requests.failed, broken);
    let reads = fake.status_reads.load(Ordering::SeqCst);
    assert_eq!(
        summary.status_reads.count as u64,
        reads as u64 - broken,
        "only answered reads are timed"
    );
    assert_eq!(summary.server_peak_rss_mb, None);
    assert_eq!((summary.uploads.count, summary.downloads.count), (10, 8));
}

#[test]
fn the_binary_uploads_the_example_box_and_prints_json() {
    let model_len = std::fs::metadata(EXAMPLE_BOX).expect("the example box").len() as usize;
    let fake = Arc::new(Fake {
        model_len,
        ..Fake::default()
    });
    let runtime = runtime();
    let url = runtime.block_on(serve(Arc::clone(&fake)));
    let output = std::process::Command::new(env!("CARGO_BIN_EXE_platener-load"))
        .args([
            "--url",
            &url,
            "--clients",
            "10",
            "--status-interval-ms",
            "5",
            "--timeout-s",
            "60",
        ])
        .output()
        .expect("platener-load runs");
    let stdout = String::from_utf8_lossy(&output.stdout);
    assert!(
        output.status.success(),
        "{:?}\n{stdout}\n{}",
        output.status,
        String::from_utf8_lossy(&output.stderr)
    );
    let summary: Summary = serde_json::from_str(&stdout).expect("a JSON summary");
    assert_eq!(summary.clients, 10);
    assert_eq!(
        summary.conversions,
        Conversions {
            submitted: 10,
            done: 10,
            failed: 0
        }
    );
    assert_eq!(summary.requests.failed, 0);
    assert_eq!(fake.uploads.load(Ordering::SeqCst), 10);
    assert_eq!(
        fake.bad_uploads.load(Ordering::SeqCst),
        0,
        "every upload was the example box"
    );
}

#[test]
fn the_binary_refuses_other_hosts_and_reports_failures_in_its_exit_code() {
    let refused = std::process::Command::new(env!("CARGO_BIN_EXE_platener-load"))
        .args(["--url", "http://192.0.2.1:3000"])
        .output()
        .expect("runs");
    assert_eq!(refused.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&refused.stderr).contains("loopback"));

    let fake = Arc::new(Fake {
        model_len: 1,
        ..Fake::default()
    });
    let runtime = runtime();
    let url = runtime.block_on(serve(Arc::clone(&fake)));
    let output = std::process::Command::new(env!("CARGO_BIN_EXE_platener-load"))
        .args(["--url", &url, "--clients", "2"])
        .output()
        .expect("runs");
    // The fake wants a 1-byte model: both uploads are refused, nothing is submitted.
    assert_eq!(output.status.code(), Some(1));
    let summary: Summary = serde_json::from_slice(&output.stdout).expect("a JSON summary");
    assert_eq!(
        summary.conversions,
        Conversions {
            submitted: 0,
            done: 0,
            failed: 0
        }
    );
    assert_eq!(summary.requests.failed, 2);
    assert_eq!(summary.errors.get("upload: HTTP 400"), Some(&2));
}

#[test]
fn status_reads_while_streaming_are_capped() {
    let fake = Arc::new(Fake {
        model_len: 25,
        ..Fake::default()
    });
    let summary = runtime().block_on(async {
        let url = serve(Arc::clone(&fake)).await;
        run(Config {
            // A read every millisecond for the fake's 60 ms of events would be dozens.
            status_interval: Duration::from_millis(1),
            status_reads_while_streaming: 2,
            ..config(url, 5, 1)
        })
        .await
        .expect("run")
    });
    assert_eq!(summary.requests.failed, 0, "{:?}", summary.errors);
    let reads = fake.status_reads.load(Ordering::SeqCst);
    // One before the events, at most two while streaming, one after: per conversion.
    assert!((10..=20).contains(&reads), "{reads}");
    assert_eq!(summary.status_reads.count, reads);
}
