//! Models the browser tests make themselves.

use std::path::Path;

/// A closed box of about a million triangles (each face a fine grid), as binary STL: big
/// enough to measure the viewer, still a box the plate method cuts.
pub fn million_triangle_box(path: &Path) {
    // 6 faces × 289² cells × 2 = 1,002,252 triangles.
    write_box(path, [100.0, 80.0, 60.0], 289);
}

/// A 0.15 × 0.12 × 0.1 mm box: a model exported in metres, which no method can cut.
pub fn metre_scale_box(path: &Path) {
    write_box(path, [0.15, 0.12, 0.1], 1);
}

/// A closed box of `size` (mm), each face an `n` × `n` grid of cells, as binary STL.
fn write_box(path: &Path, size: [f32; 3], n: usize) {
    let mut tris: Vec<[[f32; 3]; 3]> = Vec::with_capacity(6 * n * n * 2);
    for axis in 0..3 {
        for side in [0.0f32, 1.0] {
            let (u, v) = ((axis + 1) % 3, (axis + 2) % 3);
            let at = |i: usize, j: usize| {
                let mut p = [0.0f32; 3];
                p[axis] = side * size[axis];
                p[u] = size[u] * i as f32 / n as f32;
                p[v] = size[v] * j as f32 / n as f32;
                p
            };
            for i in 0..n {
                for j in 0..n {
                    let (a, b, c, d) = (at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
                    // Outward normals: the far side keeps u×v order, the near side flips it.
                    if side > 0.5 {
                        tris.extend([[a, b, c], [a, c, d]]);
                    } else {
                        tris.extend([[a, c, b], [a, d, c]]);
                    }
                }
            }
        }
    }
    let mut bytes = vec![0u8; 80];
    bytes.extend((tris.len() as u32).to_le_bytes());
    for t in &tris {
        bytes.extend([0u8; 12]);
        for p in t {
            for c in p {
                bytes.extend(c.to_le_bytes());
            }
        }
        bytes.extend([0u8; 2]);
    }
    std::fs::write(path, bytes).expect("write the STL");
}
