//! Step `export`: SVG and DXF per sheet, PNG previews, report.json and the ZIP.
//!
//! Everything the user takes to the laser and everything third-party programs read comes out
//! of here as one ZIP: plan.json (the contract in `shared/spec/plan-format.md`), report.json,
//! assembly.glb (the assembled parts in 3D, [`crate::scene::assembly`]), thumbnail.png (the
//! assembly drawn small, [`thumbnail`]), and per sheet an SVG ([`svg`]), a DXF ([`dxf`]), a
//! LightBurn project ([`lightburn`]) and a PNG preview ([`png`]), all in cut order ([`order`]),
//! and one PDF of all sheets ([`pdf`]). Entries are
//! sorted by name and stamped 1980-01-01 with mode 0644, and report.json carries no timings
//! unless asked, so the same input and settings give a byte-identical ZIP.

pub mod dxf;
pub mod instructions;
pub mod legend;
pub mod lightburn;
pub mod order;
pub mod pdf;
pub mod plan_json;
pub mod png;
pub mod reference;
pub mod report;
pub mod thumbnail;

use std::collections::BTreeMap;
use std::io::{Cursor, Write};

use serde::Serialize;
use zip::write::SimpleFileOptions;
use zip::{CompressionMethod, DateTime, ZipWriter};

use crate::context::StepRecord;
use crate::fabrication::{Fabrication, handwork::Handwork};
use crate::kerf::CutPaths;
use crate::labels::Labels;
use crate::plan::{Plan, PlanError, PlanInput};
use crate::sheets::Nesting;
use report::{Report, ReportStep};
/// The cutting-plan steps before `export`, whose warnings report.json lists with their parts.
pub const CUTTING_PLAN_STEPS: [&str; 3] = ["kerf", "labels", "sheets"];
use crate::draw::svg::{self, SvgStyle, sheet_svg};

/// Stroke widths of the PNG previews, mm: visible at 1200 pixels across a 600 mm sheet.
const PREVIEW_STYLE: SvgStyle = SvgStyle::preview(0.8, 0.4);

/// The snapshot of step `export`: the plan, the report, every file, and the ZIP of them.
#[derive(Debug, Clone, Serialize)]
pub struct Bundle {
    /// plan.json as data.
    pub plan: Plan,
    /// report.json as data.
    pub report: Report,
    /// Every file of the ZIP by name (plan.json, report.json, assembly.glb, thumbnail.png,
    /// the sheets' .svg/.dxf/.png).
    #[serde(skip)]
    pub files: BTreeMap<String, Vec<u8>>,
    /// The ZIP.
    #[serde(skip)]
    pub zip: Vec<u8>,
}

/// Step `export`: every file and the ZIP from the snapshots; `steps` are the records of every
/// step that ran before (report.json lists them).
pub fn run(
    input: &PlanInput,
    cut: &CutPaths,
    labels: &Labels,
    nesting: &Nesting,
    steps: &[StepRecord],
) -> Result<Bundle, PlanError> {
    let stem = plan_json::file_stem(&input.source.name);
    let stems = plan_json::sheet_stems(&stem, nesting, &input.settings);
    let mut groups = plan_json::sheet_groups(input, cut, labels, nesting);
    let legends = sheet_legends(input, nesting, &groups);
    for (g, legend) in groups.iter_mut().zip(&legends) {
        g.extend(legend.as_ref().and_then(legend::Legend::group));
    }
    let squares = reference_squares(input, nesting, &mut groups);
    let (groups, paths): (Vec<Vec<svg::SvgGroup>>, Vec<order::CutPath>) =
        groups.into_iter().map(order::order_sheet).unzip();
    let plan = plan_json::build_plan(input, cut, labels, nesting, &stems, (&legends, &squares));
    // The sheets' files (the PNG previews above all) and the rest (report, 3D assembly,
    // thumbnail) do not depend on each other: made side by side, the plan is ready sooner. The
    // files are keyed by name, so the ZIP is the same whichever finishes first.
    let stocks = stocks(nesting, &stems, &input.settings);
    let (sheets, rest) = rayon::join(
        || sheet_files(nesting, (&stems, &stocks), &groups, &input.settings),
        || plan_files(input, nesting, steps, (&groups, &paths), &stems, &plan),
    );
    let (report, rest) = rest?;
    let pdf = all_sheets_pdf(&stem, nesting, &groups, &stocks, input.settings.colors)?;
    let files: BTreeMap<String, Vec<u8>> = sheets?.into_iter().chain(rest).chain([pdf]).collect();
    let zip = zip_files(&files)?;
    Ok(Bundle {
        plan,
        report,
        files,
        zip,
    })
}

/// Files of the bundle by name, in no particular order (the ZIP sorts them).
type Files = Vec<(String, Vec<u8>)>;

/// Which stock each sheet is ("box-3mm-1: 3 mm wood sheet, 600 × 400 mm"), as the SVG's
/// title, the LightBurn project's notes and the PDF's captions say.
/// A measured sheet says both ("3 mm wood sheet measured 2.85 mm").
fn stocks(nesting: &Nesting, stems: &[String], settings: &crate::plan::CutSettings) -> Vec<String> {
    nesting
        .sheets
        .iter()
        .zip(stems)
        .map(|(sheet, stem)| {
            let nominal = settings.nominal(sheet.thickness);
            let measured = if nominal.total_cmp(&sheet.thickness).is_eq() {
                String::new()
            } else {
                format!(" measured {} mm", svg::num(sheet.thickness))
            };
            format!(
                "{stem}: {} mm {} sheet{measured}, {} × {} mm",
                svg::num(nominal),
                settings.material.name(),
                svg::num(sheet.width),
                svg::num(sheet.height)
            )
        })
        .collect()
}

/// `{stem}.pdf`: every sheet on a page of its own at true size ([`pdf`]).
fn all_sheets_pdf(
    stem: &str,
    nesting: &Nesting,
    groups: &[Vec<svg::SvgGroup>],
    stocks: &[String],
    colors: crate::plan::ColorProfile,
) -> Result<(String, Vec<u8>), PlanError> {
    let sheets: Vec<pdf::PdfSheet> = nesting
        .sheets
        .iter()
        .zip(groups)
        .zip(stocks)
        .map(|((sheet, g), stock)| pdf::PdfSheet {
            width: sheet.width,
            height: sheet.height,
            groups: g,
            stock,
        })
        .collect();
    let name = format!("{stem}.pdf");
    let bytes = pdf::plan_pdf(&name, &sheets, &svg::Palette::of(colors))?;
    Ok((name, bytes))
}

/// Every sheet's SVG, DXF and PNG preview, the sheets side by side.
fn sheet_files(
    nesting: &Nesting,
    (stems, stocks): (&[String], &[String]),
    groups: &[Vec<svg::SvgGroup>],
    settings: &crate::plan::CutSettings,
) -> Result<Files, PlanError> {
    use rayon::prelude::*;
    let per_sheet: Vec<Files> = nesting
        .sheets
        .par_iter()
        .zip(stems)
        .zip(stocks)
        .zip(groups)
        .map(|(((sheet, stem), stock), g)| {
            let style = SvgStyle::cut(settings.colors);
            let svg = svg::titled(&sheet_svg(sheet.width, sheet.height, g, &style), stock);
            let dxf_name = format!("{stem}.dxf");
            let dxf = dxf::sheet_dxf(sheet.width, sheet.height, g, &dxf_name)?;
            let lightburn = lightburn::sheet_lbrn2((sheet.width, sheet.height, sheet.thickness), g, settings, stock);
            let png_name = format!("{stem}.png");
            let caption = pdf::caption_strokes(stock, sheet.width, sheet.height, g);
            let preview = png::captioned(&sheet_svg(sheet.width, sheet.height, g, &PREVIEW_STYLE), &caption);
            let png = png::render_png(&preview, &png_name)?;
            Ok(vec![
                (format!("{stem}.svg"), svg.into_bytes()),
                (dxf_name, dxf),
                (format!("{stem}.lbrn2"), lightburn.into_bytes()),
                (png_name, png),
            ])
        })
        .collect::<Result<_, PlanError>>()?;
    Ok(per_sheet.into_iter().flatten().collect())
}

/// report.json (returned too), plan.json, the 3D assembly, its thumbnail and the assembly
/// instructions.
fn plan_files(
    input: &PlanInput,
    nesting: &Nesting,
    steps: &[StepRecord],
    drawn: (&[Vec<svg::SvgGroup>], &[order::CutPath]),
    stems: &[String],
    plan: &Plan,
) -> Result<(Report, Files), PlanError> {
    // The parts were validated by now, so a scene that cannot be written is our bug.
    let assembly = crate::scene::Assembly::new(&input.parts).map_err(|e| PlanError::write("assembly.glb", e))?;
    let scene = assembly.scene().map_err(|e| PlanError::write("assembly.glb", e))?;
    let edges = crate::verify::mismatched_edges(plan);
    let instructions = instructions::instructions(plan, &assembly, &edges.interchangeable_parts);
    let mut report = build_report(input, nesting, steps, drawn, stems);
    report.assembly_steps = instructions.iter().map(instructions::StepText::of).collect();
    report.mismatched_edges = edges;
    let report_json = serde_json::to_string_pretty(&report).map_err(|e| PlanError::write("report.json", e))?;
    let mut files = vec![
        ("plan.json".to_string(), plan.to_json()?.into_bytes()),
        ("report.json".to_string(), report_json.into_bytes()),
        ("assembly.glb".to_string(), scene.glb),
        (thumbnail::FILE.to_string(), thumbnail::thumbnail(&assembly)?),
    ];
    files.extend(instructions::files(plan, &instructions, &input.source.name)?);
    Ok((report, files))
}

/// Each sheet's legend saying where the numbers of its parts too thin for them went
/// ([`legend`]), placed beside its parts when there is room; `None` for a sheet whose every
/// number is on its own part.
fn sheet_legends(input: &PlanInput, nesting: &Nesting, groups: &[Vec<svg::SvgGroup>]) -> Vec<Option<legend::Legend>> {
    let report = input.method_report.as_ref();
    let lines_of = |index: usize| {
        let mut on_sheet: Vec<u32> = input
            .parts
            .iter()
            .zip(&nesting.placements)
            .filter(|(_, p)| p.index as usize == index)
            .map(|(part, _)| part.id)
            .collect();
        on_sheet.sort_unstable();
        legend::legend_lines(report, &on_sheet)
    };
    nesting
        .sheets
        .iter()
        .zip(groups)
        .enumerate()
        .map(|(index, (sheet, g))| legend::Legend::place(lines_of(index), sheet.width, sheet.height, g))
        .collect()
}

/// With `reference-square` on, each sheet's reference square added to its groups where
/// there is room ([`reference`]); its corners per sheet.
fn reference_squares(
    input: &PlanInput,
    nesting: &Nesting,
    groups: &mut [Vec<svg::SvgGroup>],
) -> Vec<Option<[glam::DVec2; 2]>> {
    if !input.settings.reference_square {
        return vec![None; nesting.sheets.len()];
    }
    nesting
        .sheets
        .iter()
        .zip(groups)
        .map(|(sheet, g)| {
            let (square, corners) = reference::place(sheet.width, sheet.height, g).unzip();
            g.extend(square);
            corners
        })
        .collect()
}

fn build_report(
    input: &PlanInput,
    nesting: &Nesting,
    records: &[StepRecord],
    (groups, paths): (&[Vec<svg::SvgGroup>], &[order::CutPath]),
    stems: &[String],
) -> Report {
    let timed = input.settings.report_timings;
    let mut steps: Vec<ReportStep> = records
        .iter()
        .map(|s| ReportStep {
            name: s.name.into(),
            millis: timed.then_some(s.millis),
            warnings: s.warnings.iter().map(|w| w.message.clone()).collect(),
        })
        .collect();
    steps.push(ReportStep {
        name: "export".into(),
        millis: None,
        warnings: Vec::new(),
    });
    let files: Vec<String> = stems.iter().map(|s| format!("{s}.svg")).collect();
    let t = report::totals(nesting, &files, paths, &input.settings);
    let (cut_length, engrave_length) = report::lengths(groups);
    let laser_seconds: f64 = t.sheets.iter().map(|s| s.laser_seconds).sum();
    let kinds = input.joints.iter().map(|j| j.kind);
    // A glued pair that is no joint (stacked layers no shaft joins) is glued all the same.
    let joined = |g: &&crate::plan::Glue| {
        let pair = |p: [u32; 2]| (p[0].min(p[1]), p[0].max(p[1]));
        input.joints.iter().any(|j| pair(j.parts) == pair(g.parts))
    };
    let glued = input
        .glued
        .iter()
        .filter(|g| !joined(g))
        .map(|_| crate::plan::JointKind::Glued);
    let handwork = Handwork::new(nesting.sheets.len(), input.parts.len(), kinds.chain(glued));
    let fabrication = Fabrication::new(input.settings.laser.text(), laser_seconds, handwork, input.source.print);
    Report {
        generator: plan_json::generator(),
        model: input.source.name.clone(),
        method: input.method,
        settings: plan_json::plan_settings(input),
        steps,
        warnings: records
            .iter()
            .filter(|r| CUTTING_PLAN_STEPS.contains(&r.name))
            .flat_map(|r| r.warnings.iter().cloned())
            .collect(),
        part_count: input.parts.len(),
        sheet_count: nesting.sheets.len(),
        sheet_count_lower_bound: report::sheet_lower_bound(nesting, &input.settings),
        sheets: t.sheets,
        density: t.density,
        parts_area: t.parts_area,
        material_used_area: t.used_area,
        sheet_area: t.sheet_area,
        cut_length,
        engrave_length,
        estimated_cutting_seconds: laser_seconds,
        fabrication,
        assembly_steps: Vec::new(),
        mismatched_edges: crate::verify::MismatchReport::default(),
        method_report: input.method_report.clone(),
    }
}

/// A ZIP of `files` in name order, with fixed timestamps and permissions.
pub fn zip_files(files: &BTreeMap<String, Vec<u8>>) -> Result<Vec<u8>, PlanError> {
    let options = SimpleFileOptions::default()
        .compression_method(CompressionMethod::Deflated)
        .last_modified_time(DateTime::default())
        .unix_permissions(0o644);
    // A PNG is deflated already; deflating it again costs time and saves nothing.
    let stored = options.compression_method(CompressionMethod::Stored);
    let mut zip = ZipWriter::new(Cursor::new(Vec::new()));
    for (name, bytes) in files {
        let options = if name.ends_with(".png") { stored } else { options };
        zip.start_file(name.as_str(), options)
            .map_err(|e| PlanError::write(name, e))?;
        zip.write_all(bytes).map_err(|e| PlanError::write(name, e))?;
    }
    let cursor = zip.finish().map_err(|e| PlanError::write("the ZIP", e))?;
    Ok(cursor.into_inner())
}
