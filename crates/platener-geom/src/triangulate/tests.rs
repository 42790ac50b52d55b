use glam::DVec2;
use proptest::prelude::*;

use super::*;
use crate::grid::STEP;
use crate::polygon::{perimeter, rect};

/// Snapping moves each corner by at most half a grid step along each axis, so the area
/// changes by at most the perimeter times a grid step.
fn area_tolerance(p: &Polygon) -> f64 {
    std::iter::once(&p.outer)
        .chain(&p.holes)
        .map(|r| perimeter(r))
        .sum::<f64>()
        * STEP
}

fn assert_area(p: &Polygon) -> Triangulation {
    let t = triangulate(p).expect("on the grid");
    let tol = area_tolerance(p);
    assert!(
        (t.area() - p.area()).abs() <= tol,
        "triangles cover {} mm², the polygon {} mm² (tolerance {tol})",
        t.area(),
        p.area()
    );
    t
}

#[test]
fn a_square_is_two_counter_clockwise_triangles() {
    let t = assert_area(&Polygon::new(rect(0.0, 0.0, 10.0, 5.0)));
    assert_eq!(t.triangles.len(), 2);
    assert_eq!(t.boundary_edges().len(), 4);
}

#[test]
fn holes_are_removed_whichever_way_they_are_wound() {
    let outer = rect(0.0, 0.0, 100.0, 60.0);
    for hole in [rect(10.0, 10.0, 30.0, 20.0), rect(30.0, 10.0, 10.0, 20.0)] {
        let p = Polygon {
            outer: outer.clone(),
            holes: vec![hole],
        };
        let t = assert_area(&p);
        assert!((t.area() - (6000.0 - 200.0)).abs() < 1e-9);
        assert_eq!(t.boundary_edges().len(), 8);
    }
}

#[test]
fn a_clockwise_outline_with_two_holes_and_exact_corners() {
    let mut outer = rect(0.1234567, 0.0, 50.0, 40.0);
    outer.reverse();
    let p = Polygon {
        outer,
        holes: vec![rect(5.0, 5.0, 15.0, 15.0), rect(20.0, 5.0, 45.0, 35.0)],
    };
    let t = assert_area(&p);
    // Corners keep their exact input coordinates, not the snapped ones.
    assert!(t.points.iter().any(|q| q.x == 0.1234567));
}

#[test]
fn degenerate_input_gives_no_triangles_and_bad_input_an_error() {
    let t = triangulate(&Polygon::new(vec![DVec2::ZERO, DVec2::X])).expect("on the grid");
    assert!(t.triangles.is_empty());
    assert!(triangulate(&Polygon::new(vec![DVec2::ZERO, DVec2::X, DVec2::splat(f64::NAN)])).is_err());
}

/// A star-shaped ring around the origin: radii at increasing angles.
fn star(radii: &[f64], scale: f64) -> Vec<DVec2> {
    let n = radii.len() as f64;
    radii
        .iter()
        .enumerate()
        .map(|(i, r)| {
            let a = std::f64::consts::TAU * i as f64 / n;
            DVec2::new(a.cos(), a.sin()) * r * scale
        })
        .collect()
}

proptest! {
    /// Star outlines (convex when all radii are equal) with a star hole inside: with at
    /// least six corners the outline stays beyond 20 · cos 30° > 17 mm of the centre, the
    /// hole within 15 mm. The triangles' areas add up to the polygon's, every triangle is
    /// counter-clockwise, and the boundary has as many edges as the rings have corners.
    #[test]
    fn triangle_areas_sum_to_the_polygon_area(
        outer in prop::collection::vec(20.0f64..50.0, 6..40),
        hole in prop::collection::vec(2.0f64..15.0, 3..20),
        convex in any::<bool>(),
        dx in -500.0f64..500.0,
    ) {
        let outer = if convex { vec![35.0; outer.len()] } else { outer };
        let shift = DVec2::new(dx, -dx * 0.5);
        let p = Polygon {
            outer: star(&outer, 1.0).into_iter().map(|q| q + shift).collect(),
            holes: vec![star(&hole, 1.0).into_iter().map(|q| q + shift).collect()],
        };
        let t = assert_area(&p);
        for tri in &t.triangles {
            let [a, b, c] = tri.map(|i| t.points[i as usize]);
            prop_assert!((b - a).perp_dot(c - a) >= 0.0);
        }
        prop_assert!(t.boundary_edges().len() <= p.vertex_count());
    }
}

/// Every boundary point has exactly one boundary edge out and one in (simple loops).
fn assert_simple_loops(t: &Triangulation) {
    let edges = t.boundary_edges();
    let mut out = vec![0; t.points.len()];
    let mut inn = vec![0; t.points.len()];
    for [a, b] in &edges {
        out[*a as usize] += 1;
        inn[*b as usize] += 1;
    }
    assert!(out.iter().zip(&inn).all(|(o, i)| *o == *i && *o <= 1), "{edges:?}");
}

#[test]
fn where_the_boundary_touches_itself_each_side_gets_its_own_point() {
    // Two squares meeting at one corner, as one self-touching ring.
    let bowtie = Polygon::new(vec![
        DVec2::new(0.0, 0.0),
        DVec2::new(10.0, 0.0),
        DVec2::new(10.0, 10.0),
        DVec2::new(20.0, 10.0),
        DVec2::new(20.0, 20.0),
        DVec2::new(10.0, 20.0),
        DVec2::new(10.0, 10.0),
        DVec2::new(0.0, 10.0),
    ]);
    // A hole touching the outline at (10, 5).
    let notch = Polygon {
        outer: rect(0.0, 0.0, 10.0, 10.0),
        holes: vec![vec![DVec2::new(5.0, 3.0), DVec2::new(10.0, 5.0), DVec2::new(5.0, 7.0)]],
    };
    for p in [bowtie, notch] {
        let t = assert_area(&p);
        assert_simple_loops(&t);
        let copies = t.points.len() - {
            let mut u: Vec<[u64; 2]> = t.points.iter().map(|q| q.to_array().map(f64::to_bits)).collect();
            u.sort_unstable();
            u.dedup();
            u.len()
        };
        assert_eq!(copies, 1, "the pinch point is doubled once");
    }
}
