use glam::DVec3;

use super::*;
use crate::convert::convert;
use crate::method::MethodKind;
use crate::pipeline::State;
use crate::plan::{JointKind, PlanJoint};
use crate::read::Triangle;
use crate::{Cancel, Settings, Source};
use platener_fixtures::samples;

/// The score of a converted state.
fn score_of(c: &State) -> Score {
    score(
        c.mesh.as_ref().expect("mesh"),
        c.bundle().expect("bundle"),
        c.plates.as_deref(),
    )
}

/// The score of another plan for the state's model.
fn score_plan(c: &State, plan: &Plan) -> Score {
    let mesh = c.mesh.as_ref().expect("mesh");
    let analysis = analyse(plan, Some(mesh));
    evaluate(mesh, plan, &c.bundle().expect("bundle").report, &analysis)
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
    // Six plates (with their joints) are the whole box: the surface is covered, every joint
    // is at the model's 90°, no part is a sliver, nothing overlaps.
    assert!(s.surface.value > 0.98, "{s:?}");
    assert_eq!(s.surface.cover_distance, 2.0);
    assert!(s.assembly.interference < 0.001, "{s:?}");
    assert_eq!(s.quality.joints_judged, 12, "{s:?}");
    let worst = s.quality.worst_joint.as_ref().expect("judged");
    assert!(
        (worst.plan - 90.0).abs() < 1e-6 && (worst.model - 90.0).abs() < 1e-6,
        "{worst:?}"
    );
    assert!(s.quality.fidelity > 0.999_999, "{s:?}");
    assert_eq!(s.quality.slender, 1.0);
    assert!(s.quality.slivers.is_empty());
    // Where plates were detected is within reach of a plate, so the measured share is no lower.
    let detected = s.surface.plates_surface_share.expect("plate method");
    assert!(detected <= s.surface.value + 0.01, "{s:?}");
    // A hollow box is one solid (its cavity is no second one), and the joints hold it.
    assert_eq!((s.assembly.groups, s.assembly.solids), (1, 1));
    assert_eq!(s.assembly.connectivity, 1.0);
    assert_eq!(s.effort.parts, 6);
    assert!(s.effort.sheets >= 1);
    assert!(s.effort.cut_length > 0.0);
    let expected = s.surface.value
        * (SURFACE_WEIGHT
            + ASSEMBLY_WEIGHT * s.assembly.value
            + QUALITY_WEIGHT * s.quality.value
            + EFFORT_WEIGHT * s.effort.value);
    assert!((s.total - expected).abs() < 1e-12);
    assert!((0.0..=1.0).contains(&s.total));
}

#[test]
fn the_same_conversion_always_gets_the_same_score() {
    let c = box_conversion();
    assert_eq!(score_of(&c), score_of(&c));
}

#[test]
fn joints_that_meet_connect_the_assembly() {
    let c = box_conversion();
    let mut plan = c.bundle().expect("bundle").plan.clone();
    let real = plan.joints.clone();
    let meets = |a: u32, b: u32| real.iter().any(|j| j.parts == [a, b] || j.parts == [b, a]);
    let joint = |a, b| PlanJoint {
        parts: [a, b],
        kind: JointKind::Finger,
        angle: 90.0,
        label: 100 * a + b,
    };
    // The box's real joints, thinned to a chain through part 1's neighbours.
    let neighbours: Vec<u32> = (2..=6).filter(|&b| meets(1, b)).collect();
    assert_eq!(neighbours.len(), 4, "part 1 meets four walls");
    plan.joints = neighbours[..2].iter().map(|&b| joint(1, b)).collect();
    let s = score_plan(&c, &plan);
    // Parts 1 and two neighbours, and three parts alone: two of the five connections.
    assert_eq!((s.assembly.groups, s.assembly.solids), (4, 1));
    assert!((s.assembly.connectivity - 2.0 / 5.0).abs() < 1e-12, "{s:?}");
    // No joints: not connected at all.
    plan.joints.clear();
    let s = score_plan(&c, &plan);
    assert_eq!((s.assembly.groups, s.assembly.connectivity), (6, 0.0));
    // A joint between parts that do not meet (opposite walls) holds nothing.
    let opposite = (2..=6).find(|&b| !meets(1, b)).expect("the wall opposite part 1");
    plan.joints = vec![joint(1, opposite)];
    let s = score_plan(&c, &plan);
    assert_eq!(s.assembly.groups, 6, "{s:?}");
    assert_eq!(s.assembly.joints_not_meeting, vec![100 + opposite]);
}

#[test]
fn parts_away_from_the_model_reproduce_nothing() {
    let c = box_conversion();
    let mut plan = c.bundle().expect("bundle").plan.clone();
    for part in &mut plan.parts {
        part.transform[0][3] += 1000.0;
    }
    let s = score_plan(&c, &plan);
    assert_eq!(s.surface.value, 0.0);
    assert_eq!(s.total, 0.0);
}

#[test]
fn overlapping_parts_interfere() {
    let c = box_conversion();
    let mut plan = c.bundle().expect("bundle").plan.clone();
    // The same parts twice: all their volume is claimed twice.
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
    let s = score_plan(&c, &plan);
    assert!(s.assembly.interference > 0.45, "{s:?}");
    assert_eq!(s.assembly.value, 0.0, "{s:?}");
}

/// Part 1 turned by `degrees` about its own centre line along its local x axis.
fn tilt(plan: &mut Plan, id: u32, degrees: f64) {
    let part = plan.parts.iter_mut().find(|p| p.id == id).expect("part");
    let m = part.transform;
    let column = |j: usize| DVec3::new(m[0][j], m[1][j], m[2][j]);
    let (u, v, n, origin) = (column(0), column(1), column(2), column(3));
    let (lo, hi) = platener_geom::polygon::bounds_of(part.outline.iter().copied());
    let centre = origin + u * (lo.x + hi.x) / 2.0 + v * (lo.y + hi.y) / 2.0;
    let turn = glam::DQuat::from_axis_angle(u, degrees.to_radians());
    let (v2, n2) = (turn * v, turn * n);
    let origin2 = centre + turn * (origin - centre);
    for (j, c) in [u, v2, n2, origin2].into_iter().enumerate() {
        for row in 0..3 {
            part.transform[row][j] = c[row];
        }
    }
}

#[test]
fn a_joint_at_another_angle_than_the_model_lowers_the_quality() {
    let c = box_conversion();
    let mut plan = c.bundle().expect("bundle").plan.clone();
    tilt(&mut plan, 1, 5.0);
    let s = score_plan(&c, &plan);
    let worst = s.quality.worst_joint.as_ref().expect("judged");
    // The tilted plate still stands for its face (model 90°), but two of its joints are 5° off.
    assert!((worst.model - 90.0).abs() < 1e-6, "{worst:?}");
    assert!((worst.plan - 85.0).abs() < 1e-6, "{worst:?}");
    assert!(s.quality.fidelity < 0.95, "{s:?}");
    assert!(s.total < score_of(&c).total, "{s:?}");
}

#[test]
fn slivers_lower_the_quality() {
    let c = box_conversion();
    let mut plan = c.bundle().expect("bundle").plan.clone();
    // Part 1 cut down to a 2 mm strip along its longest side.
    let part = &mut plan.parts[0];
    let (lo, hi) = platener_geom::polygon::bounds_of(part.outline.iter().copied());
    part.outline = platener_geom::polygon::rect(lo.x, lo.y, hi.x, lo.y + 2.0);
    part.holes.clear();
    let s = score_plan(&c, &plan);
    assert_eq!(s.quality.slivers, vec![1]);
    assert!(s.quality.slender < 1.0, "{s:?}");
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

/// The box's sharp edges are its 12 outer and 12 inner corners' edges (a closed box of
/// 100 × 80 × 60 with 3 mm walls: 4·(100 + 80 + 60) outside, 4·(94 + 74 + 54) inside), and its
/// six plates keep every one. Moving one wall a sheet away from its place loses its edges:
/// `details` drops while nothing else about the parts changes.
#[test]
fn the_box_keeps_its_sharp_edges_and_a_moved_wall_loses_them() {
    let c = box_conversion();
    let s = score_of(&c);
    let expected = 4.0 * (100.0 + 80.0 + 60.0) + 4.0 * (94.0 + 74.0 + 54.0);
    assert!(
        (s.quality.details.sharp_edges - expected).abs() < 1e-6,
        "{:?}",
        s.quality.details
    );
    assert!(s.quality.details.kept > 0.999, "{:?}", s.quality.details);
    let mut plan = c.bundle().expect("bundle").plan.clone();
    let part = plan.parts.iter_mut().max_by(|a, b| a.id.cmp(&b.id)).expect("a part");
    let n = DVec3::new(part.transform[0][2], part.transform[1][2], part.transform[2][2]);
    for (row, d) in part.transform.iter_mut().zip((n * 10.0 * part.thickness).to_array()) {
        row[3] += d;
    }
    let moved = score_plan(&c, &plan);
    assert!(moved.quality.details.kept < 0.95, "{:?}", moved.quality.details);
}
