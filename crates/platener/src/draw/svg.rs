//! SVG sheets at true size: red hairline cut paths, blue engraving, one `<g id="part-N">` per
//! part (the spec's conventions; Inkscape and LightBurn import `mm` sizes at scale 1); or the
//! colours and widths of another laser program's convention ([`Palette`]).
//!
//! Numbers are written with 4 decimals (0.1 µm, far below a laser's resolution), trailing zeros
//! trimmed and no `-0`, so the same geometry always gives the same bytes.

use std::fmt::Write as _;

use glam::DVec2;

use crate::plan::ColorProfile;

/// Cut colour: laser software maps pure red to "cut".
pub const CUT_COLOR: &str = "#ff0000";
/// Engrave colour: pure blue, "score / engrave".
pub const ENGRAVE_COLOR: &str = "#0000ff";
/// The sheet outline's colour: grey, no operation's colour in any profile.
pub const SHEET_COLOR: &str = "#808080";
/// The `id` of the sheet outline's hidden layer in a cut file.
pub const SHEET_ID: &str = "sheet";
/// Inkscape's namespace, for the sheet outline's layer attributes.
const INKSCAPE_NS: &str = " xmlns:inkscape=\"http://www.inkscape.org/namespaces/inkscape\"";
/// Hairline width, mm (0.001 in, what Epilog, Trotec and LightBurn treat as a vector line).
pub const HAIRLINE: f64 = 0.0254;

/// `#rrggbb` as bytes; black for anything else (the PDF's stroke colours, read back in tests).
pub fn rgb(color: &str) -> [u8; 3] {
    let byte = |k: usize| {
        color
            .get(1 + 2 * k..3 + 2 * k)
            .and_then(|h| u8::from_str_radix(h, 16).ok())
            .unwrap_or(0)
    };
    [byte(0), byte(1), byte(2)]
}

/// One operation's stroke: colour (`#rrggbb`) and width, mm.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Stroke {
    /// The colour, `#rrggbb` in lower case.
    pub color: &'static str,
    /// The width, mm.
    pub width: f64,
}

/// The stroke of each operation on a sheet. Laser programs tell operations apart by colour;
/// holes and slits have a colour of their own where a program orders operations by colour,
/// so every inner cut runs before the outline that frees a part.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Palette {
    /// Numbers and text (the `labels` step, the sheet's legend).
    pub label: Stroke,
    /// Score lines: bend lines, features' outlines, a layer's outline on the one below.
    pub score: Stroke,
    /// Holes and slits.
    pub cut_inner: Stroke,
    /// A part's outline.
    pub cut_outer: Stroke,
}

impl Palette {
    /// The palette of `profile` (docs/cutting-plans.md, "Colour profiles", gives the sources).
    pub const fn of(profile: ColorProfile) -> Palette {
        const fn stroke(color: &'static str, width: f64) -> Stroke {
            Stroke { color, width }
        }
        const HAIR: f64 = HAIRLINE;
        match profile {
            ColorProfile::Classic => Palette {
                label: stroke(ENGRAVE_COLOR, HAIR),
                score: stroke(ENGRAVE_COLOR, HAIR),
                cut_inner: stroke(CUT_COLOR, HAIR),
                cut_outer: stroke(CUT_COLOR, HAIR),
            },
            // LightBurn's palette: C00 black, C01 blue, C03 green, C02 red.
            ColorProfile::LightBurn => Palette {
                label: stroke("#000000", HAIR),
                score: stroke("#0000ff", HAIR),
                cut_inner: stroke("#00e000", HAIR),
                cut_outer: stroke("#ff0000", HAIR),
            },
            // Ascending colour value in run order: black < blue < green < red.
            ColorProfile::Glowforge | ColorProfile::Xtool => Palette {
                label: stroke("#000000", 0.1),
                score: stroke("#0000ff", 0.1),
                cut_inner: stroke("#00ff00", 0.1),
                cut_outer: stroke("#ff0000", 0.1),
            },
            ColorProfile::Ponoko => Palette {
                label: stroke("#ff0000", 0.01),
                score: stroke("#ff0000", 0.01),
                cut_inner: stroke("#0000ff", 0.01),
                cut_outer: stroke("#0000ff", 0.01),
            },
        }
    }
}

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
    /// Open polylines to engrave, sheet coordinates: score lines and text, one sequence so
    /// the cut order can interleave them along the shortest path.
    pub engrave: Vec<Engraved>,
}

/// One path of a group as a file draws it: its points, whether it is closed, and the stroke
/// of its operation.
#[derive(Debug, Clone, Copy)]
pub struct Drawn<'a> {
    /// The points, sheet coordinates.
    pub points: &'a [DVec2],
    /// A closed ring rather than an open polyline.
    pub closed: bool,
    /// Engraved (text or score) rather than cut.
    pub engrave: bool,
    /// The operation's stroke in the palette.
    pub stroke: Stroke,
}

impl SvgGroup {
    /// Every path of the group in file order, which is cut order (`export::order`):
    /// engraving, then slits, then rings (holes before the outline, which comes last), each
    /// with its operation's stroke in `palette`. Every file that draws a sheet draws this.
    pub fn drawn<'a>(&'a self, palette: &'a Palette) -> impl Iterator<Item = Drawn<'a>> + 'a {
        let engraved = self.engrave.iter().map(|e| Drawn {
            points: &e.path,
            closed: false,
            engrave: true,
            stroke: if e.text { palette.label } else { palette.score },
        });
        let slits = self.slits.iter().map(|l| Drawn {
            points: l,
            closed: false,
            engrave: false,
            stroke: palette.cut_inner,
        });
        let outline = self.cut.len().checked_sub(1);
        let rings = self.cut.iter().enumerate().map(move |(k, r)| Drawn {
            points: r,
            closed: true,
            engrave: false,
            stroke: if Some(k) == outline {
                palette.cut_outer
            } else {
                palette.cut_inner
            },
        });
        engraved.chain(slits).chain(rings)
    }
}

/// One engraved polyline and whether it is text (labels, legends) or a score line (bend lines,
/// features' outlines, a layer's outline on the one below): colour profiles stroke them apart.
#[derive(Debug, Clone, PartialEq)]
pub struct Engraved {
    /// The polyline, sheet coordinates.
    pub path: Vec<DVec2>,
    /// Text rather than a score line.
    pub text: bool,
}

impl AsRef<Vec<DVec2>> for Engraved {
    fn as_ref(&self) -> &Vec<DVec2> {
        &self.path
    }
}

impl AsMut<Vec<DVec2>> for Engraved {
    fn as_mut(&mut self) -> &mut Vec<DVec2> {
        &mut self.path
    }
}

impl Engraved {
    /// A score line.
    pub fn score(path: Vec<DVec2>) -> Engraved {
        Engraved { path, text: false }
    }

    /// A stroke of text.
    pub fn text(path: Vec<DVec2>) -> Engraved {
        Engraved { path, text: true }
    }
}

/// How the sheet is drawn: the cut file, or a preview for the PNG.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SvgStyle {
    /// Each operation's stroke.
    pub palette: Palette,
    /// Draw a white sheet with a grey border and fill parts (previews only; a cut file has
    /// nothing but the parts' paths).
    pub preview: bool,
}

impl SvgStyle {
    /// The cut file, in the classic colours: hairlines only.
    pub const CUT: SvgStyle = SvgStyle::cut(ColorProfile::Classic);

    /// A preview in the classic colours, cut paths `cut_width` and engraving `engrave_width`
    /// mm wide (to be seen at a preview's size, not cut).
    pub const fn preview(cut_width: f64, engrave_width: f64) -> SvgStyle {
        let cut = Stroke {
            color: CUT_COLOR,
            width: cut_width,
        };
        let engrave = Stroke {
            color: ENGRAVE_COLOR,
            width: engrave_width,
        };
        SvgStyle {
            palette: Palette {
                label: engrave,
                score: engrave,
                cut_inner: cut,
                cut_outer: cut,
            },
            preview: true,
        }
    }

    /// The cut file in `profile`'s colours.
    pub const fn cut(profile: ColorProfile) -> SvgStyle {
        SvgStyle {
            palette: Palette::of(profile),
            preview: false,
        }
    }
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

/// SVG path data of `points`, closed with `Z` or not.
pub(crate) fn path_data(points: &[DVec2], closed: bool) -> String {
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
    let p = &style.palette;
    let mut s = String::new();
    s.push_str("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n");
    let _ = writeln!(
        s,
        "<svg xmlns=\"http://www.w3.org/2000/svg\"{} version=\"1.1\" width=\"{w}mm\" height=\"{h}mm\" viewBox=\"0 0 {w} {h}\">",
        if style.preview { "" } else { INKSCAPE_NS }
    );
    if !style.preview {
        // The sheet's outline on a hidden layer of its own: a frame to place the material by
        // in Inkscape, skipped by laser programs, which import no hidden element. Hidden by
        // the `display` attribute, not a `style`: a page whose policy forbids inline styles
        // (ours) shows the sheet without complaint.
        let _ = writeln!(
            s,
            "<g id=\"{SHEET_ID}\" inkscape:groupmode=\"layer\" inkscape:label=\"Sheet (not cut)\" display=\"none\">\n<rect x=\"0\" y=\"0\" width=\"{w}\" height=\"{h}\" fill=\"none\" stroke=\"{SHEET_COLOR}\" stroke-width=\"{}\"/>\n</g>",
            num(HAIRLINE)
        );
    }
    if style.preview {
        let _ = writeln!(
            s,
            "<rect x=\"0\" y=\"0\" width=\"{w}\" height=\"{h}\" fill=\"#ffffff\" stroke=\"#808080\" stroke-width=\"{}\"/>",
            num(p.cut_outer.width)
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
        for d in g.drawn(p) {
            // Engraving has round ends and joins: text and score lines end where drawn.
            let round = if d.engrave {
                " stroke-linecap=\"round\" stroke-linejoin=\"round\""
            } else {
                ""
            };
            let _ = writeln!(
                s,
                "<path d=\"{}\" fill=\"none\" stroke=\"{}\" stroke-width=\"{}\"{round}/>",
                path_data(d.points, d.closed),
                d.stroke.color,
                num(d.stroke.width)
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

    /// Every profile strokes each operation with its own palette entry: a part with a score
    /// line, a label, a slit, a hole and its outline, read back as XML.
    #[test]
    fn each_profile_strokes_each_operation_with_its_colour_and_width() {
        let square = |x: f64, s: f64| {
            vec![
                DVec2::splat(x),
                DVec2::new(x + s, x),
                DVec2::splat(x + s),
                DVec2::new(x, x + s),
            ]
        };
        let g = SvgGroup {
            id: "part-1".into(),
            cut: vec![square(4.0, 2.0), square(0.0, 20.0)],
            slits: vec![vec![DVec2::new(10.0, 2.0), DVec2::new(10.0, 8.0)]],
            engrave: vec![
                Engraved::score(vec![DVec2::new(2.0, 12.0), DVec2::new(18.0, 12.0)]),
                Engraved::text(vec![DVec2::new(2.0, 16.0), DVec2::new(3.0, 18.0)]),
            ],
        };
        for profile in ColorProfile::ALL {
            let p = Palette::of(profile);
            let svg = sheet_svg(30.0, 30.0, std::slice::from_ref(&g), &SvgStyle::cut(profile));
            let doc = roxmltree::Document::parse(&svg).expect("well-formed");
            let strokes: Vec<(&str, &str)> = doc
                .descendants()
                .filter(|n| n.has_tag_name("path"))
                .map(|n| {
                    (
                        n.attribute("stroke").unwrap_or(""),
                        n.attribute("stroke-width").unwrap_or(""),
                    )
                })
                .collect();
            // In file order: score, label, slit, hole, outline.
            let expected: Vec<(String, String)> = [p.score, p.label, p.cut_inner, p.cut_inner, p.cut_outer]
                .iter()
                .map(|s| (s.color.to_string(), num(s.width)))
                .collect();
            let got: Vec<(String, String)> = strokes.iter().map(|(c, w)| (c.to_string(), w.to_string())).collect();
            assert_eq!(got, expected, "{profile:?}");
        }
        // LightBurn's palette tells every operation apart; the Glowforge order is ascending
        // colour value from text to outlines; Ponoko cuts blue and engraves red.
        let lb = Palette::of(ColorProfile::LightBurn);
        let mut colors = vec![lb.label.color, lb.score.color, lb.cut_inner.color, lb.cut_outer.color];
        colors.dedup();
        assert_eq!(colors.len(), 4);
        let gf = Palette::of(ColorProfile::Glowforge);
        let value = |s: Stroke| u32::from_str_radix(&s.color[1..], 16).expect("hex");
        assert!(value(gf.label) < value(gf.score) && value(gf.score) < value(gf.cut_inner));
        assert!(value(gf.cut_inner) < value(gf.cut_outer));
        let ponoko = Palette::of(ColorProfile::Ponoko);
        assert_eq!(
            (ponoko.cut_outer.color, ponoko.score.color, ponoko.cut_outer.width),
            ("#0000ff", "#ff0000", 0.01)
        );
        // The default profile is the file format of before: red hairline cuts, blue engraving.
        let classic = Palette::of(ColorProfile::default());
        let (cut, engrave) = (
            Stroke {
                color: CUT_COLOR,
                width: HAIRLINE,
            },
            Stroke {
                color: ENGRAVE_COLOR,
                width: HAIRLINE,
            },
        );
        assert_eq!(
            classic,
            Palette {
                label: engrave,
                score: engrave,
                cut_inner: cut,
                cut_outer: cut
            }
        );
    }

    #[test]
    fn a_sheet_has_true_size_and_only_part_paths_are_red() {
        let g = SvgGroup {
            id: "part-1".into(),
            cut: vec![vec![DVec2::ZERO, DVec2::X, DVec2::ONE]],
            slits: Vec::new(),
            engrave: vec![Engraved::score(vec![DVec2::ZERO, DVec2::Y])],
        };
        let svg = sheet_svg(600.0, 400.0, &[g], &SvgStyle::CUT);
        assert!(svg.contains("width=\"600mm\" height=\"400mm\" viewBox=\"0 0 600 400\""));
        assert_eq!(svg.matches(CUT_COLOR).count(), 1);
        assert!(svg.contains("<path d=\"M0 0 L1 0 L1 1 Z\""));
    }

    /// The cut file holds the sheet's outline on a hidden layer of its own, which Inkscape
    /// lists and laser programs (like usvg) do not import.
    #[test]
    fn the_sheet_outline_is_a_hidden_layer_that_imports_as_nothing() {
        let g = SvgGroup {
            id: "part-1".into(),
            cut: vec![vec![DVec2::ZERO, DVec2::X * 10.0, DVec2::splat(10.0)]],
            ..SvgGroup::default()
        };
        let svg = sheet_svg(600.0, 400.0, std::slice::from_ref(&g), &SvgStyle::CUT);
        let doc = roxmltree::Document::parse(&svg).expect("well-formed");
        let layer = doc
            .descendants()
            .find(|n| n.attribute("id") == Some(SHEET_ID))
            .expect("the sheet's layer");
        let ns = "http://www.inkscape.org/namespaces/inkscape";
        assert_eq!(layer.attribute((ns, "groupmode")), Some("layer"));
        assert_eq!(layer.attribute("display"), Some("none"));
        let rect = layer.children().find(|n| n.has_tag_name("rect")).expect("its outline");
        let size: Vec<&str> = ["x", "y", "width", "height"]
            .iter()
            .map(|a| rect.attribute(*a).unwrap_or(""))
            .collect();
        assert_eq!(size, ["0", "0", "600", "400"]);
        assert_eq!(rect.attribute("stroke"), Some(SHEET_COLOR));
        // Imported as a laser program does, only the part's path is left.
        let tree = resvg::usvg::Tree::from_str(&svg, &resvg::usvg::Options::default()).expect("parses");
        let mut paths = 0;
        count_paths(tree.root(), &mut paths);
        assert_eq!(paths, 1);
        // Previews draw the sheet themselves and have no such layer.
        let preview = sheet_svg(600.0, 400.0, &[g], &SvgStyle::preview(0.8, 0.4));
        assert!(!preview.contains(SHEET_ID) && !preview.contains("inkscape"));
    }

    fn count_paths(group: &resvg::usvg::Group, n: &mut usize) {
        for node in group.children() {
            match node {
                resvg::usvg::Node::Path(_) => *n += 1,
                resvg::usvg::Node::Group(g) => count_paths(g, n),
                _ => {}
            }
        }
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
        let end = group + svg[group..].find("</g>").expect("end");
        assert!(group < at && at < end, "inside its group");
        assert_eq!(svg.matches(CUT_COLOR).count(), 2);
    }
}
