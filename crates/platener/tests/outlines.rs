//! Issue 15, "no internal errors" and "every outline is valid": every corpus model and every
//! sample, converted with both methods at every sheet thickness from 1 to 6 mm, either
//! converts or fails with a model or setting error (never an internal error, never a panic),
//! and every part of every plan it makes has a valid outline (simple rings, holes inside, no
//! material narrower than the kerf) and a valid cut path.

use std::sync::Mutex;
use std::time::Instant;

use glam::DVec3;
use platener::convert::{MethodResult, Status, no_progress};
use platener::method::MethodKind;
use platener::samples;
use platener::{Cancel, Error, Request, Settings, Source, convert_all};
use platener_geom::validate;
use rayon::prelude::*;

/// The sheet thicknesses swept, mm.
const THICKNESSES: [f64; 6] = [1.0, 2.0, 3.0, 4.0, 5.0, 6.0];

/// Every sample model of the library (the shipped examples and the generated test models).
fn sample_sources() -> Vec<Source> {
    let mut out: Vec<Source> = samples::shipped_examples()
        .into_iter()
        .map(|(name, _, triangles)| Source::triangles(name, triangles))
        .collect();
    let generated = [
        ("sphere", samples::sphere(DVec3::ZERO, 40.0, 24, 12)),
        ("torus", samples::torus(DVec3::ZERO, DVec3::Z, 40.0, 12.0, 24, 12)),
        ("two-bodies", samples::two_bodies(10.0)),
        ("table", samples::table(120.0, 80.0, 70.0, 10.0, 3.0)),
        ("star", samples::star(5, 40.0, 3.0, 30.0)),
        ("fan", samples::fan(&[0.0, 70.0, 160.0], 40.0, 3.0, 30.0)),
        ("crossing-plates", samples::crossing_plates(80.0, 3.0)),
        ("box-grid", samples::box_grid(2, 2, 40.0, 3.0, 5.0)),
        ("shelf", samples::shelf(100.0, 120.0, 60.0, 80.0, 3.0)),
        ("roof", samples::roof(60.0, 30.0, 80.0, 3.0)),
        (
            "rounded-box",
            samples::rounded_box(DVec3::new(80.0, 60.0, 40.0), 10.0, 6),
        ),
    ];
    out.extend(generated.into_iter().map(|(n, t)| Source::triangles(n, t)));
    out
}

/// What is wrong with one method's result, if anything: an internal error or panic, or an
/// invalid outline or cut path in its plan.
fn problems(model: &str, t: f64, result: &MethodResult) -> Vec<String> {
    let at = format!("{model} {:?} {t} mm", result.method);
    if result.status == Status::Panicked {
        return vec![format!("{at}: panicked: {:?}", result.error)];
    }
    if let Some(e @ Error::Internal { .. }) = &result.error {
        return vec![format!("{at}: internal error: {e}")];
    }
    let Some(cut) = result.state.as_ref().and_then(|s| s.kerf.as_ref()) else {
        return Vec::new();
    };
    let mut out = Vec::new();
    for part in &cut.parts {
        let nominal = validate(&part.nominal, cut.kerf);
        if !nominal.is_empty() {
            out.push(format!(
                "{at}: part {} outline: {:?}",
                part.id,
                &nominal[..nominal.len().min(3)]
            ));
        }
        let path = validate(&part.cut, 0.0);
        if !path.is_empty() {
            out.push(format!(
                "{at}: part {} cut path: {:?}",
                part.id,
                &path[..path.len().min(3)]
            ));
        }
    }
    out
}

/// Converts `source` with both methods on `t` mm sheets and lists what is wrong.
fn sweep_one(source: Source, t: f64) -> (Vec<String>, usize) {
    let model = source.name();
    let settings = Settings {
        thicknesses: vec![t],
        ..Settings::default()
    };
    let request = Request {
        methods: MethodKind::ALL.to_vec(),
        ..Request::new(source, settings)
    };
    let all = convert_all(request, &Cancel::default(), no_progress());
    let converted = all.methods.iter().filter(|m| m.status == Status::Converted).count();
    let found = all.methods.iter().flat_map(|m| problems(&model, t, m)).collect();
    (found, converted)
}

/// The sweep over `sources` × [`THICKNESSES`], on rayon's threads; panics listing every
/// problem found. Prints how long it took and how many plans it checked.
fn sweep(what: &str, sources: Vec<Source>) {
    let start = Instant::now();
    let jobs: Vec<(Source, f64)> = sources
        .into_iter()
        .flat_map(|s| THICKNESSES.map(|t| (s.clone(), t)))
        .collect();
    let found = Mutex::new(Vec::new());
    let converted: usize = jobs
        .into_par_iter()
        .map(|(source, t)| {
            let (problems, converted) = sweep_one(source, t);
            found.lock().expect("lock").extend(problems);
            converted
        })
        .sum();
    let mut found = found.into_inner().expect("lock");
    found.sort();
    eprintln!(
        "{what}: {converted} plans checked in {:.0} s, {} problem(s)",
        start.elapsed().as_secs_f64(),
        found.len()
    );
    assert!(converted > 0, "{what}: nothing converted");
    assert!(
        found.is_empty(),
        "{what}: {} problem(s):\n{}",
        found.len(),
        found.join("\n")
    );
}

#[test]
fn every_sample_at_every_thickness_converts_with_valid_outlines() {
    sweep("samples", sample_sources());
}

#[test]
fn every_corpus_model_at_every_thickness_converts_with_valid_outlines() {
    let Ok(dir) = samples::shared_corpus().map_err(|m| eprintln!("{m}")) else {
        return;
    };
    let files = samples::stl_files(&dir);
    assert!(files.len() >= 50, "expected the 53-file corpus, found {}", files.len());
    sweep("corpus", files.into_iter().map(Source::File).collect());
}

/// The stacked case of issue 15 built by hand: a layer whose shaft slot has a corner exactly on
/// the layer's slanted edge (the slot is a hole touching the outline), a second layer with a
/// 0.05 mm sliver on its side, and a third that is nothing but a sliver. Cleaning for a 0.2 mm
/// kerf leaves the first two valid, keeps every point of the slot free (the shaft still fits),
/// loses less than the kerf squared at the touch, removes the sliver, and leaves out the third
/// part with its joint, naming it.
#[test]
fn a_slot_corner_on_the_layer_edge_is_repaired_where_parts_are_made() {
    use platener::parts::clean::clean_parts;
    use platener::plan::{Joint, JointKind, Part};
    use platener_geom::polygon::rect;
    use platener_geom::{Frame, Polygon};

    let v = glam::DVec2::new;
    let frame = Frame::on_plane(DVec3::ZERO, DVec3::Z);
    let mut layer = Polygon {
        outer: vec![v(0.0, 0.0), v(30.0, 0.0), v(30.0, 12.0), v(34.0, 30.0), v(0.0, 30.0)],
        holes: vec![rect(27.0, 12.0, 30.0, 18.0)],
    };
    layer.normalize_orientation();
    let mut sliver = Polygon::new(vec![
        v(0.0, 0.0),
        v(20.0, 0.0),
        v(20.0, 5.0),
        v(26.0, 5.0),
        v(26.0, 5.05),
        v(20.0, 5.05),
        v(20.0, 20.0),
        v(0.0, 20.0),
    ]);
    sliver.normalize_orientation();
    let thin = Polygon::new(rect(0.0, 0.0, 30.0, 0.05));
    let before = [layer.clone(), sliver.clone()];
    assert!(!validate(&layer, 0.2).is_empty() && !validate(&sliver, 0.2).is_empty());
    let mut parts = vec![
        Part::plate(1, 3.0, layer, frame),
        Part::plate(2, 3.0, sliver, frame),
        Part::plate(3, 3.0, thin, frame),
    ];
    let joint = |a, b, label| Joint {
        parts: [a, b],
        kind: JointKind::Shaft,
        angle_deg: 90.0,
        label,
    };
    let mut joints = vec![joint(1, 2, 1), joint(2, 3, 2)];
    let repairs = clean_parts(&mut parts, &mut joints, 0.2);
    assert_eq!(
        repairs.iter().map(|r| (r.part, r.removed)).collect::<Vec<_>>(),
        [(1, false), (2, false), (3, true)]
    );
    assert!(repairs[2].message.as_deref().is_some_and(|m| m.contains("part 3")));
    assert_eq!(parts.len(), 2);
    assert_eq!(joints, vec![joint(1, 2, 1)]);
    for (part, before) in parts.iter().zip(&before) {
        assert!(
            validate(&part.polygon, 0.2).is_empty(),
            "{:?}",
            validate(&part.polygon, 0.2)
        );
        let lost = before.area() - part.polygon.area();
        assert!((0.0..0.35).contains(&lost), "part {}: lost {lost} mm²", part.id);
    }
    for q in [v(27.1, 12.1), v(29.9, 12.1), v(29.9, 17.9), v(27.1, 17.9)] {
        assert!(!parts[0].polygon.contains(q), "slot corner {q} filled");
    }
    assert!(parts[0].polygon.contains(v(26.9, 15.0)) && parts[0].polygon.contains(v(31.0, 20.0)));
    // The sliver is gone: nothing right of x = 20.1.
    assert!(parts[1].polygon.outer.iter().all(|p| p.x <= 20.0 + 1e-9));
}
