//! The assembly order checked on whole plans made by the pipeline from generated models.
//!
//! Every step's direction is checked twice: by the blocking test the order is made with, and
//! independently by moving the new part in from 100 mm away along its direction in 50 steps
//! (2 mm apart, less than any part's thickness, so no part can jump over another) and
//! counting its interior sample points inside the parts placed before it: at most
//! [`OVERLAP_MM3`] of shared volume at any position.

use std::collections::BTreeMap;

use glam::{DVec2, DVec3};
use platener_fixtures::samples;
use proptest::prelude::*;

use super::order;
use crate::assembly::sweep::blocks;
use crate::assembly::{Solid, sample};
use crate::convert::convert;
use crate::method::MethodKind;
use crate::plan::{Method, PartKind, Plan};
use crate::{Cancel, Settings, Source};
use platener_geom::Frame;

/// Shared volume (mm³) a part may show moving in: two of its 1 mm sample cells.
const OVERLAP_MM3: f64 = 2.0;

/// The plan `method` makes of `triangles` from `t` mm sheets (one nesting try: quick).
fn plan_of(triangles: Vec<platener_geom::Triangle>, method: MethodKind, t: f64) -> Plan {
    plan_from(Source::triangles("sample", triangles), method, t)
}

/// The plan `method` makes of `source` from `t` mm sheets (one nesting try: quick).
fn plan_from(source: Source, method: MethodKind, t: f64) -> Plan {
    let mut s = Settings {
        thicknesses: vec![t],
        ..Settings::default()
    };
    s.cut.nest_tries = 1;
    s.cut.fine_rotations = false;
    let state = convert(method, source, s, &Cancel::default()).expect("converts");
    let plan = state.export.as_ref().expect("exported").plan.clone();
    assert_eq!(
        plan.assembly,
        order(&plan),
        "plan.json's order is the order of the plan"
    );
    plan
}

fn solids(plan: &Plan) -> BTreeMap<u32, Solid> {
    plan.parts.iter().map(|p| (p.id, Solid::from_part(p))).collect()
}

/// The assembly's part ids in order.
fn sequence(plan: &Plan) -> Vec<u32> {
    plan.assembly.iter().flat_map(|s| s.parts.iter().copied()).collect()
}

/// Every part exactly once, one per step, no step forced, every direction a unit vector
/// that both the blocking test and the independent motion find free.
fn assert_buildable(plan: &Plan) {
    let mut ids = sequence(plan);
    assert_eq!(ids.len(), plan.assembly.len(), "one part a step");
    ids.sort_unstable();
    let all: Vec<u32> = plan.parts.iter().map(|p| p.id).collect();
    assert_eq!(ids, all, "every part once");
    let solids = solids(plan);
    for (k, step) in plan.assembly.iter().enumerate() {
        assert!(!step.forced, "step {k} forced: {:?}", plan.assembly);
        let d = DVec3::from_array(step.direction);
        assert!((d.length() - 1.0).abs() < 1e-5, "{d}");
        let part = &solids[&step.parts[0]];
        let placed: Vec<&Solid> = plan.assembly[..k].iter().map(|s| &solids[&s.parts[0]]).collect();
        for q in &placed {
            assert!(!blocks(part, -d, q), "part {} along {d} runs into {}", part.id, q.id);
        }
        let worst = worst_overlap_moving_in(part, d, &placed);
        assert!(
            worst <= OVERLAP_MM3,
            "part {} along {d} overlaps by {worst} mm³",
            part.id
        );
    }
}

/// The largest volume (mm³) `part` shares with `placed` on its way in along `d` from 100 mm
/// away, at 51 positions: its interior sample points (1 mm apart) inside a placed part.
fn worst_overlap_moving_in(part: &Solid, d: DVec3, placed: &[&Solid]) -> f64 {
    let (points, cell) = sample::cells(part, part.thickness / 3.0);
    (0..=50)
        .map(|i| {
            let offset = -d * 100.0 * (1.0 - f64::from(i) / 50.0);
            let inside = points
                .iter()
                .filter(|p| {
                    placed
                        .iter()
                        .any(|q| q.near_box(**p + offset, 0.0) && q.contains(**p + offset))
                })
                .count();
            inside as f64 * cell
        })
        .fold(0.0, f64::max)
}

/// The id of the plate lying flat (normal ±z) lowest (`top` false) or highest.
fn flat_plate(plan: &Plan, top: bool) -> u32 {
    let solids = solids(plan);
    let flat = solids.values().filter(|s| s.frame().n.z.abs() > 0.99);
    let z = |s: &&Solid| s.lo.z + s.hi.z;
    let pick = if top {
        flat.max_by(|a, b| z(a).total_cmp(&z(b)))
    } else {
        flat.min_by(|a, b| z(a).total_cmp(&z(b)))
    };
    pick.expect("a flat plate").id
}

#[test]
fn the_closed_box_goes_base_walls_lid() {
    let plan = plan_of(samples::closed_box(100.0, 80.0, 60.0, 3.0), MethodKind::Plate, 3.0);
    assert_eq!(plan.parts.len(), 6);
    assert_buildable(&plan);
    let ids = sequence(&plan);
    assert_eq!(ids[0], flat_plate(&plan, false), "the base first: {:?}", plan.assembly);
    assert_eq!(ids[5], flat_plate(&plan, true), "the lid last: {:?}", plan.assembly);
    assert_eq!(plan.assembly[5].direction, [0.0, 0.0, -1.0], "the lid is lowered on");
    // The lid closes its four joints with the walls; every joint is closed once.
    assert_eq!(plan.assembly[5].joints.len(), 4);
    let mut closed: Vec<usize> = plan.assembly.iter().flat_map(|s| s.joints.iter().copied()).collect();
    closed.sort_unstable();
    assert_eq!(closed, (0..plan.joints.len()).collect::<Vec<_>>());
}

#[test]
fn the_tray_goes_base_first() {
    let plan = plan_of(samples::open_box(120.0, 70.0, 40.0, 3.0), MethodKind::Plate, 3.0);
    assert_eq!(plan.parts.len(), 5);
    assert_buildable(&plan);
    assert_eq!(sequence(&plan)[0], flat_plate(&plan, false), "{:?}", plan.assembly);
}

#[test]
fn the_shelf_and_the_table_are_buildable() {
    let shelf = plan_of(samples::shelf(120.0, 100.0, 50.0, 60.0, 3.0), MethodKind::Plate, 3.0);
    assert_buildable(&shelf);
    let table = plan_of(samples::table(120.0, 60.0, 70.0, 10.0, 3.0), MethodKind::Plate, 3.0);
    assert_buildable(&table);
    // The top goes on last, lowered onto the legs.
    let last = table.assembly.last().expect("steps");
    assert_eq!(last.parts, [flat_plate(&table, true)], "{:?}", table.assembly);
    assert_eq!(last.direction, [0.0, 0.0, -1.0]);
}

#[test]
fn stacked_layers_go_bottom_to_top() {
    let plan = plan_of(
        samples::sphere(DVec3::new(0.0, 0.0, 30.0), 30.0, 24, 12),
        MethodKind::Stacked,
        3.0,
    );
    assert_eq!(plan.method, Method::Stacked);
    assert_buildable(&plan);
    let solids = solids(&plan);
    let kinds: BTreeMap<u32, PartKind> = plan.parts.iter().map(|p| (p.id, p.kind)).collect();
    let layers: Vec<&crate::plan::format::AssemblyStep> = plan
        .assembly
        .iter()
        .filter(|s| kinds[&s.parts[0]] == PartKind::Layer)
        .collect();
    let axis = solids[&layers[0].parts[0]].frame().n;
    let axis = if axis.z < 0.0 { -axis } else { axis };
    let heights: Vec<f64> = layers
        .iter()
        .map(|s| axis.dot(solids[&s.parts[0]].frame().origin))
        .collect();
    assert!(
        heights.windows(2).all(|w| w[1] >= w[0] - 1e-6),
        "layers bottom to top: {heights:?}"
    );
    for s in &layers[1..] {
        assert!(DVec3::from_array(s.direction).dot(axis) < -0.999, "lowered: {s:?}");
    }
}

/// The two checks are not blind: a wall across x lowered past a wall across y runs into the
/// fingers of their corner, the lid slid in sideways through a wall, and both checks see it.
#[test]
fn both_checks_see_fingers_in_the_way() {
    let plan = plan_of(samples::closed_box(100.0, 80.0, 60.0, 3.0), MethodKind::Plate, 3.0);
    let solids = solids(&plan);
    let wall = |axis: DVec3| {
        solids
            .values()
            .find(|s| s.frame().n.dot(axis).abs() > 0.99)
            .expect("a wall")
    };
    let (x_wall, y_wall) = (wall(DVec3::X), wall(DVec3::Y));
    let lid = &solids[&flat_plate(&plan, true)];
    for (mover, placed, d) in [(x_wall, y_wall, DVec3::NEG_Z), (lid, x_wall, DVec3::X)] {
        assert!(blocks(mover, -d, placed), "{} along {d}", mover.id);
        assert!(worst_overlap_moving_in(mover, d, &[placed]) > 10.0 * OVERLAP_MM3);
    }
}

/// The egg crate: the interlocked method's slices of a block stand their B slices up and
/// lower the A slices onto them, each free along its way.
#[test]
fn the_egg_crate_is_buildable() {
    let block = samples::cuboid(DVec3::ZERO, DVec3::new(90.0, 70.0, 50.0));
    let plan = plan_of(block, MethodKind::Interlocked, 3.0);
    assert!(plan.parts.len() >= 6, "{} slices", plan.parts.len());
    assert_buildable(&plan);
    let last = plan.assembly.last().expect("steps");
    assert!(
        last.direction[2] < -0.99,
        "the last slice is lowered on: {:?}",
        plan.assembly
    );
}

/// Real models by others (the shared corpus): the drawer-like parts tray and the photo frame
/// in two parts are built without forcing a part or passing one through another.
#[test]
fn the_corpus_tray_and_photo_frame_are_buildable() {
    let dir = match platener_fixtures::samples::shared_corpus() {
        Ok(dir) => dir,
        Err(message) => return eprintln!("{message}"),
    };
    for name in ["parts_tray_drawer_holder.stl", "photo_frame_5inch_two_parts.stl"] {
        let plan = plan_from(Source::File(dir.join("plates").join(name)), MethodKind::Plate, 3.0);
        assert!(plan.parts.len() >= 4, "{name}: {} parts", plan.parts.len());
        assert_buildable(&plan);
    }
}

/// A peg through a hole, with arms wider than the hole above and below the board, is locked
/// in every direction: the order still places both, the second forced.
#[test]
fn an_interlocked_pair_is_placed_forced() {
    let mut plan = plan_of(samples::table(120.0, 60.0, 70.0, 10.0, 3.0), MethodKind::Plate, 3.0);
    let rect = |x0: f64, y0: f64, x1: f64, y1: f64| {
        vec![
            DVec2::new(x0, y0),
            DVec2::new(x1, y0),
            DVec2::new(x1, y1),
            DVec2::new(x0, y1),
        ]
    };
    let mut board = plan.parts[0].clone();
    board.id = 1;
    board.outline = rect(0.0, 0.0, 40.0, 40.0);
    board.holes = vec![rect(15.0, 18.5, 25.0, 21.5).into_iter().rev().collect()];
    board.transform = Frame::on_plane(DVec3::ZERO, DVec3::Z).matrix();
    // Standing in the hole, normal +y (its u is −x): a bar 6 wide through the hole, arms 20
    // wide 2 below and 5 above the board.
    let mut peg = board.clone();
    peg.id = 2;
    peg.outline = [
        (-5.0, 0.0),
        (15.0, 0.0),
        (15.0, 2.0),
        (8.0, 2.0),
        (8.0, 13.0),
        (15.0, 13.0),
        (15.0, 15.0),
        (-5.0, 15.0),
        (-5.0, 13.0),
        (2.0, 13.0),
        (2.0, 2.0),
        (-5.0, 2.0),
    ]
    .map(|(x, y)| DVec2::new(x, y))
    .to_vec();
    peg.holes = Vec::new();
    peg.transform = Frame::on_plane(DVec3::new(25.0, 18.5, -5.0), DVec3::Y).matrix();
    plan.parts = vec![board, peg];
    plan.joints.truncate(1);
    plan.joints[0].parts = [1, 2];
    plan.glued.clear();
    let steps = order(&plan);
    let placed: Vec<(u32, bool)> = steps.iter().map(|s| (s.parts[0], s.forced)).collect();
    assert_eq!(placed, [(2, false), (1, true)], "{steps:?}");
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 6, .. ProptestConfig::default() })]
    /// Any closed box: every part once, the lid last, nothing forced, every step free.
    #[test]
    fn any_closed_box_is_buildable_lid_last(
        (w, d, h) in (40.0f64..150.0, 40.0f64..150.0, 40.0f64..150.0),
        t in prop::sample::select(vec![3.0, 4.0]),
    ) {
        let plan = plan_of(samples::closed_box(w, d, h, t), MethodKind::Plate, t);
        prop_assert_eq!(plan.parts.len(), 6);
        assert_buildable(&plan);
        prop_assert_eq!(*sequence(&plan).last().expect("steps"), flat_plate(&plan, true));
    }
}
