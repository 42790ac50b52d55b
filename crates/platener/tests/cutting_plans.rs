//! The cutting-plan rules of issue 5, checked on the files we write (SVG, DXF, plan.json, ZIP)
//! for part sets made in code. Tolerances: 0.01 mm for cut paths against nominal outlines (as
//! the issue states), 1e-6 mm² for "no overlap" (the boolean runs on the 1 µm grid, so parts
//! that are apart intersect in exactly nothing).

#[path = "cutting_plans/svg_read.rs"]
mod svg_read;

use std::collections::BTreeMap;
use std::sync::Arc;

use platener::Cancel;
use platener::export::{Bundle, dxf};
use platener::glam::{DVec2, DVec3};
use platener::labels::Labels;
use platener::pipeline::{self, State};
use platener::plan::samples::{fingered, l_shape, rectangle, window};
use platener::plan::{CutSettings, Joint, JointKind, Method, Part, Plan, PlanInput, SheetSize, SourceInfo};
use platener::sheets::Nesting;
use platener_geom::polygon::signed_area;
use platener_geom::{Polygon, boolean, offset};

/// A 1 µm grid boolean leaves at most this much "overlap" for parts that are apart: none.
const OVERLAP_TOL: f64 = 1e-6;
/// Cut paths must match the nominal outline offset by kerf/2 within this (mm).
const PATH_TOL: f64 = 0.01;

fn input(parts: Vec<Part>, settings: CutSettings) -> PlanInput {
    let joints = vec![Joint {
        parts: [1, 2],
        kind: JointKind::Finger,
        angle_deg: 90.0,
        label: 10,
    }];
    let source = SourceInfo {
        name: "test box".into(),
        triangles: 12,
        bbox_min: DVec3::ZERO,
        bbox_max: DVec3::splat(100.0),
        units: platener::Units::Mm,
        scale: 1.0,
        print: None,
    };
    let mut input = PlanInput::new(source, Method::Plate, parts, joints);
    input.settings = settings;
    input
}

/// Rectangles, an L, a plate with a hole, plates with finger notches, a small part to go into
/// the hole.
fn mixed_parts() -> Vec<Part> {
    vec![
        fingered(1, 200.0, 120.0, 4, 3.0),
        fingered(2, 160.0, 120.0, 3, 3.0),
        rectangle(3, 300.0, 80.0),
        l_shape(4, 150.0, 150.0, 40.0),
        window(5, 180.0, 180.0, 20.0),
        rectangle(6, 60.0, 60.0),
        rectangle(7, 40.0, 25.0),
        l_shape(8, 90.0, 60.0, 20.0),
        rectangle(9, 120.0, 45.0),
    ]
}

fn run(parts: Vec<Part>, settings: CutSettings) -> (PlanInput, CuttingPlan) {
    let input = input(parts, settings);
    let plan = cutting_plan(&input);
    (input, plan)
}

/// A part's polygon from its red rings: the largest is the outline (cut last, issue 34), the
/// others its holes.
fn polygon(rings: &[Vec<DVec2>]) -> Polygon {
    let outer = (0..rings.len())
        .max_by(|&a, &b| signed_area(&rings[a]).abs().total_cmp(&signed_area(&rings[b]).abs()))
        .expect("a ring");
    let mut p = Polygon {
        outer: rings[outer].clone(),
        holes: rings
            .iter()
            .enumerate()
            .filter(|(k, _)| *k != outer)
            .map(|(_, r)| r.clone())
            .collect(),
    };
    p.normalize_orientation();
    p
}

/// Each of `actual`'s rings equals one of `expected`'s: same vertex count, every vertex within
/// `PATH_TOL` of the other ring's nearest vertex, both ways.
fn assert_same_rings(actual: &[Vec<DVec2>], expected: &[Vec<DVec2>], what: &str) {
    assert_eq!(actual.len(), expected.len(), "{what}: ring count");
    let near = |p: &DVec2, ring: &[DVec2]| ring.iter().map(|q| q.distance(*p)).fold(f64::INFINITY, f64::min);
    for a in actual {
        let matched = expected.iter().any(|e| {
            e.len() == a.len() && a.iter().all(|p| near(p, e) <= PATH_TOL) && e.iter().all(|p| near(p, a) <= PATH_TOL)
        });
        assert!(matched, "{what}: a red ring matches no offset nominal ring");
    }
}

/// Two JSON trees are equal, numbers within 1e-12 relative (serde_json's default float parser
/// may differ from the shortest round-trip text by one unit in the last place).
fn assert_json_close(a: &serde_json::Value, b: &serde_json::Value, at: &str) {
    use serde_json::Value;
    match (a, b) {
        (Value::Number(x), Value::Number(y)) => {
            let (x, y) = (x.as_f64().expect("f64"), y.as_f64().expect("f64"));
            assert!((x - y).abs() <= 1e-12 * (1.0 + y.abs()), "{at}: {x} vs {y}");
        }
        (Value::Array(x), Value::Array(y)) => {
            assert_eq!(x.len(), y.len(), "{at}");
            x.iter()
                .zip(y)
                .enumerate()
                .for_each(|(i, (x, y))| assert_json_close(x, y, &format!("{at}[{i}]")));
        }
        (Value::Object(x), Value::Object(y)) => {
            assert_eq!(x.keys().collect::<Vec<_>>(), y.keys().collect::<Vec<_>>(), "{at}");
            x.iter()
                .for_each(|(k, v)| assert_json_close(v, &y[k], &format!("{at}.{k}")));
        }
        _ => assert_eq!(a, b, "{at}"),
    }
}

/// Every rule of the "Must hold", on the written files.
fn check(input: &PlanInput, plan: &CuttingPlan) {
    let bundle = &plan.bundle;
    let parsed: Plan = serde_json::from_slice(&bundle.files["plan.json"]).expect("plan.json parses");
    let written = serde_json::to_value(&bundle.plan).expect("to json");
    assert_json_close(&serde_json::to_value(&parsed).expect("to json"), &written, "plan");
    let kerf = input.settings.kerf();
    let mut seen: BTreeMap<String, usize> = BTreeMap::new();
    for sheet in &parsed.sheets {
        let svg = String::from_utf8(bundle.files[&sheet.file].clone()).expect("utf-8");
        // Each sheet names its stock (issue 34), as its LightBurn project's notes do.
        let stem = sheet.file.trim_end_matches(".svg");
        let stock = format!(
            "{stem}: {} mm {} sheet, {} × {} mm",
            sheet.thickness,
            input.settings.material.name(),
            sheet.width,
            sheet.height
        );
        assert!(svg.contains(&format!("<title>{stock}</title>")), "{stock}");
        let project = std::str::from_utf8(&bundle.files[&format!("{stem}.lbrn2")]).expect("utf-8");
        assert!(project.contains(&format!("Notes=\"{stock}\"")), "{stock}");
        let s = svg_read::parse(&svg);
        assert_eq!((s.width, s.height), (sheet.width, sheet.height), "true size in mm");
        assert_eq!(s.view_box, [0.0, 0.0, sheet.width, sheet.height]);
        let red_rings: usize = s.groups.values().map(|g| g.cut.len()).sum();
        assert_eq!(s.red, red_rings, "nothing but cut paths is red");
        let mut cut_polys = Vec::new();
        for (id, g) in &s.groups {
            *seen.entry(id.clone()).or_default() += 1;
            let part = parsed
                .parts
                .iter()
                .find(|p| format!("part-{}", p.id) == *id)
                .expect("a part");
            assert_eq!(part.sheet.index, sheet.index, "{id} is on the sheet plan.json says");
            // Inside the sheet.
            for p in g.cut.iter().flatten() {
                assert!(
                    p.x >= 0.0 && p.y >= 0.0 && p.x <= s.width && p.y <= s.height,
                    "{id} leaves the sheet at {p}"
                );
            }
            // Red = nominal moved by the placement and offset by kerf / 2.
            let nominal = Polygon {
                outer: part.outline.clone(),
                holes: part.holes.clone(),
            };
            assert!(signed_area(&nominal.outer) > 0.0 && nominal.holes.iter().all(|h| signed_area(h) < 0.0));
            let grown = offset::offset(&[nominal], kerf / 2.0).expect("grid");
            let expected: Vec<Vec<DVec2>> = grown
                .iter()
                .flat_map(|p| std::iter::once(&p.outer).chain(&p.holes))
                .map(|r| r.iter().map(|q| part.sheet.apply(*q)).collect())
                .collect();
            assert_same_rings(&g.cut, &expected, id);
            // Engraving stays on the part.
            let cut = polygon(&g.cut);
            for p in g.engrave.iter().flatten() {
                assert!(cut.contains(*p), "{id}: engraving at {p} is off the part");
            }
            cut_polys.push((id.clone(), cut));
        }
        for (i, (a, pa)) in cut_polys.iter().enumerate() {
            for (b, pb) in &cut_polys[i + 1..] {
                let both = boolean::intersection(std::slice::from_ref(pa), std::slice::from_ref(pb)).expect("grid");
                let area: f64 = both.iter().map(Polygon::area).sum();
                assert!(area <= OVERLAP_TOL, "{a} and {b} overlap by {area} mm²");
            }
        }
    }
    // Every part on exactly one sheet.
    assert_eq!(seen.len(), input.parts.len());
    assert!(seen.values().all(|n| *n == 1), "{seen:?}");
}

#[test]
fn a_mixed_set_follows_every_rule() {
    let (input, plan) = run(mixed_parts(), CutSettings::default());
    check(&input, &plan);
    assert_eq!(plan.nesting.sheets.len(), 1, "nine parts fit one 600 × 400 sheet");
    assert!(
        plan.nesting.sheets[0].density > 0.5,
        "{}",
        plan.nesting.sheets[0].density
    );
    // Finger-jointed edges carry their connection numbers.
    assert!(plan.labels.parts[0].boxes.iter().any(|b| b.text == "#10"));
}

#[test]
fn many_parts_fill_several_sheets_of_two_thicknesses() {
    let mut parts: Vec<Part> = (1..=14).map(|id| rectangle(id, 170.0, 130.0)).collect();
    parts.push(window(15, 250.0, 200.0, 30.0));
    for p in parts.iter_mut().skip(10) {
        p.thickness = 6.0;
    }
    let settings = CutSettings {
        kerf: Some(0.3),
        nest_tries: 3,
        ..CutSettings::default()
    };
    let (input, plan) = run(parts, settings);
    check(&input, &plan);
    let sheets = &plan.bundle.plan.sheets;
    assert!(sheets.len() >= 3, "{}", sheets.len());
    // Ten 170.3 × 130.3 mm cut paths fit the 590 × 390 mm inside one sheet's margins by area,
    // and the 6 mm parts another: at least 2 sheets (issue 34's lower bound).
    let report = &plan.bundle.report;
    assert_eq!(report.sheet_count_lower_bound, 2);
    assert!(report.sheet_count >= report.sheet_count_lower_bound);
    assert!(sheets.iter().any(|s| s.file == "test-box-6mm-1.svg"));
    assert!(sheets.windows(2).all(|w| w[0].thickness <= w[1].thickness));
}

/// Issue 34: the margin and the spacing asked for hold on the written sheets: no cut path
/// nearer the edge than the margin, none nearer another part's than the spacing.
#[test]
fn margins_and_spacing_are_kept_as_set() {
    let settings = CutSettings {
        margin: 20.0,
        spacing: 6.0,
        ..CutSettings::default()
    };
    let (input, plan) = run(mixed_parts(), settings);
    check(&input, &plan);
    for sheet in &plan.bundle.plan.sheets {
        let s = svg_read::parse(std::str::from_utf8(&plan.bundle.files[&sheet.file]).expect("utf-8"));
        let polys: Vec<Polygon> = s
            .groups
            .values()
            .filter(|g| !g.cut.is_empty())
            .map(|g| polygon(&g.cut))
            .collect();
        for p in polys.iter().flat_map(|p| p.outer.iter()) {
            let edge = p.x.min(p.y).min(sheet.width - p.x).min(sheet.height - p.y);
            assert!(edge >= 20.0 - 1e-3, "{p} is {edge} mm from the edge");
        }
        for (i, a) in polys.iter().enumerate() {
            for b in &polys[i + 1..] {
                let near = |from: &Polygon, to: &Polygon| {
                    from.outer
                        .iter()
                        .map(|p| to.distance_to(*p))
                        .fold(f64::INFINITY, f64::min)
                };
                let gap = near(a, b).min(near(b, a));
                assert!(gap >= 6.0 - 0.05, "two parts {gap} mm apart");
            }
        }
    }
}

#[test]
fn fitted_sheets_and_oversized_parts_keep_the_rules() {
    let (fitted, plan) = run(
        mixed_parts(),
        CutSettings {
            sheet: SheetSize::Fit,
            ..CutSettings::default()
        },
    );
    check(&fitted, &plan);
    assert_eq!(plan.nesting.sheets.len(), 1);
    // A part longer than the 600 mm sheet: the plan stops with an error that names it.
    let mut parts = mixed_parts();
    parts.push(rectangle(10, 650.0, 100.0));
    let err = pipeline::cutting_plan(input(parts, CutSettings::default()), &Cancel::default())
        .expect_err("part 10 does not fit");
    let text = err.to_string();
    assert!(
        text.contains("part 10 is 65") && text.contains("`sheet` to fit"),
        "{text}"
    );
}

#[test]
fn a_zip_written_twice_is_byte_identical() {
    let (_, a) = run(mixed_parts(), CutSettings::default());
    let (_, b) = run(mixed_parts(), CutSettings::default());
    assert_eq!(a.bundle.zip, b.bundle.zip);
    let names: Vec<&String> = a.bundle.files.keys().collect();
    let steps: Vec<String> = (1..=9).map(|k| format!("assembly/step-{k:02}.png")).collect();
    let mut expected = vec!["assembly.glb", "assembly.html", "assembly.pdf"];
    expected.extend(steps.iter().map(String::as_str));
    expected.extend([
        "plan.json",
        "report.json",
        "test-box-3mm-1.dxf",
        "test-box-3mm-1.lbrn2",
        "test-box-3mm-1.png",
        "test-box-3mm-1.svg",
        "test-box.pdf",
        "thumbnail.png",
    ]);
    assert_eq!(names, expected);
}

#[test]
fn plan_json_has_every_field_of_the_spec() {
    let (_, plan) = run(mixed_parts(), CutSettings::default());
    let v: serde_json::Value = serde_json::from_slice(&plan.bundle.files["plan.json"]).expect("json");
    let keys = |v: &serde_json::Value| -> Vec<String> {
        let mut k: Vec<String> = v.as_object().expect("object").keys().cloned().collect();
        k.sort();
        k
    };
    assert_eq!(
        keys(&v),
        [
            "assembly",
            "format",
            "generator",
            "joints",
            "method",
            "parts",
            "settings",
            "sheets",
            "source",
            "version"
        ]
    );
    assert_eq!(v["format"], "platener-plan");
    assert_eq!(v["version"], 2);
    assert_eq!(v["method"], "plate");
    assert_eq!(
        keys(&v["source"]),
        ["bbox_max", "bbox_min", "name", "scale", "triangles", "units"]
    );
    assert_eq!(
        (&v["source"]["units"], &v["source"]["scale"]),
        (&"mm".into(), &1.0.into())
    );
    let part = &v["parts"][0];
    assert_eq!(
        keys(part),
        [
            "holes",
            "id",
            "kind",
            "marks",
            "outline",
            "sheet",
            "thickness",
            "transform"
        ]
    );
    assert_eq!(keys(&part["sheet"]), ["index", "rotation", "x", "y"]);
    assert_eq!(part["transform"].as_array().expect("rows").len(), 3);
    assert_eq!(part["outline"][0].as_array().expect("point").len(), 2);
    assert_eq!(keys(&part["marks"][0]), ["kind", "path"]);
    assert_eq!(keys(&v["joints"][0]), ["angle", "kind", "label", "parts"]);
    assert_eq!(keys(&v["sheets"][0]), ["file", "height", "index", "thickness", "width"]);
    for k in ["thicknesses", "material", "kerf"] {
        assert!(v["settings"].get(k).is_some(), "settings.{k}");
    }
    assert_eq!(v["settings"]["kerf"], 0.2);
    // The outline does not repeat its first point.
    let outline = part["outline"].as_array().expect("points");
    assert_ne!(outline.first(), outline.last());
    let report: serde_json::Value = serde_json::from_slice(&plan.bundle.files["report.json"]).expect("json");
    for k in [
        "steps",
        "density",
        "part_count",
        "sheet_count",
        "cut_length",
        "estimated_cutting_seconds",
        "material_used_area",
    ] {
        assert!(report.get(k).is_some(), "report.{k}");
    }
}

#[test]
fn dxf_read_back_has_the_svg_areas() {
    let (_, plan) = run(mixed_parts(), CutSettings::default());
    for sheet in &plan.bundle.plan.sheets {
        let stem = sheet.file.trim_end_matches(".svg");
        let svg = svg_read::parse(std::str::from_utf8(&plan.bundle.files[&sheet.file]).expect("utf-8"));
        let bytes = &plan.bundle.files[&format!("{stem}.dxf")];
        let lines = dxf::read_polylines(bytes, sheet.height).expect("reads");
        let mut dxf_areas: Vec<f64> = lines
            .iter()
            .filter(|l| l.layer == dxf::CUT_LAYER)
            .inspect(|l| assert!(l.closed))
            .map(|l| signed_area(&l.points).abs())
            .collect();
        let mut svg_areas: Vec<f64> = svg
            .groups
            .values()
            .flat_map(|g| &g.cut)
            .map(|r| signed_area(r).abs())
            .collect();
        dxf_areas.sort_by(f64::total_cmp);
        svg_areas.sort_by(f64::total_cmp);
        assert_eq!(dxf_areas.len(), svg_areas.len());
        for (a, b) in dxf_areas.iter().zip(&svg_areas) {
            // The SVG rounds to 0.1 µm; the DXF keeps full precision.
            assert!((a - b).abs() < 1e-3 * (1.0 + b), "{a} vs {b}");
        }
        let engrave = lines.iter().filter(|l| l.layer == dxf::ENGRAVE_LAYER).count();
        assert_eq!(engrave, svg.groups.values().map(|g| g.engrave.len()).sum::<usize>());
    }
}

#[test]
fn the_cutting_plan_steps_leave_one_record_each() {
    let input = input(mixed_parts(), CutSettings::default());
    let plan = cutting_plan(&input);
    let names: Vec<&str> = plan.state.records.iter().map(|r| r.name).collect();
    assert_eq!(names, ["kerf", "labels", "sheets", "export"]);
    // report.json's steps are the records, plus export.
    let report: serde_json::Value = serde_json::from_slice(&plan.bundle.files["report.json"]).expect("json");
    let listed: Vec<&str> = report["steps"]
        .as_array()
        .expect("steps")
        .iter()
        .map(|s| s["name"].as_str().expect("name"))
        .collect();
    assert_eq!(listed, names);
}

/// Everything the cutting-plan steps made for parts made in a test.
struct CuttingPlan {
    state: State,
    bundle: Arc<Bundle>,
    labels: Arc<Labels>,
    nesting: Arc<Nesting>,
}

fn cutting_plan(input: &PlanInput) -> CuttingPlan {
    let state = pipeline::cutting_plan(input.clone(), &Cancel::default()).expect("a cutting plan");
    CuttingPlan {
        bundle: state.export.clone().expect("exported"),
        labels: state.labels.clone().expect("labelled"),
        nesting: state.sheets.clone().expect("nested"),
        state,
    }
}

#[path = "cutting_plans/more.rs"]
mod more;
