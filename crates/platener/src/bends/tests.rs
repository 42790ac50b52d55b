//! Tests of the bends step: tubes become one bent part, folding the flat part back puts
//! every plate where it was, and developed shapes never overlap.

use glam::{DVec2, DVec3};

use crate::pipeline::{self, State, StepId};
use crate::read::Triangle;
use crate::settings::Settings;

/// An n-sided tube ring (open ends), the wall `wall` thick across each facet.
pub(crate) fn tube(n: usize, radius: f64, height: f64, wall: f64) -> Vec<Triangle> {
    let apothem = radius * (std::f64::consts::PI / n as f64).cos();
    let inner = radius * (apothem - wall) / apothem;
    let at = |r: f64, k: usize, z: f64| {
        let a = std::f64::consts::TAU * k as f64 / n as f64;
        DVec3::new(r * a.cos(), r * a.sin(), z)
    };
    let mut out = Vec::new();
    let mut quad = |a: DVec3, b: DVec3, c: DVec3, d: DVec3| {
        out.push([a, b, c]);
        out.push([a, c, d]);
    };
    for k in 0..n {
        let j = k + 1;
        quad(
            at(radius, k, 0.0),
            at(radius, j, 0.0),
            at(radius, j, height),
            at(radius, k, height),
        );
        quad(
            at(inner, j, 0.0),
            at(inner, k, 0.0),
            at(inner, k, height),
            at(inner, j, height),
        );
        quad(
            at(radius, k, height),
            at(radius, j, height),
            at(inner, j, height),
            at(inner, k, height),
        );
        quad(
            at(inner, k, 0.0),
            at(inner, j, 0.0),
            at(radius, j, 0.0),
            at(radius, k, 0.0),
        );
    }
    out
}

pub(crate) fn run_plate(triangles: Vec<Triangle>, settings: Settings) -> State {
    let mut state = State::new(
        pipeline::Source::Triangles {
            name: "t".into(),
            triangles: std::sync::Arc::new(triangles),
        },
        settings,
    );
    let steps = [&pipeline::PLATE[..], &[StepId::Parts]].concat();
    pipeline::run(&steps, &mut state, &crate::context::Cancel::default()).expect("converts");
    state
}

#[test]
fn a_hexagonal_tube_is_one_bent_part_with_five_bends_and_a_seam() {
    let state = run_plate(tube(6, 50.0, 60.0, 3.0), Settings::default());
    let bends = state.bends.as_ref().expect("bends");
    assert_eq!(state.plates.as_ref().unwrap().plates.len(), 6);
    assert_eq!(bends.parts.len(), 1, "{:#?}", bends.refused);
    let part = &bends.parts[0];
    assert_eq!(part.members.len(), 6);
    assert_eq!(part.bends.len(), 5);
    assert_eq!(part.seams.len(), 1);
    let parts = &state.parts.as_ref().unwrap().parts;
    assert_eq!(parts.len(), 1);
    assert_eq!(parts[0].segments.len(), 6);
    let _ = DVec2::ZERO;
}

/// The model centroid of plate `p`'s outline at mid-thickness.
fn plate_centre(plate: &crate::plates::Plate) -> DVec3 {
    let ring = &plate.polygon.outer;
    let c = ring.iter().copied().sum::<DVec2>() / ring.len() as f64;
    plate.frame.to_model(DVec3::new(c.x, c.y, plate.thickness / 2.0))
}

#[test]
fn folding_the_tube_back_puts_every_plate_where_it_was() {
    let (n, radius, wall) = (6, 50.0, 3.0);
    let state = run_plate(tube(n, radius, 60.0, wall), Settings::default());
    let plates = &state.plates.as_ref().unwrap().plates;
    let bent = &state.bends.as_ref().unwrap().parts[0];
    let part = &state.parts.as_ref().unwrap().parts[0];
    for (i, m) in bent.members.iter().enumerate() {
        let plate = &plates[m.plate as usize];
        let seg = &part.segments[i];
        // The plate's centre, taken into the flat by its segment's frame, lies in the
        // segment at mid-thickness.
        let local = seg.frame.to_local(plate_centre(plate));
        assert!((local.z - wall / 2.0).abs() < 1e-6, "member {i}: z {}", local.z);
        assert!(seg.polygon.contains(DVec2::new(local.x, local.y)), "member {i}");
        assert!(part.polygon.contains(DVec2::new(local.x, local.y)));
        // Every corner of the segment, folded back, lies within the plate's slab (as the
        // joints step cut it: the seam has fingers).
        let outline = &state.joints.as_ref().unwrap().outlines[m.plate as usize];
        for q in &seg.polygon.outer {
            let p = plate
                .frame
                .to_local(seg.frame.to_model(DVec3::new(q.x, q.y, wall / 2.0)));
            assert!((p.z - wall / 2.0).abs() < 1e-6);
            assert!(outline.distance_to(DVec2::new(p.x, p.y)) < 0.01, "member {i}: {q}");
        }
    }
    // Neighbouring plates lie a mid-plane facet width minus the bend deduction apart.
    let apothem = radius * (std::f64::consts::PI / n as f64).cos();
    let mid_width = 2.0 * (apothem - wall / 2.0) * (std::f64::consts::PI / n as f64).tan();
    for b in &bent.bends {
        let [i, j] = b.members;
        let flat = |k: usize| {
            let m = &bent.members[k];
            m.to_flat(wall, plate_centre(&plates[m.plate as usize]))
        };
        let gap = (flat(i) - flat(j)).length();
        let expected = mid_width - b.zone.deduction();
        assert!((gap - expected).abs() < 0.01, "{gap} vs {expected}");
        // The bend line runs between the two segments, a half zone from each.
        let (a, d) = (b.line[0], (b.line[1] - b.line[0]).normalize());
        for k in [i, j] {
            for q in &part.segments[k].polygon.outer {
                let dist = (*q - a).perp_dot(d).abs();
                assert!(
                    dist >= b.zone.width / 2.0 - 0.01,
                    "segment {k} reaches into the zone: {dist}"
                );
            }
        }
    }
    // The flat part is one piece, its segments apart.
    let total: f64 = part.segments.iter().map(|s| s.polygon.area()).sum();
    assert!(total < part.polygon.area());
}

#[test]
fn tubes_of_6_12_and_24_sides_and_a_cone_in_card_bend_into_one_part() {
    for n in [6, 12, 24] {
        let state = run_plate(tube(n, 50.0, 60.0, 3.0), Settings::default());
        let b = state.bends.as_ref().unwrap();
        assert_eq!(b.parts.len(), 1, "{n} sides: {:#?}", b.refused);
        assert_eq!(b.parts[0].bends.len(), n - 1, "{n} sides");
        assert_eq!(b.parts[0].seams.len(), 1, "{n} sides");
        assert_eq!(state.parts.as_ref().unwrap().parts.len(), 1, "{n} sides");
    }
}

#[test]
fn no_bending_keeps_every_plate_a_part() {
    let settings = Settings {
        bending: crate::Bending::None,
        ..Settings::default()
    };
    let state = run_plate(tube(6, 50.0, 60.0, 3.0), settings);
    assert!(state.bends.as_ref().unwrap().parts.is_empty());
    assert_eq!(state.parts.as_ref().unwrap().parts.len(), 6);
}

#[test]
fn a_box_keeps_its_finger_joints() {
    let state = run_plate(crate::samples::closed_box(100.0, 80.0, 60.0, 3.0), Settings::default());
    assert!(state.bends.as_ref().unwrap().parts.is_empty());
    assert_eq!(state.parts.as_ref().unwrap().parts.len(), 6);
}
