//! The PDF of every sheet (issue 34): one page per sheet at true size, for print shops that
//! take PDF, for laser programs that import it, and to print at 100 % and lay parts on.
//!
//! Each page is exactly its sheet (mm × 72 / 25.4 points) and draws the sheet's paths in cut
//! order with the SVG's strokes (the `colors` profile), as vector paths. Every page has a
//! 100 mm reference square beside the parts, where there is room (the `reference-square`
//! setting adds it to the other files too), and names its stock in grey in a free corner
//! (and in the document's outline, which readers show as bookmarks), because a printed page
//! no longer has a file name. Text is the labels' single-stroke font: the file embeds no font.

pub mod read;

use glam::DVec2;
use krilla::color::rgb;
use krilla::destination::XyzDestination;
use krilla::geom::{PathBuilder, Point, Transform};
use krilla::metadata::Metadata;
use krilla::outline::{Outline, OutlineNode};
use krilla::page::PageSettings;
use krilla::paint::{LineCap, LineJoin, Stroke as PdfStroke};
use krilla::{Document, SerializeSettings};

use super::reference::{self, REFERENCE_ID};
use crate::draw::font;
use crate::draw::svg::{Engraved, Palette, Stroke, SvgGroup, rgb};
use crate::plan::PlanError;

/// Points per millimetre.
pub const PT_PER_MM: f64 = 72.0 / 25.4;
/// The caption's colour: grey, no operation's colour in any profile.
pub const CAPTION_COLOR: &str = crate::draw::svg::SHEET_COLOR;
/// The caption's cap height, mm.
const CAPTION_SIZE: f64 = 4.0;
/// The caption's stroke: grey, 0.3 mm.
const CAPTION_STROKE: Stroke = Stroke {
    color: CAPTION_COLOR,
    width: 0.3,
};
/// The caption's distance to the sheet's edges and to any part, mm.
const CAPTION_GAP: f64 = 3.0;

/// One sheet of the PDF.
#[derive(Debug, Clone, Copy)]
pub struct PdfSheet<'a> {
    /// Width, mm.
    pub width: f64,
    /// Height, mm.
    pub height: f64,
    /// The sheet's groups in cut order (parts, legend, reference square).
    pub groups: &'a [SvgGroup],
    /// Which stock the sheet is ("box-3mm-1: 3 mm wood sheet, 600 × 400 mm").
    pub stock: &'a str,
}

/// A document as every PDF of ours is written: no XMP packet and no tagging (drawings, not
/// text documents), so the same content gives the same bytes.
pub(crate) fn new_document() -> Document {
    Document::new_with(SerializeSettings {
        xmp_metadata: false,
        enable_tagging: false,
        ..SerializeSettings::default()
    })
}

/// The PDF of `sheets`, one page each, stroked with `palette`; `title` names the document.
pub fn plan_pdf(title: &str, sheets: &[PdfSheet], palette: &Palette) -> Result<Vec<u8>, PlanError> {
    let mut document = new_document();
    let mut outline = Outline::new();
    for (index, sheet) in sheets.iter().enumerate() {
        let size = DVec2::new(sheet.width, sheet.height) * PT_PER_MM;
        let page_settings = PageSettings::from_wh(size.x as f32, size.y as f32)
            .ok_or_else(|| PlanError::write(title, format!("sheet {} has no area", index + 1)))?;
        let mut page = document.start_page_with(page_settings);
        let mut surface = page.surface();
        surface.push_transform(&Transform::from_scale(PT_PER_MM as f32, PT_PER_MM as f32));
        let square = extra_square(sheet);
        let groups = || sheet.groups.iter().chain(square.as_ref());
        for d in groups().flat_map(|g| g.drawn(palette)) {
            draw(&mut surface, d.points, d.closed, d.stroke);
        }
        for e in caption_strokes(sheet.stock, sheet.width, sheet.height, groups()) {
            draw(&mut surface, &e.path, false, CAPTION_STROKE);
        }
        surface.pop();
        surface.finish();
        page.finish();
        outline.push_child(OutlineNode::new(
            sheet.stock.to_string(),
            XyzDestination::new(index, Point::from_xy(0.0, 0.0)),
        ));
    }
    document.set_outline(outline);
    document.set_metadata(
        Metadata::new()
            .title(title.to_string())
            .creator(crate::export::plan_json::generator()),
    );
    document.finish().map_err(|e| PlanError::write(title, format!("{e:?}")))
}

/// The reference square the PDF adds to `sheet`: none when its groups have one already
/// (`reference-square` on) or there is no room beside the parts.
fn extra_square(sheet: &PdfSheet) -> Option<SvgGroup> {
    if sheet.groups.iter().any(|g| g.id == REFERENCE_ID) {
        return None;
    }
    reference::place(sheet.width, sheet.height, sheet.groups).map(|(g, _)| g)
}

/// The strokes of `stock` in capitals in the first free corner of the sheet (bottom left,
/// bottom right, top right, top left), clear of every group; none without such a corner.
pub fn caption_strokes<'a>(
    stock: &str,
    width: f64,
    height: f64,
    groups: impl IntoIterator<Item = &'a SvgGroup>,
) -> Vec<Engraved> {
    // In the labels' font's characters: it has no `×` and no comma.
    let text = stock.replace('×', "X").replace(", ", " - ").to_uppercase();
    let size = DVec2::new(font::text_width(&text, CAPTION_SIZE), CAPTION_SIZE);
    let (lo, hi) = (
        DVec2::splat(CAPTION_GAP),
        DVec2::new(width, height) - size - CAPTION_GAP,
    );
    if hi.x < lo.x || hi.y < lo.y {
        return Vec::new();
    }
    let boxes: Vec<(DVec2, DVec2)> = groups.into_iter().filter_map(reference::extent).collect();
    let free = |at: DVec2| {
        let (a, b) = (at - CAPTION_GAP, at + size + CAPTION_GAP);
        boxes
            .iter()
            .all(|(p, q)| b.x <= p.x || q.x <= a.x || b.y <= p.y || q.y <= a.y)
    };
    let corners = [DVec2::new(lo.x, hi.y), hi, DVec2::new(hi.x, lo.y), lo];
    let Some(at) = corners.into_iter().find(|&c| free(c)) else {
        return Vec::new();
    };
    // `place_text` takes the text's bottom-left corner; `at` is its top-left.
    font::place_text(&text, CAPTION_SIZE, at + DVec2::new(0.0, CAPTION_SIZE), DVec2::X)
        .into_iter()
        .map(Engraved::text)
        .collect()
}

/// Strokes one path, sheet mm (the surface is scaled to mm).
pub(crate) fn draw(surface: &mut krilla::surface::Surface, points: &[DVec2], closed: bool, stroke: Stroke) {
    let mut builder = PathBuilder::new();
    for (k, p) in points.iter().enumerate() {
        if k == 0 {
            builder.move_to(p.x as f32, p.y as f32);
        } else {
            builder.line_to(p.x as f32, p.y as f32);
        }
    }
    if closed {
        builder.close();
    }
    let Some(path) = builder.finish() else { return };
    let [r, g, b] = rgb(stroke.color);
    surface.set_fill(None);
    surface.set_stroke(Some(PdfStroke {
        paint: rgb::Color::new(r, g, b).into(),
        width: stroke.width as f32,
        line_cap: LineCap::Round,
        line_join: LineJoin::Round,
        ..PdfStroke::default()
    }));
    surface.draw_path(&path);
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::plan::ColorProfile;

    fn part(x0: f64, y0: f64, x1: f64, y1: f64) -> SvgGroup {
        SvgGroup {
            id: "part-1".into(),
            cut: vec![
                vec![
                    DVec2::new(x0 + 2.0, y0 + 2.0),
                    DVec2::new(x0 + 6.0, y0 + 2.0),
                    DVec2::new(x0 + 6.0, y0 + 6.0),
                ],
                vec![
                    DVec2::new(x0, y0),
                    DVec2::new(x1, y0),
                    DVec2::new(x1, y1),
                    DVec2::new(x0, y1),
                ],
            ],
            slits: vec![vec![DVec2::new(x0 + 10.0, y0 + 2.0), DVec2::new(x0 + 10.0, y0 + 8.0)]],
            engrave: vec![Engraved::text(vec![
                DVec2::new(x0 + 3.0, y0 + 12.0),
                DVec2::new(x0 + 5.0, y0 + 12.0),
            ])],
        }
    }

    /// A page is its sheet in points, draws the sheet's paths first in cut order with the
    /// profile's strokes, then a reference square (none on the sheet yet) and the stock in
    /// grey in a corner clear of everything; the same sheets give the same bytes.
    #[test]
    fn each_page_is_its_sheet_at_true_size_with_its_paths_square_and_stock() {
        let groups = [part(5.0, 5.0, 200.0, 150.0)];
        let sheets = [
            PdfSheet {
                width: 600.0,
                height: 400.0,
                groups: &groups,
                stock: "box-3mm-1: 3 mm wood sheet, 600 × 400 mm",
            },
            PdfSheet {
                width: 210.0,
                height: 160.0,
                groups: &groups,
                stock: "box-3mm-2: 3 mm wood sheet, 210 × 160 mm",
            },
        ];
        let palette = Palette::of(ColorProfile::LightBurn);
        let pdf = plan_pdf("box", &sheets, &palette).expect("writes");
        assert_eq!(
            pdf,
            plan_pdf("box", &sheets, &palette).expect("writes"),
            "deterministic"
        );
        assert!(pdf.starts_with(b"%PDF-"));
        let pages = read::read_pages(&pdf).expect("reads");
        assert_eq!(pages.len(), 2);
        for (page, sheet) in pages.iter().zip(&sheets) {
            assert!((page.size - DVec2::new(sheet.width, sheet.height)).abs().max_element() < 1e-4);
            let expected: Vec<_> = groups[0].drawn(&palette).collect();
            for (got, want) in page.paths.iter().zip(&expected) {
                assert_eq!(got.closed, want.closed);
                assert_eq!(got.color, rgb(want.stroke.color));
                assert!((got.width - want.stroke.width).abs() < 1e-6);
                assert_eq!(got.points.len(), want.points.len());
                for (a, b) in got.points.iter().zip(want.points) {
                    assert!(a.distance(*b) < 0.01, "{a} vs {b}");
                }
            }
            let rest = &page.paths[expected.len()..];
            let (grey, square): (Vec<&read::PdfPath>, Vec<&read::PdfPath>) =
                rest.iter().partition(|p| p.color == rgb(CAPTION_COLOR));
            assert!(!grey.is_empty(), "the stock is named on every page");
            let part_box = reference::extent(&groups[0]).expect("part");
            for p in grey.iter().flat_map(|p| &p.points) {
                assert!(
                    p.cmpge(DVec2::ZERO).all() && p.cmple(page.size).all(),
                    "{p} on the page"
                );
                assert!(p.x > part_box.1.x || p.y > part_box.1.y, "{p} clear of the part");
            }
            // The big sheet has room for the reference square, the small one not.
            let has_square = square.iter().any(|p| {
                let (lo, hi) = platener_geom::boxes::bounds2(p.points.iter().copied());
                !p.closed && (hi - lo - DVec2::splat(reference::SIDE)).abs().max_element() < 1e-3
            });
            assert_eq!(has_square, sheet.width > 300.0, "{}", sheet.stock);
        }
    }

    /// With `reference-square` on the sheet already has its square: the PDF adds none.
    #[test]
    fn a_sheet_with_its_square_gets_no_second_one() {
        let mut groups = vec![part(5.0, 5.0, 200.0, 150.0)];
        let (square, _) = reference::place(600.0, 400.0, &groups).expect("room");
        groups.push(square);
        let sheets = [PdfSheet {
            width: 600.0,
            height: 400.0,
            groups: &groups,
            stock: "s",
        }];
        let palette = Palette::of(ColorProfile::Classic);
        let pages = read::read_pages(&plan_pdf("t", &sheets, &palette).expect("writes")).expect("reads");
        let drawn = groups.iter().map(|g| g.drawn(&palette).count()).sum::<usize>();
        let grey = pages[0].paths.iter().filter(|p| p.color == rgb(CAPTION_COLOR)).count();
        assert_eq!(pages[0].paths.len(), drawn + grey);
    }

    #[test]
    fn no_caption_without_a_free_corner() {
        let full = [part(1.0, 1.0, 99.0, 99.0)];
        assert!(caption_strokes("s", 100.0, 100.0, &full).is_empty());
        assert!(caption_strokes("a long caption", 20.0, 20.0, []).is_empty());
    }
}
