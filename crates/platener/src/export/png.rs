//! PNG previews of sheets, rendered with resvg from a preview SVG (white sheet, filled parts,
//! visible strokes), so the user sees the layout without laser software.

use resvg::tiny_skia::{Pixmap, Transform};
use resvg::usvg::{Options, Tree};

use crate::plan::PlanError;

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
