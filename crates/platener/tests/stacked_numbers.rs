//! Issue 15, stacked layers, checked on the corpus: every part of every stacked plan carries
//! its number inside its outline, a layer that holds others is not dropped (the teapot's lid
//! knob), and layers no shaft or peg joins are named as glued groups (the acrylic bracket).
//!
//! Tolerances: a label box "lies inside" its part when the box minus the part is under
//! [`OUTSIDE`] mm² (the 1 µm grid of the booleans); islands "touch" as the stacked step decides
//! (an overlap over 0.01 mm², as in the step).

use std::path::PathBuf;

use platener::convert;
use platener::draw::font;
use platener::export::legend;
use platener::glam::DVec2;
use platener::method::MethodKind;
use platener::plan::{MarkKind, PartKind, Plan};
use platener::stacked::Stack;
use platener::{Cancel, Settings, Source, State};
use platener_fixtures::samples;
use platener_geom::polygon::total_area;
use platener_geom::{Polygon, boolean};

/// A label box sticking out of its part by less than this (mm²) is inside (grid rounding).
const OUTSIDE: f64 = 1e-6;
/// Islands of adjacent layers overlapping by more than this (mm²) touch (as in the step).
const TOUCH: f64 = 0.01;

fn corpus() -> Option<PathBuf> {
    samples::shared_corpus().map_err(|m| eprintln!("{m}")).ok()
}

/// Settings for tests: one nesting try, so a debug build nests quickly.
fn quick() -> Settings {
    let mut s = Settings::default();
    s.cut.nest_tries = 1;
    s.cut.fine_rotations = false;
    s
}

fn stacked(path: PathBuf) -> Result<State, platener::Error> {
    convert(MethodKind::Stacked, Source::File(path), quick(), &Cancel::default())
}

/// [`stacked`] from sheets `thickness` mm thick.
fn stacked_at(path: PathBuf, thickness: f64) -> Result<State, platener::Error> {
    let settings = Settings {
        thicknesses: vec![thickness],
        ..quick()
    };
    convert(MethodKind::Stacked, Source::File(path), settings, &Cancel::default())
}

fn plan(c: &State) -> &Plan {
    &c.export.as_ref().expect("exported").plan
}

fn stack(c: &State) -> &Stack {
    c.stacked.as_ref().expect("stack")
}

/// Where a layer part's number went when it has no room for it: `[part, carrier]` pairs of
/// report.json's `method_report.numbers.on_neighbour`.
fn numbered_on_neighbour(c: &State) -> Vec<[u32; 2]> {
    numbers(c, "on_neighbour")
}

/// `[part, carrier]` pairs of report.json's `method_report.numbers.{key}`.
fn numbers(c: &State, key: &str) -> Vec<[u32; 2]> {
    let report = c
        .final_parts()
        .as_ref()
        .expect("parts")
        .method_report
        .clone()
        .expect("a report");
    serde_json::from_value(report["numbers"][key].clone()).expect("pairs")
}

/// Every part's number is placed, inside its outline (not across a cut), and written to
/// plan.json, or (a rib with no room even for a tab) engraved on a part of an adjacent layer it
/// rests on. Returns (numbers on a tab, numbers on a neighbour).
fn assert_every_part_numbered(name: &str, c: &State) -> (usize, usize) {
    let input = c.final_parts().as_ref().expect("parts");
    let labels = c.labels.as_ref().expect("labels");
    let plan = plan(c);
    let on_neighbour = numbered_on_neighbour(c);
    let beside_slot = numbers(c, "beside_slot");
    let mut on_tabs = 0;
    for (i, part) in input.parts.iter().enumerate() {
        let placed = &labels.parts[i];
        assert_eq!(placed.id, part.id);
        let Some(number) = placed.boxes.first() else {
            if let Some(&[_, on]) = beside_slot.iter().find(|r| r[0] == part.id) {
                assert_beside_slot(name, c, part.id, on);
                continue;
            }
            let [_, on] = on_neighbour
                .iter()
                .find(|r| r[0] == part.id)
                .copied()
                .unwrap_or_else(|| panic!("{name}: part {} has no number", part.id));
            assert_neighbour_reference(name, c, part.id, on);
            continue;
        };
        assert_eq!(number.text, part.id.to_string(), "{name}: part {}", part.id);
        let quad = Polygon::new(number.corners(0.0).to_vec());
        let out = boolean::difference(std::slice::from_ref(&quad), std::slice::from_ref(&part.polygon)).expect("grid");
        assert!(
            total_area(&out) < OUTSIDE,
            "{name}: part {}'s number crosses its outline",
            part.id
        );
        let in_plan = plan.parts.iter().find(|p| p.id == part.id).expect("in plan.json");
        assert!(
            in_plan.marks.len() >= placed.marks.len() && !placed.marks.is_empty(),
            "{name}: part {}'s number is not in plan.json",
            part.id
        );
        if part.kind == PartKind::Layer {
            let island = island(c, part.id);
            let beyond = boolean::difference(std::slice::from_ref(&quad), std::slice::from_ref(&island.1.polygon))
                .expect("grid");
            if total_area(&beyond) > OUTSIDE {
                on_tabs += 1;
            }
        }
    }
    (on_tabs, on_neighbour.len())
}

/// The layer index and island of part `id`.
fn island(c: &State, id: u32) -> (usize, &platener::stacked::Island) {
    stack(c)
        .layers
        .iter()
        .enumerate()
        .find_map(|(k, l)| l.islands.iter().find(|i| i.part == id).map(|i| (k, i)))
        .expect("an island")
}

/// Part `on` lies in a layer next to part `id`'s, overlaps it, and carries its footprint.
fn assert_neighbour_reference(name: &str, c: &State, id: u32, on: u32) {
    let ((k, a), (n, b)) = (island(c, id), island(c, on));
    assert_eq!(
        k.abs_diff(n),
        1,
        "{name}: part {id}'s number is on part {on}, not a neighbour"
    );
    assert!(
        touches(&a.outline, &b.outline),
        "{name}: part {id} does not rest on part {on}"
    );
    let carrier = part_of(c, on);
    let footprint_marks = carrier
        .marks
        .iter()
        .filter(|m| {
            m.kind == MarkKind::Score
                && m.path
                    .iter()
                    .all(|p| a.outline.contains(*p) || a.outline.boundary_distance(*p) < 1e-3)
        })
        .count();
    assert!(
        footprint_marks >= 1,
        "{name}: part {on} does not show where part {id} goes"
    );
}

/// Part `id` of the `parts` snapshot.
fn part_of(c: &State, id: u32) -> &platener::plan::Part {
    c.final_parts()
        .as_ref()
        .expect("parts")
        .parts
        .iter()
        .find(|p| p.id == id)
        .expect("part")
}

/// Shaft `id`'s number is engraved on layer part `on`, which it passes through, within a
/// few millimetres of its slot there.
fn assert_beside_slot(name: &str, c: &State, id: u32, on: u32) {
    let st = stack(c);
    let shaft = st.shafts.iter().find(|s| s.part == id).expect("a shaft");
    let band = shaft
        .bands
        .iter()
        .find(|b| st.layers[b.layer].islands[b.island].part == on)
        .unwrap_or_else(|| panic!("{name}: shaft {id} does not pass through part {on}"));
    let slot = shaft.start + shaft.direction * ((band.from + band.to) / 2.0);
    let carrier = part_of(c, on);
    let near = carrier
        .marks
        .iter()
        .filter(|m| m.kind == MarkKind::Label)
        .any(|m| m.path.iter().all(|p| p.distance(slot) < 15.0));
    assert!(near, "{name}: shaft {id}'s number is not beside its slot on part {on}");
}

/// Polylines of an SVG group.
type Paths = Vec<Vec<DVec2>>;

/// The paths of `<g id="{id}">` in one of our SVG sheets, by stroke colour: (red, blue).
fn svg_group(svg: &str, id: &str) -> Option<(Paths, Paths)> {
    let start = svg.find(&format!("<g id=\"{id}\">"))?;
    let body = &svg[start..start + svg[start..].find("</g>").expect("group ends")];
    let (mut red, mut blue) = (Vec::new(), Vec::new());
    for tag in body.split("<path ").skip(1) {
        let d = tag
            .split("d=\"")
            .nth(1)
            .and_then(|t| t.split('"').next())
            .expect("path data");
        let nums: Vec<f64> = d
            .split_whitespace()
            .map(|t| t.trim_start_matches(['M', 'L']))
            .filter(|t| !t.is_empty() && *t != "Z")
            .map(|t| t.parse().expect("number"))
            .collect();
        let points = nums.chunks_exact(2).map(|c| DVec2::new(c[0], c[1])).collect();
        if tag.contains("stroke=\"#ff0000\"") {
            red.push(points);
        } else {
            assert!(
                tag.contains("stroke=\"#0000ff\""),
                "{id}: a path neither cut nor engraved"
            );
            blue.push(points);
        }
    }
    Some((red, blue))
}

/// Every sheet holding a part whose number is on a tab or on a neighbour has a legend saying
/// so: blue strokes only, exactly the strokes of the lines for that sheet's parts, inside the
/// sheet and outside every part's cut outline (the box around the text meets no part).
fn assert_sheet_legends(name: &str, c: &State) {
    let bundle = c.export.as_ref().expect("exported");
    let report = c.final_parts().as_ref().expect("parts").method_report.clone();
    for sheet in &bundle.plan.sheets {
        let mut on_sheet: Vec<u32> = bundle
            .plan
            .parts
            .iter()
            .filter(|p| p.sheet.index == sheet.index)
            .map(|p| p.id)
            .collect();
        on_sheet.sort_unstable();
        let lines = legend::legend_lines(report.as_ref(), &on_sheet);
        let planned = sheet.legend.as_ref();
        assert_eq!(
            planned.map(|l| &l.lines),
            (!lines.is_empty()).then_some(&lines),
            "{name}: plan.json's legend of {}",
            sheet.file
        );
        let svg = String::from_utf8(bundle.files[&sheet.file].clone()).expect("utf-8");
        let Some((red, blue)) = svg_group(&svg, legend::LEGEND_ID) else {
            // No room beside the parts: the lines are in plan.json only.
            assert!(
                planned.is_none_or(|l| !l.engraved),
                "{name}: {} lost its legend",
                sheet.file
            );
            continue;
        };
        assert!(red.is_empty(), "{name}: the legend is not cut");
        let strokes: usize = lines.iter().map(|l| font::text_strokes(l, 1.0).len()).sum();
        assert!(
            !lines.is_empty() && blue.len() == strokes,
            "{name}: {} strokes for {lines:?}",
            blue.len()
        );
        let (lo, hi) = blue.iter().flatten().fold(
            (DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY)),
            |(a, b), p| (a.min(*p), b.max(*p)),
        );
        assert!(lo.x >= 0.0 && lo.y >= 0.0 && hi.x <= sheet.width && hi.y <= sheet.height);
        assert_beside_the_parts(name, &svg, bundle, sheet.index, (lo, hi));
        let text_box = Polygon::new(vec![lo, DVec2::new(hi.x, lo.y), hi, DVec2::new(lo.x, hi.y)]);
        for p in bundle.plan.parts.iter().filter(|p| p.sheet.index == sheet.index) {
            let (cut, _) = svg_group(&svg, &format!("part-{}", p.id)).expect("part group");
            let outline = Polygon::new(cut[0].clone());
            let meet = boolean::intersection(std::slice::from_ref(&text_box), &[outline]).expect("grid");
            assert!(
                meet.is_empty(),
                "{name}: the legend on {} meets part {}",
                sheet.file,
                p.id
            );
        }
    }
}

/// The legend's text box `text` lies inside the bounding box of the sheet's parts grown by the
/// legend's own extent and twice the legend's gap: beside the parts it explains, never across
/// the sheet (the laser's travel, a smaller real sheet).
fn assert_beside_the_parts(name: &str, svg: &str, bundle: &platener::export::Bundle, sheet: u32, text: (DVec2, DVec2)) {
    let (mut a, mut b) = (DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY));
    for p in bundle.plan.parts.iter().filter(|p| p.sheet.index == sheet) {
        let (cut, _) = svg_group(svg, &format!("part-{}", p.id)).expect("part group");
        for q in cut.iter().flatten() {
            (a, b) = (a.min(*q), b.max(*q));
        }
    }
    let margin = DVec2::splat((text.1 - text.0).max_element() + 2.0 * legend::GAP + 1e-6);
    assert!(
        text.0.cmpge(a - margin).all() && text.1.cmple(b + margin).all(),
        "{name}: the legend {text:?} is not beside the parts ({a}, {b})"
    );
}

fn touches(a: &Polygon, b: &Polygon) -> bool {
    let o = boolean::intersection(std::slice::from_ref(a), std::slice::from_ref(b)).expect("grid");
    total_area(&o) > TOUCH
}

/// Groups of plan parts held by joints and, when `with_glue`, by `glued` too.
fn groups(plan: &Plan, with_glue: bool) -> usize {
    let ids: Vec<u32> = plan.parts.iter().map(|p| p.id).collect();
    let mut root: Vec<usize> = (0..ids.len()).collect();
    fn find(root: &mut [usize], mut i: usize) -> usize {
        while root[i] != i {
            root[i] = root[root[i]];
            i = root[i];
        }
        i
    }
    let glued = plan.glued.iter().map(|g| g.parts).filter(|_| with_glue);
    for pair in plan.joints.iter().map(|j| j.parts).chain(glued) {
        let a = ids.iter().position(|&x| x == pair[0]).expect("part");
        let b = ids.iter().position(|&x| x == pair[1]).expect("part");
        let (ra, rb) = (find(&mut root, a), find(&mut root, b));
        root[ra.max(rb)] = ra.min(rb);
    }
    (0..ids.len()).filter(|&i| find(&mut root, i) == i).count()
}

#[test]
fn every_part_of_every_stacked_corpus_plan_carries_its_number() {
    let Some(dir) = corpus() else { return };
    let (mut converted, mut parts, mut tabs) = (0, 0, 0);
    for path in samples::stl_files(&dir) {
        let name = path.file_name().expect("name").to_string_lossy().to_string();
        // Broken files and models a few mm across fail with their message (other tests check
        // those); every plan that is made is checked.
        let Ok(c) = stacked(path) else { continue };
        converted += 1;
        parts += plan(&c).parts.len();
        let (t, n) = assert_every_part_numbered(&name, &c);
        assert_sheet_legends(&name, &c);
        eprintln!(
            "{name}: {} parts, {t} numbered on a tab, {n} on a neighbour",
            plan(&c).parts.len()
        );
        tabs += t;
    }
    eprintln!("{converted} stacked plans, {parts} parts, {tabs} numbers on tabs");
    // 30 of the 53 files make a stacked plan with default settings (the others are broken, a
    // few mm across, or, since issue 32's smallest part, thinner than the sheet everywhere: the
    // push rods on edge, the geo lamp's 0.8 mm shell; they fail with their message); fewer
    // means models stopped converting.
    assert!(converted >= 30, "only {converted} corpus models converted");
}

/// The bird feeder's rings numbered on tabs at 2 mm.
const TABS_AT_2MM: usize = 47;

#[test]
fn the_bird_feeder_cups_thin_rings_carry_their_numbers_on_tabs() {
    let Some(dir) = corpus() else { return };
    // Its rings are about 2 mm wide: from 3 mm sheet they are under the smallest part (issue
    // 32) and left out; from 2 mm sheet they are made.
    let c = stacked_at(dir.join("other/bird_water_feeder_cup.stl"), 2.0).expect("converts");
    let (tabs, _) = assert_every_part_numbered("bird_water_feeder_cup", &c);
    let parts = plan(&c).parts.len();
    // 48 rings and one peg through bosses that holds them all (issue 31); the peg, 2 mm wide,
    // has its number beside its slot in the bottom ring.
    assert_eq!(parts, 49);
    assert_eq!(numbers(&c, "beside_slot"), vec![[49, 1]]);
    // Before tabs, the rings had no number; each now has it on a tab of the size the step
    // makes (its length out of the outline, plus under ATTACH into it, times its width).
    assert_eq!(tabs, TABS_AT_2MM, "{parts} parts");
    // The sheets say so: every sheet's legend lists its parts numbered on a tab.
    let sheets = &plan(&c).sheets;
    let with_legend = sheets
        .iter()
        .filter(|s| {
            String::from_utf8_lossy(&c.export.as_ref().expect("zip").files[&s.file]).contains("<g id=\"legend\">")
        })
        .count();
    assert_eq!(with_legend, sheets.len());
    assert_sheet_legends("bird_water_feeder_cup", &c);
    let kerf = plan(&c).settings.cut.kerf.expect("recorded");
    let input = c.final_parts().as_ref().expect("parts");
    for island in stack(&c).layers.iter().flat_map(|l| &l.islands) {
        let part = input.parts.iter().find(|p| p.id == island.part).expect("part");
        let added = part.polygon.area() - island.polygon.area();
        if added > 0.0 {
            let size = platener::stacked::tab_size(part.id, kerf);
            assert!(
                added >= size.x * size.y - 1e-3 && added <= (size.x + 0.5) * size.y + 1e-3,
                "part {}: tab of {added} mm² for a {size} tab",
                part.id
            );
        }
    }
}

#[test]
fn the_teapots_lid_knob_rests_on_the_layer_below_it() {
    let Some(dir) = corpus() else { return };
    let c = stacked(dir.join("organic/utah_teapot.stl")).expect("converts");
    let st = stack(&c);
    // The 24.6–27.6 mm layer (the knob's neck, islands under 25 mm²) is kept, enlarged.
    let first = st.layers.iter().position(|l| !l.islands.is_empty()).expect("a layer");
    let last = st.layers.iter().rposition(|l| !l.islands.is_empty()).expect("a layer");
    for (k, l) in st.layers.iter().enumerate().take(last + 1).skip(first) {
        assert!(!l.islands.is_empty(), "layer {} is empty inside the stack", k + 1);
    }
    let neck: Vec<_> = st.kept_small.iter().filter(|k| k.layer == 8).collect();
    assert_eq!(neck.len(), 1, "{:?}", st.kept_small);
    let z = st.layer_frame(8).origin.z;
    assert!((z - 24.61).abs() < 0.01, "{z}");
    assert!(neck[0].area < 25.0 && neck[0].enlarged >= 25.0, "{:?}", neck[0]);
    // No floating piece: every island touches an island of a layer next to it (the teapot has
    // no piece one layer thin on its own).
    for (k, l) in st.layers.iter().enumerate() {
        for isl in &l.islands {
            let neighbours = [k.checked_sub(1), Some(k + 1)]
                .into_iter()
                .flatten()
                .filter_map(|n| st.layers.get(n))
                .flat_map(|n| &n.islands);
            assert!(
                neighbours.into_iter().any(|o| touches(&isl.outline, &o.outline)),
                "part {} (layer {}) floats",
                isl.part,
                k + 1
            );
        }
    }
    // Shafts and glue hold the whole teapot together.
    assert_eq!(groups(plan(&c), true), 1);
}

#[test]
fn the_acrylic_brackets_unjoined_layers_are_named_as_two_glued_groups() {
    let Some(dir) = corpus() else { return };
    let c = stacked(dir.join("plates/acrylic_case_corner_bracket_5mm.stl")).expect("converts");
    let plan = plan(&c);
    // Four layers and two pegs: part 5 in a boss joining layers 1 and 2, part 6 joining layers
    // 3 and 4 (tests/stacked_pegs.rs). Between layers 2 and 3 nothing fits.
    assert_eq!(plan.parts.len(), 6);
    assert_eq!(plan.joints.len(), 4, "two pegs of two layers each");
    let pairs: Vec<[u32; 2]> = plan.glued.iter().map(|g| g.parts).collect();
    assert_eq!(pairs, vec![[2, 3]]);
    assert!(plan.glued.iter().all(|g| g.area > 1.0), "{:?}", plan.glued);
    assert_eq!(plan.glued_groups(), vec![vec![1, 2, 5], vec![3, 4, 6]]);
    assert_eq!((groups(plan, false), groups(plan, true)), (2, 1));
    let warned = c.records.iter().flat_map(|r| &r.warnings).any(|w| {
        w.step == "stacked" && w.message.contains("these 2 groups") && w.message.contains("[1–2, 5], [3–4, 6]")
    });
    assert!(warned, "{:?}", c.records);
    // plan.json carries the list (and reads back).
    let json = plan.to_json().expect("json");
    let back: Plan = serde_json::from_str(&json).expect("reads");
    assert_eq!(back.glued, plan.glued);
}
