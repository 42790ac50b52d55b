//! Chaining a planar group's boundary into closed vertex loops, in linear time.

use crate::mesh::Mesh;

/// The closed boundary loops of the faces `faces` (all in group `gid` of `face_group`), as
/// vertex indices, and how many chains could not be closed.
pub(super) fn boundary_loops(mesh: &Mesh, face_group: &[u32], gid: u32, faces: &[u32]) -> (Vec<Vec<u32>>, usize) {
    let topo = &mesh.topology;
    let mut half_edges: Vec<(u32, u32)> = Vec::new();
    for &f in faces {
        for c in 0..3 {
            let e = topo.face_edges[f as usize][c];
            let corners = topo.edge_corners(e);
            // Handle each edge once per group: at its first corner that belongs to the group.
            let first = corners.iter().find(|&&fc| face_group[(fc / 3) as usize] == gid);
            if first != Some(&(3 * f + c as u32)) {
                continue;
            }
            let [lo, hi] = topo.edges[e as usize];
            let net: i32 = corners
                .iter()
                .filter(|&&fc| face_group[(fc / 3) as usize] == gid)
                .map(|&fc| {
                    let t = &mesh.triangles[(fc / 3) as usize];
                    if t[(fc % 3) as usize] == lo { 1 } else { -1 }
                })
                .sum();
            let (from, to) = if net > 0 { (lo, hi) } else { (hi, lo) };
            for _ in 0..net.unsigned_abs() {
                half_edges.push((from, to));
            }
        }
    }
    // Outgoing half-edges per vertex, grouped by a sort (deterministic, no hashing).
    half_edges.sort_unstable();
    let out_of = |v: u32| {
        let start = half_edges.partition_point(|&(a, _)| a < v);
        let end = half_edges.partition_point(|&(a, _)| a <= v);
        start..end
    };
    let mut used = vec![false; half_edges.len()];
    let mut loops = Vec::new();
    let mut open = 0;
    // In a boundary every vertex has as many incoming as outgoing half-edges, so a walk from
    // v0 can only get stuck at v0: each closes. Each step uses a half-edge, so walks end.
    for start in 0..half_edges.len() {
        if used[start] {
            continue;
        }
        used[start] = true;
        let (v0, mut v) = half_edges[start];
        let mut lp = vec![v0];
        loop {
            if v == v0 {
                loops.push(lp);
                break;
            }
            lp.push(v);
            match out_of(v).find(|&h| !used[h]) {
                Some(h) => {
                    used[h] = true;
                    v = half_edges[h].1;
                }
                None => {
                    open += 1;
                    break;
                }
            }
        }
    }
    (loops, open)
}
