//! Deterministic sampling behind `verify`: regular grids, no randomness, so the same plan
//! always gives the same figures. Volumes are counted on cell centres, which never fall on a
//! part's face when faces lie on the grid, and are accurate to about one step times the
//! contact area.

use glam::{DVec2, DVec3};

use super::{Interference, Solid};
use crate::mesh::Mesh;

/// Fraction of a step the sampling grid is shifted by (1/√2 − 0.5).
const SHIFT: f64 = 0.207_106_781_186_547_5;

/// The sampling step: a third of the thinnest part, at most 1 mm.
pub(super) fn step_for(solids: &[Solid]) -> f64 {
    solids.iter().map(|s| s.thickness / 3.0).fold(1.0, f64::min).max(0.05)
}

fn overlap(a: &(DVec3, DVec3), b: &(DVec3, DVec3), grow: f64) -> bool {
    (a.0 - DVec3::splat(grow)).cmple(b.1).all() && (b.0 - DVec3::splat(grow)).cmple(a.1).all()
}

/// Cell centres of a part's volume (in its frame), with the volume each stands for.
fn cells(s: &Solid, step: f64) -> (Vec<DVec3>, f64) {
    let (mut lo, mut hi) = (DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY));
    for p in &s.rings[0] {
        lo = lo.min(*p);
        hi = hi.max(*p);
    }
    let layers = ((s.thickness / step).ceil() as usize).max(1);
    let dz = s.thickness / layers as f64;
    let (nx, ny) = (
        ((hi.x - lo.x) / step).ceil() as usize,
        ((hi.y - lo.y) / step).ceil() as usize,
    );
    let mut out = Vec::new();
    for i in 0..=nx {
        for j in 0..=ny {
            // Centres shifted by an irrational fraction of a step: never exactly on a face of
            // another part, which CAD models put on round numbers.
            let q = DVec2::new(
                lo.x + (i as f64 + 0.5 + SHIFT) * step,
                lo.y + (j as f64 + 0.5 - SHIFT) * step,
            );
            if s.rings
                .iter()
                .filter(|r| platener_geom::polygon::ring_contains(r, q))
                .count()
                % 2
                == 0
            {
                continue;
            }
            for k in 0..layers {
                let z = (k as f64 + 0.5) * dz;
                out.push(s.origin + s.u * q.x + s.v * q.y + s.n * z);
            }
        }
    }
    (out, step * step * dz)
}

/// Every pair of parts that shares volume, with the volume.
pub(super) fn interference(solids: &[Solid], step: f64) -> Vec<Interference> {
    let mut found = Vec::new();
    for (i, a) in solids.iter().enumerate() {
        let near: Vec<&Solid> = solids[i + 1..]
            .iter()
            .filter(|b| overlap(&a.bounds, &b.bounds, 0.0))
            .collect();
        if near.is_empty() {
            continue;
        }
        let (points, cell) = cells(a, step);
        for b in near {
            let inside = points.iter().filter(|p| b.contains(**p)).count();
            if inside > 0 {
                found.push(Interference {
                    parts: [a.id, b.id],
                    volume: inside as f64 * cell,
                });
            }
        }
    }
    found
}

/// Whether two parts touch or overlap (closer than a tenth of a step anywhere on a's surface
/// grid).
pub(super) fn meet(a: &Solid, b: &Solid, step: f64) -> bool {
    if !overlap(&a.bounds, &b.bounds, step) {
        return false;
    }
    let (points, _) = cells(a, step);
    // Cell centres lie half a step inside a's faces.
    points.iter().any(|p| b.distance(*p) <= step * 0.6)
}

/// Share of the model's surface area within `distance` of some part.
pub(super) fn surface_covered(mesh: &Mesh, solids: &[Solid], distance: f64) -> f64 {
    let (mut covered, mut total) = (0.0, 0.0);
    for f in 0..mesh.triangles.len() {
        let [a, b, c] = mesh.corners(f);
        let area = mesh.areas[f];
        // A regular triangular grid of n² samples, each standing for area / n².
        let n = ((area.sqrt() / distance).ceil() as usize).clamp(1, 64);
        let w = area / (n * n) as f64;
        for i in 0..n {
            for j in 0..n - i {
                for (di, dj) in [(1.0 / 3.0, 1.0 / 3.0), (2.0 / 3.0, 2.0 / 3.0)] {
                    if i + j + 1 == n && di > 0.5 {
                        continue;
                    }
                    let (s, t) = ((i as f64 + di) / n as f64, (j as f64 + dj) / n as f64);
                    let p = a + (b - a) * s + (c - a) * t;
                    total += w;
                    let near = solids
                        .iter()
                        .any(|x| overlap(&(p, p), &x.bounds, distance) && x.distance(p) <= distance);
                    if near {
                        covered += w;
                    }
                }
            }
        }
    }
    if total > 0.0 { covered / total } else { 0.0 }
}

/// Share of the parts' volume inside the model (ray parity along +z, triangles bucketed on
/// an x–y grid so each ray meets only its cell's triangles).
pub(super) fn volume_inside(mesh: &Mesh, solids: &[Solid], step: f64) -> f64 {
    let grid = ZGrid::new(mesh);
    let (mut inside, mut total) = (0usize, 0usize);
    for s in solids {
        let (points, _) = cells(s, step);
        total += points.len();
        inside += points.iter().filter(|p| grid.inside(mesh, **p)).count();
    }
    if total > 0 { inside as f64 / total as f64 } else { 0.0 }
}

struct ZGrid {
    lo: DVec2,
    cell: f64,
    nx: usize,
    ny: usize,
    buckets: Vec<Vec<u32>>,
}

impl ZGrid {
    fn new(mesh: &Mesh) -> Self {
        let (mut lo, mut hi) = (DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY));
        for v in &mesh.vertices {
            lo = lo.min(v.truncate());
            hi = hi.max(v.truncate());
        }
        let n = (mesh.triangles.len() as f64).sqrt().ceil().max(1.0) as usize;
        let cell = ((hi - lo).max_element() / n as f64).max(1e-6);
        let (nx, ny) = (((hi.x - lo.x) / cell) as usize + 1, ((hi.y - lo.y) / cell) as usize + 1);
        let mut buckets = vec![Vec::new(); nx * ny];
        for (f, t) in mesh.triangles.iter().enumerate() {
            let ps = t.map(|i| mesh.vertices[i as usize].truncate());
            let (a, b) = (ps[0].min(ps[1]).min(ps[2]), ps[0].max(ps[1]).max(ps[2]));
            let (i0, j0) = (((a.x - lo.x) / cell) as usize, ((a.y - lo.y) / cell) as usize);
            let (i1, j1) = (((b.x - lo.x) / cell) as usize, ((b.y - lo.y) / cell) as usize);
            for i in i0..=i1.min(nx - 1) {
                for j in j0..=j1.min(ny - 1) {
                    buckets[i * ny + j].push(f as u32);
                }
            }
        }
        Self {
            lo,
            cell,
            nx,
            ny,
            buckets,
        }
    }

    fn inside(&self, mesh: &Mesh, p: DVec3) -> bool {
        let (fi, fj) = ((p.x - self.lo.x) / self.cell, (p.y - self.lo.y) / self.cell);
        if fi < 0.0 || fj < 0.0 || fi as usize >= self.nx || fj as usize >= self.ny {
            return false;
        }
        let q = p.truncate();
        let crossings = self.buckets[fi as usize * self.ny + fj as usize]
            .iter()
            .filter(|&&f| {
                let [a, b, c] = mesh.corners(f as usize);
                let (a2, b2, c2) = (a.truncate(), b.truncate(), c.truncate());
                let d = (b2 - a2).perp_dot(c2 - a2);
                if d.abs() < 1e-12 {
                    return false;
                }
                // Barycentric coordinates of q; half-open on edges so a ray through an edge
                // counts once.
                let s = (q - a2).perp_dot(c2 - a2) / d;
                let t = (b2 - a2).perp_dot(q - a2) / d;
                if s < 0.0 || t < 0.0 || s + t >= 1.0 {
                    return false;
                }
                let z = a.z + (b.z - a.z) * s + (c.z - a.z) * t;
                z > p.z
            })
            .count();
        crossings % 2 == 1
    }
}

/// Groups of parts joined by joints.
pub(super) struct UnionFind(Vec<usize>);

impl UnionFind {
    pub fn new(n: usize) -> Self {
        Self((0..n).collect())
    }
    fn root(&mut self, mut i: usize) -> usize {
        while self.0[i] != i {
            self.0[i] = self.0[self.0[i]];
            i = self.0[i];
        }
        i
    }
    pub fn join(&mut self, a: usize, b: usize) {
        let (ra, rb) = (self.root(a), self.root(b));
        if ra != rb {
            self.0[ra.max(rb)] = ra.min(rb);
        }
    }
    pub fn count(&mut self) -> usize {
        (0..self.0.len()).filter(|&i| self.root(i) == i).count()
    }
}
