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
        piece_cells(piece, step, layers, None, &mut out);
    }
    (out, step * step * dz)
}

/// The cell centres of [`cells`] that lie in the model box `(lo, hi)`: the same grid, only
/// visited where the box falls. Whether two plates meet asks only about their contact, and
/// a 250 mm floor's 150 000 centres, tested for each of its 40 joints, were most of a minute.
pub(crate) fn cells_near(s: &Solid, step: f64, near: (DVec3, DVec3)) -> Vec<DVec3> {
    let layers = ((s.thickness / step).ceil() as usize).max(1);
    let mut out = Vec::new();
    for piece in &s.pieces {
        piece_cells(piece, step, layers, Some(near), &mut out);
    }
    out.retain(|p| p.cmpge(near.0).all() && p.cmple(near.1).all());
    out
}

/// The cell centres of one piece, `layers` through its thickness; with `near`, only the grid
/// columns whose local box meets that model box (the grid stays anchored where it is).
fn piece_cells(piece: &Slab, step: f64, layers: usize, near: Option<(DVec3, DVec3)>, out: &mut Vec<DVec3>) {
    let (lo, hi) = piece.polygon.bounds();
    let dz = piece.thickness / layers as f64;
    let (nx, ny) = (
        ((hi.x - lo.x) / step).ceil() as usize,
        ((hi.y - lo.y) / step).ceil() as usize,
    );
    let (mut i_range, mut j_range) = (0..=nx, 0..=ny);
    if let Some(near) = near {
        let (a, b) = local_box(piece, near);
        let index = |v: f64, origin: f64, shift: f64| ((v - origin) / step - 0.5 - shift).clamp(0.0, 1e9);
        i_range = (index(a.x, lo.x, SHIFT).floor() as usize)..=(index(b.x, lo.x, SHIFT).ceil() as usize).min(nx);
        j_range = (index(a.y, lo.y, -SHIFT).floor() as usize)..=(index(b.y, lo.y, -SHIFT).ceil() as usize).min(ny);
    }
    for i in i_range {
        for j in j_range.clone() {
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

/// The 2D box, in `piece`'s frame, of the model box `(lo, hi)`'s eight corners.
fn local_box(piece: &Slab, (lo, hi): (DVec3, DVec3)) -> (DVec2, DVec2) {
    platener_geom::boxes::bounds2((0..8).map(|k| {
        let corner = DVec3::new(
            if k & 1 == 0 { lo.x } else { hi.x },
            if k & 2 == 0 { lo.y } else { hi.y },
            if k & 4 == 0 { lo.z } else { hi.z },
        );
        piece.frame.to_local(corner).truncate()
    }))
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

/// SplitMix64's finaliser: a fixed, well-spread hash of `x`, so the same plan always samples
/// the same centres.
fn mix(x: u64) -> u64 {
    let mut z = x.wrapping_add(0x9E37_79B9_7F4A_7C15);
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

/// The most cell centres [`volume_inside`] tests (about): one in k of the analysis' cells,
/// chosen by a hash of their index. Ray parity over three axes costs about a
/// microsecond a point; 100 000 centres of a 6-plate box were half its conversion's time, and
/// the share changes by well under a percent.
pub const VOLUME_SAMPLES: usize = 16_384;

/// Share of the parts' cell centres (`cells`, as [`cells`] made them) inside the model
/// ([`Inside`]: ray parity voted over three axes).
pub(crate) fn volume_inside(mesh: &Mesh, cells: &[(Vec<DVec3>, f64)]) -> f64 {
    let inside = Inside::new(&mesh.vertices, &mesh.triangles);
    let total: usize = cells.iter().map(|c| c.0.len()).sum();
    let keep = total.div_ceil(VOLUME_SAMPLES).max(1) as u64;
    let (mut hits, mut tested) = (0usize, 0usize);
    // Every k-th centre by a hash of its index, not by its place in the list: a plain stride
    // that is a multiple of the layers through a part's thickness would test one layer only
    // (a textured box's plates, standing proud by a third, measured all inside).
    for (i, p) in cells.iter().flat_map(|c| c.0.iter()).enumerate() {
        if mix(i as u64).is_multiple_of(keep) {
            tested += 1;
            hits += usize::from(inside.contains(*p));
        }
    }
    if tested > 0 { hits as f64 / tested as f64 } else { 0.0 }
}

#[cfg(test)]
mod tests {
    use glam::{DVec2, DVec3};
    use platener_geom::slab::Slab;
    use platener_geom::{Frame, Polygon};
    use proptest::prelude::*;

    use super::{Solid, cells, cells_near};

    proptest! {
        #![proptest_config(ProptestConfig { cases: 48, .. ProptestConfig::default() })]
        /// `cells_near` is exactly the cells of `cells` inside the box, whatever the slab's
        /// frame and the box.
        #[test]
        fn cells_near_are_the_cells_in_the_box(
            (w, h) in (5.0f64..60.0, 5.0f64..60.0),
            (ax, ay, az) in (-1.0f64..1.0, -1.0f64..1.0, -1.0f64..1.0),
            origin in prop::array::uniform3(-20.0f64..20.0),
            corner in prop::array::uniform3(-40.0f64..40.0),
            size in prop::array::uniform3(1.0f64..30.0),
        ) {
            let n = DVec3::new(ax, ay, az + 1e-3).normalize();
            let frame = Frame::on_plane(DVec3::from_array(origin), n);
            let polygon = Polygon::new(vec![
                DVec2::ZERO, DVec2::new(w, 0.0), DVec2::new(w, h * 0.4), DVec2::new(w * 0.5, h), DVec2::new(0.0, h),
            ]);
            let solid = Solid::from_slab(0, Slab { frame, polygon, thickness: 3.0 });
            let lo = DVec3::from_array(corner);
            let hi = lo + DVec3::from_array(size);
            let all: Vec<DVec3> = cells(&solid, 1.0).0.into_iter()
                .filter(|p| p.cmpge(lo).all() && p.cmple(hi).all())
                .collect();
            prop_assert_eq!(cells_near(&solid, 1.0, (lo, hi)), all);
        }
    }
}
