//! Removing contained plates and trimming overlaps, so no volume is claimed twice.
//!
//! Plates are ranked (inherent before extruded, then larger first). Each plate gives up the part
//! of its outline whose columns meet the volume of a plate ranked above it, as that plate is
//! after its own trimming. A plate left with nothing was contained; pieces too small to cut are
//! dropped. Faces that merely touch (a wall standing on a floor) are not overlaps.

use platener_geom::GridError;
use platener_geom::boolean::difference;

use platener_geom::polygon::total_area;

use super::{Overlap, Plate, PlateKind, cuttable};

fn boxes_overlap(a: &(glam::DVec3, glam::DVec3), b: &(glam::DVec3, glam::DVec3), eps: f64) -> bool {
    (a.0 - b.1).cmplt(glam::DVec3::splat(-eps)).all() && (b.0 - a.1).cmplt(glam::DVec3::splat(-eps)).all()
}

/// What [`resolve`] found: the plates kept, how many were contained, how many were trimmed,
/// and each overlap it resolved.
pub(super) struct Resolved {
    pub plates: Vec<Plate>,
    pub contained: usize,
    pub trimmed: usize,
    pub overlaps: Vec<Overlap>,
}

/// Resolves the overlaps between `plates` (see the module's doc).
pub(super) fn resolve(mut plates: Vec<Plate>, min_area: f64, clearance: f64) -> Result<Resolved, GridError> {
    plates.sort_by(|a, b| {
        (a.kind == PlateKind::Extruded)
            .cmp(&(b.kind == PlateKind::Extruded))
            .then(b.area.total_cmp(&a.area))
    });
    let mut kept: Vec<Plate> = Vec::with_capacity(plates.len());
    let mut boxes = Vec::with_capacity(plates.len());
    let (mut contained, mut trimmed) = (0, 0);
    let mut overlaps = Vec::new();
    for plate in plates {
        let bounds = plate.bounds();
        let mut outline = vec![plate.polygon.clone()];
        let slab = plate.slab();
        let mut cut = false;
        for (k, other) in kept.iter().enumerate() {
            if !boxes_overlap(&bounds, &boxes[k], clearance) {
                continue;
            }
            let claimed = slab.columns_meeting(&other.slab(), clearance)?;
            if claimed.iter().any(|p| p.area() > 0.0) {
                let before = total_area(&outline);
                outline = difference(&outline, &claimed)?;
                cut = true;
                overlaps.push(Overlap {
                    trimmed: plate.shapes.clone(),
                    by: other.shapes.clone(),
                    area: before - total_area(&outline),
                    claimed,
                });
            }
        }
        if !cut {
            boxes.push(bounds);
            kept.push(plate);
            continue;
        }
        let pieces: Vec<_> = outline
            .into_iter()
            .filter(|p| cuttable(p, plate.thickness, min_area).is_ok())
            .collect();
        if pieces.is_empty() {
            contained += 1;
            continue;
        }
        trimmed += 1;
        for piece in pieces {
            let p = Plate {
                area: piece.area(),
                polygon: piece,
                ..plate.clone()
            };
            boxes.push(p.bounds());
            kept.push(p);
        }
    }
    Ok(Resolved {
        plates: kept,
        contained,
        trimmed,
        overlaps,
    })
}
