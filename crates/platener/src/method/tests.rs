use std::io::Read;
use std::sync::Arc;

use super::*;
use crate::samples;

#[test]
fn the_box_becomes_a_zip_with_six_parts_on_sheets() {
    let source = Source::Triangles {
        name: "box".into(),
        triangles: Arc::new(samples::closed_box(100.0, 80.0, 60.0, 3.0)),
    };
    let c = convert(MethodKind::Plate, source, Settings::default(), &Cancel::default()).expect("converts");
    let bundle = c.bundle().expect("exported");
    assert_eq!(bundle.plan.parts.len(), 6);
    let names: Vec<&str> = c.steps.iter().map(|s| s.name).collect();
    assert_eq!(
        names,
        [
            "read", "cleanup", "weld", "mesh", "coplanar", "shapes", "plates", "joints", "parts", "kerf", "labels",
            "sheets", "export"
        ]
    );
    // The ZIP holds plan.json, which lists the same six parts.
    let mut zip = zip::ZipArchive::new(std::io::Cursor::new(bundle.zip.clone())).expect("a ZIP");
    let mut plan = String::new();
    zip.by_name("plan.json")
        .expect("plan.json")
        .read_to_string(&mut plan)
        .expect("utf-8");
    let plan: serde_json::Value = serde_json::from_str(&plan).expect("JSON");
    assert_eq!(plan["parts"].as_array().expect("parts").len(), 6);
    assert_eq!(plan["method"], "plate");
    // Twelve finger-jointed edges, each naming its two parts and the 90° they enclose.
    let joints = plan["joints"].as_array().expect("joints");
    assert_eq!(joints.len(), 12);
    for j in joints {
        assert_eq!(j["kind"], "finger");
        assert!((j["angle"].as_f64().expect("angle") - 90.0).abs() < 1e-6);
    }
}

#[test]
fn plan_json_reads_back_as_a_plan() {
    let source = Source::Triangles {
        name: "box".into(),
        triangles: Arc::new(samples::closed_box(100.0, 80.0, 60.0, 3.0)),
    };
    let c = convert(MethodKind::Plate, source, Settings::default(), &Cancel::default()).expect("converts");
    let bundle = c.bundle().expect("exported");
    // No key twice (a flattened settings object could repeat one), and every field parses back.
    let plan = crate::verify::plan_from_zip(&bundle.zip).expect("plan.json parses");
    assert_eq!(plan.parts.len(), bundle.plan.parts.len());
    assert_eq!(plan.joints, bundle.plan.joints);
    assert_eq!(plan.settings.method, bundle.plan.settings.method);
    assert!(plan.settings.method.contains_key("offered_thicknesses"));
    // report.json carries the coverage report: every one of the box's 12 faces used by a plate.
    let report: serde_json::Value = serde_json::from_slice(&bundle.files["report.json"]).expect("JSON");
    let shapes = report["method_report"]["coverage"]["shapes"]
        .as_array()
        .expect("coverage");
    assert_eq!(shapes.len(), 12);
    assert!(
        shapes
            .iter()
            .all(|s| !s["plates"].as_array().expect("plates").is_empty())
    );
    assert_eq!(
        report["method_report"]["connections"]
            .as_array()
            .expect("connections")
            .len(),
        12
    );
}
