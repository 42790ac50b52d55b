//! Joints across a chamfer: plates grown across a gap (see [`super::connect::growth`]) also
//! meet where a third plate lies in that gap, and such a joint would cut the third plate away.

use glam::DVec3;
use platener_geom::boolean::intersection;
use platener_geom::offset::offset;
use platener_geom::polygon::total_area;
use platener_geom::{GridError, Polygon};

use super::connect::Overlap;
use crate::plates::Plate;

/// Which joints in `raw` bridge a third plate: the two plates do not reach their joint region
/// (they were grown across a gap), while each reaches its joint with a third plate along a
/// parallel line apart from theirs (more than `near`), over the same region. That third plate
/// is a bevel or chamfer between them (the 12.7 mm plate's chamfered rim). A filleted corner
/// has no such plate, and a "Y" of three plates is one line.
pub(super) fn bridging(plates: &[Plate], raw: &[Overlap], near: f64) -> Result<Vec<bool>, GridError> {
    let cos_max = 1f64.to_radians().cos();
    let mut of_plate: Vec<Vec<usize>> = vec![Vec::new(); plates.len()];
    for (k, r) in raw.iter().enumerate() {
        of_plate[r.a].push(k);
        of_plate[r.b].push(k);
    }
    let centres: Vec<DVec3> = raw.iter().map(|r| r.centre(plates)).collect();
    // Parallel lines apart: the cheap test, before any geometry.
    let beside = |k: usize, x: usize| {
        let off = centres[x] - centres[k];
        let axis = raw[k].axis;
        raw[x].axis.dot(axis).abs() >= cos_max && (off - axis * off.dot(axis)).length() > near
    };
    let overlap = |k: usize, x: usize, p: usize| -> Result<bool, GridError> {
        let (mine, theirs) = (raw[k].in_plate(p), raw[x].in_plate(p));
        let shared = intersection(std::slice::from_ref(mine), std::slice::from_ref(theirs))?;
        Ok(total_area(&shared) > 1e-3 * mine.area())
    };
    // Whether a joint's regions touch both its plates (computed when first asked).
    let mut direct: Vec<Option<bool>> = vec![None; raw.len()];
    let mut touched: Vec<Option<Vec<Polygon>>> = vec![None; plates.len()];
    let mut is_direct = |k: usize| -> Result<bool, GridError> {
        if let Some(d) = direct[k] {
            return Ok(d);
        }
        let mut d = true;
        for p in [raw[k].a, raw[k].b] {
            if touched[p].is_none() {
                touched[p] = Some(offset(std::slice::from_ref(&plates[p].polygon), 0.05)?);
            }
            let near_plate = touched[p].as_deref().unwrap_or_default();
            d &= total_area(&intersection(std::slice::from_ref(raw[k].in_plate(p)), near_plate)?) > 0.01;
        }
        direct[k] = Some(d);
        Ok(d)
    };
    let mut out = vec![false; raw.len()];
    for (k, r) in raw.iter().enumerate() {
        'third: for &x in &of_plate[r.a] {
            let Some(c) = raw[x].other(r.a).filter(|&c| c != r.b) else {
                continue;
            };
            if !beside(k, x) {
                continue;
            }
            for &y in of_plate[r.b].iter().filter(|&&y| raw[y].other(r.b) == Some(c)) {
                if beside(k, y)
                    && !is_direct(k)?
                    && is_direct(x)?
                    && is_direct(y)?
                    && overlap(k, x, r.a)?
                    && overlap(k, y, r.b)?
                {
                    out[k] = true;
                    break 'third;
                }
            }
        }
    }
    Ok(out)
}
