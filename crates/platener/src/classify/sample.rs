//! Area-weighted surface samples with normals, and a grid to find a sample's neighbours.
//!
//! The thesis fed RANSAC the mesh's vertices: few on large flat faces, crowded on curved
//! ones, and a box's diagonals looked like planes. Samples spread evenly over the surface fix
//! that. A sample's normal is estimated from its neighbours (a plane through the samples
//! within a few spacings) when they lie flat within the distance tolerance, so a texture or
//! noise finer than that neighbourhood does not scatter the normals; at creases, where the
//! neighbours do not lie flat, the triangle's own normal is exact and kept.

use glam::{DMat3, DVec3};
use platener_geom::plane_fit::symmetric_eigen;
use platener_geom::rng::SplitMix64;
use rayon::prelude::*;

use super::surface::Oriented;
use crate::mesh::Mesh;

/// How a sample's normal is fitted to its neighbours (see [`with_normals`]), mm.
#[derive(Debug, Clone, Copy)]
pub struct NormalFit {
    /// Mean distance between samples.
    pub spacing: f64,
    /// Radius of the neighbourhood.
    pub radius: f64,
    /// Largest RMS distance of the neighbours from their plane for it to count as flat.
    pub flat: f64,
    /// Cosine of the normal tolerance, for triangles larger than the neighbourhood.
    pub cos_alpha: f64,
}

/// One sample of the surface.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sample {
    /// Position and estimated unit normal.
    pub at: Oriented,
    /// The mesh triangle it lies on.
    pub triangle: u32,
}

/// `count` samples spread over `mesh`'s surface in proportion to area: stratified (the k-th
/// sample falls in the k-th of `count` equal slices of the cumulative area, at a random place
/// in its slice), uniform inside its triangle. Seeded: the same seed gives the same samples.
pub fn sample_surface(mesh: &Mesh, count: usize, seed: u64) -> Vec<(DVec3, u32)> {
    let mut cum = Vec::with_capacity(mesh.areas.len());
    let mut total = 0.0;
    for a in &mesh.areas {
        total += a;
        cum.push(total);
    }
    if total <= 0.0 || count == 0 {
        return Vec::new();
    }
    let mut rng = SplitMix64::new(seed);
    (0..count)
        .map(|k| {
            let at = (k as f64 + rng.unit()) / count as f64 * total;
            let f = cum.partition_point(|&c| c <= at).min(cum.len() - 1);
            let [a, b, c] = mesh.corners(f);
            let (r1, r2) = (rng.unit().sqrt(), rng.unit());
            (a * (1.0 - r1) + b * (r1 * (1.0 - r2)) + c * (r1 * r2), f as u32)
        })
        .collect()
}

/// Samples binned into cubes of one size: finding the samples near a point looks at the 27
/// cubes round it. Bins are a sorted list (no hashing), so every walk is in a fixed order.
#[derive(Debug, Clone)]
struct PointGrid {
    cell: f64,
    /// (cell key, sample index), sorted.
    keys: Vec<(u64, u32)>,
}

impl PointGrid {
    /// Bins `points` into cubes of side `cell`.
    fn new(points: impl Iterator<Item = DVec3>, cell: f64) -> Self {
        let mut keys: Vec<(u64, u32)> = points
            .enumerate()
            .map(|(i, p)| (key(cell_of(p, cell)), i as u32))
            .collect();
        keys.par_sort_unstable();
        Self { cell, keys }
    }

    /// Calls `f` with the index of every point in the 27 cubes round `p` (a superset of the
    /// points within `cell` of `p`).
    fn near(&self, p: DVec3, mut f: impl FnMut(u32)) {
        let c = cell_of(p, self.cell);
        for dz in -1..=1 {
            for dy in -1..=1 {
                for dx in -1..=1 {
                    let k = key([c[0] + dx, c[1] + dy, c[2] + dz]);
                    let start = self.keys.partition_point(|e| e.0 < k);
                    for e in self.keys[start..].iter().take_while(|e| e.0 == k) {
                        f(e.1);
                    }
                }
            }
        }
    }
}

/// The integer cube of `p`.
pub(super) fn cell_of(p: DVec3, cell: f64) -> [i64; 3] {
    let q = (p / cell).floor();
    [q.x as i64, q.y as i64, q.z as i64]
}

/// A cube's key: 21 bits per axis (wrapping far-away cubes together only costs a few extra
/// candidates, never a missed one).
pub(super) fn key(c: [i64; 3]) -> u64 {
    let m = (1u64 << 21) - 1;
    ((c[0] as u64 & m) << 42) | ((c[1] as u64 & m) << 21) | (c[2] as u64 & m)
}

/// About this many samples are fitted for a sample's normal: a plane's normal and its RMS
/// distance are as sure from 64 evenly spread samples as from the thousand a 6 mm
/// neighbourhood holds on a small, finely sampled model, which cost 60 % of the classifier's
/// time there.
const FIT_SAMPLES: f64 = 64.0;

/// Samples with normals: each normal from a plane fitted to the samples within `radius`
/// (every k-th of them, about [`FIT_SAMPLES`]: `points` are stratified over the surface in
/// order, so every k-th is too; `spacing` is their mean distance) when their RMS distance
/// from it is at most `flat` and, for a triangle larger than the neighbourhood, it lies
/// within the normal tolerance of the triangle's (near a crease the fitted plane leans over
/// the edge), else the triangle's normal.
pub fn with_normals(mesh: &Mesh, points: &[(DVec3, u32)], fit: NormalFit) -> Vec<Sample> {
    let NormalFit {
        spacing,
        radius,
        flat,
        cos_alpha,
    } = fit;
    let within = std::f64::consts::PI * radius * radius / (spacing * spacing).max(f64::MIN_POSITIVE);
    let stride = (within / FIT_SAMPLES).floor().clamp(1.0, points.len().max(1) as f64) as usize;
    let fitted_to: Vec<DVec3> = points.iter().step_by(stride).map(|p| p.0).collect();
    let grid = PointGrid::new(fitted_to.iter().copied(), radius);
    points
        .par_iter()
        .map(|&(p, t)| {
            let tn = mesh.normals[t as usize];
            let n = local_normal(&grid, &fitted_to, p, radius, flat).map(|n| if n.dot(tn) < 0.0 { -n } else { n });
            // A triangle smaller than the neighbourhood says less about the surface than the
            // neighbourhood does (a fine textured mesh); a larger one is trusted at creases.
            let [a, b, c] = mesh.corners(t as usize);
            let small = (a - b).length().max((b - c).length()).max((c - a).length()) < radius;
            let n = n.filter(|n| small || n.dot(tn) >= cos_alpha).unwrap_or(tn);
            Sample {
                at: Oriented { p, n },
                triangle: t,
            }
        })
        .collect()
}

/// The normal of the plane fitted to the points of `grid` within `radius` of `p`, if they lie
/// flat.
fn local_normal(grid: &PointGrid, points: &[DVec3], p: DVec3, radius: f64, flat: f64) -> Option<DVec3> {
    let (mut sum, mut n) = (DVec3::ZERO, 0usize);
    let mut m = DMat3::ZERO;
    grid.near(p, |i| {
        let q = points[i as usize] - p;
        if q.length_squared() <= radius * radius {
            sum += q;
            n += 1;
            m += DMat3::from_cols(q * q.x, q * q.y, q * q.z);
        }
    });
    if n < 6 {
        return None;
    }
    let c = sum / n as f64;
    let cov = m * (1.0 / n as f64) - DMat3::from_cols(c * c.x, c * c.y, c * c.z);
    let (vals, vecs) = symmetric_eigen(cov);
    (vals[0].max(0.0).sqrt() <= flat)
        .then_some(vecs[0])
        .and_then(|v| v.try_normalize())
}
