use glam::DVec2;
use platener_geom::Polygon;

use super::*;
use crate::kerf::cut_paths;

use platener_geom::polygon::rect;

use crate::plan::samples::flat_part as part;

/// Each part of `placed` inside `region` and clear of all the others, asked of the collision
/// engine part by part (the same test a fill uses).
pub(crate) fn assert_free(shapes: &[shape::NestShape], placed: &[blf::Placed], region: (DVec2, DVec2)) {
    for (k, p) in placed.iter().enumerate() {
        let mut bin = blf::Bin::rect(region.0, region.1).expect("a bin");
        for (_, q) in placed.iter().enumerate().filter(|(j, _)| *j != k) {
            bin.put(q.clone(), &shapes[q.key]);
        }
        let t = &shapes[p.key].templates[p.template];
        assert!(
            bin.is_free(t, p.pos),
            "part {} overlaps another or leaves the region",
            p.key
        );
    }
}

/// Every corner of each part's outline `ring` (all parts alike) at least `margin` inside its
/// sheet.
fn assert_within_margins(n: &Nesting, ring: &[DVec2], margin: f64) {
    for p in &n.placements {
        let sheet = &n.sheets[p.index as usize];
        for q in ring {
            let at = p.apply(*q);
            assert!(
                at.x >= margin && at.y >= margin && at.x <= sheet.width - margin && at.y <= sheet.height - margin,
                "{at} on {sheet:?}"
            );
        }
    }
}

/// Each sheet's width and height, in order.
fn sheet_sizes(n: &Nesting) -> Vec<(f64, f64)> {
    n.sheets.iter().map(|s| (s.width, s.height)).collect()
}

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

/// The stock list: parts go onto the listed sheets in order, as many as each count allows
/// (the offcut first), every part inside its own sheet's margins; a plan needing more than
/// the stock holds is refused naming the parts left over and `stock`; a part larger than every
/// stock sheet is refused naming the stock.
#[test]
fn parts_go_onto_the_stock_in_order_and_too_few_sheets_are_refused() {
    use crate::plan::stock::parse_stock;
    // Twelve 90 × 90 plates: a 200 × 200 offcut holds 4 (2 × 2 within 5 mm margins).
    let parts: Vec<Part> = (1..=12)
        .map(|id| part(id, Polygon::new(rect(0.0, 0.0, 90.0, 90.0))))
        .collect();
    let with = |stock: &str| CutSettings {
        stock: parse_stock(stock, 10_000.0).expect("valid"),
        ..CutSettings::default()
    };
    let n = nest_all(&parts, &with("3:200x200x1, 3:600x400"));
    let sizes = sheet_sizes(&n);
    assert_eq!(sizes[0], (200.0, 200.0), "the offcut first");
    assert_eq!(n.sheets[0].parts.len(), 4);
    assert!(sizes[1..].iter().all(|&s| s == (600.0, 400.0)));
    assert_eq!(n.sheets.iter().map(|s| s.parts.len()).sum::<usize>(), 12);
    // Every part inside its sheet's margins (the cut path grown by half the kerf included).
    assert_within_margins(&n, &rect(0.0, 0.0, 90.0, 90.0), 5.0);
    // Two offcuts hold 8 of the 12.
    let Err(PlanError::Setting { name, message }) = nested(&parts, &with("3:200x200x2")) else {
        panic!("two offcuts cannot hold twelve plates");
    };
    assert_eq!(name, "stock");
    assert!(
        message.contains("hold 8 of the 12") && message.contains("`stock`"),
        "{message}"
    );
    // A plate larger than every stock sheet.
    let big = [part(1, Polygon::new(rect(0.0, 0.0, 300.0, 90.0)))];
    let Err(PlanError::Setting { name, message }) = nested(&big, &with("3:200x200x2")) else {
        panic!("too large");
    };
    assert_eq!(name, "stock");
    assert!(
        message.contains("part 1") && message.contains("3:200x200x2"),
        "{message}"
    );
    // Another thickness than the stock's goes on sheets of the sheet size.
    let other = with("6:200x200x1");
    let n = nest_all(&parts, &other);
    assert!(n.sheets.iter().all(|s| (s.width, s.height) == (600.0, 400.0)));
}

/// A size listed without a count hands its last sheet to a smaller listed size that holds it,
/// the smallest such with a sheet left.
#[test]
fn the_last_sheet_goes_onto_a_smaller_size_in_stock() {
    use crate::plan::stock::parse_stock;
    let with = |stock: &str| CutSettings {
        stock: parse_stock(stock, 10_000.0).expect("valid"),
        ..CutSettings::default()
    };
    // The large sheets, then the leftovers on one small sheet.
    // Eight 180 × 180 plates: a 600 × 400 sheet holds 6 (3 × 2), the other 2 fit 400 × 200.
    let eight: Vec<Part> = (1..=8)
        .map(|id| part(id, Polygon::new(rect(0.0, 0.0, 180.0, 180.0))))
        .collect();
    let n = nest_all(&eight, &with("3:600x400, 3:400x200, 3:200x200"));
    let sizes = sheet_sizes(&n);
    assert_eq!(
        sizes,
        [(600.0, 400.0), (400.0, 200.0)],
        "the last sheet on the smallest that holds it"
    );
    assert_eq!(n.sheets[1].parts.len(), 2);
    assert_within_margins(&n, &rect(0.0, 0.0, 180.0, 180.0), 5.0);
    // A small kind already used up is not taken; one with a count left is, once.
    let n = nest_all(&eight, &with("3:400x200x1, 3:600x400"));
    let sizes = sheet_sizes(&n);
    assert_eq!(
        sizes,
        [(400.0, 200.0), (600.0, 400.0)],
        "the offcut first, the rest on one large sheet"
    );
    let sixteen: Vec<Part> = (1..=16)
        .map(|id| part(id, Polygon::new(rect(0.0, 0.0, 180.0, 180.0))))
        .collect();
    let n = nest_all(&sixteen, &with("3:600x400, 3:400x200x1"));
    let sizes = sheet_sizes(&n);
    assert_eq!(
        sizes,
        [(600.0, 400.0), (600.0, 400.0), (600.0, 400.0)],
        "4 left: more than the small sheet holds"
    );
}
