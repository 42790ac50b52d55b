//! The longest slot that fits a region: where a shaft can pass.
//!
//! A slot is a rectangle `width × thickness` around a straight centre line. It lies inside a
//! region exactly when its centre line lies inside the region shrunk by half the thickness, so
//! the search is for the longest segment inside the shrunk region. Directions tried: each
//! piece's principal axis (long thin overlaps get a slot along their length, unless a slanted
//! one is over 10 % longer) and every 15°; for each
//! direction, [`LINES`] parallel lines across the piece, each cut exactly against the piece's
//! edges. It is a placement heuristic (the best segment may lie between two lines), but what it
//! returns is exact: the centre line lies inside the shrunk region.

use glam::DVec2;
use platener_geom::{GridError, Polygon, offset};

/// Directions tried (every 180° / `DIRECTIONS`).
pub(super) const DIRECTIONS: usize = 12;
/// Parallel lines tried per direction.
const LINES: usize = 48;
/// Slots whose lengths differ by less than this (mm) are equally long.
const TIE: f64 = 1e-6;
/// A slot along the region's principal axis counts as this much longer than it is.
const PRINCIPAL_BONUS: f64 = 1.1;

/// A straight slot's centre line: from `start` along the unit `dir` for `width` mm.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct SlotLine {
    /// Start of the centre line.
    pub start: DVec2,
    /// Unit direction.
    pub dir: DVec2,
    /// Length, mm.
    pub width: f64,
}

impl SlotLine {
    /// The unit normal of the slot, the direction the shaft's thickness runs in: `dir` turned
    /// clockwise, which is where the shaft frame's `n = dir × up` points.
    pub fn normal(&self) -> DVec2 {
        DVec2::new(self.dir.y, -self.dir.x)
    }

    /// The rectangle over `from..to` along the centre line, `2·half` thick, counter-clockwise.
    pub fn rect(&self, from: f64, to: f64, half: f64) -> Polygon {
        let (d, n) = (self.dir, self.normal());
        let (a, b) = (self.start + d * from, self.start + d * to);
        let mut p = Polygon::new(vec![a - n * half, b - n * half, b + n * half, a + n * half]);
        p.normalize_orientation();
        p
    }
}

/// The longest slot `2·half` thick, between `min_width` and `max_width` long, inside `region`;
/// `None` if none is `min_width` long. A longer chord is trimmed to `max_width` about its middle.
pub(crate) fn fit_slot(
    region: &[Polygon],
    half: f64,
    min_width: f64,
    max_width: f64,
) -> Result<Option<SlotLine>, GridError> {
    best_slot(region, half, max_width, |slot| {
        Ok((slot.width >= min_width).then_some(slot))
    })
}

/// The best of the candidate slots (one per piece and direction, `max_width` at most) that
/// `accept` keeps, as it returns them (a peg lengthens its slot): longer first, then the most
/// central.
pub(crate) fn best_slot(
    region: &[Polygon],
    half: f64,
    max_width: f64,
    accept: impl Fn(SlotLine) -> Result<Option<SlotLine>, GridError>,
) -> Result<Option<SlotLine>, GridError> {
    if region.is_empty() {
        return Ok(None);
    }
    let eroded = offset::offset(region, -half)?;
    // (score, distance of the slot's middle from the piece's centre, slot)
    let mut best: Option<(f64, f64, SlotLine)> = None;
    for piece in &eroded {
        let centre = centroid(&piece.outer);
        // The principal axis first, with a head start: a slot along a long region's length
        // is kept unless a slanted one is clearly longer.
        let principal = principal_axis(&piece.outer).map(|d| (d, PRINCIPAL_BONUS));
        let around = (0..DIRECTIONS).map(|i| {
            (
                DVec2::from_angle(std::f64::consts::PI * i as f64 / DIRECTIONS as f64),
                1.0,
            )
        });
        for (d, weight) in principal.into_iter().chain(around) {
            let Some((len, start)) = longest_chord(piece, d, centre) else {
                continue;
            };
            let width = len.min(max_width);
            let chord = SlotLine {
                start: start + d * ((len - width) / 2.0),
                dir: d,
                width,
            };
            let Some(slot) = accept(chord)? else {
                continue;
            };
            let score = slot.width * weight;
            let off = (slot.start + d * (slot.width / 2.0)).distance(centre);
            // Longer wins; among equally long slots (a disc, a rectangle) the most central.
            let better = best
                .as_ref()
                .is_none_or(|(s, o, _)| score > *s + TIE || (score >= *s - TIE && off < *o));
            if better {
                best = Some((score, off, slot));
            }
        }
    }
    Ok(best.map(|(_, _, slot)| slot))
}

/// The longest segment along `d` inside `piece` on one of [`LINES`] parallel lines (of equally
/// long ones, the one whose middle is nearest `centre`): its length and start.
fn longest_chord(piece: &Polygon, d: DVec2, centre: DVec2) -> Option<(f64, DVec2)> {
    let m = d.perp();
    let rings: Vec<&[DVec2]> = std::iter::once(piece.outer.as_slice())
        .chain(piece.holes.iter().map(Vec::as_slice))
        .collect();
    let (lo, hi) = piece
        .outer
        .iter()
        .map(|p| m.dot(*p))
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| (a.min(v), b.max(v)));
    // Also refuses NaN (an empty or broken ring).
    if hi.is_nan() || lo.is_nan() || hi <= lo {
        return None;
    }
    // (length, distance of the middle from the centre, start)
    let mut best: Option<(f64, f64, DVec2)> = None;
    let mut cuts: Vec<f64> = Vec::new();
    for i in 0..LINES {
        let c = lo + (hi - lo) * (i as f64 + 0.5) / LINES as f64;
        cuts.clear();
        for ring in &rings {
            for k in 0..ring.len() {
                let (p, q) = (ring[k], ring[(k + 1) % ring.len()]);
                let (dp, dq) = (m.dot(p) - c, m.dot(q) - c);
                if (dp >= 0.0) != (dq >= 0.0) {
                    cuts.push(d.dot(p + (q - p) * (dp / (dp - dq))));
                }
            }
        }
        if !cuts.len().is_multiple_of(2) {
            continue;
        }
        cuts.sort_by(f64::total_cmp);
        for pair in cuts.chunks_exact(2) {
            let len = pair[1] - pair[0];
            let start = d * pair[0] + m * c;
            let off = (start + d * (len / 2.0)).distance(centre);
            if best.is_none_or(|(l, o, _)| len > l + TIE || (len >= l - TIE && off < o)) {
                best = Some((len, off, start));
            }
        }
    }
    best.map(|(len, _, start)| (len, start))
}

/// The mean of a ring's vertices.
fn centroid(ring: &[DVec2]) -> DVec2 {
    ring.iter().copied().sum::<DVec2>() / ring.len().max(1) as f64
}

/// The direction of a ring's largest spread (principal axis of its vertices), if it has one.
fn principal_axis(ring: &[DVec2]) -> Option<DVec2> {
    if ring.len() < 3 {
        return None;
    }
    let mean = centroid(ring);
    let (mut xx, mut yy, mut xy) = (0.0, 0.0, 0.0);
    for p in ring {
        let q = *p - mean;
        xx += q.x * q.x;
        yy += q.y * q.y;
        xy += q.x * q.y;
    }
    let angle = 0.5 * (2.0 * xy).atan2(xx - yy);
    let d = DVec2::from_angle(angle);
    d.is_finite().then_some(d)
}
