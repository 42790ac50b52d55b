//! Deterministic sampling behind the assembly analysis: regular grids, no randomness, so the
//! same plan always gives the same figures. Volumes are counted on cell centres, which never
//! fall on a part's face when faces lie on the grid, and are accurate to about one step times
//! the contact area.

use glam::{DVec2, DVec3};
use platener_geom::slab::Slab;

use super::{Inside, Interference, Solid};
use crate::mesh::Mesh;

/// Fraction of a step the sampling grid is shifted by (1/√2 − 0.5).
const SHIFT: f64 = 0.207_106_781_186_547_5;

/// The sampling step: a third of the thinnest part, at most 1 mm.
pub(super) fn step_for(solids: &[Solid]) -> f64 {
    solids.iter().map(|s| s.thickness / 3.0).fold(1.0, f64::min).max(0.05)
}

/// Whether the boxes of `a` and `b`, `a`'s grown by `grow`, overlap.
pub(super) fn overlap(a: &Solid, b: &Solid, grow: f64) -> bool {
    (a.lo - DVec3::splat(grow)).cmple(b.hi).all() && (b.lo - DVec3::splat(grow)).cmple(a.hi).all()
}

/// Cell centres of a part's volume (in the model), with the volume each stands for: every
/// piece's cells, all of one volume (the pieces share the part's thickness).
pub(crate) fn cells(s: &Solid, step: f64) -> (Vec<DVec3>, f64) {
    let layers = ((s.thickness / step).ceil() as usize).max(1);
    let dz = s.thickness / layers as f64;
    let mut out = Vec::new();
    for piece in &s.pieces {
        piece_cells(piece, step, layers, &mut out);
    }
    (out, step * step * dz)
}

/// The cell centres of one piece, `layers` through its thickness.
fn piece_cells(piece: &Slab, step: f64, layers: usize, out: &mut Vec<DVec3>) {
    let (lo, hi) = piece.polygon.bounds();
    let dz = piece.thickness / layers as f64;
    let (nx, ny) = (
        ((hi.x - lo.x) / step).ceil() as usize,
        ((hi.y - lo.y) / step).ceil() as usize,
    );
    for i in 0..=nx {
        for j in 0..=ny {
            // Centres shifted by an irrational fraction of a step: never exactly on a face of
            // another part, which CAD models put on round numbers.
            let q = DVec2::new(
                lo.x + (i as f64 + 0.5 + SHIFT) * step,
                lo.y + (j as f64 + 0.5 - SHIFT) * step,
            );
            if !piece.polygon.contains(q) {
                continue;
            }
            for k in 0..layers {
                out.push(piece.frame.to_model(DVec3::new(q.x, q.y, (k as f64 + 0.5) * dz)));
            }
        }
    }
}

/// Every pair of parts that shares volume, with the volume; `cells[i]` are part i's cell
/// centres and the volume each stands for.
pub(super) fn interference(solids: &[Solid], cells: &[(Vec<DVec3>, f64)]) -> Vec<Interference> {
    let mut found = Vec::new();
    for (i, a) in solids.iter().enumerate() {
        let (points, cell) = &cells[i];
        for b in solids[i + 1..].iter().filter(|b| overlap(a, b, 0.0)) {
            let inside = points
                .iter()
                .filter(|p| b.near_box(**p, 0.0) && b.contains(**p))
                .count();
            if inside > 0 {
                found.push(Interference {
                    parts: [a.id, b.id],
                    volume: inside as f64 * cell,
                    intended: false,
                });
            }
        }
    }
    found
}

/// Whether part `a` (whose cell centres are `points`) touches or overlaps `b`: some centre
/// within 0.6 step of `b` (centres lie half a step inside a's faces).
pub(super) fn meet(a: &Solid, points: &[DVec3], b: &Solid, step: f64) -> bool {
    overlap(a, b, step) && points.iter().any(|p| b.within(*p, step * 0.6))
}

/// Calls `visit(point, weight, triangle)` for a regular triangular grid of samples over every
/// triangle of the model, spaced about `spacing` apart, each weighted by the area it stands for.
pub(crate) fn surface_samples(mesh: &Mesh, spacing: f64, mut visit: impl FnMut(DVec3, f64, usize)) {
    for f in 0..mesh.triangles.len() {
        let [a, b, c] = mesh.corners(f);
        let area = mesh.areas[f];
        // A regular triangular grid of n² samples, each standing for area / n².
        let n = ((area.sqrt() / spacing).ceil() as usize).clamp(1, 64);
        let w = area / (n * n) as f64;
        for i in 0..n {
            for j in 0..n - i {
                for (di, dj) in [(1.0 / 3.0, 1.0 / 3.0), (2.0 / 3.0, 2.0 / 3.0)] {
                    if i + j + 1 == n && di > 0.5 {
                        continue;
                    }
                    let (s, t) = ((i as f64 + di) / n as f64, (j as f64 + dj) / n as f64);
                    visit(a + (b - a) * s + (c - a) * t, w, f);
                }
            }
        }
    }
}

/// Share of the model's surface area within `distance` of some part.
pub(super) fn surface_covered(mesh: &Mesh, solids: &[Solid], distance: f64) -> f64 {
    let (mut covered, mut total) = (0.0, 0.0);
    surface_samples(mesh, distance, |p, w, _| {
        total += w;
        if solids.iter().any(|x| x.within(p, distance)) {
            covered += w;
        }
    });
    if total > 0.0 { covered / total } else { 0.0 }
}

/// Share of the parts' volume inside the model ([`Inside`]: ray parity voted over three axes).
pub(crate) fn volume_inside(mesh: &Mesh, solids: &[Solid], step: f64) -> f64 {
    let inside = Inside::new(&mesh.vertices, &mesh.triangles);
    let (mut hits, mut total) = (0usize, 0usize);
    for s in solids {
        let (points, _) = cells(s, step);
        total += points.len();
        hits += points.iter().filter(|p| inside.contains(**p)).count();
    }
    if total > 0 { hits as f64 / total as f64 } else { 0.0 }
}
