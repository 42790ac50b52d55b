//! Laying a plate into the flat frame of a bent part: the rotation about the bend line that
//! brings it into its neighbour's plane (the thesis' development), then the bend deduction.
//!
//! Every member of a bent part has a frame whose normal agrees with the others' once
//! developed (a plate's own frame may face the other way: it is flipped), and a rigid motion
//! `place` from its mid-plane's 2D coordinates to the flat part's. Flipping a whole group of
//! members mirrors their flat, which is again a rigid layout.

use glam::{DVec2, DVec3};
use platener_geom::rigid::{Rigid2, mirror_y};
use platener_geom::{Frame, Polygon};
use serde::Serialize;

use super::find::Candidate;

/// A plate of a bent part.
#[derive(Debug, Clone, Serialize)]
pub struct Member {
    /// The plate (index into the plates snapshot).
    pub plate: u32,
    /// The plate's frame, flipped when the plate's own faces the other way (z from 0 to the
    /// thickness covers the same slab either way).
    pub frame: Frame,
    /// Whether `frame` is the plate's own frame flipped.
    pub flipped: bool,
    /// From the frame's 2D coordinates to the flat part's (the same on every face: the frame
    /// and its mid-plane share 2D coordinates).
    pub place: Rigid2,
}

impl Member {
    /// A plate on its own: its own frame, laid flat as it is.
    pub fn alone(plate: u32, frame: Frame) -> Self {
        Self {
            plate,
            frame,
            flipped: false,
            place: Rigid2::IDENTITY,
        }
    }

    /// The mid-plane of the member, `thickness` being its sheet's.
    pub fn mid(&self, thickness: f64) -> Frame {
        self.frame.shifted(thickness / 2.0)
    }

    /// A point of the member's mid-plane (in the model) on the flat part.
    pub fn to_flat(&self, thickness: f64, point: DVec3) -> DVec2 {
        self.place.apply(self.mid(thickness).to_2d(point))
    }

    /// A direction of the member's plane (in the model) on the flat part.
    pub fn dir_to_flat(&self, d: DVec3) -> DVec2 {
        self.place.rotate(DVec2::new(self.frame.u.dot(d), self.frame.v.dot(d)))
    }

    /// The plate's polygon (in its own frame) in this member's frame coordinates.
    pub fn local(&self, polygon: &Polygon) -> Polygon {
        if self.flipped {
            mirror_y(polygon)
        } else {
            polygon.clone()
        }
    }

    /// The member with its frame flipped and its flat mirrored, as when its whole group is.
    pub fn flip(&self, thickness: f64) -> Self {
        Self {
            plate: self.plate,
            frame: flipped(&self.frame, thickness),
            flipped: !self.flipped,
            place: self.place.mirrored(),
        }
    }

    /// The rigid frame placing the flat part's coordinates of this member's region in the
    /// model (z from 0 to the thickness): plan.json's segment transform.
    pub fn flat_frame(&self) -> Frame {
        let back = self.place.inverse();
        let origin = self.frame.to_model_2d(back.apply(DVec2::ZERO));
        let dir = |d: DVec2| {
            let r = back.rotate(d);
            self.frame.u * r.x + self.frame.v * r.y
        };
        Frame {
            origin,
            u: dir(DVec2::X),
            v: dir(DVec2::Y),
            n: self.frame.n,
        }
    }
}

/// The same slab seen from its other face: `(x, y, z) ↦ (x, −y, t − z)`.
pub fn flipped(f: &Frame, thickness: f64) -> Frame {
    Frame {
        origin: f.origin + f.n * thickness,
        u: f.u,
        v: -f.v,
        n: -f.n,
    }
}

/// Rotation of `v` about the unit `axis` by `angle` (Rodrigues).
pub(crate) fn rotate(v: DVec3, axis: DVec3, angle: f64) -> DVec3 {
    let (s, c) = angle.sin_cos();
    v * c + axis.cross(v) * s + axis * axis.dot(v) * (1.0 - c)
}

/// Where member `child` goes when it is developed into placed member `parent`'s flat across
/// the bend `c`, moved back towards the parent by `deduction`: the child with its frame
/// flipped if need be, and its new `place`.
pub(crate) fn develop(parent: &Member, child: &Member, c: &Candidate, thickness: f64, deduction: f64) -> Member {
    let sp = c.side_of(parent.plate as usize);
    let (into_p, into_c) = (c.into[sp], c.into[1 - sp]);
    let target = -into_p;
    let angle = c.axis.dot(into_c.cross(target)).atan2(into_c.dot(target));
    let mut child = child.clone();
    if rotate(child.frame.n, c.axis, angle).dot(parent.frame.n) < 0.0 {
        child = Member {
            frame: flipped(&child.frame, thickness),
            flipped: !child.flipped,
            ..child
        };
    }
    let (pm, cm) = (parent.mid(thickness), child.mid(thickness));
    let image = |q: DVec2| {
        let x = cm.to_model_2d(q) - c.point;
        let moved = c.point + rotate(x, c.axis, angle) + into_p * deduction;
        parent.place.apply(pm.to_2d(moved))
    };
    let (q0, q1) = (DVec2::ZERO, DVec2::new(100.0, 0.0));
    child.place = Rigid2::from_points(q0, q1, image(q0), image(q1));
    child
}
