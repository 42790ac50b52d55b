//! The 3D scenes (issue 16): every view of the examples and of the corpus loads back with the
//! `gltf` crate, solids are watertight and outward, the `final` view's parts have the plan
//! parts' volumes and places, and the Khronos validator finds no error.

#[path = "scenes/check.rs"]
mod check;

use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::{Duration, Instant};

use check::{Loaded, assert_root, bounds, load, volume, watertight};
use glam::DVec3;
use platener::convert::{Request, convert, convert_all, no_progress};
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
    platener::samples::shared_corpus().map_err(|m| eprintln!("{m}")).ok()
}

fn stl_files(dir: &Path) -> Vec<PathBuf> {
    let mut files: Vec<PathBuf> = std::fs::read_dir(dir)
        .expect("corpus folder readable")
        .flat_map(|e| {
            let p = e.expect("entry").path();
            if p.is_dir() { stl_files(&p) } else { vec![p] }
        })
        .filter(|p| p.extension().is_some_and(|e| e == "stl"))
        .collect();
    files.sort();
    files
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
        View::Plates | View::Bent => "plate-",
        View::Final => "part-",
    };
    for (i, n) in l.nodes.iter().enumerate() {
        assert!(n.name.starts_with(prefix), "{v}: node {}", n.name);
        if matches!(v, View::Plates | View::Bent) {
            assert_eq!(n.name, format!("plate-{}", i + 1));
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

/// Each part node: volume = polygon area × thickness within 0.1 %; model-space bounds = the
/// part's corners at z = 0 and z = thickness mapped by its frame (plan.json's transform),
/// within 1e-6 of the largest coordinate (f32 positions and rotations keep about 1e-7).
fn assert_parts(l: &Loaded, parts: &[Part]) {
    let mut parts: Vec<&Part> = parts.iter().collect();
    parts.sort_by_key(|p| p.id);
    assert_eq!(l.nodes.len(), parts.len());
    for (n, p) in l.nodes.iter().zip(parts) {
        assert_eq!(n.name, format!("part-{}", p.id));
        let want = p.polygon.area() * p.thickness;
        let got = volume(&n.positions, &n.triangles());
        assert!(
            (got - want).abs() <= 1e-3 * want,
            "{}: volume {got}, plan {want}",
            n.name
        );
        let (lo, hi) = bounds(n.world());
        let corners = p
            .polygon
            .outer
            .iter()
            .flat_map(|q| [0.0, p.thickness].map(|z| p.frame.to_model(q.extend(z))));
        let (elo, ehi) = bounds(corners);
        let size = (ehi - elo).length().max(elo.abs().max(ehi.abs()).max_element());
        let err = (lo - elo).abs().max((hi - ehi).abs()).max_element();
        assert!(err <= 1e-6 * size, "{}: bounds {lo}..{hi}, plan {elo}..{ehi}", n.name);
    }
}

fn parts_of(state: &State) -> &[Part] {
    state.parts.as_ref().map_or(&[], |p| &p.parts)
}

#[test]
fn every_view_of_the_examples_loads_back_and_final_matches_the_parts() {
    for path in examples() {
        let state = run(MethodKind::Plate, &path).expect("plate method");
        for v in View::ALL {
            let scene = view(&state, v);
            let l = check_view(v, &scene, parts_of(&state));
            assert!(!l.nodes.is_empty(), "{}: {v} is empty", path.display());
            if v == View::Bent {
                assert_eq!(scene.glb, view(&state, View::Plates).glb, "bent = plates for now");
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
    for v in View::ALL {
        assert_eq!(view(&c, v).glb, view(&again, v).glb, "{v}");
    }
    let bundle = c.export.as_ref().expect("export");
    assert_eq!(bundle.files["assembly.glb"], view(&c, View::Final).glb);
}

#[test]
fn view_names_round_trip_in_order() {
    let names: Vec<&str> = View::ALL.iter().map(|v| v.name()).collect();
    assert_eq!(names, ["model", "wireframe", "coplanar", "plates", "bent", "final"]);
    for v in View::ALL {
        assert_eq!(v.name().parse::<View>(), Ok(v));
    }
    assert!("assembly".parse::<View>().is_err());
}

/// Corpus models up to this size (bytes) are checked, to keep the test near a minute in a
/// debug build on two cores; the others are counted and named as skipped.
const CORPUS_MAX_BYTES: u64 = 450_000;

/// A corpus model whose conversion (a debug build) takes longer is cancelled, counted and
/// named, not checked: the views take well under a second, the conversion is what is slow.
const CORPUS_MODEL_BUDGET: Duration = Duration::from_secs(8);

/// The plate method within `budget` (the library's time limit).
fn run_within(path: &Path, budget: Duration) -> platener::Result<State> {
    let request = Request {
        methods: vec![MethodKind::Plate],
        timeout: Some(budget),
        ..Request::new(Source::File(path.into()), Settings::default())
    };
    let mut all = convert_all(request, &Cancel::default(), no_progress());
    let result = all.methods.pop().expect("one method");
    match (result.error, result.state) {
        (None, Some(state)) => Ok(state),
        (Some(e), _) => Err(e),
        (None, None) => panic!("a method without state or error"),
    }
}

#[test]
fn every_view_of_every_corpus_model_that_converts() {
    let Some(dir) = corpus_dir() else { return };
    let start = Instant::now();
    let (mut checked, mut failed, mut large, mut slow) = (0, 0, Vec::new(), Vec::new());
    for path in stl_files(&dir) {
        if std::fs::metadata(&path).map_or(0, |m| m.len()) > CORPUS_MAX_BYTES {
            large.push(path.file_name().map(|n| n.to_string_lossy().into_owned()));
            continue;
        }
        let state = match run_within(&path, CORPUS_MODEL_BUDGET) {
            Ok(state) => state,
            Err(platener::Error::TimedOut { .. }) => {
                slow.push(path.file_name().map(|n| n.to_string_lossy().into_owned()));
                continue;
            }
            Err(_) => {
                failed += 1;
                continue;
            }
        };
        for v in View::ALL {
            check_view(v, &view(&state, v), parts_of(&state));
        }
        checked += 1;
    }
    eprintln!(
        "corpus scenes: {checked} models checked (six views each), {failed} did not convert, \
         {} larger than {CORPUS_MAX_BYTES} bytes skipped {large:?}, {} slower than {:?} to convert skipped {slow:?}, {:.1} s",
        large.len(),
        slow.len(),
        CORPUS_MODEL_BUDGET,
        start.elapsed().as_secs_f64()
    );
    assert!(checked > 0, "no corpus model was checked");
}

#[test]
fn planar_shapes_of_the_corpus_triangulate_to_their_area() {
    let Some(dir) = corpus_dir() else { return };
    let (mut models, mut shapes) = (0, 0);
    for path in stl_files(&dir) {
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

/// The Khronos glTF validator over every view of the examples. Skipped with a message when
/// node or `tools/gltf-validator/node_modules` is missing, unless `PLATENER_REQUIRE_VALIDATOR=1`.
#[test]
fn the_khronos_validator_finds_no_errors() {
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
        eprintln!("skipping: node or the validator is missing (npm ci --prefix tools/gltf-validator)");
        return;
    }
    let out = tempfile::tempdir().expect("temp dir");
    let mut files = Vec::new();
    for path in examples() {
        let state = run(MethodKind::Plate, &path).expect("plate method");
        let stem = path.file_stem().expect("stem").to_string_lossy().into_owned();
        for v in View::ALL {
            let file = out.path().join(format!("{stem}-{v}.glb"));
            std::fs::write(&file, view(&state, v).glb).expect("write");
            files.push(file);
        }
    }
    let r = Command::new("node")
        .arg(tool.join("validate.js"))
        .args(&files)
        .output()
        .expect("node runs");
    let report = String::from_utf8_lossy(&r.stdout);
    eprintln!("{report}{}", String::from_utf8_lossy(&r.stderr));
    assert!(r.status.success(), "the validator found errors:\n{report}");
    assert!(report.contains(&format!("{} valid, 0 with errors", files.len())));
}

#[test]
fn a_point_of_the_model_lands_where_a_viewer_expects_it() {
    // Model (x, y, z) mm → glTF (x, z, -y) m: the root's scale and turn applied.
    let q = glam::DQuat::from_rotation_x(-std::f64::consts::FRAC_PI_2);
    let p = q * (DVec3::new(10.0, 20.0, 30.0) * 0.001);
    assert!((p - DVec3::new(0.010, 0.030, -0.020)).length() < 1e-12);
}
