//! SVG sheets at true size: red hairline cut paths, blue engraving, one `<g id="part-N">` per
//! part (the spec's conventions; Inkscape and LightBurn import `mm` sizes at scale 1).
//!
//! Numbers are written with 4 decimals (0.1 µm, far below a laser's resolution), trailing zeros
//! trimmed and no `-0`, so the same geometry always gives the same bytes.

use std::fmt::Write as _;

use glam::DVec2;

/// Cut colour: laser software maps pure red to "cut".
pub const CUT_COLOR: &str = "#ff0000";
/// Engrave colour: pure blue, "score / engrave".
pub const ENGRAVE_COLOR: &str = "#0000ff";
/// Hairline width, mm (0.001 in, what Epilog, Trotec and LightBurn treat as a vector line).
pub const HAIRLINE: f64 = 0.0254;

/// What one group (one part) draws.
#[derive(Debug, Clone, Default)]
pub struct SvgGroup {
    /// The `id` attribute, e.g. `part-3`.
    pub id: String,
    /// Closed rings to cut, sheet coordinates.
    pub cut: Vec<Vec<DVec2>>,
    /// Open polylines to cut (the part's `cut` marks: hinge slits, perforation dashes), sheet
    /// coordinates; drawn like the rings, red hairlines, but not closed.
    pub slits: Vec<Vec<DVec2>>,
    /// Open polylines to engrave, sheet coordinates.
    pub engrave: Vec<Vec<DVec2>>,
}

/// How the sheet is drawn: the cut file, or a preview for the PNG.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SvgStyle {
    /// Cut stroke width, mm.
    pub cut_width: f64,
    /// Engrave stroke width, mm.
    pub engrave_width: f64,
    /// Draw a white sheet with a grey border and fill parts (previews only; a cut file has
    /// nothing but the parts' paths).
    pub preview: bool,
}

impl SvgStyle {
    /// The cut file: hairlines only.
    pub const CUT: SvgStyle = SvgStyle {
        cut_width: HAIRLINE,
        engrave_width: HAIRLINE,
        preview: false,
    };
}

/// A number as written in our SVG and JSON-free text: 4 decimals, trimmed, never `-0`.
pub fn num(v: f64) -> String {
    let mut s = format!("{v:.4}");
    if s.contains('.') {
        while s.ends_with('0') {
            s.pop();
        }
        if s.ends_with('.') {
            s.pop();
        }
    }
    if s == "-0" { "0".into() } else { s }
}

/// `text` with `& < > " '` escaped, for XML's attributes and text nodes and for HTML alike
/// (`'` as `&#39;`, which both read; the web page escapes with it too).
pub fn xml_escape(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for c in text.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&#39;"),
            _ => out.push(c),
        }
    }
    out
}

/// `svg` (a sheet from [`sheet_svg`]) with a `<title>` naming it, first inside the root: which
/// stock the sheet is, for the maker and any program that lists it (issue 34). Laser software
/// draws no title.
pub fn titled(svg: &str, title: &str) -> String {
    match svg
        .find("<svg ")
        .and_then(|at| svg[at..].find(">\n").map(|end| at + end + 2))
    {
        Some(cut) => format!("{}<title>{}</title>\n{}", &svg[..cut], xml_escape(title), &svg[cut..]),
        None => svg.to_string(),
    }
}

fn path_data(points: &[DVec2], closed: bool) -> String {
    let mut d = String::with_capacity(points.len() * 18);
    for (i, p) in points.iter().enumerate() {
        let _ = write!(d, "{}{} {}", if i == 0 { "M" } else { " L" }, num(p.x), num(p.y));
    }
    if closed {
        d.push_str(" Z");
    }
    d
}

/// The SVG document of one sheet of `width` × `height` mm holding `groups`.
pub fn sheet_svg(width: f64, height: f64, groups: &[SvgGroup], style: &SvgStyle) -> String {
    let (w, h) = (num(width), num(height));
    let mut s = String::new();
    s.push_str("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n");
    let _ = writeln!(
        s,
        "<svg xmlns=\"http://www.w3.org/2000/svg\" version=\"1.1\" width=\"{w}mm\" height=\"{h}mm\" viewBox=\"0 0 {w} {h}\">"
    );
    if style.preview {
        let _ = writeln!(
            s,
            "<rect x=\"0\" y=\"0\" width=\"{w}\" height=\"{h}\" fill=\"#ffffff\" stroke=\"#808080\" stroke-width=\"{}\"/>",
            num(style.cut_width)
        );
    }
    for g in groups {
        let _ = writeln!(s, "<g id=\"{}\">", g.id);
        if style.preview && !g.cut.is_empty() {
            let d: Vec<String> = g.cut.iter().map(|r| path_data(r, true)).collect();
            let _ = writeln!(
                s,
                "<path d=\"{}\" fill=\"#f2e2c4\" fill-rule=\"evenodd\" stroke=\"none\"/>",
                d.join(" ")
            );
        }
        // Cut order (`export::order`): engraving, then slits, then rings (holes before the
        // outline, as the rings are ordered).
        for line in &g.engrave {
            let _ = writeln!(
                s,
                "<path d=\"{}\" fill=\"none\" stroke=\"{ENGRAVE_COLOR}\" stroke-width=\"{}\" stroke-linecap=\"round\" stroke-linejoin=\"round\"/>",
                path_data(line, false),
                num(style.engrave_width)
            );
        }
        let slits = g.slits.iter().map(|l| (l, false));
        for (path, closed) in slits.chain(g.cut.iter().map(|r| (r, true))) {
            let _ = writeln!(
                s,
                "<path d=\"{}\" fill=\"none\" stroke=\"{CUT_COLOR}\" stroke-width=\"{}\"/>",
                path_data(path, closed),
                num(style.cut_width)
            );
        }
        s.push_str("</g>\n");
    }
    s.push_str("</svg>\n");
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_are_short_and_stable() {
        assert_eq!(num(600.0), "600");
        assert_eq!(num(0.12345), "0.1235");
        assert_eq!(num(-0.00001), "0");
        assert_eq!(num(-2.5), "-2.5");
    }

    #[test]
    fn a_sheet_has_true_size_and_only_part_paths_are_red() {
        let g = SvgGroup {
            id: "part-1".into(),
            cut: vec![vec![DVec2::ZERO, DVec2::X, DVec2::ONE]],
            slits: Vec::new(),
            engrave: vec![vec![DVec2::ZERO, DVec2::Y]],
        };
        let svg = sheet_svg(600.0, 400.0, &[g], &SvgStyle::CUT);
        assert!(svg.contains("width=\"600mm\" height=\"400mm\" viewBox=\"0 0 600 400\""));
        assert_eq!(svg.matches(CUT_COLOR).count(), 1);
        assert!(svg.contains("<path d=\"M0 0 L1 0 L1 1 Z\""));
    }

    #[test]
    fn slits_are_open_red_hairlines_inside_their_part() {
        let g = SvgGroup {
            id: "part-4".into(),
            cut: vec![vec![DVec2::ZERO, DVec2::new(10.0, 0.0), DVec2::splat(10.0)]],
            slits: vec![vec![DVec2::new(2.0, 1.0), DVec2::new(2.0, 5.5)]],
            engrave: Vec::new(),
        };
        let svg = sheet_svg(600.0, 400.0, &[g], &SvgStyle::CUT);
        let red = format!("<path d=\"M2 1 L2 5.5\" fill=\"none\" stroke=\"{CUT_COLOR}\" stroke-width=\"0.0254\"/>");
        let at = svg.find(&red).expect("the slit is a red open hairline");
        let group = svg.find("<g id=\"part-4\">").expect("group");
        assert!(group < at && at < svg.find("</g>").expect("end"), "inside its group");
        assert_eq!(svg.matches(CUT_COLOR).count(), 2);
    }
}
