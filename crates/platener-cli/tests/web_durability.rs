//! `platener serve` survives `kill -9` (issue 17, "Durability"), and conversions can be
//! cancelled; on SQLite and on PostgreSQL (a database of the test's own in the test binary's
//! throwaway cluster; skipped with a message when PostgreSQL is not installed, a failure under
//! `PLATENER_REQUIRE_POSTGRES=1`).
//!
//! The real binary runs as users run it: server and workers are processes, and kill -9 means
//! kill -9. Besides the API, the tests read the job database directly, beside the server, so
//! they can look at it while the server is dead. Every wait is bounded; nothing asserts on speed.

mod durable_support;
mod web_support;

use std::path::Path;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::thread::JoinHandle;
use std::time::{Duration, Instant};

use durable_support::{JobDb, JobSnap, counts, half_written};
use serde_json::Value;
use web_support::plans::{all_links, zip_parts};
use web_support::{PATIENCE, Response, Server, events, example_box, signal};

/// How long the jobs may take to settle after the restart: the killed worker's lease (30 s)
/// runs out first. A bound on a hang, not a timed assertion.
const SETTLE: Duration = Duration::from_secs(400);

/// The test-only model names work (`platener-test-slow…` waits 3 s before converting).
const HOOKS: [(&str, &str); 1] = [("PLATENER_TEST_HOOKS", "1")];

/// Corpus models among the 20 jobs (small ones that convert).
const CORPUS_MODELS: [&str; 2] = ["plates/chess_case_bottom.stl", "solids/slic3r_20mm_box.stl"];

/// Where a test's server keeps its jobs.
#[derive(Debug, Clone, Copy)]
enum Backend {
    Sqlite,
    Postgres,
}

/// `serve`'s database flags and the URL the test reads the jobs at; `None` when PostgreSQL
/// is not installed (and not required), so the test skips after the harness said why.
fn database(backend: Backend, data: &Path) -> Option<(Vec<String>, String)> {
    match backend {
        Backend::Sqlite => Some((
            Vec::new(),
            format!("sqlite://{}", data.join("platener.sqlite").display()),
        )),
        Backend::Postgres => {
            let cluster = platener_testpg::Cluster::for_tests()?;
            let url = cluster
                .fresh_database()
                .expect("a PostgreSQL database of this test's own")
                .url;
            Some((vec!["--database".into(), url.clone()], url))
        }
    }
}

/// Starts a server on `data` with `base` flags plus the database's.
fn start(data: &Path, base: &[&str], db_args: &[String]) -> Server {
    let mut args: Vec<&str> = base.to_vec();
    args.extend(db_args.iter().map(String::as_str));
    Server::start(data, &args, &HOOKS)
}

/// Uploads a model; its id and delete token.
fn upload(server: &Server, name: &str, model: &[u8]) -> (String, String) {
    let r = server.upload(name, model, &[]);
    assert_eq!(r.status, 202, "{name}: {}", r.text());
    let c = r.json();
    (
        c["id"].as_str().expect("id").to_string(),
        c["delete_token"].as_str().expect("token").to_string(),
    )
}

/// A submitted job and whether it is the example box (6 parts).
struct Job {
    id: String,
    is_box: bool,
}

/// The 20 models: the example box, every fourth one slow (so work is mid-flight when the
/// kill comes), two from the shared corpus (boxes take their places, with a message, when
/// the corpus is absent and not required).
fn models() -> Vec<(String, Vec<u8>, bool)> {
    let box_stl = example_box();
    let corpus: Vec<(String, Vec<u8>)> = match platener_fixtures::samples::shared_corpus() {
        Ok(dir) => CORPUS_MODELS
            .iter()
            .map(|f| {
                let name = f.rsplit('/').next().unwrap_or(f).to_string();
                (name, std::fs::read(dir.join(f)).expect("corpus model"))
            })
            .collect(),
        Err(message) => {
            eprintln!("{message}; boxes take the corpus models' places");
            Vec::new()
        }
    };
    (0..20)
        .map(|i| match i {
            7 | 14 if !corpus.is_empty() => {
                let (name, bytes) = corpus[usize::from(i == 14)].clone();
                (name, bytes, false)
            }
            i if i % 4 == 1 => (format!("platener-test-slow-{i}.stl"), box_stl.clone(), true),
            i => (format!("box-{i}.stl"), box_stl.clone(), true),
        })
        .collect()
}

/// The `--name` a process was started with (workers started by `serve` have one).
fn worker_name(pid: u32) -> Option<String> {
    let cmdline = std::fs::read(format!("/proc/{pid}/cmdline")).ok()?;
    let args: Vec<String> = cmdline
        .split(|b| *b == 0)
        .map(|a| String::from_utf8_lossy(a).into_owned())
        .collect();
    args.windows(2).find(|w| w[0] == "--name").map(|w| w[1].clone())
}

/// Waits until the run is mid-way: at least four jobs ended and one of the server's workers
/// holds a running job. That worker's process id and the job.
fn mid_run(server: &Server, db: &JobDb) -> (u32, String) {
    let start = Instant::now();
    loop {
        let jobs = db.snapshot();
        let ended = jobs
            .iter()
            .filter(|j| matches!(j.status.as_str(), "done" | "failed"))
            .count();
        let named: Vec<(u32, String)> = server
            .worker_pids()
            .into_iter()
            .filter_map(|pid| worker_name(pid).map(|n| (pid, n)))
            .collect();
        let busy = jobs.iter().filter(|j| j.status == "running").find_map(|j| {
            let (pid, _) = named.iter().find(|(_, n)| j.worker.as_ref() == Some(n))?;
            Some((*pid, j.id.clone()))
        });
        if let (true, Some(found)) = (ended >= 4, busy) {
            return found;
        }
        assert!(start.elapsed() < PATIENCE, "never mid-run: {:?}", counts(&jobs));
        std::thread::sleep(Duration::from_millis(20));
    }
}

/// Looks at every job again and again until `stop`, collecting what is half-written; returns
/// how many looks it took and what it found.
fn watch(url: String, stop: Arc<AtomicBool>) -> JoinHandle<(usize, Vec<String>)> {
    std::thread::spawn(move || {
        let db = JobDb::open(&url);
        let (mut looks, mut found) = (0, Vec::new());
        while !stop.load(Ordering::SeqCst) {
            found.extend(db.snapshot().iter().filter_map(half_written));
            looks += 1;
            std::thread::sleep(Duration::from_millis(25));
        }
        (looks, found)
    })
}

/// Waits until no job is queued or running; the last look.
fn settle(db: &JobDb, n: usize) -> Vec<JobSnap> {
    let start = Instant::now();
    loop {
        let jobs = db.snapshot();
        let open = jobs.iter().any(|j| matches!(j.status.as_str(), "queued" | "running"));
        if jobs.len() == n && !open {
            return jobs;
        }
        assert!(start.elapsed() < SETTLE, "jobs stuck: {:?}", counts(&jobs));
        std::thread::sleep(Duration::from_millis(200));
    }
}

/// A job's events as stored: numbered 1, 2, 3… with no gap or repeat, exactly one last event
/// (`done`), one `retry` per attempt after the first, and each method reported once by the
/// attempt that stored the results.
fn check_events(db: &JobDb, c: &Value) {
    let id = c["id"].as_str().expect("id");
    let evs = db.events(id);
    let seqs: Vec<i64> = evs.iter().map(|(s, _, _)| *s).collect();
    let expected: Vec<i64> = (1..=i64::try_from(evs.len()).expect("count")).collect();
    assert_eq!(seqs, expected, "{id}: sequence numbers");
    let kinds: Vec<&str> = evs.iter().map(|(_, k, _)| k.as_str()).collect();
    let last = kinds
        .iter()
        .filter(|k| matches!(**k, "done" | "failed" | "cancelled"))
        .count();
    assert_eq!((last, kinds.last()), (1, Some(&"done")), "{id}: {kinds:?}");
    let retries = kinds.iter().filter(|k| **k == "retry").count();
    assert_eq!(Some(retries as i64 + 1), c["attempts"].as_i64(), "{id}: {kinds:?}");
    let from = kinds.iter().rposition(|k| *k == "retry").map_or(0, |p| p + 1);
    for m in c["methods"].as_array().expect("methods") {
        let reported = evs[from..]
            .iter()
            .filter(|(_, k, d)| k == "method" && d["method"] == m["method"])
            .count();
        assert_eq!(reported, 1, "{id}: method {} in {kinds:?}", m["method"]);
    }
}

/// A settled job through the API: done, its plan's ZIP opens with the part count its summary
/// gives (the box: 6), every link answers 200 (JSON parses, ZIPs open), and its event stream
/// is the stored list.
fn check_job(server: &Server, db: &JobDb, job: &Job) {
    let c = server.get(&format!("/api/conversions/{}", job.id)).json();
    assert_eq!(c["status"], "done", "{c}");
    check_events(db, &c);
    let best = c["best"].as_str().expect("a best method");
    let parts = c["methods"]
        .as_array()
        .and_then(|ms| ms.iter().find(|m| m["method"] == best))
        .and_then(|m| m["parts"].as_u64())
        .expect("the best method's parts");
    let zip = server.get(&format!("/api/conversions/{}/plan.zip", job.id));
    assert_eq!(zip.status, 200, "{}", zip.text());
    assert_eq!(zip_parts(&zip.body) as u64, parts, "{c}");
    if job.is_box {
        assert_eq!(parts, 6, "the box has 6 parts: {c}");
    }
    let mut links = Vec::new();
    all_links(&c["links"], &mut links);
    assert!(links.len() > 10, "{links:?}");
    for link in links.iter().filter(|l| !l.ends_with("/events")) {
        let r = server.get(link);
        assert_eq!(r.status, 200, "{link}: {}", r.text());
        if link.ends_with(".json") {
            r.json();
        } else if link.ends_with(".zip") {
            assert!(zip_parts(&r.body) > 0, "{link}");
        }
    }
    let streamed = events(&server.addr, &job.id);
    assert_eq!(streamed.len(), db.events(&job.id).len(), "{}", job.id);
    assert_eq!(streamed.last().map(|(k, _)| k.as_str()), Some("done"));
}

/// Submits 20 jobs, kills the server and a busy worker with SIGKILL mid-run, restarts the
/// server on the same data, and checks that every job converted exactly once and whole, and
/// that no look at the database ever found a job half-written.
fn survives_kill_9(backend: Backend) {
    let dir = tempfile::tempdir().expect("temp dir");
    let Some((db_args, url)) = database(backend, dir.path()) else {
        return;
    };
    let base = [
        "--workers",
        "2",
        "--no-examples",
        "--rate-limit",
        "0",
        "--max-queue",
        "1000",
    ];
    let mut server = start(dir.path(), &base, &db_args);
    let jobs: Vec<Job> = models()
        .iter()
        .map(|(name, model, is_box)| Job {
            id: upload(&server, name, model).0,
            is_box: *is_box,
        })
        .collect();
    let db = JobDb::open(&url);
    let stop = Arc::new(AtomicBool::new(false));
    let watcher = watch(url.clone(), stop.clone());
    let (worker, busy) = mid_run(&server, &db);
    server.child.kill().expect("kill -9 the server");
    server.child.wait().expect("reaped");
    signal(worker, "KILL");
    drop(server);
    // With the server dead, nothing is half-written.
    let dead = db.snapshot();
    let bad: Vec<String> = dead.iter().filter_map(half_written).collect();
    assert!(bad.is_empty(), "{bad:?}");
    let busy_after_kill = dead.iter().find(|j| j.id == busy).map(|j| j.status.clone());

    let server = start(dir.path(), &base, &db_args);
    let restarted = Instant::now();
    let settled = settle(&db, jobs.len());
    let settling = restarted.elapsed();
    stop.store(true, Ordering::SeqCst);
    let (looks, found) = watcher.join().expect("the watcher");
    assert!(looks > 10, "the watcher looked {looks} times");
    assert!(found.is_empty(), "half-written jobs seen: {found:?}");
    assert_eq!(
        counts(&settled).get("done"),
        Some(&jobs.len()),
        "{:?}",
        counts(&settled)
    );
    for job in &jobs {
        check_job(&server, &db, job);
    }
    // The killed worker's job ran again (unless it had just finished when the kill came).
    let killed = settled.iter().find(|j| j.id == busy).expect("the busy job");
    if busy_after_kill.as_deref() == Some("running") {
        assert_eq!(killed.attempts, 2, "{busy} ran again after its worker was killed");
    }
    eprintln!(
        "{backend:?}: {} jobs done; at the kill {:?}; the killed worker's job was {busy_after_kill:?} \
         and took {} attempts; settled {settling:.1?} after the restart; {looks} looks at the database",
        jobs.len(),
        counts(&dead),
        killed.attempts,
    );
}

#[test]
fn twenty_jobs_survive_kill_9_of_server_and_worker_on_sqlite() {
    survives_kill_9(Backend::Sqlite);
}

#[test]
fn twenty_jobs_survive_kill_9_of_server_and_worker_on_postgres() {
    survives_kill_9(Backend::Postgres);
}

/// `POST …/cancel`, with a token when given.
fn cancel(server: &Server, id: &str, token: Option<&str>) -> Response {
    let bearer = token.map(|t| format!("Bearer {t}"));
    let headers: Vec<(&str, &str)> = bearer.iter().map(|b| ("Authorization", b.as_str())).collect();
    server.request("POST", &format!("/api/conversions/{id}/cancel"), &headers, b"")
}

/// The kinds of a conversion's streamed events.
fn kinds(server: &Server, id: &str) -> Vec<String> {
    events(&server.addr, id).into_iter().map(|(k, _)| k).collect()
}

/// A queued job is cancelled at once; a running one is cancelled and its worker stops and
/// stores nothing (its next progress write is refused, so no event follows `cancelled`);
/// the owner's token is needed; an ended job is 409; SIGTERM still re-queues a running job.
fn cancels(backend: Backend) {
    let dir = tempfile::tempdir().expect("temp dir");
    let Some((db_args, url)) = database(backend, dir.path()) else {
        return;
    };
    let base = ["--workers", "1", "--no-examples", "--grace", "1"];
    let server = start(dir.path(), &base, &db_args);
    let box_stl = example_box();
    let (slow, slow_token) = upload(&server, "platener-test-slow-cancel.stl", &box_stl);
    let (queued, queued_token) = upload(&server, "box-queued.stl", &box_stl);
    let (after, after_token) = upload(&server, "box-after.stl", &box_stl);
    // The worker takes the oldest job first and the slow one waits 3 s before converting: the
    // second is still queued, and the first is still running when cancelled.
    let c = cancel(&server, &queued, Some(&queued_token));
    assert_eq!(c.status, 200, "{}", c.text());
    let c = c.json();
    assert_eq!(
        (c["status"].as_str(), c["attempts"].as_i64()),
        (Some("cancelled"), Some(0)),
        "{c}"
    );
    assert!(c["finished"].is_string(), "{c}");
    server.wait_for(&slow, |s| s == "running");
    let c = cancel(&server, &slow, Some(&slow_token));
    assert_eq!(c.status, 200, "{}", c.text());
    assert_eq!(c.json()["status"], "cancelled");
    assert_eq!(kinds(&server, &queued), ["cancelled"]);
    cancel(&server, &slow, None).assert_error(401, "unauthorized");
    cancel(&server, &slow, Some(&queued_token)).assert_error(401, "unauthorized");
    // The one worker leaves the cancelled job, skips the other and converts the third.
    assert_eq!(server.wait_ended(&after)["status"], "done");
    let c = server.get(&format!("/api/conversions/{slow}")).json();
    assert_eq!(
        (c["status"].as_str(), c["best"].as_str()),
        (Some("cancelled"), None),
        "{c}"
    );
    assert_eq!(c["methods"], serde_json::json!([]), "no results stored: {c}");
    let plan = server.get(&format!("/api/conversions/{slow}/plan.zip"));
    assert_eq!(plan.status, 409, "{}", plan.text());
    // Read from the database first: an event after the last would keep the stream open.
    let db = JobDb::open(&url);
    let stored: Vec<String> = db.events(&slow).into_iter().map(|(_, k, _)| k).collect();
    assert_eq!(stored.last().map(String::as_str), Some("cancelled"), "{stored:?}");
    assert_eq!(stored.iter().filter(|k| *k == "cancelled").count(), 1, "{stored:?}");
    assert_eq!(kinds(&server, &slow), stored);
    let jobs = db.snapshot();
    let job = jobs.iter().find(|j| j.id == slow).expect("the cancelled job");
    assert!(job.files.is_empty() && job.summary.is_none(), "{job:?}");

    cancel(&server, &after, Some(&after_token)).assert_error(409, "already_ended");
    cancel(&server, &slow, Some(&slow_token)).assert_error(409, "already_ended");
    let unknown = platener_web::ids::conversion_id();
    cancel(&server, &unknown, Some(&slow_token)).assert_error(404, "not_found");
    sigterm_requeues(server, dir.path(), &base, &db_args, &url);
}

/// SIGTERM with a job running past the grace period puts it back in the queue (not
/// cancelled, the attempt not counted); it converts after the next start.
fn sigterm_requeues(server: Server, data: &Path, base: &[&str], db_args: &[String], url: &str) {
    let (slow, _) = upload(&server, "platener-test-slow-term.stl", &example_box());
    server.wait_for(&slow, |s| s == "running");
    assert!(server.terminate(), "exit status 0 after SIGTERM");
    let jobs = JobDb::open(url).snapshot();
    let stored = jobs.iter().find(|j| j.id == slow).expect("the job");
    assert_eq!((stored.status.as_str(), stored.attempts), ("queued", 0), "{stored:?}");
    let server = start(data, base, db_args);
    let c = server.wait_ended(&slow);
    assert_eq!(
        (c["status"].as_str(), c["attempts"].as_i64()),
        (Some("done"), Some(1)),
        "{c}"
    );
}

#[test]
fn cancel_stops_queued_and_running_jobs_on_sqlite() {
    cancels(Backend::Sqlite);
}

#[test]
fn cancel_stops_queued_and_running_jobs_on_postgres() {
    cancels(Backend::Postgres);
}
