use glam::DVec2;
use platener_geom::{Polygon, boolean};
use proptest::prelude::*;

use super::*;

/// The kerf the parts of these tests are cut with, mm.
const KERF: f64 = 0.2;

use platener_geom::polygon::rect;

use crate::plan::samples::flat_part as part;

/// A 60 × 30 plate whose top edge (y = 30) has three fingers 3 mm deep cut into it.
fn fingered() -> Polygon {
    let mut outer = vec![DVec2::new(0.0, 0.0), DVec2::new(60.0, 0.0), DVec2::new(60.0, 30.0)];
    for i in (0..3).rev() {
        let x1 = 10.0 + 15.0 * f64::from(i) + 10.0;
        outer.extend([
            DVec2::new(x1, 30.0),
            DVec2::new(x1, 27.0),
            DVec2::new(x1 - 10.0, 27.0),
            DVec2::new(x1 - 10.0, 30.0),
        ]);
    }
    outer.push(DVec2::new(0.0, 30.0));
    Polygon::new(outer)
}

/// Every stroke point of every label lies inside the part minus holes, at least the clearance
/// of its size (less 1 µm of grid rounding) away from the boundary: checked with a boolean.
fn assert_inside(part: &Part, labels: &PartLabels) {
    for b in &labels.boxes {
        let quad = Polygon::new(b.corners(clearance(b.size, KERF) - 1e-3).to_vec());
        let outside = boolean::difference(&[quad], std::slice::from_ref(&part.polygon)).expect("grid");
        let area: f64 = outside.iter().map(Polygon::area).sum();
        assert!(
            area < 1e-6,
            "label {:?} of part {} leaves the part by {area} mm²",
            b.text,
            part.id
        );
    }
}

#[test]
fn every_part_gets_its_number_inside_it() {
    let with_hole = Polygon {
        outer: rect(0.0, 0.0, 40.0, 40.0),
        holes: vec![rect(10.0, 10.0, 30.0, 30.0)],
    };
    let parts = [part(1, Polygon::new(rect(0.0, 0.0, 80.0, 50.0))), part(12, with_hole)];
    let (labels, warnings) = label_parts(&parts, LabelMode::Parts, KERF);
    assert!(warnings.is_empty(), "{:?}", warnings);
    for (p, l) in parts.iter().zip(&labels.parts) {
        assert_eq!(l.boxes.len(), 1);
        assert_eq!(l.boxes[0].text, p.id.to_string());
        assert_inside(p, l);
    }
    // The ring part has a 10 mm wide band: its number is smaller than the big plate's.
    assert_eq!(labels.parts[0].boxes[0].size, 8.0);
    assert!(labels.parts[1].boxes[0].size < 8.0);
}

#[test]
fn a_fingered_edge_gets_its_connection_number_beyond_the_fingers() {
    let mut p = part(4, fingered());
    p.edge_labels = vec![EdgeLabel {
        connection: 7,
        segment: [DVec2::new(60.0, 30.0), DVec2::new(0.0, 30.0)],
    }];
    let (labels, warnings) = label_parts(std::slice::from_ref(&p), LabelMode::Edges, KERF);
    assert!(warnings.is_empty(), "{:?}", warnings);
    let l = &labels.parts[0];
    assert_eq!(l.boxes.len(), 2);
    let edge = &l.boxes[1];
    assert_eq!(edge.text, "#7");
    assert_inside(&p, l);
    // Below the finger roots (y = 27), and near the edge: within two thicknesses and the text.
    let corners = edge.corners(0.0);
    let top = corners.iter().map(|c| c.y).fold(f64::MIN, f64::max);
    assert!(top < 27.0 && top > 27.0 - 2.0 * 3.0 - 4.0 - 1.0, "{corners:?}");
    // Readable: the baseline runs left to right although the edge runs right to left.
    assert_eq!(edge.direction, DVec2::X);
    assert!(l.marks.iter().all(|m| m.kind == MarkKind::Label));
}

#[test]
fn labels_that_cannot_fit_are_skipped_with_a_warning() {
    let mut p = part(3, Polygon::new(rect(0.0, 0.0, 2.0, 40.0)));
    p.edge_labels = vec![EdgeLabel {
        connection: 1,
        segment: [DVec2::new(0.0, 0.0), DVec2::new(2.0, 0.0)],
    }];
    let (labels, warnings) = label_parts(&[p], LabelMode::Edges, KERF);
    assert!(labels.parts[0].boxes.is_empty());
    assert_eq!(warnings.len(), 2);
    assert_eq!(
        label_parts(&[part(1, fingered())], LabelMode::None, KERF).0.parts[0]
            .marks
            .len(),
        0
    );
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(24))]

    /// Whatever the rectangle and its hole, labels stay inside the part minus the hole.
    #[test]
    fn labels_never_leave_the_part(w in 8.0..120.0f64, h in 8.0..80.0f64, hx in 0.1..0.9f64, hy in 0.1..0.9f64, hs in 0.05..0.6f64) {
        let (cx, cy, r) = (w * hx, h * hy, w.min(h) * hs / 2.0);
        let hole = rect((cx - r).max(1.0), (cy - r).max(1.0), (cx + r).min(w - 1.0), (cy + r).min(h - 1.0));
        let mut p = part(5, Polygon { outer: rect(0.0, 0.0, w, h), holes: vec![hole] });
        p.edge_labels = vec![EdgeLabel { connection: 2, segment: [DVec2::new(0.0, 0.0), DVec2::new(w, 0.0)] },
                             EdgeLabel { connection: 3, segment: [DVec2::new(w, 0.0), DVec2::new(w, h)] }];
        let (labels, warnings) = label_parts(std::slice::from_ref(&p), LabelMode::Edges, KERF);
        p.polygon.normalize_orientation();
        assert_inside(&p, &labels.parts[0]);
        prop_assert_eq!(labels.parts[0].boxes.len() + warnings.len(), 3);
    }
}

/// A 90 × 30 part bent along x = `at` with a zone `width` wide (no marks, so only the zone
/// can keep the labels off it).
fn bent(at: f64, width: f64) -> Part {
    let mut p = part(6, Polygon::new(rect(0.0, 0.0, 90.0, 30.0)));
    p.kind = crate::plan::PartKind::Bent;
    p.bends = vec![Bend {
        line: [DVec2::new(at, 0.0), DVec2::new(at, 30.0)],
        angle_deg: 90.0,
        style: crate::plan::BendStyle::LivingHinge,
        pattern: crate::plan::HingePattern::Lattice,
        width,
        segments: [0, 1],
    }];
    p
}

/// The smallest distance of `b`'s corners to the vertical line x = `at`, signed by side: the
/// box is clear of the zone when all corners lie on one side at least half the width away.
fn clear_of_zone(b: &TextBox, at: f64, width: f64) -> bool {
    let xs = b.corners(0.0).map(|c| c.x - at);
    xs.iter().all(|x| *x >= width / 2.0) || xs.iter().all(|x| *x <= -width / 2.0)
}

#[test]
fn a_part_number_keeps_out_of_the_bend_zone() {
    // Without the bend the number sits at the first deepest point; the zone goes there.
    let flat = part(6, Polygon::new(rect(0.0, 0.0, 90.0, 30.0)));
    let (free, _) = label_part(&flat, LabelMode::Parts, KERF);
    let c = free.boxes[0].corners(0.0);
    let at = (c[0].x + c[2].x) / 2.0;
    assert!(!clear_of_zone(&free.boxes[0], at, 12.0), "{:?}", free.boxes);
    let p = bent(at, 12.0);
    let (l, warnings) = label_part(&p, LabelMode::Parts, KERF);
    assert!(warnings.is_empty(), "{warnings:?}");
    assert_eq!(l.boxes.len(), 1);
    assert!(clear_of_zone(&l.boxes[0], at, 12.0), "{:?}", l.boxes);
    assert_inside(&p, &l);
    // The zone's quadrilateral is the strip: 12 wide, crossing the whole part.
    let zone = bend_zone(&p.bends[0], 100.0);
    assert!(
        zone.iter()
            .all(|c| ((c.x - at).abs() - 6.0).abs() < 1e-12 && (c.y < 0.0 || c.y > 30.0))
    );
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(16))]

    /// Wherever the bend and however wide its zone, no label lands in it.
    #[test]
    fn labels_never_land_in_a_bend_zone(at in 5.0..85.0f64, width in 1.0..20.0f64) {
        let mut p = bent(at, width);
        p.edge_labels = vec![EdgeLabel { connection: 4, segment: [DVec2::new(0.0, 0.0), DVec2::new(90.0, 0.0)] }];
        let (l, _) = label_part(&p, LabelMode::Edges, KERF);
        prop_assert!(!l.boxes.is_empty(), "at least one side has room for the number");
        for b in &l.boxes {
            prop_assert!(clear_of_zone(b, at, width), "{:?}", b);
        }
    }
}

#[test]
fn parts_without_room_for_their_number_make_one_warning() {
    assert_eq!(super::id_ranges(&[3, 5, 6, 7, 9, 12, 13]), "3, 5–7, 9, 12–13");
}
