//! Consistent winding: neighbours across a two-face edge must run the edge in opposite
//! directions. We spread one face's winding over each orientable patch (breadth-first, from the
//! lowest face index, so the result does not depend on threads), then turn closed bodies so
//! their volume is positive (normals out) and open patches so the fewest faces change.

use std::collections::VecDeque;

use glam::DVec3;

use super::topology::Topology;

pub(super) struct Oriented {
    pub triangles: Vec<[u32; 3]>,
    /// Which input faces were reversed (corners 1 and 2 swapped).
    pub reversed: Vec<bool>,
    pub component: Vec<u32>,
    pub components: usize,
    /// Components not nested inside another closed one (cavities excluded), those that touch or
    /// cross each other counted once: the separate solids.
    pub solids: usize,
    pub flipped: usize,
    pub non_orientable_edges: usize,
}

/// Whether corner `c` of `t` runs its edge from the smaller to the larger vertex index.
fn forward(t: &[u32; 3], c: usize) -> bool {
    t[c] < t[(c + 1) % 3]
}

/// Six times the signed volume enclosed, over `faces` (all when `None`), divided by 6.
pub(super) fn signed_volume(vertices: &[DVec3], triangles: &[[u32; 3]], faces: Option<&[u32]>) -> f64 {
    let vol = |t: &[u32; 3]| {
        let [a, b, c] = t.map(|i| vertices[i as usize]);
        a.dot(b.cross(c))
    };
    let sum: f64 = match faces {
        Some(fs) => fs.iter().map(|&f| vol(&triangles[f as usize])).sum(),
        None => triangles.iter().map(vol).sum(),
    };
    sum / 6.0
}

/// Breadth-first labelling of faces connected through edges accepted by `cross`.
fn label(topology: &Topology, n: usize, cross: impl Fn(u32) -> bool) -> (Vec<u32>, Vec<Vec<u32>>) {
    let mut label = vec![u32::MAX; n];
    let mut groups = Vec::new();
    let mut queue = VecDeque::new();
    for start in 0..n {
        if label[start] != u32::MAX {
            continue;
        }
        let id = groups.len() as u32;
        let mut members = vec![start as u32];
        label[start] = id;
        queue.push_back(start);
        while let Some(f) = queue.pop_front() {
            for &e in &topology.face_edges[f] {
                if !cross(e) {
                    continue;
                }
                for &fc in topology.edge_corners(e) {
                    let g = (fc / 3) as usize;
                    if label[g] == u32::MAX {
                        label[g] = id;
                        members.push(g as u32);
                        queue.push_back(g);
                    }
                }
            }
        }
        groups.push(members);
    }
    (label, groups)
}

/// The triangles wound consistently: each edge-connected patch one way, closed bodies
/// outwards (cavities inwards), open patches the way most of their faces already were.
pub(super) fn orient(vertices: &[DVec3], triangles: &[[u32; 3]], topology: &Topology) -> Oriented {
    let n = triangles.len();
    let (component, bodies) = label(topology, n, |e| topology.edge_valence(e) >= 2);
    let Winding {
        mut flip,
        patches,
        non_orientable_edges,
    } = spread_winding(triangles, topology);
    let mut out: Vec<[u32; 3]> = triangles
        .iter()
        .zip(&flip)
        .map(|(t, &fl)| if fl { [t[0], t[2], t[1]] } else { *t })
        .collect();
    // Decide each patch's overall direction. A closed body is turned so its volume is
    // positive, unless it lies inside an odd number of other closed bodies: then it is a
    // cavity and its normals must point into the void (negative volume).
    let body_closed = closed_bodies(topology, &component, &bodies, &patches);
    let depth = nesting_depth(vertices, &out, &bodies, &body_closed);
    for members in &patches {
        let body = component[members[0] as usize] as usize;
        let turn = if body_closed[body] {
            (signed_volume(vertices, &out, Some(members)) < 0.0) != (depth[body] % 2 == 1)
        } else {
            2 * members.iter().filter(|&&f| flip[f as usize]).count() > members.len()
        };
        if turn {
            for &f in members {
                out[f as usize].swap(1, 2);
                flip[f as usize] = !flip[f as usize];
            }
        }
    }
    let top: Vec<&[u32]> = bodies
        .iter()
        .zip(&depth)
        .filter(|(_, d)| *d % 2 == 0)
        .map(|(b, _)| b.as_slice())
        .collect();
    Oriented {
        solids: super::touching::count_solids(vertices, &out, &top),
        flipped: flip.iter().filter(|&&f| f).count(),
        reversed: flip,
        triangles: out,
        components: bodies.len(),
        component,
        non_orientable_edges,
    }
}

fn patches_per_body(component: &[u32], patches: &[Vec<u32>], n_bodies: usize) -> Vec<usize> {
    let mut count = vec![0; n_bodies];
    for p in patches {
        count[component[p[0] as usize] as usize] += 1;
    }
    count
}

/// For each closed body, how many other closed bodies enclose it (ray parity from one of its
/// vertices). Bodies are compared only when one's box lies inside the other's, so models of
/// many separate parts stay fast.
fn nesting_depth(vertices: &[DVec3], triangles: &[[u32; 3]], bodies: &[Vec<u32>], closed: &[bool]) -> Vec<usize> {
    let boxes: Vec<(DVec3, DVec3)> = bodies
        .iter()
        .map(|faces| {
            platener_geom::boxes::bounds3(
                faces
                    .iter()
                    .flat_map(|&f| triangles[f as usize])
                    .map(|v| vertices[v as usize]),
            )
        })
        .collect();
    // An irrational-looking direction: rays along it almost never graze an edge of a
    // CAD model, whose edges run along axes and simple angles.
    let dir = DVec3::new(0.573_615_6, 0.692_048_1, 0.438_371_1).normalize();
    (0..bodies.len())
        .map(|a| {
            if !closed[a] {
                return 0;
            }
            let p = vertices[triangles[bodies[a][0] as usize][0] as usize];
            (0..bodies.len())
                .filter(|&b| {
                    b != a
                        && closed[b]
                        && boxes[a].0.cmpge(boxes[b].0).all()
                        && boxes[a].1.cmple(boxes[b].1).all()
                        && bodies[b]
                            .iter()
                            .filter(|&&f| ray_hits(p, dir, triangles[f as usize].map(|v| vertices[v as usize])))
                            .count()
                            % 2
                            == 1
                })
                .count()
        })
        .collect()
}

/// Whether the ray `origin + t·dir`, t > 0, crosses the triangle (Möller–Trumbore).
fn ray_hits(origin: DVec3, dir: DVec3, [a, b, c]: [DVec3; 3]) -> bool {
    let (e1, e2) = (b - a, c - a);
    let p = dir.cross(e2);
    let det = e1.dot(p);
    if det.abs() < 1e-300 {
        return false;
    }
    let inv = 1.0 / det;
    let s = origin - a;
    let u = s.dot(p) * inv;
    if !(0.0..=1.0).contains(&u) {
        return false;
    }
    let q = s.cross(e1);
    let v = dir.dot(q) * inv;
    if v < 0.0 || u + v > 1.0 {
        return false;
    }
    e2.dot(q) * inv > 0.0
}

/// Faces wound consistently within each patch of faces joined over two-face edges.
struct Winding {
    /// Per face: whether it is turned against its input winding.
    flip: Vec<bool>,
    /// The patches' faces.
    patches: Vec<Vec<u32>>,
    /// Edges whose two faces could not be wound consistently (a Möbius strip).
    non_orientable_edges: usize,
}

/// Spreads winding over two-face edges, breadth first from each face not yet reached: a
/// neighbour is turned so that it runs the shared edge the other way.
fn spread_winding(triangles: &[[u32; 3]], topology: &Topology) -> Winding {
    let n = triangles.len();
    let mut flip = vec![false; n];
    let mut seen = vec![false; n];
    let mut queue = VecDeque::new();
    let mut patches: Vec<Vec<u32>> = Vec::new();
    let mut non_orientable_edges = 0;
    for start in 0..n {
        if seen[start] {
            continue;
        }
        seen[start] = true;
        let mut members = vec![start as u32];
        queue.push_back(start);
        while let Some(f) = queue.pop_front() {
            for c in 0..3 {
                let e = topology.face_edges[f][c];
                let corners = topology.edge_corners(e);
                if corners.len() != 2 {
                    continue;
                }
                let other = if corners[0] / 3 == f as u32 && corners[0] % 3 == c as u32 {
                    corners[1]
                } else {
                    corners[0]
                };
                let (g, cg) = ((other / 3) as usize, (other % 3) as usize);
                if g == f {
                    continue;
                }
                let dir_f = forward(&triangles[f], c) ^ flip[f];
                if seen[g] {
                    if forward(&triangles[g], cg) ^ flip[g] == dir_f && f < g {
                        non_orientable_edges += 1;
                    }
                    continue;
                }
                flip[g] = forward(&triangles[g], cg) ^ !dir_f;
                seen[g] = true;
                members.push(g as u32);
                queue.push_back(g);
            }
        }
        patches.push(members);
    }
    Winding {
        flip,
        patches,
        non_orientable_edges,
    }
}

/// Per body: whether it is closed (one patch, every edge between exactly two faces).
fn closed_bodies(topology: &Topology, component: &[u32], bodies: &[Vec<u32>], patches: &[Vec<u32>]) -> Vec<bool> {
    bodies
        .iter()
        .zip(&patches_per_body(component, patches, bodies.len()))
        .map(|(faces, &np)| {
            np == 1
                && faces.iter().all(|&f| {
                    topology.face_edges[f as usize]
                        .iter()
                        .all(|&e| topology.edge_valence(e) == 2)
                })
        })
        .collect()
}
