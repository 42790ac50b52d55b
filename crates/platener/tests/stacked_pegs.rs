//! Issue 15, stacked layers joined by pegs: a neck too narrow for a shaft (the teapot's lid
//! knob, 5.7 mm across) gets a peg, a short shaft keeping only `PEG_MIN_WALL` of wall, so the
//! knob is held by a shaft instead of glue and `verify` finds the model's groups. Issue 31:
//! where even a peg finds no room (the teapot's spout foot), a boss on both layers holds one.
//!
//! Tolerances: the 1 µm grid of the booleans (areas under [`GRID_AREA`] mm² are rounding).

use std::path::PathBuf;

use platener::convert;
use platener::method::MethodKind;
use platener::plan::{MarkKind, MarkSide};
use platener::stacked::{PEG_MIN_WALL, Stack};
use platener::verify::verify;
use platener::{Cancel, Settings, Source, State};
use platener_fixtures::samples;
use platener_geom::polygon::total_area;
use platener_geom::{Polygon, boolean, offset};

/// Areas under this (mm²) are grid rounding.
const GRID_AREA: f64 = 1e-4;

fn corpus() -> Option<PathBuf> {
    samples::shared_corpus().map_err(|m| eprintln!("{m}")).ok()
}

fn stacked(path: PathBuf) -> State {
    let mut s = Settings::default();
    s.cut.nest_tries = 1;
    s.cut.fine_rotations = false;
    convert(MethodKind::Stacked, Source::File(path), s, &Cancel::default()).expect("converts")
}

fn stack(c: &State) -> &Stack {
    c.stacked.as_ref().expect("stack")
}

/// The slot rectangle of shaft `s` in band `b` (as the stack cuts it).
fn slot(st: &Stack, s: &platener::stacked::Shaft, b: &platener::stacked::Band) -> Polygon {
    let (d, n) = (s.direction, platener::glam::DVec2::new(s.direction.y, -s.direction.x));
    let half = st.shaft_thickness / 2.0;
    let (a, e) = (s.start + d * b.from, s.start + d * b.to);
    let mut p = Polygon::new(vec![a - n * half, e - n * half, e + n * half, a + n * half]);
    p.normalize_orientation();
    p
}

#[test]
fn the_teapots_knob_neck_gets_a_peg_and_verify_passes() {
    let Some(dir) = corpus() else { return };
    let c = stacked(dir.join("organic/utah_teapot.stl"));
    let st = stack(&c);
    let plan = &c.export.as_ref().expect("exported").plan;
    let v = verify(plan, c.mesh.as_deref());
    assert!(v.passed(), "{:?}", v.failures);
    // The spout (a separate solid of the model) is held too: one group, no glue.
    assert_eq!(v.model_solids, Some(2));
    assert_eq!(v.groups, 1, "{:?}", v.group_parts);
    assert!(plan.glued.is_empty(), "{:?}", plan.glued);
    assert_eq!(plan.glue_note(), "glue-free");
    let bundle = c.export.as_deref().expect("exported");
    let score = platener::score::score(c.mesh.as_deref().expect("mesh"), bundle, None);
    assert_eq!(score.assembly.glued_parts, 0);
    assert_eq!(score.assembly.interference, 0.0);
    // The spout's foot (layer 5) overlaps the body's layer 4 by 21.5 mm², a crescent no
    // peg fits in: both got a boss, and a peg runs through it.
    assert_eq!(st.bosses.len(), 1, "{:?}", st.bosses);
    let boss = &st.bosses[0];
    assert_eq!(boss.layer, 3);
    assert!((boss.overlap - 21.5).abs() < 0.1, "{}", boss.overlap);
    let side = st.shaft_thickness + 2.0 * PEG_MIN_WALL + 0.1;
    assert!((boss.square.area() - side * side).abs() < 1e-6);
    // It adds a quarter of a square at most, and both islands now hold all of it.
    assert!(boss.added > 0.0 && boss.added < 0.3 * side * side, "{}", boss.added);
    for (k, i) in [(boss.layer, boss.lower), (boss.layer + 1, boss.upper)] {
        let island = &st.layers[k].islands[i].outline;
        let out = boolean::difference(std::slice::from_ref(&boss.square), std::slice::from_ref(island)).expect("grid");
        assert!(total_area(&out) < GRID_AREA, "layer {}: {}", k + 1, total_area(&out));
    }
    // The peg: a phase 3 shaft through both islands, its slots inside the square less a wall.
    let peg = st
        .shafts
        .iter()
        .find(|s| {
            s.bands
                .windows(2)
                .any(|w| (w[0].layer, w[0].island, w[1].island) == (boss.layer, boss.lower, boss.upper))
        })
        .expect("a peg through the boss");
    assert_eq!(peg.phase, 3);
    let inner = offset::offset(std::slice::from_ref(&boss.square), -(PEG_MIN_WALL - 0.01)).expect("grid");
    for b in peg
        .bands
        .iter()
        .filter(|b| b.layer == boss.layer || b.layer == boss.layer + 1)
    {
        let out = boolean::difference(std::slice::from_ref(&slot(st, peg, b)), &inner).expect("grid");
        assert!(
            total_area(&out) < GRID_AREA,
            "layer {}: {}",
            b.layer + 1,
            total_area(&out)
        );
    }
    // The shaft through the lid (layer 8) is extended with a peg's wall through the neck
    // (layer 9, bottom at 24.61 mm) into the knob (layer 10): its top ends there.
    let peg = st
        .shafts
        .iter()
        .find(|s| s.bands.iter().any(|b| b.layer == 8))
        .expect("a shaft through the neck");
    let top = peg.bands.last().expect("bands");
    assert_eq!(top.layer, 9);
    assert!((st.layer_frame(8).origin.z - 24.61).abs() < 0.01);
    // Across, its slots in the neck and the knob lie in their islands with a wall of
    // PEG_MIN_WALL kept, at least an island's minimum width long.
    for b in peg.bands.iter().filter(|b| b.layer >= 8) {
        assert!(b.to - b.from >= 1.5 - 1e-9, "{b:?}");
        let island = &st.layers[b.layer].islands[b.island];
        let inner = offset::offset(std::slice::from_ref(&island.outline), -(PEG_MIN_WALL - 0.01)).expect("grid");
        let rect = slot(st, peg, b);
        let out = boolean::difference(std::slice::from_ref(&rect), &inner).expect("grid");
        assert!(
            total_area(&out) < GRID_AREA,
            "layer {}: {}",
            b.layer + 1,
            total_area(&out)
        );
        // The layer keeps its wall: the slot is a hole, not a notch.
        assert_eq!(
            island.polygon.holes.len(),
            island.outline.holes.len() + 1,
            "layer {}",
            b.layer + 1
        );
    }
    // The neck's slot lies in the neck (an island under 40 mm²).
    let neck = peg.bands.iter().find(|b| b.layer == 8).expect("neck band");
    assert!(st.layers[8].islands[neck.island].outline.area() < 40.0);
}

#[test]
fn the_brackets_5_mm_strip_takes_a_3_mm_peg() {
    let Some(dir) = corpus() else { return };
    let c = stacked(dir.join("plates/acrylic_case_corner_bracket_5mm.stl"));
    let st = stack(&c);
    let plan = &c.export.as_ref().expect("exported").plan;
    // Layer 4 is the strip x −9.5..−4.5, y −7..7 on layer 3: minus 1 mm walls, 3 × 12 mm.
    let strip = &st.layers[3].islands[0].outline;
    let (lo, hi) = strip.bounds();
    assert!(
        (hi.x - lo.x - 5.0).abs() < 1e-6 && (hi.y - lo.y - 14.0).abs() < 1e-6,
        "{lo} {hi}"
    );
    // Two pegs: this one, and one in the boss between layers 1 and 2.
    assert_eq!(st.shafts.len(), 2);
    assert_eq!(st.bosses.len(), 1);
    assert_eq!(st.bosses[0].layer, 0);
    let peg = st
        .shafts
        .iter()
        .find(|s| s.bands.iter().map(|b| b.layer).eq([2, 3]))
        .expect("the strip's peg");
    assert_eq!(peg.phase, 3);
    for b in &peg.bands {
        let rect = slot(st, peg, b);
        let (a, e) = rect.bounds();
        // Across: the strip's middle, 1 mm from both long sides; along: 12 mm less the slack.
        assert!((a.x + 8.5).abs() < 0.02 && (e.x + 5.5).abs() < 0.02, "{a} {e}");
        assert!(e.y - a.y > 11.9 && a.y > -6.0 - 1e-6 && e.y < 6.0 + 1e-6, "{a} {e}");
        let island = &st.layers[b.layer].islands[b.island];
        assert_eq!(
            island.polygon.holes.len(),
            island.outline.holes.len() + 1,
            "a hole, walls kept"
        );
    }
    // Layers 3 and 4 are one group now, layers 1 and 2 another (a boss holds their peg);
    // between layers 2 and 3 nothing fits, so they are glued.
    assert_eq!(plan.glued_groups(), vec![vec![1, 2, 5], vec![3, 4, 6]]);
    let glued: Vec<[u32; 2]> = plan.glued.iter().map(|g| g.parts).collect();
    assert_eq!(glued, vec![[2, 3]]);
    // What the CLI and the page say of it (issue 31).
    assert_eq!(plan.glued_parts(), vec![2, 3]);
    assert_eq!(plan.glue_note(), "needs glue: 2 parts in 2 groups");
    // Both faces glue joins carry the outline of the area they share as cut (less the slots):
    // the lower layer on its upper face (down on the sheet), the upper layer on its lower face.
    let island = |id: u32| {
        st.layers
            .iter()
            .flat_map(|l| &l.islands)
            .find(|i| i.part == id)
            .map(|i| i.polygon.clone())
            .expect("an island")
    };
    let shared = total_area(&boolean::intersection(&[island(2)], &[island(3)]).expect("grid"));
    assert!(shared > 0.5 * plan.glued[0].area && shared <= plan.glued[0].area + 1e-6);
    for (id, side) in [(2, MarkSide::Bottom), (3, MarkSide::Top)] {
        let part = plan.parts.iter().find(|p| p.id == id).expect("the part");
        let signed: f64 = part
            .marks
            .iter()
            .filter(|m| m.kind == MarkKind::Score && m.side == Some(side))
            .map(|m| platener_geom::polygon::signed_area(&m.path))
            .sum();
        assert!(
            (signed.abs() - shared).abs() < 0.01 * shared,
            "part {id}: {signed} against {shared}"
        );
    }
    // The score's assembly term keeps 4 of the 6 parts' worth (docs/score.md).
    let bundle = c.export.as_deref().expect("exported");
    let score = platener::score::score(c.mesh.as_deref().expect("mesh"), bundle, None);
    assert_eq!(score.assembly.glued_parts, 2);
    let expect = score.assembly.connectivity * (1.0 - score.assembly.interference / 0.05).max(0.0) * (4.0 / 6.0);
    assert!((score.assembly.value - expect).abs() < 1e-12, "{:?}", score.assembly);
}
