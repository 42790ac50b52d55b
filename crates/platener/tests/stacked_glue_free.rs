//! Issue 31, item 1: every stacked layer held. The organic samples (an animal on four thin
//! legs, a hull with a cabin, a torus on its rim, a vase with a handle) convert with the
//! stacked method into one group that shafts and pegs hold, without glue: where two layers
//! overlap too narrowly even for a peg (the handle's pieces, a leg's slanted end), both get a
//! boss that holds one. The teapot's spout is checked in `stacked_pegs`.
//!
//! Tolerances: the 1 µm grid of the booleans (areas under [`GRID_AREA`] mm² are rounding).

use platener::convert;
use platener::method::MethodKind;
use platener::read::Triangle;
use platener::stacked::{PEG_MIN_WALL, Stack};
use platener::verify::verify;
use platener::{Cancel, Settings, Source};
use platener_fixtures::samples;
use platener_geom::polygon::total_area;
use platener_geom::{Polygon, boolean};

/// Areas under this (mm²) are grid rounding.
const GRID_AREA: f64 = 1e-4;

fn sample(name: &str) -> Vec<Triangle> {
    samples::organic_samples()
        .into_iter()
        .find(|(n, _)| *n == name)
        .map(|(_, t)| t)
        .expect("a sample")
}

/// Every boss lies whole in both its islands, adds at most a square, and a peg joins them.
fn check_bosses(name: &str, st: &Stack) {
    let side = st.shaft_thickness + 2.0 * PEG_MIN_WALL + 0.1;
    for b in &st.bosses {
        assert!((b.square.area() - side * side).abs() < 1e-6, "{name}: {b:?}");
        assert!(b.added <= side * side + 1e-9, "{name}: {b:?}");
        for (k, i) in [(b.layer, b.lower), (b.layer + 1, b.upper)] {
            let island: &Polygon = &st.layers[k].islands[i].outline;
            let out = boolean::difference(std::slice::from_ref(&b.square), std::slice::from_ref(island)).expect("grid");
            assert!(
                total_area(&out) < GRID_AREA,
                "{name}: layer {}: {}",
                k + 1,
                total_area(&out)
            );
        }
        let pegged = st.shafts.iter().any(|s| {
            s.bands
                .windows(2)
                .any(|w| (w[0].layer, w[0].island, w[1].island) == (b.layer, b.lower, b.upper))
        });
        assert!(pegged, "{name}: no shaft through the boss {b:?}");
    }
}

#[test]
fn the_organic_samples_stack_glue_free() {
    let mut bossed = 0;
    for name in ["animal.stl", "hull_with_cabin.stl", "torus.stl", "vase_with_handle.stl"] {
        let mut s = Settings::default();
        s.cut.nest_tries = 1;
        s.cut.fine_rotations = false;
        let source = Source::triangles(name, sample(name));
        let state =
            convert(MethodKind::Stacked, source, s, &Cancel::default()).unwrap_or_else(|e| panic!("{name}: {e}"));
        let plan = &state.export.as_ref().expect("exported").plan;
        assert!(plan.glued.is_empty(), "{name}: {:?}", plan.glued);
        assert_eq!(plan.glue_note(), "glue-free", "{name}");
        let v = verify(plan, state.mesh.as_deref());
        assert!(v.passed(), "{name}: {:?}", v.failures);
        assert_eq!(v.groups, 1, "{name}: {:?}", v.group_parts);
        assert!(v.interference_share < 1e-4, "{name}: {}", v.interference_share);
        let st = state.stacked.as_ref().expect("stack");
        check_bosses(name, st);
        bossed += usize::from(!st.bosses.is_empty());
    }
    // The animal's legs and the vase's handle need bosses; the check above is not empty.
    assert!(bossed >= 2, "{bossed}");
}
