//! Rigid frames that carry a plane's 2D geometry to 3D and back.
//!
//! A planar shape is stored in its plane's own 2D coordinates; the frame is the rigid motion
//! (rotation with determinant +1, then translation) that puts those coordinates back in the
//! model: `model = u·x + v·y + n·z + origin`. It is exactly plan.json's part `transform`.

use glam::{DVec2, DVec3};
use serde::Serialize;

/// An orthonormal right-handed frame: `u × v = n`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Frame {
    /// Where local (0, 0, 0) lies in the model.
    pub origin: DVec3,
    /// Local x axis in model coordinates.
    pub u: DVec3,
    /// Local y axis in model coordinates.
    pub v: DVec3,
    /// Local z axis (the plane's normal).
    pub n: DVec3,
}

impl Frame {
    /// A frame on the plane through `origin` with unit `normal`.
    ///
    /// The in-plane axes are chosen deterministically and readably: walls (normal not near
    /// ±z) get a horizontal `u` and an upward-leaning `v`, floors get `u` along +x, so an
    /// outline printed in 2D looks like the wall seen from outside.
    pub fn on_plane(origin: DVec3, normal: DVec3) -> Self {
        let n = normal.normalize();
        let u = if n.z.abs() < 0.9 {
            DVec3::Z.cross(n).normalize()
        } else {
            (DVec3::X - n * n.x).normalize()
        };
        let v = n.cross(u);
        Self { origin, u, v, n }
    }

    /// Model point → local coordinates (x, y in the plane, z along the normal).
    pub fn to_local(&self, p: DVec3) -> DVec3 {
        let d = p - self.origin;
        DVec3::new(d.dot(self.u), d.dot(self.v), d.dot(self.n))
    }

    /// Model point → its 2D coordinates in the plane (projection along the normal).
    pub fn to_2d(&self, p: DVec3) -> DVec2 {
        let d = p - self.origin;
        DVec2::new(d.dot(self.u), d.dot(self.v))
    }

    /// Local coordinates → model point.
    pub fn to_model(&self, local: DVec3) -> DVec3 {
        self.origin + self.u * local.x + self.v * local.y + self.n * local.z
    }

    /// 2D plane coordinates → model point on the plane.
    pub fn to_model_2d(&self, p: DVec2) -> DVec3 {
        self.origin + self.u * p.x + self.v * p.y
    }

    /// The same frame moved `distance` along its normal.
    pub fn shifted(&self, distance: f64) -> Self {
        Self {
            origin: self.origin + self.n * distance,
            ..*self
        }
    }

    /// The 3×4 matrix `[R | t]` of plan.json (rows), with R's columns u, v, n.
    pub fn matrix(&self) -> [[f64; 4]; 3] {
        let (u, v, n, t) = (self.u, self.v, self.n, self.origin);
        [[u.x, v.x, n.x, t.x], [u.y, v.y, n.y, t.y], [u.z, v.z, n.z, t.z]]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn frames_are_right_handed_and_round_trip() {
        for n in [
            DVec3::Z,
            -DVec3::Z,
            DVec3::X,
            DVec3::new(1.0, 2.0, 3.0),
            DVec3::new(0.3, -0.1, -0.95),
        ] {
            let f = Frame::on_plane(DVec3::new(5.0, -3.0, 2.0), n);
            assert!((f.u.cross(f.v) - f.n).length() < 1e-12);
            assert!(f.u.dot(f.v).abs() < 1e-12);
            let p = DVec3::new(1.5, 2.5, -7.0);
            assert!((f.to_model(f.to_local(p)) - p).length() < 1e-12);
        }
    }
}
