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
//! The legend goes where its box, grown by [`GAP`], meets no part's bounding box and stays on
//! the sheet: the sheet's corners first, then beside and below each part. Bounding boxes are
//! conservative (the text never meets a part); a sheet with no such room gets no legend, and
//! report.json still says where every number is.

use glam::DVec2;
use serde::Deserialize;

use super::svg::SvgGroup;
use crate::labels::font;

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

/// The legend of `lines` on a `width` × `height` sheet holding `parts`, as an engrave-only
/// group; `None` without lines or without room.
pub fn legend_group(lines: &[String], width: f64, height: f64, parts: &[SvgGroup]) -> Option<SvgGroup> {
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
    let boxes: Vec<(DVec2, DVec2)> = parts.iter().filter_map(|g| bounds(&g.cut)).collect();
    let top_left = free_spot(size, width, height, &boxes)?;
    let engrave = lines
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
        engrave,
    })
}

/// The top-left corner of a free box of `size` on the sheet: clear of every box in `boxes` and
/// of the sheet's edges by [`GAP`].
fn free_spot(size: DVec2, width: f64, height: f64, boxes: &[(DVec2, DVec2)]) -> Option<DVec2> {
    let (lo, hi) = (DVec2::splat(GAP), DVec2::new(width, height) - size - DVec2::splat(GAP));
    let corners = [lo, DVec2::new(hi.x, lo.y), DVec2::new(lo.x, hi.y), hi];
    let beside = boxes.iter().flat_map(|(a, b)| {
        [
            DVec2::new(b.x + 2.0 * GAP, a.y),
            DVec2::new(a.x, b.y + 2.0 * GAP),
            DVec2::new(b.x + 2.0 * GAP, lo.y),
            DVec2::new(lo.x, b.y + 2.0 * GAP),
        ]
    });
    corners.into_iter().chain(beside).find(|&p| {
        p.x >= lo.x - 1e-9
            && p.y >= lo.y - 1e-9
            && p.x <= hi.x + 1e-9
            && p.y <= hi.y + 1e-9
            && boxes.iter().all(|&(a, b)| {
                let (q0, q1) = (p - DVec2::splat(GAP), p + size + DVec2::splat(GAP));
                q1.x <= a.x || b.x <= q0.x || q1.y <= a.y || b.y <= q0.y
            })
    })
}

/// The bounds of `rings`, if they have points.
fn bounds(rings: &[Vec<DVec2>]) -> Option<(DVec2, DVec2)> {
    let mut points = rings.iter().flatten();
    let first = *points.next()?;
    Some(points.fold((first, first), |(a, b), p| (a.min(*p), b.max(*p))))
}

#[cfg(test)]
mod tests {
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

    #[test]
    fn the_legend_avoids_the_parts_and_stays_on_the_sheet() {
        // A part in the top-left corner: the legend goes to the top-right one.
        let parts = [square(0.0, 0.0, 100.0)];
        let lines = vec!["7/8: NUMBER 7 ON PART 8".to_string()];
        let g = legend_group(&lines, 300.0, 200.0, &parts).expect("room");
        assert!(g.cut.is_empty());
        let (lo, hi) = bounds(&g.engrave).expect("text");
        assert!(lo.x >= 100.0 + GAP && hi.x <= 300.0 - GAP + 1e-9, "{lo} {hi}");
        assert!(lo.y >= GAP - 1e-9 && hi.y <= 200.0 - GAP, "{lo} {hi}");
        // No room at all: no legend.
        assert!(legend_group(&lines, 100.0, 100.0, &[square(0.0, 0.0, 100.0)]).is_none());
    }
}
