//! Rigid motions of the plane (rotation, then translation), and the one reflection bent parts
//! need: laying plates of a bent part side by side in one flat frame composes such motions.

use glam::DVec2;

use crate::polygon::{Polygon, Ring};

/// `p ↦ R(angle)·p + t`, stored as the rotation's cosine and sine.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct Rigid2 {
    /// cos of the rotation angle.
    pub cos: f64,
    /// sin of the rotation angle.
    pub sin: f64,
    /// The translation, applied after the rotation.
    pub t: DVec2,
}

impl Rigid2 {
    /// The motion that moves nothing.
    pub const IDENTITY: Rigid2 = Rigid2 {
        cos: 1.0,
        sin: 0.0,
        t: DVec2::ZERO,
    };

    /// Maps a point.
    pub fn apply(&self, p: DVec2) -> DVec2 {
        self.rotate(p) + self.t
    }

    /// Rotates a direction (no translation).
    pub fn rotate(&self, d: DVec2) -> DVec2 {
        DVec2::new(self.cos * d.x - self.sin * d.y, self.sin * d.x + self.cos * d.y)
    }

    /// Maps a ring, keeping its orientation (rigid motions preserve it).
    pub fn apply_ring(&self, ring: &[DVec2]) -> Ring {
        ring.iter().map(|p| self.apply(*p)).collect()
    }

    /// Maps a polygon.
    pub fn apply_polygon(&self, p: &Polygon) -> Polygon {
        Polygon {
            outer: self.apply_ring(&p.outer),
            holes: p.holes.iter().map(|h| self.apply_ring(h)).collect(),
        }
    }

    /// The motion undoing this one.
    pub fn inverse(&self) -> Rigid2 {
        let back = Rigid2 {
            cos: self.cos,
            sin: -self.sin,
            t: DVec2::ZERO,
        };
        Rigid2 {
            t: -back.rotate(self.t),
            ..back
        }
    }

    /// `self` first, then `next`.
    pub fn then(&self, next: &Rigid2) -> Rigid2 {
        Rigid2 {
            cos: next.cos * self.cos - next.sin * self.sin,
            sin: next.sin * self.cos + next.cos * self.sin,
            t: next.apply(self.t),
        }
    }

    /// The motion that takes `a0` to `b0` and the direction `a1 - a0` to that of `b1 - b0`
    /// (the distances are assumed equal: the caller maps two points of a rigid body).
    pub fn from_points(a0: DVec2, a1: DVec2, b0: DVec2, b1: DVec2) -> Rigid2 {
        let (da, db) = ((a1 - a0).normalize(), (b1 - b0).normalize());
        let rot = Rigid2 {
            cos: da.dot(db),
            sin: da.perp_dot(db),
            t: DVec2::ZERO,
        };
        Rigid2 {
            t: b0 - rot.rotate(a0),
            ..rot
        }
    }

    /// This motion seen in mirrored coordinates, `(x, y) ↦ (x, −y)` on both sides: the
    /// motion that maps mirrored points to the mirror images of where this one maps them.
    pub fn mirrored(&self) -> Rigid2 {
        Rigid2 {
            cos: self.cos,
            sin: -self.sin,
            t: DVec2::new(self.t.x, -self.t.y),
        }
    }
}

/// Mirrors a polygon across the x axis, `(x, y) ↦ (x, −y)`, and restores its orientation
/// (outer counter-clockwise, holes clockwise), which a reflection reverses.
pub fn mirror_y(p: &Polygon) -> Polygon {
    let flip = |r: &Ring| r.iter().map(|q| DVec2::new(q.x, -q.y)).collect();
    let mut out = Polygon {
        outer: flip(&p.outer),
        holes: p.holes.iter().map(flip).collect(),
    };
    out.normalize_orientation();
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn motion(angle: f64, tx: f64, ty: f64) -> Rigid2 {
        Rigid2 {
            cos: angle.cos(),
            sin: angle.sin(),
            t: DVec2::new(tx, ty),
        }
    }

    proptest! {
        #[test]
        fn compose_inverse_and_mirror_agree_with_points(
            a in -4.0f64..4.0, b in -4.0f64..4.0, x in -50.0f64..50.0, y in -50.0f64..50.0,
            tx in -20.0f64..20.0, ty in -20.0f64..20.0,
        ) {
            let (m, n) = (motion(a, tx, ty), motion(b, ty, tx));
            let p = DVec2::new(x, y);
            prop_assert!((m.then(&n).apply(p) - n.apply(m.apply(p))).length() < 1e-9);
            prop_assert!((m.inverse().apply(m.apply(p)) - p).length() < 1e-9);
            let mirror = |q: DVec2| DVec2::new(q.x, -q.y);
            prop_assert!((m.mirrored().apply(mirror(p)) - mirror(m.apply(p))).length() < 1e-9);
            let q = DVec2::new(y, x);
            let fit = Rigid2::from_points(p, q, m.apply(p), m.apply(q));
            if (q - p).length() > 1e-3 {
                prop_assert!((fit.apply(DVec2::new(3.0, -7.0)) - m.apply(DVec2::new(3.0, -7.0))).length() < 1e-6);
            }
        }
    }

    #[test]
    fn mirror_keeps_orientation_and_area() {
        let p = Polygon::new(crate::polygon::rect(0.0, 1.0, 4.0, 3.0));
        let m = mirror_y(&p);
        assert!((m.area() - 8.0).abs() < 1e-12);
        assert!(crate::polygon::signed_area(&m.outer) > 0.0);
        assert!(m.outer.iter().all(|q| q.y <= -1.0 && q.y >= -3.0));
    }
}
