//! Cross-sections of the indexed mesh at every layer's mid-plane, in one pass over the
//! triangles: a helper below the steps (issue 33) that the stacked, interlocked and layers
//! steps slice with and the plates step sections raised details with.
//!
//! Each triangle is intersected only with the planes its height range spans: the first such
//! plane follows from its lowest corner by one division, and the planes above it are visited
//! until its highest corner; the (plane, segment) pairs are then bucketed by one parallel sort.
//! Work is linear in triangles plus segments, never triangles × planes.
//!
//! **Points on a plane** (symbolic perturbation): a vertex counts as *above* a plane when its
//! height is at least the plane's, as if every vertex on the plane were lifted by an
//! infinitesimal amount (equivalently, the plane lowered). A triangle lying in a plane is then
//! entirely above it and yields no segment; its neighbours decide the outline, which is
//! therefore always the limit of the cross-section just below the plane. Every triangle that crosses has exactly one corner
//! edge going down through the plane and one going up, so every segment is well defined.
//!
//! **Shared crossing points**: the point where a plane crosses a mesh edge is computed from
//! the edge's two vertices in index order, so both triangles of the edge get the very same
//! point, and a vertex on the plane is returned exactly.

use glam::{DVec2, DVec3};
use platener_geom::Ring;
use platener_geom::polygon::{remove_straight_vertices, signed_area2};
use rayon::prelude::*;
use serde::Serialize;

mod fill;
pub(crate) mod loops;
mod plan;

pub use fill::fill;
pub use loops::LoopStats;
use loops::{Marked, OpenChain};
pub use plan::{AxisChoice, SlicePlan};

use crate::mesh::Mesh;

/// One triangle's cut by one plane: from the crossing of edge `from` (where the surface goes
/// down through the plane, walking the triangle's winding) to the crossing of edge `to`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub(crate) struct Segment {
    /// The plane (layer index).
    pub plane: u32,
    /// The mesh edge where the segment starts.
    pub from: u32,
    /// The mesh edge where it ends.
    pub to: u32,
    /// The triangle.
    pub face: u32,
}

/// One closed loop of a cross-section, in the stack's 2D frame.
#[derive(Debug, Clone, Serialize)]
pub struct SliceLoop {
    /// The loop, without vertices on straight runs; counter-clockwise around material when the
    /// mesh is wound outwards.
    pub points: Ring,
    /// The mesh body (component) it was cut from.
    pub component: u32,
    /// Share of its length cut from marked triangles ([`slice_marked`]; 0 when none are).
    #[serde(skip)]
    pub marked: f64,
}

/// Every plane's loops.
#[derive(Debug, Clone, Serialize)]
pub struct Sliced {
    /// Where the planes are.
    pub plan: SlicePlan,
    /// Per plane (layer), its loops.
    pub loops: Vec<Vec<SliceLoop>>,
    /// How the loops closed, summed over planes.
    pub stats: LoopStats,
}

/// Open chains are joined across holes in the surface up to this share of the model's
/// diagonal (and at least one layer thickness): a hole larger than that is a missing part of
/// the model, not a defect to patch.
pub const MAX_GAP_SHARE: f64 = 0.25;

/// Cuts `mesh` at every mid-plane of `plan`; loops lose vertices within `tolerance` (mm) of a
/// straight run. Open chains (holes in the surface) are closed across gaps up to
/// [`MAX_GAP_SHARE`] of the model's diagonal.
pub fn slice(mesh: &Mesh, plan: &SlicePlan, tolerance: f64) -> Sliced {
    slice_marked(mesh, plan, tolerance, &[])
}

/// [`slice`], with each loop's share of length cut from the triangles `marked` says (by
/// triangle index; missing entries are unmarked): the classifier's `layers` step keeps the
/// loops its spheres and freeforms make.
pub(crate) fn slice_marked(mesh: &Mesh, plan: &SlicePlan, tolerance: f64, marked: &[bool]) -> Sliced {
    let local: Vec<DVec3> = mesh.vertices.par_iter().map(|p| plan.frame.to_local(*p)).collect();
    let gap = local
        .par_iter()
        .map(|p| (*p, *p))
        .reduce_with(|(a, b), (c, d)| (a.min(c), b.max(d)))
        .map_or(0.0, |(lo, hi)| MAX_GAP_SHARE * lo.distance(hi))
        .max(plan.thickness);
    let segments = segments(mesh, &local, plan);
    // Bucket boundaries: segments are sorted by plane.
    let mut starts = vec![0usize; plan.count + 1];
    for (k, start) in starts.iter_mut().enumerate() {
        *start = segments.partition_point(|s| (s.plane as usize) < k);
    }
    let per_plane: Vec<(Vec<SliceLoop>, LoopStats)> = (0..plan.count)
        .into_par_iter()
        .map(|k| {
            let cut = Cut {
                mesh,
                local: &local,
                plan,
                marked,
            };
            plane_loops(&cut, k, &segments[starts[k]..starts[k + 1]], tolerance, gap)
        })
        .collect();
    let mut stats = LoopStats::default();
    let loops = per_plane
        .into_iter()
        .map(|(l, s)| {
            stats += s;
            l
        })
        .collect();
    Sliced {
        plan: *plan,
        loops,
        stats,
    }
}

/// The first plane strictly above height `z`.
fn first_plane_above(plan: &SlicePlan, z: f64) -> usize {
    let guess = (z / plan.thickness - 0.5).floor() + 1.0;
    let mut k = if guess.is_finite() {
        guess.clamp(0.0, plan.count as f64) as usize
    } else {
        0
    };
    // The division may round either way; the comparisons below are the definition.
    while k > 0 && plan.plane(k - 1) > z {
        k -= 1;
    }
    while k < plan.count && plan.plane(k) <= z {
        k += 1;
    }
    k
}

/// Every (plane, triangle) segment, sorted by plane, then start edge.
pub(crate) fn segments(mesh: &Mesh, local: &[DVec3], plan: &SlicePlan) -> Vec<Segment> {
    let fe = &mesh.topology.face_edges;
    let mut out: Vec<Segment> = mesh
        .triangles
        .par_iter()
        .enumerate()
        .fold(Vec::new, |mut acc, (f, tri)| {
            let z = tri.map(|v| local[v as usize].z);
            let (lo, hi) = (z[0].min(z[1]).min(z[2]), z[0].max(z[1]).max(z[2]));
            let mut k = first_plane_above(plan, lo);
            while k < plan.count && plan.plane(k) <= hi {
                let p = plan.plane(k);
                let above = z.map(|z| z >= p);
                let (mut from, mut to) = (0, 0);
                for c in 0..3 {
                    let d = (c + 1) % 3;
                    if above[c] && !above[d] {
                        from = fe[f][c];
                    } else if !above[c] && above[d] {
                        to = fe[f][c];
                    }
                }
                acc.push(Segment {
                    plane: k as u32,
                    from,
                    to,
                    face: f as u32,
                });
                k += 1;
            }
            acc
        })
        .reduce(Vec::new, |mut a, mut b| {
            a.append(&mut b);
            a
        });
    out.par_sort_unstable();
    out
}

/// Where plane height `p` crosses the edge `[a, b]` (vertex indices, in index order), in 2D.
fn crossing(local: &[DVec3], edge: [u32; 2], p: f64) -> DVec2 {
    let (a, b) = (local[edge[0] as usize], local[edge[1] as usize]);
    // A vertex on the plane counts as above: return it exactly.
    if a.z == p {
        return a.truncate();
    }
    if b.z == p {
        return b.truncate();
    }
    let t = (p - a.z) / (b.z - a.z);
    a.truncate() + (b.truncate() - a.truncate()) * t
}

/// What a plane's loops are cut from: the mesh, its vertices in the stack frame, the planes
/// and the marked triangles.
struct Cut<'a> {
    mesh: &'a Mesh,
    local: &'a [DVec3],
    plan: &'a SlicePlan,
    marked: &'a [bool],
}

impl Cut<'_> {
    /// The length of the chain through `points` (closed: back to the first) and the part of
    /// it cut from marked triangles; segment i runs from point i and lies in `faces[i]`.
    fn marked(&self, points: &[DVec2], faces: &[u32]) -> Marked {
        let mut m = Marked::default();
        for (i, &f) in faces.iter().enumerate() {
            let d = points[i].distance(points[(i + 1) % points.len()]);
            m.length += d;
            if self.marked.get(f as usize).copied().unwrap_or(false) {
                m.marked += d;
            }
        }
        m
    }
}

/// The loops of plane `k` from its segments (sorted by start edge).
fn plane_loops(cut: &Cut<'_>, k: usize, segments: &[Segment], tolerance: f64, gap: f64) -> (Vec<SliceLoop>, LoopStats) {
    let p = cut.plan.plane(k);
    let point = |e: u32| crossing(cut.local, cut.mesh.topology.edges[e as usize], p);
    let chains = loops::chain(segments);
    let mut closed: Vec<(Ring, u32, Marked)> = Vec::new();
    let mut open: Vec<OpenChain> = Vec::new();
    for c in chains {
        let component = cut.mesh.component.get(c.faces[0] as usize).copied().unwrap_or(0);
        let points: Ring = c.edges.iter().map(|&e| point(e)).collect();
        let marked = cut.marked(&points, &c.faces);
        if c.closed {
            closed.push((points, component, marked));
        } else {
            open.push(OpenChain {
                points,
                component,
                marked,
            });
        }
    }
    let (bridged, mut stats) = loops::close_gaps(open, gap);
    stats.closed += closed.len();
    let loops = closed
        .into_iter()
        .chain(bridged)
        .filter_map(|(points, component, marked)| {
            let ring = clean_ring(&points, tolerance);
            (ring.len() >= 3 && signed_area2(&ring) != 0.0).then_some(SliceLoop {
                points: ring,
                component,
                marked: marked.share(),
            })
        })
        .collect();
    (loops, stats)
}

/// `ring` without repeated points and without vertices on straight runs.
fn clean_ring(ring: &[DVec2], tolerance: f64) -> Ring {
    let mut out: Ring = Vec::with_capacity(ring.len());
    for &p in ring {
        if out.last() != Some(&p) {
            out.push(p);
        }
    }
    while out.len() > 1 && out.first() == out.last() {
        out.pop();
    }
    remove_straight_vertices(&out, tolerance)
}

/// The model's material in one plane: the cross-section of `mesh` at local height `z` of
/// `frame`, filled as the stacked method fills a layer, in `frame`'s 2D coordinates. The plate
/// method uses it to tell holes through a plate from features on one of its faces.
pub(crate) fn section(
    mesh: &Mesh,
    frame: &platener_geom::Frame,
    z: f64,
    tolerance: f64,
) -> Result<Vec<platener_geom::Polygon>, platener_geom::GridError> {
    // One layer of thickness 1 has its mid-plane at local 0.5: move the frame so it lies at `z`.
    let plan = SlicePlan {
        frame: frame.shifted(z - 0.5),
        thickness: 1.0,
        count: 1,
        choice: AxisChoice::Given,
    };
    let sliced = slice(mesh, &plan, tolerance);
    fill(&sliced.loops[0])
}
