//! The hinge test swatch (`platener hinge-test`): one bend at true size, to check that a hinge
//! bends as designed before cutting a whole part.
//!
//! A strip with two flat ends and the designed bend zone between them, the bend's marks
//! ([`crate::hinge::marks`]) across it and an engraved legend (style, angle, pattern, links, link
//! size, zone width, radius) on the left end; a living hinge in wood gets a strip per pattern
//! (the lattice and the straight flex), each at the radius it promises, so the maker sees
//! which one the stock takes. Sheet coordinates, mm, y down, as the kerf test strip.

use glam::DVec2;
use platener_geom::Polygon;
use platener_geom::polygon::rect;

use crate::draw::font::{place_text, text_width};
use crate::draw::svg::{Engraved, SvgGroup, SvgStyle, num, sheet_svg};
use crate::hinge::{BendDesign, HingeError, design, design_pattern, marks};
use crate::plan::{BendStyle, HingePattern, Mark, MarkKind, Material};

/// Border between the sheet edge and the strip, mm.
const MARGIN: f64 = 5.0;
/// Shortest flat end, mm: enough to hold and to see the bend's angle.
const MIN_END: f64 = 30.0;
/// Shortest strip across the bend line, mm.
const MIN_HEIGHT: f64 = 40.0;
/// Legend text size and line spacing, mm.
const TEXT: f64 = 2.5;
const LINE: f64 = 4.0;
/// Room around the legend, mm.
const PAD: f64 = 4.0;

/// The swatch sheet: one strip per pattern the bend can take (a living hinge in wood: the
/// lattice and the straight flex, each at the radius it promises), one above the other.
#[derive(Debug, Clone)]
pub struct Swatch {
    /// Sheet width, mm.
    pub width: f64,
    /// Sheet height, mm.
    pub height: f64,
    /// The strips, top first.
    pub strips: Vec<Strip>,
    /// The material, for the legend and the printout.
    pub material: Material,
}

/// One test strip: two flat ends and a bend zone between them.
#[derive(Debug, Clone)]
pub struct Strip {
    /// The strip's outline (cut).
    pub strip: Polygon,
    /// The bend line, the middle of the zone (vertical, across the strip).
    pub line: [DVec2; 2],
    /// The bend's marks: slits and dashes (cut), score and heat lines (engraved).
    pub marks: Vec<Mark>,
    /// The engraved legend's strokes.
    pub legend: Vec<Vec<DVec2>>,
    /// The bend it shows.
    pub design: BendDesign,
}

/// The legend's lines for `d` in `material`.
pub fn legend_lines(d: &BendDesign, material: Material) -> Vec<String> {
    let mut lines = vec![format!(
        "{} {}DEG {} {}MM",
        d.style.name(),
        num((d.turn.to_degrees() * 10.0).round() / 10.0),
        material.name(),
        num(d.thickness)
    )];
    match d.style {
        BendStyle::LivingHinge => lines.push(format!(
            "{} {} LINKS {}X{}MM",
            d.pattern.name(),
            d.links,
            fmt1(d.link_width),
            fmt1(d.link_length)
        )),
        BendStyle::Perforation => lines.push(format!("DASH {} TIE {}MM", fmt1(d.slit_length), fmt1(d.bridge))),
        BendStyle::Score | BendStyle::Heat => {}
    }
    lines.push(format!("ZONE {}MM R {}MM", fmt1(d.zone_width), fmt1(d.neutral_radius)));
    lines
}

/// `v` with at most one decimal.
fn fmt1(v: f64) -> String {
    num((v * 10.0).round() / 10.0)
}

/// Lays out the swatch of a bend turning `turn_deg` degrees in `thickness` mm of `material`,
/// in `style` (the material's own style when `None`): a strip for each pattern a living hinge
/// can take there, else the one strip of the style.
pub fn hinge_swatch(
    style: Option<BendStyle>,
    material: Material,
    thickness: f64,
    turn_deg: f64,
) -> Result<Swatch, HingeError> {
    let style = style.or_else(|| crate::settings::Bending::Auto.style(material));
    let style = style.unwrap_or(BendStyle::LivingHinge);
    let turn = turn_deg.to_radians();
    // The general design first: it says why a bend cannot be made at all.
    let first = design(style, material, thickness, turn, f64::INFINITY)?;
    let designs: Vec<BendDesign> = if style == BendStyle::LivingHinge {
        [HingePattern::Lattice, HingePattern::Straight]
            .into_iter()
            .filter_map(|p| design_pattern(p, material, thickness, turn))
            .collect()
    } else {
        vec![first]
    };
    let mut strips = Vec::new();
    let mut y0 = MARGIN;
    for d in designs {
        let strip = strip(d, material, y0)?;
        let (_, hi) = strip.strip.bounds();
        y0 = hi.y + MARGIN;
        strips.push(strip);
    }
    let width = strips.iter().map(|s| s.strip.bounds().1.x + MARGIN).fold(0.0, f64::max);
    Ok(Swatch {
        width,
        height: y0,
        strips,
        material,
    })
}

/// The strip of design `d`, its top at `y0`.
fn strip(d: BendDesign, material: Material, y0: f64) -> Result<Strip, HingeError> {
    let lines = legend_lines(&d, material);
    let legend_w = lines.iter().map(|l| text_width(l, TEXT)).fold(0.0, f64::max);
    let end = MIN_END.max(legend_w + 2.0 * PAD);
    let height = MIN_HEIGHT
        .max(2.0 * PAD + lines.len() as f64 * LINE)
        .max(2.0 * d.period() + 2.0 * d.link_width);
    let x0 = MARGIN;
    let strip = Polygon::new(rect(x0, y0, x0 + 2.0 * end + d.zone_width, y0 + height));
    let xc = x0 + end + d.zone_width / 2.0;
    let line = [DVec2::new(xc, y0), DVec2::new(xc, y0 + height)];
    let marks = marks(&d, line, &strip)?;
    let mut legend = Vec::new();
    for (i, text) in lines.iter().enumerate() {
        let origin = DVec2::new(x0 + PAD, y0 + PAD + TEXT + i as f64 * LINE);
        legend.extend(place_text(text, TEXT, origin, DVec2::X));
    }
    Ok(Strip {
        strip,
        line,
        marks,
        legend,
        design: d,
    })
}

impl Swatch {
    /// The sheet as SVG: strip k is `part-k`, its outline and slits red, legend and score lines
    /// blue.
    pub fn svg(&self) -> String {
        let groups: Vec<SvgGroup> = self
            .strips
            .iter()
            .enumerate()
            .map(|(k, s)| SvgGroup {
                id: format!("part-{}", k + 1),
                cut: vec![s.strip.outer.clone()],
                slits: s
                    .marks
                    .iter()
                    .filter(|m| m.kind == MarkKind::Cut)
                    .map(|m| m.path.clone())
                    .collect(),
                engrave: s
                    .legend
                    .iter()
                    .cloned()
                    .map(Engraved::text)
                    .chain(
                        s.marks
                            .iter()
                            .filter(|m| m.kind != MarkKind::Cut)
                            .map(|m| Engraved::score(m.path.clone())),
                    )
                    .collect(),
            })
            .collect();
        sheet_svg(self.width, self.height, &groups, &SvgStyle::CUT)
    }
}
