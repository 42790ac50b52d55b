//! Collision shapes for nesting: each part's cut path grown by half the spacing, pre-rotated.
//!
//! Two grown shapes that do not overlap keep their cut paths at least `spacing` apart, so the
//! nester only ever asks "do these polygons overlap?". The grown outline goes to jagua-rs as
//! an f32 polygon (its collision engine's type); f32 rounding on a 1 m sheet is below 0.1 µm
//! of a 1 µm grid and vanishes inside the spacing. Holes are not part of the collision shape:
//! parts placed into holes are handled as children of their host (see `holes.rs`).

use std::f64::consts::FRAC_PI_2;

use glam::DVec2;
use jagua_rs::geometry::Transformation;
use jagua_rs::geometry::geo_traits::Transformable;
use jagua_rs::geometry::primitives::{Point, SPolygon};
use platener_geom::polygon::{bounds_of, remove_straight_vertices};
use platener_geom::{Polygon, Ring, offset, validate};

/// Rotations closer than this (radians, 0.5°) to a multiple of 90° count as that multiple.
const SAME_ANGLE: f64 = 0.5 * std::f64::consts::PI / 180.0;

/// One orientation of a part: rotated by `angle`, then shifted so its box starts at (0, 0).
#[derive(Debug, Clone)]
pub(crate) struct Template {
    /// Rotation, radians.
    pub angle: f64,
    /// Translation after the rotation that puts the grown shape's box corner at the origin.
    pub shift: DVec2,
    /// Size of the grown shape's box, mm.
    pub size: DVec2,
    /// The grown, rotated, shifted outline as jagua-rs sees it.
    pub shape: SPolygon,
    /// The largest circle inside the grown shape (jagua-rs's pole of inaccessibility, made
    /// with the polygon): centre from the box corner, and radius, mm.
    pub core: (DVec2, f64),
    /// Reflex corners of the grown outline between two edges of at least [`POCKET_EDGE`]:
    /// the inner corners of Ls and notches where another part may nest.
    pub pockets: Vec<DVec2>,
}

impl Template {
    /// The rotation and translation mapping the part's own frame onto a position where the
    /// template's box corner is at `pos`.
    pub fn placement(&self, pos: DVec2) -> (f64, DVec2) {
        (self.angle, self.shift + pos)
    }
}

/// A part as the nester sees it.
#[derive(Debug, Clone)]
pub(crate) struct NestShape {
    /// Its orientations, the first one at 0°.
    pub templates: Vec<Template>,
    /// Nominal area (the material it uses), mm².
    pub area: f64,
    /// The cut path (part frame), for hosting children in its holes.
    pub cut: Polygon,
}

/// Rotates `p` by `angle` radians (the standard matrix; clockwise on a y-down screen).
pub(crate) fn rotate(p: DVec2, angle: f64) -> DVec2 {
    DVec2::from_angle(angle).rotate(p)
}

/// The convex hull of `points`, counter-clockwise (monotone chain).
fn convex_hull(points: &[DVec2]) -> Vec<DVec2> {
    let mut pts = points.to_vec();
    pts.sort_by(|a, b| a.x.total_cmp(&b.x).then(a.y.total_cmp(&b.y)));
    pts.dedup();
    if pts.len() < 3 {
        return pts;
    }
    let mut hull: Vec<DVec2> = Vec::with_capacity(2 * pts.len());
    for pass in 0..2 {
        let start = hull.len();
        for &p in &pts {
            while hull.len() >= start + 2
                && (hull[hull.len() - 1] - hull[hull.len() - 2]).perp_dot(p - hull[hull.len() - 2]) <= 0.0
            {
                hull.pop();
            }
            hull.push(p);
        }
        hull.pop();
        if pass == 0 {
            pts.reverse();
        }
    }
    hull
}

/// The rotation (radians, in [0, π/2)) that makes the smallest-area bounding rectangle of
/// `ring` axis-parallel (rotating calipers over the convex hull's edges).
pub(crate) fn min_area_angle(ring: &[DVec2]) -> f64 {
    let hull = convex_hull(ring);
    let mut best = (f64::INFINITY, 0.0);
    for i in 0..hull.len() {
        let e = hull[(i + 1) % hull.len()] - hull[i];
        if e.length_squared() == 0.0 {
            continue;
        }
        let angle = (-e.y.atan2(e.x)).rem_euclid(FRAC_PI_2);
        let (lo, hi) = bounds_of(hull.iter().map(|p| rotate(*p, angle)));
        let area = (hi - lo).x * (hi - lo).y;
        if area < best.0 - 1e-9 * area.abs() {
            best = (area, angle);
        }
    }
    best.1
}

/// Edges shorter than this (mm) do not make a pocket: finger notches are too small to hold a
/// part, and anchoring candidates at all their corners would only cost time.
pub(crate) const POCKET_EDGE: f64 = 10.0;

/// Reflex vertices of the counter-clockwise `ring` whose both edges are at least
/// [`POCKET_EDGE`] long.
fn pockets(ring: &[DVec2]) -> Vec<DVec2> {
    let n = ring.len();
    (0..n)
        .filter(|&i| {
            let (a, b, c) = (ring[(i + n - 1) % n], ring[i], ring[(i + 1) % n]);
            (b - a).perp_dot(c - b) < 0.0 && a.distance(b) >= POCKET_EDGE && b.distance(c) >= POCKET_EDGE
        })
        .map(|i| ring[i])
        .collect()
}

/// Shapes narrower than this (mm) never reach jagua-rs: its f32 engine unwraps a bounding box
/// and a pole of inaccessibility with no extent (a panic, not an error), and a shape a few
/// nanometres wide rounds to nothing in f32 once moved across a sheet. Far below any part: a
/// cut path is at least the spacing wide.
pub(crate) const MIN_NEST_WIDTH: f64 = 0.01;

/// Whether `ring` can go to jagua-rs as a region: a valid simple ring (exact predicates) with
/// no piece narrower than [`MIN_NEST_WIDTH`]. Hole regions are checked with it: a hole shrunk
/// by half the spacing can leave slivers microns wide.
pub(crate) fn nestable(ring: &[DVec2]) -> bool {
    let (lo, hi) = bounds_of(ring.iter().copied());
    (hi - lo).min_element() >= MIN_NEST_WIDTH && validate(&Polygon::new(ring.to_vec()), MIN_NEST_WIDTH).is_empty()
}

/// The jagua-rs polygon of `ring`; a ring it refuses (f32 duplicates, self-touching after
/// rotation) falls back to its bounding rectangle, which is larger and so still safe. `None`
/// for a ring narrower than [`MIN_NEST_WIDTH`] in x or y, which jagua-rs cannot take.
pub(crate) fn to_spolygon(ring: &[DVec2]) -> Option<SPolygon> {
    let (lo, hi) = bounds_of(ring.iter().copied());
    let extent = (hi - lo).min_element();
    if ring.len() < 3 || extent.is_nan() || extent < MIN_NEST_WIDTH {
        return None;
    }
    let points: Vec<Point> = ring.iter().map(|p| Point(p.x as f32, p.y as f32)).collect();
    SPolygon::new(points).ok().or_else(|| {
        let rect = [lo, DVec2::new(hi.x, lo.y), hi, DVec2::new(lo.x, hi.y)];
        SPolygon::new(rect.iter().map(|p| Point(p.x as f32, p.y as f32)).collect()).ok()
    })
}

/// Vertices this close (mm) to the straight line past them are dropped from a nest shape:
/// joints leave runs of vertices microns apart (hairline notches, grid steps), and collision
/// checks cost by the edge. A part's nest shape is its cut grown by half the spacing, so
/// cutting a corner this much still keeps parts far apart.
const NEST_SIMPLIFY: f64 = 0.02;

/// The outline of `cut` grown by `grow` mm (miter joins), holes dropped, without vertices on
/// straight runs ([`NEST_SIMPLIFY`]).
pub(crate) fn grown_outline(cut: &Polygon, grow: f64) -> Option<Ring> {
    let outer = Polygon::new(cut.outer.clone());
    let grown = offset::offset(&[outer], grow).ok()?;
    grown
        .into_iter()
        .max_by(|a, b| a.area().total_cmp(&b.area()))
        .map(|p| remove_straight_vertices(&p.outer, NEST_SIMPLIFY))
}

/// The nest shape of a part with cut path `cut` and nominal area `area`; `None` when no
/// orientation of its grown outline can go to jagua-rs ([`to_spolygon`]; the caller names the
/// part). Grown by half the spacing (more than half the kerf), an outline is never thinner
/// than [`MIN_NEST_WIDTH`]; simplifying it may make it touch itself, which jagua-rs refuses
/// and [`to_spolygon`] replaces by the bounding rectangle.
///
/// Orientations: 0, 90, 180 and 270°, and with `fine` also the smallest-rectangle angle plus
/// 90° steps when it differs from those (a part drawn askew in its frame).
pub(crate) fn nest_shape(cut: &Polygon, area: f64, spacing: f64, fine: bool) -> Option<NestShape> {
    let ring = grown_outline(cut, spacing / 2.0)?;
    let mut angles: Vec<f64> = (0..4).map(|k| f64::from(k) * FRAC_PI_2).collect();
    if fine {
        let a = min_area_angle(&ring);
        if a > SAME_ANGLE && a < FRAC_PI_2 - SAME_ANGLE {
            angles.extend((0..4).map(|k| a + f64::from(k) * FRAC_PI_2));
        }
    }
    // jagua-rs computes a polygon's pole of inaccessibility when it is made, the costliest
    // part of nesting a few parts; rotating one polygon keeps its pole, so it is made once.
    let base = to_spolygon(&ring);
    let templates = angles
        .into_iter()
        .filter_map(|angle| {
            let rotated: Vec<DVec2> = ring.iter().map(|p| rotate(*p, angle)).collect();
            let (lo, hi) = bounds_of(rotated.iter().copied());
            let shifted: Vec<DVec2> = rotated.iter().map(|p| *p - lo).collect();
            let shape = match &base {
                Some(base) if (hi - lo).min_element() >= MIN_NEST_WIDTH => {
                    let moved = Transformation::from_rotation(angle as f32).translate((-lo.x as f32, -lo.y as f32));
                    let mut shape = base.clone();
                    shape.transform(&moved);
                    shape
                }
                _ => to_spolygon(&shifted)?,
            };
            let poi = shape.poi();
            let core = (
                DVec2::new(f64::from(poi.center.0), f64::from(poi.center.1)),
                f64::from(poi.radius),
            );
            Some(Template {
                angle,
                shift: -lo,
                size: hi - lo,
                core,
                pockets: pockets(&shifted),
                shape,
            })
        })
        .collect::<Vec<_>>();
    (!templates.is_empty()).then(|| NestShape {
        templates,
        area,
        cut: cut.clone(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_tilted_rectangle_is_straightened() {
        let a = 0.3_f64;
        let ring: Vec<DVec2> = [(0.0, 0.0), (40.0, 0.0), (40.0, 10.0), (0.0, 10.0)]
            .iter()
            .map(|&(x, y)| rotate(DVec2::new(x, y), a))
            .collect();
        let found = min_area_angle(&ring);
        // Undoing the tilt, up to quarter turns.
        let err = (found + a).rem_euclid(FRAC_PI_2);
        assert!(err.min(FRAC_PI_2 - err) < 1e-9, "{found}");
        let shape = nest_shape(&Polygon::new(ring), 400.0, 2.0, true).expect("valid");
        assert_eq!(shape.templates.len(), 8);
        let smallest = shape
            .templates
            .iter()
            .map(|t| t.size.x * t.size.y)
            .fold(f64::INFINITY, f64::min);
        // 42 × 12 once straightened (miter-grown by 1 mm).
        assert!((smallest - 42.0 * 12.0).abs() < 0.01, "{smallest}");
    }

    /// A 40 × 10 plate whose long edges step by 5 µm every millimetre (as joints leave them):
    /// its nest shape is a plain rectangle, still at least half the spacing minus the
    /// simplification around every point of the cut.
    #[test]
    fn micro_steps_do_not_reach_the_nest_shape() {
        let mut ring = Vec::new();
        for i in 0..40 {
            let y = if i % 2 == 0 { 0.0 } else { 0.005 };
            ring.extend([DVec2::new(f64::from(i), y), DVec2::new(f64::from(i + 1), y)]);
        }
        ring.extend([DVec2::new(40.0, 10.0), DVec2::new(0.0, 10.0)]);
        let cut = Polygon::new(ring);
        let grown = grown_outline(&cut, 1.0).expect("grows");
        assert!(grown.len() <= 6, "{} vertices", grown.len());
        let nest = Polygon::new(grown);
        for p in &cut.outer {
            assert!(
                nest.contains(*p) && nest.boundary_distance(*p) >= 1.0 - NEST_SIMPLIFY,
                "{p}"
            );
        }
    }

    #[test]
    fn templates_start_at_the_origin() {
        let ring = vec![DVec2::new(5.0, 5.0), DVec2::new(25.0, 5.0), DVec2::new(5.0, 15.0)];
        let shape = nest_shape(&Polygon::new(ring), 100.0, 1.0, false).expect("valid");
        for t in &shape.templates {
            let pts: Vec<DVec2> = grown_outline(&shape.cut, 0.5)
                .expect("grows")
                .iter()
                .map(|p| rotate(*p, t.angle) + t.shift)
                .collect();
            let (lo, hi) = bounds_of(pts);
            assert!(lo.length() < 1e-9 && (hi - t.size).length() < 1e-9);
        }
    }
}
