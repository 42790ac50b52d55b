//! `platener serve` end to end: the real binary on 127.0.0.1, SQLite in a temp dir (and, for
//! the API's tests, PostgreSQL in the harness' throwaway cluster), worker processes that are the
//! same binary (issue 17). Every wait is bounded by `web_support::PATIENCE`; nothing asserts on
//! speed. The API's tests live in `web/`: the main flow, the error table, names, results as
//! they come.

mod web_support;

#[path = "web/errors.rs"]
mod errors;
#[path = "web/flow.rs"]
mod flow;
#[path = "web/live.rs"]
mod live;
#[path = "web/names.rs"]
mod names;

use std::io::{Read as _, Write as _};

use web_support::{Backend, Server, events, example_box, signal};

/// One test per database for each `module::body` (a `fn(Backend)`): `sqlite::body` and
/// `postgres::body` (which skips, saying why, when PostgreSQL is not installed, and fails
/// instead under `PLATENER_REQUIRE_POSTGRES=1`).
macro_rules! on_both_databases {
    ($($module:ident :: $body:ident),* $(,)?) => {
        mod sqlite {
            $(#[test]
            fn $body() {
                crate::$module::$body(crate::Backend::Sqlite);
            })*
        }
        mod postgres {
            $(#[test]
            fn $body() {
                crate::$module::$body(crate::Backend::Postgres);
            })*
        }
    };
}

on_both_databases!(
    flow::upload_convert_and_every_link_works,
    errors::every_error_has_its_status_and_code,
    errors::rate_limit_and_full_queue_are_429_and_503,
    errors::broken_corpus_files_give_the_readers_message,
    live::results_land_as_they_come,
);

#[test]
fn a_60_mb_upload_is_refused_before_its_body_is_read() {
    let dir = tempfile::tempdir().expect("temp dir");
    let server = Server::start(dir.path(), &["--workers", "0", "--no-examples"], &[]);
    let before = server.rss_kb();
    // Announce 60 MB and send only the head: the answer must come without the body.
    let mut stream = std::net::TcpStream::connect(&server.addr).expect("connect");
    stream.set_read_timeout(Some(web_support::PATIENCE)).expect("timeout");
    let head = format!(
        "POST /api/conversions HTTP/1.1\r\nHost: {}\r\nContent-Type: multipart/form-data; boundary=x\r\n\
         Content-Length: 60000000\r\n\r\n",
        server.addr
    );
    stream.write_all(head.as_bytes()).expect("send head");
    let mut raw = vec![0u8; 4096];
    let n = stream.read(&mut raw).expect("an answer before the body");
    web_support::parse(&raw[..n]).assert_error(413, "too_large");
    // Also when no Content-Length tells the size (chunked): the limit stops the reading.
    let mut stream = std::net::TcpStream::connect(&server.addr).expect("connect");
    stream.set_read_timeout(Some(web_support::PATIENCE)).expect("timeout");
    let head = format!(
        "POST /api/conversions HTTP/1.1\r\nHost: {}\r\nConnection: close\r\n\
         Content-Type: multipart/form-data; boundary=x\r\nTransfer-Encoding: chunked\r\n\r\n",
        server.addr
    );
    stream.write_all(head.as_bytes()).expect("send head");
    // Read while writing: the answer arrives before the server closes the connection.
    let mut reader = stream.try_clone().expect("clone");
    let answer = std::thread::spawn(move || {
        let mut raw = Vec::new();
        let mut buf = [0u8; 4096];
        while let Ok(n) = reader.read(&mut buf) {
            if n == 0 {
                break;
            }
            raw.extend_from_slice(&buf[..n]);
        }
        raw
    });
    let (_, form) = web_support::multipart("big.stl", &vec![0u8; 60_000_000], &[]);
    for chunk in form.chunks(1 << 20) {
        let mut framed = format!("{:x}\r\n", chunk.len()).into_bytes();
        framed.extend_from_slice(chunk);
        framed.extend_from_slice(b"\r\n");
        // The server answers and closes once past the limit; later writes fail.
        if stream.write_all(&framed).is_err() {
            break;
        }
    }
    let _ = stream.write_all(b"0\r\n\r\n");
    web_support::parse(&answer.join().expect("reader")).assert_error(413, "too_large");
    let grown = server.rss_kb().saturating_sub(before);
    assert!(grown < 30_000, "the server grew by {grown} kB");
}

#[test]
fn a_killed_worker_retries_and_a_hostile_model_fails_with_a_reason() {
    let dir = tempfile::tempdir().expect("temp dir");
    let server = Server::start(
        dir.path(),
        &["--workers", "1", "--no-examples"],
        &[("PLATENER_TEST_HOOKS", "1")],
    );
    let box_stl = example_box();
    // A slow model: kill -9 its worker while it runs; the job runs again and converts.
    let id = server.upload("platener-test-slow-box.stl", &box_stl, &[]).json()["id"]
        .as_str()
        .expect("id")
        .to_string();
    let c = server.wait_for(&id, |s| s == "running");
    assert_eq!(c["attempts"], 1);
    let workers = server.worker_pids();
    assert_eq!(workers.len(), 1, "{workers:?}");
    signal(workers[0], "KILL");
    let c = server.wait_ended(&id);
    assert_eq!(c["status"], "done", "{c}");
    assert_eq!(c["attempts"], 2);
    let evs = events(&server.addr, &id);
    assert!(evs.iter().any(|(k, _)| k == "retry"), "{evs:?}");

    // A model that aborts its worker every time: tried twice, then failed with a reason.
    let id = server.upload("platener-test-abort.stl", &box_stl, &[]).json()["id"]
        .as_str()
        .expect("id")
        .to_string();
    let c = server.wait_ended(&id);
    assert_eq!(c["status"], "failed", "{c}");
    assert_eq!(c["attempts"], 2);
    assert_eq!(c["error"]["code"], "worker_died");
    assert!(
        c["error"]["message"]
            .as_str()
            .is_some_and(|m| m.contains("crashed") && m.contains("after 2 attempts")),
        "{c}"
    );
    // The server still answers and a good model still converts.
    let health = server.get("/api/health");
    assert_eq!(health.status, 200, "{}", health.text());
    let id = server.upload("box.stl", &box_stl, &[]).json()["id"]
        .as_str()
        .expect("id")
        .to_string();
    assert_eq!(server.wait_ended(&id)["status"], "done");
}

#[test]
fn jobs_survive_a_killed_server_and_a_sigterm() {
    let dir = tempfile::tempdir().expect("temp dir");
    let hooks = [("PLATENER_TEST_HOOKS", "1")];
    let box_stl = example_box();
    let args = ["--workers", "1", "--no-examples", "--grace", "1"];
    let mut server = Server::start(dir.path(), &args, &hooks);
    let slow = server.upload("platener-test-slow-a.stl", &box_stl, &[]).json()["id"]
        .as_str()
        .expect("id")
        .to_string();
    let queued = server.upload("box.stl", &box_stl, &[]).json()["id"]
        .as_str()
        .expect("id")
        .to_string();
    server.wait_for(&slow, |s| s == "running");
    // kill -9 of the server mid-job: the worker finishes its job (its lifeline closed) and
    // exits; a new server finds one job done and runs the other.
    server.child.kill().expect("kill -9");
    server.child.wait().expect("reaped");
    drop(server);
    let server = Server::start(dir.path(), &args, &hooks);
    assert_eq!(server.wait_ended(&slow)["status"], "done");
    assert_eq!(server.wait_ended(&queued)["status"], "done");

    // SIGTERM with a job running past the grace period: the server stops cleanly and the
    // job, back in the queue, converts after the next start.
    let slow = server.upload("platener-test-slow-b.stl", &box_stl, &[]).json()["id"]
        .as_str()
        .expect("id")
        .to_string();
    server.wait_for(&slow, |s| s == "running");
    assert!(server.terminate(), "exit status 0 after SIGTERM");
    let server = Server::start(dir.path(), &args, &hooks);
    let c = server.wait_ended(&slow);
    assert_eq!(c["status"], "done", "{c}");
}

#[test]
fn examples_are_published_once_and_the_page_escapes_and_locks_down() {
    let dir = tempfile::tempdir().expect("temp dir");
    let server = Server::start(dir.path(), &["--workers", "1"], &[]);
    let g = server.get("/api/gallery").json();
    let mut names: Vec<&str> = g["items"]
        .as_array()
        .expect("items")
        .iter()
        .filter_map(|i| i["name"].as_str())
        .collect();
    names.sort_unstable();
    assert_eq!(names, ["box-3mm.stl", "phone-stand.stl", "tray-3mm.stl"]);
    let first = g["items"][0]["id"].as_str().expect("id").to_string();
    let page = server.get("/");
    assert_eq!(page.status, 200);
    assert!(
        page.header("content-security-policy")
            .is_some_and(|c| c.contains("default-src 'none'"))
    );
    assert!(page.text().contains("box-3mm.stl"));
    let done = server.wait_ended(&first);
    assert_eq!(done["status"], "done", "{done}");
    drop(server);
    let server = Server::start(dir.path(), &["--workers", "0"], &[]);
    assert_eq!(
        server.get("/api/gallery").json()["items"].as_array().map(Vec::len),
        Some(3),
        "seeded once"
    );
    let m = server.get("/metrics");
    assert_eq!(m.status, 200);
    assert!(
        m.text().contains("platener_conversions{status=\"done\"}"),
        "{}",
        m.text()
    );
    assert!(m.text().contains("platener_conversion_seconds_count"));
    let strip = server.get("/api/test-strip.json?thickness=3&material=wood").json();
    assert!(strip["holes"].as_array().is_some_and(|h| h.len() > 5), "{strip}");
    // The slot row: 17 slots from 2.6 to 3.4 mm sheets, each drawn the wood's 0.2 mm kerf
    // narrower than the sheet it fits.
    let slots = strip["slots"].as_array().expect("slots");
    assert_eq!(slots.len(), 17);
    for slot in slots {
        let (sheet, width) = (
            slot["sheet"].as_f64().expect("sheet"),
            slot["width"].as_f64().expect("width"),
        );
        assert!(
            (sheet - 0.2 - width).abs() < 1e-9 && (2.6 - 1e-9..=3.4 + 1e-9).contains(&sheet),
            "{slot}"
        );
        let xs: Vec<f64> = slot["ring"]
            .as_array()
            .expect("ring")
            .iter()
            .map(|p| p[0].as_f64().expect("x"))
            .collect();
        let across = xs.iter().copied().fold(f64::MIN, f64::max) - xs.iter().copied().fold(f64::MAX, f64::min);
        assert!((across - width).abs() < 1e-9, "{slot}");
    }
    assert!(server.get("/api/test-strip.svg?thickness=3").text().contains("<svg"));
}

/// The job ids a worker's log says it converted.
fn converted_by(log: &str) -> Vec<String> {
    log.lines()
        .filter(|l| l.contains("converting"))
        .filter_map(|l| l.split("job=").nth(1))
        .map(|rest| {
            rest.chars()
                .take_while(|c| c.is_ascii_alphanumeric() || *c == '_')
                .collect()
        })
        .collect()
}

#[test]
fn two_workers_on_postgres_share_40_jobs_each_run_once() {
    // Skips with a message when PostgreSQL is not installed (fails under PLATENER_REQUIRE_POSTGRES=1).
    let Some(cluster) = platener_testpg::Cluster::for_tests() else {
        return;
    };
    let url = cluster
        .fresh_database()
        .expect("a PostgreSQL database of this test's own")
        .url;
    let dir = tempfile::tempdir().expect("temp dir");
    let args = [
        "--workers",
        "0",
        "--no-examples",
        "--database",
        &url,
        "--rate-limit",
        "0",
        "--max-queue",
        "1000",
    ];
    let server = Server::start(dir.path(), &args, &[]);
    let box_stl = example_box();
    let ids: Vec<String> = (0..40)
        .map(|i| {
            let r = server.upload(&format!("box{i}.stl"), &box_stl, &[("method", "plate")]);
            assert_eq!(r.status, 202, "{}", r.text());
            r.json()["id"].as_str().expect("id").to_string()
        })
        .collect();
    let logs: Vec<_> = (0..2)
        .map(|_| tempfile::NamedTempFile::new().expect("log file"))
        .collect();
    let mut workers: Vec<std::process::Child> = logs
        .iter()
        .map(|log| {
            std::process::Command::new(env!("CARGO_BIN_EXE_platener"))
                .args(["worker", "--database", &url, "--memory-mb", "0"])
                .stderr(log.reopen().expect("log"))
                .spawn()
                .expect("worker starts")
        })
        .collect();
    for id in &ids {
        let c = server.wait_ended(id);
        assert_eq!(c["status"], "done", "{c}");
        assert_eq!(c["attempts"], 1, "run once: {c}");
        let reads = events(&server.addr, id)
            .iter()
            .filter(|(k, d)| k == "step" && d["step"] == "read" && d["state"] == "started")
            .count();
        assert_eq!(reads, 1, "{id} read once");
    }
    for w in &mut workers {
        let _ = w.kill();
        let _ = w.wait();
    }
    let done: Vec<Vec<String>> = logs
        .iter()
        .map(|l| converted_by(&std::fs::read_to_string(l.path()).unwrap_or_default()))
        .collect();
    let mut all: Vec<&String> = done.iter().flatten().filter(|id| ids.contains(id)).collect();
    assert!(done.iter().all(|d| !d.is_empty()), "both workers took jobs: {done:?}");
    all.sort();
    let n = all.len();
    all.dedup();
    assert_eq!((n, all.len()), (40, 40), "every job by exactly one worker");
}
