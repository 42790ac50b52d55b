use glam::DVec3;

use super::*;
use crate::convert::convert;
use crate::method::MethodKind;
use crate::pipeline::State;
use crate::plan::JointKind;
use crate::read::Triangle;
use crate::{Cancel, Settings, Source, samples};

/// The score of a converted state.
fn score_of(c: &State) -> Score {
    score(
        c.mesh.as_ref().expect("mesh"),
        c.bundle().expect("bundle"),
        c.plates.as_deref(),
    )
}

fn box_conversion() -> State {
    let source = Source::triangles("box", samples::closed_box(100.0, 80.0, 60.0, 3.0));
    convert(MethodKind::Plate, source, Settings::default(), &Cancel::default()).expect("converts")
}

/// Indexed triangles (no welding needed for ray tests: each triangle keeps its own corners).
fn indexed(triangles: &[Triangle]) -> (Vec<DVec3>, Vec<[u32; 3]>) {
    let vertices: Vec<DVec3> = triangles.iter().flatten().copied().collect();
    let indices = (0..triangles.len() as u32)
        .map(|i| [3 * i, 3 * i + 1, 3 * i + 2])
        .collect();
    (vertices, indices)
}

#[test]
fn the_box_plan_reproduces_the_box() {
    let c = box_conversion();
    let s = score_of(&c);
    // Six plates (with their joints) are the whole box: the surface is covered, nothing sticks
    // out, nothing overlaps (±1 point for sampling).
    assert!(s.shape.surface_covered > 0.95, "{s:?}");
    assert!(s.shape.volume_inside > 0.99, "{s:?}");
    assert!(s.assembly.interference < 0.01, "{s:?}");
    // Where plates were detected is within reach of a plate, so the sampled share is no lower.
    let detected = s.shape.plates_surface_share.expect("plate method");
    assert!(detected <= s.shape.surface_covered + 0.01, "{s:?}");
    // A hollow box is one solid (its cavity is no second one).
    assert_eq!(s.assembly.solids, 1);
    assert_eq!(s.effort.parts, 6);
    assert!(s.effort.sheets >= 1);
    assert!(s.effort.cut_length > 0.0);
    let expected = s.shape.value * (0.5 + ASSEMBLY_WEIGHT * s.assembly.value + EFFORT_WEIGHT * s.effort.value);
    assert!((s.total - expected).abs() < 1e-12);
    assert!((0.0..=1.0).contains(&s.total));
}

#[test]
fn the_same_conversion_always_gets_the_same_score() {
    let c = box_conversion();
    assert_eq!(score_of(&c), score_of(&c));
}

#[test]
fn joints_connect_the_assembly() {
    let c = box_conversion();
    let bundle = c.bundle().expect("bundle");
    let mut plan = bundle.plan.clone();
    let joint = |a, b| PlanJoint {
        parts: [a, b],
        kind: JointKind::Finger,
        angle: 90.0,
        label: a,
    };
    let mesh = c.mesh.as_ref().expect("mesh");
    let settings = ScoreSettings::default();
    // Parts 1–2–3, 4–5 and 6: three connections of the five one solid needs.
    plan.joints = vec![joint(1, 2), joint(2, 3), joint(4, 5)];
    let s = evaluate(mesh, &plan, &bundle.report, &settings);
    assert_eq!((s.assembly.groups, s.assembly.solids), (3, 1));
    assert!((s.assembly.connectivity - 3.0 / 5.0).abs() < 1e-12);
    // No joints: not connected at all.
    plan.joints.clear();
    let s = evaluate(mesh, &plan, &bundle.report, &settings);
    assert_eq!((s.assembly.groups, s.assembly.connectivity), (6, 0.0));
    // A chain through all six connects everything.
    plan.joints = (1..6).map(|i| joint(i, i + 1)).collect();
    let s = evaluate(mesh, &plan, &bundle.report, &settings);
    assert_eq!(s.assembly.connectivity, 1.0);
    assert!(s.total > 0.8, "{s:?}");
}

#[test]
fn parts_away_from_the_model_reproduce_nothing() {
    let c = box_conversion();
    let bundle = c.bundle().expect("bundle");
    let mut plan = bundle.plan.clone();
    for part in &mut plan.parts {
        part.transform[0][3] += 1000.0;
    }
    let mesh = c.mesh.as_ref().expect("mesh");
    let s = evaluate(mesh, &plan, &bundle.report, &ScoreSettings::default());
    assert_eq!(s.shape.surface_covered, 0.0);
    assert_eq!(s.shape.volume_inside, 0.0);
    assert_eq!(s.total, 0.0);
}

#[test]
fn overlapping_parts_interfere() {
    let c = box_conversion();
    let bundle = c.bundle().expect("bundle");
    let mut plan = bundle.plan.clone();
    // The same parts twice: every volume sample is inside another part.
    let copies: Vec<_> = plan
        .parts
        .iter()
        .map(|p| {
            let mut q = p.clone();
            q.id += 100;
            q
        })
        .collect();
    plan.parts.extend(copies);
    let mesh = c.mesh.as_ref().expect("mesh");
    let s = evaluate(mesh, &plan, &bundle.report, &ScoreSettings::default());
    assert!(s.assembly.interference > 0.99, "{s:?}");
}

#[test]
fn ray_parity_knows_the_inside_of_a_hollow_box() {
    let (v, t) = indexed(&samples::closed_box(100.0, 80.0, 60.0, 3.0));
    let inside = crate::assembly::Inside::new(&v, &t);
    // In a wall, in the cavity, outside.
    assert!(inside.contains(DVec3::new(1.3, 40.1, 30.2)));
    assert!(inside.contains(DVec3::new(50.3, 40.1, 58.7)));
    assert!(!inside.contains(DVec3::new(50.3, 40.1, 30.2)));
    assert!(!inside.contains(DVec3::new(-5.0, 40.1, 30.2)));
    assert!(!inside.contains(DVec3::new(50.3, 40.1, 90.0)));
}

#[test]
fn stratified_picks_follow_the_weights() {
    let mut rng = SplitMix64::new(7);
    let picks = sample::stratified(&[1.0, 0.0, 3.0], 400, &mut rng);
    let count = |k| picks.iter().filter(|&&i| i == k).count();
    assert_eq!(count(1), 0);
    assert!((count(0) as i64 - 100).abs() <= 1);
    assert!((count(2) as i64 - 300).abs() <= 1);
    assert!(sample::stratified(&[0.0], 10, &mut rng).is_empty());
}
