//! Where two plates could be one bent sheet: they have the same thickness, both end at the
//! line where their mid-planes meet, and reach it along a common stretch.
//!
//! The line is taken on the mid-planes (the neutral surface), not on a face: developing the
//! neutral surface keeps its lengths, whichever face the model's facets describe.

use glam::{DVec2, DVec3};
use platener_geom::{Frame, Polygon};

use crate::plates::Plate;

/// Two plates that meet along a line at which both end.
#[derive(Debug, Clone, serde::Serialize)]
pub struct Candidate {
    /// The plates (indices into the plates snapshot), `a < b`.
    pub plates: [usize; 2],
    /// A point of the line where the mid-planes meet.
    pub point: DVec3,
    /// Its unit direction.
    pub axis: DVec3,
    /// Where both plates reach the line, as parameters along `axis` from `point`.
    pub span: (f64, f64),
    /// Where either plate reaches the line (the bend zone's extent along it).
    pub reach: (f64, f64),
    /// Per plate: the unit direction in its mid-plane, perpendicular to the line, into it.
    pub into: [DVec3; 2],
    /// Per plate: how far it reaches from the line (its depth across it), mm.
    pub depth: [f64; 2],
    /// The angle the plates enclose, radians (π when they continue flat).
    pub enclosed: f64,
    /// How far short of the line the plates stop, mm, when the model rounds the corner
    /// between them with narrow facets no plate covers (a tessellated fillet): the bend zone
    /// must span that run of facets, an arc zone. 0 for plates that reach the line.
    pub gap: f64,
    /// Across a fillet: the plates its facets were found as (in walls thin enough for a
    /// facet to be a plate), which the arc zone replaces.
    pub facets: Vec<usize>,
}

impl Candidate {
    /// How far the sheet turns at the line, radians: π minus the enclosed angle.
    pub fn turn(&self) -> f64 {
        std::f64::consts::PI - self.enclosed
    }

    /// The length of the common stretch, mm.
    pub fn length(&self) -> f64 {
        self.span.1 - self.span.0
    }

    /// The index (0 or 1) of `plate` in this pair.
    pub fn side_of(&self, plate: usize) -> usize {
        usize::from(self.plates[1] == plate)
    }
}

/// A plate's mid-plane frame: developing the neutral surface keeps lengths.
pub(crate) fn mid_frame(plate: &Plate) -> Frame {
    plate.frame.shifted(plate.thickness / 2.0)
}

/// The widest gap an arc zone spans, in thicknesses on each side of the corner: a fillet of
/// up to 15 t neutral radius at 90° (45 mm in 3 mm sheet). Wider roundings are drawn with
/// facets wide enough to be plates of their own, which bend one by one.
const ARC_MAX_GAP: f64 = 15.0;

/// Every pair of plates that could bend into each other, in a stable order: corners turning
/// at most `max_turn`, and with `fillets` (the model's inside test) rounded corners of narrow
/// facets turning at most `max_arc` (a run of facets is a curve, not a drawn corner).
pub(crate) fn candidates(
    plates: &[Plate],
    (max_turn, max_arc): (f64, f64),
    mesh: Option<&crate::mesh::Mesh>,
) -> Vec<Candidate> {
    let boxes: Vec<_> = plates.iter().map(Plate::bounds).collect();
    let t_max = plates.iter().map(|p| p.thickness).fold(0.0, f64::max);
    let reach = t_max * if mesh.is_some() { ARC_MAX_GAP + 2.0 } else { 2.0 };
    // The inside test is built only once a pair stops short of its corner.
    let inside = std::cell::OnceCell::new();
    let fillets = mesh.map(|m| Fillets {
        inside: &inside,
        mesh: m,
    });
    platener_geom::boxes::near_pairs(&boxes, reach)
        .into_iter()
        .map(|(i, j)| (i.min(j), i.max(j)))
        .filter_map(|(a, b)| candidate(plates, a, b, fillets.as_ref(), max_arc))
        .filter(|(_, c)| c.turn() <= if c.gap > 0.0 { max_arc } else { max_turn })
        .collect::<std::collections::BTreeMap<_, _>>()
        .into_values()
        .collect()
}

/// The model's inside test for probing fillets, made on first use.
struct Fillets<'a> {
    inside: &'a std::cell::OnceCell<crate::assembly::Inside<'a>>,
    mesh: &'a crate::mesh::Mesh,
}

impl Fillets<'_> {
    fn inside(&self) -> &crate::assembly::Inside<'_> {
        self.inside
            .get_or_init(|| crate::assembly::Inside::new(&self.mesh.vertices, &self.mesh.triangles))
    }
}

/// The candidate for plates `a` and `b`, keyed by the pair, if they meet as one sheet would:
/// both reach the line where their mid-planes meet, or (`fillets`) both stop short of it by
/// a run of the model's material that curves from one to the other, turning at most
/// `max_arc`, which no plate but the run's own facets covers.
fn candidate(
    plates: &[Plate],
    a: usize,
    b: usize,
    fillets: Option<&Fillets<'_>>,
    max_arc: f64,
) -> Option<((usize, usize), Candidate)> {
    let (pa, pb) = (&plates[a], &plates[b]);
    if (pa.thickness - pb.thickness).abs() > 1e-6 {
        return None;
    }
    let (fa, fb) = (mid_frame(pa), mid_frame(pb));
    let cross = fa.n.cross(fb.n);
    if cross.length() < (0.5f64).to_radians().sin() {
        return None;
    }
    let axis = cross.normalize();
    let point = planes_meet(&fa, &fb, cross);
    let t = pa.thickness;
    let ends = |band: f64| {
        let ea = end_at(&fa, &pa.polygon, point, axis, t, band)?;
        let eb = end_at(&fb, &pb.polygon, point, axis, t, band)?;
        Some((ea, eb))
    };
    let (ea, eb) = ends(2.0 * t).or_else(|| fillets.and_then(|_| ends(ARC_MAX_GAP * t)))?;
    let span = (ea.span.0.max(eb.span.0), ea.span.1.min(eb.span.1));
    if span.1 - span.0 < 3.0 * t {
        return None;
    }
    let enclosed = ea.into.dot(eb.into).clamp(-1.0, 1.0).acos();
    let gap = ea.near.max(eb.near);
    let gap = if gap > 2.0 * t { gap } else { 0.0 };
    let c = Candidate {
        plates: [a, b],
        point,
        axis,
        span,
        reach: (ea.span.0.min(eb.span.0), ea.span.1.max(eb.span.1)),
        into: [ea.into, eb.into],
        depth: [ea.depth, eb.depth],
        enclosed,
        gap,
        facets: Vec::new(),
    };
    if c.gap > 0.0 {
        if c.turn() > max_arc {
            return None;
        }
        let facets = super::fillet::facets_of(&c, t, fillets?.inside(), plates)?;
        return Some(((a, b), Candidate { facets, ..c }));
    }
    Some(((a, b), c))
}

/// A point on both mid-planes (`cross` = na × nb, not zero).
fn planes_meet(fa: &Frame, fb: &Frame, cross: DVec3) -> DVec3 {
    let (ha, hb) = (fa.n.dot(fa.origin), fb.n.dot(fb.origin));
    (ha * fb.n.cross(cross) + hb * cross.cross(fa.n)) / cross.length_squared()
}

/// How a plate ends at a line of its mid-plane.
struct End {
    /// Into the plate, perpendicular to the line, in the model.
    into: DVec3,
    /// Where its edge runs along the line (parameters along the axis).
    span: (f64, f64),
    /// How far it reaches from the line.
    depth: f64,
    /// How far short of the line it stops (negative: it crosses it).
    near: f64,
}

/// Whether the plate lies on one side of the line (crossing it by at most `2t`, as plates
/// reach to the outer face of a corner) and has an edge within `band` of it (`2t` at a
/// corner: plates found from faces may stop short of it by about a thickness; more across a
/// fillet), and reaches at least `3t` beyond that edge (a narrower strip is all bend zone
/// and finger, and joints cut it apart); if so, where and how deep.
fn end_at(frame: &Frame, polygon: &Polygon, point: DVec3, axis: DVec3, t: f64, band: f64) -> Option<End> {
    let origin = frame.to_2d(point);
    let dir = DVec2::new(frame.u.dot(axis), frame.v.dot(axis)).normalize();
    let normal = dir.perp();
    let side = |q: DVec2| (q - origin).dot(normal);
    let (lo, hi) = polygon
        .outer
        .iter()
        .fold((f64::MAX, f64::MIN), |(lo, hi), q| (lo.min(side(*q)), hi.max(side(*q))));
    let sign = if hi >= -lo { 1.0 } else { -1.0 };
    let (near, far, depth) = if sign > 0.0 { (lo, -lo, hi) } else { (-hi, hi, -lo) };
    // Across a fillet, the edge is where the plate stops and its depth counts from there.
    let short = if near > 2.0 * t { near } else { 0.0 };
    if far > 2.0 * t || near > band || depth - short < 3.0 * t {
        return None;
    }
    let along = |q: DVec2| (frame.to_model_2d(q) - point).dot(axis);
    let mut span = (f64::MAX, f64::MIN);
    let ring = &polygon.outer;
    for (k, &q0) in ring.iter().enumerate() {
        let q1 = ring[(k + 1) % ring.len()];
        let (s0, s1) = (sign * side(q0), sign * side(q1));
        // The part of the edge within the band next to the line.
        let (lo_f, hi_f) = clip_param(s0, s1, short + 2.0 * t);
        if lo_f > hi_f {
            continue;
        }
        for f in [lo_f, hi_f] {
            let x = along(q0.lerp(q1, f));
            span = (span.0.min(x), span.1.max(x));
        }
    }
    (span.0 < span.1).then(|| End {
        into: sign * (frame.u * normal.x + frame.v * normal.y),
        span,
        depth,
        near,
    })
}

/// The parameters in [0, 1] of the edge whose signed distances run from `s0` to `s1` that
/// lie within `band` of the line (`s ≤ band`); empty when lo > hi.
fn clip_param(s0: f64, s1: f64, band: f64) -> (f64, f64) {
    match (s0 <= band, s1 <= band) {
        (true, true) => (0.0, 1.0),
        (false, false) => (1.0, 0.0),
        (true, false) => (0.0, (band - s0) / (s1 - s0)),
        (false, true) => ((band - s0) / (s1 - s0), 1.0),
    }
}
