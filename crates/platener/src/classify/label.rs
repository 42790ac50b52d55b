//! Which primitive explains each triangle. Samples are far fewer than the triangles of a
//! fine mesh, so a triangle looks at the primitives whose samples lie near its centroid (in
//! its grid cube or the 26 round it) and takes the nearest one within ε. The candidate lists
//! are made per cube once, so a million triangles cost a binary search each.

use rayon::prelude::*;

use super::sample::{Sample, cell_of as cube, key};
use super::{Primitive, Thresholds};
use crate::mesh::Mesh;

/// Each triangle's primitive (index into `primitives`), if one lies within ε of its centroid
/// among those with samples nearby; a plane must also face the triangle's side.
pub fn label_triangles(mesh: &Mesh, samples: &[Sample], primitives: &[Primitive], th: &Thresholds) -> Vec<Option<u32>> {
    let cell = th.normal_radius;
    let mut near: Vec<(u64, u32)> = Vec::new();
    for (k, p) in primitives.iter().enumerate() {
        for &i in &p.samples {
            let c = cube(samples[i as usize].at.p, cell);
            for d in NEIGHBOURS {
                near.push((key([c[0] + d[0], c[1] + d[1], c[2] + d[2]]), k as u32));
            }
        }
    }
    near.par_sort_unstable();
    near.dedup();
    (0..mesh.triangles.len())
        .into_par_iter()
        .map(|f| {
            let [a, b, c] = mesh.corners(f);
            let centroid = (a + b + c) / 3.0;
            let k = key(cube(centroid, cell));
            let start = near.partition_point(|e| e.0 < k);
            near[start..]
                .iter()
                .take_while(|e| e.0 == k)
                .filter_map(|e| {
                    let s = &primitives[e.1 as usize].shape;
                    let d = s.distance(centroid);
                    let facing =
                        !matches!(s, super::Surface::Plane { .. }) || s.normal_at(centroid).dot(mesh.normals[f]) > 0.0;
                    (d <= th.eps && facing).then_some((d, e.1))
                })
                .min_by(|x, y| x.0.total_cmp(&y.0).then(x.1.cmp(&y.1)))
                .map(|x| x.1)
        })
        .collect()
}

/// Offsets of a cube and its 26 neighbours.
const NEIGHBOURS: [[i64; 3]; 27] = {
    let mut out = [[0i64; 3]; 27];
    let mut i = 0;
    while i < 27 {
        out[i] = [(i % 3) as i64 - 1, ((i / 3) % 3) as i64 - 1, (i / 9) as i64 - 1];
        i += 1;
    }
    out
};

/// Fills each primitive's triangles and area from the labels.
pub fn attach(primitives: &mut [Primitive], labels: &[Option<u32>], mesh: &Mesh) {
    for (f, l) in labels.iter().enumerate() {
        if let Some(k) = l {
            let p = &mut primitives[*k as usize];
            p.triangles.push(f as u32);
            p.area += mesh.areas[f];
        }
    }
}
