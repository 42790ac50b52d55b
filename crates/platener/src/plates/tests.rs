use std::sync::Arc;

use glam::{DMat3, DVec3};
use proptest::prelude::*;

use super::{PlateKind, Plates, Rejection};
use crate::pipeline::{self, Cancel, Source, State};
use crate::read::Triangle;
use crate::settings::{PlateMode, Settings};
use platener_fixtures::samples;

fn plates_of(triangles: Vec<Triangle>, settings: Settings) -> Arc<Plates> {
    let source = Source::triangles("test", triangles);
    let mut state = State::new(source, settings);
    pipeline::run(&pipeline::PLATE, &mut state, &Cancel::default()).expect("converts");
    state.plates.expect("plates step ran")
}

fn with(thicknesses: &[f64]) -> Settings {
    Settings {
        thicknesses: thicknesses.to_vec(),
        ..Settings::default()
    }
}

/// The plate's volume as an axis-aligned box (for axis-aligned test models).
fn box_of(p: &super::Plate) -> (DVec3, DVec3) {
    p.bounds()
}

fn near(a: DVec3, b: DVec3) -> bool {
    (a - b).length() < 1e-3
}

#[test]
fn closed_box_gives_exactly_its_six_walls() {
    let plates = plates_of(samples::closed_box(100.0, 80.0, 60.0, 3.0), with(&[3.0]));
    assert_eq!(plates.plates.len(), 6);
    assert!(
        plates
            .plates
            .iter()
            .all(|p| p.kind == PlateKind::Inherent && p.thickness == 3.0)
    );
    // Each wall is exactly the material between the inner and outer faces.
    let mut boxes: Vec<(DVec3, DVec3)> = plates.plates.iter().map(box_of).collect();
    boxes.sort_by(|a, b| {
        let (a, b) = (a.0, b.0);
        a.x.total_cmp(&b.x).then(a.y.total_cmp(&b.y)).then(a.z.total_cmp(&b.z))
    });
    let want = [
        (DVec3::new(0.0, 3.0, 3.0), DVec3::new(3.0, 77.0, 57.0)),
        (DVec3::new(3.0, 0.0, 3.0), DVec3::new(97.0, 3.0, 57.0)),
        (DVec3::new(3.0, 3.0, 0.0), DVec3::new(97.0, 77.0, 3.0)),
        (DVec3::new(3.0, 3.0, 57.0), DVec3::new(97.0, 77.0, 60.0)),
        (DVec3::new(3.0, 77.0, 3.0), DVec3::new(97.0, 80.0, 57.0)),
        (DVec3::new(97.0, 3.0, 3.0), DVec3::new(100.0, 77.0, 57.0)),
    ];
    for (got, want) in boxes.iter().zip(want) {
        assert!(near(got.0, want.0) && near(got.1, want.1), "{got:?} vs {want:?}");
    }
    // The transform is rigid, and the outline's corners at z = 0 and z = t are exactly the
    // eight corners of the wall's box.
    for p in &plates.plates {
        let (lo, hi) = box_of(p);
        for c in &p.polygon.outer {
            for z in [0.0, p.thickness] {
                let q = p.frame.to_model(DVec3::new(c.x, c.y, z));
                for axis in 0..3 {
                    let on_face = (q[axis] - lo[axis]).abs() < 1e-9 || (q[axis] - hi[axis]).abs() < 1e-9;
                    assert!(on_face, "corner {q} is not a corner of {lo}..{hi}");
                }
            }
        }
        let m = p.frame.matrix();
        let r = DMat3::from_cols_array(&[
            m[0][0], m[1][0], m[2][0], m[0][1], m[1][1], m[2][1], m[0][2], m[1][2], m[2][2],
        ]);
        assert!((r.determinant() - 1.0).abs() < 1e-12);
        assert_eq!(p.polygon.outer.len(), 4);
    }
    assert!(plates.coverage.surface_share > 0.5);
}

#[test]
fn box_offered_6mm_has_no_inherent_plates_and_says_why() {
    let settings = Settings {
        plates: crate::settings::PlateSettings {
            mode: PlateMode::InherentOnly,
            ..Default::default()
        },
        ..with(&[6.0])
    };
    let plates = plates_of(samples::closed_box(100.0, 80.0, 60.0, 3.0), settings);
    assert!(plates.plates.is_empty());
    assert_eq!(plates.coverage.shapes.len(), 12);
    for s in &plates.coverage.shapes {
        match s.rejected {
            Some(Rejection::ThicknessMismatch { distance }) => assert!((distance - 3.0).abs() < 1e-9),
            other => panic!("shape {}: {other:?}", s.shape),
        }
    }
    let why = plates.coverage.shapes[0].rejected.expect("rejected").explain(&[6.0]);
    assert_eq!(why, "opposite face at 3.00 mm but offered 6 mm");
    // In the default mode the faces are extruded instead, never as inherent plates.
    let plates = plates_of(samples::closed_box(100.0, 80.0, 60.0, 3.0), with(&[6.0]));
    assert!(plates.plates.iter().all(|p| p.kind == PlateKind::Extruded));
}

#[test]
fn open_tray_gives_five_plates() {
    let plates = plates_of(samples::open_box(120.0, 80.0, 40.0, 3.0), with(&[3.0]));
    let mut areas: Vec<f64> = plates.plates.iter().map(|p| p.area).collect();
    areas.sort_by(f64::total_cmp);
    assert_eq!(plates.plates.len(), 5, "{areas:?}");
    // Floor 114×74, long walls 114×37, short walls 74×37.
    let want = [74.0 * 37.0, 74.0 * 37.0, 114.0 * 37.0, 114.0 * 37.0, 114.0 * 74.0];
    for (a, w) in areas.iter().zip(want) {
        assert!((a - w).abs() < 1e-3, "{areas:?}");
    }
}

#[test]
fn crossing_plates_are_two_not_four() {
    let plates = plates_of(samples::crossing_plates(100.0, 3.0), with(&[3.0]));
    assert_eq!(
        plates.plates.len(),
        2,
        "{:?}",
        plates.plates.iter().map(|p| p.area).collect::<Vec<_>>()
    );
    assert_eq!(plates.rejoined, 2);
    for p in &plates.plates {
        assert!((p.area - 10_000.0).abs() < 1e-3, "{}", p.area);
    }
}

#[test]
fn shelf_sides_stay_whole_where_the_board_meets_them() {
    let plates = plates_of(samples::shelf(80.0, 120.0, 50.0, 60.0, 3.0), with(&[3.0]));
    let mut areas: Vec<f64> = plates.plates.iter().map(|p| p.area).collect();
    areas.sort_by(f64::total_cmp);
    // The board 74 × 60 between the sides; each side 120 × 60.
    assert_eq!(areas.len(), 3, "{areas:?}");
    assert!((areas[0] - 74.0 * 60.0).abs() < 1e-3, "{areas:?}");
    assert!(
        (areas[1] - 120.0 * 60.0).abs() < 1e-3 && (areas[2] - 120.0 * 60.0).abs() < 1e-3,
        "{areas:?}"
    );
}

#[test]
fn roof_at_40_degrees_gives_two_slanted_plates() {
    let plates = plates_of(samples::roof(50.0, 40.0, 80.0, 3.0), with(&[3.0]));
    assert_eq!(plates.plates.len(), 2);
    for p in &plates.plates {
        let slope = p.frame.n.z.abs().acos().to_degrees();
        assert!((slope - 40.0).abs() < 1e-6, "{slope}");
        assert_eq!(p.thickness, 3.0);
    }
}

#[test]
fn solid_block_becomes_six_extruded_plates_without_overlap() {
    let plates = plates_of(samples::cuboid(DVec3::ZERO, DVec3::new(40.0, 30.0, 20.0)), with(&[3.0]));
    assert_eq!(plates.plates.len(), 6);
    assert!(plates.plates.iter().all(|p| p.kind == PlateKind::Extruded));
    for (i, a) in plates.plates.iter().enumerate() {
        for b in &plates.plates[i + 1..] {
            let shared = a.slab().columns_meeting(&b.slab(), 1e-3).expect("grid");
            assert!(shared.iter().map(|p| p.area()).sum::<f64>() < 1e-6, "plates overlap");
        }
    }
    // Together they are the block's 3 mm hull: 40·30·20 − 34·24·14.
    let volume: f64 = plates.plates.iter().map(|p| p.volume()).sum();
    assert!((volume - (24_000.0 - 34.0 * 24.0 * 14.0)).abs() < 1e-2, "{volume}");
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(12))]
    #[test]
    fn moving_the_model_changes_no_plate(
        ax in (-1.0f64..1.0, -1.0f64..1.0, 0.1f64..1.0),
        angle in 0.0f64..std::f64::consts::TAU,
        shift in (-300.0f64..300.0, -300.0f64..300.0, -300.0f64..300.0),
    ) {
        let model = samples::open_box(120.0, 80.0, 40.0, 3.0);
        let r = DMat3::from_axis_angle(DVec3::new(ax.0, ax.1, ax.2).normalize(), angle);
        let moved: Vec<Triangle> = model.iter().map(|t| t.map(|p| r * p + DVec3::new(shift.0, shift.1, shift.2))).collect();
        let key = |p: &Plates| {
            let mut v: Vec<(f64, f64)> = p.plates.iter().map(|x| (x.area, x.thickness)).collect();
            v.sort_by(|a, b| a.0.total_cmp(&b.0));
            v
        };
        let (a, b) = (key(&plates_of(model, with(&[3.0]))), key(&plates_of(moved, with(&[3.0]))));
        prop_assert_eq!(a.len(), b.len());
        for (x, y) in a.iter().zip(&b) {
            prop_assert!((x.0 - y.0).abs() < 0.5, "{} vs {}", x.0, y.0);
            prop_assert_eq!(x.1, y.1);
        }
    }
}

#[test]
fn the_phone_stand_file_gives_three_plates_and_a_whole_base() {
    // Read from the shipped binary STL (f32 coordinates): the slanted back plate's foot stops
    // short of the base, which must still be rejoined under it.
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/phone-stand.stl");
    let mut state = State::new(Source::File(path), with(&[3.0]));
    pipeline::run(&pipeline::PLATE, &mut state, &Cancel::default()).expect("converts");
    let plates = state.plates.expect("plates");
    let mut areas: Vec<f64> = plates.plates.iter().map(|p| p.area).collect();
    areas.sort_by(f64::total_cmp);
    assert_eq!(areas.len(), 3, "{areas:?}");
    // The base, 82 × 70 (the lip takes the first 3 mm), in one piece.
    assert!((areas[1] - 82.0 * 70.0).abs() < 1.0, "{areas:?}");
}

#[test]
fn a_model_without_plates_gets_a_warning_that_says_why() {
    // A solid 50 mm block offered 3 mm sheets, inherent plates only: every face has its
    // opposite 50 mm away.
    let settings = Settings {
        plates: crate::settings::PlateSettings {
            mode: PlateMode::InherentOnly,
            ..Default::default()
        },
        ..Settings::default()
    };
    let source = Source::triangles("block", samples::cuboid(DVec3::ZERO, DVec3::splat(50.0)));
    let mut state = State::new(source, settings);
    pipeline::run(&pipeline::PLATE, &mut state, &Cancel::default()).expect("converts");
    assert!(state.plates.as_ref().expect("plates").plates.is_empty());
    let plates_step = state.records.iter().find(|r| r.name == "plates").expect("record");
    let why = &plates_step.warnings[0].message;
    assert!(
        why.contains("6 (15000 mm²) have no opposite face within a few sheets behind them"),
        "{why}"
    );
    assert!(why.contains("sheets of 3 mm"), "{why}");
    // A model with plates gets no such warning.
    let mut boxed = State::new(
        Source::triangles("box", samples::closed_box(100.0, 80.0, 60.0, 3.0)),
        Settings::default(),
    );
    pipeline::run(&pipeline::PLATE, &mut boxed, &Cancel::default()).expect("converts");
    assert!(
        boxed
            .records
            .iter()
            .all(|r| r.name != "plates" || r.warnings.is_empty())
    );
}
