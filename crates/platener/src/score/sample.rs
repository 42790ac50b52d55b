//! Seeded sampling: points on the model's surface and inside the parts.
//!
//! The score estimates shares (of surface, of volume) by counting sample points, so two runs
//! with the same seed give the same score to the last bit. The generator is SplitMix64
//! (Steele, Lea and Flood, "Fast splittable pseudorandom number generators", OOPSLA 2014): tiny,
//! fast, and good enough for stratified sampling; it is no cryptographic generator.

use glam::{DVec2, DVec3};

use crate::assembly::Prism;

/// SplitMix64: a seeded stream of 64-bit numbers.
#[derive(Debug, Clone)]
pub(crate) struct Rng(u64);

impl Rng {
    /// A stream for `seed`; the same seed gives the same stream.
    pub(crate) fn new(seed: u64) -> Self {
        Self(seed)
    }

    fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// A number in [0, 1) with 53 random bits.
    pub(crate) fn unit(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// `n` stratified picks over items with the given weights: pick `k` falls at cumulative weight
/// `(k + u)/n` of the total, so every item gets its share of picks to within one. Returns
/// the item index of each pick, ascending; empty when the total weight is not positive.
pub(crate) fn stratified(weights: &[f64], n: usize, rng: &mut Rng) -> Vec<usize> {
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
pub(crate) fn in_triangle(a: DVec3, b: DVec3, c: DVec3, rng: &mut Rng) -> DVec3 {
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
pub(crate) fn in_prism(prism: &Prism, rng: &mut Rng) -> Option<DVec3> {
    let (lo, hi) = prism.outline_bounds();
    for _ in 0..OUTLINE_TRIES {
        let p = DVec2::new(lo.x + (hi.x - lo.x) * rng.unit(), lo.y + (hi.y - lo.y) * rng.unit());
        let z = prism.thickness * rng.unit();
        if prism.contains_2d(p) {
            return Some(prism.frame.to_model(DVec3::new(p.x, p.y, z)));
        }
    }
    None
}
