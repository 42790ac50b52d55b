//! The corpus sweep: every file in `../shared/corpus` either converts through the foundation
//! steps or fails with its specific message; broken files get warnings that name their
//! defect; nothing panics. Skipped (with a message) when the corpus is absent.

use std::path::{Path, PathBuf};

use platener::inspect::inspect;
use platener::pipeline::WarningKind;
use platener::{Cancel, Settings, Source};
use platener_geom::grid::STEP;
use platener_geom::polygon::perimeter;

/// The corpus, or `None` after saying why these tests skip (CI fails instead).
fn corpus() -> Option<PathBuf> {
    platener_fixtures::samples::shared_corpus()
        .map_err(|m| eprintln!("{m}"))
        .ok()
}

/// Files that must fail, with a piece of the message they must give.
const FAILS: &[(&str, &str)] = &[
    ("openscad_invalid_vertex.stl", "line 89"),
    ("openscad_too_many_vertices.stl", "line 93: facet with 4 vertices"),
    ("openscad_empty_0_bytes.stl", "empty"),
    ("trimesh_empty_binary_header_only.stl", "no triangles"),
    ("numpy_stl_incomplete_ascii.stl", "line 5"),
    (
        "numpy_stl_end_solid_with_space.stl",
        "line 9: unexpected text 'end solid test.stl'",
    ),
];

/// Files that convert with a warning naming their defect.
const WARNS: &[(&str, WarningKind)] = &[
    ("admesh_block_flipped_facet.stl", WarningKind::FlippedFaces),
    ("admesh_block_missing_facet.stl", WarningKind::OpenEdges),
    ("openscad_nonmanifold_open_cube.stl", WarningKind::OpenEdges),
    ("openscad_zero_area_triangle.stl", WarningKind::DegenerateFaces),
    ("radial_engine_pushrods_nonmanifold.stl", WarningKind::DuplicateFaces),
    ("trimesh_triangle_soup.stl", WarningKind::OpenEdges),
    (
        "numpy_stl_halfdonut_solid_header_trailing_byte.stl",
        WarningKind::Reader,
    ),
    (
        "lasercut_fingerjoint_examples_assembly.stl",
        WarningKind::NonManifoldEdges,
    ),
    ("stanford_bunny_99_lowpoly.stl", WarningKind::Units),
];

#[test]
fn every_corpus_file_converts_or_fails_with_its_message() {
    let Some(dir) = corpus() else { return };
    let files = platener_fixtures::samples::stl_files(&dir);
    assert!(files.len() >= 50, "expected the 53-file corpus, found {}", files.len());
    let mut converted = 0;
    for path in &files {
        let name = path.file_name().and_then(|n| n.to_str()).expect("utf-8 name");
        let result = std::panic::catch_unwind(|| {
            inspect(
                Source::File(path.clone()),
                Settings::default(),
                &Cancel::default(),
                true,
            )
        });
        let result = result.unwrap_or_else(|_| panic!("{name}: panicked"));
        match (FAILS.iter().find(|(f, _)| *f == name), result) {
            (Some((_, want)), Err(e)) => {
                let msg = e.to_string();
                assert!(msg.contains(want), "{name}: message {msg:?} lacks {want:?}");
                assert!(msg.contains(name), "{name}: message {msg:?} does not name the file");
            }
            (Some(_), Ok(_)) => panic!("{name}: should have failed"),
            (None, Err(e)) => panic!("{name}: failed: {e}"),
            (None, Ok(r)) => {
                converted += 1;
                if let Some((_, kind)) = WARNS.iter().find(|(f, _)| *f == name) {
                    assert!(
                        r.warnings().any(|w| w.kind == *kind),
                        "{name}: no {kind:?} warning in {:?}",
                        r.warnings().collect::<Vec<_>>()
                    );
                }
                assert!(r.shapes > 0, "{name}: no planar shapes");
            }
        }
    }
    assert_eq!(converted, files.len() - FAILS.len());
}

/// Without welding (which can fold triangles over each other), the planar shapes of a closed
/// model partition its surface exactly, up to projection within 1° and the 1 µm grid.
#[test]
fn shapes_cover_the_surface_of_closed_models() {
    let Some(dir) = corpus() else { return };
    let settings = Settings {
        weld: platener::Weld::Off,
        ..Settings::default()
    };
    let (mut checked, mut open) = (0, 0);
    for path in platener_fixtures::samples::stl_files(&dir) {
        let name = path.file_name().and_then(|n| n.to_str()).expect("utf-8 name");
        let source = Source::File(path.clone());
        let state = match platener::inspect::run_foundation(source, settings.clone(), &Cancel::default()) {
            Ok((state, _)) => state,
            // Only the files that must fail may fail (the test above checks their messages).
            Err(e) => {
                assert!(FAILS.iter().any(|(f, _)| *f == name), "{name}: {e}");
                continue;
            }
        };
        let mesh = state.mesh.expect("mesh");
        if !mesh.health.closed {
            open += 1;
            continue;
        }
        checked += 1;
        // Groups are within 1° of their plane, so projected areas shrink by at most cos 1°;
        // the 1 µm grid adds at most perimeter × 1 µm.
        let shapes = state.shapes.expect("shapes");
        let total: f64 = shapes.shapes.iter().map(|s| s.area).sum();
        let grid_slack: f64 = shapes
            .shapes
            .iter()
            .map(|s| {
                let p = &s.polygon;
                (perimeter(&p.outer) + p.holes.iter().map(|h| perimeter(h)).sum::<f64>()) * STEP
            })
            .sum();
        let low = mesh.surface_area * 1f64.to_radians().cos() - grid_slack;
        let high = mesh.surface_area + grid_slack;
        assert!(
            total >= low && total <= high,
            "{}: shapes {total} mm², surface {} mm²",
            path.display(),
            mesh.surface_area
        );
    }
    eprintln!("{checked} closed models checked, {open} open ones passed over");
    assert!(
        checked >= 20,
        "only {checked} closed models were checked (23 of the 53-file corpus are closed)"
    );
}

#[test]
fn two_solids_in_one_ascii_file_are_both_read() {
    let Some(dir) = corpus() else { return };
    let r = inspect(
        Source::File(dir.join("broken/assimp_two_solids_one_file.stl")),
        Settings::default(),
        &Cancel::default(),
        false,
    )
    .expect("reads");
    assert_eq!((r.solids, r.triangles_read), (2, 2));
}

fn plates_of(dir: &Path, file: &str, thicknesses: &[f64]) -> platener::inspect::PlatesReport {
    let settings = Settings {
        thicknesses: thicknesses.to_vec(),
        ..Settings::default()
    };
    let r = inspect(Source::File(dir.join(file)), settings, &Cancel::default(), true).expect("converts");
    r.plates.expect("plates were asked for")
}

#[test]
fn plycutter_test_object_offered_6mm_gives_its_two_sheets() {
    let Some(dir) = corpus() else { return };
    let p = plates_of(&dir, "plates/plycutter_PlyTest0.1.stl", &[6.0]);
    assert_eq!(p.plates.len(), 2);
    assert!(
        p.plates
            .iter()
            .all(|x| x.thickness == 6.0 && x.kind == platener::plates::PlateKind::Inherent)
    );
}

#[test]
fn tray_bottom_is_one_plate_with_its_23_holes() {
    let Some(dir) = corpus() else { return };
    let p = plates_of(&dir, "plates/tray_bottom_14in_3.2mm_sheet.stl", &[3.0]);
    let inherent: Vec<_> = p
        .plates
        .iter()
        .filter(|x| x.kind == platener::plates::PlateKind::Inherent)
        .collect();
    assert_eq!(inherent.len(), 1);
    assert_eq!(inherent[0].holes, 23);
    // 14 in square, one 1/8 in sheet: the plate is the sheet minus its holes.
    assert!(inherent[0].area > 109_000.0 && inherent[0].area < 355.6 * 355.6);
}

#[test]
fn a_thin_curved_wall_does_not_become_hundreds_of_slivers() {
    let Some(dir) = corpus() else { return };
    let p = plates_of(&dir, "other/bird_water_feeder_cup.stl", &[3.0]);
    assert!(p.plates.len() < 20, "{} plates", p.plates.len());
    let slivers = p
        .coverage
        .shapes
        .iter()
        .filter(|s| matches!(s.rejected, Some(platener::plates::Rejection::Sliver { .. })))
        .count();
    assert!(slivers > 50, "slivers are rejected and reported ({slivers})");
    // Every plate kept is at least as wide on average as it is thick: for a strip of width w,
    // twice its area over its perimeter is w.
    let plates = plates_with_outlines(&dir, "other/bird_water_feeder_cup.stl", 3.0);
    assert_eq!(plates.plates.len(), p.plates.len());
    for x in &plates.plates {
        let rings = std::iter::once(&x.polygon.outer).chain(&x.polygon.holes);
        let perimeter: f64 = rings.map(|r| perimeter(r)).sum();
        let width = 2.0 * x.polygon.area() / perimeter;
        assert!(
            width >= x.thickness,
            "a plate {width:.2} mm wide on average, {} thick",
            x.thickness
        );
    }
}

/// The plates (with their outlines) of a corpus file for one thickness.
fn plates_with_outlines(dir: &Path, file: &str, thickness: f64) -> std::sync::Arc<platener::plates::Plates> {
    let settings = Settings {
        thicknesses: vec![thickness],
        ..Settings::default()
    };
    let mut state = platener::State::new(Source::File(dir.join(file)), settings);
    platener::pipeline::run(&platener::pipeline::PLATE, &mut state, &Cancel::default()).expect("converts");
    state.plates.expect("plates")
}
