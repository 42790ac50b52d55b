//! A small reader for the SVG sheets we write: size, and per `<g id>` the red and blue paths.
//! Deliberately independent of the writer: it parses the text.

use std::collections::BTreeMap;

use platener::glam::DVec2;

/// One `<g>`: closed red rings and open blue polylines.
#[derive(Debug, Default)]
pub struct Group {
    pub cut: Vec<Vec<DVec2>>,
    pub engrave: Vec<Vec<DVec2>>,
}

/// One sheet.
#[derive(Debug)]
pub struct Sheet {
    pub width: f64,
    pub height: f64,
    pub view_box: [f64; 4],
    pub groups: BTreeMap<String, Group>,
    /// Every `#ff0000` in the file (each must belong to a cut path of a part).
    pub red: usize,
}

fn attr<'a>(tag: &'a str, name: &str) -> Option<&'a str> {
    let key = format!(" {name}=\"");
    let start = tag.find(&key)? + key.len();
    let end = tag[start..].find('"')? + start;
    Some(&tag[start..end])
}

pub fn path_points(d: &str) -> (Vec<DVec2>, bool) {
    let mut pts = Vec::new();
    let mut nums = Vec::new();
    let mut closed = false;
    for tok in d.split_whitespace() {
        let tok = tok.trim_start_matches(['M', 'L']);
        if tok == "Z" {
            closed = true;
            continue;
        }
        if tok.is_empty() {
            continue;
        }
        nums.push(tok.parse::<f64>().expect("number in path data"));
        if nums.len() == 2 {
            pts.push(DVec2::new(nums[0], nums[1]));
            nums.clear();
        }
    }
    assert!(nums.is_empty(), "odd number count in {d}");
    (pts, closed)
}

/// Parses one sheet.
pub fn parse(svg: &str) -> Sheet {
    let root_start = svg.find("<svg").expect("svg element");
    let root = &svg[root_start..root_start + svg[root_start..].find('>').expect("end of svg tag")];
    let mm = |name| {
        attr(root, name)
            .and_then(|v| v.strip_suffix("mm"))
            .map(|v| v.parse::<f64>().expect("number"))
    };
    let vb: Vec<f64> = attr(root, "viewBox")
        .expect("viewBox")
        .split_whitespace()
        .map(|v| v.parse().expect("number"))
        .collect();
    let mut groups = BTreeMap::new();
    let mut current: Option<String> = None;
    for tag in svg.split('<').skip(1) {
        if let Some(rest) = tag.strip_prefix("g ") {
            let tag = format!(" {rest}");
            // A hidden layer (the sheet's outline) is what a laser program does not import.
            if attr(&tag, "display") == Some("none") {
                current = None;
                continue;
            }
            current = attr(&tag, "id").map(str::to_string);
            groups
                .entry(current.clone().expect("group id"))
                .or_insert_with(Group::default);
        } else if tag.starts_with("/g") {
            current = None;
        } else if tag.starts_with("path ") {
            let d = attr(tag, "d").expect("path data");
            let stroke = attr(tag, "stroke").expect("stroke");
            let id = current.clone().expect("paths live in part groups");
            let g = groups.get_mut(&id).expect("group");
            let (pts, closed) = path_points(d);
            match stroke {
                "#ff0000" => {
                    assert!(closed, "cut paths are closed");
                    assert_eq!(attr(tag, "fill"), Some("none"));
                    g.cut.push(pts);
                }
                "#0000ff" => g.engrave.push(pts),
                other => panic!("unexpected stroke {other}"),
            }
        }
    }
    Sheet {
        width: mm("width").expect("width in mm"),
        height: mm("height").expect("height in mm"),
        view_box: [vb[0], vb[1], vb[2], vb[3]],
        groups,
        red: svg.matches("#ff0000").count(),
    }
}

/// One path of a sheet in document order: its group, whether it is red (cut), whether it is
/// closed, and its points.
#[derive(Debug)]
pub struct OrderedPath {
    pub group: String,
    pub red: bool,
    pub closed: bool,
    pub points: Vec<DVec2>,
}

/// Every `<path>` of the sheet in the order the file lists them (previews' fills left out).
pub fn paths_in_order(svg: &str) -> Vec<OrderedPath> {
    let mut out = Vec::new();
    let mut group = String::new();
    let mut rest = svg;
    while let Some(start) = rest.find('<') {
        let end = rest[start..].find('>').expect("end of tag") + start;
        let tag = &rest[start..=end];
        if tag.starts_with("<g ") {
            group = attr(tag, "id").unwrap_or_default().to_string();
        } else if tag.starts_with("<path ") && attr(tag, "fill") == Some("none") {
            let (points, closed) = path_points(attr(tag, "d").expect("path data"));
            let red = attr(tag, "stroke") == Some("#ff0000");
            out.push(OrderedPath {
                group: group.clone(),
                red,
                closed,
                points,
            });
        }
        rest = &rest[end + 1..];
    }
    out
}
