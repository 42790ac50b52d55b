use std::collections::BTreeMap;

use glam::{DVec2, DVec3};
use platener_geom::slab::Slab;
use proptest::prelude::*;

use super::*;
use crate::plan::format::{
    FORMAT, Method, Plan, PlanBend, PlanJoint, PlanSegment, PlanSettings, PlanSheet, PlanSource, SheetPlacement,
    VERSION,
};
use crate::plan::{CutSettings, JointKind};

const T: f64 = 3.0;
const WIDE: f64 = 30.0;
const ZONE: f64 = 10.0;

/// The radius of the neutral axis of a 90° bend of the test zone.
fn radius_90() -> f64 {
    ZONE / std::f64::consts::FRAC_PI_2
}

fn l_part() -> Part {
    sample_strip(1, T, WIDE, &[40.0, 40.0], &[90.0], ZONE)
}

/// The pieces of a strip ordered along the flat x axis: segment, its zone's slices, the next
/// segment… (the pieces partition the flat strip along x).
fn along_x(pieces: &[Slab]) -> Vec<&Slab> {
    let mut order: Vec<&Slab> = pieces.iter().collect();
    order.sort_by(|a, b| a.polygon.bounds().0.x.total_cmp(&b.polygon.bounds().0.x));
    order
}

/// The largest distance, at mid-thickness, between where two consecutive pieces put the flat
/// points of their shared edge; also that they do share an edge in the flat frame.
fn worst_gap(pieces: &[Slab]) -> f64 {
    let order = along_x(pieces);
    let mut worst: f64 = 0.0;
    for pair in order.windows(2) {
        let (end, start) = (pair[0].polygon.bounds().1.x, pair[1].polygon.bounds().0.x);
        assert!(
            (end - start).abs() < 1e-3,
            "flat pieces {end} and {start} do not share an edge"
        );
        for y in [0.0, WIDE / 2.0, WIDE] {
            let q = DVec3::new(end, y, T / 2.0);
            worst = worst.max(pair[0].frame.to_model(q).distance(pair[1].frame.to_model(q)));
        }
    }
    worst
}

fn volume(pieces: &[Slab]) -> f64 {
    pieces.iter().map(Slab::volume).sum()
}

fn model_box(pieces: &[Slab]) -> (DVec3, DVec3) {
    pieces.iter().map(Slab::model_bounds).fold(
        (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)),
        |(lo, hi), (a, b)| (lo.min(a), hi.max(b)),
    )
}

#[test]
fn the_l_is_its_segments_and_slices_meeting_edge_to_edge() {
    let part = l_part();
    let pieces = part.pieces().expect("bends");
    // Two segments and a 90° zone of slices turning at most 5° each.
    assert!(pieces.len() >= 2 + 18, "{}", pieces.len());
    let gap = worst_gap(&pieces);
    assert!(gap <= 0.01, "consecutive pieces {gap} mm apart");
    let want = part.polygon.area() * T;
    assert!(
        (volume(&pieces) - want).abs() <= 0.01 * want,
        "{} vs {want}",
        volume(&pieces)
    );
    // The L: horizontal arm on z = 0..3 from x = 0, vertical arm's outer face at
    // x = 40 + R + 1.5, rising to 1.5 + R + 40 (the neutral axis' arc ends there).
    let r = radius_90();
    let (lo, hi) = model_box(&pieces);
    let want_lo = DVec3::new(0.0, 0.0, 0.0);
    let want_hi = DVec3::new(40.0 + r + T / 2.0, WIDE, T / 2.0 + r + 40.0);
    assert!(lo.distance(want_lo) < 0.02 && hi.distance(want_hi) < 0.02, "{lo} {hi}");
}

#[test]
fn the_slices_follow_the_neutral_arc() {
    let part = l_part();
    let pieces = part.pieces().expect("bends");
    let r = radius_90();
    let centre = DVec3::new(40.0, 0.0, T / 2.0 + r);
    for slice in &pieces[2..] {
        let (lo, hi) = slice.polygon.bounds();
        let mid = slice.frame.to_model(DVec3::new((lo.x + hi.x) / 2.0, 5.0, T / 2.0));
        let off = DVec2::new(mid.x - centre.x, mid.z - centre.z).length();
        assert!((off - r).abs() < 1e-6, "slice middle {off} from the axis, radius {r}");
    }
}

#[test]
fn a_u_of_three_bends_and_a_ring_rebuild_edge_to_edge() {
    let u = sample_strip(2, T, WIDE, &[40.0, 30.0, 20.0, 40.0], &[90.0, 45.0, 45.0], ZONE);
    let pieces = u.pieces().expect("bends");
    assert!(worst_gap(&pieces) <= 0.01);
    // The U's last segment comes back antiparallel to the first.
    let n_last = u.segments[3].frame.n;
    assert!(n_last.distance(-u.segments[0].frame.n) < 1e-9, "{n_last}");
    let want = u.polygon.area() * T;
    assert!((volume(&pieces) - want).abs() <= 0.01 * want);
    let ring = ring_part();
    let pieces = ring.pieces().expect("bends");
    assert!(worst_gap(&pieces) <= 0.01);
    // Closed: the last segment's end face rests on the first segment's start face.
    let last = &ring.segments[3];
    let end = last.polygon.bounds().1.x;
    let corner = last.frame.to_model(DVec3::new(end, 0.0, T));
    assert!(corner.distance(DVec3::new(0.0, 0.0, 0.0)) < 1e-9, "{corner}");
}

/// A square ring of four segments and three 90° bends; the fourth corner is a seam where the
/// last segment's inner face meets the first segment's start face.
fn ring_part() -> Part {
    let (a, b, r) = (40.0, 40.0, radius_90());
    let lengths = [a, b, a - r + T / 2.0, T / 2.0 + r + b];
    sample_strip(1, T, WIDE, &lengths, &[90.0, 90.0, 90.0], ZONE)
}

#[test]
fn segments_that_disagree_with_their_bend_are_an_error() {
    let mut part = l_part();
    part.segments[1].frame.origin.x += 0.2;
    match part.pieces() {
        Err(BentError::Mismatch {
            bend: 0,
            segment: 1,
            distance,
            ..
        }) => assert!(distance > 0.15, "{distance}"),
        other => panic!("{other:?}"),
    }
    let mut part = l_part();
    part.bends[0].segments = [0, 5];
    assert!(matches!(part.pieces(), Err(BentError::Segments { .. })));
    let mut part = l_part();
    part.bends[0].width = 0.0;
    assert!(matches!(part.pieces(), Err(BentError::Bend { .. })));
}

#[test]
fn a_plate_is_one_piece() {
    let part = crate::plan::samples::rectangle(3, 50.0, 20.0);
    let pieces = part.pieces().expect("flat");
    assert_eq!(pieces.len(), 1);
    assert_eq!(pieces[0].frame, part.frame);
}

/// plan.json's part of a library part (segments and bends as the exporter writes them).
fn plan_part(p: &Part) -> crate::plan::PlanPart {
    crate::plan::PlanPart {
        id: p.id,
        kind: p.kind,
        thickness: p.thickness,
        outline: p.polygon.outer.clone(),
        holes: p.polygon.holes.clone(),
        transform: p.frame.matrix(),
        sheet: SheetPlacement {
            index: 0,
            x: 10.0,
            y: 10.0,
            rotation: 0.0,
        },
        marks: Vec::new(),
        merged: p.merged.clone(),
        segments: p
            .segments
            .iter()
            .map(|s| PlanSegment {
                outline: s.polygon.outer.clone(),
                holes: s.polygon.holes.clone(),
                transform: s.frame.matrix(),
            })
            .collect(),
        bends: p
            .bends
            .iter()
            .map(|b| PlanBend {
                line: b.line,
                angle: b.angle_deg,
                style: b.style,
                pattern: b.pattern,
                width: b.width,
                segments: b.segments,
            })
            .collect(),
    }
}

/// A plan of one bent part whose plates (ids 101…) are joined by bend joints, plus `extra`
/// joints.
fn plan_of(mut part: Part, extra: &[PlanJoint]) -> Plan {
    part.merged = (0..part.segments.len() as u32).map(|k| 101 + k).collect();
    let mut joints: Vec<PlanJoint> = (0..part.bends.len() as u32)
        .map(|k| PlanJoint {
            parts: [101 + k, 102 + k],
            kind: JointKind::Bend,
            angle: part.bends[k as usize].angle_deg,
            label: k + 1,
        })
        .collect();
    joints.extend_from_slice(extra);
    Plan {
        format: FORMAT.into(),
        version: VERSION,
        generator: "test".into(),
        source: PlanSource {
            name: "bent".into(),
            triangles: 0,
            bbox_min: [0.0; 3],
            bbox_max: [100.0; 3],
            units: crate::settings::Units::default(),
            scale: 1.0,
        },
        method: Method::Plate,
        settings: PlanSettings {
            thicknesses: vec![T],
            cut: CutSettings::default(),
            method: BTreeMap::new(),
        },
        parts: vec![plan_part(&part)],
        joints,
        sheets: vec![PlanSheet {
            reference_square: None,
            index: 0,
            thickness: T,
            width: 600.0,
            height: 400.0,
            file: "bent.svg".into(),
            legend: None,
        }],
        glued: Vec::new(),
        assembly: Vec::new(),
    }
}

/// The model the L fills: its cross-section (sharp outer corner, inner corner rounded to the
/// bend's inner radius) extruded across its width.
fn l_model() -> crate::mesh::Mesh {
    let r = radius_90();
    let (outer, top) = (40.0 + r + T / 2.0, T / 2.0 + r + 40.0);
    let centre = DVec2::new(40.0, T / 2.0 + r);
    let mut profile = vec![
        DVec2::new(0.0, 0.0),
        DVec2::new(outer, 0.0),
        DVec2::new(outer, top),
        DVec2::new(outer - T, top),
    ];
    for k in 0..=18 {
        let a = -(k as f64) * 5f64.to_radians();
        profile.push(centre + DVec2::new(a.cos(), a.sin()) * (r - T / 2.0));
    }
    profile.push(DVec2::new(0.0, T));
    let w = crate::weld::weld_soup(&platener_fixtures::samples::prism(&profile, WIDE), 0.0);
    crate::mesh::Mesh::build(w.vertices, &w.triangles, 1e-9)
}

#[test]
fn the_l_assembles_as_one_group_covering_its_model_and_verifies() {
    let plan = plan_of(l_part(), &[]);
    let pieces = plan.parts[0].pieces().expect("plan.json bends");
    assert!(worst_gap(&pieces) <= 0.01);
    let model = l_model();
    let v = crate::verify::verify(&plan, Some(&model));
    assert!(v.passed(), "{:?}", v.problems);
    assert_eq!(v.group_parts, vec![vec![1]]);
    assert!(v.interference.is_empty(), "{:?}", v.interference);
    assert!(v.joints_not_meeting.is_empty());
    let want = l_part().polygon.area() * T;
    assert!((v.parts_volume - want).abs() <= 0.01 * want, "{}", v.parts_volume);
    let covered = v.surface_covered.expect("model given");
    eprintln!(
        "L: {} pieces, gap {:.4} mm, volume {:.1} of {want:.1}, covered {covered:.4}, inside {:?}",
        pieces.len(),
        worst_gap(&pieces),
        v.parts_volume,
        v.volume_inside
    );
    assert!(covered >= 0.9, "covered {covered}");
    assert!(v.volume_inside.expect("model given") >= 0.95, "{:?}", v.volume_inside);
}

#[test]
fn a_ring_closed_by_a_seam_and_a_u_verify() {
    let seam = PlanJoint {
        parts: [1, 1],
        kind: JointKind::Finger,
        angle: 90.0,
        label: 9,
    };
    let v = crate::verify::verify(&plan_of(ring_part(), &[seam]), None);
    assert!(v.passed(), "{:?}", v.problems);
    assert_eq!(v.groups, 1);
    let u = sample_strip(1, T, WIDE, &[40.0, 30.0, 20.0, 40.0], &[90.0, 45.0, 45.0], ZONE);
    let v = crate::verify::verify(&plan_of(u, &[]), None);
    assert!(v.passed(), "{:?}", v.problems);
}

#[test]
fn verify_fails_a_bent_part_whose_segments_disagree_and_bends_naming_unknown_plates() {
    let mut plan = plan_of(l_part(), &[]);
    plan.parts[0].segments[1].transform[0][3] += 1.0;
    plan.joints[0].parts = [101, 555];
    let v = crate::verify::verify(&plan, None);
    let checks: Vec<_> = v.failures.iter().map(|f| f.check).collect();
    assert!(checks.contains(&crate::verify::Check::Bends), "{checks:?}");
    assert_eq!(v.joints_not_meeting, vec![1], "a bend naming a plate no part merged");
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]
    #[test]
    fn random_chains_meet_edge_to_edge(
        turns in prop::collection::vec((0.5f64..=90.0, any::<bool>()), 1..5),
        lengths in prop::collection::vec(5.0f64..60.0, 5),
        zone in 1.0f64..25.0,
        thickness in 0.5f64..6.0,
    ) {
        let turns: Vec<f64> = turns.iter().map(|(t, up)| if *up { *t } else { -*t }).collect();
        let part = sample_strip(1, thickness, WIDE, &lengths[..turns.len() + 1], &turns, zone);
        let pieces = part.pieces().expect("a consistent chain bends");
        let order = along_x(&pieces);
        for pair in order.windows(2) {
            let x = pair[0].polygon.bounds().1.x;
            prop_assert!((x - pair[1].polygon.bounds().0.x).abs() < 1e-3);
            for y in [0.0, WIDE] {
                let q = DVec3::new(x, y, thickness / 2.0);
                let d = pair[0].frame.to_model(q).distance(pair[1].frame.to_model(q));
                prop_assert!(d <= 0.01, "{d} mm apart at x = {x}");
            }
        }
        let want = part.polygon.area() * thickness;
        prop_assert!((volume(&pieces) - want).abs() <= 0.01 * want);
    }
}
