//! Crush ribs in the slots of a shelf's sides (issue 34): each slot a tab passes through
//! loses exactly the ribs' area, keeps its width between them, and the assembly still
//! passes `verify` (the ribs' overlap with the tabs is intended).

use super::ribs::{BASE, HEIGHT, TWO_RIBS};
use crate::convert::convert;
use crate::method::MethodKind;
use crate::plan::{JointKind, Plan};
use crate::settings::Settings;
use crate::{Cancel, Source};
use platener_fixtures::samples;

/// Two sides and three shelves between them, 3 mm sheets; the plate method's plan.
fn shelf(ribs: bool) -> Plan {
    let (w, d, t) = (80.0, 60.0, 3.0);
    let zs = [0.0, 20.0, 20.0 + t, 60.0, 60.0 + t, 100.0, 100.0 + t, 120.0];
    let model = samples::voxels(&[0.0, t, w - t, w], &[0.0, d], &zs, |i, _, k| i != 1 || k % 2 == 1);
    let mut s = Settings {
        thicknesses: vec![t],
        ..Settings::default()
    };
    s.cut.nest_tries = 1;
    s.cut.crush_ribs = ribs;
    let c = convert(
        MethodKind::Plate,
        Source::triangles("shelf", model),
        s,
        &Cancel::default(),
    )
    .expect("converts");
    c.bundle().expect("a plan").plan.clone()
}

fn holes_of(plan: &Plan, id: u32) -> Vec<platener_geom::Polygon> {
    let part = plan.parts.iter().find(|p| p.id == id).expect("a part");
    part.holes
        .iter()
        .map(|h| {
            let mut p = platener_geom::Polygon::new(h.clone());
            p.normalize_orientation();
            p
        })
        .collect()
}

#[test]
fn slots_get_ribs_of_the_stated_size_and_the_plan_still_verifies() {
    let (plain, ribbed) = (shelf(false), shelf(true));
    assert!(ribbed.settings.cut.crush_ribs && !plain.settings.cut.crush_ribs);
    let tees: Vec<[u32; 2]> = plain
        .joints
        .iter()
        .filter(|j| j.kind == JointKind::Slot)
        .map(|j| j.parts)
        .collect();
    assert!(
        !tees.is_empty(),
        "the shelf has tab-and-slot joints: {:?}",
        plain.joints
    );
    let rib_area = 0.5 * BASE * HEIGHT;
    let mut ribbed_slots = 0;
    for part in &plain.parts {
        let (before, after) = (holes_of(&plain, part.id), holes_of(&ribbed, part.id));
        assert_eq!(before.len(), after.len(), "part {}: the same slots", part.id);
        for (b, a) in before.iter().zip(&after) {
            let (lo, hi) = platener_geom::polygon::bounds_of(b.outer.iter().copied());
            let (long, wide) = ((hi - lo).max_element(), (hi - lo).min_element());
            if b.outer.len() == a.outer.len() {
                assert!((a.area() - b.area()).abs() < 1e-6, "part {}: a hole changed", part.id);
                continue;
            }
            // A slot: a rectangle as long as a tab and as wide as the shelf is thick.
            assert_eq!(b.outer.len(), 4, "part {}: {:?}", part.id, b.outer);
            assert!((wide - 3.0).abs() < 0.01, "part {}: slot {wide} mm wide", part.id);
            let per_wall = if long >= TWO_RIBS { 2 } else { 1 };
            assert_eq!(a.outer.len(), 4 + 2 * per_wall * 3, "part {}: {:?}", part.id, a.outer);
            let lost = b.area() - a.area();
            assert!(
                (lost - 2.0 * per_wall as f64 * rib_area).abs() < 1e-3,
                "part {}: the slot lost {lost} mm²",
                part.id
            );
            // The ribs' tips: each HEIGHT in from its wall, the slot's box unchanged.
            let (alo, ahi) = platener_geom::polygon::bounds_of(a.outer.iter().copied());
            assert!(alo.distance(lo) < 1e-6 && ahi.distance(hi) < 1e-6);
            let across = if (hi - lo).x < (hi - lo).y { 0 } else { 1 };
            let tips = a.outer.iter().filter(|p| {
                let w = p.to_array()[across];
                let (w0, w1) = (lo.to_array()[across], hi.to_array()[across]);
                (w - w0 - HEIGHT).abs() < 1e-3 || (w1 - w - HEIGHT).abs() < 1e-3
            });
            assert_eq!(tips.count(), 2 * per_wall, "part {}: {:?}", part.id, a.outer);
            ribbed_slots += 1;
        }
    }
    assert!(ribbed_slots >= 3, "{ribbed_slots} slots ribbed");
    let v = crate::verify::verify(&ribbed, None);
    assert!(v.passed(), "{:?}", v.problems);
    // The outlines (not the slots) are the same plan.
    for (p, q) in plain.parts.iter().zip(&ribbed.parts) {
        assert_eq!(p.outline, q.outline, "part {}", p.id);
    }
}
