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
use platener::plan::{MarkKind, Part};
use platener::plates::{Feature, Relief, Side};
use platener::samples::voxels;
use platener::{Cancel, Features, Settings, Source, State, Weld, WarningKind};

/// Converts `triangles` with the plate method, no weld, and `features`.
fn plate_method(name: &str, triangles: Vec<platener::read::Triangle>, features: Features) -> State {
    let settings = Settings {
        weld: Weld::Off,
        features,
        ..Settings::default()
    };
    convert(MethodKind::Plate, Source::triangles(name, triangles), settings, &Cancel::default())
        .unwrap_or_else(|e| panic!("{name}: {e}"))
}

fn parts(state: &State) -> &[Part] {
    &state.parts.as_ref().expect("parts").parts
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
        .fold((DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)), |(lo, hi), p| {
            (lo.min(p), hi.max(p))
        })
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
    assert_eq!(f[0].relief, Relief::Recessed);
    assert!((f[0].area - 150.0).abs() < 1e-6, "area {}", f[0].area);
    // The pocket is in the model's top face (z = 3): the side named is the face there.
    let face_z = if f[0].side == Side::Up { 0.0 } else { p.thickness };
    let face = p.frame.to_model(DVec3::new(0.0, 0.0, face_z));
    assert!((face.z - 3.0).abs() < 1e-6, "{:?} face at z {}", f[0].side, face.z);
    assert!((f[0].center - DVec3::new(27.5, 20.0, 3.0)).length() < 1e-6, "{}", f[0].center);
    assert!(
        state.warnings().any(|w| w.kind == WarningKind::Features && w.message.contains("1 feature")),
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
    // As before issue 15: the plate has the pocket as a hole, and the pocket's floor, left
    // over, is extruded into a plate of its own.
    assert_eq!(ps.len(), 2);
    assert_eq!(ps[0].polygon.holes.len(), 1, "the pocket is cut through");
    assert!((ps[0].polygon.area() - 2250.0).abs() < 1e-6);
    assert!((ps[1].polygon.area() - 150.0).abs() < 1e-6);
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
    assert!(floor.polygon.holes.is_empty(), "no hole under the standoff");
    assert_eq!(score_marks(floor).len(), 1);
    let f = features(&state);
    assert_eq!(f.len(), 1);
    assert_eq!(f[0].relief, Relief::Raised);
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

#[test]
fn plan_json_has_the_marks_as_score() {
    let state = plate_method("pocket", plate_with_cell(|k| k == 0), Features::Engrave);
    let bundle = state.bundle().expect("bundle");
    let (_, json) = bundle
        .files
        .iter()
        .find(|(n, _)| n.ends_with("plan.json"))
        .expect("plan.json");
    let plan: serde_json::Value = serde_json::from_slice(json).expect("json");
    let scores = plan["parts"][0]["marks"]
        .as_array()
        .expect("marks")
        .iter()
        .filter(|m| m["kind"] == "score")
        .count();
    assert_eq!(scores, 1);
}
