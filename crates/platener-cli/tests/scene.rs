//! `platener scene` driven through the real binary.

use std::io::Read as _;
use std::path::{Path, PathBuf};

use assert_cmd::Command;

fn example(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples").join(name)
}

fn platener() -> Command {
    let mut c = Command::cargo_bin("platener").expect("binary built");
    c.env_remove("PLATENER_FAULT");
    c
}

/// `platener scene examples/box-3mm.stl ARGS -o OUT`.
fn scene_of_box(args: &[&str], out: &Path) -> std::process::Output {
    platener()
        .arg("scene")
        .arg(example("box-3mm.stl"))
        .args(args)
        .arg("-o")
        .arg(out)
        .output()
        .expect("runs")
}

/// The JSON chunk of a GLB (after the 12-byte header and the chunk's 8-byte header).
fn glb_json(glb: &[u8]) -> serde_json::Value {
    assert_eq!(&glb[..4], b"glTF", "GLB magic");
    assert_eq!(u32::from_le_bytes(glb[4..8].try_into().expect("4 bytes")), 2, "glTF 2");
    assert_eq!(
        u32::from_le_bytes(glb[8..12].try_into().expect("4 bytes")) as usize,
        glb.len()
    );
    let len = u32::from_le_bytes(glb[12..16].try_into().expect("4 bytes")) as usize;
    assert_eq!(&glb[16..20], b"JSON");
    serde_json::from_slice(&glb[20..20 + len]).expect("JSON chunk")
}

#[test]
fn the_final_view_is_the_assembly_in_the_plan_zip() {
    let dir = tempfile::tempdir().expect("temp dir");
    let glb = dir.path().join("box.glb");
    let out = scene_of_box(&["--method", "plate"], &glb);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let convert = platener()
        .args([
            "convert",
            example("box-3mm.stl").to_str().expect("utf-8"),
            "--method",
            "plate",
            "-o",
        ])
        .arg(dir.path())
        .output()
        .expect("runs");
    assert!(convert.status.success(), "{}", String::from_utf8_lossy(&convert.stderr));
    let zip = std::fs::read(dir.path().join("box-3mm-plate.zip")).expect("zip written");
    let mut archive = zip::ZipArchive::new(std::io::Cursor::new(zip)).expect("a ZIP");
    let mut in_zip = Vec::new();
    archive
        .by_name("assembly.glb")
        .expect("assembly.glb in the ZIP")
        .read_to_end(&mut in_zip)
        .expect("readable");
    assert_eq!(std::fs::read(&glb).expect("glb written"), in_zip);
}

#[test]
fn the_plates_view_has_one_node_per_plate_under_the_scaled_root() {
    let dir = tempfile::tempdir().expect("temp dir");
    let glb = dir.path().join("plates.glb");
    let out = scene_of_box(&["--view", "plates"], &glb);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let json = glb_json(&std::fs::read(&glb).expect("written"));
    let nodes = json["nodes"].as_array().expect("nodes");
    let root = &nodes[json["scenes"][0]["nodes"][0].as_u64().expect("root") as usize];
    assert_eq!(root["scale"], serde_json::json!([0.001, 0.001, 0.001]));
    let names: Vec<&str> = root["children"]
        .as_array()
        .expect("children")
        .iter()
        .map(|c| {
            nodes[c.as_u64().expect("index") as usize]["name"]
                .as_str()
                .expect("name")
        })
        .collect();
    assert_eq!(
        names,
        ["plate-1", "plate-2", "plate-3", "plate-4", "plate-5", "plate-6"]
    );
}

#[test]
fn a_view_the_method_has_not_or_an_unknown_view_is_an_error() {
    let dir = tempfile::tempdir().expect("temp dir");
    let glb = dir.path().join("x.glb");
    let out = scene_of_box(&["--view", "plates", "--method", "stacked"], &glb);
    assert_eq!(out.status.code(), Some(1));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(stderr.contains("needs step plates"), "{stderr}");
    assert!(!glb.exists());
    let out = scene_of_box(&["--view", "primitives", "--method", "plate"], &glb);
    assert_eq!(out.status.code(), Some(1));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(stderr.contains("needs step classify"), "{stderr}");
    let out = scene_of_box(&["--view", "assembly"], &glb);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("unknown view"));
}

/// The classifier's primitives of the box: a plane node per wall face, each with its inlier
/// points beside its triangles and its fitted plane in `extras`.
#[test]
fn the_primitives_view_names_each_plane_and_carries_its_shape() {
    let dir = tempfile::tempdir().expect("temp dir");
    let glb = dir.path().join("primitives.glb");
    let out = scene_of_box(&["--view", "primitives", "--method", "classifier"], &glb);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{stderr}");
    assert!(
        stderr.contains("the primitives view of the classifier method"),
        "{stderr}"
    );
    let json = glb_json(&std::fs::read(&glb).expect("written"));
    let nodes = json["nodes"].as_array().expect("nodes");
    let planes: Vec<&serde_json::Value> = nodes
        .iter()
        .filter(|n| n["name"].as_str().is_some_and(|s| s.starts_with("plane-")))
        .collect();
    assert!(planes.len() >= 6, "{stderr}");
    for n in planes {
        let normal = n["extras"]["shape"]["normal"].as_array().expect("a plane's normal");
        let length: f64 = normal.iter().filter_map(serde_json::Value::as_f64).map(|c| c * c).sum();
        assert!((length - 1.0).abs() < 1e-9, "{n}");
        let mesh = &json["meshes"][n["mesh"].as_u64().expect("mesh") as usize];
        let modes: Vec<u64> = mesh["primitives"]
            .as_array()
            .expect("primitives")
            .iter()
            .filter_map(|p| p["mode"].as_u64())
            .collect();
        assert_eq!(modes, [4, 0], "triangles, then the inlier points: {n}");
    }
}
