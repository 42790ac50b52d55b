//! `platener verify` driven through the real binary, on a plan `platener convert` wrote.

use std::path::{Path, PathBuf};

use assert_cmd::Command;

fn example(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples").join(name)
}

fn platener() -> Command {
    Command::cargo_bin("platener").expect("binary built")
}

/// Converts the shipped box with the plate method (and `extra` flags); returns the ZIP's path.
fn convert_box(out: &Path, extra: &[&str]) -> PathBuf {
    platener()
        .arg("convert")
        .arg(example("box-3mm.stl"))
        .arg("-o")
        .arg(out)
        .args(["--method", "plate"])
        .args(extra)
        .assert()
        .code(0);
    out.join("box-3mm-plate.zip")
}

/// `platener verify ZIP --model box-3mm.stl --json`, which must pass: its JSON report.
fn verified_against_the_box(zip: &Path) -> serde_json::Value {
    let o = platener()
        .arg("verify")
        .arg(zip)
        .arg("--model")
        .arg(example("box-3mm.stl"))
        .arg("--json")
        .output()
        .expect("runs");
    assert_eq!(o.status.code(), Some(0), "{}", String::from_utf8_lossy(&o.stdout));
    serde_json::from_slice(&o.stdout).expect("JSON")
}

#[test]
fn a_converted_box_verifies_against_its_model() {
    let out = tempfile::tempdir().expect("tempdir");
    let v = verified_against_the_box(&convert_box(out.path(), &[]));
    assert_eq!(v["parts"], 6);
    assert_eq!(v["groups"], 1);
    assert!(v["interference_share"].as_f64().expect("share") < 0.001);
    assert!(v["surface_covered"].as_f64().expect("covered") >= 0.98);
}

#[test]
fn a_file_that_is_not_a_plan_is_refused_with_its_name() {
    let dir = tempfile::tempdir().expect("tempdir");
    let path = dir.path().join("notes.zip");
    std::fs::write(&path, b"hello").expect("write");
    let o = platener().arg("verify").arg(&path).output().expect("runs");
    assert_eq!(o.status.code(), Some(1));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(err.contains("notes.zip") && err.contains("not a ZIP"), "{err}");
}

/// Issue 33: verify takes the plan's weld, sheets and features; flags for them would be
/// ignored, so they are refused as unknown, while the model's unit and scale are taken.
#[test]
fn verify_refuses_the_flags_it_would_ignore() {
    for flag in [["--weld", "0.5"], ["-t", "3"], ["--features", "cut"]] {
        let o = platener()
            .arg("verify")
            .arg("plan.zip")
            .args(flag)
            .output()
            .expect("runs");
        assert_eq!(o.status.code(), Some(2), "{flag:?}");
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(err.contains(flag[0]), "{flag:?}: {err}");
    }
    let o = platener()
        .args(["verify", "missing.zip", "--units", "cm", "--scale", "2"])
        .output()
        .expect("runs");
    assert_eq!(o.status.code(), Some(1), "the flags are taken; the missing plan fails");
}

#[test]
fn the_joint_option_chooses_the_joints() {
    let out = tempfile::tempdir().expect("tempdir");
    let bytes = std::fs::read(convert_box(out.path(), &["--joint", "jim"])).expect("zip");
    let plan = platener::verify::plan_from_zip(&bytes).expect("plan");
    assert_eq!(plan.joints.len(), 12);
    assert!(plan.joints.iter().all(|j| j.kind == platener::plan::JointKind::Jim));
}

/// Dovetails bring their keys as extra parts; the whole assembly (plates and keys) verifies
/// against the model: no interference, one group.
#[test]
fn dovetail_joints_come_with_keys_and_verify() {
    let out = tempfile::tempdir().expect("tempdir");
    let zip = convert_box(out.path(), &["--joint", "dovetail"]);
    let plan = platener::verify::plan_from_zip(&std::fs::read(&zip).expect("zip")).expect("plan");
    assert!(
        plan.joints
            .iter()
            .all(|j| j.kind == platener::plan::JointKind::Dovetail)
    );
    let keys = plan.parts.len() - 6;
    assert!(keys >= 24 && keys.is_multiple_of(2), "{keys} keys");
    assert_eq!(plan.joints.len(), 12 + keys);
    let v = verified_against_the_box(&zip);
    assert_eq!(v["parts"], 6 + keys);
    assert_eq!(v["groups"], 1, "{v}");
    assert!(v["interference_share"].as_f64().expect("share") < 0.001, "{v}");
    assert!(v["surface_covered"].as_f64().expect("covered") >= 0.98, "{v}");
}

#[test]
fn a_model_that_is_not_the_plans_source_is_named_and_the_plan_records_units_and_scale() {
    let dir = tempfile::tempdir().expect("temp dir");
    let zip = convert_box(dir.path(), &["--units", "cm", "--scale", "0.1"]);
    let plan = platener::verify::plan_from_zip(&std::fs::read(&zip).expect("zip")).expect("plan");
    assert_eq!((plan.source.units, plan.source.scale), (platener::Units::Cm, 0.1));
    // The same model read the same way matches (1 cm × 0.1 = 1 mm per unit).
    let same = verified_against(&zip, &["--units", "cm", "--scale", "0.1"]);
    assert_eq!(same["warnings"], serde_json::json!([]));
    // Read in cm without the scale it is ten times larger: a warning names both sizes and
    // the units and scale the plan was made with.
    let other = verified_against(&zip, &["--units", "cm"]);
    let warning = other["warnings"][0].as_str().expect("a warning");
    assert!(
        warning.contains("1000.0 × 800.0 × 600.0 mm") && warning.contains("100.0 × 80.0 × 60.0 mm"),
        "{warning}"
    );
    assert!(warning.contains("units cm, scale 0.1"), "{warning}");
}

/// `platener verify ZIP --model box-3mm.stl --json` with extra model flags: its JSON report,
/// whether or not it passed.
fn verified_against(zip: &Path, extra: &[&str]) -> serde_json::Value {
    let o = platener()
        .arg("verify")
        .arg(zip)
        .arg("--model")
        .arg(example("box-3mm.stl"))
        .args(extra)
        .arg("--json")
        .output()
        .expect("runs");
    serde_json::from_slice(&o.stdout).unwrap_or_else(|e| panic!("{e}: {}", String::from_utf8_lossy(&o.stderr)))
}

/// The ZIP at `zip` with its plan.json changed by `change`, written beside it as `name`.
fn altered(zip: &Path, name: &str, change: impl FnOnce(&mut platener::plan::Plan)) -> PathBuf {
    use std::io::Read;
    let bytes = std::fs::read(zip).expect("zip");
    let mut archive = zip::ZipArchive::new(std::io::Cursor::new(bytes)).expect("a ZIP");
    let mut files = std::collections::BTreeMap::new();
    for i in 0..archive.len() {
        let mut entry = archive.by_index(i).expect("entry");
        let mut data = Vec::new();
        entry.read_to_end(&mut data).expect("read");
        files.insert(entry.name().expect("entry name").to_string(), data);
    }
    let mut plan: platener::plan::Plan = serde_json::from_slice(&files["plan.json"]).expect("plan");
    change(&mut plan);
    files.insert("plan.json".into(), serde_json::to_vec_pretty(&plan).expect("json"));
    let path = zip.with_file_name(name);
    std::fs::write(&path, platener::export::zip_files(&files).expect("zipped")).expect("write");
    path
}

/// A plan with a loose part and a part pushed into its neighbours fails, and every failure
/// line names the parts.
#[test]
fn verify_fails_a_loose_part_and_overlapping_parts_naming_them() {
    let out = tempfile::tempdir().expect("tempdir");
    let zip = convert_box(out.path(), &[]);
    let broken = altered(&zip, "broken.zip", |plan| {
        plan.joints.retain(|j| !j.parts.contains(&3));
        let part = &mut plan.parts[1];
        for row in 0..3 {
            part.transform[row][3] -= part.transform[row][2] * 1.5;
        }
    });
    let o = platener()
        .arg("verify")
        .arg(&broken)
        .arg("--model")
        .arg(example("box-3mm.stl"))
        .output()
        .expect("runs");
    assert_eq!(o.status.code(), Some(1));
    let text = String::from_utf8_lossy(&o.stdout);
    let failed: Vec<&str> = text.lines().filter(|l| l.starts_with("FAILED")).collect();
    assert!(
        failed
            .iter()
            .any(|l| l.contains("no joint holds parts [3] to the rest")),
        "{text}"
    );
    assert!(
        failed
            .iter()
            .any(|l| l.contains("parts intersect") && (l.contains("parts 2 and") || l.contains("and 2 ("))),
        "{text}"
    );
}

/// The `edges` line: the box's walls fit only their partners or their twins' places; with
/// holes in two neighbouring walls they are no twins any more, and the wrong fits are counted
/// and named, without failing the plan.
#[test]
fn verify_counts_edges_that_fit_where_they_do_not_belong_without_failing() {
    let out = tempfile::tempdir().expect("tempdir");
    let zip = convert_box(out.path(), &[]);
    let v = verified_against_the_box(&zip);
    assert_eq!(v["mismatched_edges"]["accepting_pairs"], 0, "{v}");
    assert_eq!(v["mismatched_edges"]["joints_read"], 12, "{v}");
    let holed = altered(&zip, "holed.zip", |plan| {
        for part in plan.parts.iter_mut().filter(|p| p.id == 3 || p.id == 5) {
            let (lo, hi) = part.outline.iter().fold(
                (
                    platener::glam::DVec2::splat(f64::INFINITY),
                    platener::glam::DVec2::splat(f64::NEG_INFINITY),
                ),
                |(lo, hi), p| (lo.min(*p), hi.max(*p)),
            );
            let c = (lo + hi) / 2.0;
            let d = platener::glam::DVec2::new;
            // Clockwise, as plan.json's holes are.
            part.holes.push(vec![
                c + d(-5.0, -5.0),
                c + d(-5.0, 5.0),
                c + d(5.0, 5.0),
                c + d(5.0, -5.0),
            ]);
        }
    });
    let o = platener().arg("verify").arg(&holed).output().expect("runs");
    let text = String::from_utf8_lossy(&o.stdout);
    assert_eq!(o.status.code(), Some(0), "{text}");
    let edges = text.lines().find(|l| l.starts_with("edges")).expect("an edges line");
    assert!(
        edges.contains("of edges of different joints fit each other: joints "),
        "{edges}"
    );
}
