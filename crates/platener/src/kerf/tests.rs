use glam::DVec2;
use platener_geom::Polygon;
use platener_geom::polygon::signed_area;
use platener_geom::validate;

use super::*;

use platener_geom::polygon::rect;

use crate::plan::samples::flat_part as part;

/// Tolerance of these checks: the 1 µm grid, squared into areas.
const AREA_TOL: f64 = 1e-3;

#[test]
fn outline_grows_and_holes_shrink_by_half_the_kerf() {
    let p = Polygon {
        outer: rect(0.0, 0.0, 40.0, 20.0),
        holes: vec![rect(10.0, 5.0, 20.0, 15.0)],
    };
    let cut = cut_polygon(&p, 0.2).expect("on grid");
    // (40.2 × 20.2) − (9.8 × 9.8)
    assert!(
        (cut.area() - (40.2 * 20.2 - 9.8 * 9.8)).abs() < AREA_TOL,
        "{}",
        cut.area()
    );
    assert!(signed_area(&cut.outer) > 0.0 && signed_area(&cut.holes[0]) < 0.0);
    let (lo, hi) = cut.bounds();
    assert!((lo - DVec2::splat(-0.1)).length() < 1e-9 && (hi - DVec2::new(40.1, 20.1)).length() < 1e-9);
}

#[test]
fn notches_keep_their_square_corners() {
    // A plate with two finger notches on its top edge: 12 corners, all right angles.
    let outer = vec![
        DVec2::new(0.0, 0.0),
        DVec2::new(60.0, 0.0),
        DVec2::new(60.0, 30.0),
        DVec2::new(45.0, 30.0),
        DVec2::new(45.0, 27.0),
        DVec2::new(35.0, 27.0),
        DVec2::new(35.0, 30.0),
        DVec2::new(25.0, 30.0),
        DVec2::new(25.0, 27.0),
        DVec2::new(15.0, 27.0),
        DVec2::new(15.0, 30.0),
        DVec2::new(0.0, 30.0),
    ];
    let cut = cut_polygon(&Polygon::new(outer), 0.3).expect("on grid");
    assert_eq!(cut.outer.len(), 12);
    // Each notch is 0.3 narrower: its corners moved by exactly 0.15 in x and y.
    assert!(
        cut.outer
            .iter()
            .any(|p| (*p - DVec2::new(15.15, 27.15)).length() < 1e-9)
    );
    assert!(
        cut.outer
            .iter()
            .any(|p| (*p - DVec2::new(-0.15, 30.15)).length() < 1e-9)
    );
}

#[test]
fn cut_paths_keep_the_part_order_and_warn_about_closed_holes() {
    let tiny_hole = Polygon {
        outer: rect(0.0, 0.0, 10.0, 10.0),
        holes: vec![rect(4.0, 4.0, 4.1, 6.0)],
    };
    let parts = [part(7, Polygon::new(rect(0.0, 0.0, 5.0, 5.0))), part(3, tiny_hole)];
    let (cut, warnings) = cut_paths(&parts, 0.2).expect("valid");
    assert_eq!(cut.parts.iter().map(|p| p.id).collect::<Vec<_>>(), [7, 3]);
    assert!(cut.parts[1].cut.holes.is_empty());
    assert!(
        cut.parts[1].nominal.holes.is_empty(),
        "plan.json has no hole the laser cannot cut"
    );
    assert_eq!(warnings.len(), 1);
    assert_eq!(warnings[0].part, Some(3));
}

/// Issue 32: holes narrower than twice the kerf are left out of the nominal shape and the cut
/// path, with a warning; one just wider stays; slivers of a triangulation's gaps go whatever
/// the kerf.
#[test]
fn holes_narrower_than_twice_the_kerf_are_not_cut() {
    let sliver = vec![DVec2::new(20.0, 20.0), DVec2::new(23.0, 20.0), DVec2::new(20.0, 20.03)];
    let plate = Polygon {
        outer: rect(0.0, 0.0, 40.0, 40.0),
        // 0.35 mm wide (< 0.4 mm), 0.45 mm wide (kept), a 0.045 mm² triangle.
        holes: vec![rect(5.0, 5.0, 5.35, 15.0), rect(10.0, 5.0, 10.45, 15.0), sliver.clone()],
    };
    let (cut, warnings) = cut_paths(&[part(1, plate.clone())], 0.2).expect("valid");
    let nominal = &cut.parts[0].nominal;
    assert_eq!(nominal.holes.len(), 1);
    let kept = nominal.holes[0].iter().map(|p| p.x).fold(f64::INFINITY, f64::min);
    assert!((kept - 10.0).abs() < 1e-9);
    assert_eq!(cut.parts[0].cut.holes.len(), 1);
    assert!(
        (cut.parts[0].cut.holes[0]
            .iter()
            .map(|p| p.x)
            .fold(f64::INFINITY, f64::min)
            - 10.1)
            .abs()
            < 1e-6
    );
    assert!(
        warnings[0]
            .message
            .contains("2 hole(s) of part 1 are narrower than 0.40 mm"),
        "{}",
        warnings[0].message
    );
    // With no kerf, the triangle still goes: no beam is finer than 0.1 mm.
    let (cut, _) = cut_paths(&[part(1, plate)], 0.0).expect("valid");
    assert_eq!(cut.parts[0].nominal.holes.len(), 2);
}

#[test]
fn zero_kerf_cuts_the_nominal_shape() {
    let p = Polygon::new(rect(0.0, 0.0, 7.0, 3.0));
    let cut = cut_polygon(&p, 0.0).expect("on grid");
    assert!((cut.area() - 21.0).abs() < AREA_TOL);
}

#[test]
fn closed_input_rings_are_opened() {
    let mut closed = rect(0.0, 0.0, 4.0, 4.0);
    closed.push(closed[0]);
    closed.insert(1, closed[0]);
    let (cut, _) = cut_paths(&[part(1, Polygon::new(closed))], 0.0).expect("valid");
    assert_eq!(cut.parts[0].nominal.outer, rect(0.0, 0.0, 4.0, 4.0));
}

/// Two holes of a cut path meeting at a corner (the geo lamp's part 55 at 3 mm, after growing)
/// are cut as one hole: the path is valid and the material lost is a speck at the corner.
#[test]
fn holes_touching_in_a_cut_path_are_merged() {
    let mut cut = Polygon {
        outer: rect(0.0, 0.0, 40.0, 20.0),
        holes: vec![rect(5.0, 5.0, 15.0, 15.0), rect(15.0, 15.0, 25.0, 18.0)],
    };
    cut.normalize_orientation();
    assert!(!validate(&cut, 0.0).is_empty());
    let (repaired, touches) = separate_touches(&cut).expect("grid");
    assert_eq!(touches, 1);
    assert!(validate(&repaired, 0.0).is_empty(), "{:?}", validate(&repaired, 0.0));
    assert_eq!(repaired.holes.len(), 1, "the touching holes are one");
    let lost = cut.area() - repaired.area();
    assert!((0.0..AREA_TOL).contains(&lost), "lost {lost} mm²");
}

/// A notch whose mouth the growth closed to a point (the geo lamp's part 24 at 2 mm): the
/// outline touches itself there; separated, the notch opens again and the part keeps its
/// area to a speck.
#[test]
fn a_notch_pinched_shut_by_the_growth_is_opened() {
    let v = DVec2::new;
    let cut = Polygon::new(vec![
        v(0.0, 0.0),
        v(20.0, 0.0),
        v(20.0, 20.0),
        v(10.0, 20.0),
        v(13.0, 17.0),
        v(10.0, 14.0),
        v(7.0, 17.0),
        v(10.0, 20.0),
        v(0.0, 20.0),
    ]);
    assert!(!validate(&cut, 0.0).is_empty());
    let (repaired, touches) = separate_touches(&cut).expect("grid");
    assert!(touches >= 1);
    assert!(validate(&repaired, 0.0).is_empty(), "{:?}", validate(&repaired, 0.0));
    assert!(repaired.holes.is_empty(), "the notch stays open to the outside");
    assert!((cut.area() - repaired.area()).abs() < AREA_TOL);
    assert!(!repaired.contains(v(10.0, 17.0)), "the notch is not filled");
}

#[test]
fn a_valid_cut_path_is_left_alone() {
    let cut = Polygon::new(rect(0.0, 0.0, 10.0, 5.0));
    assert_eq!(separate_touches(&cut).expect("grid"), (cut.clone(), 0));
}

/// The fit moves every cut path by a quarter of its clearance: a 10 mm finger grows by half
/// the press interference beyond the kerf, and a 10 mm notch shrinks by as much, so the
/// finger is 0.1 mm wider than its notch; loose leaves 0.15 mm of play; snug is the kerf alone.
#[test]
fn each_fit_sets_the_clearance_between_a_finger_and_its_notch() {
    use crate::plan::Fit;
    let kerf = 0.2;
    // A plate with a 10 mm wide notch, and a 10 mm wide finger (a plate 10 mm across).
    let notched = Polygon::new(vec![
        DVec2::new(0.0, 0.0),
        DVec2::new(40.0, 0.0),
        DVec2::new(40.0, 20.0),
        DVec2::new(25.0, 20.0),
        DVec2::new(25.0, 10.0),
        DVec2::new(15.0, 10.0),
        DVec2::new(15.0, 20.0),
        DVec2::new(0.0, 20.0),
    ]);
    let finger = Polygon::new(vec![
        DVec2::new(0.0, 0.0),
        DVec2::new(10.0, 0.0),
        DVec2::new(10.0, 30.0),
        DVec2::new(0.0, 30.0),
    ]);
    let width_at = |ring: &[DVec2], y: f64, pick_notch: bool| {
        // The notch: the gap between the two prongs at height y; the finger: its extent.
        let xs: Vec<f64> = ring
            .iter()
            .zip(ring.iter().cycle().skip(1))
            .filter(|(a, b)| (a.y - y) * (b.y - y) < 0.0)
            .map(|(a, b)| a.x + (y - a.y) * (b.x - a.x) / (b.y - a.y))
            .collect();
        let mut xs = xs;
        xs.sort_by(f64::total_cmp);
        if pick_notch {
            xs[2] - xs[1]
        } else {
            xs[xs.len() - 1] - xs[0]
        }
    };
    for fit in Fit::ALL {
        let parts = [part(1, notched.clone()), part(2, finger.clone())];
        let (cut, _) = fitted_cut_paths(&parts, kerf, fit).expect("valid");
        let notch = width_at(&cut.parts[0].cut.outer, 15.0, true);
        let tab = width_at(&cut.parts[1].cut.outer, 15.0, false);
        // Cut: the laser takes half the kerf off each side of every path.
        let (notch, tab) = (notch + kerf, tab - kerf);
        assert!(
            // Four flanks, each on the 1 µm grid.
            (notch - tab - fit.clearance()).abs() < 4e-3,
            "{fit:?}: notch {notch} finger {tab}"
        );
    }
    let snug = fitted_cut_paths(&[part(1, finger.clone())], kerf, Fit::Snug)
        .expect("valid")
        .0;
    let plain = cut_paths(&[part(1, finger)], kerf).expect("valid").0;
    assert_eq!(snug.parts[0].cut, plain.parts[0].cut, "snug is the kerf alone");
}
