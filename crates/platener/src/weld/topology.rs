//! Counting a triangle list's edges and its Euler characteristic, by one parallel sort.

use rayon::slice::ParallelSliceMut;

/// Edge statistics of an indexed triangle list.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct EdgeCounts {
    /// Edges used by one triangle.
    pub open: usize,
    /// Edges used by three or more.
    pub non_manifold: usize,
    /// V − E + F over the vertices triangles use: 2 per closed sphere-like body, 2 less for
    /// every hole through a plate (handle).
    pub euler: i64,
}

/// Counts edges of `triangles` (whose vertex indices are below `vertex_count`), skipping
/// triangles with a repeated corner.
pub fn edge_counts(triangles: &[[u32; 3]], vertex_count: usize) -> EdgeCounts {
    let mut keys: Vec<u64> = Vec::with_capacity(triangles.len() * 3);
    let mut used = vec![false; vertex_count];
    let mut faces = 0i64;
    for t in triangles {
        if t[0] == t[1] || t[1] == t[2] || t[0] == t[2] {
            continue;
        }
        faces += 1;
        for i in 0..3 {
            let (a, b) = (t[i], t[(i + 1) % 3]);
            used[a as usize] = true;
            keys.push((u64::from(a.min(b)) << 32) | u64::from(a.max(b)));
        }
    }
    keys.par_sort_unstable();
    let (mut open, mut non_manifold, mut edges) = (0, 0, 0i64);
    for run in keys.chunk_by(|a, b| a == b) {
        edges += 1;
        match run.len() {
            1 => open += 1,
            2 => {}
            _ => non_manifold += 1,
        }
    }
    let vertices = used.iter().filter(|&&u| u).count() as i64;
    EdgeCounts {
        open,
        non_manifold,
        euler: vertices - edges + faces,
    }
}
