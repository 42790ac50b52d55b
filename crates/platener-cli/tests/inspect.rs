//! `platener inspect` driven through the real binary.

use std::path::{Path, PathBuf};

use assert_cmd::Command;

fn example(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples").join(name)
}

fn platener() -> Command {
    Command::cargo_bin("platener").expect("binary built")
}

fn json(args: &[&str]) -> serde_json::Value {
    let out = platener().args(args).arg("--json").output().expect("runs");
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    serde_json::from_slice(&out.stdout).expect("valid JSON")
}

#[test]
fn box_example_as_json() {
    let v = json(&["inspect", example("box-3mm.stl").to_str().expect("utf-8")]);
    assert_eq!(v["format"], "STL (binary)");
    assert_eq!(v["triangles_read"], 120);
    assert_eq!(v["shapes"], 12);
    assert_eq!(v["health"]["closed"], true);
    assert_eq!(v["health"]["components"], 2);
    let volume = v["health"]["volume"].as_f64().expect("volume");
    assert!((volume - (100.0 * 80.0 * 60.0 - 94.0 * 74.0 * 54.0)).abs() < 1e-3);
    assert_eq!(v["bounds"]["max"], serde_json::json!([100.0, 80.0, 60.0]));
    let largest = v["largest_shapes"][0]["area"].as_f64().expect("area");
    assert!((largest - 8000.0).abs() < 1e-6);
    let steps: Vec<&str> = v["steps"]
        .as_array()
        .expect("steps")
        .iter()
        .map(|s| s["name"].as_str().expect("name"))
        .collect();
    assert_eq!(steps, ["read", "cleanup", "weld", "mesh", "coplanar", "shapes"]);
}

#[test]
fn text_report_names_what_it_found() {
    let out = platener()
        .arg("inspect")
        .arg(example("tray-3mm.stl"))
        .output()
        .expect("runs");
    assert!(out.status.success());
    let text = String::from_utf8(out.stdout).expect("utf-8");
    assert!(text.contains("120.00 × 80.00 × 40.00 mm"), "{text}");
    assert!(text.contains("11 planar shapes"), "{text}");
    assert!(text.contains("9600.00"), "{text}");
}

#[test]
fn units_scale_the_model() {
    let v = json(&[
        "inspect",
        example("box-3mm.stl").to_str().expect("utf-8"),
        "--units",
        "cm",
    ]);
    assert_eq!(v["bounds"]["max"], serde_json::json!([1000.0, 800.0, 600.0]));
    let v = json(&[
        "inspect",
        example("box-3mm.stl").to_str().expect("utf-8"),
        "--scale",
        "0.001",
    ]);
    let warnings = v["steps"][0]["warnings"].as_array().expect("warnings");
    assert!(warnings.iter().any(|w| w["kind"] == "units"), "{warnings:?}");
}

#[test]
fn missing_file_fails_with_its_name() {
    let out = platener()
        .args(["inspect", "no/such/model.stl"])
        .output()
        .expect("runs");
    assert_eq!(out.status.code(), Some(1));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("no/such/model.stl") && err.contains("cannot read"),
        "{err}"
    );
}

#[test]
fn other_file_types_are_refused_with_the_formats_we_read() {
    let dir = tempfile::tempdir().expect("tempdir");
    let path = dir.path().join("drawing.dxf");
    std::fs::write(&path, "0\nSECTION\n").expect("write");
    let out = platener().arg("inspect").arg(&path).output().expect("runs");
    assert_eq!(out.status.code(), Some(1));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains(".stl, .obj and .3mf"), "{err}");
}

#[test]
fn usage_errors_exit_with_2() {
    platener().args(["inspect"]).assert().code(2);
    platener().args(["inspect", "x.stl", "--weld", "lots"]).assert().code(1);
    platener()
        .args(["inspect", "x.stl", "--units", "furlong"])
        .assert()
        .code(2);
}
