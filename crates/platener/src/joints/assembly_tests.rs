//! Joints checked on whole assemblies: the parts (each plate's outline with its fingers, tabs
//! and slots, extruded by its thickness and placed by its frame) must neither share volume nor
//! leave gaps, and together must rebuild the model.

use glam::{DVec2, DVec3};
use platener_geom::Polygon;
use platener_geom::slab::Slab;

use super::tests::{in_slab, mesh_of, model_volume, parts, plates_with, shared_volume, volume, worst_overlap};
use super::*;
use crate::assembly::Inside;
use crate::samples;

/// Distance from `p` to the segment `a`–`b`.
fn to_segment(p: DVec2, a: DVec2, b: DVec2) -> f64 {
    let d = b - a;
    let s = ((p - a).dot(d) / d.length_squared()).clamp(0.0, 1.0);
    p.distance(a + d * s)
}

/// Distance from `p` to the part (a prism): `sqrt(dz² + d2²)`, where `dz` is how far the local
/// z lies outside `[0, thickness]` and `d2` is 0 inside the outline, else the distance to its
/// boundary.
fn distance(part: &Slab, p: DVec3) -> f64 {
    let l = part.frame.to_local(p);
    let dz = (-l.z).max(l.z - part.thickness).max(0.0);
    let q = DVec2::new(l.x, l.y);
    let d2 = if part.polygon.contains(q) {
        0.0
    } else {
        std::iter::once(&part.polygon.outer)
            .chain(&part.polygon.holes)
            .flat_map(|ring| (0..ring.len()).map(|i| to_segment(q, ring[i], ring[(i + 1) % ring.len()])))
            .fold(f64::INFINITY, f64::min)
    };
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
    let joints = compute(&plates, &JointSettings::default()).expect("grid");
    assert_eq!(joints.connections.len(), 2, "{:?}", joints.connections);
    assert!(joints.warnings.is_empty(), "{:?}", joints.warnings);
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
        let joints = compute(&plates, &JointSettings::default()).expect("grid");
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

/// How many parts hold each point of the model near a joint `line` where two or more plates'
/// layers cross: `[unowned, owned once, owned more than once]`, sampled on a 0.1 mm grid
/// within `reach` of the line (model inside-ness decided per cross-section point at the
/// line's middle, as the models are prisms along it).
fn owners_where_layers_cross(
    model: &Inside,
    plates: &[Plate],
    parts: &[Slab],
    line: [DVec3; 2],
    reach: f64,
) -> [usize; 3] {
    let step = 0.1;
    let axis = (line[1] - line[0]).normalize();
    let (e2, mid) = (axis.any_orthonormal_vector(), (line[0] + line[1]) / 2.0);
    let e3 = axis.cross(e2);
    let n = (2.0 * reach / step) as usize;
    let mut counts = [0; 3];
    for i in 0..n {
        for j in 0..n {
            let across = e2 * (-reach + (i as f64 + 0.5137) * step) + e3 * (-reach + (j as f64 + 0.4729) * step);
            let crossing = plates.iter().filter(|p| in_layer(p, mid + across)).count() >= 2;
            if !crossing || !model.contains(mid + across) {
                continue;
            }
            for k in 0..(line[0].distance(line[1]) / step) as usize {
                let p = line[0] + axis * ((k as f64 + 0.5311) * step) + across;
                counts[parts.iter().filter(|s| in_slab(s, p)).count().min(2)] += 1;
            }
        }
    }
    counts
}

/// Three plates meeting on one line (a "Y", 120° apart, 3 mm thick): one plate per arm and
/// three corner joints along the same line whose fingers never collide: no point of the model
/// belongs to two plates and no two parts share volume. Four arms (a "+") are found as two
/// plates passing through each other (opposite arms are one plate, as in
/// `samples::crossing_plates`) with a halved joint, which fills the crossing exactly.
///
/// Measured (arms 40 mm, depth 50 mm): Y: nothing owned twice, parts 17610.3 mm³ against the
/// model's 17805.1 mm³; but 16.6 % of the sampled points where two layers cross near the line
/// belong to no plate: in each finger the owning plate's slab wins both of its connections and
/// the third plate gives up its columns there, and a finger can only fill its own layer. That
/// is a known limit (the closing note of issue 4), so unowned points are printed, not asserted.
#[test]
fn three_and_four_plates_on_one_line_share_no_volume() {
    let (arm_len, t, depth) = (40.0, 3.0, 50.0);
    for (arms, plates_found, kind) in [(3, 3, ConnectionKind::Corner), (4, 2, ConnectionKind::Cross)] {
        let model = samples::star(arms, arm_len, t, depth);
        let expected = Polygon::new(samples::star_profile(arms, arm_len, t)).area() * depth;
        assert!((model_volume(&model) - expected).abs() < 1e-6 * expected);
        let plates = plates_with(model.clone(), t);
        assert_eq!(plates.len(), plates_found, "{arms} arms");
        let joints = compute(&plates, &JointSettings::default()).expect("grid");
        assert_eq!(joints.connections.len(), plates_found * (plates_found - 1) / 2);
        assert!(
            joints.connections.iter().all(|c| c.kind == kind),
            "{:?}",
            joints.connections
        );
        assert!(joints.warnings.is_empty(), "{:?}", joints.warnings);
        let parts = parts(&plates, &joints);
        let total = volume(&parts);
        for i in 0..parts.len() {
            for j in i + 1..parts.len() {
                let shared = shared_volume(&parts[i], &parts[j]);
                assert!(
                    shared < 1e-3 * total,
                    "{arms} arms: parts {i} and {j} share {shared} mm³"
                );
            }
        }
        let mesh = mesh_of(&model);
        let inside = Inside::new(&mesh.vertices, &mesh.triangles);
        let [none, once, more] =
            owners_where_layers_cross(&inside, &plates, &parts, joints.connections[0].line, 2.0 * t);
        eprintln!(
            "{arms} arms: parts {total:.1} mm³, model {expected:.1} mm³; where layers cross: {once} points owned once, {none} unowned, {more} owned twice"
        );
        assert_eq!(more, 0, "{arms} arms: no point belongs to two plates");
        assert!(
            (total - expected).abs() < 0.015 * expected,
            "{arms} arms: {total} vs {expected}"
        );
    }
}
