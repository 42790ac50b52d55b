//! Issue 31, item 2: interlocked slices. The organic samples (an animal on four legs, a hull
//! with a cabin, a torus on its rim, a vase with a handle) and the corpus's teapot convert
//! into upright slices crossing in halved slots: glue-free, without interference, with at least
//! 90 % of the parts' volume inside the model, and still standing on the model's feet.
//!
//! The insertion (every A slice lowered onto the B slices meets them only in its slots) is
//! checked geometrically in the module's tests, on a sphere, a torus and random ellipsoids.

use platener::convert;
use platener::method::MethodKind;
use platener::plan::{JointKind, Method, PartKind, Plan};
use platener::read::Triangle;
use platener::verify::verify;
use platener::{Cancel, Settings, Source, State};
use platener_fixtures::samples;

fn interlocked(name: &str, source: Source) -> State {
    let mut s = Settings::default();
    s.cut.nest_tries = 1;
    convert(MethodKind::Interlocked, source, s, &Cancel::default()).unwrap_or_else(|e| panic!("{name}: {e}"))
}

fn sample(name: &str) -> Vec<Triangle> {
    samples::organic_samples()
        .into_iter()
        .find(|(n, _)| *n == name)
        .map(|(_, t)| t)
        .expect("a sample")
}

/// The lowest and highest model z any part reaches.
fn z_range(plan: &Plan) -> (f64, f64) {
    let mut range = (f64::INFINITY, f64::NEG_INFINITY);
    for p in &plan.parts {
        let r = p.transform;
        for q in &p.outline {
            for z in [0.0, p.thickness] {
                let mz = r[2][0] * q.x + r[2][1] * q.y + r[2][2] * z + r[2][3];
                range = (range.0.min(mz), range.1.max(mz));
            }
        }
    }
    range
}

/// Checks what every interlocked plan must be; returns it.
fn check(name: &str, state: &State) -> Plan {
    let plan = state.export.as_ref().expect("exported").plan.clone();
    assert_eq!(plan.method, Method::Interlocked, "{name}");
    assert!(plan.parts.iter().all(|p| p.kind == PartKind::Plate), "{name}");
    assert!(!plan.joints.is_empty(), "{name}");
    assert!(plan.joints.iter().all(|j| j.kind == JointKind::Halved), "{name}");
    assert!(plan.glued.is_empty(), "{name}: {:?}", plan.glued);
    let v = verify(&plan, state.mesh.as_deref());
    assert!(v.passed(), "{name}: {:?}", v.failures);
    assert!(v.interference_share < 1e-4, "{name}: {}", v.interference_share);
    let inside = v.volume_inside.expect("measured against the model");
    assert!(inside >= 0.9, "{name}: {inside}");
    // Every part is held: it is in a joint.
    for p in &plan.parts {
        assert!(
            plan.joints.iter().any(|j| j.parts.contains(&p.id)),
            "{name}: part {} is held by nothing",
            p.id
        );
    }
    plan
}

#[test]
fn the_animal_stands_on_its_legs_glue_free() {
    let state = interlocked("animal", Source::triangles("animal", sample("animal.stl")));
    let plan = check("animal", &state);
    // The legs reach down to their rounded feet and the head to its top (0 and 86 mm; a slice
    // keeps only what lies inside the model across its whole thickness, so a rounded foot
    // loses its tip: 3.7 mm). Without the legs the lowest part would end at the body, 40 mm
    // up. The ears, 4–6 mm thick, fall between slices 12.8 mm apart.
    let (low, high) = z_range(&plan);
    assert!(low < 5.0, "{low}");
    assert!(high > 84.0, "{high}");
    // Ten slices along its 128 mm, three across its 44 mm (spacing 12.8 mm).
    let slices = &state.interlocked.as_ref().expect("snapshot").families;
    assert_eq!(slices.map(|f| f.count()), [10, 3]);
}

#[test]
fn the_other_organic_samples_interlock_glue_free() {
    for name in ["hull_with_cabin.stl", "torus.stl", "vase_with_handle.stl"] {
        let state = interlocked(name, Source::triangles(name, sample(name)));
        let plan = check(name, &state);
        let (low, _) = z_range(&plan);
        let model_low = state.read.as_ref().expect("read").bounds.min.z;
        // Rounded bottoms lose the tip a slice's thickness cannot hold (the vase: 1.2 mm).
        assert!(low - model_low < 2.0, "{name}: {low} against {model_low}");
    }
}

#[test]
fn a_slice_spacing_under_two_sheets_is_refused_with_its_name() {
    let mut s = Settings::default();
    s.interlocked.spacing = Some(5.0);
    let source = Source::triangles("animal", sample("animal.stl"));
    let e = convert(MethodKind::Interlocked, source, s, &Cancel::default()).expect_err("refused");
    let text = e.to_string();
    assert!(text.starts_with("`slice-spacing`:"), "{text}");
    assert!(text.contains("at least 6 mm"), "{text}");
}

#[test]
fn the_teapot_interlocks_glue_free() {
    let Ok(dir) = samples::shared_corpus().map_err(|m| eprintln!("{m}")) else {
        return;
    };
    let path = dir.join("organic/utah_teapot.stl");
    let state = interlocked("teapot", Source::File(path));
    check("teapot", &state);
}
