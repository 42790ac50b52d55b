//! Capping finger length at shallow corners.
//!
//! Two plates' layers cross in a parallelogram (the thesis' joint region); at a corner each
//! plate's fingers fill it across the whole layer of the other. Towards 180° it gets long and
//! thin: 17 mm for 3 mm sheets at 160°. A laser's cut is square to the sheet, so a finger that
//! long runs straight on where the surface bends: it sticks out of the model on one face and
//! leaves a wedge unfilled on the other, both growing with the square of its length, and the
//! notches it needs cut deep into small facets (a low-poly model's plates fall into pieces).
//!
//! So past the joint's middle line (where the two plates' middle planes meet) the region
//! reaches no further into either plate than it does at 150° (the shallowest angle
//! that must close without gaps). It is cut by a plane square to each plate
//! and each plate keeps the columns of the cut region: a finger then never meets what its
//! partner keeps, because every point of the partner's layer under the finger lies in the cut
//! region and so in the partner's notch.

use glam::DVec3;

use super::connect::{band, into_plate};
use crate::plates::Plate;
use platener_geom::{GridError, Polygon};

/// The steepest angle (degrees) between the plates' normals whose region is left whole. A
/// region reaches past the middle line half the crossing width, which grows as the normals
/// close up; from here on (an enclosed angle above 150° or below 30°) it is held at this
/// angle's length.
pub(super) const CAP_DEG: f64 = 30.0;

/// The cap of the short variant a joint falls back to when its fingers would cut a plate
/// apart: fingers as long as at 60°, less than a thickness past the middle line.
pub(super) const SHORT_DEG: f64 = 60.0;

/// How far `a`'s fingers may reach past the middle line into `b` under a cap of `deg`: half
/// the width of `b`'s layer seen in `a`'s plane at that angle.
fn limit(a: &Plate, b: &Plate, deg: f64) -> f64 {
    let (s, c) = deg.to_radians().sin_cos();
    (b.thickness + a.thickness * c) / (2.0 * s)
}

/// The cross-section of two plates' layers (across `axis`), relative to a point `m` on both
/// middle planes: the corners of the parallelogram where they cross.
fn crossing(a: &Plate, b: &Plate) -> [DVec3; 4] {
    let (na, nb) = (a.frame.n, b.frame.n);
    let c = na.dot(nb);
    // The point at heights h1 and h2 above the middle planes, on the middle line's cross-section.
    let point = |h1: f64, h2: f64| ((h1 - h2 * c) * na + (h2 - h1 * c) * nb) / (1.0 - c * c);
    let (ha, hb) = (a.thickness / 2.0, b.thickness / 2.0);
    [point(ha, hb), point(ha, -hb), point(-ha, -hb), point(-ha, hb)]
}

/// The point on both plates' middle planes closest to `near`.
pub(super) fn middle_line(a: &Plate, b: &Plate, near: DVec3) -> DVec3 {
    let (na, nb) = (a.frame.n, b.frame.n);
    let c = na.dot(nb);
    let h1 = na.dot(a.frame.origin) + a.thickness / 2.0;
    let h2 = nb.dot(b.frame.origin) + b.thickness / 2.0;
    let on_both = ((h1 - h2 * c) * na + (h2 - h1 * c) * nb) / (1.0 - c * c);
    let axis = na.cross(nb).normalize();
    on_both + axis * axis.dot(near - on_both)
}

/// The part of the convex polygon `ring` where `f` is at most `limit` (Sutherland–Hodgman
/// against one half-plane; `f` is linear).
fn clip(ring: &[DVec3], f: impl Fn(DVec3) -> f64, limit: f64) -> Vec<DVec3> {
    let mut out = Vec::with_capacity(ring.len() + 1);
    for (i, &p) in ring.iter().enumerate() {
        let q = ring[(i + 1) % ring.len()];
        let (fp, fq) = (f(p) - limit, f(q) - limit);
        if fp <= 0.0 {
            out.push(p);
        }
        if (fp < 0.0 && fq > 0.0) || (fp > 0.0 && fq < 0.0) {
            out.push(p + (q - p) * (fp / (fp - fq)));
        }
    }
    out
}

/// The joint regions `in_a` and `in_b` of a corner between `a` and `b` along `axis` (around
/// the model point `center`), cut so that neither plate's fingers reach further past the
/// middle line than at `deg` between the normals; `None` where the layers' crossing is
/// shorter than that.
pub(super) fn capped(
    a: &Plate,
    b: &Plate,
    axis: DVec3,
    center: DVec3,
    (in_a, in_b): (&Polygon, &Polygon),
    deg: f64,
) -> Result<Option<(Polygon, Polygon)>, GridError> {
    let m = middle_line(a, b, center);
    // Directions from the line into each plate: a finger of a reaches along −into_a.
    let (into_a, into_b) = (into_plate(a, axis, m), into_plate(b, axis, m));
    let (limit_a, limit_b) = (limit(a, b, deg), limit(b, a, deg));
    let region = crossing(a, b);
    let reach = |into: DVec3| region.iter().map(|p| -into.dot(*p)).fold(f64::NEG_INFINITY, f64::max);
    if reach(into_a) <= limit_a + 1e-9 && reach(into_b) <= limit_b + 1e-9 {
        return Ok(None);
    }
    let cut = clip(&clip(&region, |p| -into_a.dot(p), limit_a), |p| -into_b.dot(p), limit_b);
    let cut_to = |plate: &Plate, into: DVec3, region: &Polygon| -> Result<Option<Polygon>, GridError> {
        let (lo, hi) = super::along::span(cut.iter().map(|p| into.dot(*p)));
        let s = into.dot(m);
        let pieces = band(plate, region, into, s + lo, s + hi)?;
        Ok(pieces.into_iter().max_by(|x, y| x.area().total_cmp(&y.area())))
    };
    Ok(cut_to(a, into_a, in_a)?.zip(cut_to(b, into_b, in_b)?))
}
