//! Joints checked on whole assemblies: the parts (each plate's outline with its fingers, tabs
//! and slots, extruded by its thickness and placed by its frame) must neither share volume nor
//! leave gaps, and together must rebuild the model.

use glam::{DVec2, DVec3};
use platener_geom::Polygon;
use platener_geom::slab::Slab;

use super::tests::{
    in_slab, mesh_of, model_volume, parts, plates_with, shared_volume, shared_volumes, volume, worst_overlap,
};
use super::*;
use crate::assembly::Inside;
use platener_fixtures::samples;

/// Distance from `p` to the part (a prism): `sqrt(dz² + d2²)`, where `dz` is how far the local
/// z lies outside `[0, thickness]` and `d2` is 0 inside the outline, else the distance to its
/// boundary.
fn distance(part: &Slab, p: DVec3) -> f64 {
    let l = part.frame.to_local(p);
    let dz = (-l.z).max(l.z - part.thickness).max(0.0);
    let d2 = part.polygon.distance_to(DVec2::new(l.x, l.y));
    dz.hypot(d2)
}

/// The widest gap (mm) between the parts within `reach` of the joint `line`, in a model that
/// is a prism along that line (the method is described on the roof test below). Whether a
/// point is inside the model depends only on where it lies across the line, so that is decided
/// once per cross-section point, at the line's middle.
fn widest_gap(model: &Inside, parts: &[Slab], line: [DVec3; 2], reach: f64, measured: impl Fn(DVec3) -> bool) -> f64 {
    let step = 0.1;
    let axis = (line[1] - line[0]).normalize();
    let e2 = axis.any_orthonormal_vector();
    let e3 = axis.cross(e2);
    let mid = (line[0] + line[1]) / 2.0;
    let len = line[0].distance(line[1]);
    let n = (2.0 * reach / step) as usize;
    let (mut worst, mut kept): (f64, usize) = (0.0, 0);
    for i in 0..n {
        for j in 0..n {
            let a = -reach + (i as f64 + 0.5137) * step;
            let b = -reach + (j as f64 + 0.4729) * step;
            let across = e2 * a + e3 * b;
            if a.hypot(b) > reach || !model.contains(mid + across) {
                continue;
            }
            for k in 0..(len / step) as usize {
                kept += 1;
                let p = line[0] + axis * ((k as f64 + 0.5311) * step) + across;
                // Most points lie in a part: only the others are measured.
                if measured(p) && !parts.iter().any(|s| in_slab(s, p)) {
                    worst = worst.max(parts.iter().map(|s| distance(s, p)).fold(f64::INFINITY, f64::min));
                }
            }
        }
    }
    assert!(kept > 0, "no point of the model near the joint");
    2.0 * worst
}

#[test]
fn table_top_on_two_legs_is_tee_from_below() {
    let (w, d, h, inset, t) = (120.0, 60.0, 70.0, 10.0, 3.0);
    let model = samples::table(w, d, h, inset, t);
    let plates = plates_with(model.clone(), t);
    assert_eq!(plates.len(), 3, "top and two legs");
    let (joints, warnings) = compute(&plates, &JointSettings::default()).expect("grid");
    assert_eq!(joints.connections.len(), 2, "{:?}", joints.connections);
    assert!(warnings.is_empty(), "{:?}", warnings);
    let top = plates
        .iter()
        .position(|p| p.frame.n.z.abs() > 0.99)
        .expect("a flat top");
    let mut tabs = 0;
    for c in &joints.connections {
        assert_eq!(c.kind, ConnectionKind::Tee, "{c:?}");
        assert!(c.plates.contains(&(top as u32)), "every leg meets the top: {c:?}");
        assert!(c.segments % 2 == 1 && c.segments >= 3, "{c:?}");
        // The top owns both ends and every other segment; the leg owns the ones between.
        tabs += c.segments / 2;
    }
    // The top passes through: its outline is unchanged and the legs' tabs go through slots
    // (holes); the legs grow by their tabs.
    let outline = &joints.outlines[top];
    assert_eq!(outline.outer.len(), 4, "the top's outline is unchanged");
    assert_eq!(outline.holes.len(), tabs, "one slot per tab");
    assert!(outline.area() < plates[top].area - 1.0);
    for (i, p) in plates.iter().enumerate().filter(|&(i, _)| i != top) {
        assert!(joints.outlines[i].area() > p.area + 1.0, "leg {i} has tabs");
    }
    let parts = parts(&plates, &joints);
    let overlap = worst_overlap(&parts);
    assert!(overlap < 1e-6, "parts overlap by {overlap} mm²");
    let (total, expected) = (volume(&parts), model_volume(&model));
    assert!((expected - (w * d * t + 2.0 * t * d * (h - t))).abs() < 1e-6);
    eprintln!("table: {tabs} tabs, parts {total:.3} mm³, model {expected:.3} mm³, overlap {overlap:.2e} mm²");
    assert!((total - expected).abs() < 1e-3 * expected, "{total} vs {expected}");
}

/// Whether `p` lies between the two faces of `plate`'s (unbounded) layer.
fn in_layer(plate: &Plate, p: DVec3) -> bool {
    let z = plate.frame.to_local(p).z;
    z > 0.0 && z < plate.thickness
}

/// Roofs (two 3 mm plates meeting in a mitred ridge, `samples::roof` with pitch
/// (180° − enclosed) / 2) at enclosed angles of 60°, 90°, 120° and 150°.
///
/// How the gap is measured ([`widest_gap`]): points on a 0.1 mm grid aligned with the
/// connection's `line` (offset off round numbers: 0.5137, 0.4729 and 0.5311 of a step), within
/// 2·t of the line and over its whole length, are kept when they are inside the model (ray
/// parity through its closed mesh); for each the distance to the nearest part is
/// `sqrt(dz² + d2²)` in the part's local coordinates, `dz` how far z lies outside
/// [0, thickness], `d2` 0 inside the outline, else the distance to its boundary. A point in a
/// gap `w` wide is at most `w / 2` from a part, so the widest gap is twice the largest distance.
///
/// *Along the joint* means where the two plates' layers cross (the thesis' parallelogram),
/// where fingers and notches interleave: no gap there may be wider than 0.2 mm. Outside it, at
/// the mitre's outer and inner edges, a laser's cuts (square to the sheet) cannot follow a
/// mitre: each finger either leaves a notch or would collide with the other plate. Platener
/// never lets parts collide, so away from 90° the mitre's edge shows notches up to
/// t·|cot α| wide (α the enclosed angle; a bevelling laser head could close them); that bound
/// is asserted too. The parts must share (sampled) volume under 0.5 % of their own.
///
/// Measured (run 50 mm, depth 40 mm, t = 3 mm): in the joint 0 mm at every angle; at the
/// mitre's edge 0 at 90°, 1.57 mm at 60° and 120° (bound 1.73 mm), 3.3 mm at 150° (bound
/// 5.2 mm); nothing shared.
#[test]
fn corners_at_60_90_120_150_degrees_have_no_gap_wider_than_0_2_mm() {
    let t = 3.0;
    for enclosed in [60.0, 90.0, 120.0, 150.0f64] {
        let model = samples::roof(50.0, (180.0 - enclosed) / 2.0, 40.0, t);
        let plates = plates_with(model.clone(), t);
        assert_eq!(plates.len(), 2, "{enclosed}°");
        let (joints, _) = compute(&plates, &JointSettings::default()).expect("grid");
        assert_eq!(joints.connections.len(), 1, "{enclosed}°: {:?}", joints.connections);
        let c = &joints.connections[0];
        assert_eq!(c.kind, ConnectionKind::Corner, "{enclosed}°");
        let parts = parts(&plates, &joints);
        let mesh = mesh_of(&model);
        let inside = Inside::new(&mesh.vertices, &mesh.triangles);
        let in_joint = widest_gap(&inside, &parts, c.line, 2.0 * t, |p| {
            plates.iter().all(|plate| in_layer(plate, p))
        });
        let at_mitre = widest_gap(&inside, &parts, c.line, 2.0 * t, |_| true);
        let shared = shared_volume(&parts[0], &parts[1]);
        let total = volume(&parts);
        eprintln!(
            "{enclosed}°: widest gap in the joint {in_joint:.3} mm, at the mitre {at_mitre:.3} mm, shared {shared:.3} mm³ of {total:.1} mm³"
        );
        assert!(in_joint < 0.2, "{enclosed}°: gap {in_joint} mm in the joint");
        let bound = t / enclosed.to_radians().tan().abs();
        assert!(
            at_mitre < bound.max(0.2),
            "{enclosed}°: notch {at_mitre} mm over {bound} mm"
        );
        assert!(
            shared < 0.005 * total,
            "{enclosed}°: shared {shared} mm³ of {total} mm³"
        );
    }
}

/// One cross-section of an assembly across a joint line (areas in mm², sampled on a grid).
#[derive(Debug)]
struct Section {
    /// Model that no part holds.
    unowned: f64,
    /// Held by two parts or more.
    twice: f64,
    /// Part outside the model.
    outside: f64,
    /// The parts holding the line's own point.
    centre: Vec<usize>,
}

/// The cross-section of `parts` and `model` across `line`, `at` mm along it, over a square
/// `2·reach` wide centred on the line, sampled every `step` mm (cell centres off round numbers).
fn section(model: &Inside, parts: &[Slab], line: [DVec3; 2], at: f64, reach: f64, step: f64) -> Section {
    let axis = (line[1] - line[0]).normalize();
    let e2 = axis.any_orthonormal_vector();
    let e3 = axis.cross(e2);
    let origin = line[0] + axis * at;
    let n = (2.0 * reach / step) as usize;
    let cell = step * step;
    let mut out = Section {
        unowned: 0.0,
        twice: 0.0,
        outside: 0.0,
        centre: (0..parts.len()).filter(|&k| in_slab(&parts[k], origin)).collect(),
    };
    for i in 0..n {
        for j in 0..n {
            let p = origin + e2 * (-reach + (i as f64 + 0.5137) * step) + e3 * (-reach + (j as f64 + 0.4729) * step);
            let owners = parts.iter().filter(|s| in_slab(s, p)).count();
            match (model.contains(p), owners) {
                (true, 0) => out.unowned += cell,
                (false, 1..) => out.outside += cell,
                _ => {}
            }
            if owners > 1 {
                out.twice += cell;
            }
        }
    }
    out
}

/// Three plates meeting on one line (a "Y", 120° apart, 3 mm thick): one plate per arm, three
/// corner joints cut as one row of fingers in which the plates take turns: in each finger one
/// plate takes the whole junction (the triangle where all three layers cross) and the other
/// two end against its faces. Nothing is held twice and nothing sticks out of the model.
///
/// Square cuts cannot fill a Y: every cross-section of a plate is a rectangle, and the best
/// three rectangles that neither overlap nor leave the model still miss √3/4·t² (3.90 mm² for
/// t = 3, found by a brute-force search over where each arm ends): the notch in front of each
/// of the two plates that give way. The test asserts that bound.
///
/// Four arms (a "+") are found as two plates passing through each other (opposite arms are
/// one plate, as in `samples::crossing_plates`) with a halved joint, which fills the crossing
/// exactly.
#[test]
fn three_and_four_plates_on_one_line_share_no_volume() {
    let (arm_len, t, depth) = (40.0, 3.0, 50.0);
    for (arms, plates_found, kind, missing) in [
        (3, 3, ConnectionKind::Corner, 3f64.sqrt() / 4.0 * t * t),
        (4, 2, ConnectionKind::Cross, 0.0),
    ] {
        let model = samples::star(arms, arm_len, t, depth);
        let expected = Polygon::new(samples::star_profile(arms, arm_len, t)).area() * depth;
        assert!((model_volume(&model) - expected).abs() < 1e-6 * expected);
        let plates = plates_with(model.clone(), t);
        assert_eq!(plates.len(), plates_found, "{arms} arms");
        let (joints, warnings) = compute(&plates, &JointSettings::default()).expect("grid");
        assert_eq!(joints.connections.len(), plates_found * (plates_found - 1) / 2);
        assert!(
            joints.connections.iter().all(|c| c.kind == kind),
            "{:?}",
            joints.connections
        );
        assert!(warnings.is_empty(), "{:?}", warnings);
        let parts = parts(&plates, &joints);
        let total = volume(&parts);
        for ((i, j), shared) in shared_volumes(&parts) {
            assert!(
                shared < 1e-3 * total,
                "{arms} arms: parts {i} and {j} share {shared} mm³"
            );
        }
        assert!(
            (total - (expected - missing * depth)).abs() < 1e-3 * expected,
            "{arms} arms: parts {total} mm³, model {expected} mm³"
        );
        let mesh = mesh_of(&model);
        let inside = Inside::new(&mesh.vertices, &mesh.triangles);
        let line = joints.connections[0].line;
        let mut owners_of_centre = Vec::new();
        for k in 0..14 {
            let at = (k as f64 + 0.5) * depth / 14.0;
            let s = section(&inside, &parts, line, at, 2.0 * t, 0.08);
            assert!(s.twice < 0.01 && s.outside < 0.01, "{arms} arms at {at} mm: {s:?}");
            assert!(s.unowned < missing + 0.05, "{arms} arms at {at} mm: {s:?}");
            assert_eq!(
                s.centre.len(),
                1,
                "{arms} arms at {at} mm: the line belongs to one part"
            );
            owners_of_centre.extend(s.centre);
        }
        owners_of_centre.sort_unstable();
        owners_of_centre.dedup();
        if kind == ConnectionKind::Corner {
            assert_eq!(owners_of_centre, vec![0, 1, 2], "each plate takes the junction in turn");
        }
    }
}

mod uneven_y {
    use proptest::prelude::*;

    use super::*;

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(8))]

        /// Three plates on one line at uneven angles (each gap 70°–160°): the fingers take
        /// turns (each plate holds the line somewhere), nothing is held twice and nothing sticks
        /// out of the model, in every cross-section.
        #[test]
        fn three_plates_at_any_angles_take_turns_without_collisions(g1 in 70.0f64..160.0, g2 in 70.0f64..160.0) {
            prop_assume!((70.0..160.0).contains(&(360.0 - g1 - g2)));
            let (t, depth) = (3.0, 30.0);
            let angles = [0.0, g1, g1 + g2];
            let model = samples::fan(&angles, 30.0, t, depth);
            let plates = plates_with(model.clone(), t);
            prop_assert_eq!(plates.len(), 3);
            let (joints, warnings) = compute(&plates, &JointSettings::default()).expect("grid");
            prop_assert_eq!(joints.connections.len(), 3, "{:?}", joints.connections);
            prop_assert!(warnings.is_empty(), "{:?}", warnings);
            let parts = parts(&plates, &joints);
            let mesh = mesh_of(&model);
            let inside = Inside::new(&mesh.vertices, &mesh.triangles);
            let c = &joints.connections[0];
            let fingers = c.segments;
            let mut owners = Vec::new();
            for k in 0..fingers {
                let at = (k as f64 + 0.5) * depth / fingers as f64;
                let s = section(&inside, &parts, c.line, at, 2.0 * t, 0.1);
                eprintln!("{angles:?} at {at:.1}: {s:?}");
                prop_assert!(s.twice < 0.05 && s.outside < 0.05, "at {} mm: {:?}", at, s);
                prop_assert!(s.unowned < t * t, "at {} mm: {:?}", at, s);
                owners.extend(s.centre);
            }
            owners.sort_unstable();
            owners.dedup();
            prop_assert_eq!(owners, vec![0, 1, 2]);
        }
    }
}

/// A V standing on a board (walls at 60°/120°, 45°/90°, 70°/140° from the board, all 3 mm): the
/// board, split in two by the walls' faces, is one plate again; both walls meet it at a T and
/// each other at a corner, all on one line. The board and the walls take turns holding the
/// line: a wall's tab goes through the board where it does. Nothing is held twice
/// and nothing sticks out of the model.
#[test]
fn v_standing_on_a_board_takes_turns_on_the_line() {
    let (t, depth) = (3.0, 30.0);
    for walls in [[60.0, 120.0], [45.0, 90.0], [70.0, 140.0]] {
        let model = samples::fan(&[0.0, walls[0], walls[1], 180.0], 30.0, t, depth);
        let plates = plates_with(model.clone(), t);
        assert_eq!(plates.len(), 3, "{walls:?}: the board and two walls");
        let board = plates.iter().position(|p| p.frame.n.y.abs() > 0.999).expect("a board");
        let (joints, warnings) = compute(&plates, &JointSettings::default()).expect("grid");
        assert!(warnings.is_empty(), "{:?}", warnings);
        let mut kinds: Vec<_> = joints.connections.iter().map(|c| c.kind).collect();
        kinds.sort_by_key(|k| *k != ConnectionKind::Corner);
        assert_eq!(
            kinds,
            [ConnectionKind::Corner, ConnectionKind::Tee, ConnectionKind::Tee],
            "{walls:?}"
        );
        let parts = parts(&plates, &joints);
        let mesh = mesh_of(&model);
        let inside = Inside::new(&mesh.vertices, &mesh.triangles);
        let c = &joints.connections[0];
        let mut owners = Vec::new();
        for k in 0..c.segments {
            let at = (k as f64 + 0.5) * depth / c.segments as f64;
            let s = section(&inside, &parts, c.line, at, 2.0 * t, 0.1);
            assert!(s.twice < 0.05 && s.outside < 0.05, "{walls:?} at {at} mm: {s:?}");
            owners.extend(s.centre);
        }
        owners.sort_unstable();
        owners.dedup();
        assert_eq!(owners, [0, 1, 2], "{walls:?}: each plate holds the line somewhere");
        assert!(
            joints.outlines[board].area() < plates[board].area - 10.0,
            "{walls:?}: the walls' tabs pass through the board"
        );
    }
}

/// Roofs closer to flat than 150° (155°, 160°, 164°; 3 mm): the layers' crossing grows
/// without bound towards 180° (17.5 mm at 160°), and a finger that long runs straight on where
/// the surface bends, sticking out of the model on one face and leaving a wedge empty on the
/// other. So fingers reach no further than at 150°: the plates grow by no more than they do at
/// 150°, and in every cross-section less of the model is left empty and less sticks out than at
/// 150° (measured at 164°: 4.75 and 4.16 mm², against 7.79 and 7.79 at 150° and 14.05 and 14.05
/// uncapped), and nothing is held twice.
#[test]
fn shallow_corners_keep_the_150_degree_finger_length() {
    let t = 3.0;
    let measure = |enclosed: f64| {
        let model = samples::roof(50.0, (180.0 - enclosed) / 2.0, 40.0, t);
        let plates = plates_with(model.clone(), t);
        assert_eq!(plates.len(), 2, "{enclosed}°");
        let (joints, _) = compute(&plates, &JointSettings::default()).expect("grid");
        assert_eq!(joints.connections.len(), 1, "{enclosed}°");
        let c = &joints.connections[0];
        assert_eq!(c.kind, ConnectionKind::Corner, "{enclosed}°");
        assert!((c.angle_deg - enclosed).abs() < 1e-6, "{enclosed}°: {}", c.angle_deg);
        let grow = (0..2)
            .flat_map(|i| joints.outlines[i].outer.iter().map(move |v| (i, *v)))
            .map(|(i, v)| plates[i].polygon.distance_to(v))
            .fold(0.0, f64::max);
        let parts = parts(&plates, &joints);
        let mesh = mesh_of(&model);
        let inside = Inside::new(&mesh.vertices, &mesh.triangles);
        let sections: Vec<Section> = (0..c.segments)
            .map(|k| {
                let at = (k as f64 + 0.5) * 40.0 / c.segments as f64;
                section(&inside, &parts, c.line, at, 12.0, 0.05)
            })
            .collect();
        eprintln!("{enclosed}°: grows {grow:.2} mm, {sections:?}");
        (grow, sections)
    };
    let (grow_150, at_150) = measure(150.0);
    let worst = |s: &[Section], f: fn(&Section) -> f64| s.iter().map(f).fold(0.0, f64::max);
    for enclosed in [155.0, 160.0, 164.0] {
        let (grow, sections) = measure(enclosed);
        assert!(
            grow < grow_150 + 0.01,
            "{enclosed}°: grows {grow} mm, at 150° {grow_150}"
        );
        for s in &sections {
            assert!(s.twice < 0.01, "{enclosed}°: {s:?}");
            assert!(s.outside < worst(&at_150, |s| s.outside) + 0.05, "{enclosed}°: {s:?}");
            assert!(s.unowned < worst(&at_150, |s| s.unowned) + 0.05, "{enclosed}°: {s:?}");
        }
    }
}

/// A 12 × 8 low-poly ball (40 mm radius, 3 mm sheets; corners at 147° to 163°): only facets
/// along an edge are joined (not the four that touch a facet at each vertex), no facet falls
/// apart, and the parts neither share volume nor stick out of the ball.
#[test]
fn low_poly_ball_keeps_every_facet_whole() {
    let t = 3.0;
    let model = samples::sphere(DVec3::ZERO, 40.0, 12, 8);
    let plates = plates_with(model.clone(), t);
    let (joints, warnings) = compute(&plates, &JointSettings::default()).expect("grid");
    assert!(!warnings.iter().any(|w| w.contains("pieces")), "{:?}", warnings);
    // Each facet has at most its own edges' neighbours (4 on a quad, fewer where plate finding
    // trimmed the poles).
    let mut per_plate = vec![0; plates.len()];
    for c in &joints.connections {
        assert!(c.angle_deg > 140.0, "{c:?}");
        per_plate[c.plates[0] as usize] += 1;
        per_plate[c.plates[1] as usize] += 1;
    }
    assert!(per_plate.iter().all(|&n| (1..=5).contains(&n)), "{per_plate:?}");
    let parts = parts(&plates, &joints);
    let total = volume(&parts);
    let shared: f64 = shared_volumes(&parts).into_iter().map(|(_, v)| v).sum();
    eprintln!("parts {total:.0} mm³, shared {shared:.1} mm³");
    assert!(shared < 0.001 * total, "parts share {shared} of {total} mm³");
    // Parts lie inside the ball: at most a plate's layer of volume more than its surface holds.
    let mesh = mesh_of(&model);
    let area: f64 = mesh.areas.iter().sum();
    assert!(total < area * t, "parts {total} mm³, surface {area} mm² × {t} mm");
}
