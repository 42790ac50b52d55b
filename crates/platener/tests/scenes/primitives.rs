//! The `primitives` view (issue 20, "Debug view") on the classifier's samples: one node per
//! primitive with the triangles it explains (their area its area) in a colour of its own,
//! its inlier samples as points on its surface, its shape in `extras`; valid and
//! deterministic.

use std::collections::BTreeSet;

use glam::DVec3;
use platener::classify::Classification;
use platener::convert::{Request, convert_all, no_progress};
use platener::method::MethodKind;
use platener::read::Triangle;
use platener::scene::{POINT_LIMIT, SceneError, View};
use platener::{Cancel, Settings, Source, State};
use platener_fixtures::samples;
use serde_json::Value;

use super::check::{Node, assert_root, load};
use super::{assert_valid, validator};

/// The classifier method's state on `triangles`, whether or not its later steps convert
/// (the view needs only `classify`).
fn classified(name: &str, triangles: Vec<Triangle>) -> State {
    let request = Request {
        methods: vec![MethodKind::Classifier],
        ..Request::new(Source::triangles(name, triangles), Settings::default())
    };
    let mut all = convert_all(request, &Cancel::default(), no_progress());
    let result = all.methods.pop().expect("one method");
    let state = result.state.expect("a state");
    assert!(state.classify.is_some(), "{name}: not classified ({:?})", result.error);
    state
}

/// The GLB's JSON chunk.
fn json_of(glb: &[u8]) -> Value {
    let len = u32::from_le_bytes(glb[12..16].try_into().expect("4 bytes")) as usize;
    serde_json::from_slice(&glb[20..20 + len]).expect("JSON chunk")
}

/// Each child of the root's colours (`baseColorFactor` of every primitive of its mesh).
fn colours(doc: &Value) -> Vec<Vec<String>> {
    doc["nodes"][0]["children"]
        .as_array()
        .expect("children")
        .iter()
        .map(|k| {
            let node = &doc["nodes"][k.as_u64().expect("index") as usize];
            let mesh = &doc["meshes"][node["mesh"].as_u64().expect("a mesh") as usize];
            let prims = mesh["primitives"].as_array().expect("primitives");
            prims
                .iter()
                .map(|p| {
                    let m = p["material"].as_u64().expect("material") as usize;
                    doc["materials"][m]["pbrMetallicRoughness"]["baseColorFactor"].to_string()
                })
                .collect()
        })
        .collect()
}

fn area(n: &Node) -> f64 {
    n.triangles()
        .iter()
        .map(|t| {
            let [a, b, c] = t.map(|i| n.positions[i as usize]);
            (b - a).cross(c - a).length() / 2.0
        })
        .sum()
}

/// Asserts what the view promises for `state`'s classification, which must hold `kinds`
/// (sorted kind names, one per primitive); returns the GLB.
fn check_primitives(state: &State, kinds: &[&str]) -> Vec<u8> {
    let c: &Classification = state.classify.as_deref().expect("classified");
    let scene = state.scene(View::Primitives).expect("the primitives view");
    let l = load(&scene.glb);
    assert_root(&l);
    let mut found: Vec<&str> = c.primitives.iter().map(|p| p.shape.kind().name()).collect();
    found.sort_unstable();
    assert_eq!(found, kinds);
    let (nodes, rest) = l.nodes.split_at(c.primitives.len());
    assert!(rest.iter().all(|n| n.name == "unexplained" && n.points.is_empty()));
    let doc = json_of(&scene.glb);
    let colours = colours(&doc);
    let eps = c.thresholds.eps;
    let (mut worst_off, mut worst_area) = (0.0f64, 0.0f64);
    for (i, (n, p)) in nodes.iter().zip(&c.primitives).enumerate() {
        assert_eq!(n.name, format!("{}-{}", p.shape.kind().name(), i + 1));
        assert_eq!(n.mode, Some(gltf::mesh::Mode::Triangles), "{}", n.name);
        let got = area(n);
        assert!(
            (got - p.area).abs() <= 0.01 * p.area,
            "{}: {got} mm² drawn of {}",
            n.name,
            p.area
        );
        assert!(!n.points.is_empty(), "{}: no inliers drawn", n.name);
        // f32 positions keep about 1e-5 mm at these sizes.
        let off = n.points.iter().map(|q| p.shape.distance(*q)).fold(0.0, f64::max);
        assert!(
            off <= eps + 1e-4,
            "{}: a point {off} mm off its surface (ε {eps})",
            n.name
        );
        (worst_off, worst_area) = (worst_off.max(off), worst_area.max((got - p.area).abs() / p.area));
        let extras = &doc["nodes"][i + 1]["extras"];
        assert_eq!(extras["kind"], p.shape.kind().name());
        // Parsed from the same text as the extras, so the same f64s.
        let shape: Value = serde_json::from_str(&serde_json::to_string(&p.shape).expect("json")).expect("json");
        assert_eq!(extras["shape"], shape);
        assert_eq!(colours[i].len(), 2, "{}: triangles and points", n.name);
        assert_eq!(
            colours[i][0], colours[i][1],
            "{}: points in the surface's colour",
            n.name
        );
    }
    let distinct: BTreeSet<&String> = colours.iter().map(|c| &c[0]).collect();
    assert_eq!(distinct.len(), colours.len(), "a colour per node: {colours:?}");
    assert!(scene.points <= POINT_LIMIT);
    assert_eq!(scene.points, l.nodes.iter().map(|n| n.points.len()).sum::<usize>());
    let again = state.scene(View::Primitives).expect("the primitives view");
    assert_eq!(again.glb, scene.glb);
    eprintln!(
        "primitives view: {} nodes, {} triangles, {} points, {} bytes; worst area error {:.2e}, \
         worst point {off:.3} mm off its surface (ε {eps:.3} mm)",
        scene.nodes,
        scene.triangles,
        scene.points,
        scene.glb.len(),
        worst_area,
        off = worst_off,
    );
    scene.glb
}

#[test]
fn the_primitives_view_draws_each_primitive_its_triangles_and_inliers() {
    let textured = || samples::textured_box(DVec3::new(120.0, 90.0, 70.0), 3.0, 0.5, 10.0);
    let boxed = classified("textured-box", textured());
    let box_glb = check_primitives(&boxed, &["plane"; 12]);
    let knurled = classified("knurled", samples::knurled_cylinder(50.0, 60.0, 0.5, 36));
    let knurled_glb = check_primitives(&knurled, &["cylinder", "plane", "plane"]);
    let c = knurled.classify.as_deref().expect("classified");
    let cylinder = c.primitives.iter().find_map(|p| match p.shape {
        platener::classify::Surface::Cylinder { radius, .. } => Some(radius),
        _ => None,
    });
    assert!(cylinder.is_some_and(|r| (49.0..=50.0).contains(&r)), "{cylinder:?}");
    let again = classified("textured-box", textured());
    assert_eq!(
        again.scene(View::Primitives).expect("view").glb,
        box_glb,
        "same input, same bytes"
    );
    if let Some(script) = validator() {
        let out = tempfile::tempdir().expect("temp dir");
        let files: Vec<_> = [("box", &box_glb), ("knurled", &knurled_glb)]
            .into_iter()
            .map(|(name, glb)| {
                let file = out.path().join(format!("{name}-primitives.glb"));
                std::fs::write(&file, glb).expect("write");
                file
            })
            .collect();
        assert_valid(&script, &files);
    }
}

#[test]
fn methods_without_a_classification_have_no_primitives_view() {
    let state = platener::convert::convert(
        MethodKind::Plate,
        Source::triangles("box", samples::closed_box(100.0, 80.0, 60.0, 3.0)),
        Settings::default(),
        &Cancel::default(),
    )
    .expect("converts");
    assert_eq!(
        state.scene(View::Primitives),
        Err(SceneError::NotReached {
            view: "primitives",
            step: "classify"
        })
    );
}
