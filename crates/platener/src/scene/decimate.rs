//! Keeping large models viewable: vertex clustering on a grid (Rossignac & Borrel, "Multi-
//! resolution 3D approximations for rendering complex scenes", 1993).
//!
//! A browser chokes on millions of triangles, and a view only has to show the shape. Above
//! [`TRIANGLE_LIMIT`] the vertices are merged per grid cell (to their mean, summed in index
//! order, so the result is deterministic); triangles that collapse or repeat are dropped. The
//! grid starts at about `sqrt(limit / 4)` cells along the longest side and is coarsened by a
//! quarter until the result is under the limit. The error is at most one cell's diagonal.

use std::collections::{HashMap, HashSet};

use glam::DVec3;

/// The most triangles the `model` and `wireframe` views draw as they are. 200 000 rather than
/// more: the web page's viewer must still turn smoothly where WebGL runs on the CPU
/// (SwiftShader drew 500 000 at 2 frames a second while orbiting; docs/performance.md).
pub const TRIANGLE_LIMIT: usize = 200_000;

/// An indexed triangle mesh.
pub(crate) type Indexed = (Vec<DVec3>, Vec<[u32; 3]>);

/// The mesh, or its clustered version with fewer than `limit` triangles and a note saying so.
pub(crate) fn under_limit(mesh: Indexed, limit: usize) -> (Indexed, Option<String>) {
    let before = mesh.1.len();
    if before <= limit {
        return (mesh, None);
    }
    let (lo, hi) = bounds(&mesh.0);
    let longest = (hi - lo).max_element().max(f64::MIN_POSITIVE);
    let mut cells = ((limit / 4) as f64).sqrt().max(1.0);
    loop {
        let out = cluster(&mesh, lo, longest / cells);
        if out.1.len() <= limit || cells <= 1.0 {
            let note = format!("decimated from {before} to {} triangles for viewing", out.1.len());
            return (out, Some(note));
        }
        cells = (cells * 0.75).floor().max(1.0);
    }
}

fn bounds(points: &[DVec3]) -> (DVec3, DVec3) {
    platener_geom::boxes::bounds3(points.iter().copied())
}

/// Merges the vertices of each cell of size `cell` (from `lo`) into their mean.
fn cluster((points, triangles): &Indexed, lo: DVec3, cell: f64) -> Indexed {
    let mut cell_of: HashMap<[i64; 3], u32> = HashMap::new();
    let mut sums: Vec<(DVec3, f64)> = Vec::new();
    let remap: Vec<u32> = points
        .iter()
        .map(|p| {
            let key = ((*p - lo) / cell).floor().as_i64vec3().to_array();
            let next = sums.len() as u32;
            let id = *cell_of.entry(key).or_insert(next);
            if id == next {
                sums.push((DVec3::ZERO, 0.0));
            }
            sums[id as usize].0 += *p;
            sums[id as usize].1 += 1.0;
            id
        })
        .collect();
    let mut seen = HashSet::new();
    let kept: Vec<[u32; 3]> = triangles
        .iter()
        .map(|t| t.map(|i| remap[i as usize]))
        .filter(|&[a, b, c]| a != b && b != c && a != c)
        .filter(|t| seen.insert(canonical(*t)))
        .collect();
    let positions: Vec<DVec3> = sums.into_iter().map(|(s, n)| s / n).collect();
    compact(&positions, kept)
}

/// The same triangle whichever corner it starts at (direction kept).
fn canonical([a, b, c]: [u32; 3]) -> [u32; 3] {
    if a <= b && a <= c {
        [a, b, c]
    } else if b <= c {
        [b, c, a]
    } else {
        [c, a, b]
    }
}

/// Drops vertices no triangle uses, keeping the others' order.
pub(crate) fn compact(points: &[DVec3], triangles: Vec<[u32; 3]>) -> Indexed {
    let mut new = vec![u32::MAX; points.len()];
    let mut kept = Vec::new();
    let triangles = triangles
        .into_iter()
        .map(|t| {
            t.map(|i| {
                if new[i as usize] == u32::MAX {
                    new[i as usize] = kept.len() as u32;
                    kept.push(points[i as usize]);
                }
                new[i as usize]
            })
        })
        .collect();
    (kept, triangles)
}
