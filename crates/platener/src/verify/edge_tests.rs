//! The check of edges that fit where they do not belong, on plans the pipeline makes: the
//! patterns it reads, the pairs it counts, and the plate method's joints that each fit only
//! their own partner (issue 35).

use proptest::prelude::*;

use super::edge_pattern::joint_edges;
use super::*;
use crate::convert::convert;
use crate::method::MethodKind;
use crate::pipeline::{Cancel, Source};
use crate::plan::{JointKind, Material};
use crate::settings::Settings;
use platener_fixtures::samples;

/// The plate method's plan of `model` in 3 mm `material` (one nesting try: quick), checked
/// against the model.
fn verified(model: Vec<crate::read::Triangle>, material: Material) -> (Plan, Verification) {
    let mut s = Settings {
        thicknesses: vec![3.0],
        ..Settings::default()
    };
    s.cut.material = material;
    s.cut.nest_tries = 1;
    s.cut.fine_rotations = false;
    let c = convert(MethodKind::Plate, Source::triangles("m", model), s, &Cancel::default()).expect("converts");
    let plan = c.bundle().expect("plan").plan.clone();
    let v = verify(&plan, c.mesh.as_deref());
    (plan, v)
}

/// Each finger joint's two parts as slabs, by label.
fn slabs_of(plan: &Plan, parts: [u32; 2]) -> [platener_geom::slab::Slab; 2] {
    parts.map(|id| {
        let part = plan.parts.iter().find(|p| p.id == id).expect("a part of the plan");
        part.pieces().expect("flat").remove(0)
    })
}

/// The plan holds together as one piece without interference, every edge of its finger joints
/// fits only its partner, and each finger joint's two edges are exact complements along the
/// joint (no gap, no overlap beyond 0.01 mm).
fn assert_foolproof(plan: &Plan, v: &Verification) {
    assert!(v.passed(), "{:?}", v.problems);
    assert_eq!(v.groups, 1);
    assert!(v.interference_share < 0.001, "{}", v.interference_share);
    let m = &v.mismatched_edges;
    assert_eq!(m.accepting_pairs, 0, "{:?}", m.pairs);
    assert_eq!(m.joints_read, plan.joints.len(), "every joint read");
    for j in plan.joints.iter().filter(|j| j.kind == JointKind::Finger) {
        let [a, b] = slabs_of(plan, j.parts);
        let e = joint_edges(&a, &b).expect("a finger joint reads");
        let mut all: Vec<(f64, f64)> = e.sides.iter().flat_map(|s| s.tabs.iter().copied()).collect();
        all.sort_by(|x, y| x.0.total_cmp(&y.0));
        let mut reached = 0.0;
        for (s0, s1) in all {
            assert!(
                (s0 - reached).abs() < 0.01,
                "joint {}: {reached} then {s0}: {e:?}",
                j.label
            );
            reached = s1;
        }
        assert!((reached - e.sides[0].length).abs() < 0.01, "joint {}: {e:?}", j.label);
    }
}

#[test]
fn a_box_joint_reads_as_two_complementary_rows_of_fingers() {
    let (plan, _) = verified(samples::closed_box(100.0, 80.0, 60.0, 3.0), Material::Wood);
    // The 100 mm edge of the bottom: 11 segments of 100/11 mm, its own at both ends.
    let j = plan.joints[0];
    let e = joint_edges(&slabs_of(&plan, j.parts)[0], &slabs_of(&plan, j.parts)[1]).expect("reads");
    assert!((e.sides[0].length - 100.0).abs() < 1e-6, "{e:?}");
    let step = 100.0 / 11.0;
    assert_eq!(e.sides[0].tabs.len(), 6);
    assert_eq!(e.sides[1].tabs.len(), 5);
    for (k, (s0, s1)) in e.sides[0].tabs.iter().enumerate() {
        assert!(
            (s0 - 2.0 * k as f64 * step).abs() < 1e-3 && (s1 - s0 - step).abs() < 1e-3,
            "{e:?}"
        );
    }
    assert!(e.sides[0].matches(&e.sides[0].reversed()), "a symmetric row");
    assert!(!e.sides[0].matches(&e.sides[1]));
}

#[test]
fn boxes_fit_only_the_right_way() {
    for model in [
        samples::closed_box(100.0, 80.0, 60.0, 3.0),
        samples::open_box(120.0, 80.0, 40.0, 3.0),
    ] {
        let (plan, v) = verified(model, Material::Wood);
        assert_foolproof(&plan, &v);
        // Their walls are twins: a wall in its twin's place builds the same box.
        assert!(v.mismatched_edges.interchangeable_pairs > 0);
        assert_twins(&plan, &v.mismatched_edges.interchangeable_parts);
    }
    // The closed box: base and lid, the long walls, the short walls.
    let (plan, v) = verified(samples::closed_box(100.0, 80.0, 60.0, 3.0), Material::Wood);
    let size = |id: u32| {
        let p = plan.parts.iter().find(|p| p.id == id).expect("a part");
        let (lo, hi) = platener_geom::polygon::bounds_of(p.outline.iter().copied());
        ((hi - lo).max_element().round(), (hi - lo).min_element().round())
    };
    let groups = &v.mismatched_edges.interchangeable_parts;
    let sizes: Vec<Vec<(f64, f64)>> = groups.iter().map(|g| g.iter().map(|&id| size(id)).collect()).collect();
    assert_eq!(groups.len(), 3, "{groups:?} {sizes:?}");
    assert!(groups.iter().all(|g| g.len() == 2), "{groups:?}");
}

/// Each group of twins holds parts of one thickness and the same area (within 1 %), and no
/// part is in two groups.
fn assert_twins(plan: &Plan, groups: &[Vec<u32>]) {
    let mut seen = std::collections::BTreeSet::new();
    for g in groups {
        assert!(g.len() >= 2 && g.windows(2).all(|w| w[0] < w[1]), "{groups:?}");
        let slabs: Vec<_> = g
            .iter()
            .map(|id| {
                plan.parts
                    .iter()
                    .find(|p| p.id == *id)
                    .expect("a part")
                    .pieces()
                    .expect("flat")[0]
                    .clone()
            })
            .collect();
        for s in &slabs {
            assert!((s.thickness - slabs[0].thickness).abs() < 1e-9);
            let (a, b) = (s.polygon.area(), slabs[0].polygon.area());
            assert!((a - b).abs() <= 0.01 * b, "{g:?}: {a} vs {b}");
        }
        assert!(g.iter().all(|id| seen.insert(*id)), "{groups:?}");
    }
}

/// A cube's twelve edges are all alike: before keys, 19 pairs of edges of different joints
/// fitted each other (a wall in the place of one that is no twin of it).
#[test]
fn a_cube_fits_only_the_right_way_in_every_style() {
    for material in [Material::Wood, Material::Cardboard] {
        let (plan, v) = verified(samples::closed_box(60.0, 60.0, 60.0, 3.0), material);
        assert_foolproof(&plan, &v);
    }
    let mut s = Settings::default();
    s.joints.style = Some(crate::settings::JointStyle::Dovetail);
    s.cut.nest_tries = 1;
    let model = samples::closed_box(60.0, 60.0, 60.0, 3.0);
    let c = convert(MethodKind::Plate, Source::triangles("m", model), s, &Cancel::default()).expect("converts");
    let v = verify(&c.bundle().expect("plan").plan, c.mesh.as_deref());
    assert!(v.passed(), "{:?}", v.problems);
    assert_eq!(v.mismatched_edges.accepting_pairs, 0, "{:?}", v.mismatched_edges.pairs);
}

/// Two sides and three identical shelves between them: every fit is between twins, so
/// nothing changes and the shelves stay interchangeable.
#[test]
fn identical_shelves_stay_identical() {
    let (w, d, t) = (80.0, 60.0, 3.0);
    let zs = [0.0, 20.0, 20.0 + t, 60.0, 60.0 + t, 100.0, 100.0 + t, 120.0];
    let model = samples::voxels(&[0.0, t, w - t, w], &[0.0, d], &zs, |i, _, k| i != 1 || k % 2 == 1);
    let (plan, v) = verified(model, Material::Wood);
    assert_foolproof(&plan, &v);
    assert!(v.mismatched_edges.interchangeable_pairs > 0);
    let mut shelves: Vec<f64> = plan
        .parts
        .iter()
        .map(|p| p.pieces().expect("flat")[0].polygon.area())
        .filter(|a| *a < 0.9 * 120.0 * d)
        .collect();
    shelves.sort_by(f64::total_cmp);
    assert_eq!(shelves.len(), 3, "{shelves:?}");
    assert!(shelves[2] - shelves[0] < 0.01, "{shelves:?}");
    let groups = &v.mismatched_edges.interchangeable_parts;
    assert_twins(&plan, groups);
    assert!(
        groups.iter().any(|g| g.len() >= 3),
        "the three shelves are one group: {groups:?}"
    );
}

/// Holes in two neighbouring walls of a box make them no twins of the walls opposite: the
/// fits that were harmless (a wall in the place of its twin) are counted now.
#[test]
fn walls_that_are_no_twins_are_counted() {
    let (mut plan, v) = verified(samples::closed_box(100.0, 80.0, 60.0, 3.0), Material::Wood);
    assert_eq!(v.mismatched_edges.accepting_pairs, 0);
    // Parts 3 to 6 are the walls; 3 and 5 meet.
    assert!(plan.joints.iter().any(|j| j.parts == [3, 5]), "{:?}", plan.joints);
    for id in [3, 5] {
        let wall = plan.parts.iter_mut().find(|p| p.id == id).expect("a wall");
        let (lo, hi) = platener_geom::polygon::bounds_of(wall.outline.iter().copied());
        let c = (lo + hi) / 2.0;
        let hole = platener_geom::polygon::rect(c.x - 5.0, c.y - 5.0, c.x + 5.0, c.y + 5.0);
        wall.holes.push(hole.into_iter().rev().collect());
    }
    let m = mismatched_edges(&plan);
    assert!(m.accepting_pairs > 0, "{m:?}");
    assert!(
        m.pairs.iter().all(|p| p.parts.iter().all(|id| (3..=6).contains(id))),
        "{m:?}"
    );
    assert!(m.interchangeable_pairs < v.mismatched_edges.interchangeable_pairs);
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 8, ..ProptestConfig::default() })]

    /// Closed boxes of any proportions, cubes included: joints that fit only their partner,
    /// an assembly that holds as one piece.
    #[test]
    fn random_closed_boxes_fit_only_the_right_way(
        w in 40.0..140.0f64,
        d in 40.0..140.0f64,
        h in 30.0..100.0f64,
        cube in proptest::bool::ANY,
    ) {
        let (d, h) = if cube { (w, w) } else { (d, h) };
        let (plan, v) = verified(samples::closed_box(w, d, h, 3.0), Material::Wood);
        assert_foolproof(&plan, &v);
    }
}
