use glam::DVec2;
use platener_geom::Polygon;

use super::*;
use crate::kerf::cut_paths;

use platener_geom::polygon::rect;

use crate::plan::samples::flat_part as part;

fn nest_all(parts: &[Part], settings: &CutSettings) -> Nesting {
    nested(parts, settings).expect("nests")
}

fn nested(parts: &[Part], settings: &CutSettings) -> Result<Nesting, PlanError> {
    let (cut, _) = cut_paths(parts, settings.kerf()).expect("cut");
    nest(parts, &cut, settings, &|| false)
}

#[test]
fn two_plates_share_one_sheet_left_to_right() {
    let parts = [
        part(1, Polygon::new(rect(0.0, 0.0, 100.0, 380.0))),
        part(2, Polygon::new(rect(0.0, 0.0, 100.0, 380.0))),
    ];
    let n = nest_all(&parts, &CutSettings::default());
    assert_eq!(n.sheets.len(), 1);
    assert_eq!(n.sheets[0].parts, [1, 2]);
    // Side by side: the second starts one spacing (2 mm) plus the kerf after the first.
    let xs: Vec<f64> = n.placements.iter().map(|p| p.x).collect();
    assert!((xs[0] - 5.1).abs() < 0.06, "{xs:?}");
    assert!((xs[1] - (5.1 + 100.2 + 2.0)).abs() < 0.06, "{xs:?}");
    // Used: up to the second part's cut edge plus the margin, full height.
    let used = (5.0 + 100.2 + 2.0 + 100.2 + 5.0) * 400.0;
    assert!(
        (n.sheets[0].used_area - used).abs() < 0.1 * 400.0,
        "{}",
        n.sheets[0].used_area
    );
}

#[test]
fn a_small_part_goes_into_a_hole() {
    let frame = Polygon {
        outer: rect(0.0, 0.0, 100.0, 100.0),
        holes: vec![rect(20.0, 20.0, 80.0, 80.0)],
    };
    let parts = [part(1, frame), part(2, Polygon::new(rect(0.0, 0.0, 30.0, 30.0)))];
    let settings = CutSettings {
        sheet: SheetSize::Fit,
        ..CutSettings::default()
    };
    let n = nest_all(&parts, &settings);
    assert_eq!(n.sheets.len(), 1);
    let (host, child) = (n.placements[0], n.placements[1]);
    let c = host.apply(DVec2::new(50.0, 50.0));
    let q = child.apply(DVec2::new(15.0, 15.0));
    assert!(c.distance(q) < 30.0, "the small part sits in the hole: {c} vs {q}");
    // Fit: the sheet is the frame plus margins.
    assert!((n.sheets[0].width - 110.2).abs() < 0.1 && (n.sheets[0].height - 110.2).abs() < 0.1);
}

#[test]
fn an_oversized_part_is_an_error_naming_it_its_size_and_what_to_do() {
    let parts = [
        part(1, Polygon::new(rect(0.0, 0.0, 700.0, 100.0))),
        part(2, Polygon::new(rect(0.0, 0.0, 50.0, 50.0))),
    ];
    let err = nested(&parts, &CutSettings::default()).expect_err("too large for 600 × 400");
    let PlanError::Setting { name: "sheet", message } = err else {
        panic!("{err}")
    };
    // 700 × 100 grown by half the kerf on each side and the spacing.
    assert!(message.starts_with("part 1 is 70"), "{message}");
    assert!(
        message.contains("600 × 400 mm") && message.contains("`sheet` to fit"),
        "{message}"
    );
    // With --sheet fit the same parts nest on one sheet wide enough for the long part.
    let fit = CutSettings {
        sheet: SheetSize::Fit,
        ..CutSettings::default()
    };
    let n = nest_all(&parts, &fit);
    assert_eq!(n.sheets.len(), 1);
    assert!(n.sheets[0].width > 700.0);
}

#[test]
fn thicknesses_get_separate_sheets() {
    let mut thick = part(2, Polygon::new(rect(0.0, 0.0, 40.0, 40.0)));
    thick.thickness = 6.0;
    let parts = [part(1, Polygon::new(rect(0.0, 0.0, 40.0, 40.0))), thick];
    let n = nest_all(&parts, &CutSettings::default());
    assert_eq!(n.sheets.len(), 2);
    assert_eq!((n.sheets[0].thickness, n.sheets[1].thickness), (3.0, 6.0));
    assert_eq!((n.placements[0].index, n.placements[1].index), (0, 1));
}

#[test]
fn the_same_seed_gives_the_same_layout() {
    let parts: Vec<Part> = (1..=12)
        .map(|i| {
            let w = 20.0 + f64::from(i * 7 % 50);
            part(i, Polygon::new(rect(0.0, 0.0, w, 150.0 - w)))
        })
        .collect();
    let a = nest_all(&parts, &CutSettings::default());
    let b = nest_all(&parts, &CutSettings::default());
    assert_eq!(a.placements, b.placements);
}

/// Issue 15: a near-zero-width shape (3 µm, below the grid) never reaches jagua-rs, whose f32
/// engine panics on boxes with no extent; the nester names the part instead.
#[test]
fn shapes_jagua_cannot_take_are_refused_not_passed_on() {
    let sliver = [
        DVec2::new(10.0, 10.0),
        DVec2::new(10.000_003, 10.0),
        DVec2::new(10.000_003, 50.0),
    ];
    assert!(shape::to_spolygon(&sliver).is_none());
    assert!(!shape::nestable(&sliver));
    // A wide ring with a zero-width spike is not nestable either; a plain square is.
    let spike = [
        DVec2::new(0.0, 0.0),
        DVec2::new(10.0, 0.0),
        DVec2::new(10.0, 5.0),
        DVec2::new(20.0, 5.0),
        DVec2::new(10.0, 5.0),
        DVec2::new(10.0, 10.0),
        DVec2::new(0.0, 10.0),
    ];
    assert!(!shape::nestable(&spike));
    assert!(shape::nestable(&rect(0.0, 0.0, 10.0, 10.0)));
    // A part whose cut path arrives with nothing to nest (grown by half the spacing, any
    // sliver is the spacing wide; an empty path is not): a typed error naming it, no panic.
    let settings = CutSettings {
        kerf: Some(0.0),
        ..CutSettings::default()
    };
    let parts = [part(7, Polygon::new(rect(0.0, 0.0, 10.0, 10.0)))];
    let cut = CutPaths {
        kerf: 0.0,
        parts: vec![crate::kerf::CutPart {
            id: 7,
            nominal: parts[0].polygon.clone(),
            cut: Polygon::default(),
            slits: Vec::new(),
        }],
    };
    match nest(&parts, &cut, &settings, &|| false) {
        Err(PlanError::Part { part: 7, .. }) => {}
        other => panic!("{other:?}"),
    }
}

/// A host whose hole shrinks (by half the spacing) to slivers microns wide: the regions are
/// skipped, the small part goes on the sheet, nothing panics.
#[test]
fn a_hole_barely_wider_than_the_spacing_hosts_nothing() {
    // A 2.004 mm wide slot: shrunk by 1 mm on each side, 4 µm remain.
    let host = Polygon {
        outer: rect(0.0, 0.0, 100.0, 100.0),
        holes: vec![rect(20.0, 20.0, 22.004, 80.0)],
    };
    let parts = [part(1, host), part(2, Polygon::new(rect(0.0, 0.0, 1.0, 1.0)))];
    let settings = CutSettings {
        kerf: Some(0.0),
        ..CutSettings::default()
    };
    let n = nest_all(&parts, &settings);
    assert_eq!(n.sheets.len(), 1);
    let child = n.placements[1].apply(DVec2::new(0.5, 0.5));
    assert!(
        !(20.0..=22.004).contains(&child.x) || !(20.0..=80.0).contains(&child.y),
        "{child}"
    );
}
