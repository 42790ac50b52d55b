//! Plates as slabs: a polygon in a frame's plane, extruded from local z = 0 to z = thickness.
//!
//! The question plates keep asking each other is "which part of my outline lies over (or
//! under) your material?": to remove a plate contained in another, to trim overlapping
//! plates so no volume is claimed twice, and to bridge a plate split by one passing through
//! it. [`Slab::columns_meeting`] answers it: the region of this slab's outline whose columns
//! (segments through the thickness) meet the other slab's volume. It is exact when the planes
//! are parallel or perpendicular; at other angles it may include a little more, never less.
//!
//! A slab is also a part as a solid (verify and the score rebuild a plan's parts as slabs):
//! [`Slab::contains`] and [`Slab::within`] answer whether a model point is in it or near it.

use glam::{DVec2, DVec3};

use crate::boolean::{self, union_all};
use crate::frame::Frame;
use crate::grid::GridError;
use crate::polygon::Polygon;

/// A polygon extruded along its frame's normal.
#[derive(Debug, Clone, PartialEq)]
pub struct Slab {
    /// Local z = 0 is one face, z = `thickness` the other.
    pub frame: Frame,
    /// The outline in the frame's plane.
    pub polygon: Polygon,
    /// Thickness in mm.
    pub thickness: f64,
}

/// Points closer than this (mm, 1 nm) to a slab's face count as outside it, so that parts
/// merely touching face to face do not interfere.
pub const FACE_MARGIN: f64 = 1e-6;

impl Slab {
    /// The model-space box `(min, max)` of the volume.
    pub fn model_bounds(&self) -> (DVec3, DVec3) {
        extruded_bounds(&self.frame, &self.polygon.outer, self.thickness)
    }

    /// The volume in mm³ (0 for an outline whose holes cover it).
    pub fn volume(&self) -> f64 {
        self.polygon.area().max(0.0) * self.thickness
    }

    /// Whether the model point `p` is inside the volume; points within [`FACE_MARGIN`] of a
    /// face count as outside.
    pub fn contains(&self, p: DVec3) -> bool {
        let l = self.frame.to_local(p);
        l.z > FACE_MARGIN && l.z < self.thickness - FACE_MARGIN && self.polygon.contains(DVec2::new(l.x, l.y))
    }

    /// Whether the model point `p` is within `reach` of the volume (exact for a slab: the
    /// in-plane distance to the outline and the distance along the normal combine by
    /// Pythagoras).
    pub fn within(&self, p: DVec3, reach: f64) -> bool {
        let l = self.frame.to_local(p);
        let dz = (-l.z).max(l.z - self.thickness).max(0.0);
        if dz > reach {
            return false;
        }
        let q = DVec2::new(l.x, l.y);
        self.polygon.contains(q) || self.polygon.boundary_distance_squared(q) <= reach * reach - dz * dz
    }

    /// The region of `self.polygon` whose columns meet `other`'s volume, shrunk by `clearance`
    /// mm on the slab intervals so that slabs merely touching face to face give nothing.
    pub fn columns_meeting(&self, other: &Slab, clearance: f64) -> Result<Vec<Polygon>, GridError> {
        let clip = other.part_within_slab_of(self, clearance)?;
        if clip.is_empty() {
            return Ok(Vec::new());
        }
        // Project other's clipped prism along self's normal onto self's plane: the caps and
        // one quad per edge, unioned.
        let to_self = |p: DVec2, z: f64| self.frame.to_2d(other.frame.to_model(DVec3::new(p.x, p.y, z)));
        let mut pieces = Vec::new();
        for poly in &clip {
            for z in [0.0, other.thickness] {
                let mut cap = Polygon {
                    outer: poly.outer.iter().map(|p| to_self(*p, z)).collect(),
                    holes: poly
                        .holes
                        .iter()
                        .map(|h| h.iter().map(|p| to_self(*p, z)).collect())
                        .collect(),
                };
                cap.normalize_orientation();
                pieces.push(cap);
            }
            for ring in std::iter::once(&poly.outer).chain(&poly.holes) {
                for i in 0..ring.len() {
                    let (a, b) = (ring[i], ring[(i + 1) % ring.len()]);
                    let mut quad = Polygon::new(vec![
                        to_self(a, 0.0),
                        to_self(b, 0.0),
                        to_self(b, other.thickness),
                        to_self(a, other.thickness),
                    ]);
                    quad.normalize_orientation();
                    pieces.push(quad);
                }
            }
        }
        let shadow = union_all(&pieces)?;
        boolean::intersection(&shadow, std::slice::from_ref(&self.polygon))
    }

    /// The part of this slab's outline whose columns pass through `other`'s slab (the infinite
    /// layer between other's two faces), as polygons in this slab's frame.
    pub fn part_within_slab_of(&self, other: &Slab, clearance: f64) -> Result<Vec<Polygon>, GridError> {
        // other's height above its z = 0 face, for a point (u, v, z) of self, is
        // a·u + b·v + c·z + e.
        let n = other.frame.n;
        let (a, b, c) = (n.dot(self.frame.u), n.dot(self.frame.v), n.dot(self.frame.n));
        let e = n.dot(self.frame.origin - other.frame.origin);
        // Over z in [0, t], a·u + b·v + e must reach [clearance, other.t − clearance].
        let lo = clearance - (c * self.thickness).max(0.0);
        let hi = other.thickness - clearance - (c * self.thickness).min(0.0);
        let ab = DVec2::new(a, b);
        // The strip lo − e ≤ ab·p ≤ hi − e, clipped to a box around the outline: clipping a
        // box keeps every coordinate near the outline however close to parallel the planes are
        // (and parallel planes give the whole box or nothing).
        let (min, max) = self.polygon.bounds();
        let Some(strip) = strip_in_box(min - DVec2::ONE, max + DVec2::ONE, ab, lo - e, hi - e) else {
            return Ok(Vec::new());
        };
        boolean::intersection(std::slice::from_ref(&self.polygon), &[strip])
    }
}

/// The model-space box `(min, max)` of `ring` (in `frame`'s plane) extruded from local
/// z = 0 to z = `thickness`.
pub fn extruded_bounds(frame: &Frame, ring: &[DVec2], thickness: f64) -> (DVec3, DVec3) {
    let mut lo = DVec3::splat(f64::INFINITY);
    let mut hi = DVec3::splat(f64::NEG_INFINITY);
    for p in ring {
        for z in [0.0, thickness] {
            let q = frame.to_model(DVec3::new(p.x, p.y, z));
            lo = lo.min(q);
            hi = hi.max(q);
        }
    }
    (lo, hi)
}

/// The part of the box `min`–`max` where `lo ≤ n · p ≤ hi`, as a counter-clockwise polygon
/// (`None` when empty). Every coordinate stays inside the box.
pub fn strip_in_box(min: DVec2, max: DVec2, n: DVec2, lo: f64, hi: f64) -> Option<Polygon> {
    let mut ring = vec![min, DVec2::new(max.x, min.y), max, DVec2::new(min.x, max.y)];
    ring = clip_half_plane(&ring, n, lo);
    ring = clip_half_plane(&ring, -n, -hi);
    if ring.len() < 3 {
        return None;
    }
    let mut strip = Polygon::new(ring);
    strip.normalize_orientation();
    (strip.area() > 0.0).then_some(strip)
}

/// The part of a convex ring where `n · p ≥ c` (Sutherland–Hodgman, one plane).
fn clip_half_plane(ring: &[DVec2], n: DVec2, c: f64) -> Vec<DVec2> {
    let mut out = Vec::with_capacity(ring.len() + 1);
    for i in 0..ring.len() {
        let (p, q) = (ring[i], ring[(i + 1) % ring.len()]);
        let (dp, dq) = (n.dot(p) - c, n.dot(q) - c);
        if dp >= 0.0 {
            out.push(p);
        }
        if (dp >= 0.0) != (dq >= 0.0) {
            out.push(p + (q - p) * (dp / (dp - dq)));
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::polygon::total_area;

    fn rect(w: f64, h: f64) -> Polygon {
        Polygon::new(vec![
            DVec2::new(0.0, 0.0),
            DVec2::new(w, 0.0),
            DVec2::new(w, h),
            DVec2::new(0.0, h),
        ])
    }

    /// A horizontal 100×100×3 plate on z = 0 and a vertical 100 (y) × 50 (z) × 3 plate at
    /// x ∈ [40, 43], standing on z = −10 … 40: it passes through the first.
    fn cross() -> (Slab, Slab) {
        let floor = Slab {
            frame: Frame::on_plane(DVec3::ZERO, DVec3::Z),
            polygon: rect(100.0, 100.0),
            thickness: 3.0,
        };
        // Wall frame: normal +x at x = 40; on_plane gives u = z × n = +y, v = n × u = +z.
        let wall_frame = Frame::on_plane(DVec3::new(40.0, 0.0, 0.0), DVec3::X);
        let wall = Polygon::new(vec![
            DVec2::new(0.0, -10.0),
            DVec2::new(100.0, -10.0),
            DVec2::new(100.0, 40.0),
            DVec2::new(0.0, 40.0),
        ]);
        (
            floor,
            Slab {
                frame: wall_frame,
                polygon: wall,
                thickness: 3.0,
            },
        )
    }

    #[test]
    fn perpendicular_plates_cut_exact_strips() {
        let (floor, wall) = cross();
        let on_floor = floor.columns_meeting(&wall, 1e-6).expect("grid");
        // The wall's footprint on the floor: x ∈ [40, 43], y ∈ [0, 100].
        assert!(
            (total_area(&on_floor) - 300.0).abs() < 1e-3,
            "{}",
            total_area(&on_floor)
        );
        let (lo, hi) = on_floor[0].bounds();
        assert!((lo.x - 40.0).abs() < 1e-3 && (hi.x - 43.0).abs() < 1e-3);
        let on_wall = wall.columns_meeting(&floor, 1e-6).expect("grid");
        // The floor's layer on the wall: z ∈ [0, 3] over the wall's 100 mm width.
        assert!((total_area(&on_wall) - 300.0).abs() < 1e-3, "{}", total_area(&on_wall));
    }

    #[test]
    fn touching_faces_do_not_count() {
        let a = Slab {
            frame: Frame::on_plane(DVec3::ZERO, DVec3::Z),
            polygon: rect(10.0, 10.0),
            thickness: 3.0,
        };
        let b = Slab {
            frame: Frame::on_plane(DVec3::new(0.0, 0.0, 3.0), DVec3::Z),
            ..a.clone()
        };
        assert!(a.columns_meeting(&b, 1e-6).expect("grid").is_empty());
        // A wall standing on the plate's top face.
        let wall = Slab {
            frame: Frame::on_plane(DVec3::new(5.0, 0.0, 0.0), DVec3::X),
            polygon: Polygon::new(vec![
                DVec2::new(0.0, 3.0),
                DVec2::new(10.0, 3.0),
                DVec2::new(10.0, 20.0),
                DVec2::new(0.0, 20.0),
            ]),
            thickness: 2.0,
        };
        assert!(total_area(&a.columns_meeting(&wall, 1e-6).expect("grid")) < 1e-9);
    }

    #[test]
    fn nearly_parallel_plates_stay_near_the_outline() {
        let a = Slab {
            frame: Frame::on_plane(DVec3::ZERO, DVec3::Z),
            polygon: rect(10.0, 10.0),
            thickness: 3.0,
        };
        for tilt in [1e-12, 1e-9, 1e-7, 1e-4] {
            let n = DVec3::new(tilt, 0.0, 1.0).normalize();
            let b = Slab {
                frame: Frame::on_plane(DVec3::new(0.0, 0.0, 1.0), n),
                polygon: rect(10.0, 10.0),
                thickness: 3.0,
            };
            let got = a.columns_meeting(&b, 1e-6).expect("stays on the grid");
            assert!(
                (total_area(&got) - 100.0).abs() < 1e-3,
                "tilt {tilt}: {}",
                total_area(&got)
            );
        }
    }

    #[test]
    fn parallel_overlap_and_containment() {
        let big = Slab {
            frame: Frame::on_plane(DVec3::ZERO, DVec3::Z),
            polygon: rect(10.0, 10.0),
            thickness: 6.0,
        };
        let mut small = Slab {
            frame: Frame::on_plane(DVec3::new(0.0, 0.0, 2.0), DVec3::Z),
            polygon: rect(4.0, 4.0),
            thickness: 3.0,
        };
        assert!((total_area(&small.columns_meeting(&big, 1e-6).expect("grid")) - 16.0).abs() < 1e-6);
        small.frame = Frame::on_plane(DVec3::new(0.0, 0.0, 7.0), DVec3::Z);
        assert!(small.columns_meeting(&big, 1e-6).expect("grid").is_empty());
        // Opposite normal, overlapping in thickness: still found.
        let flipped = Slab {
            frame: Frame::on_plane(DVec3::new(0.0, 0.0, 4.0), -DVec3::Z),
            polygon: rect(4.0, -4.0),
            thickness: 1.0,
        };
        assert!(total_area(&flipped.columns_meeting(&big, 1e-6).expect("grid")) > 15.9);
    }
}
