use glam::DVec2;

use super::*;
use crate::polygon::rect;

fn v(x: f64, y: f64) -> DVec2 {
    DVec2::new(x, y)
}

fn problems(p: &Polygon, w: f64) -> Vec<Problem> {
    validate(p, w).into_iter().map(|f| f.problem).collect()
}

#[test]
fn a_square_with_a_hole_is_valid() {
    let mut p = Polygon {
        outer: rect(0.0, 0.0, 10.0, 10.0),
        holes: vec![rect(2.0, 2.0, 5.0, 5.0)],
    };
    p.normalize_orientation();
    assert!(validate(&p, 0.5).is_empty(), "{:?}", validate(&p, 0.5));
    // Its narrowest walls (left and bottom of the hole) are 2 mm.
    assert!(is_valid(&p, 1.9));
    assert!(!is_valid(&p, 2.1));
}

#[test]
fn wrong_orientation_is_found_per_ring() {
    let p = Polygon {
        outer: rect(0.0, 0.0, 10.0, 10.0),
        holes: vec![rect(2.0, 2.0, 5.0, 5.0)],
    };
    let f = validate(&p, 0.0);
    assert_eq!(f.len(), 1);
    assert_eq!((f[0].ring, f[0].problem), (RingId::Hole(0), Problem::Orientation));
}

#[test]
fn a_bow_tie_crosses_itself_at_its_centre() {
    let p = Polygon::new(vec![v(0.0, 0.0), v(4.0, 4.0), v(4.0, 0.0), v(0.0, 4.0)]);
    let f: Vec<_> = validate(&p, 0.0)
        .into_iter()
        .filter(|f| matches!(f.problem, Problem::Crossing { .. }))
        .collect();
    assert_eq!(f.len(), 1);
    assert_eq!(f[0].problem, Problem::Crossing { other: RingId::Outer });
    assert!(f[0].at.distance(v(2.0, 2.0)) < 1e-12);
}

#[test]
fn a_zero_width_spike_is_found_where_it_turns() {
    // A square with a spike running out to (15, 5) and back along the same line.
    let p = Polygon::new(vec![
        v(0.0, 0.0),
        v(10.0, 0.0),
        v(10.0, 5.0),
        v(15.0, 5.0),
        v(10.0, 5.0),
        v(10.0, 10.0),
        v(0.0, 10.0),
    ]);
    let f = validate(&p, 0.0);
    assert!(
        f.iter().any(|f| f.problem == Problem::Spike && f.at == v(15.0, 5.0)),
        "{f:?}"
    );
    // The spike's base vertex is visited twice: a touch too.
    assert!(
        f.iter()
            .any(|f| matches!(f.problem, Problem::Touching { .. }) && f.at == v(10.0, 5.0))
    );
}

#[test]
fn a_hole_corner_on_the_outer_edge_is_a_touch() {
    // The shaft-slot case: a slot rectangle whose corner lies exactly on the layer's edge.
    let mut p = Polygon {
        outer: rect(0.0, 0.0, 10.0, 10.0),
        holes: vec![rect(10.0 - 3.0, 4.0, 10.0, 6.0)],
    };
    // Move the slot so only its corner (10, 4) touches: slanted right edge of the layer.
    p.outer = vec![v(0.0, 0.0), v(10.0, 0.0), v(10.0, 4.0), v(12.0, 10.0), v(0.0, 10.0)];
    p.holes = vec![rect(7.0, 4.0, 10.0, 6.0)];
    p.normalize_orientation();
    let f = validate(&p, 0.0);
    assert!(
        f.iter().any(|f| f.ring == RingId::Outer
            && f.problem == Problem::Touching { other: RingId::Hole(0) }
            && f.at == v(10.0, 4.0)),
        "{f:?}"
    );
}

#[test]
fn holes_outside_inside_others_and_touching_each_other() {
    let mut p = Polygon {
        outer: rect(0.0, 0.0, 10.0, 10.0),
        holes: vec![
            rect(20.0, 0.0, 22.0, 2.0),
            rect(1.0, 1.0, 6.0, 6.0),
            rect(2.0, 2.0, 3.0, 3.0),
        ],
    };
    p.normalize_orientation();
    let f = problems(&p, 0.0);
    assert_eq!(f, vec![Problem::HoleOutside, Problem::HoleInHole { other: 1 }]);
    let mut q = Polygon {
        outer: rect(0.0, 0.0, 10.0, 10.0),
        holes: vec![rect(1.0, 1.0, 4.0, 4.0), rect(4.0, 4.0, 6.0, 6.0)],
    };
    q.normalize_orientation();
    let f = validate(&q, 0.0);
    assert_eq!(f.len(), 1, "{f:?}");
    assert_eq!(f[0].problem, Problem::Touching { other: RingId::Hole(1) });
    assert_eq!((f[0].ring, f[0].at), (RingId::Hole(0), v(4.0, 4.0)));
}

#[test]
fn narrow_material_is_found_and_wide_material_is_not() {
    // A 10 × 10 square with a 0.1 mm wide, 5 mm long strip on its right.
    let p = Polygon::new(vec![
        v(0.0, 0.0),
        v(10.0, 0.0),
        v(10.0, 4.0),
        v(15.0, 4.0),
        v(15.0, 4.1),
        v(10.0, 4.1),
        v(10.0, 10.0),
        v(0.0, 10.0),
    ]);
    let f = validate(&p, 0.2);
    assert!(!f.is_empty() && f.iter().all(|f| f.problem == Problem::Narrow), "{f:?}");
    assert!(
        f.iter().all(|f| f.at.x >= 10.0 - 1e-9 && (4.0..=4.1).contains(&f.at.y)),
        "{f:?}"
    );
    assert!(validate(&p, 0.09).is_empty());
    // A sharp but wide corner (a 20° wedge 10 mm across) is not narrow at 0.2 mm width: the
    // opening restores miter corners exactly.
    let wedge = Polygon::new(vec![
        v(0.0, 0.0),
        v(30.0, 0.0),
        v(30.0, 30.0 * 20f64.to_radians().tan()),
    ]);
    assert!(validate(&wedge, 0.2).is_empty(), "{:?}", validate(&wedge, 0.2));
}

#[test]
fn degenerate_rings_are_named() {
    let p = Polygon::new(vec![v(0.0, 0.0), v(1.0, 0.0)]);
    assert_eq!(problems(&p, 0.1), vec![Problem::TooFewVertices]);
    let flat = Polygon::new(vec![v(0.0, 0.0), v(1.0, 0.0), v(2.0, 0.0)]);
    assert!(problems(&flat, 0.0).contains(&Problem::NoArea));
    let nan = Polygon::new(vec![v(0.0, 0.0), v(f64::NAN, 0.0), v(2.0, 1.0)]);
    assert_eq!(problems(&nan, 0.1), vec![Problem::NonFinite]);
    let repeated = Polygon::new(vec![v(0.0, 0.0), v(1.0, 0.0), v(1.0, 0.0), v(1.0, 1.0)]);
    assert!(problems(&repeated, 0.0).contains(&Problem::RepeatedVertex));
}
