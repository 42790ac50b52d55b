//! Seeded sampling: points on the model's surface and inside the parts.
//!
//! The score estimates shares (of surface, of volume) by counting sample points, so two runs
//! with the same seed give the same score to the last bit. The generator is the kernel's
//! [`SplitMix64`], good enough for stratified sampling.

use glam::{DVec2, DVec3};

use platener_geom::rng::SplitMix64;

use crate::assembly::Solid;

/// `n` stratified picks over items with the given weights: pick `k` falls at cumulative weight
/// `(k + u)/n` of the total, so every item gets its share of picks to within one. Returns
/// the item index of each pick, ascending; empty when the total weight is not positive.
pub(crate) fn stratified(weights: &[f64], n: usize, rng: &mut SplitMix64) -> Vec<usize> {
    let mut cumulative = Vec::with_capacity(weights.len());
    let mut total = 0.0;
    for w in weights {
        total += w.max(0.0);
        cumulative.push(total);
    }
    if !(total > 0.0 && total.is_finite()) {
        return Vec::new();
    }
    (0..n)
        .map(|k| {
            let target = (k as f64 + rng.unit()) / n as f64 * total;
            cumulative.partition_point(|c| *c <= target).min(weights.len() - 1)
        })
        .collect()
}

/// A uniformly random point of the triangle `abc`.
pub(crate) fn in_triangle(a: DVec3, b: DVec3, c: DVec3, rng: &mut SplitMix64) -> DVec3 {
    let (mut s, mut t) = (rng.unit(), rng.unit());
    if s + t > 1.0 {
        (s, t) = (1.0 - s, 1.0 - t);
    }
    a + (b - a) * s + (c - a) * t
}

/// How often a point is drawn in a part's outline box before the part is given up: a part
/// covering under 1/64 of its box (a thin diagonal strip) loses its sample, which the score
/// then simply does not count.
const OUTLINE_TRIES: usize = 64;

/// A uniformly random point inside the part's volume (outline × thickness), in model
/// coordinates; `None` when [`OUTLINE_TRIES`] draws in the outline's box all missed.
pub(crate) fn in_prism(prism: &Solid, rng: &mut SplitMix64) -> Option<DVec3> {
    let (lo, hi) = prism.slab.polygon.bounds();
    for _ in 0..OUTLINE_TRIES {
        let p = DVec2::new(lo.x + (hi.x - lo.x) * rng.unit(), lo.y + (hi.y - lo.y) * rng.unit());
        let z = prism.slab.thickness * rng.unit();
        if prism.slab.polygon.contains(p) {
            return Some(prism.slab.frame.to_model(DVec3::new(p.x, p.y, z)));
        }
    }
    None
}
