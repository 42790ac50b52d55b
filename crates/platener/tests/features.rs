//! A plate's shape is the model's material at its mid-plane (issue 15): features on one face
//! (pockets, engraved lettering, standoff footprints) are scored on the face where they are,
//! holes are cut only where the model is open through the plate. `--features cut` keeps the
//! holes, `--features ignore` gives solid plates without marks.
//!
//! Hand-made plates are rectilinear solids (`samples::voxels`) converted with `--weld 0`, so the
//! expected geometry is exact; the corpus models use the default settings.

use platener::convert::convert;
use platener::glam::{DVec2, DVec3};
use platener::method::MethodKind;
use platener::plan::{JointKind, MarkKind, Part, PartKind};
use platener::plates::{Elevation, Feature, Side};
use platener::{Cancel, Features, Settings, Source, State, WarningKind, Weld};
use platener_fixtures::samples::voxels;

/// Converts `triangles` with the plate method, no weld, and `features`.
fn plate_method(name: &str, triangles: Vec<platener::read::Triangle>, features: Features) -> State {
    let settings = Settings {
        weld: Weld::Off,
        features,
        ..Settings::default()
    };
    convert(
        MethodKind::Plate,
        Source::triangles(name, triangles),
        settings,
        &Cancel::default(),
    )
    .unwrap_or_else(|e| panic!("{name}: {e}"))
}

fn parts(state: &State) -> &[Part] {
    &state.final_parts().as_ref().expect("parts").parts
}

fn features(state: &State) -> &[Feature] {
    &state.plates.as_ref().expect("plates").features
}

fn score_marks(part: &Part) -> Vec<&Vec<DVec2>> {
    part.marks
        .iter()
        .filter(|m| m.kind == MarkKind::Score)
        .map(|m| &m.path)
        .collect()
}

/// A 60 × 40 mm plate, 3 mm thick, with cell (1, 1) (x 20–35, y 15–25) shaped by `cell`:
/// `cell(k)` says whether layer k (z 0–2, 2–3) is material there.
fn plate_with_cell(cell: impl Fn(usize) -> bool) -> Vec<platener::read::Triangle> {
    voxels(
        &[0.0, 20.0, 35.0, 60.0],
        &[0.0, 15.0, 25.0, 40.0],
        &[0.0, 2.0, 3.0],
        |i, j, k| (i, j) != (1, 1) || cell(k),
    )
}

/// The model-space bounds of a part's marks.
fn mark_bounds(part: &Part) -> (DVec3, DVec3) {
    score_marks(part)
        .into_iter()
        .flatten()
        .map(|q| part.frame.to_model(q.extend(0.0)))
        .fold(
            (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)),
            |(lo, hi), p| (lo.min(p), hi.max(p)),
        )
}

#[test]
fn a_1mm_pocket_is_a_score_mark_not_a_hole() {
    let state = plate_with_cell(|k| k == 0);
    let state = plate_method("pocket", state, Features::Engrave);
    let ps = parts(&state);
    assert_eq!(ps.len(), 1, "one plate");
    let p = &ps[0];
    assert!(p.polygon.holes.is_empty(), "no hole: {:?}", p.polygon.holes);
    assert!((p.polygon.area() - 2400.0).abs() < 1e-6, "area {}", p.polygon.area());
    let marks = score_marks(p);
    assert_eq!(marks.len(), 1, "one ring around the pocket");
    assert_eq!(marks[0].first(), marks[0].last(), "the ring is closed");
    let (lo, hi) = mark_bounds(p);
    assert!((lo.x - 20.0).abs() < 1e-6 && (hi.x - 35.0).abs() < 1e-6, "x {lo}..{hi}");
    assert!((lo.y - 15.0).abs() < 1e-6 && (hi.y - 25.0).abs() < 1e-6, "y {lo}..{hi}");
    let f = features(&state);
    assert_eq!(f.len(), 1);
    assert_eq!(f[0].relief, Elevation::Recessed);
    assert!((f[0].area - 150.0).abs() < 1e-6, "area {}", f[0].area);
    // The pocket is in the model's top face (z = 3): the side named is the face there.
    let face_z = if f[0].side == Side::Up { 0.0 } else { p.thickness };
    let face = p.frame.to_model(DVec3::new(0.0, 0.0, face_z));
    assert!((face.z - 3.0).abs() < 1e-6, "{:?} face at z {}", f[0].side, face.z);
    assert!(
        (f[0].center - DVec3::new(27.5, 20.0, 3.0)).length() < 1e-6,
        "{}",
        f[0].center
    );
    assert!(
        state
            .warnings()
            .any(|w| w.kind == WarningKind::Features && w.message.contains("1 feature")),
        "the report lists the feature"
    );
}

#[test]
fn a_hole_through_the_plate_stays_a_hole() {
    let state = plate_method("through", plate_with_cell(|_| false), Features::Engrave);
    let ps = parts(&state);
    assert_eq!(ps.len(), 1);
    assert_eq!(ps[0].polygon.holes.len(), 1);
    assert!((ps[0].polygon.area() - (2400.0 - 150.0)).abs() < 1e-6);
    assert!(score_marks(&ps[0]).is_empty());
    assert!(features(&state).is_empty());
}

#[test]
fn features_cut_gives_the_holes_of_before() {
    let state = plate_method("pocket", plate_with_cell(|k| k == 0), Features::Cut);
    let ps = parts(&state);
    // As before issue 15, the plate has the pocket as a hole. The pocket's floor, left over,
    // is extruded into a plate of its own that no joint holds and that is under a tenth of
    // the largest: a loose fragment, left out with a warning naming its size.
    assert_eq!(ps.len(), 1);
    assert_eq!(ps[0].polygon.holes.len(), 1, "the pocket is cut through");
    assert!((ps[0].polygon.area() - 2250.0).abs() < 1e-6);
    assert!(
        state
            .warnings()
            .any(|w| w.message.contains("15.0 × 10.0 mm") && w.message.contains("left out")),
        "the left-out floor is named: {:?}",
        state.warnings().map(|w| &w.message).collect::<Vec<_>>()
    );
    assert!(ps.iter().all(|p| score_marks(p).is_empty()));
    assert!(features(&state).is_empty());
}

#[test]
fn features_ignore_gives_a_solid_plate_without_marks() {
    let state = plate_method("pocket", plate_with_cell(|k| k == 0), Features::Ignore);
    let ps = parts(&state);
    assert_eq!(ps.len(), 1);
    assert!(ps[0].polygon.holes.is_empty());
    assert!((ps[0].polygon.area() - 2400.0).abs() < 1e-6);
    assert!(score_marks(&ps[0]).is_empty());
    assert!(features(&state).is_empty());
}

#[test]
fn a_standoff_is_scored_and_reported_with_its_size_and_height() {
    // A 5 × 5 × 6 mm column on a 60 × 40 × 3 mm floor.
    let triangles = voxels(
        &[0.0, 20.0, 25.0, 60.0],
        &[0.0, 15.0, 20.0, 40.0],
        &[0.0, 3.0, 9.0],
        |i, j, k| k == 0 || (i, j) == (1, 1),
    );
    let state = plate_method("standoff", triangles, Features::Engrave);
    let floor = parts(&state)
        .iter()
        .find(|p| (p.polygon.area() - 2400.0).abs() < 1e-6)
        .expect("the whole floor is one part");
    // A 3 × 3 mm peg's slot would leave discs of 16 mm² with 1 mm walls: too small to cut
    // (issue 32), so the column is listed, not cut.
    assert!(floor.polygon.holes.is_empty(), "no hole under the standoff");
    assert_eq!(parts(&state).len(), 1);
    assert_eq!(score_marks(floor).len(), 1);
    let f = features(&state);
    assert_eq!(f.len(), 1);
    assert_eq!(f[0].relief, Elevation::Raised);
    assert!((f[0].size[0] - 5.0).abs() < 1e-6 && (f[0].size[1] - 5.0).abs() < 1e-6);
    assert_eq!(f[0].height.map(|h| (h * 1e6).round() / 1e6), Some(6.0));
    assert!((f[0].center - DVec3::new(22.5, 17.5, 3.0)).length() < 1e-6);
    assert!(
        state
            .warnings()
            .any(|w| w.kind == WarningKind::Features && w.message.contains("5.0 × 5.0 mm, 6.0 mm tall")),
        "the standoff is reported"
    );
}

/// Issue 32: a table's legs stand on its top as a boss would, but they are plates of the
/// plan; "left out" is said only of what no plate builds.
#[test]
fn legs_built_as_plates_are_not_reported_as_bosses_left_out() {
    let state = plate_method(
        "table",
        platener_fixtures::samples::table_square_legs(),
        Features::Engrave,
    );
    let tall = parts(&state)
        .iter()
        .filter(|p| {
            let (lo, hi) = p.polygon.bounds();
            (hi - lo).max_element() > 60.0 && (hi - lo).min_element() < 20.0
        })
        .count();
    assert!(tall >= 4, "each leg is built by plates: {tall} leg plates");
    let bosses: Vec<String> = state
        .warnings()
        .filter(|w| w.message.contains("left out"))
        .map(|w| w.message.clone())
        .collect();
    assert!(bosses.is_empty(), "{bosses:?}");
}

/// Issue 32: raised letters up to a sheet high (the keychain's 1.25 mm) are engraved as
/// their outline, and said so, not "left out"; and the score counts the details kept: with
/// `features` ignored the tag is blank, keeps under half of the model's sharp edges (the
/// letters' outlines) and scores below the engraved tag, which keeps them all.
#[test]
fn raised_letters_are_said_engraved_and_a_blank_tag_scores_lower() {
    let engraved = plate_method(
        "keychain",
        platener_fixtures::samples::keychain_tag(),
        Features::Engrave,
    );
    let said: Vec<&str> = engraved.warnings().map(|w| w.message.as_str()).collect();
    assert!(
        said.iter()
            .any(|m| m.contains("5 raised detail(s)") && m.contains("engraved")),
        "{said:?}"
    );
    assert!(!said.iter().any(|m| m.contains("left out")), "{said:?}");
    let blank = plate_method("keychain", platener_fixtures::samples::keychain_tag(), Features::Ignore);
    let score = |state: &State| {
        let bundle = state.export.as_ref().expect("exported");
        let mesh = state.mesh.as_deref().expect("mesh");
        platener::score::score(mesh, bundle, state.plates.as_deref())
    };
    let (kept, lost) = (score(&engraved), score(&blank));
    assert!(kept.quality.details.kept > 0.99, "{:?}", kept.quality.details);
    assert!(lost.quality.details.kept < 0.5, "{:?}", lost.quality.details);
    assert!(kept.total - lost.total > 0.04, "{} against {}", kept.total, lost.total);
}

#[test]
fn plan_json_has_the_marks_as_score() {
    let state = plate_method("pocket", plate_with_cell(|k| k == 0), Features::Engrave);
    let plan = plan_json(&state);
    let scores = plan["parts"][0]["marks"]
        .as_array()
        .expect("marks")
        .iter()
        .filter(|m| m["kind"] == "score")
        .count();
    assert_eq!(scores, 1);
}

/// Converts a corpus model with the plate method and default settings but `features`; `None`
/// (after saying why) when the corpus is absent.
fn corpus_plan(file: &str, features: Features) -> Option<State> {
    let dir = platener_fixtures::samples::shared_corpus()
        .map_err(|m| eprintln!("{m}"))
        .ok()?;
    let settings = Settings {
        features,
        ..Settings::default()
    };
    let state = convert(
        MethodKind::Plate,
        Source::File(dir.join(file)),
        settings,
        &Cancel::default(),
    )
    .unwrap_or_else(|e| panic!("{file}: {e}"));
    Some(state)
}

/// One line per part: holes, score marks; and the features found. The figures of the report.
fn describe(file: &str, features: Features, state: &State) {
    let ps = parts(state);
    let holes: Vec<usize> = ps.iter().map(|p| p.polygon.holes.len()).collect();
    let marks: Vec<usize> = ps.iter().map(|p| score_marks(p).len()).collect();
    eprintln!(
        "{file} ({features:?}): {} parts, holes per part {holes:?}, score marks per part {marks:?}, {} features",
        ps.len(),
        self::features(state).len()
    );
    for w in state.warnings().filter(|w| w.kind == WarningKind::Features) {
        eprintln!("  {}", w.message);
    }
}

/// The plate method's plans of corpus `file` with features cut and engraved, each described;
/// `None` when the corpus is absent.
fn cut_and_engraved(file: &str) -> Option<(State, State)> {
    let cut = corpus_plan(file, Features::Cut)?;
    describe(file, Features::Cut, &cut);
    let engraved = corpus_plan(file, Features::Engrave)?;
    describe(file, Features::Engrave, &engraved);
    Some((cut, engraved))
}

/// Every score mark of `part` lies inside its outline (clear of its holes).
fn marks_inside(part: &Part) -> bool {
    score_marks(part)
        .into_iter()
        .flatten()
        .all(|q| part.polygon.contains(*q) || part.polygon.boundary_distance(*q) < 1e-6)
}

#[test]
fn ipad_base_keeps_its_lettering_as_score_marks_on_its_top() {
    let Some((cut, state)) = cut_and_engraved("plates/ipad_mini_arcade_cabinet_half.stl") else {
        return;
    };
    let ps = parts(&state);
    let fs = features(&state);
    assert!(!fs.is_empty(), "the lettering is found");
    // The base: the plate the lettering is on. Its part's holes are joint slots only; cut, the
    // same part had the letters as holes.
    let base = fs[0].plate as usize;
    assert!(fs.iter().all(|f| f.plate as usize == base), "all on the base");
    let base_plate = &state.plates.as_ref().expect("plates").plates[base];
    assert!(base_plate.polygon.holes.is_empty(), "no hole from the lettering");
    let cut_base = &parts(&cut)[base];
    assert!(
        cut_base.polygon.holes.len() >= ps[base].polygon.holes.len() + fs.len(),
        "cut: {} holes, engraved: {}",
        cut_base.polygon.holes.len(),
        ps[base].polygon.holes.len()
    );
    let part = &ps[base];
    assert!(marks_inside(part), "part {}: marks outside it", part.id);
    assert!(score_marks(part).len() >= fs.len(), "every letter is scored");
    for f in fs {
        assert_eq!(f.relief, Elevation::Recessed, "lettering is engraved");
        // The lettering is on the base's top face: the side named is the face at the top.
        let z = if f.side == Side::Up { 0.0 } else { part.thickness };
        let face = part.frame.to_model(DVec3::new(0.0, 0.0, z));
        let other = part.frame.to_model(DVec3::new(0.0, 0.0, part.thickness - z));
        assert!(face.z > other.z, "feature at {} is on the lower face", f.center);
    }
    assert_eq!(ps.len(), parts(&cut).len(), "the same parts");
}

#[test]
fn xyz_cube_faces_have_no_holes_from_their_letters() {
    let file = "solids/xyz_calibration_cube_20mm.stl";
    let Some(state) = corpus_plan(file, Features::Engrave) else {
        return;
    };
    describe(file, Features::Engrave, &state);
    let ps = parts(&state);
    assert_eq!(ps.len(), 6, "a hull of six faces");
    assert!(ps.iter().all(|p| p.polygon.holes.is_empty()), "no through-hole");
    let marked = ps.iter().filter(|p| !score_marks(p).is_empty()).count();
    assert!(marked >= 3, "X, Y and Z are scored ({marked} parts marked)");
    assert!(ps.iter().all(marks_inside));
    assert!(features(&state).iter().all(|f| f.relief == Elevation::Recessed));
}

/// The Arduino enclosure's 5.2 mm standoffs (1 mm walls round a 3.2 mm hole) are too small
/// to cut from 3 mm sheet: listed, with their screw holes cut through the floor for bought
/// spacers (issue 32).
#[test]
fn arduino_floor_has_screw_holes_under_its_standoffs_and_lists_them() {
    let Some((_, state)) = cut_and_engraved("plates/arduino_uno_enclosure.stl") else {
        return;
    };
    let floor_of = |ps: &[Part]| -> Part {
        ps.iter()
            .filter(|p| p.frame.n.z.abs() > 0.999)
            .max_by(|a, b| a.polygon.area().total_cmp(&b.polygon.area()))
            .expect("a floor")
            .clone()
    };
    let floor = floor_of(parts(&state));
    let hole_areas = |p: &Part| -> Vec<f64> {
        p.polygon
            .holes
            .iter()
            .map(|r| platener_geom::Polygon::new(r.clone()).area())
            .collect()
    };
    // Four 3.2 mm screw holes (8 mm² each), not the 5.2 mm footprints (21 mm²).
    let holes = hole_areas(&floor);
    assert_eq!(holes.len(), 4, "{holes:?}");
    assert!(holes.iter().all(|a| (a - 8.0).abs() < 1.0), "{holes:?}");
    let standoffs: Vec<&Feature> = features(&state)
        .iter()
        .filter(|f| f.relief == Elevation::Raised && parts(&state)[f.plate as usize].id == floor.id)
        .collect();
    assert!(standoffs.len() >= 4, "{} standoffs found", standoffs.len());
    for s in &standoffs {
        assert!(s.height.is_some_and(|h| h > 1.0), "standoff height {:?}", s.height);
    }
    assert!(
        state.warnings().any(|w| w.kind == WarningKind::Features
            && w.message.contains("4 boss(es)")
            && w.message.contains("screw holes (3.2 mm)")),
        "the standoffs are listed"
    );
}

#[test]
fn features_setting_parses_the_three_words_and_names_a_bad_one() {
    assert_eq!("engrave".parse::<Features>().ok(), Some(Features::Engrave));
    assert_eq!(" CUT ".parse::<Features>().ok(), Some(Features::Cut));
    assert_eq!("ignore".parse::<Features>().ok(), Some(Features::Ignore));
    let e = "drill".parse::<Features>().expect_err("not a mode").to_string();
    assert!(e.contains("features") && e.contains("drill"), "{e}");
    assert_eq!(Settings::default().features, Features::Engrave);
}

/// A 60 × 40 mm plate, 3 mm thick, with a pocket 15 × 10 mm at its edge (x 20–35, y 0–10),
/// `depth` deep from the top face (z = 3).
fn plate_with_edge_pocket(depth: f64) -> Vec<platener::read::Triangle> {
    voxels(
        &[0.0, 20.0, 35.0, 60.0],
        &[0.0, 10.0, 40.0],
        &[0.0, 3.0 - depth, 3.0],
        |i, j, k| (i, j, k) != (1, 0, 1),
    )
}

/// A pocket shallower than the sheet that reaches the plate's edge is scored like one inside
/// it: the outline is the whole 60 × 40 rectangle (no notch), and a score mark traces the
/// pocket (its side along the edge included).
#[test]
fn a_pocket_at_the_edge_is_scored_not_notched() {
    let state = plate_method("edge pocket", plate_with_edge_pocket(1.0), Features::Engrave);
    let ps = parts(&state);
    assert_eq!(ps.len(), 1, "one plate");
    let p = &ps[0];
    assert!(p.polygon.holes.is_empty(), "no hole: {:?}", p.polygon.holes);
    assert!((p.polygon.area() - 2400.0).abs() < 1e-6, "area {}", p.polygon.area());
    assert_eq!(p.polygon.outer.len(), 4, "a plain rectangle: {:?}", p.polygon.outer);
    let marks = score_marks(p);
    assert_eq!(marks.len(), 1, "one ring around the pocket");
    let (lo, hi) = mark_bounds(p);
    assert!((lo.x - 20.0).abs() < 1e-6 && (hi.x - 35.0).abs() < 1e-6, "x {lo}..{hi}");
    assert!(lo.y.abs() < 1e-6 && (hi.y - 10.0).abs() < 1e-6, "y {lo}..{hi}");
    assert!(
        (lo.z - 3.0).abs() < 1e-6 && (hi.z - 3.0).abs() < 1e-6,
        "on the top face: {lo}..{hi}"
    );
    let f = features(&state);
    assert_eq!(f.len(), 1);
    assert_eq!(f[0].relief, Elevation::Recessed);
    assert!((f[0].area - 150.0).abs() < 1e-6, "area {}", f[0].area);
    // A pocket deeper than half the sheet is no material at the mid-plane: a notch.
    let deep = plate_method("deep edge pocket", plate_with_edge_pocket(2.0), Features::Engrave);
    let p = &parts(&deep)[0];
    assert!((p.polygon.area() - 2250.0).abs() < 1e-6, "area {}", p.polygon.area());
    assert!(features(&deep).is_empty());
}

/// Score marks say in plan.json which face they are on: `top` (up on the sheet, engraved as
/// drawn) or `bottom` (turn the part over), the face of the feature the report names.
#[test]
fn plan_json_score_marks_name_their_side() {
    for (zs, cell, model_z) in [([0.0, 2.0, 3.0], 0, 3.0), ([0.0, 1.0, 3.0], 1, 0.0)] {
        // A 1 mm pocket in the top face (z = 3) or the bottom one (z = 0).
        let model = voxels(&[0.0, 20.0, 35.0, 60.0], &[0.0, 15.0, 25.0, 40.0], &zs, |i, j, k| {
            (i, j) != (1, 1) || k == cell
        });
        let state = plate_method("pocket", model, Features::Engrave);
        let p = &parts(&state)[0];
        let f = features(&state);
        assert_eq!(f.len(), 1);
        let face_z = if f[0].side == Side::Up { 0.0 } else { p.thickness };
        assert!((p.frame.to_model(DVec3::new(0.0, 0.0, face_z)).z - model_z).abs() < 1e-6);
        let want = if f[0].side == Side::Up { "top" } else { "bottom" };
        let plan = plan_json(&state);
        let marks = plan["parts"][0]["marks"].as_array().expect("marks");
        let sides: Vec<&serde_json::Value> = marks
            .iter()
            .filter(|m| m["kind"] == "score")
            .map(|m| &m["side"])
            .collect();
        assert_eq!(sides, vec![want], "pocket at z {model_z}");
        assert!(
            marks
                .iter()
                .filter(|m| m["kind"] != "score")
                .all(|m| m.get("side").is_none()),
            "other marks have no side"
        );
    }
}

/// The plan.json a conversion wrote, as JSON.
fn plan_json(state: &State) -> serde_json::Value {
    let bundle = state.bundle().expect("bundle");
    let (_, json) = bundle
        .files
        .iter()
        .find(|(n, _)| n.ends_with("plan.json"))
        .expect("plan.json");
    serde_json::from_slice(json).expect("json")
}

/// Issue 32: offered a sheet as thin as the raised details stand tall (`-t 2.5 -t 1.25`),
/// each detail that passes the smallest-part rule at that sheet is cut from it as a part
/// glued on its engraved outline: a 60 × 13 × 2.5 mm tag with a 10 × 8 mm block and a
/// 10 × 8 mm ring (4 × 2 mm hole) standing 1.25 mm on it, and a 1 × 8 mm stroke too thin to
/// cut, which stays engraved only. Each cut detail lies on the tag's face over its own
/// footprint, 1.25 mm thick; plan.json names the glue (a `glued` joint and `glued` entry).
#[test]
fn raised_details_as_tall_as_an_offered_sheet_are_cut_from_it_and_glued() {
    // The block, the ring as four strokes round its hole, the thin stroke.
    let triangles = platener_fixtures::samples::tag_with_raised(&[
        (10.0, 2.5, 20.0, 10.5),
        (25.0, 2.5, 35.0, 5.5),
        (25.0, 7.5, 35.0, 10.5),
        (25.0, 5.5, 28.0, 7.5),
        (32.0, 5.5, 35.0, 7.5),
        (45.0, 2.5, 46.0, 10.5),
    ]);
    let settings = Settings {
        weld: Weld::Off,
        thicknesses: vec![2.5, 1.25],
        ..Settings::default()
    };
    let state = convert(
        MethodKind::Plate,
        Source::triangles("tag", triangles),
        settings,
        &Cancel::default(),
    )
    .expect("converts");
    let plan = &state.export.as_ref().expect("exported").plan;
    assert_eq!(plan.parts.len(), 3, "the tag and two details");
    let tag = plan
        .parts
        .iter()
        .find(|p| (p.thickness - 2.5).abs() < 1e-9)
        .expect("the tag");
    let glued: Vec<_> = plan.joints.iter().filter(|j| j.kind == JointKind::Glued).collect();
    assert_eq!(glued.len(), 2);
    assert_eq!(plan.glued.len(), 2);
    let mut areas = Vec::new();
    for j in &glued {
        assert_eq!(j.parts[0], tag.id);
        let part = plan.parts.iter().find(|p| p.id == j.parts[1]).expect("the detail");
        assert!((part.thickness - 1.25).abs() < 1e-9);
        // On the tag's upper face, over its footprint: its volume spans z 2.5–3.75.
        let (lo, hi) = z_range(part);
        assert!((lo - 2.5).abs() < 1e-6 && (hi - 3.75).abs() < 1e-6, "{lo}–{hi}");
        areas.push(plan_area(part));
    }
    areas.sort_by(f64::total_cmp);
    assert!(
        (areas[0] - 72.0).abs() < 1e-6 && (areas[1] - 80.0).abs() < 1e-6,
        "{areas:?}"
    );
    // The stroke stays engraved only; every detail keeps its engraved outline on the tag.
    let rings = tag.marks.iter().filter(|m| m.kind == MarkKind::Score).count();
    assert!(
        rings >= 4,
        "{rings} engraved rings: the block, the ring's two, the stroke"
    );
    assert_eq!(plan.glue_note(), "needs glue: 3 parts in 1 group");
    let v = platener::verify::verify(plan, state.mesh.as_deref());
    assert!(v.passed(), "{:?}", v.problems);
    assert_eq!(v.groups, 1);
    assert!(v.interference_share < 1e-3);
}

/// Issue 32: a 2.5 mm tag cut from 1.25 mm sheet is two plates face to face that no joint
/// can hold; they are glued, and plan.json says so (before: two loose parts, verify failed).
#[test]
fn plates_face_to_face_that_no_joint_holds_are_glued() {
    let settings = Settings {
        weld: Weld::Off,
        thicknesses: vec![1.25],
        ..Settings::default()
    };
    let tag = voxels(&[0.0, 60.0], &[0.0, 13.0], &[0.0, 2.5], |_, _, _| true);
    let state = convert(
        MethodKind::Plate,
        Source::triangles("tag", tag),
        settings,
        &Cancel::default(),
    )
    .expect("converts");
    let plan = &state.export.as_ref().expect("exported").plan;
    assert_eq!(plan.parts.len(), 2);
    let glued: Vec<_> = plan.joints.iter().filter(|j| j.kind == JointKind::Glued).collect();
    assert_eq!(glued.len(), 1);
    assert_eq!(plan.glued.len(), 1);
    assert!((plan.glued[0].area - 60.0 * 13.0).abs() < 1e-3, "{:?}", plan.glued);
    let v = platener::verify::verify(plan, state.mesh.as_deref());
    assert!(v.passed(), "{:?}", v.problems);
    assert_eq!(v.groups, 1);
}

/// The model-space z range of a plan part (its outline's first vertex through its thickness).
fn z_range(part: &platener::plan::PlanPart) -> (f64, f64) {
    let frame = platener::plan::bent::frame_from_matrix(&part.transform);
    let zs: Vec<f64> = [0.0, part.thickness]
        .iter()
        .map(|&z| frame.to_model(part.outline[0].extend(z)).z)
        .collect();
    (zs[0].min(zs[1]), zs[0].max(zs[1]))
}

/// The model-space box of a plan part (every outline vertex, both faces).
fn model_box(part: &platener::plan::PlanPart) -> (DVec3, DVec3) {
    let frame = platener::plan::bent::frame_from_matrix(&part.transform);
    platener_geom::boxes::bounds3(
        part.outline
            .iter()
            .flat_map(|p| [0.0, part.thickness].map(|z| frame.to_model(p.extend(z)))),
    )
}

/// The area of a plan part's outline less its holes, mm².
fn plan_area(part: &platener::plan::PlanPart) -> f64 {
    platener_geom::Polygon {
        outer: part.outline.clone(),
        holes: part.holes.clone(),
    }
    .area()
}

/// Issue 32: standoffs taller than a sheet become stacked discs held glue-free by a peg, or
/// by a screw through their own hole; one too small to cut is listed and its screw hole cut
/// through the floor.
#[test]
fn standoffs_become_stacked_discs_on_a_peg_or_a_screw() {
    let state = plate_method(
        "standoffs",
        platener_fixtures::samples::standoff_floor(),
        Features::Engrave,
    );
    let plan = &state.export.as_ref().expect("exported").plan;
    let area = plan_area;
    let floor = plan
        .parts
        .iter()
        .max_by(|a, b| area(a).total_cmp(&area(b)))
        .expect("the floor");
    // The floor loses the peg's slot (3 × 6 mm), the screw hole and the small standoff's hole.
    assert_eq!(floor.holes.len(), 3, "{:?}", floor.holes);
    assert!(
        (area(floor) - (4000.0 - 18.0 - 2.0 * 3.2 * 3.2)).abs() < 1e-3,
        "{}",
        area(floor)
    );
    // Two discs for each 6 mm standoff (3–6 and 6–9 mm up), and a peg.
    let discs: Vec<_> = plan
        .parts
        .iter()
        .filter(|p| p.id != floor.id && p.kind == PartKind::Plate)
        .collect();
    assert_eq!(discs.len(), 4, "{:?}", discs.iter().map(|p| p.id).collect::<Vec<_>>());
    for d in &discs {
        let (lo, hi) = model_box(d);
        let on = |x0: f64| (lo.x - x0).abs() < 1e-6 && (hi.x - x0 - 10.0).abs() < 1e-6;
        assert!(on(10.0) || on(35.0), "over the boss or the standoff: {lo} {hi}");
        assert!((lo.y - 10.0).abs() < 1e-6 && (hi.y - 20.0).abs() < 1e-6, "{lo} {hi}");
        let (z0, z1) = z_range(d);
        assert!(
            ((z0 - 3.0).abs() < 1e-6 && (z1 - 6.0).abs() < 1e-6)
                || ((z0 - 6.0).abs() < 1e-6 && (z1 - 9.0).abs() < 1e-6),
            "{z0}–{z1}"
        );
        // The boss's discs have the peg's slot, the standoff's keep its screw hole.
        let hole = area(d) - 100.0;
        assert!(
            (hole + 18.0).abs() < 1e-3 || (hole + 3.2 * 3.2).abs() < 1e-3,
            "{}",
            area(d)
        );
    }
    let pegs: Vec<_> = plan.parts.iter().filter(|p| p.kind == PartKind::Shaft).collect();
    assert_eq!(pegs.len(), 1);
    let (lo, hi) = model_box(pegs[0]);
    // Through the floor and both discs: z 0–9, 6 mm along x, 3 mm along y, in the boss.
    assert!((lo.z - 0.0).abs() < 1e-6 && (hi.z - 9.0).abs() < 1e-6, "{lo} {hi}");
    assert!(
        ((hi - lo).x - 6.0).abs() < 1e-6 && ((hi - lo).y - 3.0).abs() < 1e-6,
        "{lo} {hi}"
    );
    assert!(lo.x > 10.0 && hi.x < 20.0 && lo.y > 10.0 && hi.y < 20.0, "{lo} {hi}");
    let kinds = |k: JointKind| plan.joints.iter().filter(|j| j.kind == k).count();
    assert_eq!(kinds(JointKind::Shaft), 3, "the peg holds the floor and two discs");
    assert_eq!(kinds(JointKind::Screw), 2, "floor–disc, disc–disc");
    assert!(plan.glued.is_empty());
    let v = platener::verify::verify(plan, state.mesh.as_deref());
    assert!(v.passed(), "{:?}", v.problems);
    assert_eq!(v.groups, 1);
    assert!(v.interference_share < 1e-3, "{}", v.interference_share);
    let said: Vec<&str> = state
        .warnings()
        .filter(|w| w.kind == WarningKind::Features)
        .map(|w| w.message.as_str())
        .collect();
    assert!(
        said.iter()
            .any(|m| m.contains("1 boss(es) standing on it left out") && m.contains("5.2 × 5.2 mm, 5.0 mm tall")),
        "{said:?}"
    );
    assert!(said.iter().any(|m| m.contains("2 standoff(s)")), "{said:?}");
}

/// The same standoffs hanging under the floor (the model upside down): the discs stack
/// downwards from the floor's lower face and the peg runs through them and the floor.
#[test]
fn standoffs_under_a_plate_stack_downwards() {
    let flipped: Vec<platener::read::Triangle> = platener_fixtures::samples::standoff_floor()
        .into_iter()
        .map(|[a, b, c]| [a, c, b].map(|p| DVec3::new(p.x, p.y, -p.z)))
        .collect();
    let state = plate_method("hanging", flipped, Features::Engrave);
    let plan = &state.export.as_ref().expect("exported").plan;
    assert_eq!(plan.parts.len(), 6, "the floor, four discs and a peg");
    let discs: Vec<(f64, f64)> = plan
        .parts
        .iter()
        .filter(|p| p.kind == PartKind::Plate && p.outline.len() == 4 && p.holes.len() == 1)
        .map(z_range)
        .collect();
    assert_eq!(discs.len(), 4, "{discs:?}");
    for (z0, z1) in &discs {
        let at = |a: f64, b: f64| (z0 - a).abs() < 1e-6 && (z1 - b).abs() < 1e-6;
        assert!(at(-6.0, -3.0) || at(-9.0, -6.0), "{z0}–{z1}");
    }
    let peg = plan.parts.iter().find(|p| p.kind == PartKind::Shaft).expect("the peg");
    let (lo, hi) = model_box(peg);
    assert!((lo.z + 9.0).abs() < 1e-6 && hi.z.abs() < 1e-6, "{lo} {hi}");
    let v = platener::verify::verify(plan, state.mesh.as_deref());
    assert!(v.passed(), "{:?}", v.problems);
    assert_eq!(v.groups, 1);
}
