//! Which bent parts hold together once jointed. The `bends` step proposes bent parts from
//! the plates alone; only with the joints known can one tell whether a joint's slot or
//! shortened fingers cut a plate apart next to a bend, or leave a small facet all joint. The
//! `joints` step decides it here and joins the plates of a refused part as plates.

use glam::DVec2;
use platener_geom::GridError;
use platener_geom::polygon::Polygon;

use super::Joints;
use crate::bends::flat::flat_part;
use crate::bends::{BentPart, Refusal, plate_list};
use crate::plan::BendStyle;
use crate::plates::Plates;

/// Whether bent part `bent` still makes one sound part once its plates carry their joints
/// (`joints`, computed without fingers along its bends): its flat shape one piece, every bend
/// drawn, and its segments and zones rebuilding it. The `joints` step keeps only such parts.
pub(super) fn holds_together(bent: &BentPart, plates: &Plates, joints: &Joints, style: BendStyle) -> bool {
    let outlines: Vec<&Polygon> = bent
        .members
        .iter()
        .map(|m| &joints.outlines[m.plate as usize])
        .collect();
    if loses_joints(bent, plates, &outlines).unwrap_or(true) {
        return false;
    }
    let labels: Vec<Vec<(u32, [DVec2; 2])>> = vec![Vec::new(); bent.members.len()];
    let no_marks = |_: u32, _: &Polygon| Vec::new();
    match flat_part(1, bent, plates, &outlines, &labels, &no_marks, style) {
        Ok((part, notes)) => {
            notes.is_empty()
                && part.segments.iter().all(|s| s.polygon.area() > 0.0)
                && part
                    .pieces()
                    .is_ok_and(|pieces| joints_still_meet(bent, plates, joints, &pieces))
        }
        Err(_) => false,
    }
}

/// Whether cutting the members at their bend lines takes away joint material: fingers or
/// tabs of another connection that reach past a bend line (at a corner where a third plate
/// meets both) would be lost, and that joint would no longer meet.
fn loses_joints(bent: &BentPart, plates: &Plates, outlines: &[&Polygon]) -> Result<bool, GridError> {
    for (i, m) in bent.members.iter().enumerate() {
        let plate = &plates.plates[m.plate as usize];
        let t = plate.thickness;
        let lost = |shape: Polygon| -> Result<f64, GridError> {
            let whole = shape.area();
            let mut kept = vec![shape];
            for h in &bent.cuts[i] {
                kept = h.cut(m, t, &kept)?;
            }
            Ok(whole - platener_geom::polygon::total_area(&kept))
        };
        if lost(m.local(outlines[i]))? - lost(m.local(&plate.polygon))? > 0.5 * t * t {
            return Ok(true);
        }
    }
    Ok(false)
}

/// Whether every joint between a member and a plate outside the part still meets with the
/// part bent: fingers inside a bend zone move with its arc, off their partner's.
fn joints_still_meet(bent: &BentPart, plates: &Plates, joints: &Joints, pieces: &[platener_geom::slab::Slab]) -> bool {
    let inside = |p: u32| bent.members.iter().any(|m| m.plate == p);
    joints.connections.iter().all(|c| {
        let [a, b] = c.plates;
        let other = match (inside(a), inside(b)) {
            (true, false) => b,
            (false, true) => a,
            _ => return true,
        } as usize;
        let slab = plates.plates[other].slab_of(joints.outlines[other].clone());
        pieces.iter().any(|p| crate::assembly::slabs_meet(p, &slab))
    })
}

/// Why bent part `part` stays jointed plates, naming them as the plates step numbers them.
pub(super) fn refusal(part: &BentPart) -> Refusal {
    let first = &part.members[0];
    Refusal {
        plates: [first.plate, part.members.get(1).map_or(first.plate, |m| m.plate)],
        reason: format!(
            "the bent part of plates {} would not hold together once jointed; they stay jointed plates",
            plate_list(part)
        ),
    }
}
