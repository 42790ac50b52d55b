//! The classified-objects graph of the thesis: volumes (boxes, prisms, cylinders, spheres),
//! connectors (primitives outside every volume that join two or more of them), surfaces
//! (other primitives outside volumes) and freeforms (connected triangles nothing explains),
//! with an edge wherever two of them share a triangle edge. The conversion builds each node
//! its own way and joins the parts along these edges.

use serde::Serialize;

use super::{Primitive, Volume, VolumeKind};
use crate::mesh::Mesh;

/// What a node of the graph is.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum NodeKind {
    /// A volume (see [`Node::volume`]).
    Volume,
    /// A primitive outside the volumes touching two or more of them.
    Connector,
    /// A primitive outside the volumes touching fewer than two.
    Surface,
    /// Connected triangles no primitive explains.
    Freeform,
}

/// A node of the graph.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Node {
    /// What it is.
    pub kind: NodeKind,
    /// The volume's kind, for volume nodes.
    pub volume: Option<VolumeKind>,
    /// Its primitives (indices), ascending; empty for freeforms.
    pub primitives: Vec<u32>,
    /// How many triangles it holds.
    pub triangles: usize,
    /// Their area, mm².
    pub area: f64,
}

/// The graph: nodes and their adjacency.
#[derive(Debug, Clone, Default, PartialEq, Serialize)]
pub struct Graph {
    /// Volumes first (in [`super::Classification::volumes`] order), then connectors and
    /// surfaces (by primitive), then freeforms (by lowest triangle).
    pub nodes: Vec<Node>,
    /// Pairs of adjacent nodes, smaller first, sorted.
    pub edges: Vec<[u32; 2]>,
    /// Each triangle's node.
    #[serde(skip)]
    pub node_of_triangle: Vec<u32>,
}

/// Calls `f` with every face sharing an edge with face `f0`.
pub(super) fn for_each_neighbour(mesh: &Mesh, f0: usize, mut f: impl FnMut(usize)) {
    for &e in &mesh.topology.face_edges[f0] {
        for &fc in mesh.topology.edge_corners(e) {
            let g = (fc / 3) as usize;
            if g != f0 {
                f(g);
            }
        }
    }
}

/// Sorted distinct pairs `[a, b]` (a < b) of the classes `class` gives faces that share an
/// edge (faces `class` maps to `None` are skipped).
fn class_pairs(mesh: &Mesh, class: impl Fn(usize) -> Option<u32>) -> Vec<[u32; 2]> {
    let mut pairs = Vec::new();
    for e in 0..mesh.topology.edges.len() as u32 {
        let faces = mesh.topology.edge_corners(e);
        for (i, a) in faces.iter().enumerate() {
            for b in &faces[i + 1..] {
                if let (Some(x), Some(y)) = (class((a / 3) as usize), class((b / 3) as usize))
                    && x != y
                {
                    pairs.push([x.min(y), x.max(y)]);
                }
            }
        }
    }
    pairs.sort_unstable();
    pairs.dedup();
    pairs
}

/// Pairs of primitives whose triangles share an edge.
pub fn primitive_adjacency(mesh: &Mesh, labels: &[Option<u32>]) -> Vec<[u32; 2]> {
    class_pairs(mesh, |f| labels[f])
}

/// Builds the graph from the primitives, the triangle labels and the volumes.
pub fn build(mesh: &Mesh, primitives: &[Primitive], labels: &[Option<u32>], volumes: &[Volume]) -> Graph {
    let mut nodes: Vec<Node> = Vec::new();
    let mut node_of_prim = vec![u32::MAX; primitives.len()];
    for v in volumes {
        for &p in &v.primitives {
            node_of_prim[p as usize] = nodes.len() as u32;
        }
        nodes.push(Node {
            kind: NodeKind::Volume,
            volume: Some(v.kind),
            primitives: v.primitives.clone(),
            triangles: 0,
            area: 0.0,
        });
    }
    let volume_nodes = nodes.len() as u32;
    for (k, slot) in node_of_prim.iter_mut().enumerate() {
        if *slot == u32::MAX {
            *slot = nodes.len() as u32;
            nodes.push(Node {
                kind: NodeKind::Surface,
                volume: None,
                primitives: vec![k as u32],
                triangles: 0,
                area: 0.0,
            });
        }
    }
    let node_of_triangle = assign_freeforms(mesh, labels, &node_of_prim, &mut nodes);
    for (f, &n) in node_of_triangle.iter().enumerate() {
        nodes[n as usize].triangles += 1;
        nodes[n as usize].area += mesh.areas[f];
    }
    let edges = class_pairs(mesh, |f| Some(node_of_triangle[f]));
    for (i, node) in nodes.iter_mut().enumerate().skip(volume_nodes as usize) {
        let touching = edges
            .iter()
            .filter(|e| (e[0] == i as u32 && e[1] < volume_nodes) || (e[1] == i as u32 && e[0] < volume_nodes))
            .count();
        if node.kind == NodeKind::Surface && touching >= 2 {
            node.kind = NodeKind::Connector;
        }
    }
    Graph {
        nodes,
        edges,
        node_of_triangle,
    }
}

/// Each triangle's node: its primitive's, or a freeform node per connected region of
/// unlabelled triangles (appended to `nodes` in order of their lowest triangle).
fn assign_freeforms(mesh: &Mesh, labels: &[Option<u32>], node_of_prim: &[u32], nodes: &mut Vec<Node>) -> Vec<u32> {
    let mut node: Vec<u32> = labels
        .iter()
        .map(|l| l.map_or(u32::MAX, |k| node_of_prim[k as usize]))
        .collect();
    let mut stack = Vec::new();
    for f in 0..node.len() {
        if node[f] != u32::MAX {
            continue;
        }
        let id = nodes.len() as u32;
        nodes.push(Node {
            kind: NodeKind::Freeform,
            volume: None,
            primitives: Vec::new(),
            triangles: 0,
            area: 0.0,
        });
        node[f] = id;
        stack.push(f);
        while let Some(g) = stack.pop() {
            for_each_neighbour(mesh, g, |h| {
                if node[h] == u32::MAX {
                    node[h] = id;
                    stack.push(h);
                }
            });
        }
    }
    node
}
