//! The marks that make a designed bend bend, drawn in a part's flat frame.
//!
//! A living hinge is rows of staggered slits across its zone; a perforation is a dashed cut
//! along the line; score and heat bends are one engraved line. Slits and dashes stop inside
//! the part's outline eroded by the link width (or the perforation's tie), so they never open
//! to the outline: fingers and edges stay whole, and the part stays one piece.

use glam::DVec2;
use platener_geom::Polygon;
use platener_geom::offset::offset;

use super::{BendDesign, HingeError};
use crate::plan::{BendStyle, Mark, MarkKind};

/// Parameters closer than this along a clipped segment (as a fraction of it) are one.
const PARAM_EPS: f64 = 1e-9;

/// The marks of one bend along `line` (the middle of its zone, in the part's flat frame),
/// clipped to `clip` (the part's flat shape, or the region of it the bend crosses).
/// Deterministic: rows from one side of the zone to the other, slits along the line.
pub fn marks(design: &BendDesign, line: [DVec2; 2], clip: &Polygon) -> Result<Vec<Mark>, HingeError> {
    let along = line[1] - line[0];
    let len = along.length();
    if !(len.is_finite() && len > 0.0) {
        return Err(HingeError::Invalid {
            name: "bend line length",
            value: len,
        });
    }
    let axes = Axes {
        origin: line[0],
        u: along / len,
        v: (along / len).perp(),
    };
    match design.style {
        BendStyle::LivingHinge => {
            let inner = offset(std::slice::from_ref(clip), -design.link_width)?;
            let rows = (0..design.rows).map(|i| {
                let d = -design.zone_width / 2.0 + f64::from(i) * design.pitch;
                (d, if i % 2 == 1 { design.period() / 2.0 } else { 0.0 })
            });
            Ok(dashes(design, &axes, &inner, rows, design.link_width))
        }
        BendStyle::Perforation => {
            let inner = offset(std::slice::from_ref(clip), -design.bridge)?;
            Ok(dashes(design, &axes, &inner, creases(design).map(|d| (d, 0.0)), 0.0))
        }
        BendStyle::Score | BendStyle::Heat => {
            let clip = std::slice::from_ref(clip);
            let (lo, hi) = axes.extent(clip);
            Ok(creases(design)
                .flat_map(|d| clip_segment(axes.at(lo - 1.0, d), axes.at(hi + 1.0, d), clip))
                .map(|s| mark(MarkKind::Score, s))
                .collect())
        }
    }
}

/// Where a fold's creases lie across its zone: one on the line, or (a fold spread over a
/// fillet's arc) `rows` evenly spaced, each in the middle of its share of the zone.
fn creases(design: &BendDesign) -> impl Iterator<Item = f64> + '_ {
    (0..design.rows.max(1)).map(|i| {
        if design.rows <= 1 {
            0.0
        } else {
            -design.zone_width / 2.0 + (f64::from(i) + 0.5) * design.pitch
        }
    })
}

/// The bend's own axes: `u` along the line from its first point, `v` across it.
struct Axes {
    origin: DVec2,
    u: DVec2,
    v: DVec2,
}

impl Axes {
    /// The point `a` along the line and `d` across it.
    fn at(&self, a: f64, d: f64) -> DVec2 {
        self.origin + self.u * a + self.v * d
    }

    /// The range of `polygons` along the line.
    fn extent(&self, polygons: &[Polygon]) -> (f64, f64) {
        polygons
            .iter()
            .flat_map(|p| p.outer.iter())
            .map(|&q| (q - self.origin).dot(self.u))
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), a| (lo.min(a), hi.max(a)))
    }
}

/// Cut marks `design.slit_length` long repeating every period, one row at each `(offset
/// across, phase along)` of `rows`, clipped to `inner`; pieces shorter than `min_piece` free
/// nothing and are dropped.
fn dashes(
    design: &BendDesign,
    axes: &Axes,
    inner: &[Polygon],
    rows: impl Iterator<Item = (f64, f64)>,
    min_piece: f64,
) -> Vec<Mark> {
    let (lo, hi) = axes.extent(inner);
    let period = design.period();
    let mut out = Vec::new();
    if inner.is_empty() || period.is_nan() || period <= 0.0 {
        return out;
    }
    for (d, phase) in rows {
        let first = ((lo - phase) / period).floor() as i64 - 1;
        let last = ((hi - phase) / period).ceil() as i64;
        for k in first..=last {
            let a = phase + k as f64 * period;
            let (p, q) = (axes.at(a, d), axes.at(a + design.slit_length, d));
            out.extend(
                clip_segment(p, q, inner)
                    .into_iter()
                    .filter(|s| s[0].distance(s[1]) >= min_piece)
                    .map(|s| mark(MarkKind::Cut, s)),
            );
        }
    }
    out
}

/// An open two-point mark.
fn mark(kind: MarkKind, s: [DVec2; 2]) -> Mark {
    Mark {
        kind,
        path: s.to_vec(),
        side: None,
    }
}

/// The pieces of the segment `a`–`b` inside `polygons` (holes excluded), in order from `a`.
/// The segment is split where it crosses any ring edge (and at the ends of edges it runs
/// along), and each piece is kept when its middle is inside: robust to vertices on the
/// segment and to edges collinear with it.
pub(super) fn clip_segment(a: DVec2, b: DVec2, polygons: &[Polygon]) -> Vec<[DVec2; 2]> {
    let dir = b - a;
    let mut params = vec![0.0, 1.0];
    for ring in polygons.iter().flat_map(|p| std::iter::once(&p.outer).chain(&p.holes)) {
        for (i, &p) in ring.iter().enumerate() {
            let q = ring[(i + 1) % ring.len()];
            params.extend(crossing(a, dir, p, q));
        }
    }
    params.retain(|t| (0.0..=1.0).contains(t));
    params.sort_by(f64::total_cmp);
    params.dedup_by(|x, y| (*x - *y).abs() < PARAM_EPS);
    let mut pieces: Vec<[f64; 2]> = Vec::new();
    for w in params.windows(2) {
        let mid = a + dir * (0.5 * (w[0] + w[1]));
        if !polygons.iter().any(|p| p.contains(mid)) {
            continue;
        }
        match pieces.last_mut() {
            Some(last) if (last[1] - w[0]).abs() < PARAM_EPS => last[1] = w[1],
            _ => pieces.push([w[0], w[1]]),
        }
    }
    pieces.into_iter().map(|[s, t]| [a + dir * s, a + dir * t]).collect()
}

/// Where (as a parameter of `a + t·dir`) the line meets the edge `p`–`q`: its crossing, or
/// the edge's ends when it runs along the line.
fn crossing(a: DVec2, dir: DVec2, p: DVec2, q: DVec2) -> Vec<f64> {
    let e = q - p;
    let denom = dir.perp_dot(e);
    let scale = dir.length() * e.length();
    if denom.abs() <= 1e-12 * scale {
        // Parallel: only an edge on the line itself splits it.
        if (p - a).perp_dot(dir).abs() <= 1e-9 * dir.length() * (1.0 + (p - a).length()) {
            let dd = dir.length_squared();
            return vec![(p - a).dot(dir) / dd, (q - a).dot(dir) / dd];
        }
        return Vec::new();
    }
    let t = (p - a).perp_dot(e) / denom;
    let s = (p - a).perp_dot(dir) / denom;
    if (-PARAM_EPS..=1.0 + PARAM_EPS).contains(&s) {
        vec![t]
    } else {
        Vec::new()
    }
}
