//! The debug view's service side against a real `platener serve` (127.0.0.1, SQLite in a temp
//! dir, one worker): a conversion submitted with `debug=true` has every step's snapshot stored
//! by the worker, served as JSON with real values (a box: 6 plates from 6 face pairs, 12
//! corner joints with finger style), with scene links that load; options reach the library;
//! a conversion without `debug` has none; the test set is served.

mod web_support;

use serde_json::{Value, json};
use web_support::{Server, example_box};

const PLATE_STEPS: [&str; 14] = [
    "read", "cleanup", "weld", "mesh", "coplanar", "shapes", "plates", "bends", "joints", "parts", "kerf", "labels",
    "sheets", "export",
];

fn start() -> (tempfile::TempDir, Server) {
    let dir = tempfile::tempdir().expect("temp dir");
    let server = Server::start(dir.path(), &["--workers", "1", "--no-examples"], &[]);
    (dir, server)
}

/// Uploads `model` with `fields`, waits for its end; the conversion's id.
fn convert(server: &Server, name: &str, model: &[u8], fields: &[(&str, &str)]) -> String {
    let r = server.upload(name, model, fields);
    assert_eq!(r.status, 202, "{}", r.text());
    let id = r.json()["id"].as_str().expect("id").to_string();
    server.wait_ended(&id);
    id
}

/// GETs `path`, checks status 200 and the content type; the body as JSON.
fn get_json(server: &Server, path: &str) -> Value {
    let r = server.get(path);
    assert_eq!(r.status, 200, "{path}: {}", r.text());
    assert_eq!(r.header("content-type"), Some("application/json"), "{path}");
    r.json()
}

/// The step `name` of a debug index's first method.
fn step<'a>(index: &'a Value, name: &str) -> &'a Value {
    index["methods"][0]["steps"]
        .as_array()
        .expect("steps")
        .iter()
        .find(|s| s["step"] == name)
        .unwrap_or_else(|| panic!("no step {name} in {index}"))
}

#[test]
fn a_debug_box_stores_every_step_with_real_plate_pairs_and_joint_kinds() {
    let (_dir, server) = start();
    let id = convert(
        &server,
        "box-3mm.stl",
        &example_box(),
        &[("debug", "true"), ("method", "plate"), ("thickness", "3")],
    );
    let c = server.get(&format!("/api/conversions/{id}")).json();
    assert_eq!(c["status"], "done", "{c}");
    assert_eq!(c["settings"]["debug"], true);
    assert_eq!(c["links"]["debug"], format!("/api/conversions/{id}/debug"));
    assert!(
        c["links"]["methods"]["plate"].get("debug/index_json").is_none(),
        "debug files stay out of the method links: {c}"
    );

    let index = get_json(&server, &format!("/api/conversions/{id}/debug"));
    assert_eq!(index["methods"].as_array().map(Vec::len), Some(1));
    assert_eq!(index["methods"][0]["method"], "plate");
    let steps = index["methods"][0]["steps"].as_array().expect("steps");
    let names: Vec<&str> = steps.iter().filter_map(|s| s["step"].as_str()).collect();
    assert_eq!(names, PLATE_STEPS);
    for pair in steps.windows(2) {
        assert_eq!(pair[1]["input"], pair[0]["step"], "each step's input is the one before");
    }
    assert!(steps.iter().all(|s| s["ms"].as_f64().is_some_and(|ms| ms >= 0.0)));

    let plates_step = step(&index, "plates");
    assert_eq!(plates_step["view"], "plates");
    assert_eq!(
        plates_step["scene"],
        format!("/api/conversions/{id}/scenes/plates.glb?method=plate")
    );
    assert_eq!(step(&index, "joints")["view_exact"], false);
    let scene = server.get(plates_step["scene"].as_str().expect("scene link"));
    assert_eq!(scene.status, 200);
    assert_eq!(scene.header("content-type"), Some("model/gltf-binary"));
    assert_eq!(&scene.body[..4], b"glTF");

    let plates = get_json(&server, plates_step["json"].as_str().expect("json link"));
    assert_eq!(plates["step"], "plates");
    assert_eq!(plates["input"], "shapes");
    assert_eq!(plates["summary"]["count"], 6);
    assert_eq!(
        plates["summary"]["pairs"], 6,
        "a closed box: six pairs of opposite faces"
    );
    let ids: Vec<u64> = plates["summary"]["plates"]
        .as_array()
        .expect("plates")
        .iter()
        .filter_map(|p| p["id"].as_u64())
        .collect();
    assert_eq!(ids, [1, 2, 3, 4, 5, 6]);
    assert!(plates["snapshot"]["plates"].is_array(), "the snapshot itself, bounded");

    check_joints_and_parts(&server, &index);

    for bad in [
        format!("/api/conversions/{id}/debug/plate/nosuchstep.json"),
        format!("/api/conversions/{id}/debug/plate/plates.txt"),
        format!("/api/conversions/{id}/debug/bent/plates.json"),
        format!("/api/conversions/{id}/debug/stacked/plates.json"),
        "/api/conversions/c_nosuchconversion/debug".to_string(),
    ] {
        server.get(&bad).assert_error(404, "not_found");
    }
}

/// The box's joints (12 corner joints with finger style, four per plate) and parts.
fn check_joints_and_parts(server: &Server, index: &Value) {
    let joints = get_json(server, step(index, "joints")["json"].as_str().expect("json link"));
    assert_eq!(joints["summary"]["count"], 12);
    let connections = joints["summary"]["connections"].as_array().expect("connections");
    assert_eq!(connections.len(), 12);
    for c in connections {
        assert_eq!(
            (c["kind"].as_str(), c["style"].as_str()),
            (Some("corner"), Some("finger")),
            "{c}"
        );
        assert!((c["angle_deg"].as_f64().unwrap_or(0.0) - 90.0).abs() < 1.0, "{c}");
    }
    // Every plate of a box meets four others.
    for plate in 1..=6u64 {
        let n = connections
            .iter()
            .filter(|c| {
                c["plates"]
                    .as_array()
                    .is_some_and(|p| p.iter().any(|x| x.as_u64() == Some(plate)))
            })
            .count();
        assert_eq!(n, 4, "plate {plate}");
    }
    let parts = get_json(server, step(index, "parts")["json"].as_str().expect("json link"));
    assert_eq!(parts["summary"]["count"], 6);
    assert_eq!(parts["summary"]["joints"].as_array().map(Vec::len), Some(12));
}

#[test]
fn options_reach_the_worker_and_plain_conversions_keep_no_snapshots() {
    let (_dir, server) = start();
    let plain = convert(&server, "box-3mm.stl", &example_box(), &[("method", "plate")]);
    server
        .get(&format!("/api/conversions/{plain}/debug"))
        .assert_error(404, "not_found");
    let c = server.get(&format!("/api/conversions/{plain}")).json();
    assert_eq!(c["links"]["debug"], Value::Null);

    let models = get_json(&server, "/api/debug/models");
    let names: Vec<&str> = models["models"]
        .as_array()
        .expect("models")
        .iter()
        .filter_map(|m| m["name"].as_str())
        .collect();
    for name in [
        "closed-box",
        "shelf",
        "crossing-plates",
        "solid-block",
        "box-3mm",
        "phone-stand",
    ] {
        assert!(names.contains(&name), "{name} in {names:?}");
    }
    assert_eq!(models["methods"]["plate"], json!(PLATE_STEPS));
    let block = server.get("/api/debug/models/solid-block.stl");
    assert_eq!(block.status, 200);
    assert_eq!(block.header("content-type"), Some("model/stl"));
    assert_eq!(block.body.len(), 84 + 50 * 12, "a cuboid: 12 triangles of binary STL");
    server
        .get("/api/debug/models/nosuchmodel.stl")
        .assert_error(404, "not_found");

    // A solid block has no inherent plates: with all plates it is a hull of extruded ones,
    // with inherent plates only it has none.
    let all = convert(
        &server,
        "solid-block.stl",
        &block.body,
        &[("debug", "true"), ("method", "plate")],
    );
    let index = get_json(&server, &format!("/api/conversions/{all}/debug"));
    let plates = get_json(&server, step(&index, "plates")["json"].as_str().expect("json"));
    assert_eq!(plates["summary"]["pairs"], 0);
    assert!(
        plates["summary"]["count"].as_u64().is_some_and(|n| n >= 6),
        "{}",
        plates["summary"]
    );

    let token_free = server.request(
        "POST",
        &format!("/api/conversions/{all}/recut"),
        &[("Content-Type", "application/json")],
        br#"{"plates": "inherent", "weld": 0}"#,
    );
    assert_eq!(token_free.status, 202, "{}", token_free.text());
    let recut = token_free.json()["id"].as_str().expect("id").to_string();
    let ended = server.wait_ended(&recut);
    assert_eq!(ended["settings"]["plates"], "inherent");
    assert_eq!(ended["settings"]["debug"], true, "a recut keeps the debug setting");
    let index = get_json(&server, &format!("/api/conversions/{recut}/debug"));
    let weld = get_json(&server, step(&index, "weld")["json"].as_str().expect("json"));
    assert_eq!(weld["summary"]["distance"], 0.0, "weld 0: exact duplicates only");
    let plates = index["methods"][0]["steps"]
        .as_array()
        .expect("steps")
        .iter()
        .find(|s| s["step"] == "plates");
    if let Some(p) = plates {
        let p = get_json(&server, p["json"].as_str().expect("json"));
        assert_eq!(p["summary"]["count"], 0, "{}", p["summary"]);
        assert!(
            p["warnings"].as_array().is_some_and(|w| !w.is_empty()),
            "the plates step says why it found none: {p}"
        );
    } else {
        assert_eq!(
            ended["status"], "failed",
            "no plates step stored only when it failed: {ended}"
        );
    }
}
