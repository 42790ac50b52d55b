//! Rounded corners drawn as runs of narrow facets (a tray's 12 mm fillet in six 3 mm facets):
//! no facet is wide enough to be a plate or to hold a bend zone of its own, so the two walls
//! the fillet joins stop short of their corner and would stay apart. Where the model's
//! material between them curves as one wall would once bent, the pair is a candidate whose
//! single bend zone spans the whole run (an arc zone, issue 32): the zone's arc replaces the
//! facets.

use glam::DVec3;

use super::find::Candidate;
use super::zone::BendZone;
use crate::assembly::Inside;
use crate::plates::Plate;

/// Along the arc and along the line: where the model is probed (fractions of each).
const PROBES: [f64; 3] = [0.25, 0.5, 0.75];

/// The neutral arc of a fillet: tangent to both plates' mid-planes at `setback` from the line
/// where they meet, the arc a bend zone of that setback makes.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Arc {
    /// The arc's centre, at the start of the line (`Candidate::point`).
    pub centre: DVec3,
    /// Unit directions from the centre to the two tangent points.
    pub ends: [DVec3; 2],
    /// Its radius, mm.
    pub radius: f64,
    /// The turn it makes, radians.
    pub turn: f64,
}

impl Arc {
    /// The arc of candidate `c` at `setback` from its line.
    pub fn of(c: &Candidate, setback: f64) -> Self {
        let turn = c.turn();
        let radius = setback / (turn / 2.0).tan();
        let bisector = (c.into[0] + c.into[1]).normalize_or_zero();
        let centre = c.point + bisector * setback.hypot(radius);
        let end = |k: usize| ((c.point + c.into[k] * setback - centre) / radius).normalize_or_zero();
        Self {
            centre,
            ends: [end(0), end(1)],
            radius,
            turn,
        }
    }

    /// The unit direction from the centre a fraction `f` of the way from the first end to
    /// the second (spherical interpolation: both ends are perpendicular to the line).
    pub fn direction(&self, f: f64) -> DVec3 {
        let s = self.turn.sin();
        if s.abs() < 1e-9 {
            return self.ends[0];
        }
        (self.ends[0] * ((1.0 - f) * self.turn).sin() + self.ends[1] * (f * self.turn).sin()) / s
    }
}

/// Whether the model rounds the corner of candidate `c` (plates `t` thick stopping `c.gap`
/// short of their line) with one curved wall: along the arc a bend of that setback makes,
/// the model is solid at mid-thickness, empty a thickness outside and (where the arc is
/// wide enough to have an inside) a thickness inside, and nothing but the fillet's own
/// facets covers it. If so, those facets (plates lying along the arc, in thinner walls
/// wide enough to be found as plates): the arc zone replaces them.
pub(crate) fn facets_of(c: &Candidate, t: f64, inside: &Inside<'_>, plates: &[Plate]) -> Option<Vec<usize>> {
    let arc = Arc::of(c, c.gap);
    if !(arc.radius.is_finite() && arc.radius > 0.0) {
        return None;
    }
    let (a, b) = (c.point + c.axis * c.span.0, c.point + c.axis * c.span.1);
    let reach = DVec3::splat(arc.radius + c.gap + t);
    let near: Vec<usize> = (0..plates.len())
        .filter(|&k| {
            let (lo, hi) = plates[k].bounds();
            !c.plates.contains(&k) && lo.cmple(a.max(b) + reach).all() && (a.min(b) - reach).cmple(hi).all()
        })
        .collect();
    let facets: Vec<usize> = near
        .iter()
        .copied()
        .filter(|&k| on_arc(&plates[k], c, &arc, t))
        .collect();
    let blockers: Vec<_> = near
        .iter()
        .chain(&c.plates)
        .filter(|k| !facets.contains(k))
        .map(|&k| plates[k].slab())
        .collect();
    let solid = PROBES.iter().all(|&f| {
        let dir = arc.direction(f);
        PROBES.iter().all(|&g| {
            let along = c.axis * (c.span.0 + g * (c.span.1 - c.span.0));
            let at = |r: f64| arc.centre + along + dir * r;
            let mid = at(arc.radius);
            inside.contains(mid)
                && !blockers.iter().any(|s| s.contains(mid))
                && !inside.contains(at(arc.radius + t))
                && (arc.radius < 1.5 * t || !inside.contains(at(arc.radius - t)))
        })
    });
    solid.then_some(facets)
}

/// Whether `plate` (as thick as the candidate's) lies along `arc`: every corner of its
/// mid-plane within a thickness of the arc's radius, inside the arc's sector, and within
/// the candidate's reach along the line.
fn on_arc(plate: &Plate, c: &Candidate, arc: &Arc, t: f64) -> bool {
    if (plate.thickness - t).abs() > 1e-6 {
        return false;
    }
    let half = arc.turn / 2.0;
    let middle = arc.direction(0.5);
    plate.polygon.outer.iter().all(|q| {
        let p = plate.frame.to_model(q.extend(t / 2.0)) - arc.centre;
        let along = p.dot(c.axis);
        let radial = p - c.axis * along;
        let r = radial.length();
        let angle = (radial.dot(middle) / r.max(1e-12)).clamp(-1.0, 1.0).acos();
        (r - arc.radius).abs() <= t
            && angle <= half + 1e-3
            && along >= c.reach.0 - 2.0 * t
            && along <= c.reach.1 + 2.0 * t
    })
}

/// Between an arc zone across a fillet whose facets are plates and those facets' own bends:
/// where every bend of the run has a zone (facets wide enough to bend one by one, a tray's
/// corner of four 14 mm facets), the run bends facet by facet as before and the arc
/// candidate goes; otherwise the arc replaces the facets and every other candidate of theirs
/// goes. Only the widest arcs count (an arc from one facet to another is part of the arc
/// between the walls), and arcs without a zone go.
pub(crate) fn prefer_arcs(
    candidates: Vec<Candidate>,
    zones: Vec<Result<BendZone, String>>,
) -> (Vec<Candidate>, Vec<Result<BendZone, String>>) {
    let arc = |k: usize| candidates[k].gap > 0.0;
    let mut keep: Vec<bool> = (0..candidates.len()).map(|k| !arc(k) || zones[k].is_ok()).collect();
    let arcs: Vec<usize> = (0..candidates.len()).filter(|&k| arc(k) && keep[k]).collect();
    for &ci in &arcs {
        let c = &candidates[ci];
        let within = arcs
            .iter()
            .any(|&o| o != ci && c.plates.iter().any(|p| candidates[o].facets.contains(p)));
        if within {
            keep[ci] = false;
        }
    }
    let widest: Vec<usize> = arcs
        .iter()
        .copied()
        .filter(|&k| keep[k] && !candidates[k].facets.is_empty())
        .collect();
    for ci in widest {
        let facets = &candidates[ci].facets;
        let run: Vec<usize> = (0..candidates.len())
            .filter(|&k| !arc(k) && candidates[k].plates.iter().any(|p| facets.contains(p)))
            .collect();
        if !run.is_empty() && run.iter().all(|&k| zones[k].is_ok()) {
            keep[ci] = false;
        } else {
            for k in run {
                keep[k] = false;
            }
        }
    }
    candidates
        .into_iter()
        .zip(zones)
        .zip(keep)
        .filter_map(|(pair, k)| k.then_some(pair))
        .unzip()
}
