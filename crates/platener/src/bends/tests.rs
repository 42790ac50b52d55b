//! Tests of the bends step: tubes become one bent part, folding the flat part back puts
//! every plate where it was, and developed shapes never overlap.

use glam::{DVec2, DVec3};

use crate::pipeline::{self, State, StepId};
use crate::read::Triangle;
use crate::settings::Settings;
use platener_fixtures::samples::tube;

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

/// Settings bending living hinges whatever the corner they round.
fn hinges() -> Settings {
    Settings {
        bending: crate::Bending::Style(crate::plan::BendStyle::LivingHinge),
        ..Settings::default()
    }
}

#[test]
fn a_hexagonal_tube_is_one_bent_part_with_five_bends_and_a_seam_when_hinges_are_asked_for() {
    let state = run_plate(tube(6, 50.0, 60.0, 3.0), hinges());
    let bends = state.bends.as_ref().expect("bends");
    assert_eq!(state.plates.as_ref().expect("the step ran").plates.len(), 6);
    assert_eq!(bends.parts.len(), 1, "{:#?}", bends.refused);
    let part = &bends.parts[0];
    assert_eq!(part.members.len(), 6);
    assert_eq!(part.bends.len(), 5);
    assert_eq!(part.seams.len(), 1);
    let parts = &state.final_parts().as_ref().expect("the step ran").parts;
    assert_eq!(parts.len(), 1);
    assert_eq!(parts[0].segments.len(), 6);
    // Chosen by material, the hexagon's 60° corners stay finger joints: the hinge would
    // round them by 4 mm.
    let auto = run_plate(tube(6, 50.0, 60.0, 3.0), Settings::default());
    assert!(auto.bends.as_ref().expect("the step ran").parts.is_empty());
    assert!(
        auto.bends
            .as_ref()
            .expect("the step ran")
            .refused
            .iter()
            .all(|r| r.reason.contains("rounding"))
    );
}

/// The model centroid of plate `p`'s outline at mid-thickness.
fn plate_centre(plate: &crate::plates::Plate) -> DVec3 {
    let ring = &plate.polygon.outer;
    let c = ring.iter().copied().sum::<DVec2>() / ring.len() as f64;
    plate.frame.to_model(DVec3::new(c.x, c.y, plate.thickness / 2.0))
}

#[test]
fn folding_the_tube_back_puts_every_plate_where_it_was() {
    let (n, radius, wall) = (12, 50.0, 3.0);
    let state = run_plate(tube(n, radius, 60.0, wall), Settings::default());
    let plates = &state.plates.as_ref().expect("the step ran").plates;
    let bent = &state.bends.as_ref().expect("the step ran").parts[0];
    let part = &state.final_parts().as_ref().expect("the step ran").parts[0];
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
        let outline = &state.joints.as_ref().expect("the step ran").outlines[m.plate as usize];
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
                    dist >= b.zone.width() / 2.0 - 0.01,
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
        let settings = if n == 6 { hinges() } else { Settings::default() };
        let state = run_plate(tube(n, 50.0, 60.0, 3.0), settings);
        let b = state.bends.as_ref().expect("the step ran");
        assert_eq!(b.parts.len(), 1, "{n} sides: {:#?}", b.refused);
        assert_eq!(b.parts[0].bends.len(), n - 1, "{n} sides");
        assert_eq!(b.parts[0].seams.len(), 1, "{n} sides");
        assert_eq!(
            state.final_parts().as_ref().expect("the step ran").parts.len(),
            1,
            "{n} sides"
        );
    }
}

#[test]
fn no_bending_keeps_every_plate_a_part() {
    let settings = Settings {
        bending: crate::Bending::None,
        ..Settings::default()
    };
    let state = run_plate(tube(12, 50.0, 60.0, 3.0), settings);
    assert!(state.bends.as_ref().expect("the step ran").parts.is_empty());
    assert_eq!(state.final_parts().as_ref().expect("the step ran").parts.len(), 12);
}

#[test]
fn a_box_keeps_its_finger_joints() {
    let state = run_plate(
        platener_fixtures::samples::closed_box(100.0, 80.0, 60.0, 3.0),
        Settings::default(),
    );
    assert!(state.bends.as_ref().expect("the step ran").parts.is_empty());
    assert_eq!(state.final_parts().as_ref().expect("the step ran").parts.len(), 6);
}

mod chains {
    //! Random chains of facets: a strip of trapezoids sharing edges, folded in space by
    //! random turns about those edges, as plates of 3 mm.

    use super::*;
    use crate::plan::{BendStyle, Material};
    use crate::plates::{Plate, PlateKind};
    use platener_geom::{Frame, Polygon, polygon::total_area};
    use proptest::prelude::*;

    const T: f64 = 3.0;

    /// The strip's facets in the flat (each a CCW quad) and the chain folded: one plate per
    /// facet whose mid-plane holds the folded facet.
    fn chain(widths: &[f64], tapers: &[f64], turns: &[f64]) -> (Vec<Polygon>, Vec<Plate>) {
        let mut flat = Vec::new();
        let (mut b0, mut b1) = (DVec2::new(0.0, 0.0), DVec2::new(0.0, 60.0));
        for (w, taper) in widths.iter().zip(tapers) {
            let d = (b1 - b0).perp().normalize() * -1.0;
            let (c0, c1) = (b0 + d * *w + (b1 - b0).normalize() * *taper, b1 + d * *w);
            let mut p = Polygon::new(vec![b0, c0, c1, b1]);
            p.normalize_orientation();
            flat.push(p);
            (b0, b1) = (c0, c1);
        }
        // Fold: each facet's motion is its predecessor's, then a turn about their edge.
        let mut motion = glam::DAffine3::IDENTITY;
        let mut plates = Vec::new();
        for (k, f) in flat.iter().enumerate() {
            if k > 0 {
                let e0 = &flat[k - 1].outer;
                let shared: Vec<DVec2> = f
                    .outer
                    .iter()
                    .filter(|q| e0.iter().any(|r| (**q - *r).length() < 1e-9))
                    .copied()
                    .collect();
                let (a, b) = (shared[0].extend(0.0), shared[1].extend(0.0));
                let axis = (b - a).normalize();
                let turn = glam::DAffine3::from_translation(a)
                    * glam::DAffine3::from_axis_angle(axis, turns[k - 1])
                    * glam::DAffine3::from_translation(-a);
                motion *= turn;
            }
            let origin = motion.transform_point3(DVec3::new(0.0, 0.0, -T / 2.0));
            let frame = Frame {
                origin,
                u: motion.transform_vector3(DVec3::X),
                v: motion.transform_vector3(DVec3::Y),
                n: motion.transform_vector3(DVec3::Z),
            };
            plates.push(Plate {
                kind: PlateKind::Inherent,
                thickness: T,
                frame,
                area: f.area(),
                polygon: f.clone(),
                shapes: vec![k as u32],
            });
        }
        (flat, plates)
    }

    proptest! {
        #![proptest_config(ProptestConfig { cases: 24, .. ProptestConfig::default() })]
        #[test]
        fn developing_and_folding_back_returns_every_facet_and_nothing_overlaps(
            widths in prop::collection::vec(20.0f64..60.0, 2..7),
            tapers in prop::collection::vec(-4.0f64..4.0, 7),
            turns in prop::collection::vec(prop_oneof![-1.2f64..-0.1, 0.1f64..1.2], 7),
        ) {
            let (_, plates) = chain(&widths, &tapers, &turns);
            let bends = crate::bends::compute(
                &plates, None, crate::Bending::Style(BendStyle::Heat), Material::Acrylic, (1e4, 1e4),
            ).expect("on the grid");
            prop_assert_eq!(bends.parts.len(), 1, "{:?}", bends.refused);
            let part = &bends.parts[0];
            prop_assert_eq!(part.members.len(), plates.len());
            // Folding back: a facet's corners, laid flat and placed by the member's flat
            // frame, are where they were in the model.
            for m in &part.members {
                let plate = &plates[m.plate as usize];
                let frame = m.flat_frame();
                for q in &plate.polygon.outer {
                    let model = plate.frame.to_model(q.extend(T / 2.0));
                    let flat = m.to_flat(T, model);
                    let back = frame.to_model(flat.extend(T / 2.0));
                    prop_assert!((back - model).length() < 0.01);
                }
            }
            // Laid flat, the facets only overlap by the bend deductions along their edges.
            let developed: Vec<Polygon> = part.members.iter().map(|m| {
                m.place.apply_polygon(&m.local(&plates[m.plate as usize].polygon))
            }).collect();
            let union = platener_geom::boolean::union_all(&developed).expect("grid");
            prop_assert_eq!(union.len(), 1);
            for i in 0..developed.len() {
                for j in i + 1..developed.len() {
                    let shared = platener_geom::boolean::intersection(
                        std::slice::from_ref(&developed[i]), std::slice::from_ref(&developed[j]),
                    ).expect("grid");
                    let bend = part.bends.iter().find(|b| b.members.contains(&i) && b.members.contains(&j));
                    // Neighbours overlap by a strip one bend deduction wide along their edge.
                    let allowed = bend.map_or(0.01, |b| b.zone.deduction() * (70.0 + 10.0 * b.zone.deduction()) + 0.05);
                    let overlap = total_area(&shared);
                    prop_assert!(overlap <= allowed, "{} and {} overlap by {} > {}", i, j, overlap, allowed);
                }
            }
        }
    }
}

#[test]
fn a_style_the_material_cannot_take_is_named_in_a_warning() {
    let settings = Settings {
        bending: crate::Bending::Style(crate::plan::BendStyle::Heat),
        ..Settings::default()
    };
    let state = run_plate(tube(12, 50.0, 60.0, 3.0), settings);
    assert!(state.bends.as_ref().expect("the step ran").parts.is_empty());
    let warned = state
        .records
        .iter()
        .flat_map(|r| &r.warnings)
        .any(|w| w.message.contains("a heat bend does not work in 3 mm wood"));
    assert!(warned);
}

#[test]
fn the_joints_step_holds_a_sound_bent_part_and_leaves_its_bends_without_fingers() {
    let state = run_plate(tube(12, 50.0, 60.0, 3.0), Settings::default());
    let plates = &state.plates.as_ref().expect("the step ran").plates;
    let bends = state.bends.as_ref().expect("the step ran");
    assert_eq!(bends.parts.len(), 1);
    let joints = state.joints.as_ref().expect("the step ran");
    assert_eq!(joints.held_bends, [0], "{:?}", joints.refused_bends);
    assert!(joints.refused_bends.is_empty());
    // The joints step's outlines are the ones computed with the bends left without fingers:
    // 12 plates, 11 bends without fingers and one seam with them.
    let settings = crate::joints::settings_for(&state.settings);
    let (fresh, _) = crate::joints::compute_except(plates, &settings, &bends.unjointed()).expect("on the grid");
    assert_eq!(joints.outlines, fresh.outlines);
    assert_eq!(joints.connections.len(), 1);
    assert_eq!(joints.connections[0].plates, fresh.connections[0].plates);
    let (all, _) = crate::joints::compute_except(plates, &settings, &Default::default()).expect("on the grid");
    assert_eq!(
        all.connections.len(),
        12,
        "without the bends every edge of the ring is jointed"
    );
    // The parts step merged the held part: one bent part of 12 segments.
    let parts = &state.parts.as_ref().expect("the step ran").parts;
    assert_eq!(parts.len(), 1);
    assert_eq!(parts[0].segments.len(), 12);
}

mod orders {
    //! The easiest-first comparator over turns that differ only by rounding (a cup beside its
    //! saucer made a tolerance comparator panic: "does not correctly implement a total order").

    use proptest::prelude::*;

    proptest! {
        #![proptest_config(ProptestConfig { cases: 64, .. ProptestConfig::default() })]
        #[test]
        fn near_equal_turns_sort_without_panic_into_a_consistent_order(
            base in 0.0f64..3.0,
            jitter in prop::collection::vec((-3e-6f64..3e-6, 1.0f64..100.0), 2..60),
        ) {
            let keys: Vec<(f64, f64)> = jitter.iter().map(|&(d, l)| (base + d, l)).collect();
            let order = super::super::easiest_first(&keys);
            let mut seen = order.clone();
            seen.sort_unstable();
            prop_assert_eq!(seen, (0..keys.len()).collect::<Vec<_>>());
            // Sorted by the integer turn key, then longest first: a total order.
            for w in order.windows(2) {
                let (a, b) = (keys[w[0]], keys[w[1]]);
                let (ka, kb) = (super::super::turn_key(a.0), super::super::turn_key(b.0));
                prop_assert!(ka < kb || (ka == kb && (a.1 > b.1 || (a.1 == b.1 && w[0] < w[1]))));
            }
        }
    }
}

/// The arc of a fillet: tangent to both mid-planes at the setback, its radius
/// setback / tan(turn / 2), its middle on the bisector (a right-angle corner at the origin,
/// walls along +x and +y, setback 10: radius 10, centre (10, 10), middle at 10 − 5√2).
#[test]
fn a_fillet_arc_is_tangent_to_both_walls_at_its_setback() {
    let c = crate::bends::Candidate {
        plates: [0, 1],
        point: DVec3::ZERO,
        axis: DVec3::Z,
        span: (0.0, 40.0),
        reach: (0.0, 40.0),
        into: [DVec3::X, DVec3::Y],
        depth: [100.0, 60.0],
        enclosed: std::f64::consts::FRAC_PI_2,
        gap: 10.0,
        facets: Vec::new(),
    };
    let arc = super::fillet::Arc::of(&c, 10.0);
    assert!((arc.radius - 10.0).abs() < 1e-9);
    assert!(arc.centre.distance(DVec3::new(10.0, 10.0, 0.0)) < 1e-9);
    for (k, tangent) in [DVec3::new(10.0, 0.0, 0.0), DVec3::new(0.0, 10.0, 0.0)]
        .into_iter()
        .enumerate()
    {
        assert!((arc.centre + arc.ends[k] * arc.radius).distance(tangent) < 1e-9);
        assert!(arc.ends[k].dot(c.into[k]).abs() < 1e-9, "perpendicular to its wall");
    }
    let middle = arc.centre + arc.direction(0.5) * arc.radius;
    let m = 10.0 - 5.0 * std::f64::consts::SQRT_2;
    assert!(middle.distance(DVec3::new(m, m, 0.0)) < 1e-9);
}
