//! The load benchmark, bounded: 20 clients against the real `platener serve` on SQLite
//! (`platener-load bench`'s code path, issue 17). Every request must succeed and every
//! conversion end done with a whole plan ZIP; nothing asserts on speed. And the event stream
//! through the server's one poller: a client joining mid-conversion sees what an early one saw.

mod web_support;

use std::io::{Read as _, Write as _};
use std::net::TcpStream;
use std::time::Duration;

use platener_testpg::load::Config;
use platener_testpg::load::bench::{BenchConfig, Database, bench};
use web_support::{PATIENCE, Server, example_box, parse, request};

const EXAMPLE_BOX: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples/box-3mm.stl");

#[test]
fn twenty_clients_on_sqlite_all_done_with_no_failed_request() {
    let model = std::fs::read(EXAMPLE_BOX).expect("the example box");
    let config = BenchConfig {
        platener: env!("CARGO_BIN_EXE_platener").into(),
        databases: vec![Database::Sqlite],
        clients: vec![20],
        workers: 2,
        client: Config {
            base_url: String::new(),
            clients: 0,
            conversions_per_client: 1,
            model,
            model_name: "box-3mm.stl".into(),
            status_interval: Duration::from_millis(100),
            status_reads_while_streaming: 5,
            // Bounds a hang; a conversion of the box takes well under a second.
            timeout: Duration::from_secs(300),
            server_pid: None,
        },
    };
    let runs = bench(&config, |_| {}).expect("the benchmark runs");
    let [run] = &runs[..] else { panic!("one run: {runs:?}") };
    let s = &run.summary;
    assert_eq!(s.requests.failed, 0, "{:?}", s.errors);
    assert_eq!(
        (s.conversions.submitted, s.conversions.done, s.conversions.failed),
        (20, 20, 0)
    );
    // Every client uploaded, streamed to `done`, read its status and downloaded a ZIP whose
    // directory lists plan.json (the client checks it).
    assert_eq!((s.uploads.count, s.downloads.count, s.conversion.count), (20, 20, 20));
    assert!(s.status_reads.count >= 40, "{:?}", s.status_reads);
    assert!(s.plan_bytes > 20 * 1000, "{}", s.plan_bytes);
    assert!(s.workers_peak_rss_mb.is_some_and(|mb| mb > 1.0), "{s:?}");
}

/// The event lines of an SSE body (keep-alive comments left out).
fn event_lines(body: &str) -> Vec<String> {
    body.lines()
        .filter(|l| !l.is_empty() && !l.starts_with(':'))
        .map(str::to_string)
        .collect()
}

#[test]
fn a_client_joining_mid_conversion_sees_the_same_events_as_one_from_the_start() {
    let dir = tempfile::tempdir().expect("temp dir");
    let server = Server::start(dir.path(), &["--workers", "1", "--no-examples"], &[]);
    let r = server.upload("box-3mm.stl", &example_box(), &[]);
    assert_eq!(r.status, 202, "{}", r.text());
    let id = r.json()["id"].as_str().expect("id").to_string();
    // The early client reads its stream as it comes; the late one connects once the early
    // one has its first step, while the box is still converting.
    let mut early = TcpStream::connect(&server.addr).expect("connect");
    early.set_read_timeout(Some(PATIENCE)).expect("timeout");
    let head = format!(
        "GET /api/conversions/{id}/events HTTP/1.1\r\nHost: {}\r\nConnection: close\r\n\r\n",
        server.addr
    );
    early.write_all(head.as_bytes()).expect("send");
    let mut raw = Vec::new();
    let mut chunk = [0u8; 4096];
    while !String::from_utf8_lossy(&raw).contains("event: step") {
        let n = early.read(&mut chunk).expect("the first event");
        assert!(n > 0, "the stream ended before its first event");
        raw.extend_from_slice(&chunk[..n]);
    }
    let late = request(&server.addr, "GET", &format!("/api/conversions/{id}/events"), &[], b"");
    early.read_to_end(&mut raw).expect("the rest of the stream");
    let early = parse(&raw);
    assert_eq!((early.status, late.status), (200, 200));
    let (early, late) = (event_lines(&early.text()), event_lines(&late.text()));
    assert_eq!(early, late);
    // Every event once, numbered 1, 2, 3, … and the last one is done.
    let ids: Vec<String> = early
        .iter()
        .filter_map(|l| l.strip_prefix("id: "))
        .map(str::to_string)
        .collect();
    let expected: Vec<String> = (1..=ids.len()).map(|i| i.to_string()).collect();
    assert_eq!(ids, expected);
    assert!(ids.len() > 10, "{early:?}");
    let kinds: Vec<&str> = early.iter().filter_map(|l| l.strip_prefix("event: ")).collect();
    assert_eq!(kinds.last(), Some(&"done"), "{kinds:?}");
    assert!(server.terminate(), "the server stops on SIGTERM");
}
