//! A bent part on paper (issue 19): a part made by hand of two 40 mm squares joined by one
//! living-hinge bend, with slits in the bend zone, run through the cutting-plan steps. Checks
//! plan.json version 2 (segments, bends, merged, mark kinds), the slits as red open paths in
//! the SVG at the nested position, that kerf leaves them as drawn, that labels keep out of the
//! zone, and that the cut length counts the slits. Also: a version 1 plan still reads.

use platener::Cancel;
use platener::export::{Bundle, zip_files};
use platener::glam::{DVec2, DVec3};
use platener::pipeline::{self, State};
use platener::plan::{
    Bend, BendStyle, Joint, JointKind, Mark, MarkKind, Method, Part, PartKind, Plan, PlanInput, Segment, SourceInfo,
};
use platener::verify::plan_from_zip;
use platener_geom::Frame;
use platener_geom::polygon::{Polygon, rect};
use serde_json::Value;

/// Side of each square segment, mm.
const SIDE: f64 = 40.0;
/// Width of the bend zone, mm.
const ZONE: f64 = 6.0;
/// Sheet thickness, mm.
const THICKNESS: f64 = 3.0;
/// The id of the bent part; its plates are numbered after it (as the bends step does).
const BENT_ID: u32 = 1;
const PLATES: [u32; 2] = [3, 4];

/// The slits of the hinge: vertical lines inside the zone (x from 40 to 46), clear of the
/// outline. Their total length is [`SLIT_LENGTH`].
fn slits() -> Vec<Vec<DVec2>> {
    let v = |x: f64, y0: f64, y1: f64| vec![DVec2::new(x, y0), DVec2::new(x, y1)];
    vec![
        v(41.5, 3.0, 37.0),
        v(43.0, 3.0, 18.0),
        v(43.0, 22.0, 37.0),
        v(44.5, 3.0, 37.0),
    ]
}
const SLIT_LENGTH: f64 = 34.0 + 15.0 + 15.0 + 34.0;

/// The second square's frame: the first one's (the model's x–y plane) turned 90° up about the
/// bend axis (parallel to y at x = 40, z = t/2 + R, R = width / turn), shifted back by the
/// zone's width along the flat x, so the zone's neutral arc has the zone's width as length.
fn second_frame() -> Frame {
    let r = ZONE / std::f64::consts::FRAC_PI_2;
    let h = THICKNESS / 2.0 + r;
    Frame {
        origin: DVec3::new(SIDE + h, 0.0, h - SIDE - ZONE),
        u: DVec3::Z,
        v: DVec3::Y,
        n: DVec3::NEG_X,
    }
}

/// The hand-made bent part, with or without its slits.
fn bent_part(with_slits: bool) -> Part {
    let first = Frame::on_plane(DVec3::ZERO, DVec3::Z);
    let flat = Polygon::new(rect(0.0, 0.0, 2.0 * SIDE + ZONE, SIDE));
    let mut part = Part::plate(BENT_ID, THICKNESS, flat, first);
    part.kind = PartKind::Bent;
    part.merged = PLATES.to_vec();
    part.segments = vec![
        Segment {
            polygon: Polygon::new(rect(0.0, 0.0, SIDE, SIDE)),
            frame: first,
        },
        // Clockwise on purpose: plan.json must write it counter-clockwise.
        Segment {
            polygon: Polygon::new(
                rect(SIDE + ZONE, 0.0, 2.0 * SIDE + ZONE, SIDE)
                    .into_iter()
                    .rev()
                    .collect(),
            ),
            frame: second_frame(),
        },
    ];
    let x = SIDE + ZONE / 2.0;
    part.bends = vec![Bend {
        line: [DVec2::new(x, 0.0), DVec2::new(x, SIDE)],
        angle_deg: 90.0,
        style: BendStyle::LivingHinge,
        pattern: platener::plan::HingePattern::Lattice,
        width: ZONE,
        segments: [0, 1],
    }];
    part.marks.push(Mark {
        kind: MarkKind::Score,
        path: vec![DVec2::new(x, 0.5), DVec2::new(x, SIDE - 0.5)],
        side: None,
    });
    if with_slits {
        part.marks.extend(slits().into_iter().map(|path| Mark {
            kind: MarkKind::Cut,
            path,
            side: None,
        }));
    }
    part
}

fn input(with_slits: bool) -> PlanInput {
    let source = SourceInfo {
        name: "hinge".into(),
        triangles: 12,
        bbox_min: DVec3::ZERO,
        bbox_max: DVec3::splat(50.0),
        units: platener::Units::Mm,
        scale: 1.0,
        print: None,
    };
    let joints = vec![Joint {
        parts: PLATES,
        kind: JointKind::Bend,
        angle_deg: 90.0,
        label: 1,
    }];
    PlanInput::new(source, Method::Plate, vec![bent_part(with_slits)], joints)
}

fn run(with_slits: bool) -> State {
    pipeline::cutting_plan(input(with_slits), &Cancel::default()).expect("a cutting plan")
}

fn bundle(state: &State) -> &Bundle {
    state.export.as_ref().expect("exported")
}

fn plan_json(state: &State) -> Value {
    serde_json::from_slice(&bundle(state).files["plan.json"]).expect("plan.json is JSON")
}

fn point(v: &Value) -> DVec2 {
    DVec2::new(v[0].as_f64().expect("x"), v[1].as_f64().expect("y"))
}

#[test]
fn plan_json_writes_segments_bends_and_merged() {
    let json = plan_json(&run(true));
    assert_eq!(json["version"], 2);
    let part = &json["parts"][0];
    assert_eq!(part["kind"], "bent");
    assert_eq!(part["merged"], serde_json::json!([3, 4]));
    let segments = part["segments"].as_array().expect("segments");
    assert_eq!(segments.len(), 2);
    for (s, x0) in segments.iter().zip([0.0, SIDE + ZONE]) {
        let outline: Vec<DVec2> = s["outline"].as_array().expect("outline").iter().map(point).collect();
        assert_eq!(outline.len(), 4);
        assert!(platener_geom::polygon::signed_area(&outline) > 0.0, "counter-clockwise");
        assert!((platener_geom::polygon::signed_area(&outline) - SIDE * SIDE).abs() < 1e-9);
        assert!(outline.iter().all(|p| p.x >= x0 && p.x <= x0 + SIDE));
        assert_eq!(s["holes"], serde_json::json!([]));
    }
    // The first segment's transform is the part's; the second one places its zone-side edge
    // at the end of the neutral arc: x = 40 + R, z = t/2 + R.
    assert_eq!(segments[0]["transform"], part["transform"]);
    let rows: Vec<Vec<f64>> = serde_json::from_value(segments[1]["transform"].clone()).expect("rows");
    let (x, z) = (SIDE + ZONE, THICKNESS / 2.0);
    let model: Vec<f64> = rows.iter().map(|r| r[0] * x + r[2] * z + r[3]).collect();
    let r = ZONE / std::f64::consts::FRAC_PI_2;
    assert!(
        (model[0] - (SIDE + r)).abs() < 1e-9 && (model[2] - (z + r)).abs() < 1e-9,
        "{model:?}"
    );
    let bends = part["bends"].as_array().expect("bends");
    assert_eq!(bends.len(), 1);
    let b = &bends[0];
    assert_eq!(
        (point(&b["line"][0]), point(&b["line"][1])),
        (DVec2::new(43.0, 0.0), DVec2::new(43.0, SIDE))
    );
    assert_eq!((b["angle"].as_f64(), b["width"].as_f64()), (Some(90.0), Some(ZONE)));
    assert_eq!(
        (b["style"].as_str(), b["segments"].clone()),
        (Some("living-hinge"), serde_json::json!([0, 1]))
    );
    // Mark kinds are only the spec's three; the four slits are `cut`, as drawn.
    let marks = part["marks"].as_array().expect("marks");
    assert!(
        marks
            .iter()
            .all(|m| ["cut", "score", "label"].contains(&m["kind"].as_str().expect("kind")))
    );
    let cut: Vec<Vec<DVec2>> = marks
        .iter()
        .filter(|m| m["kind"] == "cut")
        .map(|m| m["path"].as_array().expect("path").iter().map(point).collect())
        .collect();
    assert_eq!(cut, slits());
    assert!(marks.iter().any(|m| m["kind"] == "label"), "the part is numbered");
    // The bend joint names the merged plates, and the plan reads back as written.
    assert_eq!(json["joints"][0]["kind"], "bend");
    assert_eq!(json["joints"][0]["parts"], serde_json::json!([3, 4]));
    let back: Plan = serde_json::from_value(json.clone()).expect("reads back");
    assert_eq!(back, bundle(&run(true)).plan);
}

#[test]
fn kerf_keeps_the_slits_as_drawn() {
    let state = run(true);
    let cut = state.kerf.as_ref().expect("kerf ran");
    assert!(cut.kerf > 0.0);
    assert_eq!(cut.parts[0].slits, slits(), "neither offset nor dropped");
    // The slits are no holes: the cut path is the grown rectangle alone.
    assert!(cut.parts[0].cut.holes.is_empty());
    let area = (2.0 * SIDE + ZONE + cut.kerf) * (SIDE + cut.kerf);
    assert!((cut.parts[0].cut.area() - area).abs() < 1e-3);
}

/// The red open paths (no `Z`) of the group `part-ID` of an SVG written by platener, as point
/// lists: read with roxmltree and svgtypes, usvg's own XML and path parsers.
fn red_open_paths(svg: &str, id: u32) -> Vec<Vec<DVec2>> {
    use svgtypes::{SimplePathSegment, SimplifyingPathParser};
    let doc = roxmltree::Document::parse(svg).expect("the SVG parses");
    let group = format!("part-{id}");
    let group = doc
        .descendants()
        .find(|n| n.attribute("id") == Some(group.as_str()))
        .expect("the part's group");
    let mut out = Vec::new();
    for path in group.descendants().filter(|n| n.has_tag_name("path")) {
        if path.attribute("stroke") != Some("#ff0000") {
            continue;
        }
        let (mut points, mut closed) = (Vec::new(), false);
        for segment in SimplifyingPathParser::from(path.attribute("d").unwrap_or_default()) {
            match segment.expect("d parses") {
                SimplePathSegment::MoveTo { x, y } | SimplePathSegment::LineTo { x, y } => {
                    points.push(DVec2::new(x, y))
                }
                SimplePathSegment::ClosePath => closed = true,
                other => panic!("straight segments only: {other:?}"),
            }
        }
        if !closed {
            out.push(points);
        }
    }
    out
}

#[test]
fn the_sheet_cuts_the_slits_red_where_the_part_was_nested() {
    let state = run(true);
    let b = bundle(&state);
    let placement = b.plan.parts[0].sheet;
    let svg = String::from_utf8(b.files[&b.plan.sheets[0].file].clone()).expect("utf-8");
    let red = red_open_paths(&svg, BENT_ID);
    assert_eq!(red.len(), slits().len());
    // In cut order (issue 34): each slit once, in any order, from either end. The SVG writes
    // 4 decimals.
    for slit in slits() {
        let placed: Vec<DVec2> = slit.iter().map(|q| placement.apply(*q)).collect();
        let same = |drawn: &Vec<DVec2>, want: &[DVec2]| {
            drawn.len() == want.len() && drawn.iter().zip(want).all(|(p, q)| p.distance(*q) < 1e-4)
        };
        let reversed: Vec<DVec2> = placed.iter().rev().copied().collect();
        assert!(
            red.iter().any(|d| same(d, &placed) || same(d, &reversed)),
            "{placed:?} is drawn"
        );
    }
    // A plan without slits has no red open path at all.
    let plain = run(false);
    let pb = bundle(&plain);
    let svg = String::from_utf8(pb.files[&pb.plan.sheets[0].file].clone()).expect("utf-8");
    assert!(red_open_paths(&svg, BENT_ID).is_empty());
}

#[test]
fn the_cut_length_counts_the_slits() {
    let with = bundle(&run(true)).report.cut_length;
    let without = bundle(&run(false)).report.cut_length;
    assert!((with - without - SLIT_LENGTH).abs() < 1e-9, "{with} − {without}");
}

#[test]
fn labels_keep_out_of_the_bend_zone() {
    let state = run(true);
    let labels = state.labels.as_ref().expect("labelled");
    let marks = &labels.parts[0].marks;
    assert!(!marks.is_empty(), "the part is numbered");
    let line_x = SIDE + ZONE / 2.0;
    for p in marks.iter().flat_map(|m| &m.path) {
        assert!((p.x - line_x).abs() >= ZONE / 2.0, "label stroke at {p} is in the zone");
    }
}

#[test]
fn a_version_1_plan_still_reads() {
    let mut json = plan_json(&run(true));
    json["version"] = 1.into();
    let part = json["parts"][0].as_object_mut().expect("part");
    for key in ["segments", "bends", "merged"] {
        part.remove(key);
    }
    part.insert("kind".into(), "plate".into());
    // Version 1 wrote engraving as `engrave` and bend lines as `bend`, and had no `cut`.
    let marks = part["marks"].as_array_mut().expect("marks");
    marks.retain(|m| m["kind"] != "cut");
    marks[0]["kind"] = "bend".into();
    marks.push(serde_json::json!({"kind": "engrave", "path": [[1.0, 1.0], [2.0, 2.0]]}));
    let files = [("plan.json".to_string(), serde_json::to_vec(&json).expect("json"))]
        .into_iter()
        .collect();
    let plan = plan_from_zip(&zip_files(&files).expect("zip")).expect("a version 1 plan reads");
    assert_eq!(plan.version, 1);
    let p = &plan.parts[0];
    assert!(p.segments.is_empty() && p.bends.is_empty() && p.merged.is_empty());
    assert_eq!(p.marks[0].kind, MarkKind::Score);
    assert_eq!(p.marks.last().map(|m| m.kind), Some(MarkKind::Score));
    // Written again, the old kinds come out as the spec's `score`.
    let again = serde_json::to_value(&plan).expect("json");
    let kinds: Vec<&str> = again["parts"][0]["marks"]
        .as_array()
        .expect("marks")
        .iter()
        .map(|m| m["kind"].as_str().expect("kind"))
        .collect();
    assert_eq!(kinds.first(), Some(&"score"));
    assert!(kinds.iter().all(|k| ["score", "label"].contains(k)), "{kinds:?}");
}
