//! Property tests of the kernel's invariants: booleans keep area (inclusion–exclusion),
//! offsetting out and back in returns a convex shape, frames carry points to 3D and back.
//!
//! Tolerances derive from the grid: every boolean or offset snaps vertices to the
//! [`STEP`] grid, which moves a boundary by at most a step, so an area may change by at most
//! the boundary's length times a step (taken twice, for margin).

use platener_geom::boolean::{self, Op};
use platener_geom::glam::{DVec2, DVec3};
use platener_geom::grid::STEP;
use platener_geom::offset::offset;
use platener_geom::polygon::{perimeter, total_area};
use platener_geom::{Frame, Polygon};
use proptest::prelude::*;

/// A point on the grid near `p`, so that the input itself needs no snapping.
fn on_grid(p: DVec2) -> DVec2 {
    (p / STEP).round() * STEP
}

/// A star-shaped polygon around `center`: `radii.len()` vertices at evenly spaced angles
/// (each moved by up to 0.3 of the spacing by `jitter`), counter-clockwise, on the grid.
fn star(center: DVec2, radii: &[f64], jitter: &[f64]) -> Polygon {
    let n = radii.len();
    let spacing = std::f64::consts::TAU / n as f64;
    let ring = (0..n)
        .map(|i| {
            let a = (i as f64 + 0.3 * jitter[i]) * spacing;
            on_grid(center + DVec2::from_angle(a) * radii[i])
        })
        .collect();
    Polygon::new(ring)
}

/// The total boundary length of some polygons.
fn boundary(polygons: &[&Polygon]) -> f64 {
    polygons
        .iter()
        .map(|p| perimeter(&p.outer) + p.holes.iter().map(|h| perimeter(h)).sum::<f64>())
        .sum()
}

/// Star polygons with 3 to 16 vertices, radii 2–40 mm, centred within ±30 mm.
fn any_star() -> impl Strategy<Value = Polygon> {
    (3usize..16, -30.0f64..30.0, -30.0f64..30.0).prop_flat_map(|(n, x, y)| {
        (
            prop::collection::vec(2.0f64..40.0, n),
            prop::collection::vec(-1.0f64..1.0, n),
        )
            .prop_map(move |(radii, jitter)| star(DVec2::new(x, y), &radii, &jitter))
    })
}

/// Convex polygons: 4 to 16 vertices on a circle of radius 5–40 mm, spaced so that no
/// interior angle is sharp (i_overlay bevels turns under 5° instead of mitring them).
fn any_convex() -> impl Strategy<Value = Polygon> {
    (4usize..16, 5.0f64..40.0).prop_flat_map(|(n, r)| {
        prop::collection::vec(-1.0f64..1.0, n).prop_map(move |jitter| star(DVec2::ZERO, &vec![r; n], &jitter))
    })
}

proptest! {
    #[test]
    fn union_and_intersection_keep_the_total_area(a in any_star(), b in any_star()) {
        let (sa, sb) = (std::slice::from_ref(&a), std::slice::from_ref(&b));
        let union = total_area(&boolean::union(sa, sb).expect("on the grid"));
        let common = total_area(&boolean::intersection(sa, sb).expect("on the grid"));
        let tolerance = 2.0 * STEP * boundary(&[&a, &b]);
        let gap = (union + common - a.area() - b.area()).abs();
        prop_assert!(gap <= tolerance, "|A∪B| + |A∩B| − |A| − |B| = {gap} > {tolerance}");
    }

    #[test]
    fn offset_out_and_in_returns_a_convex_shape(p in any_convex(), microns in 10i32..5000) {
        let d = f64::from(microns) * STEP;
        let out = offset(std::slice::from_ref(&p), d).expect("on the grid");
        let back = offset(&out, -d).expect("on the grid");
        let tolerance = 2.0 * STEP * boundary(&[&p]);
        let area_gap = (total_area(&back) - p.area()).abs();
        prop_assert!(area_gap <= tolerance, "area changed by {area_gap} > {tolerance}");
        let moved = total_area(&boolean::apply(Op::Xor, std::slice::from_ref(&p), &back).expect("on the grid"));
        prop_assert!(moved <= tolerance, "symmetric difference {moved} > {tolerance}");
    }

    #[test]
    fn frames_carry_plane_points_to_the_model_and_back(
        n in (-1.0f64..1.0, -1.0f64..1.0, -1.0f64..1.0).prop_filter("a normal", |(x, y, z)| x * x + y * y + z * z > 1e-2),
        origin in (-500.0f64..500.0, -500.0f64..500.0, -500.0f64..500.0),
        p in (-500.0f64..500.0, -500.0f64..500.0),
        q in (-500.0f64..500.0, -500.0f64..500.0, -500.0f64..500.0),
    ) {
        let frame = Frame::on_plane(DVec3::new(origin.0, origin.1, origin.2), DVec3::new(n.0, n.1, n.2));
        // Rounding of a few products of numbers up to ~1000 mm: far below a nanometre.
        let tolerance = 1e-9;
        let p = DVec2::new(p.0, p.1);
        let back = frame.to_2d(frame.to_model_2d(p));
        prop_assert!(back.distance(p) <= tolerance, "2D {p} came back as {back}");
        // A model point moved onto the plane along the normal.
        let q = DVec3::new(q.0, q.1, q.2);
        let on_plane = q - frame.n * (q - frame.origin).dot(frame.n);
        let again = frame.to_model_2d(frame.to_2d(on_plane));
        prop_assert!(again.distance(on_plane) <= tolerance, "3D {on_plane} came back as {again}");
        prop_assert!(frame.to_local(on_plane).z.abs() <= tolerance);
    }
}
