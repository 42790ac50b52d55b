//! Volumes made of primitives: the thesis' prism classifier (two parallel, congruent planar
//! shapes facing apart, and a lateral surface between them found by flood fill over the
//! mesh), boxes (three pairs of parallel planes at right angles, or a prism whose lateral
//! surface is four planes), solid cylinders with their caps and bores, and spheres.
//!
//! Plane normals are sorted into buckets on the sphere so that a plane is only compared with
//! the planes in the buckets round its opposite direction; parallelism is then scored by the
//! actual angle, not by the bucket.

use std::collections::BTreeSet;

use glam::{DVec2, DVec3};
use serde::Serialize;

use super::graph::for_each_neighbour;
use super::sample::Sample;
use super::surface::{Surface, basis};
use super::{Primitive, Thresholds};
use crate::mesh::Mesh;

/// What kind of volume.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum VolumeKind {
    /// A cuboid.
    Box,
    /// A straight prism of any cross-section.
    Prism,
    /// A solid cylinder (or tube) with its caps.
    Cylinder,
    /// A sphere.
    Sphere,
}

/// A volume and the primitives it is made of.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Volume {
    /// Its kind.
    pub kind: VolumeKind,
    /// Its primitives (indices), ascending.
    pub primitives: Vec<u32>,
    /// The two end planes of a prism (or the first pair of a box).
    pub caps: Option<[u32; 2]>,
    /// The axis of a prism or cylinder (unit).
    pub axis: Option<DVec3>,
}

/// A pair of parallel planes facing apart with the solid between them.
#[derive(Debug, Clone, Copy)]
struct Pair {
    a: u32,
    b: u32,
    angle: f64,
}

/// Everything the classifiers look at.
struct Ctx<'a> {
    mesh: &'a Mesh,
    samples: &'a [Sample],
    prims: &'a [Primitive],
    labels: &'a [Option<u32>],
    adjacency: &'a [[u32; 2]],
    th: &'a Thresholds,
}

impl Ctx<'_> {
    fn adjacent(&self, a: u32, b: u32) -> bool {
        self.adjacency.binary_search(&[a.min(b), a.max(b)]).is_ok()
    }

    fn plane(&self, k: u32) -> Option<(DVec3, f64)> {
        match self.prims[k as usize].shape {
            Surface::Plane { normal, offset } => Some((normal, offset)),
            _ => None,
        }
    }
}

/// Finds the volumes: boxes, then prisms, then cylinders and spheres, each primitive used
/// by at most one volume.
pub fn find(
    mesh: &Mesh,
    samples: &[Sample],
    prims: &[Primitive],
    labels: &[Option<u32>],
    adjacency: &[[u32; 2]],
    th: &Thresholds,
) -> Vec<Volume> {
    let cx = Ctx {
        mesh,
        samples,
        prims,
        labels,
        adjacency,
        th,
    };
    let pairs = parallel_pairs(&cx);
    let mut used = vec![false; prims.len()];
    let mut out = boxes(&cx, &pairs, &mut used);
    out.extend(prisms(&cx, &pairs, &mut used));
    out.extend(round(&cx, &mut used));
    out
}

/// The volume of `kind` made of `prims` (sorted here), each marked used.
fn claim(
    used: &mut [bool],
    mut prims: Vec<u32>,
    kind: VolumeKind,
    caps: Option<[u32; 2]>,
    axis: Option<DVec3>,
) -> Volume {
    prims.sort_unstable();
    for &k in &prims {
        used[k as usize] = true;
    }
    Volume {
        kind,
        primitives: prims,
        caps,
        axis,
    }
}

/// Bucket of a unit direction on a latitude-longitude grid of `n` rows.
fn bucket(d: DVec3, n: usize) -> (usize, usize) {
    let lat = d.z.clamp(-1.0, 1.0).acos() / std::f64::consts::PI;
    let lon = (d.y.atan2(d.x) / std::f64::consts::TAU).rem_euclid(1.0);
    (
        ((lat * n as f64) as usize).min(n - 1),
        ((lon * 2.0 * n as f64) as usize).min(2 * n - 1),
    )
}

/// Pairs of planes whose normals are opposite within the parallel tolerance, with the solid
/// between them and congruent shapes, most parallel first.
fn parallel_pairs(cx: &Ctx<'_>) -> Vec<Pair> {
    let tol = cx.th.parallel_deg.to_radians();
    // Buckets at least twice the tolerance wide: an opposite normal is in the bucket of the
    // exact opposite direction or a neighbouring one.
    let rows = ((std::f64::consts::PI / (2.0 * tol)).floor() as usize).clamp(1, 90);
    let planes: Vec<(u32, DVec3, f64)> = (0..cx.prims.len() as u32)
        .filter_map(|k| cx.plane(k).map(|(n, d)| (k, n, d)))
        .collect();
    let mut buckets: Vec<((usize, usize), usize)> =
        planes.iter().enumerate().map(|(i, p)| (bucket(p.1, rows), i)).collect();
    buckets.sort_unstable();
    let mut pairs = Vec::new();
    for (i, &(a, na, da)) in planes.iter().enumerate() {
        let (r, c) = bucket(-na, rows);
        for dr in -1i64..=1 {
            let rr = r as i64 + dr;
            if !(0..rows as i64).contains(&rr) {
                continue;
            }
            let at_pole = rr == 0 || rr == rows as i64 - 1;
            for &((br, bc), j) in &buckets {
                let near_col = at_pole || {
                    let d = (bc as i64 - c as i64).rem_euclid(2 * rows as i64);
                    d <= 1 || d == 2 * rows as i64 - 1
                };
                if br as i64 != rr || !near_col || j <= i {
                    continue;
                }
                let (b, nb, db) = planes[j];
                let angle = (-na).dot(nb).clamp(-1.0, 1.0).acos();
                // Facing apart with material between: b's plane lies behind a's.
                let apart = da + db > cx.th.eps;
                if angle <= tol && apart && congruent(cx, a, b) {
                    pairs.push(Pair { a, b, angle });
                }
            }
        }
    }
    pairs.sort_by(|x, y| x.angle.total_cmp(&y.angle).then((x.a, x.b).cmp(&(y.a, y.b))));
    pairs.dedup_by_key(|p| (p.a, p.b));
    pairs
}

/// Whether planes `a` and `b` have the same shape: seen along `a`'s normal, each one's
/// occupied bitmap cells are (within one cell) covered by the other's, for all but 5 %.
fn congruent(cx: &Ctx<'_>, a: u32, b: u32) -> bool {
    let Some((n, _)) = cx.plane(a) else { return false };
    let (u, v) = basis(n);
    let cells = |k: u32| -> BTreeSet<(i64, i64)> {
        cx.prims[k as usize]
            .samples
            .iter()
            .map(|&i| {
                let p = cx.samples[i as usize].at.p;
                let q = DVec2::new(p.dot(u), p.dot(v)) / cx.th.cell;
                (q.x.floor() as i64, q.y.floor() as i64)
            })
            .collect()
    };
    let (ca, cb) = (cells(a), cells(b));
    let covered = |x: &BTreeSet<(i64, i64)>, y: &BTreeSet<(i64, i64)>| {
        let hit = x
            .iter()
            .filter(|c| (-1..=1).any(|dx| (-1..=1).any(|dy| y.contains(&(c.0 + dx, c.1 + dy)))))
            .count();
        hit as f64 >= 0.95 * x.len() as f64
    };
    !ca.is_empty() && !cb.is_empty() && covered(&ca, &cb) && covered(&cb, &ca)
}

/// Boxes: three pairs at right angles whose planes each touch the four planes of the other
/// two pairs.
fn boxes(cx: &Ctx<'_>, pairs: &[Pair], used: &mut [bool]) -> Vec<Volume> {
    let sin_tol = cx.th.parallel_deg.to_radians().sin();
    let normal = |k: u32| cx.plane(k).map_or(DVec3::ZERO, |p| p.0);
    let square = |p: &Pair, q: &Pair| {
        normal(p.a).dot(normal(q.a)).abs() <= sin_tol
            && [p.a, p.b]
                .iter()
                .all(|&x| [q.a, q.b].iter().all(|&y| cx.adjacent(x, y)))
    };
    let mut out = Vec::new();
    for i in 0..pairs.len() {
        for j in i + 1..pairs.len() {
            for k in j + 1..pairs.len() {
                let (p, q, r) = (&pairs[i], &pairs[j], &pairs[k]);
                let all = [p.a, p.b, q.a, q.b, r.a, r.b];
                if all.iter().any(|&x| used[x as usize]) || !(square(p, q) && square(p, r) && square(q, r)) {
                    continue;
                }
                out.push(claim(
                    used,
                    all.to_vec(),
                    VolumeKind::Box,
                    Some([p.a, p.b]),
                    Some(normal(p.a)),
                ));
            }
        }
    }
    out
}

/// Prisms: a pair whose lateral surface (flood fill between the two planes) reaches the
/// other plane and is made only of primitives parallel to the axis (and unexplained
/// triangles). A lateral surface of four planes makes it a box, of cylinders only (a rod, a
/// tube) a cylinder.
fn prisms(cx: &Ctx<'_>, pairs: &[Pair], used: &mut [bool]) -> Vec<Volume> {
    let mut out = Vec::new();
    for p in pairs {
        if used[p.a as usize] || used[p.b as usize] {
            continue;
        }
        let Some(lateral) = lateral(cx, p) else { continue };
        if lateral.iter().any(|&k| used[k as usize]) {
            continue;
        }
        let planes = lateral.iter().filter(|&&k| cx.plane(k).is_some()).count();
        let round = lateral
            .iter()
            .all(|&k| matches!(cx.prims[k as usize].shape, Surface::Cylinder { .. }));
        let kind = match (planes, round) {
            (4, _) if lateral.len() == 4 => VolumeKind::Box,
            (_, true) => VolumeKind::Cylinder,
            _ => VolumeKind::Prism,
        };
        let mut prims = lateral;
        prims.extend([p.a, p.b]);
        out.push(claim(used, prims, kind, Some([p.a, p.b]), cx.plane(p.a).map(|x| x.0)));
    }
    out
}

/// The primitives of the lateral surface of pair `p`: flood fill from the faces next to
/// plane `a` over faces whose centroids lie between the planes; `None` when it never reaches
/// plane `b` or holds a primitive not parallel to the axis.
fn lateral(cx: &Ctx<'_>, p: &Pair) -> Option<Vec<u32>> {
    let (n, d) = cx.plane(p.a)?;
    let depth = d + cx.plane(p.b)?.1;
    let height = |f: usize| {
        let [x, y, z] = cx.mesh.corners(f);
        d - n.dot((x + y + z) / 3.0)
    };
    let cap = |f: usize| cx.labels[f] == Some(p.a) || cx.labels[f] == Some(p.b);
    let mut seen = vec![false; cx.mesh.triangles.len()];
    let mut stack: Vec<usize> = Vec::new();
    for &f in &cx.prims[p.a as usize].triangles {
        for_each_neighbour(cx.mesh, f as usize, |g| {
            if !cap(g) && !seen[g] {
                seen[g] = true;
                stack.push(g);
            }
        });
    }
    let (mut reached, mut prims) = (false, BTreeSet::new());
    while let Some(f) = stack.pop() {
        let h = height(f);
        if h < -cx.th.eps || h > depth + cx.th.eps {
            continue;
        }
        if let Some(k) = cx.labels[f] {
            prims.insert(k);
        }
        for_each_neighbour(cx.mesh, f, |g| {
            reached |= cx.labels[g] == Some(p.b);
            if !cap(g) && !seen[g] {
                seen[g] = true;
                stack.push(g);
            }
        });
    }
    let sin_tol = cx.th.parallel_deg.to_radians().sin();
    let parallel = |k: &u32| match cx.prims[*k as usize].shape {
        Surface::Plane { normal, .. } => normal.dot(n).abs() <= sin_tol,
        Surface::Cylinder { axis, .. } => axis.cross(n).length() <= sin_tol,
        _ => false,
    };
    (reached && !prims.is_empty() && prims.iter().all(parallel)).then(|| prims.into_iter().collect())
}

/// Solid cylinders (an outward cylinder, the adjacent planes across its axis as caps, and
/// coaxial bores touching those caps) and spheres (an outward sphere).
fn round(cx: &Ctx<'_>, used: &mut [bool]) -> Vec<Volume> {
    let sin_tol = cx.th.parallel_deg.to_radians().sin();
    let mut out = Vec::new();
    for (k, prim) in cx.prims.iter().enumerate() {
        if used[k] || !prim.outward {
            continue;
        }
        match prim.shape {
            Surface::Sphere { .. } => {
                out.push(claim(used, vec![k as u32], VolumeKind::Sphere, None, None));
            }
            Surface::Cylinder { axis, point, .. } => {
                let caps: Vec<u32> = (0..cx.prims.len() as u32)
                    .filter(|&c| {
                        !used[c as usize]
                            && cx.adjacent(k as u32, c)
                            && cx.plane(c).is_some_and(|(n, _)| n.cross(axis).length() <= sin_tol)
                    })
                    .collect();
                let coaxial = |s: &Surface| {
                    matches!(*s, Surface::Cylinder { axis: a, point: p, .. }
                    if a.cross(axis).length() <= sin_tol && (p - point).reject_from_normalized(axis).length() <= cx.th.eps)
                };
                let bores: Vec<u32> = (0..cx.prims.len() as u32)
                    .filter(|&b| {
                        b as usize != k
                            && !used[b as usize]
                            && !cx.prims[b as usize].outward
                            && coaxial(&cx.prims[b as usize].shape)
                    })
                    .filter(|&b| caps.iter().any(|&c| cx.adjacent(b, c)))
                    .collect();
                let prims: Vec<u32> = caps.iter().chain(&bores).copied().chain([k as u32]).collect();
                out.push(claim(used, prims, VolumeKind::Cylinder, None, Some(axis)));
            }
            _ => {}
        }
    }
    out
}
