use std::sync::Arc;

use glam::{DMat3, DVec3};
use proptest::prelude::*;

use crate::inspect::run_foundation;
use crate::pipeline::{Cancel, Source};
use crate::read::Triangle;
use crate::settings::Settings;
use platener_fixtures::samples::{cuboid, open_box, voxels};

use platener_geom::grid::STEP;
use platener_geom::polygon::perimeter;

use super::Shapes;

fn shapes_of(triangles: Vec<Triangle>) -> Arc<Shapes> {
    let source = Source::triangles("test", triangles);
    let (state, _) = run_foundation(source, Settings::default(), &Cancel::default()).expect("converts");
    state.shapes.expect("shapes step ran")
}

fn sorted_areas(s: &Shapes) -> Vec<f64> {
    let mut a: Vec<f64> = s.shapes.iter().map(|s| s.area).collect();
    a.sort_by(f64::total_cmp);
    a
}

#[test]
fn cuboid_has_six_rectangles() {
    let s = shapes_of(cuboid(DVec3::ZERO, DVec3::new(10.0, 20.0, 30.0)));
    let areas = sorted_areas(&s);
    let want = [200.0, 200.0, 300.0, 300.0, 600.0, 600.0];
    assert_eq!(areas.len(), 6);
    for (a, w) in areas.iter().zip(want) {
        assert!((a - w).abs() < 1e-6, "{areas:?}");
    }
    for shape in &s.shapes {
        assert_eq!(shape.polygon.outer.len(), 4);
        assert!(shape.polygon.holes.is_empty());
        // Every outline corner maps back onto a corner of the box.
        for p in &shape.polygon.outer {
            let q = shape.frame.to_model_2d(*p);
            for (c, hi) in [(q.x, 10.0), (q.y, 20.0), (q.z, 30.0)] {
                assert!(c.abs() < 1e-6 || (c - hi).abs() < 1e-6, "{q}");
            }
        }
    }
}

#[test]
fn open_box_rim_is_a_ring_and_cells_merge() {
    let s = shapes_of(open_box(100.0, 60.0, 40.0, 3.0));
    // Outer faces: bottom 100×60, walls 100×40 and 60×40 twice; inner floor 94×54; inner
    // walls 94×37 and 54×37 twice; the rim 100×60 − 94×54 with one hole.
    let mut want = vec![
        6000.0, 5076.0, 4000.0, 4000.0, 2400.0, 2400.0, 3478.0, 3478.0, 1998.0, 1998.0, 924.0,
    ];
    want.sort_by(f64::total_cmp);
    let areas = sorted_areas(&s);
    assert_eq!(areas.len(), want.len(), "{areas:?}");
    for (a, w) in areas.iter().zip(&want) {
        assert!((a - w).abs() < 1e-6, "{areas:?}");
    }
    let rim = s.shapes.iter().find(|x| (x.area - 924.0).abs() < 1e-6).expect("rim");
    assert_eq!(rim.polygon.holes.len(), 1);
    assert_eq!(rim.polygon.outer.len(), 4, "grid vertices on straight runs removed");
    assert!((rim.frame.origin.z - 40.0).abs() < 1e-9 && rim.frame.n.z > 0.999);
}

#[test]
fn plate_with_hole_and_a_pillar_inside() {
    // 5×5 cells of 10 mm: a 3 mm plate with a 10 mm square hole in the middle.
    let xs: Vec<f64> = (0..=5).map(|i| i as f64 * 10.0).collect();
    let s = shapes_of(voxels(&xs, &xs, &[0.0, 3.0], |i, j, _| !(i == 2 && j == 2)));
    let top = s.shapes.iter().find(|x| x.frame.n.z > 0.99).expect("top face");
    assert!((top.area - 2400.0).abs() < 1e-6);
    assert_eq!(top.polygon.holes.len(), 1);
    assert!((platener_geom::polygon::signed_area(&top.polygon.holes[0]) + 100.0).abs() < 1e-6);
}

fn rigid(axis: DVec3, angle: f64, shift: DVec3) -> impl Fn(DVec3) -> DVec3 {
    let r = DMat3::from_axis_angle(axis.normalize(), angle);
    move |p| r * p + shift
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(16))]
    #[test]
    fn shapes_do_not_depend_on_placement(
        ax in (-1.0f64..1.0, -1.0f64..1.0, 0.1f64..1.0),
        angle in 0.0f64..std::f64::consts::TAU,
        shift in (-500.0f64..500.0, -500.0f64..500.0, -500.0f64..500.0),
    ) {
        let model = open_box(100.0, 60.0, 40.0, 3.0);
        let base = shapes_of(model.clone());
        let f = rigid(DVec3::new(ax.0, ax.1, ax.2), angle, DVec3::new(shift.0, shift.1, shift.2));
        let moved = shapes_of(model.iter().map(|t| t.map(&f)).collect());
        let by_area = |s: &Shapes| {
            let mut v: Vec<(f64, f64)> = s
                .shapes
                .iter()
                .map(|x| (x.area, perimeter(&x.polygon.outer) + x.polygon.holes.iter().map(|h| perimeter(h)).sum::<f64>()))
                .collect();
            v.sort_by(|a, b| a.0.total_cmp(&b.0));
            v
        };
        let (a, b) = (by_area(&base), by_area(&moved));
        prop_assert_eq!(a.len(), b.len());
        for ((x, per), (y, _)) in a.iter().zip(&b) {
            // Snapping to the grid moves each vertex by at most half a step (per axis): the
            // area changes by at most perimeter × step.
            prop_assert!((x - y).abs() <= per * STEP, "{} vs {}", x, y);
        }
        let holes = |s: &Shapes| s.shapes.iter().map(|x| x.polygon.holes.len()).sum::<usize>();
        prop_assert_eq!(holes(&base), holes(&moved));
    }
}

#[test]
fn welding_removes_chamfers_so_faces_meet_again() {
    // A 40 mm cube profile with 0.5 mm chamfers on four edges, extruded 40 mm: 10 faces.
    let (s, c) = (40.0, 0.5);
    let p = |x: f64, y: f64| glam::DVec2::new(x, y);
    let profile = [
        p(c, 0.0),
        p(s - c, 0.0),
        p(s, c),
        p(s, s - c),
        p(s - c, s),
        p(c, s),
        p(0.0, s - c),
        p(0.0, c),
    ];
    let model = platener_fixtures::samples::prism(&profile, s);
    let unwelded = {
        let source = Source::triangles("chamfered", model.clone());
        let settings = Settings {
            weld: crate::Weld::Off,
            ..Settings::default()
        };
        run_foundation(source, settings, &Cancel::default())
            .expect("converts")
            .0
            .shapes
            .expect("shapes")
    };
    assert_eq!(unwelded.shapes.len(), 10);
    // Automatic welding (40 mm model: 0.8 mm) collapses the 0.71 mm chamfers.
    let welded = shapes_of(model);
    let areas = sorted_areas(&welded);
    assert_eq!(areas.len(), 6, "{areas:?}");
    for a in areas {
        // Each chamfer's two edges merge into one point on the chamfer, so every face edge
        // ends up between 0 and c inside the sharp cube's: the face is (s − c)² … s².
        assert!(a >= (s - c) * (s - c) - 1e-6 && a <= s * s + 1e-6, "{a}");
    }
}

#[test]
fn results_do_not_depend_on_the_thread_count() {
    let model = platener_fixtures::samples::rounded_box(DVec3::new(60.0, 40.0, 30.0), 5.0, 24);
    let run_with = |threads: usize| {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .expect("pool");
        pool.install(|| shapes_of(model.clone()))
    };
    let (one, two) = (run_with(1), run_with(2));
    assert_eq!(one.shapes.len(), two.shapes.len());
    for (a, b) in one.shapes.iter().zip(&two.shapes) {
        assert_eq!(a.polygon, b.polygon);
        assert_eq!(a.frame, b.frame);
    }
}
