//! The SVG sheets and swatches platener writes, read back with real parsers: roxmltree (the
//! XML reader usvg uses) for the elements and svgtypes (usvg's path parser) for `d`. Not usvg's
//! own tree: it regroups elements and converts the file's millimetres to pixels, while these
//! tests measure the numbers as written, group by group.

#![allow(dead_code, reason = "each test uses a part")]

use svgtypes::{SimplePathSegment, SimplifyingPathParser};

/// One `<path>`: its stroke colour, its points (absolute, in the file's units) and whether it
/// is closed.
#[derive(Debug, Clone, PartialEq)]
pub struct SvgPath {
    pub stroke: String,
    pub points: Vec<(f64, f64)>,
    pub closed: bool,
}

/// The `<path>` elements of `svg` in file order, within the element whose `id` is `group`
/// when given. Panics (a test failure) on a file that does not parse.
pub fn paths(svg: &str, group: Option<&str>) -> Vec<SvgPath> {
    let doc = roxmltree::Document::parse(svg).unwrap_or_else(|e| panic!("the SVG does not parse: {e}"));
    let root = match group {
        Some(id) => doc
            .descendants()
            .find(|n| n.attribute("id") == Some(id))
            .unwrap_or_else(|| panic!("no element with id {id}")),
        None => doc.root_element(),
    };
    root.descendants()
        .filter(|n| n.has_tag_name("path"))
        .map(|n| {
            let mut path = SvgPath {
                stroke: n.attribute("stroke").unwrap_or_default().to_string(),
                points: Vec::new(),
                closed: false,
            };
            for segment in SimplifyingPathParser::from(n.attribute("d").unwrap_or_default()) {
                match segment.unwrap_or_else(|e| panic!("a path's d does not parse: {e}")) {
                    SimplePathSegment::MoveTo { x, y } | SimplePathSegment::LineTo { x, y } => path.points.push((x, y)),
                    SimplePathSegment::ClosePath => path.closed = true,
                    other => panic!("platener writes straight segments only: {other:?}"),
                }
            }
            path
        })
        .collect()
}

/// The root's attribute `name` (`width`, `height`, `viewBox`).
pub fn root_attribute(svg: &str, name: &str) -> String {
    let doc = roxmltree::Document::parse(svg).unwrap_or_else(|e| panic!("the SVG does not parse: {e}"));
    doc.root_element()
        .attribute(name)
        .unwrap_or_else(|| panic!("no {name}"))
        .to_string()
}
