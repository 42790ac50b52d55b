//! Closing corners that plate finding left open.
//!
//! Where two walls meet through a rounded or chamfered corner (too curved or too narrow to be
//! a plate of its own), each wall's plate ends where its flat face ends, short of the other
//! wall: an enclosure with 5 mm corner radii got walls 9 mm short of each other and no joint.
//! A plate that ends short of a non-parallel plate grows in its plane up to that plate's near
//! face, when the gap is short, the other plate runs along the same line, the model is solid
//! all the way (a real opening stays open) and the growth meets no third plate. The joint
//! step then finds a corner (or a T) there as in any box.

use glam::{DVec2, DVec3};
use platener_geom::boolean::{difference, union_all};
use platener_geom::{GridError, Polygon};

use super::Plate;
use crate::assembly::Inside;

/// Plates closer to parallel than this (degrees between their normals) are not corners to
/// close: facets of a faceted curve meet at shallow angles and already touch, and near a
/// low-poly ball's poles a facet would grow towards one it meets only at a vertex.
const MIN_ANGLE_DEG: f64 = 60.0;
/// The shortest stretch along the corner line worth closing, in sheet thicknesses.
const MIN_STRETCH: f64 = 2.0;
/// The longest gap closed, in sheet thicknesses (the thicker of the two plates).
const MAX_GAP: f64 = 4.0;
/// Gaps shorter than this (mm) are left to the joint step, which reaches across them.
const MIN_GAP: f64 = 0.01;
/// Growth overlaps the plate by this much (mm) so the union is one piece on the grid.
const SEAM: f64 = 0.01;

/// Where plate `b`'s slab lies as seen in plate `a`'s plane: `level(q)` is b's local z at
/// a's mid-plane point `q`, an affine function `c + g·q`.
struct Across {
    c: f64,
    g: DVec2,
}

impl Across {
    fn new(a: &Plate, b: &Plate) -> Self {
        let z = |q: DVec2| {
            b.frame
                .to_local(a.frame.to_model(DVec3::new(q.x, q.y, a.thickness / 2.0)))
                .z
        };
        let c = z(DVec2::ZERO);
        Self {
            c,
            g: DVec2::new(z(DVec2::X) - c, z(DVec2::Y) - c),
        }
    }
    fn level(&self, q: DVec2) -> f64 {
        self.c + self.g.dot(q)
    }
}

/// The strips `a` would add to reach `b`'s near face, if a ends short of b across a closable
/// gap along a line where b also runs, where the model is solid across the gap.
fn growth(a: &Plate, b: &Plate, inside: &Inside) -> Option<Vec<Polygon>> {
    let across = Across::new(a, b);
    let slope = across.g.length();
    if slope < MIN_ANGLE_DEG.to_radians().sin() {
        return None;
    }
    let (dir, along) = (across.g / slope, DVec2::new(-across.g.y, across.g.x) / slope);
    let levels: Vec<f64> = a.polygon.outer.iter().map(|&q| across.level(q)).collect();
    let (lo, hi) = levels
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |m, &z| (m.0.min(z), m.1.max(z)));
    // Distances in a's plane (along `dir`) from b's near face to a's nearest corner.
    let (face, near, sign) = if lo > b.thickness {
        (b.thickness, lo, 1.0)
    } else if hi < 0.0 {
        (0.0, hi, -1.0)
    } else {
        return None;
    };
    let gap = sign * (near - face) / slope;
    let max_gap = MAX_GAP * a.thickness.max(b.thickness);
    if !(MIN_GAP..=max_gap).contains(&gap) {
        return None;
    }
    // a's end: its corners within the closable gap of b's face (an end wall's body and the
    // lip above it may end at different distances); the strip reaches the farthest of them.
    let end: Vec<(DVec2, f64)> = a
        .polygon
        .outer
        .iter()
        .zip(&levels)
        .filter(|(_, z)| sign * (**z - face) / slope <= max_gap)
        .map(|(q, z)| (*q, *z))
        .collect();
    let (a0, a1) = span(end.iter().map(|(q, _)| q.dot(along)));
    let far = end.iter().map(|(_, z)| sign * z).fold(f64::NEG_INFINITY, f64::max) * sign;
    // b must run along the same stretch and come up to a's plane.
    let b_in_a: Vec<DVec2> = b
        .polygon
        .outer
        .iter()
        .map(|&q| a.frame.to_2d(b.frame.to_model_2d(q)))
        .collect();
    let (b0, b1) = span(b_in_a.iter().map(|q| q.dot(along)));
    let (s0, s1) = (a0.max(b0), a1.min(b1));
    if s1 - s0 < MIN_STRETCH * a.thickness || !comes_up_to(a, b, gap) {
        return None;
    }
    // Position along `dir` where a level is reached: level = c + slope·w (w along dir).
    let at = |level: f64| (level - across.c) / slope;
    let (w0, w1) = (at(face), at(far) + sign * SEAM);
    let corner = |s: f64, w: f64| along * s + dir * w;
    let solid = solid_runs(a, inside, (s0, s1), (w0, w1), &corner);
    let strips: Vec<Polygon> = solid
        .into_iter()
        .map(|(s0, s1)| {
            let mut p = Polygon::new(vec![corner(s0, w0), corner(s1, w0), corner(s1, w1), corner(s0, w1)]);
            p.normalize_orientation();
            p
        })
        .collect();
    (!strips.is_empty()).then_some(strips)
}

/// The stretches of `s` (along the corner line) over which the model is solid across the
/// whole gap somewhere through a's thickness, tested in bands half a sheet long: a rounded corner is solid, a
/// connector opening beside the corner is not, and the plate grows only beside it.
fn solid_runs(
    a: &Plate,
    inside: &Inside,
    (s0, s1): (f64, f64),
    (w0, w1): (f64, f64),
    corner: &dyn Fn(f64, f64) -> DVec2,
) -> Vec<(f64, f64)> {
    let bands = ((s1 - s0) / (a.thickness / 2.0)).ceil().max(1.0) as usize;
    let len = (s1 - s0) / bands as f64;
    let solid = |k: usize| {
        (0..2).all(|i| {
            (0..5).all(|j| {
                let s = s0 + len * (k as f64 + 0.25 + 0.5 * i as f64);
                let q = corner(s, w0 + (w1 - w0) * (0.1 + 0.2 * j as f64));
                // Through the sheet, not only at its mid-plane: a corner rounded by more
                // than the sheet is thick leaves the outer face's corner outside the model.
                [0.05, 0.5, 0.95]
                    .iter()
                    .any(|f| inside.contains(a.frame.to_model(DVec3::new(q.x, q.y, a.thickness * f))))
            })
        })
    };
    let mut runs: Vec<(f64, f64)> = Vec::new();
    for k in (0..bands).filter(|&k| solid(k)) {
        let (lo, hi) = (s0 + len * k as f64, s0 + len * (k + 1) as f64);
        match runs.last_mut() {
            Some(last) if (last.1 - lo).abs() < 1e-9 => last.1 = hi,
            _ => runs.push((lo, hi)),
        }
    }
    runs
}

/// Whether `b` reaches within the closable gap of `a`'s slab (b ends near a, or passes it).
fn comes_up_to(a: &Plate, b: &Plate, gap: f64) -> bool {
    let across = Across::new(b, a);
    let slope = across.g.length();
    let reach = gap + MAX_GAP * a.thickness.max(b.thickness);
    b.polygon.outer.iter().any(|&q| {
        let z = across.level(q);
        let outside = (-z).max(z - a.thickness).max(0.0);
        outside / slope <= reach
    })
}

/// The smallest and largest of some numbers.
fn span(values: impl Iterator<Item = f64>) -> (f64, f64) {
    values.fold((f64::INFINITY, f64::NEG_INFINITY), |m, v| (m.0.min(v), m.1.max(v)))
}

/// Grows plates across short gaps to the plates they meet in the model; returns how many
/// grew. Pairs are taken in index order and each growth is seen by the next, so the result
/// does not depend on anything but the plates' order.
pub(super) fn close(plates: &mut [Plate], inside: &Inside, clearance: f64) -> Result<usize, GridError> {
    let mut grown = 0;
    for i in 0..plates.len() {
        for j in 0..plates.len() {
            if i == j {
                continue;
            }
            let Some(strips) = growth(&plates[i], &plates[j], inside) else {
                continue;
            };
            let mut strip = free_of_others(plates, i, j, strips, clearance)?;
            strip.retain(|s| s.area() > 1e-6);
            if strip.is_empty() {
                continue;
            }
            strip.push(plates[i].polygon.clone());
            let mut joined = union_all(&strip)?;
            if joined.len() != 1 {
                continue;
            }
            let p = joined.pop().expect("one piece");
            plates[i].area = p.area();
            plates[i].polygon = p;
            grown += 1;
        }
    }
    Ok(grown)
}

/// `strips` (in plate `i`'s plane) less the columns where it would share volume with a plate
/// other than `j` (a floor the walls stand on).
fn free_of_others(
    plates: &[Plate],
    i: usize,
    j: usize,
    strips: Vec<Polygon>,
    clearance: f64,
) -> Result<Vec<Polygon>, GridError> {
    let mut free = strips;
    for (k, other) in plates.iter().enumerate() {
        if k == i || k == j {
            continue;
        }
        for strip in free.clone() {
            let claimed = plates[i].slab_of(strip).columns_meeting(&other.slab(), clearance)?;
            if claimed.iter().any(|p| p.area() > 1e-6) {
                free = difference(&free, &claimed)?;
            }
        }
    }
    Ok(free)
}
