//! The assembly instructions (issue 35, item 3): `assembly.html`, `assembly.pdf` and a picture
//! per step in every ZIP, following plan.json's `assembly`; pictures that show the parts
//! placed so far in grey, the new part in colour and an arrow; a PDF page per two steps after
//! the parts list.

use platener::convert::{Status, no_progress};
use platener::export::Bundle;
use platener::export::instructions::{MAX_STEPS, PICTURE, pdf::STEPS_PER_PAGE};
use platener::export::thumbnail::{ARROW, BACKGROUND};
use platener::method::MethodKind;
use platener::{Cancel, Request, Settings, Source, convert_all};
use platener_fixtures::samples;

fn bundle(name: &str, triangles: Vec<platener::read::Triangle>, method: MethodKind) -> std::sync::Arc<Bundle> {
    let request = Request {
        methods: vec![method],
        ..Request::new(Source::triangles(name, triangles), Settings::default())
    };
    let all = convert_all(request, &Cancel::default(), no_progress());
    let result = all
        .methods
        .iter()
        .find(|m| m.method == method && m.status == Status::Converted)
        .unwrap_or_else(|| panic!("{name} converts with {method:?}"));
    result.bundle().expect("a plan").clone()
}

/// The RGB pixels of a PNG.
fn pixels(png: &[u8]) -> Vec<[u8; 3]> {
    let pixmap = resvg::tiny_skia::Pixmap::decode_png(png).expect("a PNG");
    assert_eq!((pixmap.width(), pixmap.height()), PICTURE);
    pixmap.data().chunks_exact(4).map(|p| [p[0], p[1], p[2]]).collect()
}

#[test]
fn a_boxs_instructions_show_each_step_with_its_picture() {
    let b = bundle("box", samples::closed_box(100.0, 80.0, 60.0, 3.0), MethodKind::Plate);
    let steps = &b.plan.assembly;
    assert_eq!(steps.len(), 6, "one step per plate");
    let html = std::str::from_utf8(&b.files["assembly.html"]).expect("utf-8");
    for (k, step) in steps.iter().enumerate() {
        let file = format!("assembly/step-{:02}.png", k + 1);
        assert!(html.contains(&format!("src=\"{file}\"")), "the page shows {file}");
        assert!(html.contains(&format!("Step {} of 6", k + 1)));
        let px = pixels(&b.files[&file]);
        let drawn = px.iter().filter(|p| **p != BACKGROUND).count();
        assert!(
            drawn > px.len() / 20,
            "step {}: {drawn} of {} pixels drawn",
            k + 1,
            px.len()
        );
        // Grey parts placed before (none at the base), and an arrow for every part that moves
        // in onto others.
        let grey = px
            .iter()
            .filter(|p| p[0] == p[1] && p[1] == p[2] && p[0] < 250 && p[0] > 60)
            .count();
        let arrow = px.iter().filter(|p| **p == ARROW).count();
        if k == 0 {
            assert!(html.contains(&format!("Lay part {} down as the base.", step.parts[0])));
            assert_eq!(arrow, 0, "the base has no arrow");
        } else {
            assert!(grey > 100, "step {}: the placed parts in grey ({grey} pixels)", k + 1);
            assert!(arrow > 50, "step {}: an arrow ({arrow} pixels)", k + 1);
        }
    }
    // The lid goes last and says which engraved edge numbers it closes.
    let last = steps.last().expect("steps");
    for &j in &last.joints {
        let label = b.plan.joints[j].label;
        assert!(html.contains(&format!("edge {label} to part")), "edge {label} named");
    }
    // The twins (base and lid, the long walls, the short walls) are told once each, where the
    // first of them goes in; report.json gives the same groups.
    let report: serde_json::Value = serde_json::from_slice(&b.files["report.json"]).expect("report.json");
    let groups = &report["mismatched_edges"]["interchangeable_parts"];
    assert_eq!(report["mismatched_edges"]["accepting_pairs"], 0);
    assert_eq!(groups.as_array().map(Vec::len), Some(3), "{groups}");
    for g in groups.as_array().into_iter().flatten() {
        let ids: Vec<u64> = g.as_array().into_iter().flatten().filter_map(|v| v.as_u64()).collect();
        let said = format!(
            "Parts {} and {} are identical: either one fits in either of their places.",
            ids[0], ids[1]
        );
        assert_eq!(html.matches(&said).count(), 1, "{said}");
        let first = steps
            .iter()
            .position(|s| s.parts.iter().any(|p| ids.contains(&u64::from(*p))));
        let told = report["assembly_steps"][first.expect("a step adds them")]["lines"].to_string();
        assert!(told.contains(&said), "{told}");
    }
    // Parts list: every part with its number.
    for part in &b.plan.parts {
        assert!(html.contains(&format!("aria-label=\"part {}\"", part.id)));
    }
    let pdf = &b.files["assembly.pdf"];
    assert!(pdf.starts_with(b"%PDF-"));
    let pages = platener::export::pdf::read::read_pages(pdf).expect("the PDF reads back");
    assert_eq!(
        pages.len(),
        1 + 6usize.div_ceil(STEPS_PER_PAGE),
        "parts list, then 2 steps a page"
    );
    assert_eq!(pages[0].images, 0);
    assert!(pages[0].paths.len() >= 6, "every part drawn in the list");
    for page in &pages[1..] {
        assert_eq!(page.images, STEPS_PER_PAGE, "a picture a step");
        assert!(
            (page.size.x - 210.0).abs() < 0.01 && (page.size.y - 297.0).abs() < 0.01,
            "A4"
        );
    }
}

#[test]
fn a_long_stack_is_told_in_runs_of_layers() {
    let b = bundle(
        "sphere",
        samples::sphere(glam::DVec3::ZERO, 40.0, 48, 24),
        MethodKind::Stacked,
    );
    let parts = b.plan.parts.len();
    assert!(parts > MAX_STEPS, "{parts} parts");
    let html = std::str::from_utf8(&b.files["assembly.html"]).expect("utf-8");
    let steps = html.matches("<section class=\"step\"").count();
    assert!(steps <= MAX_STEPS && steps > 1, "{steps} steps for {parts} parts");
    // Every part is added in exactly one step.
    let mut added: Vec<u32> = b.plan.assembly.iter().flat_map(|s| s.parts.clone()).collect();
    added.sort_unstable();
    let mut ids: Vec<u32> = b.plan.parts.iter().map(|p| p.id).collect();
    ids.sort_unstable();
    assert_eq!(added, ids);
    assert_eq!(
        b.files.keys().filter(|k| k.starts_with("assembly/step-")).count(),
        steps
    );
}

/// Two boxes side by side are two objects: each is built on its own, in one run of steps
/// starting with its own base (no arrow), and the instructions say which parts it has.
#[test]
fn separate_objects_are_built_one_after_another() {
    let mut model = samples::closed_box(100.0, 80.0, 60.0, 3.0);
    let shift = glam::DVec3::new(160.0, 0.0, 0.0);
    model.extend(
        samples::closed_box(100.0, 80.0, 60.0, 3.0)
            .into_iter()
            .map(|t| t.map(|v| v + shift)),
    );
    let b = bundle("two boxes", model, MethodKind::Plate);
    let steps = &b.plan.assembly;
    assert_eq!(steps.len(), 12, "{steps:?}");
    let numbers: Vec<Option<u32>> = steps.iter().map(|s| s.subassembly).collect();
    assert_eq!(numbers[..6], [Some(1); 6], "{numbers:?}");
    assert_eq!(numbers[6..], [Some(2); 6], "{numbers:?}");
    // Each object's parts are one box: all on one side of the gap between them.
    let centre_x = |id: u32| {
        let p = b.plan.parts.iter().find(|p| p.id == id).expect("a part");
        p.transform[0][3]
    };
    for object in [&steps[..6], &steps[6..]] {
        let xs: Vec<f64> = object.iter().map(|s| centre_x(s.parts[0])).collect();
        assert!(
            xs.iter().all(|x| *x < 130.0) || xs.iter().all(|x| *x > 130.0),
            "one object spans both boxes: {xs:?}"
        );
    }
    let html = std::str::from_utf8(&b.files["assembly.html"]).expect("utf-8");
    for (n, object) in [(1, &steps[..6]), (2, &steps[6..])] {
        let mut ids: Vec<u32> = object.iter().map(|s| s.parts[0]).collect();
        ids.sort_unstable();
        let words: Vec<String> = ids.iter().map(u32::to_string).collect();
        let said = format!(
            "Object {n} of 2 (parts {} and {}): build it on its own.",
            words[..5].join(", "),
            words[5]
        );
        assert!(html.contains(&said), "{said}");
        assert!(html.contains(&format!("Lay part {} down as the base.", object[0].parts[0])));
    }
    let px = pixels(&b.files["assembly/step-07.png"]);
    assert_eq!(
        px.iter().filter(|p| **p == ARROW).count(),
        0,
        "the second base has no arrow"
    );
}

/// Loose plates no joint holds (tiles side by side) are each laid down on their own, with no
/// object heading and no arrow.
#[test]
fn loose_plates_are_laid_down_on_their_own() {
    use glam::DVec3;
    let mut model = samples::cuboid(DVec3::ZERO, DVec3::new(60.0, 40.0, 3.0));
    model.extend(samples::cuboid(
        DVec3::new(80.0, 0.0, 0.0),
        DVec3::new(140.0, 40.0, 3.0),
    ));
    let b = bundle("tiles", model, MethodKind::Plate);
    let steps = &b.plan.assembly;
    assert_eq!(steps.len(), 2, "{steps:?}");
    assert_eq!(
        steps.iter().map(|s| s.subassembly).collect::<Vec<_>>(),
        [Some(1), Some(2)]
    );
    let html = std::str::from_utf8(&b.files["assembly.html"]).expect("utf-8");
    assert!(!html.contains("Object "), "no heading for a one-part object");
    for s in steps {
        let said = format!(
            "Lay part {} down on its own: no joint holds it to the others.",
            s.parts[0]
        );
        assert!(html.contains(&said), "{said}");
    }
    let px = pixels(&b.files["assembly/step-02.png"]);
    assert_eq!(
        px.iter().filter(|p| **p == ARROW).count(),
        0,
        "a loose plate has no arrow"
    );
}
