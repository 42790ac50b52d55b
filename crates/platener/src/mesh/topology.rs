//! Edges of an indexed mesh: face → edges and edge → faces, built by one sort (O(n log n),
//! in practice linear-like and parallel), with a deterministic edge order.

use rayon::slice::ParallelSliceMut;

/// Edge ↔ face incidence of an indexed triangle list.
#[derive(Debug, Clone, Default)]
pub struct Topology {
    /// Each edge's two vertex indices, smaller first; sorted.
    pub edges: Vec<[u32; 2]>,
    /// For each face, the edge between corner `i` and corner `i + 1`.
    pub face_edges: Vec<[u32; 3]>,
    /// CSR offsets into `edge_face_list`, one more than there are edges.
    offsets: Vec<u32>,
    /// Face-corner ids (`3·face + corner`) of each edge, grouped by edge.
    edge_face_list: Vec<u32>,
}

impl Topology {
    /// Builds the incidence for `triangles`.
    pub fn build(triangles: &[[u32; 3]]) -> Self {
        let mut keys: Vec<(u64, u32)> = Vec::with_capacity(triangles.len() * 3);
        for (f, t) in triangles.iter().enumerate() {
            for c in 0..3 {
                let (a, b) = (t[c], t[(c + 1) % 3]);
                let key = (u64::from(a.min(b)) << 32) | u64::from(a.max(b));
                keys.push((key, (3 * f + c) as u32));
            }
        }
        keys.par_sort_unstable();
        let mut edges = Vec::with_capacity(keys.len() / 2 + 1);
        let mut face_edges = vec![[0u32; 3]; triangles.len()];
        let mut offsets = Vec::with_capacity(keys.len() / 2 + 2);
        let mut edge_face_list = Vec::with_capacity(keys.len());
        let mut last = None;
        for &(key, fc) in &keys {
            if last != Some(key) {
                offsets.push(edge_face_list.len() as u32);
                edges.push([(key >> 32) as u32, key as u32]);
                last = Some(key);
            }
            let e = (edges.len() - 1) as u32;
            face_edges[(fc / 3) as usize][(fc % 3) as usize] = e;
            edge_face_list.push(fc);
        }
        offsets.push(edge_face_list.len() as u32);
        Self {
            edges,
            face_edges,
            offsets,
            edge_face_list,
        }
    }

    /// Follows faces whose winding was reversed by swapping corners 1 and 2: corner 0 then
    /// runs the old corner 2's edge and corner 2 the old corner 0's, corner 1 keeps its edge.
    pub fn reverse_faces(&mut self, reversed: &[bool]) {
        for (f, fe) in self.face_edges.iter_mut().enumerate() {
            if reversed[f] {
                fe.swap(0, 2);
            }
        }
        for fc in &mut self.edge_face_list {
            let (f, c) = (*fc / 3, *fc % 3);
            if reversed[f as usize] {
                *fc = 3 * f + (2 - c);
            }
        }
    }

    /// The face-corners (`3·face + corner`) using edge `e`; corner `c` of a face runs from
    /// its vertex `c` to vertex `c + 1`.
    pub fn edge_corners(&self, e: u32) -> &[u32] {
        let e = e as usize;
        &self.edge_face_list[self.offsets[e] as usize..self.offsets[e + 1] as usize]
    }

    /// How many faces use edge `e`.
    pub fn edge_valence(&self, e: u32) -> usize {
        let e = e as usize;
        (self.offsets[e + 1] - self.offsets[e]) as usize
    }

    /// (open edges, non-manifold edges).
    pub fn edge_counts(&self) -> (usize, usize) {
        (0..self.edges.len() as u32).fold((0, 0), |(open, nm), e| match self.edge_valence(e) {
            1 => (open + 1, nm),
            2 => (open, nm),
            _ => (open, nm + 1),
        })
    }
}
