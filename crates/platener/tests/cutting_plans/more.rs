//! The test strip measured from its SVG, the DXF read by an outside reader (ezdxf), and random
//! part sets nested without overlap.

use std::process::Command;

use platener::fabrication::handwork::joint_seconds;
use platener::glam::DVec2;
use platener::kerf::cut_paths;
use platener::plan::laser::parse_laser;
use platener::plan::samples::{l_shape, rectangle, window};
use platener::plan::{CutSettings, Material, Part, SheetSize};
use platener::sheets::nest;
use platener::swatches::strip::{HOLE_COUNT, SLOT_COUNT, SPIKE_WIDTH, hole_kerf, test_strip};
use platener_geom::{Polygon, boolean};
use proptest::prelude::*;

use super::{OVERLAP_TOL, mixed_parts, run, svg_read};

/// Widths are written with 4 decimals: measured widths are exact to 1e-4 mm.
const WIDTH_TOL: f64 = 1e-4;

fn x_extent(ring: &[DVec2]) -> (f64, f64) {
    ring.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), p| {
        (lo.min(p.x), hi.max(p.x))
    })
}

#[test]
fn the_test_strip_holes_and_spike_have_the_stated_widths() {
    for (t, material) in [(3.0, Material::Wood), (6.0, Material::Acrylic)] {
        let svg = svg_read::parse(&test_strip(t, material).expect("strip").svg());
        let strip = &svg.groups["part-1"];
        // Holes first, then the slot row, the outline last (cut order).
        let n = HOLE_COUNT as usize;
        let mut holes: Vec<(f64, f64)> = strip.cut[..n].iter().map(|r| x_extent(r)).collect();
        // Slot k is drawn for the sheet `t + (k − 9) × 0.05` less the material's kerf.
        let slots: Vec<f64> = strip.cut[n..strip.cut.len() - 1]
            .iter()
            .map(|r| x_extent(r))
            .map(|(lo, hi)| hi - lo)
            .collect();
        assert_eq!(slots.len(), SLOT_COUNT as usize);
        for (k, w) in slots.iter().enumerate() {
            let sheet = t + (k as f64 - 8.0) * 0.05;
            assert!(
                (w - (sheet - material.default_kerf())).abs() < WIDTH_TOL,
                "slot {k}: {w}"
            );
        }
        assert_eq!(holes.len(), HOLE_COUNT as usize);
        // Numbered left to right.
        holes.sort_by(|a, b| a.0.total_cmp(&b.0));
        for (i, (lo, hi)) in holes.iter().enumerate() {
            let n = i as u32 + 1;
            let kerf = (SPIKE_WIDTH - (hi - lo)) / 2.0;
            assert!((kerf - hole_kerf(n)).abs() < WIDTH_TOL, "hole {n}: {kerf}");
            assert!(
                (kerf - 0.025 * f64::from(n - 1)).abs() < WIDTH_TOL,
                "the documented formula"
            );
        }
        // The spike: the two lowest points on screen (largest y) are its tip.
        let key = &svg.groups["part-2"].cut[0];
        let mut tip: Vec<DVec2> = key.clone();
        tip.sort_by(|a, b| b.y.total_cmp(&a.y));
        assert!((tip[0].y - tip[1].y).abs() < WIDTH_TOL);
        assert!(((tip[0].x - tip[1].x).abs() - SPIKE_WIDTH).abs() < WIDTH_TOL);
        assert!(!strip.engrave.is_empty() && svg.red == 1 + (HOLE_COUNT + SLOT_COUNT) as usize + 1);
    }
}

#[test]
fn ezdxf_reads_our_dxf_with_the_same_areas() {
    // `.ci/run` installs ezdxf into its own virtual environment, names its python in
    // PLATENER_PYTHON and sets PLATENER_REQUIRE_EZDXF=1, so CI fails rather than skips.
    let python = std::env::var("PLATENER_PYTHON").unwrap_or_else(|_| "python3".into());
    let probe = Command::new(&python).args(["-c", "import ezdxf"]).output();
    if !probe.is_ok_and(|o| o.status.success()) {
        let message = format!("skipped: {python} with ezdxf is not available (pip install ezdxf)");
        assert!(
            std::env::var_os("PLATENER_REQUIRE_EZDXF").is_none_or(|v| v != "1"),
            "{message}, and PLATENER_REQUIRE_EZDXF=1 requires it"
        );
        eprintln!("{message}");
        return;
    }
    let (_, plan) = run(mixed_parts(), CutSettings::default());
    let sheet = &plan.bundle.plan.sheets[0];
    let dir = tempfile::tempdir().expect("temp dir");
    let path = dir.path().join("sheet.dxf");
    let stem = sheet.file.trim_end_matches(".svg");
    std::fs::write(&path, &plan.bundle.files[&format!("{stem}.dxf")]).expect("write");
    let script = r#"
import sys, ezdxf
doc = ezdxf.readfile(sys.argv[1])
print(doc.dxfversion, doc.header.get("$INSUNITS"))
rings = []
def inside(p, ring):
    x, y, c = p[0], p[1], False
    for i in range(len(ring)):
        (x1, y1), (x2, y2) = ring[i], ring[(i + 1) % len(ring)]
        if (y1 > y) != (y2 > y) and x < x1 + (y - y1) * (x2 - x1) / (y2 - y1):
            c = not c
    return c
for e in doc.modelspace().query("LWPOLYLINE"):
    pts = [(p[0], p[1]) for p in e.get_points("xy")]
    a = sum(pts[i][0] * pts[(i + 1) % len(pts)][1] - pts[(i + 1) % len(pts)][0] * pts[i][1] for i in range(len(pts))) / 2
    print(e.dxf.layer, int(e.closed), abs(a))
    if e.dxf.layer == "CUT" and e.closed:
        rings.append(pts)
# Cut order (issue 34): a ring inside another (a hole in its outline, a part in its hole) is
# cut before it.
for i, outer in enumerate(rings):
    for later in rings[i + 1:]:
        if inside(later[0], outer):
            print("ORDER a ring inside another is cut after it")
"#;
    let out = Command::new(&python)
        .args(["-c", script])
        .arg(&path)
        .output()
        .expect("python runs");
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let text = String::from_utf8(out.stdout).expect("utf-8");
    assert!(!text.contains("ORDER"), "{text}");
    let mut lines = text.lines();
    assert_eq!(lines.next(), Some("AC1015 4"), "R2000, millimetres");
    let mut cut: Vec<f64> = lines
        .filter_map(|l| {
            let f: Vec<&str> = l.split_whitespace().collect();
            (f[0] == "CUT").then(|| {
                assert_eq!(f[1], "1", "cut polylines are closed");
                f[2].parse::<f64>().expect("area")
            })
        })
        .collect();
    let svg = svg_read::parse(std::str::from_utf8(&plan.bundle.files[&sheet.file]).expect("utf-8"));
    let mut expected: Vec<f64> = svg
        .groups
        .values()
        .flat_map(|g| &g.cut)
        .map(|r| platener_geom::polygon::signed_area(r).abs())
        .collect();
    cut.sort_by(f64::total_cmp);
    expected.sort_by(f64::total_cmp);
    assert_eq!(cut.len(), expected.len());
    for (a, b) in cut.iter().zip(&expected) {
        assert!((a - b).abs() < 1e-3 * (1.0 + b), "{a} vs {b}");
    }
}

fn random_part(id: u32, kind: u8, w: f64, h: f64) -> Part {
    match kind % 3 {
        0 => rectangle(id, w, h),
        1 => l_shape(id, w.max(20.0), h.max(20.0), 8.0),
        _ => window(id, w.max(30.0), h.max(30.0), 8.0),
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(6))]

    /// Random sets of rectangles, Ls and frames nest on 300 × 200 sheets with every cut path
    /// inside its sheet and no two overlapping.
    #[test]
    fn random_sets_nest_without_overlap(specs in prop::collection::vec((0u8..3, 5.0..150.0f64, 5.0..120.0f64), 1..14)) {
        let parts: Vec<Part> = specs.iter().enumerate().map(|(i, (k, w, h))| random_part(i as u32 + 1, *k, *w, *h)).collect();
        let settings = CutSettings { sheet: SheetSize::Fixed { width: 300.0, height: 200.0 }, nest_tries: 2, ..CutSettings::default() };
        let (cut, _) = cut_paths(&parts, settings.kerf()).expect("cut");
        let n = nest(&parts, &cut, &settings, &|| false).expect("nests");
        let mut by_sheet: Vec<Vec<Polygon>> = vec![Vec::new(); n.sheets.len()];
        for (i, p) in n.placements.iter().enumerate() {
            let c = &cut.parts[i].cut;
            let moved = |r: &Vec<DVec2>| r.iter().map(|q| p.apply(*q)).collect::<Vec<_>>();
            let placed = Polygon { outer: moved(&c.outer), holes: c.holes.iter().map(moved).collect() };
            let s = &n.sheets[p.index as usize];
            for q in &placed.outer {
                prop_assert!(q.x >= 0.0 && q.y >= 0.0 && q.x <= s.width && q.y <= s.height);
            }
            by_sheet[p.index as usize].push(placed);
        }
        for polys in &by_sheet {
            for (i, a) in polys.iter().enumerate() {
                for b in &polys[i + 1..] {
                    let both = boolean::intersection(std::slice::from_ref(a), std::slice::from_ref(b)).expect("grid");
                    prop_assert!(both.iter().map(Polygon::area).sum::<f64>() <= OVERLAP_TOL);
                }
            }
        }
    }
}

#[test]
fn timings_reach_report_json_only_when_asked() {
    let millis = |settings: CutSettings| {
        let (_, plan) = run(mixed_parts(), settings);
        let r: serde_json::Value = serde_json::from_slice(&plan.bundle.files["report.json"]).expect("json");
        r["steps"]
            .as_array()
            .expect("steps")
            .iter()
            .filter(|s| s.get("millis").is_some())
            .count()
    };
    assert_eq!(millis(CutSettings::default()), 0);
    let timed = CutSettings {
        report_timings: true,
        ..CutSettings::default()
    };
    assert_eq!(millis(timed), 3, "kerf, labels and sheets are timed");
}

/// Issue 34: every sheet lists each part's engraving before its cuts, its slits and holes
/// before its outline (the ring of largest area, last), and the path through the sheet that
/// report.json gives is the one the file draws.
#[test]
fn every_sheet_is_in_cut_order() {
    let (_, plan) = run(mixed_parts(), CutSettings::default());
    let report = &plan.bundle.report;
    for (sheet, measured) in plan.bundle.plan.sheets.iter().zip(&report.sheets) {
        let svg = std::str::from_utf8(&plan.bundle.files[&sheet.file]).expect("utf-8");
        let paths = svg_read::paths_in_order(svg);
        assert!(!paths.is_empty());
        let mut groups: Vec<&str> = paths.iter().map(|p| p.group.as_str()).collect();
        groups.dedup();
        let mut seen = groups.clone();
        seen.sort_unstable();
        seen.dedup();
        assert_eq!(seen.len(), groups.len(), "each part's paths are together: {groups:?}");
        for g in groups {
            let mine: Vec<&svg_read::OrderedPath> = paths.iter().filter(|p| p.group == g).collect();
            let first_red = mine.iter().position(|p| p.red).unwrap_or(mine.len());
            assert!(mine[first_red..].iter().all(|p| p.red), "{g}: engraving before cutting");
            let rings: Vec<f64> = mine
                .iter()
                .filter(|p| p.red && p.closed)
                .map(|p| platener_geom::polygon::signed_area(&p.points).abs())
                .collect();
            if let Some((last, before)) = rings.split_last() {
                assert!(
                    before.iter().all(|a| a < last),
                    "{g}: holes before the outline {rings:?}"
                );
                let last_path = mine.last().expect("a path");
                assert!(last_path.red && last_path.closed, "{g}: the outline is cut last");
            }
        }
        let Walk {
            pierces, cut, travel, ..
        } = walk(&paths);
        assert_eq!(measured.path.pierces, pierces);
        assert!(
            (measured.path.cut_length - cut).abs() < 1e-2,
            "{} vs {cut}",
            measured.path.cut_length
        );
        assert!(
            (measured.path.travel_length - travel).abs() < 1e-2,
            "{} vs {travel}",
            measured.path.travel_length
        );
    }
}

/// What the laser's head does through a sheet's paths in file order: pierces (cut paths
/// started), cut and engraved lengths and the travel between paths from the origin, mm.
struct Walk {
    pierces: usize,
    cut: f64,
    engrave: f64,
    travel: f64,
}

fn walk(paths: &[svg_read::OrderedPath]) -> Walk {
    let mut w = Walk {
        pierces: 0,
        cut: 0.0,
        engrave: 0.0,
        travel: 0.0,
    };
    let mut head = DVec2::ZERO;
    for p in paths {
        w.travel += head.distance(p.points[0]);
        let open: f64 = p.points.windows(2).map(|s| s[0].distance(s[1])).sum();
        let last = *p.points.last().expect("points");
        let (length, end) = if p.closed {
            (open + p.points[0].distance(last), p.points[0])
        } else {
            (open, last)
        };
        head = end;
        if p.red {
            w.pierces += 1;
            w.cut += length;
        } else {
            w.engrave += length;
        }
    }
    w
}

/// Issue 35: each sheet's laser time is its lengths and pierces read from the SVG at the
/// table's speeds for 3 mm wood on the default laser (cut 15, engrave 150, travel 300 mm/s,
/// 0.2 s a pierce); the plan's total adds 2 minutes a sheet, 20 s a part and each joint's time; a laser set to
/// its own cutting speed takes that speed.
#[test]
fn laser_time_is_the_svgs_lengths_at_the_tables_speeds() {
    let seconds = |settings: CutSettings, cut_speed: f64| {
        let (input, plan) = run(mixed_parts(), settings);
        let report = &plan.bundle.report;
        let mut total = 0.0;
        for (sheet, measured) in plan.bundle.plan.sheets.iter().zip(&report.sheets) {
            assert_eq!(sheet.thickness, 3.0);
            let svg = std::str::from_utf8(&plan.bundle.files[&sheet.file]).expect("utf-8");
            let w = walk(&svg_read::paths_in_order(svg));
            assert!(w.pierces > 0 && w.engrave > 0.0, "cuts and labels on {}", sheet.file);
            let by_hand = w.cut / cut_speed + w.engrave / 150.0 + w.travel / 300.0 + w.pierces as f64 * 0.2;
            assert!(
                (measured.laser_seconds - by_hand).abs() < 1e-3,
                "{}: {} s, by hand {by_hand} s",
                sheet.file,
                measured.laser_seconds
            );
            total += by_hand;
        }
        let f = &report.fabrication;
        assert!((f.laser_seconds - total).abs() < 1e-2 && (report.estimated_cutting_seconds - total).abs() < 1e-2);
        let sheets = plan.bundle.plan.sheets.len() as f64;
        assert_eq!(f.sheet_seconds, 120.0 * sheets);
        let joints: f64 = input.joints.iter().map(|j| joint_seconds(j.kind)).sum();
        assert_eq!(f.assembly_seconds, 20.0 * input.parts.len() as f64 + joints);
        assert!((f.total_seconds - (total + 120.0 * sheets + f.assembly_seconds)).abs() < 1e-2);
        total
    };
    let table = seconds(CutSettings::default(), 15.0);
    let own = CutSettings {
        laser: parse_laser("co2, cut=7.5").expect("a laser"),
        ..CutSettings::default()
    };
    let slower = seconds(own, 7.5);
    assert!(slower > table);
}

/// Issue 34: each sheet's LightBurn project, parsed back as XML, has the SVG's paths shape by
/// shape in the same order (within 0.01 mm, y flipped), on the layer of their operation: engrave
/// (1), cut inner (3: slits and holes), cut outer (2: the outline, its part's last ring).
#[test]
fn the_lightburn_project_has_the_svgs_shapes_on_their_layers() {
    let (_, plan) = run(mixed_parts(), CutSettings::default());
    for sheet in &plan.bundle.plan.sheets {
        let svg = std::str::from_utf8(&plan.bundle.files[&sheet.file]).expect("utf-8");
        let paths = svg_read::paths_in_order(svg);
        let stem = sheet.file.trim_end_matches(".svg");
        let text = std::str::from_utf8(&plan.bundle.files[&format!("{stem}.lbrn2")]).expect("utf-8");
        let doc = roxmltree::Document::parse(text).expect("well-formed XML");
        let root = doc.root_element();
        assert_eq!(root.tag_name().name(), "LightBurnProject");
        let layers: Vec<(u32, u32)> = root
            .children()
            .filter(|n| n.has_tag_name("CutSetting"))
            .map(|n| {
                let value = |tag: &str| -> u32 {
                    let node = n.children().find(|c| c.has_tag_name(tag)).expect("field");
                    node.attribute("Value").expect("value").parse().expect("number")
                };
                (value("index"), value("priority"))
            })
            .collect();
        assert_eq!(
            layers,
            [(1, 0), (3, 1), (2, 2), (0, 3)],
            "engrave, then inner, then outer; the sheet"
        );
        let shapes: Vec<(u32, Vec<DVec2>, usize)> = root
            .children()
            .filter(|n| n.has_tag_name("Shape"))
            .map(|n| {
                let index = n.attribute("CutIndex").expect("layer").parse().expect("number");
                let child = |tag: &str| {
                    n.children()
                        .find(|c| c.has_tag_name(tag))
                        .and_then(|c| c.text())
                        .expect(tag)
                };
                let verts: Vec<DVec2> = child("VertList")
                    .split('V')
                    .filter(|v| !v.is_empty())
                    .map(|v| {
                        let xy: Vec<f64> = v.split_whitespace().map(|x| x.parse().expect("number")).collect();
                        DVec2::new(xy[0], sheet.height - xy[1])
                    })
                    .collect();
                let lines = child("PrimList").matches('L').count();
                (index, verts, lines)
            })
            .collect();
        // The sheet's outline first, on its layer that is not cut.
        let (sheet_layer, frame, _) = &shapes[0];
        assert_eq!(*sheet_layer, 0);
        let corners = [
            DVec2::ZERO,
            DVec2::new(sheet.width, 0.0),
            DVec2::new(sheet.width, sheet.height),
            DVec2::new(0.0, sheet.height),
        ];
        assert!(
            frame.iter().zip(corners).all(|(a, b)| a.distance(b) < 0.01),
            "{frame:?}"
        );
        let shapes = &shapes[1..];
        assert_eq!(shapes.len(), paths.len());
        for (k, (p, (index, verts, lines))) in paths.iter().zip(shapes).enumerate() {
            let last_ring =
                p.red && p.closed && !paths[k + 1..].iter().any(|q| q.group == p.group && q.red && q.closed);
            let want = match (p.red, p.closed) {
                (false, _) => 1,
                (true, true) if last_ring => 2,
                _ => 3,
            };
            assert_eq!(*index, want, "shape {k} of {}", p.group);
            assert_eq!(verts.len(), p.points.len());
            assert!(verts.iter().zip(&p.points).all(|(a, b)| a.distance(*b) < 0.01));
            assert_eq!(*lines, if p.closed { verts.len() } else { verts.len() - 1 });
        }
    }
}

/// `colors` = LightBurn (issue 34): in every sheet of a mixed plan, each part's outline is its
/// last path, red (LightBurn's C02) and its largest ring; its holes are green (C03) before it;
/// its numbers black (C00). plan.json names the profile; the classic plan leaves it out.
#[test]
fn a_lightburn_plan_strokes_each_operation_in_its_colour() {
    use platener::plan::ColorProfile;
    let settings = CutSettings {
        colors: ColorProfile::LightBurn,
        ..CutSettings::default()
    };
    let (_, plan) = run(mixed_parts(), settings);
    let (mut outlines, mut holes, mut labels) = (0, 0, 0);
    for (name, bytes) in plan.bundle.files.iter().filter(|(n, _)| n.ends_with(".svg")) {
        let text = std::str::from_utf8(bytes).expect("utf-8");
        let doc = roxmltree::Document::parse(text).expect("well-formed");
        for g in doc
            .descendants()
            .filter(|n| n.attribute("id").is_some_and(|id| id.starts_with("part-")))
        {
            let paths: Vec<(&str, bool, f64)> = g
                .children()
                .filter(|n| n.has_tag_name("path"))
                .map(|n| {
                    let d = n.attribute("d").expect("d");
                    let ring = svg_read::path_points(d).0;
                    (
                        n.attribute("stroke").expect("stroke"),
                        d.ends_with('Z'),
                        Polygon::new(ring).area().abs(),
                    )
                })
                .collect();
            let (last, rest) = paths.split_last().expect("a part has paths");
            assert_eq!(
                (last.0, last.1),
                ("#ff0000", true),
                "{name}: the outline comes last, red"
            );
            outlines += 1;
            for (stroke, closed, area) in rest {
                match (*stroke, *closed) {
                    ("#00e000", true) => {
                        assert!(*area < last.2, "{name}: a hole is smaller than its outline");
                        holes += 1;
                    }
                    ("#000000", false) => labels += 1,
                    other => panic!("{name}: unexpected path {other:?}"),
                }
            }
        }
    }
    assert_eq!(outlines, mixed_parts().len());
    assert!(
        holes >= 1 && labels >= mixed_parts().len(),
        "{holes} holes, {labels} label strokes"
    );
    let json = String::from_utf8(plan.bundle.files["plan.json"].clone()).expect("utf-8");
    assert!(
        json.contains("\"colors\": \"lightburn\""),
        "plan.json names the profile"
    );
    let (_, classic) = run(mixed_parts(), CutSettings::default());
    let json = String::from_utf8(classic.bundle.files["plan.json"].clone()).expect("utf-8");
    assert!(!json.contains("\"colors\""), "the default profile is not written");
}

/// `reference-square` on (issue 34): every sheet of a mixed plan with room gets a scored
/// 100 × 100 mm square clear of every part, in its SVG (`<g id="reference-square">`, score
/// colour) and its DXF (ENGRAVE layer), and plan.json gives its corners; off, nothing of it.
#[test]
fn the_reference_square_is_100_mm_beside_the_parts_in_svg_dxf_and_plan() {
    use platener::export::dxf::read_polylines;
    use platener::export::reference::REFERENCE_ID;
    let settings = CutSettings {
        sheet: SheetSize::Fixed {
            width: 800.0,
            height: 600.0,
        },
        reference_square: true,
        ..CutSettings::default()
    };
    let (_, plan) = run(mixed_parts(), settings);
    let bundle = &plan.bundle;
    assert!(!bundle.plan.sheets.is_empty());
    for sheet in &bundle.plan.sheets {
        let [lo, hi] = sheet.reference_square.expect("room on an 800 × 600 sheet");
        assert!((hi[0] - lo[0] - 100.0).abs() < 1e-9 && (hi[1] - lo[1] - 100.0).abs() < 1e-9);
        assert!(lo[0] >= 0.0 && lo[1] >= 0.0 && hi[0] <= sheet.width && hi[1] <= sheet.height);
        for part in bundle.plan.parts.iter().filter(|p| p.sheet.index == sheet.index) {
            let inside = |q: &[f64; 2]| q[0] > lo[0] && q[0] < hi[0] && q[1] > lo[1] && q[1] < hi[1];
            let on_sheet = part.outline.iter().map(|q| part.sheet.apply(*q));
            assert!(
                !on_sheet.map(|q| [q.x, q.y]).any(|q| inside(&q)),
                "part {} reaches into the square",
                part.id
            );
        }
        let svg = std::str::from_utf8(&bundle.files[&sheet.file]).expect("utf-8");
        let doc = roxmltree::Document::parse(svg).expect("well-formed");
        let g = doc
            .descendants()
            .find(|n| n.attribute("id") == Some(REFERENCE_ID))
            .expect("the square's group");
        let square = g.children().find(|n| n.has_tag_name("path")).expect("the square");
        assert_eq!(square.attribute("stroke"), Some("#0000ff"), "scored, not cut");
        let dxf_name = sheet.file.replace(".svg", ".dxf");
        let lines = read_polylines(&bundle.files[&dxf_name], sheet.height).expect("reads");
        let found = lines.iter().any(|l| {
            l.layer == "ENGRAVE"
                && l.points.len() == 5
                && l.points
                    .iter()
                    .all(|p| (p.x - lo[0]).abs() < 1e-6 || (p.x - hi[0]).abs() < 1e-6)
        });
        assert!(found, "the DXF scores the square");
    }
    let (_, off) = run(mixed_parts(), CutSettings::default());
    assert!(off.bundle.plan.sheets.iter().all(|s| s.reference_square.is_none()));
    assert!(
        !off.bundle
            .files
            .values()
            .any(|f| f.windows(REFERENCE_ID.len()).any(|w| w == REFERENCE_ID.as_bytes()))
    );
}

/// The PDF (issue 34): one page per sheet in plan.json's order, each page the sheet's size in
/// points, drawing the SVG's paths in the SVG's order with its colours and widths (within
/// 0.01 mm), then only the PDF's own reference square and grey stock caption.
#[test]
fn the_pdf_has_a_page_per_sheet_with_the_svg_paths_at_true_size() {
    use platener::draw::svg::rgb as hex_color;
    use platener::export::pdf::PT_PER_MM;
    use platener::export::pdf::read::read_pages;
    use platener::plan::ColorProfile;
    let settings = CutSettings {
        sheet: SheetSize::Fixed {
            width: 400.0,
            height: 300.0,
        },
        colors: ColorProfile::Ponoko,
        ..CutSettings::default()
    };
    let (_, plan) = run(mixed_parts(), settings);
    let bundle = &plan.bundle;
    let stem = bundle.plan.sheets[0]
        .file
        .split("-3mm-")
        .next()
        .expect("stem")
        .to_string();
    let pages = read_pages(&bundle.files[&format!("{stem}.pdf")]).expect("reads");
    assert!(bundle.plan.sheets.len() > 1, "a test of several pages");
    assert_eq!(pages.len(), bundle.plan.sheets.len());
    for (page, sheet) in pages.iter().zip(&bundle.plan.sheets) {
        let points = DVec2::new(sheet.width, sheet.height) * PT_PER_MM;
        assert!(
            (page.size * PT_PER_MM - points).abs().max_element() < 1e-3,
            "{}",
            sheet.file
        );
        let svg = std::str::from_utf8(&bundle.files[&sheet.file]).expect("utf-8");
        let doc = roxmltree::Document::parse(svg).expect("well-formed");
        let svg_paths: Vec<_> = doc.descendants().filter(|n| n.has_tag_name("path")).collect();
        assert!(page.paths.len() > svg_paths.len(), "the SVG's paths, then the caption");
        for (pdf, node) in page.paths.iter().zip(&svg_paths) {
            let (pts, closed) = svg_read::path_points(node.attribute("d").expect("d"));
            assert_eq!(pdf.closed, closed);
            assert_eq!(pdf.color, hex_color(node.attribute("stroke").expect("stroke")));
            let width: f64 = node.attribute("stroke-width").expect("width").parse().expect("number");
            assert!((pdf.width - width).abs() < 1e-6);
            assert_eq!(pdf.points.len(), pts.len());
            for (a, b) in pdf.points.iter().zip(&pts) {
                assert!(a.distance(*b) < 0.01, "{a} vs {b} in {}", sheet.file);
            }
        }
        let grey = hex_color(platener::export::pdf::CAPTION_COLOR);
        assert!(
            page.paths[svg_paths.len()..].iter().any(|p| p.color == grey),
            "the stock caption"
        );
    }
}
