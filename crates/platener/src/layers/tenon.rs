//! The stack jointed to the plates it rests on: shafts go on through a slot in the plate.
//!
//! Where the bottom layer lies on a plate parallel to the layers (a dome on a lid), every shaft
//! through the bottom layer is extended down by the plate's thickness over its bottom slot, and
//! the plate gets that slot as a hole: the shaft is a tenon through the plate, as tab-and-slot
//! joints are (joint kind `slot`). The same holds upside down for a top layer under a plate.
//! A slot is cut only where it lies inside the plate with a margin of one plate thickness, so
//! the plate keeps a frame around it. Islands of the end layer no tenon reaches are glued to
//! the plate (plan.json's `glued`).

use glam::{DVec2, DVec3};
use platener_geom::polygon::total_area;
use platener_geom::{GridError, Polygon, boolean, offset};

use super::footprint::{Slab, height_range, mapped};
use crate::plan::{Glue, Part, PartKind};
use crate::stacked::{Shaft, Stack};

/// Plate faces within this of a stack end count as touching it, mm.
const TOUCH: f64 = 0.05;

/// What jointing the stack to the plates did.
#[derive(Debug, Clone, Default)]
pub(crate) struct Joined {
    /// Shafts through a slot in a plate: (shaft part, plate part).
    pub tenons: Vec<[u32; 2]>,
    /// End-layer islands glued to the plate they lie on.
    pub glued: Vec<Glue>,
}

/// Which end of the stack.
#[derive(Debug, Clone, Copy, PartialEq)]
enum End {
    Bottom,
    Top,
}

/// Extends the stack's shafts through the plates among `parts` its end layers lie on, cutting
/// their slots into those plates; glues the end islands no tenon reaches.
pub(crate) fn join(stack: &mut Stack, parts: &mut [Part]) -> Result<Joined, GridError> {
    let mut joined = Joined::default();
    if stack.layers.is_empty() {
        return Ok(joined);
    }
    for end in [End::Bottom, End::Top] {
        let (layer, height) = match end {
            End::Bottom => (0, 0.0),
            End::Top => (stack.layers.len() - 1, stack.layers.len() as f64 * stack.layer_thickness()),
        };
        for at in touching_plates(stack, parts, end, height) {
            let before = joined.tenons.len();
            for s in 0..stack.shafts.len() {
                if tenon(stack, s, layer, height, end, &mut parts[at])? {
                    joined.tenons.push([stack.shafts[s].part, parts[at].id]);
                }
            }
            let reached: Vec<usize> = stack
                .shafts
                .iter()
                .filter(|s| joined.tenons[before..].iter().any(|t| t[0] == s.part))
                .flat_map(|s| s.bands.iter().filter(|b| b.layer == layer).map(|b| b.island))
                .collect();
            joined.glued.extend(glue(stack, layer, &parts[at], &reached, end)?);
        }
    }
    Ok(joined)
}

/// Indices of the plates parallel to the layers whose face lies at stack height `height`, on
/// the far side of the stack's `end`.
fn touching_plates(stack: &Stack, parts: &[Part], end: End, height: f64) -> Vec<usize> {
    let frame = stack.plan.frame;
    (0..parts.len())
        .filter(|&i| {
            let p = &parts[i];
            if p.kind != PartKind::Plate || p.frame.n.dot(frame.n).abs() < 1.0 - 1e-6 {
                return false;
            }
            let slab = Slab {
                polygon: &p.polygon,
                frame: &p.frame,
                thickness: p.thickness,
            };
            let (lo, hi) = height_range(&slab, &frame);
            match end {
                End::Bottom => (hi - height).abs() < TOUCH,
                End::Top => (lo - height).abs() < TOUCH,
            }
        })
        .collect()
}

/// The slot of shaft `s` in `layer`, in the stack's 2D frame, and its stretch along the shaft.
fn end_slot(shaft: &Shaft, layer: usize, half: f64) -> Option<(Polygon, f64, f64)> {
    let band = shaft.bands.iter().find(|b| b.layer == layer)?;
    let (d, n) = (shaft.direction, shaft.direction.perp());
    let (a, b) = (shaft.start + d * band.from, shaft.start + d * band.to);
    let mut rect = Polygon::new(vec![a - n * half, b - n * half, b + n * half, a + n * half]);
    rect.normalize_orientation();
    Some((rect, band.from, band.to))
}

/// Extends shaft `s` through `plate` at the stack's `end` when its end slot lies inside the
/// plate with a margin; cuts the slot into the plate. Returns whether it did.
fn tenon(stack: &mut Stack, s: usize, layer: usize, height: f64, end: End, plate: &mut Part) -> Result<bool, GridError> {
    let half = stack.shaft_thickness / 2.0;
    let Some((rect, from, to)) = end_slot(&stack.shafts[s], layer, half) else {
        return Ok(false);
    };
    let frame = stack.plan.frame;
    let to_plate = |p: DVec2| plate.frame.to_local(frame.to_model(DVec3::new(p.x, p.y, height))).truncate();
    let mut slot = Polygon::new(rect.outer.iter().map(|&p| to_plate(p)).collect());
    slot.normalize_orientation();
    let around = offset::offset(std::slice::from_ref(&slot), plate.thickness)?;
    if total_area(&boolean::difference(&around, std::slice::from_ref(&plate.polygon))?) > 1e-6 {
        return Ok(false);
    }
    let cut = boolean::difference(std::slice::from_ref(&plate.polygon), std::slice::from_ref(&slot))?;
    let (y0, y1) = match end {
        End::Bottom => (-plate.thickness, 0.0),
        End::Top => (height, height + plate.thickness),
    };
    let extension = Polygon::new(vec![
        DVec2::new(from, y0),
        DVec2::new(to, y0),
        DVec2::new(to, y1),
        DVec2::new(from, y1),
    ]);
    let shaft = &mut stack.shafts[s];
    let longer = boolean::union(std::slice::from_ref(&shaft.polygon), std::slice::from_ref(&extension))?;
    let ([cut], [longer]) = (&cut[..], &longer[..]) else {
        return Ok(false);
    };
    plate.polygon = cut.clone();
    shaft.polygon = longer.clone();
    Ok(true)
}

/// Glue between `plate` and the islands of end layer `layer` that overlap it and no tenon
/// reaches (`reached`: island indices).
fn glue(stack: &Stack, layer: usize, plate: &Part, reached: &[usize], end: End) -> Result<Vec<Glue>, GridError> {
    let frame = stack.plan.frame;
    let to_stack = |p: DVec2| frame.to_local(plate.frame.to_model_2d(p)).truncate();
    let mut seen = mapped(&plate.polygon, to_stack);
    seen.normalize_orientation();
    let mut out = Vec::new();
    for (i, island) in stack.layers[layer].islands.iter().enumerate() {
        if reached.contains(&i) {
            continue;
        }
        let area = total_area(&boolean::intersection(
            std::slice::from_ref(&island.polygon),
            std::slice::from_ref(&seen),
        )?);
        if area > 0.0 {
            let parts = match end {
                End::Bottom => [plate.id, island.part],
                End::Top => [island.part, plate.id],
            };
            out.push(Glue { parts, area });
        }
    }
    Ok(out)
}
