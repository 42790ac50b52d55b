//! PNG previews of sheets, rendered with resvg from a preview SVG (white sheet, filled parts,
//! visible strokes), so the user sees the layout without laser software.

use resvg::tiny_skia::{Pixmap, Transform};
use resvg::usvg::{Options, Tree};

use crate::draw::svg::{Engraved, num, path_data};
use crate::plan::PlanError;

/// The stock caption's stroke width in a preview, mm (as the preview's engraving).
const CAPTION_WIDTH: f64 = 0.4;

/// `svg` (a preview from `sheet_svg`) with `caption`'s strokes drawn in grey on top: the
/// sheet's stock, which a preview names as the SVG's title and the PDF's caption do, in a
/// colour no operation has, so it does not read as engraving.
pub fn captioned(svg: &str, caption: &[Engraved]) -> String {
    let Some(end) = svg.rfind("</svg>") else {
        return svg.to_string();
    };
    if caption.is_empty() {
        return svg.to_string();
    }
    let d: Vec<String> = caption.iter().map(|e| path_data(&e.path, false)).collect();
    format!(
        "{}<path id=\"caption\" d=\"{}\" fill=\"none\" stroke=\"{}\" stroke-width=\"{}\" stroke-linecap=\"round\" stroke-linejoin=\"round\"/>\n{}",
        &svg[..end],
        d.join(" "),
        super::pdf::CAPTION_COLOR,
        num(CAPTION_WIDTH),
        &svg[end..]
    )
}

/// Longest side of a preview, pixels.
pub const PREVIEW_PIXELS: f64 = 1200.0;

/// Renders `svg` so that its longest side is [`PREVIEW_PIXELS`] and encodes it as PNG.
pub fn render_png(svg: &str, file: &str) -> Result<Vec<u8>, PlanError> {
    let tree = Tree::from_str(svg, &Options::default()).map_err(|e| PlanError::write(file, e))?;
    let size = tree.size();
    let scale = PREVIEW_PIXELS / f64::from(size.width().max(size.height()));
    let w = (f64::from(size.width()) * scale).round().max(1.0) as u32;
    let h = (f64::from(size.height()) * scale).round().max(1.0) as u32;
    let mut pixmap = Pixmap::new(w, h).ok_or_else(|| PlanError::write(file, format!("no {w} × {h} pixmap")))?;
    resvg::render(
        &tree,
        Transform::from_scale(scale as f32, scale as f32),
        &mut pixmap.as_mut(),
    );
    pixmap.encode_png().map_err(|e| PlanError::write(file, e))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::draw::svg::{SvgGroup, SvgStyle, sheet_svg};
    use glam::DVec2;

    /// The caption is one grey path over the preview, drawn in the PNG: pixels there turn
    /// grey where the sheet was white.
    #[test]
    fn a_captioned_preview_draws_the_stock_in_grey() {
        let style = SvgStyle::preview(1.0, 0.5);
        let svg = sheet_svg(200.0, 100.0, &[], &style);
        let caption = crate::export::pdf::caption_strokes("box-3mm-1: 3 mm wood sheet", 200.0, 100.0, []);
        assert!(!caption.is_empty());
        let with = captioned(&svg, &caption);
        let doc = roxmltree::Document::parse(&with).expect("well-formed");
        let path = doc
            .descendants()
            .find(|n| n.attribute("id") == Some("caption"))
            .expect("the caption");
        assert_eq!(path.attribute("stroke"), Some(crate::export::pdf::CAPTION_COLOR));
        let grey = |png: &[u8]| {
            let pixmap = Pixmap::decode_png(png).expect("png");
            pixmap
                .pixels()
                .iter()
                .filter(|p| p.red() < 200 && p.red() == p.green() && p.green() == p.blue())
                .count()
        };
        let (plain, drawn) = (
            render_png(&svg, "a.png").expect("png"),
            render_png(&with, "b.png").expect("png"),
        );
        assert!(grey(&drawn) > grey(&plain) + 50, "{} vs {}", grey(&drawn), grey(&plain));
        assert_eq!(captioned(&svg, &[]), svg);
    }

    #[test]
    fn a_preview_is_a_png_of_the_right_shape() {
        let style = SvgStyle::preview(1.0, 0.5);
        let g = SvgGroup {
            id: "part-1".into(),
            cut: vec![vec![
                DVec2::new(10.0, 10.0),
                DVec2::new(100.0, 10.0),
                DVec2::new(100.0, 50.0),
            ]],
            slits: vec![],
            engrave: vec![],
        };
        let png = render_png(&sheet_svg(600.0, 400.0, &[g], &style), "p.png").expect("renders");
        assert_eq!(&png[1..4], b"PNG");
        // IHDR: width and height, big-endian, at bytes 16..24.
        let w = u32::from_be_bytes([png[16], png[17], png[18], png[19]]);
        let h = u32::from_be_bytes([png[20], png[21], png[22], png[23]]);
        assert_eq!((w, h), (1200, 800));
    }

    #[test]
    fn a_slit_is_drawn_red_in_the_preview() {
        let style = SvgStyle::preview(2.0, 0.5);
        // A vertical slit at x = 300 mm in a part spanning 100..500 mm: 2 pixels per mm.
        let g = SvgGroup {
            id: "part-1".into(),
            cut: vec![vec![
                DVec2::new(100.0, 100.0),
                DVec2::new(500.0, 100.0),
                DVec2::new(500.0, 300.0),
                DVec2::new(100.0, 300.0),
            ]],
            slits: vec![vec![DVec2::new(300.0, 150.0), DVec2::new(300.0, 250.0)]],
            engrave: vec![],
        };
        let png = render_png(&sheet_svg(600.0, 400.0, &[g], &style), "p.png").expect("renders");
        let pixmap = resvg::tiny_skia::Pixmap::decode_png(&png).expect("decodes");
        let red = |x: u32, y: u32| {
            let c = pixmap.pixel(x, y).expect("on the image");
            (c.red(), c.green(), c.blue()) == (255, 0, 0)
        };
        assert!(red(600, 400), "on the slit");
        assert!(!red(640, 400), "beside it, the part's fill");
    }
}
