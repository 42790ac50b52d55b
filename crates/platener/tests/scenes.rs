//! The 3D scenes (issue 16): every view of the examples and of the corpus loads back with the
//! `gltf` crate, solids are watertight and outward, the `final` view's parts have the plan
//! parts' volumes and places, and the Khronos validator finds no error. The classifier's
//! `primitives` view is tested in `scenes/primitives.rs`.

#[path = "scenes/check.rs"]
mod check;
#[path = "scenes/primitives.rs"]
mod primitives;

use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::Instant;

use check::{Loaded, assert_root, bounds, load, volume, watertight};
use glam::DVec3;
use platener::convert::{MethodResult, Request, convert, convert_all, no_progress};
use platener::method::MethodKind;
use platener::plan::Part;
use platener::scene::{Scene, View};
use platener::{Cancel, Settings, Source, State};

fn examples() -> Vec<PathBuf> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples");
    let mut files: Vec<PathBuf> = std::fs::read_dir(dir)
        .expect("examples folder")
        .map(|e| e.expect("entry").path())
        .filter(|p| p.extension().is_some_and(|e| e == "stl"))
        .collect();
    files.sort();
    assert_eq!(files.len(), 3, "{files:?}");
    files
}

/// The corpus, or `None` after saying why these tests skip (CI fails instead).
fn corpus_dir() -> Option<PathBuf> {
    platener_fixtures::samples::shared_corpus()
        .map_err(|m| eprintln!("{m}"))
        .ok()
}

fn run(method: MethodKind, path: &Path) -> platener::Result<State> {
    convert(
        method,
        Source::File(path.into()),
        Settings::default(),
        &Cancel::default(),
    )
}

/// One view of a conversion's snapshots, as the library draws it for viewers.
fn view(state: &State, v: View) -> Scene {
    state.scene(v).unwrap_or_else(|e| panic!("view {v}: {e}"))
}

/// Loads the scene back and checks what every view promises: the root's scale and turn, node
/// names, line or triangle meshes, closed outward solids; for `final` the plan's parts.
fn check_view(v: View, scene: &Scene, parts: &[Part]) -> Loaded {
    let l = load(&scene.glb);
    assert_root(&l);
    assert_eq!(scene.nodes, l.nodes.len() + 1, "{v}");
    let prefix = match v {
        View::Model => "model",
        View::Wireframe => "wireframe",
        View::Coplanar => "group-",
        View::Primitives => "",
        View::Plates | View::Bent => "plate-",
        View::Final => "part-",
    };
    for (i, n) in l.nodes.iter().enumerate() {
        assert!(n.name.starts_with(prefix), "{v}: node {}", n.name);
        if matches!(v, View::Plates | View::Bent) {
            assert_eq!(n.name, format!("plate-{}", i + 1));
        }
        if v == View::Primitives {
            let kind = n.name.rsplit_once('-').map(|(k, _)| k);
            let named =
                n.name == "unexplained" || kind.is_some_and(|k| ["plane", "cylinder", "sphere", "cone"].contains(&k));
            assert!(named, "{v}: node {}", n.name);
        }
        let Some(mode) = n.mode else { continue };
        let want = if v == View::Wireframe {
            gltf::mesh::Mode::Lines
        } else {
            gltf::mesh::Mode::Triangles
        };
        assert_eq!(mode, want, "{v}");
        if matches!(v, View::Plates | View::Bent | View::Final) {
            let tris = n.triangles();
            watertight(&n.positions, &tris).unwrap_or_else(|e| panic!("{v} {}: {e}", n.name));
            assert!(volume(&n.positions, &tris) > 0.0, "{v} {}: faces inward", n.name);
        }
    }
    if v == View::Final {
        assert_parts(&l, parts);
    }
    l
}

/// Each part node: volume = polygon area × thickness within 0.1 % (a bent part's within 10 %:
/// its zone slices open or overlap by a hair at the faces, and where three plates of a net
/// meet at a vertex (the low-poly lamp) a zone's strip and its neighbours' segments overlap
/// or miss a corner); model-space bounds = the
/// corners of the part's pieces (a flat part is one, placed by plan.json's transform; a bent
/// part's segments and bend slices each by their own frame) at z = 0 and z = thickness,
/// within 1e-6 of the largest coordinate (f32 positions and rotations keep about 1e-7).
fn assert_parts(l: &Loaded, parts: &[Part]) {
    let mut parts: Vec<&Part> = parts.iter().collect();
    parts.sort_by_key(|p| p.id);
    assert_eq!(l.nodes.len(), parts.len());
    for (n, p) in l.nodes.iter().zip(parts) {
        assert_eq!(n.name, format!("part-{}", p.id));
        let want = p.polygon.area() * p.thickness;
        let got = volume(&n.positions, &n.triangles());
        let within = if p.segments.is_empty() { 1e-3 } else { 0.1 };
        assert!(
            (got - want).abs() <= within * want,
            "{}: volume {got}, plan {want}",
            n.name
        );
        let (lo, hi) = bounds(n.world());
        // Every piece's corners: a bent part's segments and bend slices, a flat part itself.
        let pieces = p.pieces().unwrap_or_else(|e| panic!("{}: {e}", n.name));
        let corners = pieces.iter().flat_map(|s| {
            s.polygon
                .outer
                .iter()
                .flat_map(|q| [0.0, s.thickness].map(|z| s.frame.to_model(q.extend(z))))
        });
        let (elo, ehi) = bounds(corners);
        let size = (ehi - elo).length().max(elo.abs().max(ehi.abs()).max_element());
        let err = (lo - elo).abs().max((hi - ehi).abs()).max_element();
        assert!(err <= 1e-6 * size, "{}: bounds {lo}..{hi}, plan {elo}..{ehi}", n.name);
    }
}

/// The views the plate method reaches: all but the classifier's `primitives`.
fn plate_views() -> impl Iterator<Item = View> {
    View::ALL.into_iter().filter(|v| *v != View::Primitives)
}

fn parts_of(state: &State) -> &[Part] {
    state.final_parts().as_ref().map_or(&[], |p| &p.parts)
}

#[test]
fn every_view_of_the_examples_loads_back_and_final_matches_the_parts() {
    for path in examples() {
        let state = run(MethodKind::Plate, &path).expect("plate method");
        for v in plate_views() {
            let scene = view(&state, v);
            let l = check_view(v, &scene, parts_of(&state));
            assert!(!l.nodes.is_empty(), "{}: {v} is empty", path.display());
            if v == View::Bent && state.bends.as_ref().is_some_and(|b| b.parts.is_empty()) {
                // No bent parts: the same plates, in the same colours, as the plates view.
                let plates = load(&view(&state, View::Plates).glb);
                assert_eq!(l.nodes.len(), plates.nodes.len());
                for (a, b) in l.nodes.iter().zip(&plates.nodes) {
                    assert_eq!((&a.name, &a.positions, &a.indices), (&b.name, &b.positions, &b.indices));
                }
            }
        }
        let stacked = run(MethodKind::Stacked, &path).expect("stacked method");
        check_view(View::Final, &view(&stacked, View::Final), parts_of(&stacked));
    }
}

#[test]
fn scenes_are_byte_identical_and_every_plan_zip_holds_the_assembly() {
    let path = &examples()[0];
    let c = run(MethodKind::Plate, path).expect("plate method");
    let again = run(MethodKind::Plate, path).expect("plate method");
    for v in plate_views() {
        assert_eq!(view(&c, v).glb, view(&again, v).glb, "{v}");
    }
    let bundle = c.export.as_ref().expect("export");
    assert_eq!(bundle.files["assembly.glb"], view(&c, View::Final).glb);
}

#[test]
fn view_names_round_trip_in_order() {
    let names: Vec<&str> = View::ALL.iter().map(|v| v.name()).collect();
    assert_eq!(
        names,
        [
            "model",
            "wireframe",
            "coplanar",
            "primitives",
            "plates",
            "bent",
            "final"
        ]
    );
    for v in View::ALL {
        assert_eq!(v.name().parse::<View>(), Ok(v));
    }
    assert!("assembly".parse::<View>().is_err());
}

/// The plate method's result, whether it converted or stopped part way (its snapshots so far
/// are kept).
fn plate_result(path: &Path) -> MethodResult {
    let request = Request {
        methods: vec![MethodKind::Plate],
        ..Request::new(Source::File(path.into()), Settings::default())
    };
    let mut all = convert_all(request, &Cancel::default(), no_progress());
    all.methods.pop().expect("one method")
}

/// Every view of every corpus model that the plate method reaches: a model that converts
/// gets all six, one whose plate method fails part way the views of the steps it reached
/// (at least the model, its edges and its planar groups), an unreadable file none. Every
/// scene loads back and holds what its view promises; the Khronos validator checks them all.
#[test]
fn every_view_of_every_corpus_model() {
    let Some(dir) = corpus_dir() else { return };
    let start = Instant::now();
    let out = tempfile::tempdir().expect("temp dir");
    let (mut files, mut full, mut partial, mut unreadable) = (Vec::new(), 0, 0, 0);
    for path in platener_fixtures::samples::stl_files(&dir) {
        let result = plate_result(&path);
        let name = path.file_stem().expect("stem").to_string_lossy().into_owned();
        let Some(state) = result.state.as_ref().filter(|s| s.read.is_some()) else {
            unreadable += 1;
            continue;
        };
        let mut drawn = 0;
        for v in View::ALL {
            let Ok(scene) = state.scene(v) else { continue };
            check_view(v, &scene, parts_of(state));
            let file = out.path().join(format!("{name}-{v}.glb"));
            std::fs::write(&file, &scene.glb).expect("write");
            files.push(file);
            drawn += 1;
        }
        assert!(drawn >= 3, "{name}: only {drawn} views");
        if result.error.is_none() {
            assert_eq!(drawn, 6, "{name}");
            full += 1;
        } else {
            partial += 1;
        }
    }
    eprintln!(
        "corpus scenes: {full} models with all six views, {partial} with the views their plate method reached, \
         {unreadable} unreadable; {} scenes, {:.1} s",
        files.len(),
        start.elapsed().as_secs_f64()
    );
    // The plate method converts 29 of the 53 files; the 6 unreadable ones are the corpus'
    // deliberately broken files (tests/corpus.rs checks their messages).
    assert!(full >= 29, "only {full} corpus models converted with all six views");
    assert_eq!(unreadable, 6);
    assert_eq!(full + partial + unreadable, 53);
    if let Some(script) = validator() {
        assert_valid(&script, &files);
    }
}

#[test]
fn planar_shapes_of_the_corpus_triangulate_to_their_area() {
    let Some(dir) = corpus_dir() else { return };
    let (mut models, mut shapes) = (0, 0);
    for path in platener_fixtures::samples::stl_files(&dir) {
        let Ok((state, _)) =
            platener::inspect::run_foundation(Source::File(path.clone()), Settings::default(), &Cancel::default())
        else {
            continue;
        };
        let Some(s) = state.shapes.as_ref() else { continue };
        for shape in &s.shapes {
            let t = platener_geom::triangulate::triangulate(&shape.polygon).expect("on the grid");
            // Snapping moves a corner by at most 0.7 µm: the area by at most that times the
            // perimeter (1 µm × perimeter stated).
            let perimeter: f64 = std::iter::once(&shape.polygon.outer)
                .chain(&shape.polygon.holes)
                .map(|r| platener_geom::polygon::perimeter(r))
                .sum();
            let (got, want) = (t.area(), shape.polygon.area());
            assert!(
                (got - want).abs() <= 1e-3 * perimeter + 1e-9 * want,
                "{}: a shape of {want} mm² triangulates to {got} mm²",
                path.display()
            );
            shapes += 1;
        }
        models += 1;
    }
    eprintln!("corpus triangulation: {shapes} planar shapes of {models} models");
    assert!(shapes > 0);
}

/// The Khronos validator's script, or `None` (with a message) when node or
/// `tools/gltf-validator/node_modules` is missing, unless `PLATENER_REQUIRE_VALIDATOR=1`.
fn validator() -> Option<PathBuf> {
    let tool = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../tools/gltf-validator");
    let required = std::env::var("PLATENER_REQUIRE_VALIDATOR").as_deref() == Ok("1");
    let node = Command::new("node")
        .arg("--version")
        .output()
        .is_ok_and(|o| o.status.success());
    if !node || !tool.join("node_modules/gltf-validator").is_dir() {
        assert!(
            !required,
            "PLATENER_REQUIRE_VALIDATOR=1 but node or {}/node_modules is missing",
            tool.display()
        );
        eprintln!("skipping validation: node or the validator is missing (npm ci --prefix tools/gltf-validator)");
        return None;
    }
    Some(tool.join("validate.js"))
}

/// Runs the validator on `files`; every one must be free of errors.
fn assert_valid(script: &Path, files: &[PathBuf]) {
    let r = Command::new("node")
        .arg(script)
        .args(files)
        .output()
        .expect("node runs");
    let report = String::from_utf8_lossy(&r.stdout);
    assert!(
        r.status.success(),
        "the validator found errors:\n{report}{}",
        String::from_utf8_lossy(&r.stderr)
    );
    assert!(
        report.contains(&format!("{} valid, 0 with errors", files.len())),
        "{report}"
    );
}

/// The Khronos glTF validator over every view of the examples.
#[test]
fn the_khronos_validator_finds_no_errors() {
    let Some(script) = validator() else { return };
    let out = tempfile::tempdir().expect("temp dir");
    let mut files = Vec::new();
    for path in examples() {
        let state = run(MethodKind::Plate, &path).expect("plate method");
        let stem = path.file_stem().expect("stem").to_string_lossy().into_owned();
        for v in plate_views() {
            let file = out.path().join(format!("{stem}-{v}.glb"));
            std::fs::write(&file, view(&state, v).glb).expect("write");
            files.push(file);
        }
    }
    assert_valid(&script, &files);
}

/// Bent parts (an L, a U of three bends, a ring) in `final`: each node closed and outward,
/// of the flat shape's volume, within the bounds of its pieces; the L's box is the L's; the
/// Khronos validator accepts the file.
#[test]
fn bent_parts_draw_as_closed_curved_strips_in_the_final_view() {
    use platener::plan::bent::sample_strip;
    let r = 10.0 / std::f64::consts::FRAC_PI_2;
    let parts = vec![
        sample_strip(1, 3.0, 30.0, &[40.0, 40.0], &[90.0], 10.0),
        sample_strip(2, 3.0, 30.0, &[40.0, 30.0, 20.0, 40.0], &[90.0, 45.0, 45.0], 10.0),
        sample_strip(
            3,
            3.0,
            30.0,
            &[40.0, 40.0, 40.0 - r + 1.5, 41.5 + r],
            &[90.0, 90.0, 90.0],
            10.0,
        ),
    ];
    let scene = platener::scene::assembly(&parts).expect("draws");
    let l = check_view(View::Final, &scene, &parts);
    let (lo, hi) = bounds(l.nodes[0].world());
    let want = DVec3::new(40.0 + r + 1.5, 30.0, 1.5 + r + 40.0);
    // glTF positions are f32 (about 1e-5 mm here); the slices' corners stray from the arc by
    // their sagitta (0.005 mm).
    assert!(
        lo.abs().max_element() < 0.01 && (hi - want).abs().max_element() < 0.01,
        "{lo} {hi}"
    );
    if let Some(script) = validator() {
        let out = tempfile::tempdir().expect("temp dir");
        let file = out.path().join("bent-final.glb");
        std::fs::write(&file, &scene.glb).expect("write");
        assert_valid(&script, &[file]);
    }
}

#[test]
fn a_point_of_the_model_lands_where_a_viewer_expects_it() {
    // Model (x, y, z) mm → glTF (x, z, -y) m: the root's scale and turn applied.
    let q = glam::DQuat::from_rotation_x(-std::f64::consts::FRAC_PI_2);
    let p = q * (DVec3::new(10.0, 20.0, 30.0) * 0.001);
    assert!((p - DVec3::new(0.010, 0.030, -0.020)).length() < 1e-12);
}

/// The material index of each child of the root, by node name.
fn materials(glb: &[u8]) -> Vec<(String, Option<usize>)> {
    let g = gltf::Gltf::from_slice(glb).expect("a valid GLB");
    let scene = g.default_scene().expect("a default scene");
    let root = scene.nodes().next().expect("a root");
    root.children()
        .map(|n| {
            let material = n
                .mesh()
                .and_then(|m| m.primitives().next())
                .and_then(|p| p.material().index());
            (n.name().unwrap_or_default().to_string(), material)
        })
        .collect()
}

#[test]
fn the_bent_view_colours_a_tube_as_one_part_and_a_box_plate_by_plate() {
    let tube = Source::Triangles {
        name: "tube".into(),
        triangles: std::sync::Arc::new(platener_fixtures::samples::tube(12, 50.0, 60.0, 3.0)),
    };
    let state = convert(MethodKind::Plate, tube, Settings::default(), &Cancel::default()).expect("tube");
    let nodes = materials(&view(&state, View::Bent).glb);
    assert_eq!(nodes.len(), 12);
    assert!(nodes.iter().all(|(_, m)| m.is_some() && *m == nodes[0].1), "{nodes:?}");
    let plates = materials(&view(&state, View::Plates).glb);
    let distinct: std::collections::BTreeSet<_> = plates.iter().map(|(_, m)| *m).collect();
    assert!(distinct.len() > 1, "the plates view keeps a colour per plate");
    let boxed = run(MethodKind::Plate, &examples()[0]).expect("example");
    let nodes = materials(&view(&boxed, View::Bent).glb);
    let distinct: std::collections::BTreeSet<_> = nodes.iter().map(|(_, m)| *m).collect();
    assert_eq!(
        distinct.len(),
        nodes.len(),
        "a box has no bent parts: one colour per plate"
    );
}
