//! `platener serve` end to end: the real binary on 127.0.0.1, SQLite in a temp dir, worker
//! processes that are the same binary (issue 17). Every wait is bounded by
//! `web_support::PATIENCE`; nothing asserts on speed.

mod web_support;

use std::io::{Read as _, Write as _};

use serde_json::{Value, json};
use web_support::plans::{all_links, zip_parts};
use web_support::{Server, events, example_box, signal};

/// Checks one link's answer by what it names: content type, magic bytes, headers.
fn check_link(server: &Server, link: &str) {
    let r = server.get(link);
    assert_eq!(r.status, 200, "{link}: {}", r.text());
    assert_eq!(r.header("x-content-type-options"), Some("nosniff"), "{link}");
    let path = link.split('?').next().unwrap_or_default();
    let ct = r.header("content-type").unwrap_or_default().to_string();
    if path.ends_with(".zip") {
        assert_eq!(ct, "application/zip", "{link}");
        assert!(
            r.header("content-disposition")
                .is_some_and(|d| d.starts_with("attachment;")),
            "{link}"
        );
        assert!(zip_parts(&r.body) > 0, "{link}");
    } else if path.ends_with(".glb") {
        assert_eq!(ct, "model/gltf-binary", "{link}");
        assert_eq!(&r.body[..4], b"glTF", "{link}");
    } else if path.ends_with(".png") {
        assert_eq!(ct, "image/png", "{link}");
        assert_eq!(&r.body[..4], b"\x89PNG", "{link}");
    } else if path.ends_with(".svg") {
        assert_eq!(ct, "image/svg+xml", "{link}");
        assert!(r.text().contains("<svg"), "{link}");
        assert!(r.header("content-security-policy").is_some(), "{link}");
    } else if path.ends_with(".json") {
        assert!(ct.starts_with("application/json"), "{link}");
        r.json();
    } else if path.ends_with("/events") {
        assert!(ct.starts_with("text/event-stream"), "{link}");
    } else {
        assert!(ct.starts_with("application/json"), "{link}: {ct}");
    }
}

#[test]
fn upload_box_streams_events_and_every_link_works() {
    let dir = tempfile::tempdir().expect("temp dir");
    let server = Server::start(dir.path(), &["--workers", "2", "--no-examples"], &[]);
    let r = server.upload(
        "box-3mm.stl",
        &example_box(),
        &[("thickness", "3"), ("material", "wood")],
    );
    assert_eq!(r.status, 202, "{}", r.text());
    let c = r.json();
    let id = c["id"].as_str().expect("id").to_string();
    assert_eq!(r.header("location"), Some(format!("/api/conversions/{id}").as_str()));
    assert_eq!(c["status"], "queued");
    assert_eq!(c["model"]["name"], "box-3mm.stl");
    let token = c["delete_token"].as_str().expect("a delete token once").to_string();

    let evs = events(&server.addr, &id);
    let kinds: Vec<&str> = evs.iter().map(|(k, _)| k.as_str()).collect();
    assert_eq!(kinds.last(), Some(&"done"), "{kinds:?}");
    assert!(
        evs.iter()
            .any(|(k, d)| k == "step" && d["step"] == "read" && d["state"] == "finished")
    );
    for m in ["plate", "stacked"] {
        assert!(
            evs.iter().any(|(k, d)| k == "method" && d["method"] == m),
            "{m}: {kinds:?}"
        );
    }
    // A late client gets the same events so far.
    assert_eq!(events(&server.addr, &id).len(), evs.len());

    let c = server.get(&format!("/api/conversions/{id}")).json();
    assert_eq!(c["status"], "done", "{c}");
    assert_eq!(c["best"], "plate");
    assert!(c.get("delete_token").is_none(), "the token is shown once only");
    assert_eq!(c["model"]["triangles"], 120);
    let bbox: Vec<f64> = c["model"]["bbox_mm"]
        .as_array()
        .expect("bbox")
        .iter()
        .filter_map(Value::as_f64)
        .collect();
    assert_eq!(bbox.len(), 3);
    let plate = c["methods"]
        .as_array()
        .expect("methods")
        .iter()
        .find(|m| m["method"] == "plate")
        .expect("plate")
        .clone();
    assert_eq!(plate["parts"], 6, "{plate}");
    assert_eq!(plate["status"], "done");
    assert!(plate["score"].as_f64().is_some_and(|s| s > 0.5 && s <= 1.0), "{plate}");
    assert_eq!(
        zip_parts(&server.get(&format!("/api/conversions/{id}/plan.zip")).body),
        6
    );

    let mut links = Vec::new();
    all_links(&c["links"], &mut links);
    assert!(links.len() > 20, "{links:?}");
    for view in ["model", "wireframe", "coplanar", "plates", "bent", "final"] {
        assert!(c["links"]["scenes"][view].is_string(), "scene {view}");
    }
    for link in links.iter().filter(|l| !l.ends_with("/events")) {
        check_link(&server, link);
    }

    publish_recut_delete(&server, &id, &token);
}

/// Publish (401 without the token), gallery, recut, delete.
fn publish_recut_delete(server: &Server, id: &str, token: &str) {
    let publish = format!("/api/conversions/{id}/publish");
    server
        .request("POST", &publish, &[], b"")
        .assert_error(401, "unauthorized");
    server
        .request("POST", &publish, &[("Authorization", "Bearer 00")], b"")
        .assert_error(401, "unauthorized");
    let bearer = format!("Bearer {token}");
    let r = server.request("POST", &publish, &[("Authorization", &bearer)], b"");
    assert_eq!(r.status, 200, "{}", r.text());
    assert_eq!(r.json()["published"], true);
    let g = server.get("/api/gallery?page=1").json();
    let item = &g["items"][0];
    assert_eq!(item["id"], id);
    assert_eq!(item["parts"], 6);
    assert_eq!(server.get(item["thumbnail"].as_str().expect("thumbnail")).status, 200);

    let body = json!({"kerf": 0.15}).to_string();
    let r = server.request(
        "POST",
        &format!("/api/conversions/{id}/recut"),
        &[("Content-Type", "application/json")],
        body.as_bytes(),
    );
    assert_eq!(r.status, 202, "{}", r.text());
    let recut = r.json();
    let rid = recut["id"].as_str().expect("id");
    assert_ne!(rid, id);
    assert_eq!(recut["recut_of"], id);
    assert_eq!(recut["settings"]["kerf"], 0.15);
    let done = server.wait_ended(rid);
    assert_eq!(done["status"], "done", "{done}");

    let path = format!("/api/conversions/{id}");
    server
        .request("DELETE", &path, &[], b"")
        .assert_error(401, "unauthorized");
    assert_eq!(
        server
            .request("DELETE", &path, &[("Authorization", &bearer)], b"")
            .status,
        204
    );
    server.get(&path).assert_error(404, "not_found");
    server.get(&format!("{path}/plan.zip")).assert_error(404, "not_found");
    server.get(&format!("{path}/events")).assert_error(404, "not_found");
    let g = server.get("/api/gallery").json();
    assert!(g["items"].as_array().expect("items").iter().all(|i| i["id"] != id));
    assert_eq!(
        server.get(&format!("/api/conversions/{rid}")).status,
        200,
        "the recut stays"
    );
}

#[test]
fn every_error_has_its_status_and_code() {
    let dir = tempfile::tempdir().expect("temp dir");
    let server = Server::start(
        dir.path(),
        &["--workers", "0", "--no-examples", "--max-upload-mb", "1"],
        &[],
    );
    let unknown = format!("/api/conversions/c_{}", "0".repeat(32));
    server.get(&unknown).assert_error(404, "not_found");
    server
        .get("/api/conversions/../../etc/passwd")
        .assert_error(404, "not_found");
    server.get("/api/conversions/c_nothex").assert_error(404, "not_found");
    server.get("/nothing/here").assert_error(404, "not_found");
    server.get("/api/gallery?page=0").assert_error(400, "bad_request");
    server
        .get("/api/test-strip.svg?thickness=-1")
        .assert_error(400, "bad_request");
    server
        .get("/api/test-strip.json?material=gold")
        .assert_error(400, "bad_request");

    let box_stl = example_box();
    server
        .upload("box.stl", &box_stl, &[("material", "<b>gold</b>")])
        .assert_error(400, "bad_request");
    server
        .upload("box.stl", &box_stl, &[("colour", "red")])
        .assert_error(400, "bad_request");
    server
        .request(
            "POST",
            "/api/conversions",
            &[("Content-Type", "application/json")],
            b"{}",
        )
        .assert_error(400, "bad_request");
    server
        .upload("page.stl", b"<html><script>alert(1)</script></html>", &[])
        .assert_error(415, "unsupported_format");
    server
        .upload("empty.stl", b"", &[])
        .assert_error(422, "unreadable_model");
    let big = vec![b'x'; 1_200_000];
    server.upload("big.stl", &big, &[]).assert_error(413, "too_large");

    // Accepted, but no worker runs it: its plan is not ready; its files do not exist.
    let r = server.upload("<script>x</script>.stl", &box_stl, &[]);
    assert_eq!(r.status, 202, "{}", r.text());
    let c = r.json();
    let name = c["model"]["name"].as_str().expect("name");
    assert!(!name.contains('<') && name.ends_with(".stl"), "{name}");
    let id = c["id"].as_str().expect("id");
    server
        .get(&format!("/api/conversions/{id}/plan.zip"))
        .assert_error(409, "not_ready");
    server
        .get(&format!("/api/conversions/{id}/methods/cubist/plan.zip"))
        .assert_error(404, "not_found");
    server
        .get(&format!("/api/conversions/{id}/methods/plate/sheets/0.svg"))
        .assert_error(404, "not_found");
    server
        .get(&format!("/api/conversions/{id}/scenes/nothing.glb"))
        .assert_error(404, "not_found");
    server
        .request(
            "POST",
            &format!("/api/conversions/{id}/recut"),
            &[("Content-Type", "application/json")],
            b"[1]",
        )
        .assert_error(400, "bad_request");
    server
        .request(
            "POST",
            &format!("/api/conversions/{id}/recut"),
            &[("Content-Type", "application/json")],
            b"{\"colour\":1}",
        )
        .assert_error(400, "bad_request");
}

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
fn rate_limit_and_full_queue_are_429_and_503() {
    let dir = tempfile::tempdir().expect("temp dir");
    let server = Server::start(
        dir.path(),
        &[
            "--workers",
            "0",
            "--no-examples",
            "--rate-limit",
            "3",
            "--max-queue",
            "2",
        ],
        &[],
    );
    let box_stl = example_box();
    assert_eq!(server.upload("a.stl", &box_stl, &[]).status, 202);
    assert_eq!(server.upload("b.stl", &box_stl, &[]).status, 202);
    let busy = server.upload("c.stl", &box_stl, &[]);
    busy.assert_error(503, "busy");
    assert!(busy.header("retry-after").is_some());
    server.get("/api/health").assert_error(503, "busy");
    let limited = server.upload("d.stl", &box_stl, &[]);
    limited.assert_error(429, "rate_limited");
    assert!(
        limited
            .header("retry-after")
            .and_then(|s| s.parse::<u64>().ok())
            .is_some_and(|s| (1..=60).contains(&s))
    );
}

#[test]
fn broken_corpus_files_give_the_readers_message() {
    let corpus = match platener::samples::shared_corpus() {
        Ok(dir) => dir,
        Err(message) => {
            eprintln!("{message}");
            return;
        }
    };
    let dir = tempfile::tempdir().expect("temp dir");
    let server = Server::start(dir.path(), &["--workers", "1", "--no-examples"], &[]);
    // The files SOURCES.md lists as not parsing, and where the reader stops.
    let cases = [
        ("openscad_invalid_vertex.stl", "line 89"),
        ("openscad_too_many_vertices.stl", "line 93"),
        ("openscad_empty_0_bytes.stl", "empty"),
        ("trimesh_empty_binary_header_only.stl", "no triangles"),
        ("numpy_stl_incomplete_ascii.stl", "line"),
        ("numpy_stl_end_solid_with_space.stl", "line"),
    ];
    for (file, says) in cases {
        let bytes = std::fs::read(corpus.join("broken").join(file)).expect("corpus file");
        let r = server.upload(file, &bytes, &[]);
        let error = if r.status == 202 {
            let c = server.wait_ended(r.json()["id"].as_str().expect("id"));
            assert_eq!(c["status"], "failed", "{file}: {c}");
            c["error"].clone()
        } else {
            r.assert_error(422, "unreadable_model");
            r.json()["error"].clone()
        };
        assert_eq!(error["code"], "unreadable_model", "{file}: {error}");
        let message = error["message"].as_str().expect("message");
        assert!(message.contains(says), "{file}: {message}");
    }
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
            .is_some_and(|m| m.contains("stopped 2 times")),
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
