//! Every volume to one part: where a plate's growth (its fingers, and what joins them to it)
//! reaches into another part, it is cut back.
//!
//! Fingers are decided joint by joint, and at a box corner the three joints agree on who owns
//! the corner's cube. Where four or more plates meet at a vertex (a low-poly ball) two plates
//! with no joint between them can each own the end finger of a joint with a common
//! neighbour, over the same corner of it. The lower-ranked plate gives way (the higher-ranked
//! one owns the ends of its joints too); a plate's own outline never does.

use std::collections::BTreeMap;

use platener_geom::boolean::{difference, intersection};
use platener_geom::boxes::{Box3, near_pairs};
use platener_geom::offset::{offset, opening};
use platener_geom::polygon::total_area;
use platener_geom::slab::Slab;
use platener_geom::tolerance::OVERLAP_NOISE_AREA;
use platener_geom::{GridError, Polygon, polygon};

use super::connect::Region;
use super::fingers::{HAIRLINE, of_plate};
use crate::plates::Plate;

/// The joint regions between two plates, in each one's plane: what their joints decided.
pub(super) type Decided = BTreeMap<(usize, usize), [Vec<Polygon>; 2]>;

/// What the joints `regions` decided, pair by pair.
pub(super) fn decided(regions: &[Region]) -> Decided {
    let mut out = Decided::new();
    for r in regions {
        let [in_a, in_b] = out.entry((r.a, r.b)).or_default();
        in_a.push(r.in_a.clone());
        in_b.push(r.in_b.clone());
    }
    out
}

/// The label of each joint in `regions` (numbered from 1), or `None` where its parts no longer
/// meet (other joints at a crowded vertex took all of it): that is no joint, and the others are
/// numbered on without it. Also the pairs of plates (1-based, "a–b") left unjoined so.
/// `min_feature`: the narrowest feature in plates of a thickness, the least they must touch.
/// Only joints of parts that gave way (`gave_way`, from [`settle`]) are checked: the others
/// are as their joint cut them.
pub(super) fn labels(
    plates: &[Plate],
    outlines: &[Polygon],
    regions: &[Region],
    gave_way: &[bool],
    min_feature: impl Fn(f64) -> f64,
) -> Result<(Vec<Option<u32>>, Vec<String>), GridError> {
    let mut labels = Vec::with_capacity(regions.len());
    let mut unjoined = Vec::new();
    let mut next = 0;
    for r in regions {
        let length = min_feature(plates[r.a].thickness.max(plates[r.b].thickness));
        let (a, b) = ((r.a, &r.in_a), (r.b, &r.in_b));
        let as_cut = !gave_way[r.a] && !gave_way[r.b];
        if as_cut || meet(plates, outlines, a, b, length)? || meet(plates, outlines, b, a, length)? {
            next += 1;
            labels.push(Some(next));
        } else {
            labels.push(None);
            unjoined.push(format!("{}–{}", r.a + 1, r.b + 1));
        }
    }
    Ok((labels, unjoined))
}

/// The columns of `polygons` (in `plate`'s plane) that meet `other`'s volume: one shadow of
/// `other` for all of them (it does not depend on them, only on the box they lie in).
fn columns_meeting(
    plate: &Plate,
    polygons: &[Polygon],
    other: &Slab,
    clearance: f64,
) -> Result<Vec<Polygon>, GridError> {
    let Some((lo, hi)) = polygons
        .iter()
        .map(Polygon::bounds)
        .reduce(|a, b| (a.0.min(b.0), a.1.max(b.1)))
    else {
        return Ok(Vec::new());
    };
    let cover = plate.slab_of(Polygon::new(polygon::rect(lo.x, lo.y, hi.x, hi.y)));
    let shadow = cover.columns_meeting(other, clearance)?;
    if shadow.is_empty() {
        return Ok(shadow);
    }
    intersection(&shadow, polygons)
}

/// Cuts `j`'s growth (`growth[j]`, kept up to date) back where it meets part `i`, outside what
/// a joint between them decided; whether it changed.
fn give_way(
    plates: &[Plate],
    outlines: &mut [Polygon],
    growth: &mut [Vec<Polygon>],
    decided: &Decided,
    (j, i): (usize, usize),
) -> Result<bool, GridError> {
    let pj = &plates[j];
    let mut mine = growth[j].clone();
    if let Some(regions) = decided.get(&(i.min(j), i.max(j))) {
        mine = difference(&mine, &regions[usize::from(j > i)])?;
    }
    if total_area(&mine) < OVERLAP_NOISE_AREA {
        return Ok(false);
    }
    let cut = columns_meeting(pj, &mine, &plates[i].slab_of(outlines[i].clone()), 1e-3)?;
    if total_area(&cut) < OVERLAP_NOISE_AREA {
        return Ok(false);
    }
    let pieces = opening(&difference(std::slice::from_ref(&outlines[j]), &cut)?, HAIRLINE)?;
    if let Some(main) = of_plate(pj, pieces)?.into_iter().next() {
        outlines[j] = main;
    }
    growth[j] = grown_by(pj, &outlines[j])?;
    Ok(true)
}

/// What of `outline` lies outside `plate`'s own outline.
fn grown_by(plate: &Plate, outline: &Polygon) -> Result<Vec<Polygon>, GridError> {
    let mut g = difference(std::slice::from_ref(outline), std::slice::from_ref(&plate.polygon))?;
    g.retain(|p| p.area() > OVERLAP_NOISE_AREA);
    Ok(g)
}

/// Cuts back the growth of every part that reaches into another, lower-ranked (higher index)
/// first, except where a joint between the two decided who owns what (`decided`; JimJoints'
/// barbs overlap there on purpose, and the test here is by columns, which at oblique angles
/// takes a little more than the overlap). Returns which parts gave way somewhere.
pub(super) fn settle(plates: &[Plate], outlines: &mut [Polygon], decided: &Decided) -> Result<Vec<bool>, GridError> {
    let boxes: Vec<Box3> = plates
        .iter()
        .zip(outlines.iter())
        .map(|(p, o)| p.bounds_of(o))
        .collect();
    let mut growth: Vec<Vec<Polygon>> = plates
        .iter()
        .zip(outlines.iter())
        .map(|(p, o)| grown_by(p, o))
        .collect::<Result<_, _>>()?;
    let mut pairs = near_pairs(&boxes, 0.0);
    pairs.sort_unstable();
    let mut changed = vec![false; plates.len()];
    for (i, j) in pairs {
        if growth[i].is_empty() && growth[j].is_empty() {
            continue;
        }
        changed[j] |= give_way(plates, outlines, &mut growth, decided, (j, i))?;
        changed[i] |= give_way(plates, outlines, &mut growth, decided, (i, j))?;
    }
    Ok(changed)
}

/// Whether parts `a` and `b` still hold each other at their joint (`near_a`, `near_b`: its
/// region in each plane): they touch (within a twentieth of a millimetre) along at least
/// `length` mm there, or overlap.
pub(super) fn meet(
    plates: &[Plate],
    outlines: &[Polygon],
    (a, near_a): (usize, &Polygon),
    (b, near_b): (usize, &Polygon),
    length: f64,
) -> Result<bool, GridError> {
    const TOUCH: f64 = 0.05;
    // Only around the joint: the rest of two large parts is far from each other.
    let local = |p: usize, near: &Polygon| -> Result<Vec<Polygon>, GridError> {
        intersection(
            std::slice::from_ref(&outlines[p]),
            &offset(std::slice::from_ref(near), 1.0)?,
        )
    };
    let grown = offset(&local(a, near_a)?, TOUCH)?;
    let mut area = 0.0;
    for other in local(b, near_b)? {
        area += total_area(&columns_meeting(&plates[a], &grown, &plates[b].slab_of(other), -TOUCH)?);
    }
    Ok(area >= TOUCH * length)
}

#[cfg(test)]
mod tests {
    use glam::DVec3;

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

    /// Where the wall stands on the floor, in the floor's plane and in the wall's.
    fn joint() -> (Polygon, Polygon) {
        (
            Polygon::new(rect(10.0, 0.0, 13.0, 20.0)),
            Polygon::new(rect(0.0, 0.0, 20.0, 3.0)),
        )
    }

    #[test]
    fn growth_into_a_part_with_no_joint_is_cut_back_to_the_plate() {
        let (plates, mut outlines) = floor_and_wall();
        assert_eq!(
            settle(&plates, &mut outlines, &Decided::new()).expect("grid"),
            [false, true]
        );
        // The floor keeps everything; the wall loses what passed through the floor, and what
        // hung below it lost its hold on the wall.
        assert!((outlines[0].area() - 400.0).abs() < 1e-6);
        assert!((outlines[1].area() - 340.0).abs() < 1e-3, "{}", outlines[1].area());
        let (lo, _) = outlines[1].bounds();
        assert!((lo.y - 3.0).abs() < 1e-3, "{lo:?}");
        let (floor, wall) = joint();
        assert!(meet(&plates, &outlines, (1, &wall), (0, &floor), 1.0).expect("grid"));
    }

    #[test]
    fn what_a_joint_between_the_two_decided_stays() {
        let (plates, mut outlines) = floor_and_wall();
        let mut decided = Decided::new();
        decided.insert((0, 1), [Vec::new(), vec![Polygon::new(rect(0.0, -5.0, 20.0, 3.0))]]);
        let before = outlines.clone();
        assert_eq!(settle(&plates, &mut outlines, &decided).expect("grid"), [false, false]);
        assert_eq!(outlines, before);
    }

    #[test]
    fn parts_a_millimetre_apart_do_not_meet() {
        let (plates, mut outlines) = floor_and_wall();
        outlines[1] = Polygon::new(rect(0.0, 4.0, 20.0, 20.0));
        let (floor, wall) = joint();
        assert!(!meet(&plates, &outlines, (1, &wall), (0, &floor), 1.0).expect("grid"));
        assert!(!meet(&plates, &outlines, (0, &floor), (1, &wall), 1.0).expect("grid"));
    }
}
