//! `assembly.html`: the instructions for a screen, one page with no script, style in its own
//! `<style>`, the pictures beside it in the ZIP (`assembly/step-NN.png`).

use std::fmt::Write as _;

use glam::DVec2;

use super::{Instruction, PICTURE};
use crate::draw::svg::{num, xml_escape};
use crate::plan::{Plan, PlanPart};

/// A part's drawing in the parts list: its longer side, CSS pixels.
const PART_PX: f64 = 96.0;

/// The whole page.
pub fn page(plan: &Plan, steps: &[Instruction], title: &str) -> String {
    let mut s = String::new();
    let title = xml_escape(title);
    let _ = write!(
        s,
        "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n\
         <meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n\
         <title>{title}: assembly</title>\n<style>{STYLE}</style>\n</head>\n<body>\n\
         <h1>{title}: assembly</h1>\n<p>{} parts in {} steps. Every joint's two edges carry the same \
         engraved number; each part carries its own.</p>\n",
        plan.parts.len(),
        steps.len()
    );
    parts_list(&mut s, plan);
    for step in steps {
        let _ = write!(
            s,
            "<section class=\"step\" id=\"step-{n}\">\n<h2>Step {n} of {total}</h2>\n\
             <img src=\"{file}\" width=\"{w}\" height=\"{h}\" alt=\"Step {n}: parts {parts} added\">\n<ul>\n",
            n = step.number,
            total = steps.len(),
            file = step.file(),
            w = PICTURE.0,
            h = PICTURE.1,
            parts = step.parts.iter().map(u32::to_string).collect::<Vec<_>>().join(", "),
        );
        for line in &step.lines {
            let _ = writeln!(s, "<li>{}</li>", xml_escape(line));
        }
        s.push_str("</ul>\n</section>\n");
    }
    s.push_str("</body>\n</html>\n");
    s
}

const STYLE: &str = "body{font-family:system-ui,sans-serif;max-width:60rem;margin:1rem auto;padding:0 1rem;color:#222}\
.parts{display:flex;flex-wrap:wrap;gap:.75rem}.parts figure{margin:0;text-align:center}\
.parts svg{display:block;margin:auto}.step{border-top:1px solid #ccc;padding:.5rem 0}\
.step img{max-width:100%;height:auto;border:1px solid #eee}";

/// Per sheet, every part on it drawn small with its number and size.
fn parts_list(s: &mut String, plan: &Plan) {
    s.push_str("<h2>Parts</h2>\n");
    for sheet in &plan.sheets {
        let _ = writeln!(
            s,
            "<h3>Sheet {}: {} ({} mm)</h3>\n<div class=\"parts\">",
            sheet.index + 1,
            xml_escape(&sheet.file),
            num(sheet.thickness)
        );
        for part in plan.parts.iter().filter(|p| p.sheet.index == sheet.index) {
            part_figure(s, part);
        }
        s.push_str("</div>\n");
    }
}

/// One part: its outline and holes as an inline SVG (y up, as cut), its number and size.
fn part_figure(s: &mut String, part: &PlanPart) {
    let (lo, hi) = part.outline.iter().fold(
        (DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY)),
        |(lo, hi), p| (lo.min(*p), hi.max(*p)),
    );
    let size = (hi - lo).max(DVec2::splat(1e-6));
    let scale = PART_PX / size.x.max(size.y);
    let ring = |r: &[DVec2]| {
        let mut d = String::new();
        for (i, p) in r.iter().enumerate() {
            let q = DVec2::new(p.x - lo.x, hi.y - p.y) * scale;
            let _ = write!(d, "{}{} {} ", if i == 0 { "M" } else { "L" }, num(q.x), num(q.y));
        }
        d.push('Z');
        d
    };
    let mut d = ring(&part.outline);
    for h in &part.holes {
        d.push(' ');
        d.push_str(&ring(h));
    }
    let _ = writeln!(
        s,
        "<figure><svg width=\"{w}\" height=\"{h}\" viewBox=\"0 0 {w} {h}\" role=\"img\" aria-label=\"part {id}\">\
         <path d=\"{d}\" fill=\"#e8d5b0\" fill-rule=\"evenodd\" stroke=\"#555\" stroke-width=\"1\"/></svg>\
         <figcaption>{id}: {x} × {y} mm</figcaption></figure>",
        w = num((size.x * scale).ceil()),
        h = num((size.y * scale).ceil()),
        id = part.id,
        x = num(size.x.round()),
        y = num(size.y.round()),
    );
}
