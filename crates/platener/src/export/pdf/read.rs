//! Reading back the PDFs [`super::plan_pdf`] writes (tests and checks).

use std::collections::BTreeMap;
use std::io::Read;

use glam::{DAffine2, DVec2};

use super::PT_PER_MM;
use crate::plan::PlanError;

/// One page read back: its size and its stroked paths, in sheet mm with y down (as the SVG).
#[derive(Debug, Clone, PartialEq)]
pub struct PdfPage {
    /// Width and height, mm.
    pub size: DVec2,
    /// The stroked paths in drawing order.
    pub paths: Vec<PdfPath>,
    /// Images drawn (`Do`: the assembly instructions' step pictures).
    pub images: usize,
}

/// One stroked path read back.
#[derive(Debug, Clone, PartialEq)]
pub struct PdfPath {
    /// Stroke colour.
    pub color: [u8; 3],
    /// Stroke width, mm.
    pub width: f64,
    /// Closed (`h` before `S`).
    pub closed: bool,
    /// The points, sheet mm, y down.
    pub points: Vec<DVec2>,
}

fn bad(what: impl std::fmt::Display) -> PlanError {
    PlanError::write("pdf (reading)", what.to_string())
}

/// The pages of a PDF written by [`super::plan_pdf`] or the assembly instructions, in page
/// order. Reads only what those writers write: uncompressed objects, a flat page tree, one
/// Flate content stream per page, paths made of `m`, `l`, `h` and `S` under `q`/`cm`/`Q`,
/// coloured with `RG`, and images drawn with `Do` (counted).
pub fn read_pages(bytes: &[u8]) -> Result<Vec<PdfPage>, PlanError> {
    let objects = objects(bytes);
    let dict = |n: u32| {
        objects
            .get(&n)
            .map(|(d, _)| d.as_str())
            .ok_or_else(|| bad(format!("no object {n}")))
    };
    let (_, pages) = objects
        .iter()
        .find(|(_, (d, _))| d.contains("/Type/Pages"))
        .ok_or_else(|| bad("no page tree"))?;
    let kids = between(&pages.0, "/Kids[", "]").ok_or_else(|| bad("no /Kids"))?;
    refs(kids)
        .into_iter()
        .map(|page| {
            let page = dict(page)?;
            let media: Vec<f64> = numbers(between(page, "/MediaBox[", "]").ok_or_else(|| bad("no /MediaBox"))?);
            let [x0, y0, x1, y1] = media[..] else {
                return Err(bad("a /MediaBox of four numbers"));
            };
            let contents = between(page, "/Contents ", " R").ok_or_else(|| bad("no /Contents"))?;
            let n = refs(&format!("{contents} R"))
                .first()
                .copied()
                .ok_or_else(|| bad("no content ref"))?;
            let stream = objects
                .get(&n)
                .and_then(|(_, s)| s.as_ref())
                .ok_or_else(|| bad("no content stream"))?;
            let mut text = String::new();
            flate2::read::ZlibDecoder::new(&stream[..])
                .read_to_string(&mut text)
                .map_err(bad)?;
            let size = DVec2::new(x1 - x0, y1 - y0) / PT_PER_MM;
            let (paths, images) = content_paths(&text, size.y)?;
            Ok(PdfPage { size, paths, images })
        })
        .collect()
}

/// Every `N 0 obj … endobj` by number: its dictionary text and its stream's bytes.
fn objects(bytes: &[u8]) -> BTreeMap<u32, (String, Option<Vec<u8>>)> {
    let mut out = BTreeMap::new();
    let mut at = 0;
    while let Some(k) = find(&bytes[at..], b" 0 obj").map(|k| k + at) {
        let start = bytes[..k]
            .iter()
            .rposition(|b| !b.is_ascii_digit())
            .map_or(0, |p| p + 1);
        let number = std::str::from_utf8(&bytes[start..k]).ok().and_then(|s| s.parse().ok());
        let body = k + b" 0 obj".len();
        let end = find(&bytes[body..], b"endobj").map_or(bytes.len(), |e| e + body);
        let (dict, stream) = match find(&bytes[body..end], b"stream\n") {
            Some(s) => {
                let dict = String::from_utf8_lossy(&bytes[body..body + s]).into_owned();
                let length: usize = between(&dict, "/Length ", "/")
                    .or_else(|| between(&dict, "/Length ", ">"))
                    .and_then(|l| l.trim().parse().ok())
                    .unwrap_or(0);
                let data = body + s + b"stream\n".len();
                (dict, Some(bytes[data..(data + length).min(end)].to_vec()))
            }
            None => (String::from_utf8_lossy(&bytes[body..end]).into_owned(), None),
        };
        if let Some(n) = number {
            out.insert(n, (dict, stream));
        }
        at = end;
    }
    out
}

fn find(hay: &[u8], needle: &[u8]) -> Option<usize> {
    hay.windows(needle.len()).position(|w| w == needle)
}

fn between<'a>(text: &'a str, open: &str, close: &str) -> Option<&'a str> {
    let start = text.find(open)? + open.len();
    let end = text[start..].find(close)? + start;
    Some(&text[start..end])
}

fn numbers(text: &str) -> Vec<f64> {
    text.split_whitespace().filter_map(|t| t.parse().ok()).collect()
}

/// The object numbers of `N 0 R` references in `text`.
fn refs(text: &str) -> Vec<u32> {
    let tokens: Vec<&str> = text.split_whitespace().collect();
    tokens
        .windows(3)
        .filter(|w| w[1] == "0" && w[2].starts_with('R'))
        .filter_map(|w| w[0].trim_start_matches(|c: char| !c.is_ascii_digit()).parse().ok())
        .collect()
}

/// The stroked paths of one page's content, sheet mm with y down on a sheet `height` mm tall,
/// and the count of images it draws.
fn content_paths(content: &str, height: f64) -> Result<(Vec<PdfPath>, usize), PlanError> {
    let mut images = 0;
    let mut stack = vec![DAffine2::IDENTITY];
    let mut operands: Vec<f64> = Vec::new();
    let mut color = [0u8; 3];
    let mut width = 1.0;
    let mut current: Vec<DVec2> = Vec::new();
    let mut closed = false;
    let mut out = Vec::new();
    let to_mm = |p: DVec2| DVec2::new(p.x / PT_PER_MM, height - p.y / PT_PER_MM);
    // A name may follow an operator with no space between ("cm/x0 Do").
    let spaced = content.replace('/', " /");
    for token in spaced.split_whitespace() {
        if let Ok(v) = token.parse::<f64>() {
            operands.push(v);
            continue;
        }
        if token.starts_with('/') {
            // A resource's name (an image's, for `Do`).
            continue;
        }
        let ctm = *stack.last().ok_or_else(|| bad("Q without q"))?;
        match (token, &operands[..]) {
            ("q", _) => stack.push(ctm),
            ("Q", _) => {
                stack.pop();
            }
            ("cm", &[a, b, c, d, e, f]) => {
                let m = DAffine2::from_cols_array(&[a, b, c, d, e, f]);
                *stack.last_mut().ok_or_else(|| bad("cm outside q"))? = ctm * m;
            }
            ("RG", &[r, g, b]) => color = [r, g, b].map(|v| (v * 255.0).round() as u8),
            ("w", &[w]) => width = w * ctm.matrix2.determinant().abs().sqrt() / PT_PER_MM,
            ("J" | "j", _) => {}
            ("Do", _) => images += 1,
            ("m" | "l", &[x, y]) => current.push(to_mm(ctm.transform_point2(DVec2::new(x, y)))),
            ("h", _) => closed = true,
            ("S", _) => out.push(PdfPath {
                color,
                width,
                closed: std::mem::take(&mut closed),
                points: std::mem::take(&mut current),
            }),
            (op, args) => return Err(bad(format!("operator {op} with {} operands", args.len()))),
        }
        operands.clear();
    }
    Ok((out, images))
}
