//! Results as they come (issue 30) on one database: the model scene answers before any method
//! ends, a method's ZIP, sheets and scenes while another still runs, the queue's order, a cancel
//! that keeps what landed, and a retry after a killed worker that starts from nothing.
//!
//! Methods of a `platener-test-hold…` model wait as their `sheets` step starts until the test
//! opens their gate (a file in `PLATENER_TEST_GATE`), so every "before" here is made so, not
//! hoped for; every wait is bounded.

use std::path::Path;
use std::time::Instant;

use platener::method::MethodKind;
use platener::pipeline::StepId;
use serde_json::Value;

use crate::web_support::plans::zip_parts;
use crate::web_support::{Backend, PATIENCE, Server, events, example_box, signal};

/// Lets `method` of the model stored as `name` go on past its `sheets` step.
fn open_gate(gates: &Path, name: &str, method: &str) {
    std::fs::write(gates.join(format!("{name}.{method}")), b"").expect("write a gate");
}

/// Uploads the box as `name`: the `202`'s JSON and the delete token.
fn upload(server: &Server, name: &str) -> (Value, String) {
    let r = server.upload(name, &example_box(), &[]);
    assert_eq!(r.status, 202, "{}", r.text());
    let c = r.json();
    let token = c["delete_token"].as_str().expect("a token").to_string();
    (c, token)
}

fn id_of(c: &Value) -> String {
    c["id"].as_str().expect("an id").to_string()
}

/// Polls conversion `id` until `ready` holds; its JSON.
fn wait_until(server: &Server, id: &str, what: &str, ready: impl Fn(&Value) -> bool) -> Value {
    let start = Instant::now();
    loop {
        let c = server.get(&format!("/api/conversions/{id}")).json();
        if ready(&c) {
            return c;
        }
        assert!(start.elapsed() < PATIENCE, "waited for {what}: {c}");
        std::thread::sleep(std::time::Duration::from_millis(50));
    }
}

/// The summary line of `method`, once it landed.
fn method_line<'c>(c: &'c Value, method: &str) -> Option<&'c Value> {
    c["methods"].as_array()?.iter().find(|m| m["method"] == method)
}

/// GET that must answer 200; the body.
fn get_ok(server: &Server, path: &str) -> Vec<u8> {
    let r = server.get(path);
    assert_eq!(r.status, 200, "{path}: {}", r.text());
    r.body
}

/// The model scene answers, its event says so with the model's size, while no method made a
/// plan (all are held); a held method's bar reads its step in words.
fn model_first(server: &Server, id: &str) {
    let c = wait_until(server, id, "the model scene", |c| {
        c["links"]["scenes"]["model"].is_string()
    });
    assert_eq!(c["status"], "running", "{c}");
    for m in ["plate", "stacked"] {
        assert!(method_line(&c, m).is_none(), "{m} ended while held: {c}");
    }
    assert_eq!(c["model"]["triangles"], 120, "{c}");
    let link = c["links"]["scenes"]["model"].as_str().expect("link");
    assert_eq!(&get_ok(server, link)[..4], b"glTF");
    let shared = get_ok(server, &format!("/api/conversions/{id}/scenes/model.glb?method=plate"));
    assert_eq!(shared, get_ok(server, link), "one model scene for every method");
    server
        .get(&format!("/api/conversions/{id}/plan.zip"))
        .assert_error(409, "not_ready");
}

/// Plate's results land while stacked is held: its ZIP, a sheet and its final scene answer
/// and the conversion lists it, still running, with no best yet.
fn plate_lands_alone(server: &Server, id: &str) -> Value {
    let c = wait_until(server, id, "the plate method's results", |c| {
        method_line(c, "plate").is_some()
    });
    assert_eq!(c["status"], "running", "{c}");
    assert_eq!(c["best"], Value::Null, "the best is chosen at the end: {c}");
    assert_eq!(method_line(&c, "plate").expect("plate")["status"], "done", "{c}");
    assert!(method_line(&c, "stacked").is_none(), "{c}");
    let plate = &c["links"]["methods"]["plate"];
    let zip = get_ok(server, plate["plan_zip"].as_str().expect("plan_zip"));
    assert_eq!(zip_parts(&zip), 6, "the box's six plates");
    assert!(get_ok(server, plate["sheets"][0].as_str().expect("a sheet")).starts_with(b"<"));
    assert_eq!(
        &get_ok(server, plate["scenes"]["final"].as_str().expect("final"))[..4],
        b"glTF"
    );
    assert_eq!(
        get_ok(server, &format!("/api/conversions/{id}/methods/plate/plan.zip")),
        zip
    );
    c
}

/// The events of a conversion that ran `plate` to its end: the model event before every method
/// event, and the plate method's steps with their words and places.
fn check_events(server: &Server, id: &str) {
    let evs = events(&server.addr, id);
    let kinds: Vec<&str> = evs.iter().map(|(k, _)| k.as_str()).collect();
    let model = kinds.iter().position(|k| *k == "model").expect("a model event");
    let first_method = kinds.iter().position(|k| *k == "method").expect("a method event");
    assert!(model < first_method, "{kinds:?}");
    assert_eq!(evs[model].1["triangles"], 120);
    assert_eq!(evs[model].1["scene"], true);
    let nesting = evs
        .iter()
        .find(|(k, d)| k == "step" && d["method"] == "plate" && d["step"] == "sheets" && d["state"] == "started")
        .expect("plate's sheets step started");
    assert_eq!(nesting.1["label"], StepId::Sheets.label(), "{nesting:?}");
    let steps = StepId::of_method(MethodKind::Plate);
    let place = steps.iter().position(|s| *s == StepId::Sheets);
    assert_eq!(nesting.1["index"].as_u64(), place.map(|p| p as u64), "{nesting:?}");
    assert_eq!(nesting.1["of"].as_u64(), Some(steps.len() as u64), "{nesting:?}");
    let read = evs
        .iter()
        .find(|(k, d)| k == "step" && d["step"] == "read")
        .expect("read");
    assert_eq!(read.1["label"], StepId::Read.label());
}

/// Two more boxes wait behind the held one: their places in the queue.
fn queue_places(server: &Server) -> [String; 2] {
    let (b, _) = upload(server, "box-b.stl");
    let (c, _) = upload(server, "box-c.stl");
    assert_eq!(
        (b["queue_ahead"].as_i64(), c["queue_ahead"].as_i64()),
        (Some(0), Some(1))
    );
    let (b, c) = (id_of(&b), id_of(&c));
    assert_eq!(server.get(&format!("/api/conversions/{c}")).json()["queue_ahead"], 1);
    [b, c]
}

/// A cancel keeps the plate method that landed; the job ends cancelled with one last event.
fn cancel_keeps_plate(server: &Server, id: &str, token: &str) {
    let bearer = format!("Bearer {token}");
    let r = server.request(
        "POST",
        &format!("/api/conversions/{id}/cancel"),
        &[("Authorization", &bearer)],
        b"",
    );
    assert_eq!(r.status, 200, "{}", r.text());
    let c = r.json();
    assert_eq!(c["status"], "cancelled", "{c}");
    assert_eq!(method_line(&c, "plate").expect("plate kept")["status"], "done", "{c}");
    let zip = get_ok(
        server,
        c["links"]["methods"]["plate"]["plan_zip"].as_str().expect("zip"),
    );
    assert_eq!(zip_parts(&zip), 6);
    let kinds: Vec<String> = events(&server.addr, id).into_iter().map(|(k, _)| k).collect();
    assert_eq!(kinds.last().map(String::as_str), Some("cancelled"), "{kinds:?}");
    assert_eq!(kinds.iter().filter(|k| *k == "cancelled").count(), 1, "{kinds:?}");
}

/// A worker killed after plate landed: the retry starts from nothing (its own model and plate
/// events after the `retry`), and the job ends done on its second attempt with each method
/// once.
fn retry_starts_afresh(server: &Server, gates: &Path) {
    let name = "platener-test-hold-d.stl";
    open_gate(gates, name, "plate");
    let (d, _) = upload(server, name);
    let d = id_of(&d);
    wait_until(server, &d, "plate landed on the first attempt", |c| {
        c["attempts"] == 1 && method_line(c, "plate").is_some()
    });
    let workers = server.worker_pids();
    assert_eq!(workers.len(), 1, "{workers:?}");
    signal(workers[0], "KILL");
    wait_until(server, &d, "plate landed on the second attempt", |c| {
        c["attempts"] == 2 && method_line(c, "plate").is_some()
    });
    for method in ["stacked", "classifier", "interlocked"] {
        open_gate(gates, name, method);
    }
    let c = server.wait_ended(&d);
    assert_eq!(
        (c["status"].as_str(), c["attempts"].as_i64()),
        (Some("done"), Some(2)),
        "{c}"
    );
    let methods: Vec<&str> = c["methods"]
        .as_array()
        .expect("methods")
        .iter()
        .filter_map(|m| m["method"].as_str())
        .collect();
    assert_eq!(methods, ["plate", "stacked", "classifier", "interlocked"], "{c}");
    let kinds: Vec<String> = events(&server.addr, &d).into_iter().map(|(k, _)| k).collect();
    let retry = kinds.iter().position(|k| k == "retry").expect("a retry event");
    for kind in ["model", "method"] {
        assert!(
            kinds[..retry].iter().any(|k| k == kind),
            "{kind} before the retry: {kinds:?}"
        );
        assert!(
            kinds[retry..].iter().any(|k| k == kind),
            "{kind} after the retry: {kinds:?}"
        );
    }
}

/// See the module documentation.
pub fn results_land_as_they_come(backend: Backend) {
    let data = tempfile::tempdir().expect("temp dir");
    let gates = tempfile::tempdir().expect("gates dir");
    let gate_dir = gates.path().to_str().expect("a UTF-8 path");
    let env = [("PLATENER_TEST_HOOKS", "1"), ("PLATENER_TEST_GATE", gate_dir)];
    // A 10 s lease: the worker sees the cancel at its next heartbeat within 2.5 s.
    let args = ["--workers", "1", "--no-examples", "--worker-lease", "10"];
    let Some(server) = Server::start_on(backend, data.path(), &args, &env) else {
        return;
    };
    let name = "platener-test-hold-a.stl";
    let (a, token) = upload(&server, name);
    assert_eq!(a["queue_ahead"], 0, "{a}");
    let a = id_of(&a);
    model_first(&server, &a);
    let [b, c] = queue_places(&server);
    open_gate(gates.path(), name, "plate");
    plate_lands_alone(&server, &a);
    cancel_keeps_plate(&server, &a, &token);
    check_events(&server, &a);
    for id in [&b, &c] {
        let done = server.wait_ended(id);
        assert_eq!(
            (done["status"].as_str(), done["queue_ahead"].as_i64()),
            (Some("done"), None)
        );
    }
    retry_starts_afresh(&server, gates.path());
}
