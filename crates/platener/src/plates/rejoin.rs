//! Rejoining plates that a plate passing through them split in two, or that touch.
//!
//! Two coplanar plates of one thickness on either side of a third plate (a board crossing a
//! divider, or a shelf board ending against a side), or of several side by side (a board
//! under the two walls of a V), were found as two because the third plate's faces cut their
//! faces. If adding the band where the third plate passes through or
//! ends against their plane (within their convex hull) joins them into one piece, they become
//! one plate; the joint step later joins the third plate to it with a cross or T joint.

use platener_geom::boolean::{difference, intersection, union_all};
use platener_geom::boxes::{Box3, near, near_pairs};
use platener_geom::offset::{closing, offset};
use platener_geom::polygon::convex_hull;
use platener_geom::slab::Slab;
use platener_geom::{GridError, Polygon};

use super::{Plate, map_polygon};

/// Same thickness and kind, parallel, and the same mid-plane (the two pieces may have been
/// found from opposite faces, so their normals may point either way).
fn coplanar(a: &Plate, b: &Plate, cos_max: f64, clearance: f64) -> bool {
    let mid = |p: &Plate| p.frame.origin + p.frame.n * (p.thickness / 2.0);
    a.thickness == b.thickness
        && a.kind == b.kind
        && a.frame.n.dot(b.frame.n).abs() >= cos_max
        && (mid(b) - mid(a)).dot(a.frame.n).abs() < clearance.max(1e-3 * a.thickness)
}

/// Tries to join `b` to `a` through some third plate; returns the joined outline (in a's frame).
fn bridge(a: &Plate, b: &Plate, others: &[&Plate], clearance: f64) -> Result<Option<Polygon>, GridError> {
    let b_in_a = map_polygon(&b.polygon, &b.frame, &a.frame);
    let points: Vec<_> = a.polygon.outer.iter().chain(&b_in_a.outer).copied().collect();
    let mut hull = Polygon::new(convex_hull(&points));
    hull.normalize_orientation();
    let region = Slab {
        frame: a.frame,
        polygon: hull,
        thickness: a.thickness,
    };
    // Pieces that already touch (an enclosure's front wall and the lip above it, found from
    // two faces) need no third plate: closing hairline gaps makes them one.
    let mut closed = closing(&union_all(&[a.polygon.clone(), b_in_a.clone()])?, HAIRLINE)?;
    if closed.len() == 1 {
        return Ok(closed.pop());
    }
    let mut bands = Vec::new();
    for third in others {
        // The third plate grown in its plane by a's thickness: a plate that ends against the
        // gap (a shelf board meeting a side) bridges it as well as one passing through.
        let grown = offset(std::slice::from_ref(&third.polygon), a.thickness)?;
        let mut band = Vec::new();
        for polygon in grown {
            band.extend(region.columns_meeting(
                &Slab {
                    frame: third.frame,
                    polygon,
                    thickness: third.thickness,
                },
                clearance,
            )?);
        }
        if band.is_empty() {
            continue;
        }
        if let Some(joined) = joined(a, &b_in_a, &band, &region.polygon)? {
            return Ok(Some(joined));
        }
        bands.push(band);
    }
    // Several plates ending side by side (the two walls of a V standing on a board) bridge the
    // gap together.
    if bands.len() > 1 {
        return joined(a, &b_in_a, &bands.concat(), &region.polygon);
    }
    Ok(None)
}

/// `a` and `b` (in a's frame) joined by `band`, if that makes one piece. The band is widened
/// by a hairline (and the result kept within `hull`): the pieces were trimmed against other
/// plates on the grid and may miss the band by a few µm.
fn joined(a: &Plate, b_in_a: &Polygon, band: &[Polygon], hull: &Polygon) -> Result<Option<Polygon>, GridError> {
    let mut parts = vec![a.polygon.clone(), b_in_a.clone()];
    parts.extend(offset(band, HAIRLINE)?);
    let joined = intersection(&union_all(&parts)?, std::slice::from_ref(hull))?;
    Ok((joined.len() == 1).then(|| joined.into_iter().next()).flatten())
}

/// Gaps (mm) between a piece and a bridging band that are grid noise.
const HAIRLINE: f64 = 0.01;

/// How many pieces of at least t² across a plate's outline holds when every point within `t`
/// of its edge is taken away: more than one where it has a neck narrower than 2·t.
fn pieces(outline: &[Polygon], t: f64) -> Result<usize, GridError> {
    Ok(offset(outline, -t)?.iter().filter(|p| p.area() >= t * t).count())
}

/// A plate that another plate stands on or passes through may have been found with a slit
/// where that plate's foot interrupts its face (an iPad cabinet's base under a diagonal
/// wall: one piece joined by a neck under 1 mm). Where filling the slits (what closing the
/// outline over twice its thickness adds) within half a thickness of the other plate's band
/// (as in [`bridge`]) removes a neck
/// narrower than two thicknesses, the plate is made whole; the joint step then joins the
/// other plate to it with a T. Returns how many plates were mended.
fn fill_slits(plates: &mut [Plate], cos_max: f64, clearance: f64) -> Result<usize, GridError> {
    let mut mended = 0;
    for i in 0..plates.len() {
        let t = plates[i].thickness;
        let before = pieces(std::slice::from_ref(&plates[i].polygon), t)?;
        if before < 2 {
            continue;
        }
        let closed = closing(std::slice::from_ref(&plates[i].polygon), 2.0 * t)?;
        // The slits: what closing over 2·t adds (the other plate's foot may be thinner than
        // the slit its wall left, a 3 mm plate in a 4 mm wall).
        let slits = difference(&closed, std::slice::from_ref(&plates[i].polygon))?;
        let mut filled = vec![plates[i].polygon.clone()];
        for k in 0..plates.len() {
            if k == i || plates[k].frame.n.dot(plates[i].frame.n).abs() >= cos_max {
                continue;
            }
            let band = foot(&plates[i], &closed, &plates[k], clearance)?;
            if band.is_empty() {
                continue;
            }
            let mut parts = filled.clone();
            parts.extend(intersection(&offset(&band, t / 2.0)?, &slits)?);
            let joined = union_all(&parts)?;
            if joined.len() == 1 && pieces(&joined, t)? < pieces(&filled, t)? {
                filled = joined;
            }
        }
        if filled.len() == 1 && pieces(&filled, t)? < before {
            let p = filled.pop().expect("one piece");
            plates[i].area = p.area();
            plates[i].polygon = p;
            mended += 1;
        }
    }
    Ok(mended)
}

/// Where `third`, grown in its plane by the plate's thickness, meets the columns of the
/// plate's `closed` outline: the foot of a plate standing on it or passing through.
fn foot(plate: &Plate, closed: &[Polygon], third: &Plate, clearance: f64) -> Result<Vec<Polygon>, GridError> {
    let mut band = Vec::new();
    for polygon in offset(std::slice::from_ref(&third.polygon), plate.thickness)? {
        let grown = third.slab_of(polygon);
        for piece in closed {
            band.extend(plate.slab_of(piece.clone()).columns_meeting(&grown, clearance)?);
        }
    }
    Ok(band)
}

/// Returns the plates with split pairs rejoined, and how many joins were made.
pub(super) fn rejoin(mut plates: Vec<Plate>, angle: f64, clearance: f64) -> Result<(Vec<Plate>, usize), GridError> {
    let cos_max = angle.cos();
    let mut joins = 0;
    // Split pieces are a plate's footprint apart: one thickness for a plate ending square,
    // more for one ending at a slant or for the two walls of a V (2·t/sin 60° for walls 60°
    // apart). Candidates only: the bridge itself decides.
    let reach = plates.iter().map(|p| p.thickness).fold(0.0, f64::max) * 4.0 + clearance;
    // Repeat until nothing joins: a plate split into three by two dividers needs two rounds.
    'again: loop {
        let bounds: Vec<Box3> = plates.iter().map(Plate::bounds).collect();
        for (i, j) in near_pairs(&bounds, reach) {
            if !coplanar(&plates[i], &plates[j], cos_max, clearance) {
                continue;
            }
            let span = (bounds[i].0.min(bounds[j].0), bounds[i].1.max(bounds[j].1));
            let others: Vec<&Plate> = plates
                .iter()
                .enumerate()
                .filter(|(k, p)| {
                    *k != i
                        && *k != j
                        && p.frame.n.dot(plates[i].frame.n).abs() < cos_max
                        && near(span, bounds[*k], reach)
                })
                .map(|(_, p)| p)
                .collect();
            if let Some(joined) = bridge(&plates[i], &plates[j], &others, clearance)? {
                let b = plates.remove(j);
                let a = &mut plates[i];
                a.area = joined.area();
                a.polygon = joined;
                a.shapes.extend(b.shapes);
                a.shapes.sort_unstable();
                a.shapes.dedup();
                joins += 1;
                continue 'again;
            }
        }
        break;
    }
    joins += fill_slits(&mut plates, cos_max, clearance)?;
    Ok((plates, joins))
}

#[cfg(test)]
mod tests {
    use glam::DVec3;

    use super::*;
    use crate::plates::PlateKind;
    use platener_geom::Frame;
    use platener_geom::polygon::rect;

    fn plate(outline: Polygon) -> Plate {
        Plate {
            kind: PlateKind::Inherent,
            thickness: 3.0,
            frame: Frame::on_plane(DVec3::ZERO, DVec3::Z),
            area: outline.area(),
            polygon: outline,
            shapes: Vec::new(),
        }
    }

    /// A wall and the lip above it, found from two faces: edge to edge, one plate. A piece a
    /// millimetre away stays apart (nothing bridges it).
    #[test]
    fn coplanar_pieces_that_touch_become_one_plate() {
        let wall = plate(Polygon::new(rect(0.0, 0.0, 50.0, 30.0)));
        let lip = plate(Polygon::new(rect(-4.0, 30.0, 54.0, 34.0)));
        let (plates, joins) = rejoin(vec![wall.clone(), lip], 1f64.to_radians(), 0.01).expect("grid");
        assert_eq!((plates.len(), joins), (1, 1));
        assert!(
            (plates[0].area - (50.0 * 30.0 + 58.0 * 4.0)).abs() < 1e-6,
            "{}",
            plates[0].area
        );
        let apart = plate(Polygon::new(rect(-4.0, 31.0, 54.0, 35.0)));
        let (plates, joins) = rejoin(vec![wall, apart], 1f64.to_radians(), 0.01).expect("grid");
        assert_eq!((plates.len(), joins), (2, 0));
    }
}
