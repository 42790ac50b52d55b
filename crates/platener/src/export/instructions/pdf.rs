//! `assembly.pdf`: the instructions to print, on A4 in portrait: the parts list (each part
//! drawn to fit a cell, with its number), then two steps a page, each its picture and its
//! sentences in the labels' single-stroke font (the file embeds no font; capitals only).

use glam::DVec2;
use krilla::geom::{Size, Transform};
use krilla::image::Image;
use krilla::page::PageSettings;

use super::{Instruction, PICTURE};
use crate::draw::font;
use crate::draw::svg::Stroke;
use crate::export::pdf::{PT_PER_MM, draw, new_document};
use crate::plan::{Plan, PlanError, PlanPart};

/// A4, mm.
const PAGE: DVec2 = DVec2::new(210.0, 297.0);
/// The margin around everything, mm.
const MARGIN: f64 = 15.0;
/// Text height (capitals), mm.
const TEXT: f64 = 3.2;
/// Line spacing, mm.
const LINE: f64 = 5.5;
/// Parts list cells, mm: columns and rows of a page.
const CELL: DVec2 = DVec2::new(36.0, 40.0);
/// Steps a page.
pub const STEPS_PER_PAGE: usize = 2;
/// Ink: black, 0.3 mm.
const INK: Stroke = Stroke {
    color: "#000000",
    width: 0.3,
};

/// The document: parts list pages, then the steps.
pub fn document(plan: &Plan, steps: &[Instruction], title: &str) -> Result<Vec<u8>, PlanError> {
    let mut document = new_document();
    let page_size = PAGE * PT_PER_MM;
    let a4 = || PageSettings::from_wh(page_size.x as f32, page_size.y as f32).expect("A4 has an area");
    let per_page = cells_per_page();
    let parts: Vec<&PlanPart> = plan.parts.iter().collect();
    for (k, chunk) in parts.chunks(per_page.max(1)).enumerate() {
        let mut page = document.start_page_with(a4());
        let mut surface = page.surface();
        surface.push_transform(&Transform::from_scale(PT_PER_MM as f32, PT_PER_MM as f32));
        let mut y = MARGIN;
        if k == 0 {
            text(
                &mut surface,
                &format!("{title}: assembly"),
                DVec2::new(MARGIN, y + 6.0),
                6.0,
            );
            y += 12.0;
            let intro = format!("{} parts in {} steps", plan.parts.len(), steps.len());
            text(&mut surface, &intro, DVec2::new(MARGIN, y + TEXT), TEXT);
            y += LINE * 2.0;
        }
        for (i, part) in chunk.iter().enumerate() {
            let columns = ((PAGE.x - 2.0 * MARGIN) / CELL.x).floor() as usize;
            let at = DVec2::new(
                MARGIN + (i % columns) as f64 * CELL.x,
                y + (i / columns) as f64 * CELL.y,
            );
            part_cell(&mut surface, part, at);
        }
        surface.pop();
        surface.finish();
        page.finish();
    }
    for chunk in steps.chunks(STEPS_PER_PAGE) {
        let mut page = document.start_page_with(a4());
        let mut surface = page.surface();
        surface.push_transform(&Transform::from_scale(PT_PER_MM as f32, PT_PER_MM as f32));
        let half = (PAGE.y - 2.0 * MARGIN) / STEPS_PER_PAGE as f64;
        for (i, step) in chunk.iter().enumerate() {
            step_block(&mut surface, step, steps.len(), MARGIN + i as f64 * half)?;
        }
        surface.pop();
        surface.finish();
        page.finish();
    }
    document
        .finish()
        .map_err(|e| PlanError::write("assembly.pdf", format!("{e:?}")))
}

/// Parts list cells on a page (the first page's title takes two rows' worth less room, so
/// every page holds the same count: the smaller).
fn cells_per_page() -> usize {
    let columns = ((PAGE.x - 2.0 * MARGIN) / CELL.x).floor() as usize;
    let rows = ((PAGE.y - 2.0 * MARGIN - 12.0 - 2.0 * LINE) / CELL.y).floor() as usize;
    columns * rows
}

/// One step: heading, picture (the page's width), sentences wrapped to the width.
fn step_block(
    surface: &mut krilla::surface::Surface,
    step: &Instruction,
    total: usize,
    top: f64,
) -> Result<(), PlanError> {
    let heading = format!("Step {} of {total}", step.number);
    text(surface, &heading, DVec2::new(MARGIN, top + 5.0), 5.0);
    let width = PAGE.x - 2.0 * MARGIN;
    let height = width * f64::from(PICTURE.1) / f64::from(PICTURE.0) * 0.7;
    let image_width = height * f64::from(PICTURE.0) / f64::from(PICTURE.1);
    let rgba: Vec<u8> = step
        .picture
        .chunks_exact(3)
        .flat_map(|c| [c[0], c[1], c[2], 255])
        .collect();
    let image = Image::from_rgba8(rgba, PICTURE.0, PICTURE.1);
    let size = Size::from_wh(image_width as f32, height as f32)
        .ok_or_else(|| PlanError::write("assembly.pdf", "a step picture has no size"))?;
    surface.push_transform(&Transform::from_translate(MARGIN as f32, (top + 8.0) as f32));
    surface.draw_image(image, size);
    surface.pop();
    let mut y = top + 8.0 + height + LINE;
    for line in &step.lines {
        for row in wrap(line, width) {
            text(surface, &row, DVec2::new(MARGIN, y), TEXT);
            y += LINE;
        }
    }
    Ok(())
}

/// A part in its cell: its outline and holes scaled to fit above its number.
fn part_cell(surface: &mut krilla::surface::Surface, part: &PlanPart, at: DVec2) {
    let (lo, hi) = part.outline.iter().fold(
        (DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY)),
        |(lo, hi), p| (lo.min(*p), hi.max(*p)),
    );
    let room = DVec2::new(CELL.x - 4.0, CELL.y - 10.0);
    let size = (hi - lo).max(DVec2::splat(1e-6));
    let scale = (room.x / size.x).min(room.y / size.y);
    // y up in the part's frame, down on the page.
    let place = |p: &DVec2| at + DVec2::new(p.x - lo.x, hi.y - p.y) * scale;
    for ring in std::iter::once(&part.outline).chain(&part.holes) {
        let points: Vec<DVec2> = ring.iter().map(place).collect();
        draw(surface, &points, true, INK);
    }
    let label = format!("{}: {:.0}X{:.0}", part.id, size.x, size.y);
    text(surface, &label, at + DVec2::new(0.0, room.y + 6.0), TEXT);
}

/// `words` in capitals with its baseline's left end at `at` (page mm, y down), in the
/// labels' font: characters it lacks (commas, ×) as the nearest it has.
fn text(surface: &mut krilla::surface::Surface, words: &str, at: DVec2, size: f64) {
    let plain = words
        .replace('×', "X")
        .replace(',', "")
        .replace('−', "-")
        .to_uppercase();
    for stroke in font::place_text(&plain, size, at, DVec2::X) {
        draw(surface, &stroke, false, INK);
    }
}

/// `line` cut at spaces into rows no wider than `width` mm at the text size.
fn wrap(line: &str, width: f64) -> Vec<String> {
    let mut rows: Vec<String> = Vec::new();
    for word in line.split(' ') {
        match rows.last_mut() {
            Some(row) if font::text_width(&format!("{row} {word}"), TEXT) <= width => {
                row.push(' ');
                row.push_str(word);
            }
            _ => rows.push(word.to_string()),
        }
    }
    rows
}
