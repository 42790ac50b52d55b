//! A part as a solid: its outline extruded by its thickness, placed by its transform.
//!
//! Built from plan.json's part (outline, holes, `[R | t]`), so what is measured is exactly
//! what a reader of the plan would assemble, whichever method made it.

use glam::{DVec2, DVec3};
use platener_geom::Frame;
use platener_geom::polygon::ring_contains;

use crate::plan::PlanPart;

/// One part's volume: points `frame.to_model((x, y, z))` with (x, y) in the outline and
/// 0 ≤ z ≤ thickness.
#[derive(Debug, Clone)]
pub(crate) struct Prism {
    /// The part's id in the plan.
    pub(crate) id: u32,
    /// Local → model.
    pub(crate) frame: Frame,
    /// Outer ring in the frame's plane.
    outer: Vec<DVec2>,
    /// Holes in the frame's plane.
    holes: Vec<Vec<DVec2>>,
    /// Thickness, mm.
    pub(crate) thickness: f64,
    /// Model-space box of the volume.
    pub(crate) lo: DVec3,
    /// Model-space box of the volume.
    pub(crate) hi: DVec3,
    /// Volume, mm³.
    pub(crate) volume: f64,
}

impl Prism {
    /// The part of the plan as a solid.
    pub(crate) fn from_part(part: &PlanPart) -> Self {
        let m = part.transform;
        let column = |j: usize| DVec3::new(m[0][j], m[1][j], m[2][j]);
        let frame = Frame {
            u: column(0),
            v: column(1),
            n: column(2),
            origin: column(3),
        };
        let mut lo = DVec3::splat(f64::INFINITY);
        let mut hi = DVec3::splat(f64::NEG_INFINITY);
        for p in &part.outline {
            for z in [0.0, part.thickness] {
                let q = frame.to_model(DVec3::new(p.x, p.y, z));
                lo = lo.min(q);
                hi = hi.max(q);
            }
        }
        let area = platener_geom::polygon::signed_area(&part.outline).abs()
            - part
                .holes
                .iter()
                .map(|h| platener_geom::polygon::signed_area(h).abs())
                .sum::<f64>();
        Self {
            id: part.id,
            frame,
            outer: part.outline.clone(),
            holes: part.holes.clone(),
            thickness: part.thickness,
            lo,
            hi,
            volume: area.max(0.0) * part.thickness,
        }
    }

    /// Box of the outline in the frame's plane.
    pub(crate) fn outline_bounds(&self) -> (DVec2, DVec2) {
        self.outer.iter().fold(
            (DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY)),
            |(lo, hi), p| (lo.min(*p), hi.max(*p)),
        )
    }

    /// Whether the plane point `p` is inside the outline and outside every hole.
    pub(crate) fn contains_2d(&self, p: DVec2) -> bool {
        ring_contains(&self.outer, p) && !self.holes.iter().any(|h| ring_contains(h, p))
    }

    /// Whether the box of the volume, grown by `reach`, holds `p` (a cheap first test).
    pub(crate) fn near_box(&self, p: DVec3, reach: f64) -> bool {
        p.cmpge(self.lo - reach).all() && p.cmple(self.hi + reach).all()
    }

    /// Whether the model point `p` is inside the volume; points within 1 nm of a face count
    /// as outside, so parts that merely touch do not interfere.
    pub(crate) fn contains(&self, p: DVec3) -> bool {
        let l = self.frame.to_local(p);
        l.z > 1e-6 && l.z < self.thickness - 1e-6 && self.contains_2d(DVec2::new(l.x, l.y))
    }

    /// Whether the model point `p` is within `reach` of the volume (exact for a prism: the
    /// in-plane distance to the outline and the distance along the normal combine by
    /// Pythagoras).
    pub(crate) fn within(&self, p: DVec3, reach: f64) -> bool {
        if !self.near_box(p, reach) {
            return false;
        }
        let l = self.frame.to_local(p);
        let dz = (-l.z).max(l.z - self.thickness).max(0.0);
        if dz > reach {
            return false;
        }
        let q = DVec2::new(l.x, l.y);
        if self.contains_2d(q) {
            return true;
        }
        let left = reach * reach - dz * dz;
        std::iter::once(&self.outer)
            .chain(&self.holes)
            .any(|ring| ring_distance_squared(ring, q) <= left)
    }
}

/// Squared distance from `p` to the closed ring's edges.
fn ring_distance_squared(ring: &[DVec2], p: DVec2) -> f64 {
    let n = ring.len();
    (0..n)
        .map(|i| segment_distance_squared(ring[i], ring[(i + 1) % n], p))
        .fold(f64::INFINITY, f64::min)
}

/// Squared distance from `p` to the segment `ab`.
fn segment_distance_squared(a: DVec2, b: DVec2, p: DVec2) -> f64 {
    let d = b - a;
    let len2 = d.length_squared();
    let t = if len2 > 0.0 {
        ((p - a).dot(d) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    (a + d * t).distance_squared(p)
}
