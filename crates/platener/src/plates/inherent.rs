//! Inherent plates: the material between two opposite faces a sheet thickness apart.
//!
//! Candidate pairs come from [`super::pairs`]. They are taken thinnest gap first (a face's
//! nearest opposite face is the other side of its plate), and each takes only what is still
//! free of both shapes: a shape is consumed only where a plate covers it, and the rest may pair
//! with another face. The plate keeps the model's mid-plane between the two faces.

use std::cell::OnceCell;

use glam::DVec3;
use platener_geom::boolean::{difference, intersection};
use platener_geom::slab::Slab;
use platener_geom::{GridError, Polygon, polygon::total_area};

use super::features::{Face, Feature, Sections, Side};
use super::pairs::{Pair, opposite_pairs};
use super::{Plate, PlateKind, Rejection, cuttable, map_polygon};
use crate::settings::Settings;
use crate::shapes::{Shape, Shapes};

/// The nearest opposite faces each shape has (that overlap it in projection).
#[derive(Debug, Clone, Copy, Default)]
pub(super) struct Nearest {
    /// Nearest face with the material between (a plate candidate).
    pub apart: Option<f64>,
    /// Nearest face with empty space between (a slot or gap).
    pub facing: Option<f64>,
    /// Why a piece of this shape was refused as a plate, if one was.
    pub refused: Option<Rejection>,
}

/// What detection found, per shape and in total.
pub(super) struct Detection {
    /// Plates found so far.
    pub plates: Vec<Plate>,
    /// Per shape: what is still free (not covered by a plate).
    pub remaining: Vec<Vec<Polygon>>,
    /// Per shape: nearest opposite faces.
    pub detail: Vec<Nearest>,
    /// Features on one face of the plates (in the frames they were found in).
    pub features: Vec<Feature>,
}

/// The offered thickness that makes a plate of faces `distance` apart: the nearest offered
/// one with `min_factor·t < distance < max_factor·t`.
pub(super) fn matching_thickness(distance: f64, settings: &Settings) -> Option<f64> {
    let p = &settings.plates;
    settings
        .thicknesses
        .iter()
        .copied()
        .filter(|t| p.min_factor * t < distance && distance < p.max_factor * t)
        // Equally near: the thinner, whatever order the sheets were offered in.
        .min_by(|a, b| {
            (a - distance)
                .abs()
                .total_cmp(&(b - distance).abs())
                .then(a.total_cmp(b))
        })
}

/// The inherent plates of `shapes`: pairs of facing shapes on parallel planes a sheet's
/// thickness apart, thinnest gap first, each taking the parts of both shapes not yet taken.
pub(super) fn find(
    shapes: &Shapes,
    sections: &Sections<'_>,
    center: DVec3,
    settings: &Settings,
) -> Result<Detection, GridError> {
    let list = &shapes.shapes;
    let ps = &settings.plates;
    let t_max = settings.thicknesses.iter().copied().fold(0.0, f64::max);
    // Look further than any plate could be, to say "opposite face at 9 mm" in the report.
    let search = (ps.max_factor * t_max).max(4.0 * t_max);
    let pairs = opposite_pairs(list, ps.parallel_angle_deg.to_radians(), search, center);
    let mut detail = vec![Nearest::default(); list.len()];
    let candidates = candidates(list, pairs, settings, &mut detail)?;
    let mut features = Vec::new();
    let (plates, remaining) = take_plates(list, candidates, sections, settings, &mut detail, &mut features)?;
    Ok(Detection {
        plates,
        remaining,
        detail,
        features,
    })
}

/// The model-space box of each shape's outline.
fn model_boxes(list: &[Shape]) -> Vec<(DVec3, DVec3)> {
    list.iter()
        .map(|s| platener_geom::boxes::bounds3(s.polygon.outer.iter().map(|p| s.frame.to_model_2d(*p))))
        .collect()
}

/// The pairs whose shapes overlap seen along their normal and lie a sheet's thickness apart,
/// with that thickness and the overlap's area: thinnest gap first, then the larger overlap.
/// Every overlapping pair's distance goes into `detail` for the report.
fn candidates(
    list: &[Shape],
    pairs: Vec<Pair>,
    settings: &Settings,
    detail: &mut [Nearest],
) -> Result<Vec<(Pair, f64, f64)>, GridError> {
    let mut candidates: Vec<(Pair, f64, f64)> = Vec::new();
    // Shapes on parallel planes overlap in projection only if their boxes, grown by the
    // distance between the planes, overlap: a cheap test before any boolean.
    let boxes = model_boxes(list);
    for pair in pairs {
        let (ba, bb) = (boxes[pair.a as usize], boxes[pair.b as usize]);
        let grow = DVec3::splat(pair.distance + 1e-6);
        if (ba.0 - grow).cmpgt(bb.1).any() || (bb.0 - grow).cmpgt(ba.1).any() {
            continue;
        }
        let (a, b) = (&list[pair.a as usize], &list[pair.b as usize]);
        let b_in_a = map_polygon(&b.polygon, &b.frame, &a.frame);
        let overlap = total_area(&intersection(std::slice::from_ref(&a.polygon), &[b_in_a])?);
        if overlap <= 0.0 {
            continue;
        }
        for s in [pair.a, pair.b] {
            let slot = if pair.apart {
                &mut detail[s as usize].apart
            } else {
                &mut detail[s as usize].facing
            };
            if slot.is_none_or(|d| pair.distance < d) {
                *slot = Some(pair.distance);
            }
        }
        if pair.apart
            && let Some(t) = matching_thickness(pair.distance, settings)
        {
            candidates.push((pair, t, overlap));
        }
    }
    // Thinnest gap first, then the larger overlap; indices make the order total.
    candidates.sort_by(|x, y| {
        x.0.distance
            .total_cmp(&y.0.distance)
            .then(y.2.total_cmp(&x.2))
            .then((x.0.a, x.0.b).cmp(&(y.0.a, y.0.b)))
    });
    Ok(candidates)
}

/// The plates of the `candidates`, in order: each takes what both its shapes still have in
/// common, where that can be cut, as the model's material at its mid-plane (see
/// [`super::features`]); returns the plates and what remains of each shape.
fn take_plates(
    list: &[Shape],
    candidates: Vec<(Pair, f64, f64)>,
    sections: &Sections<'_>,
    settings: &Settings,
    detail: &mut [Nearest],
    features: &mut Vec<Feature>,
) -> Result<(Vec<Plate>, Vec<Vec<Polygon>>), GridError> {
    let ps = &settings.plates;
    let mut remaining: Vec<Vec<Polygon>> = list.iter().map(|s| vec![s.polygon.clone()]).collect();
    let mut plates = Vec::new();
    for (pair, t, _) in candidates {
        let (ia, ib) = (pair.a as usize, pair.b as usize);
        let (fa, fb) = (list[ia].frame, list[ib].frame);
        let b_in_a: Vec<Polygon> = remaining[ib].iter().map(|p| map_polygon(p, &fb, &fa)).collect();
        let common = intersection(&remaining[ia], &b_in_a)?;
        // Face a is at local z = 0 of its frame, face b at −distance: the plate keeps their
        // mid-plane, so face a lies at z = (distance + t)/2 of the plate's frame.
        let frame = fa.shifted(-(pair.distance + t) / 2.0);
        // Only pieces with holes need the faces (every shape is looked at): made on demand.
        let faces = || {
            vec![
                Face {
                    side: Side::Down,
                    z: (pair.distance + t) / 2.0,
                    shape: in_plane_of(list, ia, &fa),
                },
                Face {
                    side: Side::Up,
                    z: (t - pair.distance) / 2.0,
                    shape: in_plane_of(list, ib, &fa),
                },
            ]
        };
        let mut used = Vec::new();
        for piece in common {
            if let Err(why) = cuttable(&piece, t, ps.min_area) {
                detail[ia].refused.get_or_insert(why);
                detail[ib].refused.get_or_insert(why);
                continue;
            }
            let (solid, found) = sections.solid(piece, &frame, t, faces)?;
            features.extend(found);
            // Islands of material inside a through-hole are plates of their own if they can
            // be cut; the piece itself always can.
            for p in solid.into_iter().filter(|p| cuttable(p, t, ps.min_area).is_ok()) {
                plates.push(Plate {
                    kind: PlateKind::Inherent,
                    thickness: t,
                    frame,
                    area: p.area(),
                    polygon: p.clone(),
                    shapes: vec![pair.a, pair.b],
                });
                used.push(p);
            }
        }
        if !used.is_empty() {
            remaining[ia] = difference(&remaining[ia], &used)?;
            let used_in_b: Vec<Polygon> = used.iter().map(|p| map_polygon(p, &fa, &fb)).collect();
            remaining[ib] = difference(&remaining[ib], &used_in_b)?;
        }
    }
    Ok((plates, remaining))
}

/// Every shape in the plane of shape `i` and facing its way (the shape itself, the islands
/// inside a letter's counter), mapped to `frame`'s plane: what a face covers, for telling
/// features from the face.
fn in_plane_of(list: &[Shape], i: usize, frame: &platener_geom::Frame) -> Vec<Polygon> {
    let own = &list[i].frame;
    list.iter()
        .filter(|s| s.frame.n.dot(own.n) > 1.0 - 1e-9 && own.to_local(s.frame.origin).z.abs() < 1e-3)
        .map(|s| map_polygon(&s.polygon, &s.frame, frame))
        .collect()
}

/// Extrudes what is left of every shape inwards (along its inverse normal) by the extrusion
/// thickness, piece by piece, skipping pieces too small or too thin to cut. What is left of a
/// face an inherent plate used must be at least twice the thickness wide: the rim of a wall's
/// outer face, as wide as the wall is thick, is where joints will go, not a plate of its own.
/// A piece's holes are closed where the model has material at the plate's mid-plane, as for
/// inherent plates; its features are on the face, down on the sheet.
pub(super) fn extrude_leftovers(
    shapes: &Shapes,
    sections: &Sections<'_>,
    found: &mut Detection,
    settings: &Settings,
) -> Result<(), GridError> {
    let t = settings.extrusion_thickness();
    let inherent: Vec<Slab> = found.plates.iter().map(Plate::slab).collect();
    // Each inherent plate grown once, when a piece first needs it: growing it again for every
    // piece of every partly used face was 8 of the 9 s of a tray with 200 holes (issue 29).
    let grown: Vec<OnceCell<Slab>> = inherent.iter().map(|_| OnceCell::new()).collect();
    for (i, shape) in shapes.shapes.iter().enumerate() {
        let mut pieces = std::mem::take(&mut found.remaining[i]);
        let partly_used = pieces.len() != 1 || (pieces[0].area() - shape.area).abs() > 1e-6 * shape.area.max(1.0);
        let needed = if partly_used { 2.0 * t } else { t };
        if partly_used {
            pieces = outside_neighbours(pieces, shape, (&inherent, &grown), t);
        }
        let frame = shape.frame.shifted(-t);
        let face = || {
            vec![Face {
                side: Side::Down,
                z: t,
                shape: in_plane_of(&shapes.shapes, i, &frame),
            }]
        };
        for piece in pieces {
            if let Err(why) = cuttable(&piece, needed, settings.plates.min_area) {
                found.detail[i].refused.get_or_insert(why);
                found.remaining[i].push(piece);
                continue;
            }
            let (solid, features) = sections.solid(piece, &frame, t, face)?;
            found.features.extend(features);
            for p in solid
                .into_iter()
                .filter(|p| cuttable(p, needed, settings.plates.min_area).is_ok())
            {
                found.plates.push(Plate {
                    kind: PlateKind::Extruded,
                    thickness: t,
                    frame,
                    area: p.area(),
                    polygon: p,
                    shapes: vec![i as u32],
                });
            }
        }
    }
    Ok(())
}

/// What is left of a partly used face, minus the parts lying in the layer of an inherent plate
/// that touches it: near a corner, the rim of a face between two plates lies in the other
/// plate's layer (the wider the sharper the angle) and belongs to the joint there, not to a plate.
/// `grown` holds each inherent plate's slab grown by `2t`, made on first use.
fn outside_neighbours(
    pieces: Vec<Polygon>,
    shape: &crate::shapes::Shape,
    (inherent, grown): (&[Slab], &[OnceCell<Slab>]),
    t: f64,
) -> Vec<Polygon> {
    let mut out = Vec::new();
    for piece in pieces {
        let slab = Slab {
            frame: shape.frame.shifted(-t),
            polygon: piece.clone(),
            thickness: t,
        };
        let mut rest = vec![piece];
        for (other, grown) in inherent.iter().zip(grown) {
            let Ok(inside) = slab.part_within_slab_of(other, 1e-3) else {
                continue;
            };
            // Only plates that actually touch the piece: their grown outline must meet it.
            let grown = || {
                grown.get_or_init(|| Slab {
                    polygon: grow(&other.polygon, 2.0 * t),
                    ..other.clone()
                })
            };
            let touching = inside.iter().any(|p| p.area() > 0.0)
                && slab.columns_meeting(grown(), 1e-3).is_ok_and(|c| !c.is_empty());
            if touching && let Ok(r) = difference(&rest, &inside) {
                rest = r;
            }
        }
        out.extend(rest);
    }
    out
}

fn grow(p: &Polygon, by: f64) -> Polygon {
    platener_geom::offset::offset(std::slice::from_ref(p), by)
        .ok()
        .and_then(|v| v.into_iter().next())
        .unwrap_or_else(|| p.clone())
}
