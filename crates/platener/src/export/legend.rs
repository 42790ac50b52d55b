//! The sheet legend: where the numbers of parts too thin for them went.
//!
//! A stacked layer too thin for its digits carries its number on a tab or engraved on the
//! layer it rests on (`stacked::tabs`, report.json's `method_report.numbers`). Someone sorting
//! the cut parts looks for "7" on part 7 and does not find it, so the sheet says where it is:
//! a few lines of engraved text (blue, like every label; nothing outside the parts is red)
//! in free room on the sheet, clear of every part, e.g. `7/8: NUMBER 7 ON PART 8`. Only the
//! parts on that sheet are listed. The text is drawn with the labels' stroke font, so the
//! laser engraves it like any label; the font has capitals and no comma, hence the wording.
//!
//! The legend goes beside the parts it explains: where its box, grown by [`GAP`], meets no
//! part's bounding box, stays on the sheet, and grows the parts' bounding box (the used area)
//! the least: inside it when there is room, else just outside it. Bounding boxes are
//! conservative (the text never meets a part). A sheet with no such room gets no legend
//! engraved; plan.json's `sheets[].legend` still holds its lines (and report.json says where
//! every number is).

use glam::DVec2;
use serde::Deserialize;

use crate::draw::font;
use crate::draw::svg::{Engraved, SvgGroup};
use crate::plan::SheetLegend;

/// Cap height of the legend's text, mm.
pub const LEGEND_SIZE: f64 = 3.0;
/// Baseline to baseline, in cap heights.
const LINE_PITCH: f64 = 1.6;
/// Room kept between the legend and every part and the sheet's edges, mm.
pub const GAP: f64 = 2.0;
/// Part ids per line of the "numbers on tabs" list.
const IDS_PER_LINE: usize = 12;
/// The group id of the legend in the SVG.
pub const LEGEND_ID: &str = "legend";

/// The part of `method_report` the legend reads (`stacked::Numbers` as written).
#[derive(Debug, Default, Deserialize)]
struct Numbers {
    #[serde(default)]
    on_tab: Vec<u32>,
    #[serde(default)]
    on_neighbour: Vec<[u32; 2]>,
}

/// The legend's lines for the parts `on_sheet` (ascending ids), from the method's report; empty
/// when every number on the sheet is on its own part.
pub fn legend_lines(method_report: Option<&serde_json::Value>, on_sheet: &[u32]) -> Vec<String> {
    let numbers: Numbers = method_report
        .and_then(|r| r.get("numbers"))
        .and_then(|n| Numbers::deserialize(n).ok())
        .unwrap_or_default();
    let here = |id: &u32| on_sheet.binary_search(id).is_ok();
    let mut lines: Vec<String> = numbers
        .on_neighbour
        .iter()
        .filter(|[part, _]| here(part))
        .map(|[part, on]| format!("{part}/{on}: NUMBER {part} ON PART {on}"))
        .collect();
    let tabs: Vec<String> = numbers
        .on_tab
        .iter()
        .filter(|id| here(id))
        .map(u32::to_string)
        .collect();
    for chunk in tabs.chunks(IDS_PER_LINE) {
        lines.push(format!("NUMBER ON A TAB: {}", chunk.join(" ")));
    }
    lines
}

/// A sheet's legend: its lines and where they are engraved, if anywhere.
#[derive(Debug, Clone, PartialEq)]
pub struct Legend {
    /// The lines ([`legend_lines`]).
    pub lines: Vec<String>,
    /// The text's top-left corner on the sheet; `None` when there is no room beside the parts.
    pub top_left: Option<DVec2>,
    /// The text's width and height, mm.
    pub size: DVec2,
}

impl Legend {
    /// The legend of `lines` on a `width` × `height` sheet holding `parts`: placed beside the
    /// parts ([`free_spot`]) or, without room there, kept off the sheet. `None` without lines.
    pub fn place(lines: Vec<String>, width: f64, height: f64, parts: &[SvgGroup]) -> Option<Legend> {
        if lines.is_empty() {
            return None;
        }
        let size = DVec2::new(
            lines
                .iter()
                .map(|l| font::text_width(l, LEGEND_SIZE))
                .fold(0.0, f64::max),
            LEGEND_SIZE * (1.0 + LINE_PITCH * (lines.len() - 1) as f64),
        );
        let boxes: Vec<Bounds> = parts.iter().filter_map(|g| bounds(&g.cut)).collect();
        let top_left = free_spot(size, DVec2::new(width, height), &boxes);
        Some(Legend { lines, top_left, size })
    }

    /// The engrave-only group of the legend, when it is on the sheet.
    pub fn group(&self) -> Option<SvgGroup> {
        let top_left = self.top_left?;
        let labels: Vec<Vec<DVec2>> = self
            .lines
            .iter()
            .enumerate()
            .flat_map(|(i, line)| {
                let baseline = top_left + DVec2::new(0.0, LEGEND_SIZE * (1.0 + LINE_PITCH * i as f64));
                font::place_text(line, LEGEND_SIZE, baseline, DVec2::X)
            })
            .collect();
        Some(SvgGroup {
            id: LEGEND_ID.into(),
            cut: Vec::new(),
            slits: Vec::new(),
            engrave: labels.into_iter().map(Engraved::text).collect(),
        })
    }

    /// The legend as plan.json's `sheets[].legend`.
    pub fn plan(&self) -> SheetLegend {
        SheetLegend {
            lines: self.lines.clone(),
            engraved: self.top_left.is_some(),
            min: self.top_left.map(|p| p.to_array()),
            max: self.top_left.map(|p| (p + self.size).to_array()),
        }
    }
}

/// A box: smallest and largest corner.
type Bounds = (DVec2, DVec2);

/// The top-left corner of a free box of `size` on a `sheet`-sized sheet, beside the parts:
/// clear of every box in `boxes` and of the sheet's edges by [`GAP`], and growing the parts'
/// bounding box (the used area) the least. Spots inside the used area (its corners, beside and
/// below each part) grow it not at all; spots just outside it (right of, below, left of, above
/// it) grow it by the legend alone. The sheet's far corners are never tried: the laser would
/// travel there and a smaller real sheet would lose the legend. Ties keep the first spot, so
/// the choice is deterministic.
pub(super) fn free_spot(size: DVec2, sheet: DVec2, boxes: &[Bounds]) -> Option<DVec2> {
    let used = platener_geom::boxes::enclosing2(boxes.iter().copied())?;
    let (lo, hi) = (DVec2::splat(GAP), sheet - size - DVec2::splat(GAP));
    let step = 2.0 * GAP;
    let (u0, u1) = used;
    let inside = [
        u0,
        DVec2::new(u1.x - size.x, u0.y),
        DVec2::new(u0.x, u1.y - size.y),
        u1 - size,
    ];
    let beside = boxes.iter().flat_map(|(a, b)| {
        [
            DVec2::new(b.x + step, a.y),
            DVec2::new(a.x, b.y + step),
            DVec2::new(b.x + step, u0.y),
            DVec2::new(u0.x, b.y + step),
        ]
    });
    let outside = [
        DVec2::new(u1.x + step, u0.y),
        DVec2::new(u0.x, u1.y + step),
        DVec2::new(u0.x - step - size.x, u0.y),
        DVec2::new(u0.x, u0.y - step - size.y),
    ];
    if hi.x < lo.x || hi.y < lo.y {
        return None;
    }
    let free = |p: &DVec2| {
        boxes.iter().all(|&(a, b)| {
            let (q0, q1) = (*p - DVec2::splat(GAP), *p + size + DVec2::splat(GAP));
            q1.x <= a.x || b.x <= q0.x || q1.y <= a.y || b.y <= q0.y
        })
    };
    let growth = |p: DVec2| {
        let (g0, g1) = (u0.min(p), u1.max(p + size));
        (g1 - g0).x * (g1 - g0).y
    };
    inside
        .into_iter()
        .chain(beside)
        .chain(outside)
        // A spot past the sheet's edge slides back onto it (a part on the margin's edge).
        .map(|p| p.clamp(lo, hi))
        .filter(free)
        .map(|p| (growth(p), p))
        .reduce(|best, next| if next.0.total_cmp(&best.0).is_lt() { next } else { best })
        .map(|(_, p)| p)
}

/// The bounds of `rings`, if they have points.
fn bounds(rings: &[Vec<DVec2>]) -> Option<Bounds> {
    let (lo, hi) = platener_geom::boxes::bounds2(rings.iter().flatten().copied());
    (lo.x <= hi.x).then_some((lo, hi))
}

#[cfg(test)]
mod tests {
    use platener_geom::{Polygon, boolean};

    use super::*;

    fn square(x: f64, y: f64, s: f64) -> SvgGroup {
        SvgGroup {
            id: "part-1".into(),
            cut: vec![vec![
                DVec2::new(x, y),
                DVec2::new(x + s, y),
                DVec2::new(x + s, y + s),
                DVec2::new(x, y + s),
            ]],
            slits: Vec::new(),
            engrave: Vec::new(),
        }
    }

    #[test]
    fn lines_name_where_each_number_on_the_sheet_went() {
        let report =
            serde_json::json!({ "numbers": { "on_tab": [3, 5], "on_neighbour": [[7, 8], [9, 2]], "none": [] } });
        let lines = legend_lines(Some(&report), &[3, 7, 8]);
        assert_eq!(lines, ["7/8: NUMBER 7 ON PART 8", "NUMBER ON A TAB: 3"]);
        assert!(legend_lines(Some(&report), &[1, 2]).is_empty());
        assert!(legend_lines(None, &[3]).is_empty());
    }

    /// The legend's text box (from its strokes), the parts' bounding box, and whether the text
    /// box lies within the parts' box grown by `margin`.
    fn text_box(g: &SvgGroup) -> Bounds {
        assert!(g.cut.is_empty() && g.slits.is_empty(), "the legend is engraved only");
        bounds(&g.engrave.iter().map(|e| e.path.clone()).collect::<Vec<_>>()).expect("text")
    }

    fn near(a: Bounds, b: Bounds, margin: f64) -> bool {
        let m = DVec2::splat(margin);
        a.0.cmpge(b.0 - m).all() && a.1.cmple(b.1 + m).all()
    }

    /// A regular `n`-gon of radius `r` about `c`, counter-clockwise in the y-down frame.
    fn disc(id: u32, c: DVec2, r: f64, n: usize) -> SvgGroup {
        let ring = (0..n)
            .map(|i| {
                let a = std::f64::consts::TAU * i as f64 / n as f64;
                c + r * DVec2::new(a.cos(), a.sin())
            })
            .collect();
        SvgGroup {
            id: format!("part-{id}"),
            cut: vec![ring],
            slits: Vec::new(),
            engrave: Vec::new(),
        }
    }

    #[test]
    fn the_legend_sits_beside_a_corner_part_not_in_the_far_corner() {
        let parts = [square(0.0, 0.0, 100.0)];
        let lines = vec!["7/8: NUMBER 7 ON PART 8".to_string()];
        let legend = Legend::place(lines, 300.0, 200.0, &parts).expect("lines");
        let (lo, hi) = text_box(&legend.group().expect("room"));
        let used = (DVec2::ZERO, DVec2::splat(100.0));
        // Beside the part: inside its box grown by the legend and twice the gap, never past.
        assert!(
            near((lo, hi), used, legend.size.x.max(legend.size.y) + 2.0 * GAP + 1e-9),
            "{lo} {hi}"
        );
        assert!(
            lo.x >= 100.0 + GAP || lo.y >= 100.0 + GAP,
            "clear of the part: {lo} {hi}"
        );
        assert!(lo.cmpge(DVec2::splat(GAP - 1e-9)).all() && hi.x <= 300.0 - GAP && hi.y <= 200.0 - GAP);
    }

    /// Teapot-like: twelve stacked layers of different widths in a column at the sheet's left
    /// edge (x < 60 on a 600 mm sheet), two of them numbered on tabs. The legend goes into the
    /// column's room or right beside it, never across the sheet, and meets no layer.
    #[test]
    fn a_stacked_columns_legend_stays_beside_the_column_and_off_every_layer() {
        let radii = [14.0, 20.0, 25.0, 27.0, 28.0, 27.0, 25.0, 22.0, 18.0, 12.0, 6.0, 4.0];
        let mut y = 5.0;
        let parts: Vec<SvgGroup> = (1..)
            .zip(radii)
            .map(|(id, r)| {
                let g = disc(id, DVec2::new(5.0 + r, y + r), r, 40);
                y += 2.0 * r + 2.0;
                g
            })
            .collect();
        let report = serde_json::json!({ "numbers": { "on_tab": [10, 11], "on_neighbour": [[12, 9]] } });
        let ids: Vec<u32> = (1..=12).collect();
        let lines = legend_lines(Some(&report), &ids);
        let legend = Legend::place(lines.clone(), 600.0, 600.0, &parts).expect("lines");
        let g = legend.group().expect("room beside the column");
        let (lo, hi) = text_box(&g);
        let used = platener_geom::boxes::enclosing2(parts.iter().filter_map(|p| bounds(&p.cut))).expect("parts");
        assert!(used.1.x < 62.0, "the column is narrow: {used:?}");
        let margin = legend.size.x.max(legend.size.y) + 2.0 * GAP + 1e-9;
        assert!(
            near((lo, hi), used, margin),
            "legend {lo} {hi} far from the parts {used:?}"
        );
        let text = Polygon::new(vec![lo, DVec2::new(hi.x, lo.y), hi, DVec2::new(lo.x, hi.y)]);
        for p in &parts {
            let outline = Polygon::new(p.cut[0].clone());
            let meet = boolean::intersection(std::slice::from_ref(&text), &[outline]).expect("grid");
            assert!(meet.is_empty(), "the legend meets {}", p.id);
        }
        // plan.json says the same box.
        let plan = legend.plan();
        assert!(plan.engraved && plan.lines == lines);
        let (min, max) = (DVec2::from(plan.min.expect("min")), DVec2::from(plan.max.expect("max")));
        assert!(near((lo, hi), (min, max), 1e-6), "{lo} {hi} vs {min} {max}");
    }

    #[test]
    fn without_room_beside_the_parts_the_legend_is_kept_off_the_sheet() {
        let lines = vec!["7/8: NUMBER 7 ON PART 8".to_string()];
        let legend = Legend::place(lines.clone(), 100.0, 100.0, &[square(0.0, 0.0, 100.0)]).expect("lines");
        assert!(legend.group().is_none());
        let plan = legend.plan();
        assert_eq!(
            (plan.lines, plan.engraved, plan.min, plan.max),
            (lines, false, None, None)
        );
        assert!(
            Legend::place(Vec::new(), 100.0, 100.0, &[]).is_none(),
            "no lines, no legend"
        );
    }
}
