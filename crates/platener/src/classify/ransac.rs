//! Efficient RANSAC (Schnabel, Wahl and Klein 2007), written from the paper's description.
//!
//! Each draw takes a random live sample and two more from one octree cell round it
//! (localized sampling: points of one surface lie together, so draws from a cell hit one
//! surface far more often than draws from the whole model); the octree level is chosen with
//! probabilities that follow the scores each level has produced. Every draw proposes a
//! plane, cylinder, sphere and cone through its points, kept when all of the draw's points
//! agree with it. Candidates are scored on a fixed random subset of the live samples; the
//! best is extracted once the paper's probability that no better one was missed exceeds
//! [`CONFIDENCE`]: its inliers are collected, cut to their largest connected piece,
//! refitted by least squares and collected again, then removed from the live samples.

use glam::DVec3;
use platener_geom::rng::SplitMix64;
use rayon::prelude::*;

use super::bitmap::largest_component;
use super::fit::{refit, simplest};
use super::sample::Sample;
use super::surface::{Oriented, Prepared, Surface, cone_from, cylinder_from, plane_from, sphere_from};
use super::{Primitive, Thresholds};

/// The probability (the paper's p_t) that no shape larger than the extracted one, nor any
/// of at least the minimum size after the last, was missed.
pub const CONFIDENCE: f64 = 0.99;
/// Samples the candidate scores are estimated on.
const SUBSET: usize = 1000;
/// Draws between two looks at the best candidate (scored in parallel).
const BATCH: usize = 256;
/// Most candidates whose connected inliers are counted before one is extracted.
const CHECKED: usize = 16;
/// Bits per axis of the octree's Morton codes.
const BITS: u32 = 10;

/// A candidate and its estimated inlier count.
#[derive(Debug, Clone, Copy)]
struct Candidate {
    shape: Surface,
    /// The estimated inlier count, or once checked the connected inliers counted
    /// ([`Search::best_connected`]): an upper bound either way, as samples only die.
    estimate: f64,
    level: usize,
}

/// Samples sorted along the Morton curve: the samples of an octree cell are a contiguous
/// run of `order`.
struct Octree {
    codes: Vec<u64>,
    order: Vec<u32>,
    code_of: Vec<u64>,
    levels: usize,
}

impl Octree {
    fn new(samples: &[Sample], levels: usize) -> Self {
        let (lo, hi) = platener_geom::boxes::bounds3(samples.iter().map(|s| s.at.p));
        let size = (hi - lo).max_element().max(1e-9);
        let scale = ((1u64 << BITS) - 1) as f64 / size;
        let code_of: Vec<u64> = samples.iter().map(|s| morton((s.at.p - lo) * scale)).collect();
        let mut order: Vec<u32> = (0..samples.len() as u32).collect();
        order.sort_by_key(|&i| (code_of[i as usize], i));
        let codes = order.iter().map(|&i| code_of[i as usize]).collect();
        Self {
            codes,
            order,
            code_of,
            levels: levels.clamp(1, BITS as usize),
        }
    }

    /// The run of `order` in the cell of sample `i` at `level` (1 = the root's children).
    fn cell(&self, i: u32, level: usize) -> &[u32] {
        let shift = 3 * (BITS as usize - level);
        let prefix = self.code_of[i as usize] >> shift;
        let a = self.codes.partition_point(|&c| (c >> shift) < prefix);
        let b = self.codes.partition_point(|&c| (c >> shift) <= prefix);
        &self.order[a..b]
    }
}

/// Interleaves the bits of three coordinates in [0, 2^BITS).
fn morton(q: DVec3) -> u64 {
    let spread = |v: f64| {
        let mut x = (v.max(0.0) as u64).min((1 << BITS) - 1);
        let mut out = 0u64;
        for b in 0..BITS {
            out |= (x & 1) << (3 * b);
            x >>= 1;
        }
        out
    };
    spread(q.x) | (spread(q.y) << 1) | (spread(q.z) << 2)
}

/// The index of the candidate with the highest estimate (the first of equals).
fn best_of(pool: &[Candidate]) -> Option<usize> {
    (0..pool.len()).reduce(|b, i| if pool[i].estimate > pool[b].estimate { i } else { b })
}

/// The RANSAC state between extractions.
struct Search<'a> {
    samples: &'a [Sample],
    th: &'a Thresholds,
    octree: Octree,
    alive: Vec<bool>,
    live: Vec<u32>,
    subset: Vec<u32>,
    shuffled: Vec<u32>,
    level_score: Vec<f64>,
    rng: SplitMix64,
    /// Shapes whose connected inliers were too few (as drawn and refitted to them): samples
    /// only die, so they never grow, and new candidates like them are not scored again. A
    /// model of many coplanar islands (chips, tiles) otherwise proposes its plane in every
    /// batch and checks it at the cost of a full inlier search each time.
    rejected: Vec<Surface>,
}

/// Detects primitives among `samples`, largest first; each keeps its inliers (sample
/// indices, ascending).
pub fn detect(samples: &[Sample], th: &Thresholds, seed: u64) -> Vec<Primitive> {
    if samples.len() < th.min_points.max(3) {
        return Vec::new();
    }
    let mut rng = SplitMix64::new(seed);
    let mut shuffled: Vec<u32> = (0..samples.len() as u32).collect();
    for i in (1..shuffled.len()).rev() {
        shuffled.swap(i, (rng.next_u64() % (i as u64 + 1)) as usize);
    }
    let mut s = Search {
        samples,
        th,
        octree: Octree::new(samples, th.octree_levels),
        alive: vec![true; samples.len()],
        live: Vec::new(),
        subset: Vec::new(),
        shuffled,
        level_score: vec![1.0; th.octree_levels.clamp(1, BITS as usize)],
        rng,
        rejected: Vec::new(),
    };
    s.refresh();
    let mut found = Vec::new();
    while let Some(p) = s.next_primitive() {
        found.push(p);
    }
    found
}

impl Search<'_> {
    /// Rebuilds the live list and the scoring subset after samples were removed.
    fn refresh(&mut self) {
        self.live = (0..self.samples.len() as u32)
            .filter(|&i| self.alive[i as usize])
            .collect();
        self.subset = self
            .shuffled
            .iter()
            .copied()
            .filter(|&i| self.alive[i as usize])
            .take(SUBSET)
            .collect();
    }

    /// The paper's probability that a shape of `n` of the `live` samples was drawn at
    /// least once in `draws` localized draws of three points.
    fn found_probability(&self, n: f64, draws: usize) -> f64 {
        let per = (n / (self.live.len() as f64 * self.octree.levels as f64 * 4.0)).min(1.0);
        1.0 - (1.0 - per).powf(draws as f64)
    }

    /// Draws until the best candidate is certain enough, extracts it; `None` when no shape
    /// of the minimum size is left (with [`CONFIDENCE`]).
    fn next_primitive(&mut self) -> Option<Primitive> {
        let mut pool: Vec<Candidate> = Vec::new();
        let mut draws = 0usize;
        loop {
            if self.live.len() < self.th.min_points {
                return None;
            }
            let batch: Vec<([Oriented; 3], usize)> = (0..BATCH).filter_map(|_| self.draw()).collect();
            draws += BATCH;
            let scored: Vec<Candidate> = batch
                .par_iter()
                .flat_map_iter(|(q, level)| self.candidates(q, *level))
                .collect();
            for c in &scored {
                self.level_score[c.level - 1] += c.estimate;
            }
            pool.extend(scored);
            while let Some(b) = best_of(&pool) {
                if self.found_probability(pool[b].estimate, draws) < CONFIDENCE {
                    break;
                }
                let (k, inliers) = self.best_connected(&mut pool);
                let cand = pool.swap_remove(k);
                if inliers.len() < self.th.min_points {
                    self.reject(&cand.shape, &inliers);
                    let least = self.th.min_points as f64;
                    pool.retain(|c| c.estimate >= least && !self.is_rejected(&c.shape));
                    continue;
                }
                if let Some(p) = self.extract(&cand.shape, inliers) {
                    return Some(p);
                }
            }
            if self.found_probability(self.th.min_points as f64, draws) >= CONFIDENCE {
                return None;
            }
        }
    }

    /// The candidate with the most connected inliers among the leading ones, and those
    /// inliers. Estimates count every inlier, so a candidate grazing several surfaces can
    /// lead on its estimate yet hold few connected inliers; candidates are checked in order of
    /// estimate until the estimate falls below the best connected count (it bounds that count
    /// up to sampling error), at most [`CHECKED`]. Each checked candidate's estimate becomes its
    /// connected count, an upper bound from then on.
    fn best_connected(&self, pool: &mut [Candidate]) -> (usize, Vec<u32>) {
        let mut order: Vec<usize> = (0..pool.len()).collect();
        order.sort_by(|&a, &b| pool[b].estimate.total_cmp(&pool[a].estimate).then(a.cmp(&b)));
        let mut best: Option<(usize, Vec<u32>)> = None;
        for &i in order.iter().take(CHECKED) {
            if best.as_ref().is_some_and(|b| pool[i].estimate < b.1.len() as f64) {
                break;
            }
            let inliers = self.inliers(&pool[i].shape);
            pool[i].estimate = inliers.len() as f64;
            if best.as_ref().is_none_or(|b| inliers.len() > b.1.len()) {
                best = Some((i, inliers));
            }
        }
        best.unwrap_or_default()
    }

    /// One localized minimal set: a random live sample, an octree level chosen by the
    /// scores levels have produced, two more live samples from that cell.
    fn draw(&mut self) -> Option<([Oriented; 3], usize)> {
        let first = self.live[(self.rng.next_u64() % self.live.len() as u64) as usize];
        let level = self.pick_level();
        let cell = self.octree.cell(first, level);
        let mut picked = [first; 3];
        let mut got = 1;
        for _ in 0..12 {
            let j = cell[(self.rng.next_u64() % cell.len() as u64) as usize];
            if self.alive[j as usize] && !picked[..got].contains(&j) {
                picked[got] = j;
                got += 1;
                if got == 3 {
                    return Some((picked.map(|i| self.samples[i as usize].at), level));
                }
            }
        }
        None
    }

    /// A level with probability mixing the levels' accumulated scores (90 %) with uniform
    /// (10 %), so no level is ever starved.
    fn pick_level(&mut self) -> usize {
        let total: f64 = self.level_score.iter().sum();
        let k = self.level_score.len() as f64;
        let mut u = self.rng.unit();
        for (l, s) in self.level_score.iter().enumerate() {
            let p = 0.9 * s / total + 0.1 / k;
            if u < p {
                return l + 1;
            }
            u -= p;
        }
        self.level_score.len()
    }

    /// The shapes through a minimal set that all its points accept and that are not
    /// better explained by a simpler shape, with their estimated inlier counts.
    fn candidates(&self, q: &[Oriented; 3], level: usize) -> Vec<Candidate> {
        let shapes = [
            plane_from(q),
            cylinder_from(&q[0], &q[1]),
            sphere_from(&q[0], &q[1]),
            cone_from(q),
        ];
        shapes
            .into_iter()
            .flatten()
            .filter(|s| self.th.plausible(s) && q.iter().all(|o| s.accepts(o, self.th.eps, self.th.cos_alpha)))
            .filter(|s| !self.is_rejected(s))
            .map(|shape| Candidate {
                shape,
                estimate: self.estimate(&shape),
                level,
            })
            .collect()
    }

    /// Remembers `shape` and its refit to `inliers` as too small (see `rejected`).
    fn reject(&mut self, shape: &Surface, inliers: &[u32]) {
        let (pts, nrm): (Vec<DVec3>, Vec<DVec3>) = inliers
            .iter()
            .map(|&i| (self.samples[i as usize].at.p, self.samples[i as usize].at.n))
            .unzip();
        self.rejected.push(*shape);
        if let Some(r) = refit(shape, &pts, &nrm) {
            self.rejected.push(r);
        }
    }

    /// Whether `shape` is one of the rejected ones, within ε and α.
    fn is_rejected(&self, shape: &Surface) -> bool {
        let (eps, cos) = (self.th.eps, self.th.cos_alpha);
        self.rejected.iter().any(|r| r.same_as(shape, eps, cos))
    }

    /// Inliers on the subset, scaled to all live samples.
    fn estimate(&self, shape: &Surface) -> f64 {
        let shape = shape.prepared();
        let hits = self.subset.iter().filter(|&&i| self.accepts(&shape, i)).count();
        hits as f64 * self.live.len() as f64 / self.subset.len().max(1) as f64
    }

    fn accepts(&self, shape: &Prepared, i: u32) -> bool {
        shape.accepts(&self.samples[i as usize].at, self.th.eps, self.th.cos_alpha)
    }

    /// The live inliers of `shape` in their largest connected piece (ascending).
    fn inliers(&self, shape: &Surface) -> Vec<u32> {
        let prepared = shape.prepared();
        let all: Vec<u32> = self
            .live
            .par_iter()
            .copied()
            .filter(|&i| self.accepts(&prepared, i))
            .collect();
        let r = shape.reference_radius(all.iter().map(|&i| self.samples[i as usize].at.p));
        let params: Vec<_> = all
            .iter()
            .map(|&i| shape.parameters(self.samples[i as usize].at.p, r))
            .collect();
        let period = params.first().and_then(|p| p.1);
        let uv: Vec<_> = params.iter().map(|p| p.0).collect();
        largest_component(&uv, period, self.th.cell)
            .into_iter()
            .map(|k| all[k])
            .collect()
    }

    /// Refits `shape` to its connected `inliers`, collects them again, and removes them when
    /// enough remain; `None` (nothing removed) when the candidate was smaller than it looked.
    fn extract(&mut self, shape: &Surface, mut inliers: Vec<u32>) -> Option<Primitive> {
        let mut fitted = *shape;
        // Two rounds: the candidate's inliers give a close fit, whose inliers give the
        // final one (a candidate from three noisy points may be a degree off).
        for _ in 0..2 {
            if inliers.len() < self.th.min_points {
                return None;
            }
            let (pts, nrm): (Vec<DVec3>, Vec<DVec3>) = inliers
                .iter()
                .map(|&i| (self.samples[i as usize].at.p, self.samples[i as usize].at.n))
                .unzip();
            let refined = refit(&fitted, &pts, &nrm)
                .filter(|s| self.th.plausible(s))
                .unwrap_or(fitted);
            fitted = simplest(&refined, &pts, &nrm, self.th.eps);
            inliers = self.inliers(&fitted);
        }
        if inliers.len() < self.th.min_points {
            return None;
        }
        for &i in &inliers {
            self.alive[i as usize] = false;
        }
        self.refresh();
        let outward = inliers
            .iter()
            .map(|&i| {
                fitted
                    .normal_at(self.samples[i as usize].at.p)
                    .dot(self.samples[i as usize].at.n)
            })
            .sum::<f64>()
            >= 0.0;
        Some(Primitive {
            shape: fitted,
            outward,
            samples: inliers,
            triangles: Vec::new(),
            area: 0.0,
        })
    }
}
