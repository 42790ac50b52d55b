//! report.json: what the conversion did and what cutting it will take.
//!
//! The laser's time per sheet is its path in cut order at the laser setting's speeds for the
//! sheet's material and thickness, pierces and travel included; `fabrication` adds the
//! maker's handwork and sets it against printing the model ([`crate::fabrication`]).

use serde::Serialize;

use super::order::CutPath;
use crate::context::Warning;
use crate::draw::svg::SvgGroup;
use crate::plan::{Method, PlanSettings};
use crate::sheets::Nesting;

/// One step in report.json.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ReportStep {
    /// The step's name.
    pub name: String,
    /// Wall time in ms; only with `report_timings` (timings differ between runs).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub millis: Option<f64>,
    /// Its warnings.
    pub warnings: Vec<String>,
}

/// One sheet in report.json.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ReportSheet {
    /// Index as in plan.json.
    pub index: u32,
    /// Its SVG file.
    pub file: String,
    /// Material thickness, mm.
    pub thickness: f64,
    /// Width, mm.
    pub width: f64,
    /// Height, mm.
    pub height: f64,
    /// Parts on it.
    pub parts: usize,
    /// Parts' area over used area.
    pub density: f64,
    /// Used area (height × used length), mm².
    pub used_area: f64,
    /// The laser's path through the sheet's file, in its cut order (`export::order`): cut,
    /// engrave and travel lengths, mm, and the pierces.
    #[serde(flatten)]
    pub path: CutPath,
    /// The speeds the sheet is cut with (the `laser` setting's for its material and thickness).
    pub laser_speeds: crate::plan::LaserSpeeds,
    /// The laser's time for the sheet, s.
    pub laser_seconds: f64,
}

/// report.json.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Report {
    /// "platener" and its version.
    pub generator: String,
    /// The model's name.
    pub model: String,
    /// The method.
    pub method: Method,
    /// The settings (as in plan.json).
    pub settings: PlanSettings,
    /// Every step: earlier ones (read, plates…) and kerf, labels, sheets, export.
    pub steps: Vec<ReportStep>,
    /// Every warning of the cutting-plan steps, with the part it concerns.
    #[serde(serialize_with = "part_warnings")]
    pub warnings: Vec<Warning>,
    /// Number of parts.
    pub part_count: usize,
    /// Number of sheets.
    pub sheet_count: usize,
    /// The fewest sheets that could hold the parts: per thickness, the parts' area over the
    /// area inside a sheet's margins, rounded up (an extension; makers judge nesting by it).
    pub sheet_count_lower_bound: usize,
    /// Per sheet.
    pub sheets: Vec<ReportSheet>,
    /// All parts' area over all used area.
    pub density: f64,
    /// Nominal area of all parts, mm².
    pub parts_area: f64,
    /// Material used: sum of the sheets' used areas, mm².
    pub material_used_area: f64,
    /// Sum of the sheets' full areas, mm².
    pub sheet_area: f64,
    /// Length of all cut paths, mm.
    pub cut_length: f64,
    /// Length of all engraving, mm.
    pub engrave_length: f64,
    /// Estimated laser time, s: the sheets' `laser_seconds` added up.
    pub estimated_cutting_seconds: f64,
    /// The object's making time, laser and hands, against printing it (an extension, issue 35).
    pub fabrication: crate::fabrication::Fabrication,
    /// The assembly instructions' steps as the ZIP's assembly.html tells them (an extension,
    /// issue 35): what the page lists beside its 3D player.
    pub assembly_steps: Vec<super::instructions::StepText>,
    /// Edges that fit where they do not belong (an extension, issue 35; `platener verify`'s
    /// `edges` line): pairs of non-partner finger-like edges that accept each other, those
    /// between interchangeable twins apart, and the groups of twins.
    pub mismatched_edges: crate::verify::MismatchReport,
    /// What the method reports about itself (the plate method: which faces became plates and
    /// why the others did not).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub method_report: Option<serde_json::Value>,
}

fn length(points: &[glam::DVec2], closed: bool) -> f64 {
    let open: f64 = points.windows(2).map(|w| w[0].distance(w[1])).sum();
    match (closed, points.first(), points.last()) {
        (true, Some(a), Some(b)) => open + a.distance(*b),
        _ => open,
    }
}

/// Lengths of cut paths (rings and slits: the laser cuts both) and engraving over all
/// sheets, mm.
pub fn lengths(groups: &[Vec<SvgGroup>]) -> (f64, f64) {
    let all = groups.iter().flatten();
    let rings: f64 = all.clone().flat_map(|g| &g.cut).map(|r| length(r, true)).sum();
    let slits: f64 = all.clone().flat_map(|g| &g.slits).map(|l| length(l, false)).sum();
    let cut = rings + slits;
    let engrave = all
        .flat_map(|g| g.engrave.iter().map(|e| &e.path))
        .map(|l| length(l, false))
        .sum();
    (cut, engrave)
}

/// Everything of report.json but the header, computed from the nesting and the drawings.
pub struct Totals {
    /// Per sheet.
    pub sheets: Vec<ReportSheet>,
    /// Overall density.
    pub density: f64,
    /// Parts' area, mm².
    pub parts_area: f64,
    /// Used area, mm².
    pub used_area: f64,
    /// Full sheet area, mm².
    pub sheet_area: f64,
}

/// The fewest sheets the parts could need (see [`Report::sheet_count_lower_bound`]); with
/// sheets sized to fit, one per thickness.
pub fn sheet_lower_bound(nesting: &Nesting, settings: &crate::plan::CutSettings) -> usize {
    let mut by_thickness: std::collections::BTreeMap<u64, f64> = std::collections::BTreeMap::new();
    for s in &nesting.sheets {
        *by_thickness.entry(s.thickness.to_bits()).or_default() += s.parts_area;
    }
    let usable = |width: f64, height: f64| (width - 2.0 * settings.margin) * (height - 2.0 * settings.margin);
    by_thickness
        .iter()
        .map(|(bits, &area)| {
            let stock = settings.stock_of(f64::from_bits(*bits));
            match settings.sheet {
                _ if !stock.is_empty() => stock_lower_bound(area, &stock, usable),
                crate::plan::SheetSize::Fit => 1,
                crate::plan::SheetSize::Fixed { width, height } => {
                    (area / usable(width, height)).ceil().max(1.0) as usize
                }
            }
        })
        .sum()
}

/// The fewest sheets of `stock` whose usable areas add up to `area`: the largest first, each
/// kind as many times as it counts (the last without a count as often as needed).
fn stock_lower_bound(area: f64, stock: &[crate::plan::StockSheet], usable: impl Fn(f64, f64) -> f64) -> usize {
    let mut kinds: Vec<(f64, Option<u32>)> = stock.iter().map(|s| (usable(s.width, s.height), s.count)).collect();
    kinds.sort_by(|a, b| b.0.total_cmp(&a.0));
    let (mut left, mut sheets) = (area, 0usize);
    for (each, count) in kinds {
        if left <= 0.0 || each <= 0.0 {
            break;
        }
        let need = (left / each).ceil() as usize;
        let take = count.map_or(need, |n| need.min(n as usize));
        sheets += take;
        left -= take as f64 * each;
    }
    sheets.max(1)
}

/// Per-sheet and overall areas and densities.
pub fn totals(nesting: &Nesting, files: &[String], paths: &[CutPath], settings: &crate::plan::CutSettings) -> Totals {
    let sheets: Vec<ReportSheet> = nesting
        .sheets
        .iter()
        .zip(files)
        .zip(paths)
        .map(|((s, f), path)| {
            let speeds = settings.laser.speeds(settings.material, s.thickness);
            (s, f, path, speeds)
        })
        .map(|(s, f, path, speeds)| ReportSheet {
            index: s.index,
            file: f.clone(),
            thickness: s.thickness,
            width: s.width,
            height: s.height,
            parts: s.parts.len(),
            density: s.density,
            used_area: s.used_area,
            path: *path,
            laser_speeds: speeds,
            laser_seconds: crate::fabrication::laser_seconds(path.sheet_path(), speeds),
        })
        .collect();
    let parts_area: f64 = nesting.sheets.iter().map(|s| s.parts_area).sum();
    let used_area: f64 = nesting.sheets.iter().map(|s| s.used_area).sum();
    Totals {
        sheets,
        density: if used_area > 0.0 { parts_area / used_area } else { 0.0 },
        parts_area,
        used_area,
        sheet_area: nesting.sheets.iter().map(|s| s.width * s.height).sum(),
    }
}

/// report.json's form of a cutting-plan warning: the step, the part (or null), the message.
fn part_warnings<S: serde::Serializer>(warnings: &[Warning], serializer: S) -> Result<S::Ok, S::Error> {
    #[derive(Serialize)]
    struct Entry<'a> {
        step: &'a str,
        part: Option<u32>,
        message: &'a str,
    }
    serializer.collect_seq(warnings.iter().map(|w| Entry {
        step: w.step,
        part: w.part,
        message: &w.message,
    }))
}

#[cfg(test)]
mod stock_tests {
    use super::*;
    use crate::plan::StockSheet;

    /// The fewest stock sheets whose usable areas cover the parts: the largest first, counts
    /// kept, the last kind as often as needed.
    #[test]
    fn the_lower_bound_takes_the_largest_stock_first() {
        let usable = |w: f64, h: f64| w * h;
        let sheet = |w, h, count| StockSheet {
            thickness: 3.0,
            width: w,
            height: h,
            count,
        };
        let stock = [sheet(100.0, 100.0, None), sheet(200.0, 100.0, Some(2))];
        // 45 000 mm²: both large sheets (40 000) and one small one.
        assert_eq!(stock_lower_bound(45_000.0, &stock, usable), 3);
        assert_eq!(stock_lower_bound(15_000.0, &stock, usable), 1);
        assert_eq!(stock_lower_bound(75_000.0, &stock, usable), 6);
    }
}
