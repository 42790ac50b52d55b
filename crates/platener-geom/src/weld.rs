//! Welding: merging points closer than a distance, for any 2D or 3D point set.
//!
//! Near-linear and deterministic: points are visited in input order and joined to the nearest
//! existing cluster *leader* closer than the distance (found through a spatial hash whose
//! cells are twice the distance wide, so at most 2^D cells are probed), or start a new
//! cluster. Leaders are never chained, so a cluster is at most twice the distance across:
//! a finely tessellated curve is coarsened, never collapsed into one point. Each cluster
//! becomes the weighted mean of its members. Because means can drift closer than the
//! distance, rounds repeat until none merges (so welding twice changes nothing).

use std::collections::HashMap;
use std::hash::{BuildHasherDefault, Hasher};

/// Rounds of re-welding at most; real meshes settle in two or three.
const MAX_ROUNDS: usize = 16;

/// Result of welding `n` points into `m` clusters.
#[derive(Debug, Clone, PartialEq)]
pub struct Welded<const D: usize> {
    /// One point per cluster (weighted mean of its members).
    pub points: Vec<[f64; D]>,
    /// Summed weight of each cluster.
    pub weights: Vec<f64>,
    /// For each input point, the index of its cluster.
    pub map: Vec<u32>,
}

/// A fast, deterministic hasher for integer and float-bit keys (multiply-rotate, with a
/// splitmix64 finaliser: coordinates read from f32 have ~29 trailing zero bits, and without
/// mixing the high bits down every key would land in the same hash bucket).
#[derive(Default, Clone, Copy)]
pub struct CellHasher(u64);

impl Hasher for CellHasher {
    fn finish(&self) -> u64 {
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    }
    fn write(&mut self, bytes: &[u8]) {
        // Slices of integers arrive here as one byte string: take them 8 bytes at a time.
        let mut chunks = bytes.chunks_exact(8);
        for c in &mut chunks {
            let mut word = [0u8; 8];
            word.copy_from_slice(c);
            self.write_u64(u64::from_le_bytes(word));
        }
        let rest = chunks.remainder();
        if !rest.is_empty() {
            let mut word = [0u8; 8];
            word[..rest.len()].copy_from_slice(rest);
            self.write_u64(u64::from_le_bytes(word));
        }
    }
    fn write_usize(&mut self, i: usize) {
        self.write_u64(i as u64);
    }
    fn write_u32(&mut self, i: u32) {
        self.write_u64(u64::from(i));
    }
    fn write_u64(&mut self, i: u64) {
        self.0 = (self.0.rotate_left(5) ^ i).wrapping_mul(0x51_7c_c1_b7_27_22_0a_95);
    }
    fn write_i64(&mut self, i: i64) {
        self.write_u64(i as u64);
    }
}

/// A `HashMap` with [`CellHasher`] (iteration order is never relied upon for output).
pub type CellMap<K, V> = HashMap<K, V, BuildHasherDefault<CellHasher>>;

/// Merges exactly equal points (bitwise, with -0.0 == 0.0). Returns the unique points in
/// first-seen order, how many inputs each stands for, and each input's unique index.
pub fn dedup_exact<const D: usize>(points: &[[f64; D]]) -> (Vec<[f64; D]>, Vec<f64>, Vec<u32>) {
    let keys: Vec<[u64; D]> = points.iter().map(|p| p.map(|c| (c + 0.0).to_bits())).collect();
    let (map, firsts) = crate::dedup::number_distinct(&keys);
    let unique = firsts.iter().map(|&i| points[i as usize]).collect();
    let mut counts = vec![0.0; firsts.len()];
    for &m in &map {
        counts[m as usize] += 1.0;
    }
    (unique, counts, map)
}

fn cell_of<const D: usize>(p: &[f64; D], inv_cell: f64) -> [i64; D] {
    p.map(|c| (c * inv_cell).floor() as i64)
}

fn dist2<const D: usize>(a: &[f64; D], b: &[f64; D]) -> f64 {
    (0..D).map(|i| (a[i] - b[i]) * (a[i] - b[i])).sum()
}

/// One round of leader clustering; `None` when nothing merged.
fn cluster_round<const D: usize>(points: &[[f64; D]], weights: &[f64], distance: f64) -> Option<Welded<D>> {
    let inv_cell = 1.0 / (2.0 * distance);
    let d2 = distance * distance;
    // Each cell holds the newest leader in it; `next` chains to the older ones (no list
    // allocated per cell: with a small distance nearly every point is a cell of its own).
    let mut grid: CellMap<[i64; D], u32> = CellMap::default();
    grid.reserve(points.len());
    let mut next: Vec<u32> = Vec::new();
    let mut leaders: Vec<[f64; D]> = Vec::new();
    let mut map = Vec::with_capacity(points.len());
    for p in points {
        let lo = cell_of(&p.map(|c| c - distance), inv_cell);
        let hi = cell_of(&p.map(|c| c + distance), inv_cell);
        let mut best: Option<(f64, u32)> = None;
        // Probe every cell of the box [lo, hi] (at most 2 per axis).
        for combo in 0..(1usize << D) {
            let mut key = lo;
            let mut valid = true;
            for (axis, k) in key.iter_mut().enumerate() {
                if combo >> axis & 1 == 1 {
                    if hi[axis] == lo[axis] {
                        valid = false;
                        break;
                    }
                    *k = hi[axis];
                }
            }
            if !valid {
                continue;
            }
            let mut l = grid.get(&key).copied().unwrap_or(u32::MAX);
            while l != u32::MAX {
                let dd = dist2(p, &leaders[l as usize]);
                if dd < d2 && best.is_none_or(|(bd, bl)| dd < bd || (dd == bd && l < bl)) {
                    best = Some((dd, l));
                }
                l = next[l as usize];
            }
        }
        let id = match best {
            Some((_, l)) => l,
            None => {
                leaders.push(*p);
                let id = (leaders.len() - 1) as u32;
                let head = grid.entry(cell_of(p, inv_cell)).or_insert(u32::MAX);
                next.push(*head);
                *head = id;
                id
            }
        };
        map.push(id);
    }
    if leaders.len() == points.len() {
        return None;
    }
    Some(means(points, weights, &leaders, map))
}

/// Welds `points` (with per-point `weights`, e.g. how many mesh corners each stands for) so
/// that no two results are closer than `distance`. `distance <= 0` merges exact duplicates
/// only.
pub fn weld<const D: usize>(points: &[[f64; D]], weights: &[f64], distance: f64) -> Welded<D> {
    debug_assert_eq!(points.len(), weights.len());
    let (mut current, mut cur_weights, mut map) = dedup_exact(points);
    // Exact duplicates add their weights.
    let mut w = vec![0.0; current.len()];
    for (i, &m) in map.iter().enumerate() {
        w[m as usize] += weights.get(i).copied().unwrap_or(1.0);
    }
    cur_weights.copy_from_slice(&w);
    if distance > 0.0 && distance.is_finite() {
        for _ in 0..MAX_ROUNDS {
            let Some(round) = cluster_round(&current, &cur_weights, distance) else {
                break;
            };
            for m in &mut map {
                *m = round.map[*m as usize];
            }
            current = round.points;
            cur_weights = round.weights;
        }
    }
    Welded {
        points: current,
        weights: cur_weights,
        map,
    }
}

/// One round of leader clustering where a point may only join the cluster of a neighbour
/// (through `adjacency`, CSR: `offsets`, `targets`) whose leader is closer than `distance`.
fn connected_round<const D: usize>(
    points: &[[f64; D]],
    weights: &[f64],
    distance: f64,
    offsets: &[u32],
    targets: &[u32],
) -> Option<Welded<D>> {
    let d2 = distance * distance;
    let mut cluster = vec![u32::MAX; points.len()];
    let mut leaders: Vec<[f64; D]> = Vec::new();
    for (i, p) in points.iter().enumerate() {
        let mut best: Option<(f64, u32)> = None;
        for &j in &targets[offsets[i] as usize..offsets[i + 1] as usize] {
            let c = cluster[j as usize];
            if c == u32::MAX {
                continue;
            }
            let dd = dist2(p, &leaders[c as usize]);
            if dd < d2 && best.is_none_or(|(bd, bc)| dd < bd || (dd == bd && c < bc)) {
                best = Some((dd, c));
            }
        }
        cluster[i] = match best {
            Some((_, c)) => c,
            None => {
                leaders.push(*p);
                (leaders.len() - 1) as u32
            }
        };
    }
    (leaders.len() < points.len()).then(|| means(points, weights, &leaders, cluster))
}

/// Each cluster's weighted mean, summed relative to its leader: keeps precision far from the
/// origin.
fn means<const D: usize>(points: &[[f64; D]], weights: &[f64], leaders: &[[f64; D]], map: Vec<u32>) -> Welded<D> {
    let mut sums = vec![[0.0; D]; leaders.len()];
    let mut wsum = vec![0.0; leaders.len()];
    for ((p, w), &c) in points.iter().zip(weights).zip(&map) {
        let c = c as usize;
        for i in 0..D {
            sums[c][i] += (p[i] - leaders[c][i]) * w;
        }
        wsum[c] += w;
    }
    let points = leaders
        .iter()
        .zip(&sums)
        .zip(&wsum)
        .map(|((l, s), w)| std::array::from_fn(|i| if *w > 0.0 { l[i] + s[i] / w } else { l[i] }))
        .collect();
    Welded {
        points,
        weights: wsum,
        map,
    }
}

/// Adjacency (both directions) of `n` points in CSR form, by counting: no sort needed, since
/// the clustering picks the nearest neighbour whatever the order (ties by cluster index).
fn adjacency(n: usize, edges: &[[u32; 2]]) -> (Vec<u32>, Vec<u32>) {
    let mut offsets = vec![0u32; n + 1];
    for e in edges {
        offsets[e[0] as usize + 1] += 1;
        offsets[e[1] as usize + 1] += 1;
    }
    for i in 0..n {
        offsets[i + 1] += offsets[i];
    }
    let mut fill = offsets.clone();
    let mut targets = vec![0u32; offsets[n] as usize];
    for e in edges {
        for (a, b) in [(e[0], e[1]), (e[1], e[0])] {
            targets[fill[a as usize] as usize] = b;
            fill[a as usize] += 1;
        }
    }
    (offsets, targets)
}

/// Welds like [`weld`], but a point only joins a cluster it is connected to by one of `edges`
/// (pairs of point indices, e.g. a mesh's edges). Two faces of a thin wall, or the far sides
/// of a small hole, are near but not connected, so they never fuse; a bevel's two sides are
/// connected by its cross edges, so it collapses. Rounds repeat (edges follow the clusters)
/// until no connected pair is closer than `distance`, so welding twice changes nothing.
pub fn weld_connected<const D: usize>(
    points: &[[f64; D]],
    weights: &[f64],
    distance: f64,
    edges: &[[u32; 2]],
) -> Welded<D> {
    let mut current = Welded {
        points: points.to_vec(),
        weights: weights.to_vec(),
        map: (0..points.len() as u32).collect(),
    };
    if !(distance > 0.0 && distance.is_finite()) {
        return current;
    }
    let mut edges: Vec<[u32; 2]> = edges.iter().filter(|e| e[0] != e[1]).copied().collect();
    for _ in 0..MAX_ROUNDS {
        let (offsets, targets) = adjacency(current.points.len(), &edges);
        let Some(round) = connected_round(&current.points, &current.weights, distance, &offsets, &targets) else {
            break;
        };
        for m in &mut current.map {
            *m = round.map[*m as usize];
        }
        // Edges inside a cluster are gone; the rest follow their ends.
        edges = edges
            .iter()
            .map(|e| [round.map[e[0] as usize], round.map[e[1] as usize]])
            .filter(|e| e[0] != e[1])
            .collect();
        current.points = round.points;
        current.weights = round.weights;
    }
    current
}

#[cfg(test)]
mod tests;
