//! Assembly marks: every layer carries `L` and its number (bottom = 1) after an alignment
//! arrow, every shaft `S` and its number after an arrow pointing up the stack.
//!
//! The layers' arrows all point along the stack frame's x axis and have a single barb on one
//! side, so a layer put on turned round *or* upside down shows at once (a symmetric arrow would
//! not show the flip; the rectangular slots alone allow both). Each tag is placed as near the
//! point over the model's centre as fits (its box, grown by a clearance, checked inside the part
//! by a boolean), so the arrows of a stack line up. The `labels` step then engraves part numbers
//! clear of these marks.

use glam::DVec2;
use platener_geom::{GridError, Polygon, boolean, offset};

use crate::draw::font::{place_text, text_width};
use crate::plan::{Mark, MarkKind};

/// Text sizes tried, mm, largest first.
const SIZES: [f64; 4] = [4.0, 3.0, 2.0, 1.5];
/// Free room kept around a tag, mm (from the outline, slots and holes).
const CLEARANCE: f64 = 1.0;
/// Candidate centres tried per size and direction, nearest the reference first.
const CANDIDATES: usize = 64;
/// A tag box sticking out of the part by less than this (mm²) is inside (grid rounding).
const OUTSIDE: f64 = 1e-6;

/// A tag: an arrow along `arrow` in a square cell, then `text` reading along one of `alongs`
/// (tried in order), as large as fits inside `polygon` with a clearance and as near
/// `reference` as it can be. `None` if nothing fits.
pub(crate) fn tag(
    polygon: &Polygon,
    text: &str,
    alongs: &[DVec2],
    arrow: DVec2,
    reference: DVec2,
) -> Result<Option<Vec<Mark>>, GridError> {
    for size in SIZES {
        let cell = 1.5 * size;
        let gap = 0.5 * size;
        let width = cell + gap + text_width(text, size);
        // Centres at least half the box's height (plus clearance) inside the part.
        let room = offset::offset(std::slice::from_ref(polygon), -(cell / 2.0 + CLEARANCE))?;
        if room.is_empty() {
            continue;
        }
        for &along in alongs {
            let Some(center) = place(
                std::slice::from_ref(polygon),
                &room,
                reference,
                along,
                width + 2.0 * CLEARANCE,
                cell + 2.0 * CLEARANCE,
            )?
            else {
                continue;
            };
            return Ok(Some(draw(text, size, center, along, arrow)));
        }
    }
    Ok(None)
}

/// Text alone (no arrow), reading along x, as large as fits inside `inside` with a
/// clearance and as near `reference` as it can be: its marks and the box it takes (grown by
/// the clearance), so later text keeps off it. `None` if nothing fits.
pub(crate) fn text_near(
    inside: &[Polygon],
    text: &str,
    reference: DVec2,
) -> Result<Option<(Vec<Mark>, Polygon)>, GridError> {
    for size in &SIZES[1..] {
        let (w, h) = (text_width(text, *size) + 2.0 * CLEARANCE, size + 2.0 * CLEARANCE);
        let room = offset::offset(inside, -(h / 2.0))?;
        if room.is_empty() {
            continue;
        }
        let Some(c) = place(inside, &room, reference, DVec2::X, w, h)? else {
            continue;
        };
        let origin = c - DVec2::new(text_width(text, *size) / 2.0, -size / 2.0);
        let marks = place_text(text, *size, origin, DVec2::X)
            .into_iter()
            .map(|path| Mark {
                kind: MarkKind::Label,
                path,
                side: None,
            })
            .collect();
        let half = DVec2::new(w, h) / 2.0;
        let taken = Polygon::new(platener_geom::polygon::rect(
            c.x - half.x,
            c.y - half.y,
            c.x + half.x,
            c.y + half.y,
        ));
        return Ok(Some((marks, taken)));
    }
    Ok(None)
}

/// The centre nearest `reference` of a `w` × `h` box along `along` that lies inside
/// `inside`, among grid points of `room` (the centres where its height fits).
fn place(
    inside: &[Polygon],
    room: &[Polygon],
    reference: DVec2,
    along: DVec2,
    w: f64,
    h: f64,
) -> Result<Option<DVec2>, GridError> {
    let step = (h / 2.0).max(0.5);
    let (lo, hi) = room.iter().map(Polygon::bounds).fold(
        (DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY)),
        |(a, b), (c, d)| (a.min(c), b.max(d)),
    );
    let (nx, ny) = (((hi.x - lo.x) / step) as usize + 1, ((hi.y - lo.y) / step) as usize + 1);
    let mut candidates: Vec<DVec2> = (0..=nx)
        .flat_map(|i| (0..=ny).map(move |j| lo + DVec2::new(i as f64, j as f64) * step))
        .collect();
    // The reference itself first, then grid points by distance, ties by position; only those
    // in `room` are tried (tested lazily: the first few usually fit).
    candidates.push(reference);
    candidates.sort_by(|a, b| {
        a.distance_squared(reference)
            .total_cmp(&b.distance_squared(reference))
            .then(a.x.total_cmp(&b.x))
            .then(a.y.total_cmp(&b.y))
    });
    let candidates = candidates.into_iter().filter(|p| room.iter().any(|r| r.contains(*p)));
    let up = along.perp();
    for c in candidates.take(CANDIDATES) {
        let (dx, dy) = (along * (w / 2.0), up * (h / 2.0));
        let mut rect = Polygon::new(vec![c - dx - dy, c + dx - dy, c + dx + dy, c - dx + dy]);
        rect.normalize_orientation();
        let out = boolean::difference(&[rect], inside)?;
        if out.iter().map(Polygon::area).sum::<f64>() < OUTSIDE {
            return Ok(Some(c));
        }
    }
    Ok(None)
}

/// The arrow and the text of a tag centred on `center`.
fn draw(text: &str, size: f64, center: DVec2, along: DVec2, arrow: DVec2) -> Vec<Mark> {
    let cell = 1.5 * size;
    let gap = 0.5 * size;
    let width = cell + gap + text_width(text, size);
    // Text frames are y-down (as laid on the sheet): "up" of a text is `along` turned −90°.
    let up = DVec2::new(along.y, -along.x);
    let left = center - along * (width / 2.0);
    let q = left + along * (cell / 2.0);
    let (tail, tip) = (q - arrow * (cell / 2.0), q + arrow * (cell / 2.0));
    let barb = tip - arrow * (cell / 3.0) + arrow.perp() * (cell / 3.0);
    let mut marks = vec![Mark {
        kind: MarkKind::Score,
        path: vec![tail, tip, barb],
        side: None,
    }];
    let origin = left + along * (cell + gap) - up * (size / 2.0);
    marks.extend(place_text(text, size, origin, along).into_iter().map(|path| Mark {
        kind: MarkKind::Label,
        path,
        side: None,
    }));
    marks
}
