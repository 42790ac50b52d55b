//! Details kept: how much of the model's sharp edges the plan reproduces (issue 32).
//!
//! The surface term cannot see a detail: raised letters 1.25 mm tall on a tag are within
//! half a sheet of a blank 3 mm part, so a plan that drops them kept the whole score
//! (0.995). What a detail has, and a blank part lacks, are edges: a letter's outline at its
//! foot and top. So the model's **sharp edges** (where the faces on either side turn by more
//! than [`SHARP_DEG`]) are sampled, and a sample is kept when some edge of the plan lies
//! within the cover distance of it: a part's outline or hole at either face, or a score mark
//! (an engraved feature's outline, a layer's outline on the one below). The share kept,
//! weighted by length, is the quality's `details` factor, found against kept whatever the
//! method: it does not ask a method what it looked for.

use glam::{DVec2, DVec3};
use platener_geom::slab::Slab;
use serde::Serialize;

use crate::assembly::Solid;
use crate::mesh::Mesh;
use crate::plan::{MarkKind, MarkSide, Plan, PlanPart};

/// Faces turning by more than this at an edge make it sharp, degrees: fillets and curves
/// tessellated finer than this are not details.
pub const SHARP_DEG: f64 = 30.0;
/// Sharp-edge samples taken, at most (spread evenly over the edges' length).
const MAX_SAMPLES: f64 = 20_000.0;
/// Weight of the details in the quality: a plan that keeps none of the model's sharp edges
/// loses this share of its quality.
pub const DETAILS_WEIGHT: f64 = 0.5;

/// How much of the model's sharp edges a plan reproduces.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct DetailScore {
    /// Length of the model's sharp edges, mm.
    pub sharp_edges: f64,
    /// Share of it within the cover distance of an edge or score mark of the plan; 1 when
    /// the model has no sharp edge.
    pub kept: f64,
    /// 1 − [`DETAILS_WEIGHT`]·(1 − kept): the factor in the quality.
    pub value: f64,
}

/// The details of `mesh` that `plan`'s parts (as `solids`) keep within `reach`.
pub(crate) fn measure(mesh: &Mesh, plan: &Plan, solids: &[Solid], reach: f64) -> DetailScore {
    let edges = sharp_edges(mesh);
    let total: f64 = edges.iter().map(|(a, b)| a.distance(*b)).sum();
    if total <= 0.0 || reach <= 0.0 {
        return DetailScore {
            sharp_edges: total,
            kept: 1.0,
            value: 1.0,
        };
    }
    // A model of more sharp edges than samples (a knurled or textured surface) is judged on
    // every k-th edge.
    let stride = edges.len().div_ceil(MAX_SAMPLES as usize).max(1);
    let judged: f64 = edges.iter().step_by(stride).map(|(a, b)| a.distance(*b)).sum();
    let spacing = (judged / MAX_SAMPLES).max(reach / 4.0);
    let mut samples = Vec::new();
    for (a, b) in edges.iter().step_by(stride) {
        let len = a.distance(*b);
        let n = (len / spacing).ceil().max(1.0);
        samples.extend((0..n as usize).map(|k| (a.lerp(*b, (k as f64 + 0.5) / n), len / n)));
    }
    let kept_at = reached(&samples, &plan_edges(plan, solids), reach);
    let kept: f64 = samples
        .iter()
        .zip(&kept_at)
        .filter(|(_, k)| **k)
        .map(|((_, w), _)| w)
        .sum();
    let kept = if judged > 0.0 {
        (kept / judged).clamp(0.0, 1.0)
    } else {
        1.0
    };
    DetailScore {
        sharp_edges: total,
        kept,
        value: 1.0 - DETAILS_WEIGHT * (1.0 - kept),
    }
}

/// The model's sharp edges (two faces turning by more than [`SHARP_DEG`]), as segments in
/// the topology's edge order.
fn sharp_edges(mesh: &Mesh) -> Vec<(DVec3, DVec3)> {
    let cos = SHARP_DEG.to_radians().cos();
    let topo = &mesh.topology;
    (0..topo.edges.len() as u32)
        .filter_map(|e| {
            let corners = topo.edge_corners(e);
            let [f, g] = [corners.first()?, corners.get(1)?].map(|c| *c as usize / 3);
            let (nf, ng) = (mesh.normals[f], mesh.normals[g]);
            // Degenerate triangles have no normal to turn by.
            if corners.len() != 2 || nf.length_squared() < 0.25 || ng.length_squared() < 0.25 || nf.dot(ng) >= cos {
                return None;
            }
            let [a, b] = topo.edges[e as usize].map(|v| mesh.vertices[v as usize]);
            Some((a, b))
        })
        .collect()
}

/// The plan's edges in the model: every piece's outline and holes at both faces, and each
/// flat part's score marks on their face.
fn plan_edges(plan: &Plan, solids: &[Solid]) -> Vec<(DVec3, DVec3)> {
    let mut out = Vec::new();
    for solid in solids {
        for piece in &solid.pieces {
            for z in [0.0, piece.thickness] {
                for ring in std::iter::once(&piece.polygon.outer).chain(&piece.polygon.holes) {
                    push_ring(&mut out, ring, |q| piece.frame.to_model(q.extend(z)), true);
                }
            }
        }
    }
    for part in &plan.parts {
        out.extend(score_marks(part, solids));
    }
    out
}

/// A flat part's score marks on the face they belong on, in the model (a bent part's marks
/// are its hinge's and stay in its flat).
fn score_marks(part: &PlanPart, solids: &[Solid]) -> Vec<(DVec3, DVec3)> {
    let Some(piece) = solids.iter().find(|s| s.id == part.id).and_then(one_piece) else {
        return Vec::new();
    };
    let mut out = Vec::new();
    for mark in part.marks.iter().filter(|m| m.kind == MarkKind::Score) {
        let z = if mark.side == Some(MarkSide::Bottom) {
            piece.thickness
        } else {
            0.0
        };
        push_ring(&mut out, &mark.path, |q| piece.frame.to_model(q.extend(z)), false);
    }
    out
}

/// The only piece of a flat part's solid.
fn one_piece(solid: &Solid) -> Option<&Slab> {
    match solid.pieces.as_slice() {
        [piece] => Some(piece),
        _ => None,
    }
}

/// The segments of a polyline (closed when `closed`) mapped into the model by `to_model`.
fn push_ring(out: &mut Vec<(DVec3, DVec3)>, ring: &[DVec2], to_model: impl Fn(DVec2) -> DVec3, closed: bool) {
    let points: Vec<DVec3> = ring.iter().map(|q| to_model(*q)).collect();
    let n = points.len();
    let segments = if closed { n } else { n.saturating_sub(1) };
    out.extend((0..segments).map(|i| (points[i], points[(i + 1) % n])));
}

/// Which of `samples` lie within `reach` of some segment. The samples (at most
/// [`MAX_SAMPLES`]) are binned on a grid of cells 3·reach wide; each segment is walked in
/// steps of `reach`, and a sample within reach of the segment is within 1.5·reach of some
/// step, so in one of the at most 8 cells the box of that half-width around the step meets.
fn reached(samples: &[(DVec3, f64)], segments: &[(DVec3, DVec3)], reach: f64) -> Vec<bool> {
    let cell = 3.0 * reach;
    let mut grid: std::collections::HashMap<[i64; 3], Vec<u32>> = std::collections::HashMap::new();
    for (i, (p, _)) in samples.iter().enumerate() {
        grid.entry(key(*p, cell)).or_default().push(i as u32);
    }
    let mut kept = vec![false; samples.len()];
    let mut cells: Vec<[i64; 3]> = Vec::new();
    for &(a, b) in segments {
        cells.clear();
        let steps = (a.distance(b) / reach).ceil().max(1.0) as usize;
        for k in 0..=steps {
            let p = a.lerp(b, k as f64 / steps as f64);
            let (lo, hi) = (key(p - 1.5 * reach, cell), key(p + 1.5 * reach, cell));
            for x in lo[0]..=hi[0] {
                for y in lo[1]..=hi[1] {
                    for z in lo[2]..=hi[2] {
                        if !cells.contains(&[x, y, z]) {
                            cells.push([x, y, z]);
                        }
                    }
                }
            }
        }
        for c in &cells {
            for &i in grid.get(c).into_iter().flatten() {
                let i = i as usize;
                kept[i] = kept[i] || distance_to_segment(samples[i].0, a, b) <= reach;
            }
        }
    }
    kept
}

/// The grid cell of `p`.
fn key(p: DVec3, cell: f64) -> [i64; 3] {
    (p / cell).floor().to_array().map(|c| c as i64)
}

/// The distance from `p` to the segment `ab`.
fn distance_to_segment(p: DVec3, a: DVec3, b: DVec3) -> f64 {
    let ab = b - a;
    let len2 = ab.length_squared();
    let t = if len2 > 0.0 {
        ((p - a).dot(ab) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    p.distance(a + ab * t)
}
