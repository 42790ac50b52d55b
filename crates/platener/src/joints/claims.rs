//! Every volume to one part: where a plate's growth (its fingers, and what joins them to it)
//! reaches into another part, it is cut back.
//!
//! Fingers are decided joint by joint, and at a box corner the three joints agree on who owns
//! the corner's cube. Where four or more plates meet at a vertex (a low-poly ball) two plates
//! with no joint between them can each own the end finger of a joint with a common
//! neighbour, over the same corner of it. The lower-ranked plate gives way (the higher-ranked
//! one owns the ends of its joints too); a plate's own outline never does.

use std::collections::BTreeMap;

use glam::DVec3;
use platener_geom::boolean::difference;
use platener_geom::offset::{offset, opening};
use platener_geom::polygon::total_area;
use platener_geom::slab::Slab;
use platener_geom::{GridError, Polygon};

use super::fingers::{HAIRLINE, of_plate};
use crate::plates::Plate;

/// Overlaps smaller than this (mm²) are grid noise.
const NOISE_AREA: f64 = 1e-3;

fn slab(plate: &Plate, polygon: Polygon) -> Slab {
    Slab {
        frame: plate.frame,
        polygon,
        thickness: plate.thickness,
    }
}

/// The model-space box of a part.
fn bounds(plate: &Plate, outline: &Polygon) -> (DVec3, DVec3) {
    let (lo, hi) = outline.bounds();
    let mut b = (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY));
    for x in [lo.x, hi.x] {
        for y in [lo.y, hi.y] {
            for z in [0.0, plate.thickness] {
                let q = plate.frame.to_model(DVec3::new(x, y, z));
                b = (b.0.min(q), b.1.max(q));
            }
        }
    }
    b
}

/// The joint regions between two plates, in each one's plane: what their joints decided.
pub(super) type Decided = BTreeMap<(usize, usize), [Vec<Polygon>; 2]>;

/// Cuts `j`'s growth back where it meets part `i`, outside what a joint between them decided;
/// whether it changed.
fn give_way(
    plates: &[Plate],
    outlines: &mut [Polygon],
    decided: &Decided,
    j: usize,
    i: usize,
) -> Result<bool, GridError> {
    let (pj, pi) = (&plates[j], &plates[i]);
    let mut own = vec![pj.polygon.clone()];
    if let Some(regions) = decided.get(&(i.min(j), i.max(j))) {
        own.extend(regions[usize::from(j > i)].iter().cloned());
    }
    let growth = difference(std::slice::from_ref(&outlines[j]), &own)?;
    if total_area(&growth) < NOISE_AREA {
        return Ok(false);
    }
    let other = slab(pi, outlines[i].clone());
    let mut cut = Vec::new();
    for g in growth {
        cut.extend(slab(pj, g).columns_meeting(&other, 1e-3)?);
    }
    if total_area(&cut) < NOISE_AREA {
        return Ok(false);
    }
    let pieces = opening(&difference(std::slice::from_ref(&outlines[j]), &cut)?, HAIRLINE)?;
    if let Some(main) = of_plate(pj, pieces)?.into_iter().next() {
        outlines[j] = main;
    }
    Ok(true)
}

/// Cuts back the growth of every part that reaches into another, lower-ranked (higher index)
/// first, except where a joint between the two decided who owns what (`decided`; JimJoints'
/// barbs overlap there on purpose, and the test here is by columns, which at oblique angles
/// takes a little more than the overlap). Returns how many parts gave way somewhere.
pub(super) fn settle(plates: &[Plate], outlines: &mut [Polygon], decided: &Decided) -> Result<usize, GridError> {
    let boxes: Vec<(DVec3, DVec3)> = plates.iter().zip(outlines.iter()).map(|(p, o)| bounds(p, o)).collect();
    let mut order: Vec<usize> = (0..plates.len()).collect();
    order.sort_by(|&a, &b| boxes[a].0.x.total_cmp(&boxes[b].0.x).then(a.cmp(&b)));
    let mut pairs = Vec::new();
    for (k, &a) in order.iter().enumerate() {
        for &b in &order[k + 1..] {
            if boxes[b].0.x > boxes[a].1.x {
                break;
            }
            if boxes[a].0.cmple(boxes[b].1).all() && boxes[b].0.cmple(boxes[a].1).all() {
                pairs.push((a.min(b), a.max(b)));
            }
        }
    }
    pairs.sort_unstable();
    let mut changed = vec![false; plates.len()];
    for (i, j) in pairs {
        changed[j] |= give_way(plates, outlines, decided, j, i)?;
        changed[i] |= give_way(plates, outlines, decided, i, j)?;
    }
    Ok(changed.iter().filter(|&&c| c).count())
}

/// Whether parts `a` and `b` still hold each other: they touch (within a twentieth of a
/// millimetre) along at least `length` mm, or overlap.
pub(super) fn meet(plates: &[Plate], outlines: &[Polygon], a: usize, b: usize, length: f64) -> Result<bool, GridError> {
    const TOUCH: f64 = 0.05;
    let grown = offset(std::slice::from_ref(&outlines[a]), TOUCH)?;
    let other = slab(&plates[b], outlines[b].clone());
    let mut area = 0.0;
    for g in grown {
        area += total_area(&slab(&plates[a], g).columns_meeting(&other, -TOUCH)?);
    }
    Ok(area >= TOUCH * length)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::joints::tests::plate;
    use platener_geom::Frame;
    use platener_geom::polygon::rect;

    /// A 20 × 20 floor (z 0–3) and a wall standing on it (x 10–13, its plane's y is the model's
    /// z), whose outline has grown 8 mm down through the floor.
    fn floor_and_wall() -> (Vec<Plate>, Vec<Polygon>) {
        let floor = plate(
            Frame::on_plane(DVec3::ZERO, DVec3::Z),
            Polygon::new(rect(0.0, 0.0, 20.0, 20.0)),
        );
        let wall = plate(
            Frame::on_plane(DVec3::new(10.0, 0.0, 0.0), DVec3::X),
            Polygon::new(rect(0.0, 3.0, 20.0, 20.0)),
        );
        let grown = Polygon::new(rect(0.0, -5.0, 20.0, 20.0));
        let outlines = vec![floor.polygon.clone(), grown];
        (vec![floor, wall], outlines)
    }

    #[test]
    fn growth_into_a_part_with_no_joint_is_cut_back_to_the_plate() {
        let (plates, mut outlines) = floor_and_wall();
        assert_eq!(settle(&plates, &mut outlines, &Decided::new()).expect("grid"), 1);
        // The floor keeps everything; the wall loses what passed through the floor, and what
        // hung below it lost its hold on the wall.
        assert!((outlines[0].area() - 400.0).abs() < 1e-6);
        assert!((outlines[1].area() - 340.0).abs() < 1e-3, "{}", outlines[1].area());
        let (lo, _) = outlines[1].bounds();
        assert!((lo.y - 3.0).abs() < 1e-3, "{lo:?}");
        assert!(meet(&plates, &outlines, 1, 0, 1.0).expect("grid"));
    }

    #[test]
    fn what_a_joint_between_the_two_decided_stays() {
        let (plates, mut outlines) = floor_and_wall();
        let mut decided = Decided::new();
        decided.insert((0, 1), [Vec::new(), vec![Polygon::new(rect(0.0, -5.0, 20.0, 3.0))]]);
        let before = outlines.clone();
        assert_eq!(settle(&plates, &mut outlines, &decided).expect("grid"), 0);
        assert_eq!(outlines, before);
    }

    #[test]
    fn parts_a_millimetre_apart_do_not_meet() {
        let (plates, mut outlines) = floor_and_wall();
        outlines[1] = Polygon::new(rect(0.0, 4.0, 20.0, 20.0));
        assert!(!meet(&plates, &outlines, 1, 0, 1.0).expect("grid"));
        assert!(!meet(&plates, &outlines, 0, 1, 1.0).expect("grid"));
    }
}
