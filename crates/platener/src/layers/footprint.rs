//! Where the plates are in a layer: the ground a plate covers within a layer's slab, seen down
//! the stack, so the layer can keep clear of it.
//!
//! A plate is its outline extruded over its thickness; within the slab `z0 ≤ z ≤ z1` of the
//! stack frame it is the outline clipped to the strip where some depth of the plate lies in the
//! slab, swept through the plate's thickness. Seen down the stack, that sweep is the clipped
//! outline at depth 0, at full depth, and one parallelogram per edge between the two: exact for
//! tilted plates and walls standing across the layers alike (a wall's clipped outline is a
//! line seen from above; its parallelograms are the wall's section). The strip is the union
//! over depths, so the footprint may be a little larger than the plate's section, never
//! smaller.

use glam::{DVec2, DVec3};
use platener_geom::{Frame, GridError, Polygon, boolean};

/// A plate's solid: outline, placement and thickness.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Slab<'a> {
    /// The outline in its own 2D frame.
    pub polygon: &'a Polygon,
    /// Where it sits: local z from 0 to `thickness`.
    pub frame: &'a Frame,
    /// Its thickness, mm.
    pub thickness: f64,
}

/// The slab as the stack sees it: coordinates of the plate frame's axes in the stack frame.
struct Seen {
    /// Stack coordinates of the plate's local origin.
    origin: DVec3,
    u: DVec3,
    v: DVec3,
    n: DVec3,
}

impl Seen {
    fn new(slab: &Slab<'_>, stack: &Frame) -> Self {
        let dir = |d: DVec3| DVec3::new(d.dot(stack.u), d.dot(stack.v), d.dot(stack.n));
        Self {
            origin: stack.to_local(slab.frame.origin),
            u: dir(slab.frame.u),
            v: dir(slab.frame.v),
            n: dir(slab.frame.n),
        }
    }

    /// Stack coordinates of plate point `p` at depth `w`.
    fn at(&self, p: DVec2, w: f64) -> DVec3 {
        self.origin + self.u * p.x + self.v * p.y + self.n * w
    }
}

/// The heights (stack z) the slab spans.
pub(crate) fn height_range(slab: &Slab<'_>, stack: &Frame) -> (f64, f64) {
    let seen = Seen::new(slab, stack);
    let mut range = (f64::INFINITY, f64::NEG_INFINITY);
    for &p in &slab.polygon.outer {
        for w in [0.0, slab.thickness] {
            let z = seen.at(p, w).z;
            range = (range.0.min(z), range.1.max(z));
        }
    }
    range
}

/// The ground `slab` covers within heights `z0..z1` of `stack`, in the stack's 2D frame
/// (empty when it does not reach into the slab by more than a micrometre).
pub(crate) fn footprint(slab: &Slab<'_>, stack: &Frame, z0: f64, z1: f64) -> Result<Vec<Polygon>, GridError> {
    const TOUCH: f64 = 1e-3;
    let (lo, hi) = height_range(slab, stack);
    if hi <= z0 + TOUCH || lo >= z1 - TOUCH {
        return Ok(Vec::new());
    }
    let seen = Seen::new(slab, stack);
    let t = slab.thickness;
    let clipped = clip_to_heights(slab.polygon, &seen, t, z0, z1)?;
    let mut pieces: Vec<Polygon> = Vec::new();
    for p in &clipped {
        for w in [0.0, t] {
            pieces.push(mapped(p, |q| seen.at(q, w).truncate()));
        }
        for ring in std::iter::once(&p.outer).chain(&p.holes) {
            for (i, &a) in ring.iter().enumerate() {
                let b = ring[(i + 1) % ring.len()];
                let (a0, b0) = (seen.at(a, 0.0).truncate(), seen.at(b, 0.0).truncate());
                let (a1, b1) = (seen.at(a, t).truncate(), seen.at(b, t).truncate());
                pieces.push(Polygon::new(vec![a0, b0, b1, a1]));
            }
        }
    }
    for p in &mut pieces {
        p.normalize_orientation();
    }
    pieces.retain(|p| p.area() > 1e-9);
    boolean::union_all(&pieces)
}

/// `polygon` with every point mapped by `f`.
pub(crate) fn mapped(polygon: &Polygon, f: impl Fn(DVec2) -> DVec2) -> Polygon {
    Polygon {
        outer: polygon.outer.iter().map(|&p| f(p)).collect(),
        holes: polygon
            .holes
            .iter()
            .map(|h| h.iter().map(|&p| f(p)).collect())
            .collect(),
    }
}

/// The part of the outline where some depth `0..t` of the plate lies within `z0..z1`.
fn clip_to_heights(polygon: &Polygon, seen: &Seen, t: f64, z0: f64, z1: f64) -> Result<Vec<Polygon>, GridError> {
    // Height at depth 0 is linear in the outline's point: origin.z + g · p.
    let g = DVec2::new(seen.u.z, seen.v.z);
    let (dz_lo, dz_hi) = ((seen.n.z * t).min(0.0), (seen.n.z * t).max(0.0));
    let (lo, hi) = (z0 - dz_hi - seen.origin.z, z1 - dz_lo - seen.origin.z);
    let len = g.length();
    if len < 1e-9 {
        // Parallel to the layers: all of it or nothing (the caller checked the heights).
        return Ok(vec![polygon.clone()]);
    }
    let (along, across) = (g / len, g.perp() / len);
    let (bmin, bmax) = polygon.bounds();
    let reach = bmin.length().max(bmax.length()) + 1.0;
    let (a, b) = (lo / len, hi / len);
    let strip = Polygon::new(vec![
        along * a - across * reach,
        along * b - across * reach,
        along * b + across * reach,
        along * a + across * reach,
    ]);
    let mut strip = strip;
    strip.normalize_orientation();
    boolean::intersection(std::slice::from_ref(polygon), std::slice::from_ref(&strip))
}

#[cfg(test)]
mod tests {
    use super::*;
    use platener_geom::polygon::total_area;

    fn square(w: f64, h: f64) -> Polygon {
        Polygon::new(vec![
            DVec2::ZERO,
            DVec2::new(w, 0.0),
            DVec2::new(w, h),
            DVec2::new(0.0, h),
        ])
    }

    /// The stack frame: z up, origin at 0.
    fn stack() -> Frame {
        Frame {
            origin: DVec3::ZERO,
            u: DVec3::X,
            v: DVec3::Y,
            n: DVec3::Z,
        }
    }

    #[test]
    fn a_wall_across_the_layers_covers_its_section() {
        // A wall 40 long (x), 30 tall (z), 3 thick (y from 10 to 13).
        let polygon = square(40.0, 30.0);
        let frame = Frame {
            origin: DVec3::new(0.0, 13.0, 0.0),
            u: DVec3::X,
            v: DVec3::Z,
            n: DVec3::NEG_Y,
        };
        let slab = Slab {
            polygon: &polygon,
            frame: &frame,
            thickness: 3.0,
        };
        let f = footprint(&slab, &stack(), 6.0, 9.0).unwrap();
        assert!((total_area(&f) - 120.0).abs() < 1e-3, "{}", total_area(&f));
        let (lo, hi) = f[0].bounds();
        assert!(lo.abs_diff_eq(DVec2::new(0.0, 10.0), 1e-6) && hi.abs_diff_eq(DVec2::new(40.0, 13.0), 1e-6));
        assert!(footprint(&slab, &stack(), 30.0, 33.0).unwrap().is_empty());
    }

    #[test]
    fn a_plate_parallel_to_the_layers_covers_its_outline_where_it_reaches_into_the_slab() {
        let polygon = square(20.0, 10.0);
        let frame = Frame {
            origin: DVec3::new(5.0, 5.0, -3.0),
            ..stack()
        };
        let slab = Slab {
            polygon: &polygon,
            frame: &frame,
            thickness: 3.0,
        };
        // Touching the layer above at z = 0 is not reaching into it.
        assert!(footprint(&slab, &stack(), 0.0, 3.0).unwrap().is_empty());
        let f = footprint(&slab, &stack(), -1.0, 2.0).unwrap();
        assert!((total_area(&f) - 200.0).abs() < 1e-3);
    }

    #[test]
    fn a_tilted_plate_covers_at_least_its_true_section() {
        // A plate at 45° through the slab 0..3: its section is a band 3 + 3·√2 wide (plane
        // through the thickness), 10 long.
        let polygon = square(10.0, 40.0);
        let s = std::f64::consts::FRAC_1_SQRT_2;
        let frame = Frame {
            origin: DVec3::new(0.0, -10.0, -10.0),
            u: DVec3::X,
            v: DVec3::new(0.0, s, s),
            n: DVec3::new(0.0, s, -s),
        };
        let slab = Slab {
            polygon: &polygon,
            frame: &frame,
            thickness: 3.0,
        };
        let f = footprint(&slab, &stack(), 0.0, 3.0).unwrap();
        let (lo, hi) = f[0].bounds();
        // The mid-plane z = 0..3 meets the top face (depth 0) at y = z − 0 … and the bottom
        // face shifted by 3·√2 along y: the band spans y from 0 to 3 + 3√2.
        assert!(lo.y <= 1e-6 && hi.y >= 3.0 + 3.0 * 2f64.sqrt() - 1e-6, "{lo} {hi}");
        assert!((hi.x - lo.x - 10.0).abs() < 1e-6);
    }
}
