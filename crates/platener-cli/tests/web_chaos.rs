//! No model can stall the service (issue 29): a storm of hostile models against the real
//! `platener serve` with 4 workers and a 3 s time limit, on SQLite and on PostgreSQL (a
//! database of the test's own in the throwaway cluster; skipped with a message when
//! PostgreSQL is not installed, a failure under `PLATENER_REQUIRE_POSTGRES=1`).
//!
//! 40 jobs: 24 boxes that convert, and 16 built to hurt a worker through the test-only model
//! names (`PLATENER_TEST_HOOKS=1`): 4 whose first step never returns and ignores cancellation
//! (`hang`), 4 that stop their whole worker process (`freeze`, SIGSTOP: only the server can
//! end it), 4 that abort their worker and 4 that allocate past its memory limit. Every good
//! job must end done with a plan, every bad one failed with its reason, every worker must be
//! alive and idle afterwards, and a box sent after the storm must convert. Every wait is
//! bounded and fails with a message; nothing asserts on speed.

mod web_support;

use std::collections::BTreeMap;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Mutex, PoisonError};
use std::time::{Duration, Instant};

use serde_json::Value;
use web_support::plans::zip_parts;
use web_support::{Backend, Server, example_box, request};

/// The two databases' storms run one after the other: 8 workers on 2 cores would make the
/// boxes race the 3 s limit.
static ONE_STORM_AT_A_TIME: Mutex<()> = Mutex::new(());

/// The bound on the whole storm settling: far above what it takes, only so a stalled
/// service fails the test with a message instead of hanging it.
const STORM_LIMIT: Duration = Duration::from_secs(100);

/// How long the box sent after the storm may take from its upload (its turn: the queue is
/// empty by then).
const AFTER_LIMIT: Duration = Duration::from_secs(10);

/// The time limit and lease the server runs with: short, so hostile models end quickly.
const TIMEOUT_S: &str = "3";
const LEASE_S: &str = "6";

/// What a job is, and how it must end: its status and error code.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
enum Kind {
    Good,
    Hang,
    Freeze,
    Abort,
    Alloc,
}

impl Kind {
    /// The model name that makes a worker behave so (a box for the good ones).
    fn name(self, i: usize) -> String {
        match self {
            Kind::Good => format!("box-{i}.stl"),
            Kind::Hang => format!("platener-test-hang-{i}.stl"),
            Kind::Freeze => format!("platener-test-freeze-{i}.stl"),
            Kind::Abort => format!("platener-test-abort-{i}.stl"),
            Kind::Alloc => format!("platener-test-alloc-{i}.stl"),
        }
    }

    /// The status and error code it must end with.
    fn expected(self) -> (&'static str, Option<&'static str>) {
        match self {
            Kind::Good => ("done", None),
            Kind::Hang => ("failed", Some("timed_out")),
            Kind::Freeze => ("failed", Some("worker_stalled")),
            Kind::Abort => ("failed", Some("worker_died")),
            Kind::Alloc => ("failed", Some("out_of_memory")),
        }
    }
}

/// The 40 jobs in upload order: every fifth a box, the hostile ones spread between them so
/// they meet busy workers, 24 boxes in all.
fn storm_kinds() -> Vec<Kind> {
    let bad = [
        Kind::Hang,
        Kind::Abort,
        Kind::Freeze,
        Kind::Alloc,
        Kind::Hang,
        Kind::Abort,
        Kind::Alloc,
        Kind::Freeze,
    ];
    let mut kinds = Vec::new();
    let mut bad_left = bad.iter().cycle().take(16);
    for i in 0..40 {
        // 16 bad ones at positions 2 and 4 of each group of 5 (0-based), boxes elsewhere.
        let kind = match i % 5 {
            2 | 4 => bad_left.next().copied().unwrap_or(Kind::Good),
            _ => Kind::Good,
        };
        kinds.push(kind);
    }
    kinds
}

/// Samples `/api/health` every 250 ms until `stop`: (seconds since the start, HTTP status,
/// body).
fn sample_health(addr: String, stop: Arc<AtomicBool>) -> std::thread::JoinHandle<Vec<(f64, u16, Value)>> {
    std::thread::spawn(move || {
        let start = Instant::now();
        let mut samples = Vec::new();
        // Bounded in count as well as by `stop`.
        while !stop.load(Ordering::SeqCst) && samples.len() < 800 {
            let r = request(&addr, "GET", "/api/health", &[], b"");
            samples.push((start.elapsed().as_secs_f64(), r.status, r.json()));
            std::thread::sleep(Duration::from_millis(250));
        }
        samples
    })
}

/// Polls every job until all have ended; their final JSON, in upload order.
fn settle(server: &Server, ids: &[String]) -> Vec<Value> {
    let start = Instant::now();
    let mut ended: Vec<Option<Value>> = vec![None; ids.len()];
    loop {
        for (id, slot) in ids.iter().zip(ended.iter_mut()).filter(|(_, s)| s.is_none()) {
            let c = server.get(&format!("/api/conversions/{id}")).json();
            if matches!(c["status"].as_str(), Some("done" | "failed" | "cancelled")) {
                *slot = Some(c);
            }
        }
        let open: Vec<&String> = ids
            .iter()
            .zip(&ended)
            .filter(|(_, s)| s.is_none())
            .map(|(i, _)| i)
            .collect();
        if open.is_empty() {
            return ended.into_iter().flatten().collect();
        }
        assert!(
            start.elapsed() < STORM_LIMIT,
            "the storm did not settle within {STORM_LIMIT:?}: {} jobs still open ({open:?}); health: {}",
            open.len(),
            server.get("/api/health").text()
        );
        std::thread::sleep(Duration::from_millis(300));
    }
}

/// A good job: done, its best plan's ZIP opens with the box's 6 parts.
fn check_good(server: &Server, c: &Value) {
    let id = c["id"].as_str().expect("id");
    assert_eq!(c["status"], "done", "{c}");
    let zip = server.get(&format!("/api/conversions/{id}/plan.zip"));
    assert_eq!(zip.status, 200, "{id}: {}", zip.text());
    assert_eq!(zip_parts(&zip.body), 6, "{id}: the box has 6 parts");
}

/// Waits until health says ok with all `workers` alive and none busy (so none is stuck on a
/// job); the answer.
fn settled_health(server: &Server, workers: u64) -> Value {
    let start = Instant::now();
    loop {
        let r = server.get("/api/health");
        let h = r.json();
        if r.status == 200 && h["workers"] == workers && h["busy_workers"] == 0 {
            return h;
        }
        assert!(
            start.elapsed() < Duration::from_secs(30),
            "health never reported {workers} live, idle workers and ok: {} {h}",
            r.status
        );
        std::thread::sleep(Duration::from_millis(200));
    }
}

/// The storm on `backend`; prints the outcome table and the health answers.
fn storm(backend: Backend) {
    let _one = ONE_STORM_AT_A_TIME.lock().unwrap_or_else(PoisonError::into_inner);
    let dir = tempfile::tempdir().expect("temp dir");
    let args = [
        "--workers",
        "4",
        "--no-examples",
        "--timeout",
        TIMEOUT_S,
        "--worker-lease",
        LEASE_S,
        "--rate-limit",
        "0",
        "--max-queue",
        "1000",
    ];
    let Some(server) = Server::start_on(backend, dir.path(), &args, &[("PLATENER_TEST_HOOKS", "1")]) else {
        return;
    };
    let box_stl = example_box();
    let kinds = storm_kinds();
    let stop = Arc::new(AtomicBool::new(false));
    let sampler = sample_health(server.addr.clone(), stop.clone());
    let started = Instant::now();
    let ids: Vec<String> = kinds
        .iter()
        .enumerate()
        .map(|(i, kind)| {
            // The plate method alone: a box converts in a fraction of the time limit.
            let r = server.upload(&kind.name(i), &box_stl, &[("method", "plate")]);
            assert_eq!(r.status, 202, "{kind:?} {i}: {}", r.text());
            r.json()["id"].as_str().expect("id").to_string()
        })
        .collect();
    let ended = settle(&server, &ids);
    let storm_time = started.elapsed();
    stop.store(true, Ordering::SeqCst);
    let samples = sampler.join().expect("the health sampler");

    let mut table: BTreeMap<(Kind, String, String, i64), usize> = BTreeMap::new();
    for (kind, c) in kinds.iter().zip(&ended) {
        let code = c["error"]["code"].as_str().unwrap_or("-").to_string();
        let attempts = c["attempts"].as_i64().unwrap_or(0);
        *table
            .entry((*kind, c["status"].as_str().unwrap_or("?").to_string(), code, attempts))
            .or_insert(0) += 1;
    }
    eprintln!("{backend:?}: the storm settled in {storm_time:.1?}; outcomes (kind, status, code, attempts: count):");
    for ((kind, status, code, attempts), n) in &table {
        eprintln!("  {kind:?}\t{status}\t{code}\t{attempts}\t{n}");
    }
    eprintln!("{backend:?}: /api/health during the storm (s, HTTP status, answer):");
    for (t, status, body) in &samples {
        eprintln!("  {t:5.1}  {status}  {body}");
    }
    for (kind, c) in kinds.iter().zip(&ended) {
        let (status, code) = kind.expected();
        if *kind == Kind::Good {
            check_good(&server, c);
        } else {
            assert_eq!(
                (c["status"].as_str(), c["error"]["code"].as_str()),
                (Some(status), code),
                "{kind:?}: {c}"
            );
            let message = c["error"]["message"].as_str().unwrap_or_default();
            assert!(!message.is_empty() && !message.contains('<'), "{kind:?}: {c}");
        }
    }
    assert!(samples.len() > 4, "health was sampled {} times", samples.len());

    let health = settled_health(&server, 4);
    assert_eq!(
        server.worker_pids().len(),
        4,
        "4 worker processes, none stopped or extra: {health}"
    );
    after_the_storm(&server, &box_stl);
    eprintln!("{backend:?}: after the storm: {health}");
}

/// A box sent after the storm converts: done within [`AFTER_LIMIT`] of its upload.
fn after_the_storm(server: &Server, box_stl: &[u8]) {
    let r = server.upload("box-after.stl", box_stl, &[("method", "plate")]);
    assert_eq!(r.status, 202, "{}", r.text());
    let id = r.json()["id"].as_str().expect("id").to_string();
    let start = Instant::now();
    loop {
        let c = server.get(&format!("/api/conversions/{id}")).json();
        match c["status"].as_str() {
            Some("done") => return check_good(server, &c),
            Some("queued" | "running") => {}
            _ => panic!("the box after the storm did not convert: {c}"),
        }
        assert!(
            start.elapsed() < AFTER_LIMIT,
            "the box after the storm was not done within {AFTER_LIMIT:?} of its turn: {c}; health: {}",
            server.get("/api/health").text()
        );
        std::thread::sleep(Duration::from_millis(100));
    }
}

#[test]
fn a_storm_of_hostile_models_stalls_nothing_on_sqlite() {
    storm(Backend::Sqlite);
}

#[test]
fn a_storm_of_hostile_models_stalls_nothing_on_postgres() {
    storm(Backend::Postgres);
}

/// The health check tells a stalled service from a working one: with workers that cannot
/// even start (a 1 MB memory limit), a queued job waits with no worker alive, and
/// `/api/health` answers `503` with status `stalled` and the queue's numbers (it used to say
/// `ok`, issue 29).
#[test]
fn health_reports_a_queue_no_worker_serves_as_stalled() {
    let dir = tempfile::tempdir().expect("temp dir");
    let args = ["--workers", "1", "--no-examples", "--worker-memory-mb", "1"];
    let server = Server::start(dir.path(), &args, &[]);
    let r = server.upload("box.stl", &example_box(), &[]);
    assert_eq!(r.status, 202, "{}", r.text());
    let start = Instant::now();
    let stalled = loop {
        let r = server.get("/api/health");
        let h = r.json();
        if r.status == 503 && h["status"] == "stalled" {
            break h;
        }
        assert!(
            start.elapsed() < Duration::from_secs(30),
            "health never said stalled: {} {h}",
            r.status
        );
        std::thread::sleep(Duration::from_millis(100));
    };
    assert_eq!(
        (stalled["queue"].as_i64(), stalled["workers"].as_u64()),
        (Some(1), Some(0)),
        "{stalled}"
    );
    assert!(stalled["oldest_queued_s"].as_f64().is_some(), "{stalled}");
    assert!(
        stalled["reason"].as_str().is_some_and(|r| r.contains("no worker")),
        "{stalled}"
    );
}

/// Issue 29, bug 2: a worker whose model ran past the time limit used to hang on its way out
/// (its runtime waited on the lifeline's read), so with one worker every later upload stayed
/// queued. Now it exits, another process takes its place, and the next box converts.
#[test]
fn a_worker_past_its_time_limit_is_replaced_and_the_next_model_converts() {
    let dir = tempfile::tempdir().expect("temp dir");
    let args = ["--workers", "1", "--no-examples", "--timeout", "1"];
    let server = Server::start(dir.path(), &args, &[("PLATENER_TEST_HOOKS", "1")]);
    let box_stl = example_box();
    let hang = server.upload("platener-test-hang.stl", &box_stl, &[("method", "plate")]);
    assert_eq!(hang.status, 202, "{}", hang.text());
    let hang = hang.json()["id"].as_str().expect("id").to_string();
    let first = server.wait_for(&hang, |s| s == "running");
    let before = server.worker_pids();
    let next = server.upload("box.stl", &box_stl, &[("method", "plate")]);
    assert_eq!(next.status, 202, "{}", next.text());
    let next = next.json()["id"].as_str().expect("id").to_string();
    let c = server.wait_ended(&hang);
    assert_eq!(
        (c["status"].as_str(), c["error"]["code"].as_str()),
        (Some("failed"), Some("timed_out")),
        "{c}"
    );
    assert_eq!(first["attempts"], 1);
    // Its turn came when the hang ended; 15 s is far more than a box takes and less than the
    // server's own kill of a worker stuck on one job (limit + 30 s), so a worker that hangs on
    // its way out fails here, with a message.
    let start = Instant::now();
    let c = loop {
        let c = server.get(&format!("/api/conversions/{next}")).json();
        if c["status"] != "queued" && c["status"] != "running" {
            break c;
        }
        assert!(
            start.elapsed() < Duration::from_secs(15),
            "the box after a timed-out model was not converted within 15 s of its turn \
             (the worker did not exit?): {c}; workers {:?}",
            server.worker_pids()
        );
        std::thread::sleep(Duration::from_millis(100));
    };
    assert_eq!(c["status"], "done", "{c}");
    let after = server.worker_pids();
    assert_eq!(after.len(), 1, "{after:?}");
    assert_ne!(before, after, "the worker that timed out was replaced by a new process");
}
