//! Measured sheets (issue 34, item 7): `thickness` 3@2.8 makes the parts for sheets that
//! measure 2.8 mm (fingers 2.8 mm long, so slots as deep), names the sheets 3 mm in files and
//! captions, and the plan still holds together without interference.

use platener::convert::{Status, no_progress};
use platener::glam::DVec2;
use platener::method::MethodKind;
use platener::options::Chosen;
use platener::{Cancel, Request, Source, convert_all};
use platener_fixtures::samples;

/// The depths of the steps along a part's outline near the edges of its box: how far each
/// coordinate level within 4 mm of the box's side lies inside it, mm.
fn finger_depths(outline: &[DVec2]) -> Vec<f64> {
    let mut depths = Vec::new();
    for axis in 0..2 {
        let mut levels: Vec<f64> = outline.iter().map(|p| p.to_array()[axis]).collect();
        levels.sort_by(f64::total_cmp);
        levels.dedup_by(|a, b| (*a - *b).abs() < 1e-6);
        let (lo, hi) = (levels[0], levels[levels.len() - 1]);
        for &l in &levels {
            for depth in [l - lo, hi - l] {
                if depth > 1e-6 && depth < 4.0 {
                    depths.push(depth);
                }
            }
        }
    }
    depths
}

#[test]
fn a_measured_sheet_makes_fingers_its_measured_thickness_and_keeps_its_nominal_name() {
    let model = samples::open_box(120.0, 80.0, 50.0, 3.0);
    let mut chosen = Chosen::default();
    chosen.set("thickness", &["3@2.8"]).expect("a measured sheet");
    assert_eq!(chosen.settings.thicknesses, vec![2.8]);
    let request = Request {
        methods: vec![MethodKind::Plate],
        ..Request::new(Source::triangles("case", model), chosen.settings.clone())
    };
    let all = convert_all(request, &Cancel::default(), no_progress());
    let plate = all
        .methods
        .iter()
        .find(|m| m.method == MethodKind::Plate && m.status == Status::Converted)
        .expect("the plate method converts");
    let bundle = plate.bundle().expect("a plan");
    let plan = &bundle.plan;
    assert!(
        plan.parts.iter().all(|p| p.thickness == 2.8),
        "parts are made for the measured sheet"
    );
    let depths: Vec<f64> = plan.parts.iter().flat_map(|p| finger_depths(&p.outline)).collect();
    assert!(depths.len() >= 8, "fingers on the case's edges: {depths:?}");
    for d in &depths {
        assert!((d - 2.8).abs() < 1e-3, "a finger {d} mm long, not 2.8 mm");
    }
    // Named by what it is sold as, saying what it measures.
    let svg = plan.sheets[0].file.as_str();
    assert!(svg.ends_with("-3mm-1.svg"), "{svg}");
    let text = std::str::from_utf8(&bundle.files[svg]).expect("utf-8");
    assert!(text.contains("3 mm wood sheet measured 2.8 mm"), "the SVG's title");
    // The parts are the model's walls at their measured thickness: they hold together
    // without interfering.
    let verdict = plate.verification.as_ref().expect("verified");
    assert_eq!(verdict.groups, 1, "one piece");
    assert!(verdict.interference.is_empty(), "{:?}", verdict.interference);
    // The setting reads back as it was given.
    assert_eq!(
        platener::options::find("thickness").expect("def").value(&chosen),
        serde_json::json!(["3@2.8"])
    );
}

#[test]
fn a_measured_thickness_far_from_its_nominal_one_is_refused() {
    let mut chosen = Chosen::default();
    let error = chosen.set("thickness", &["3@28.5"]).expect_err("a typing error");
    assert!(error.to_string().contains("within 25 %"), "{error}");
    assert!(chosen.set("thickness", &["3@x"]).is_err());
    chosen.set("thickness", &["3", "6@5.6"]).expect("mixed");
    assert_eq!(chosen.settings.thicknesses, vec![3.0, 5.6]);
    assert_eq!(chosen.settings.cut.nominal(5.6), 6.0);
    assert_eq!(chosen.settings.cut.nominal(3.0), 3.0);
}
