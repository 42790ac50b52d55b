//! Crush ribs (issue 34, the `crush-ribs` setting): small bumps on the long walls of each slot
//! a tab passes through, as Ponoko and Onshape's slot tutorials describe for press fits in
//! wood. The slot keeps its width (the tab's measured thickness, the fit's clearance on top);
//! only the ribs touch the tab, and being narrow they crush as it is pressed home, so one
//! plan holds on plywood a little thicker or thinner than sold without a mallet or a gap.
//!
//! A rib is a triangle [`HEIGHT`] high on a [`BASE`] wide foot, pointed into the slot: its
//! tip crushes first, and it is wide enough at its foot for the laser to cut (the kerf is
//! compensated on it like on any edge). Slots shorter than [`MIN_SLOT`] get none; slots from
//! [`TWO_RIBS`] long get two per wall, at a quarter of their length from each end.

use glam::{DVec2, DVec3};
use platener_geom::boolean::union_all;
use platener_geom::{GridError, Polygon};

use super::connect::band;
use crate::plates::Plate;

/// How far a rib reaches into the slot from its wall, mm.
pub const HEIGHT: f64 = 0.25;
/// The width of a rib's foot along the wall, mm.
pub const BASE: f64 = 1.5;
/// How far a rib's foot reaches into the wall's material, so it joins the plate, mm.
const INTO_WALL: f64 = 0.05;
/// Slots shorter than this (mm) get no ribs.
pub const MIN_SLOT: f64 = 4.0;
/// Slots at least this long (mm) get two ribs per wall.
pub const TWO_RIBS: f64 = 20.0;

/// The ribs of the slots `host` gives up along `axis` over each of `slots` (ranges along the
/// axis, model units) within `region` (the joint's region in the host's plane), in the host's
/// frame.
pub(super) fn ribs(
    host: &Plate,
    region: &Polygon,
    axis: DVec3,
    slots: &[(f64, f64)],
) -> Result<Vec<Polygon>, GridError> {
    let f = &host.frame;
    let along = DVec2::new(axis.dot(f.u), axis.dot(f.v)).normalize_or_zero();
    if along == DVec2::ZERO {
        return Ok(Vec::new());
    }
    let across = along.perp();
    let mut out = Vec::new();
    for &(s0, s1) in slots {
        for slot in band(host, region, axis, s0, s1)? {
            let extent = |d: DVec2| {
                slot.outer
                    .iter()
                    .map(|p| d.dot(*p))
                    .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| (lo.min(v), hi.max(v)))
            };
            let ((t0, t1), (w0, w1)) = (extent(along), extent(across));
            let length = t1 - t0;
            if length < MIN_SLOT || w1 - w0 <= 2.0 * HEIGHT {
                continue;
            }
            let places: &[f64] = if length >= TWO_RIBS { &[0.25, 0.75] } else { &[0.5] };
            for &k in places {
                let t = t0 + k * length;
                out.push(rib(along, across, t, w0, 1.0));
                out.push(rib(along, across, t, w1, -1.0));
            }
        }
    }
    Ok(out)
}

/// One rib at `t` along the wall at `w` across it, pointing `into` (+1 or −1) the slot.
fn rib(along: DVec2, across: DVec2, t: f64, w: f64, into: f64) -> Polygon {
    let at = |dt: f64, dw: f64| along * (t + dt) + across * (w + into * dw);
    let half = BASE / 2.0;
    let mut p = Polygon::new(vec![
        at(-half, -INTO_WALL),
        at(half, -INTO_WALL),
        at(half, 0.0),
        at(0.0, HEIGHT),
        at(-half, 0.0),
    ]);
    p.normalize_orientation();
    p
}

/// `outline` with `ribs` joined to it: the piece holding most of it (a rib with no wall
/// beside it, where a later claim filled the slot, joins nothing and is dropped).
pub(super) fn with_ribs(outline: &Polygon, ribs: &[Polygon]) -> Result<Polygon, GridError> {
    if ribs.is_empty() {
        return Ok(outline.clone());
    }
    let mut all = vec![outline.clone()];
    all.extend(ribs.iter().cloned());
    let merged = union_all(&all)?;
    Ok(merged
        .into_iter()
        .max_by(|a, b| a.area().total_cmp(&b.area()))
        .unwrap_or_else(|| outline.clone()))
}
