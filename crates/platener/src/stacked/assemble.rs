//! The stack as it will be cut: slots in the layers, shaft outlines and every part's frame.
//!
//! A shaft's slot in a layer and the shaft's piece inside that layer are the same set: the
//! stretch `from..to` of its centre line, the shaft's thickness wide, the layer's thickness
//! tall. The layer loses that rectangle (a hole, or a notch where phase 2 cut the shaft flush
//! with the outline; where that would leave material narrower than a bridge beside it, the notch
//! opens through it to the outside, see `notch`) and the shaft's outline is the stack of those rectangles, so the two
//! meet face to face with no overlap and no gap; the `kerf` step then grows the shaft and shrinks
//! the slot by half the kerf each, which keeps them fitting once cut.

use glam::{DVec2, DVec3};
use platener_geom::polygon::remove_straight_vertices;
use platener_geom::{Frame, GridError, Polygon, Ring};

use super::islands::LayerIslands;
use super::notch::cut_slots;
use super::shafts::{Placed, PlacedShaft};
use super::{Island, Layer, Shaft, Stack};
use crate::slicing::LoopStats;
use crate::slicing::SlicePlan;

/// Builds the [`Stack`]: part ids go to layers bottom up (islands in order), then to shafts.
pub(crate) fn assemble(
    plan: SlicePlan,
    shaft_thickness: f64,
    islands: LayerIslands,
    placed: Placed,
    loops: LoopStats,
) -> Result<Stack, GridError> {
    let half = shaft_thickness / 2.0;
    let mut next_id = 1u32;
    let mut layers = Vec::with_capacity(islands.islands.len());
    for (k, outlines) in islands.islands.into_iter().enumerate() {
        let mut layer = Layer {
            number: k as u32 + 1,
            z: plan.bottom(k),
            islands: Vec::with_capacity(outlines.len()),
        };
        for (i, outline) in outlines.into_iter().enumerate() {
            let cuts: Vec<(Polygon, f64)> = placed
                .shafts
                .iter()
                .flat_map(|s| {
                    let bridge = placed.bridge_of(s, k);
                    s.bands
                        .iter()
                        .filter(|b| b.layer == k && b.island == i)
                        .map(move |b| (s.line.rect(b.from, b.to, half), bridge))
                })
                .collect();
            // Slots keep a margin (phase 1) or were checked not to split the island (phase 2),
            // so one piece remains; grid crumbs are dropped with the smaller pieces.
            let polygon = cut_slots(&outline, &cuts)?.into_iter().next().unwrap_or_default();
            layer.islands.push(Island {
                outline,
                polygon,
                part: next_id,
            });
            next_id += 1;
        }
        layers.push(layer);
    }
    let shafts = placed
        .shafts
        .iter()
        .map(|s| {
            let shaft = shaft(&plan, shaft_thickness, s, next_id);
            next_id += 1;
            shaft
        })
        .collect();
    Ok(Stack {
        plan,
        shaft_thickness,
        layers,
        shafts,
        dropped: islands.dropped,
        kept_small: islands.kept_small,
        unjoined: placed.unjoined,
        bosses: Vec::new(),
        shafts_removed: placed.removed,
        loops,
        raised: Vec::new(),
    })
}

/// A placed shaft's outline and frame.
fn shaft(plan: &SlicePlan, thickness: f64, s: &PlacedShaft, part: u32) -> Shaft {
    let f = &plan.frame;
    let u = f.u * s.line.dir.x + f.v * s.line.dir.y;
    let n = u.cross(f.n);
    let origin = f.to_model(DVec3::new(s.line.start.x, s.line.start.y, 0.0)) - n * (thickness / 2.0);
    let frame = Frame { origin, u, v: f.n, n };
    Shaft {
        start: s.line.start,
        direction: s.line.dir,
        width: s.line.width,
        bands: s.bands.clone(),
        phase: s.phase,
        polygon: staircase(plan, s),
        frame,
        part,
    }
}

/// The union of the shaft's slot rectangles in its own plane (x along the centre line, y up
/// the stack): consecutive slots overlap along the line, so the outline is one staircase.
fn staircase(plan: &SlicePlan, s: &PlacedShaft) -> Polygon {
    let mut ring: Ring = Vec::with_capacity(4 * s.bands.len());
    for b in &s.bands {
        let (z0, z1) = (plan.bottom(b.layer), plan.bottom(b.layer + 1));
        ring.push(DVec2::new(b.to, z0));
        ring.push(DVec2::new(b.to, z1));
    }
    for b in s.bands.iter().rev() {
        let (z0, z1) = (plan.bottom(b.layer), plan.bottom(b.layer + 1));
        ring.push(DVec2::new(b.from, z1));
        ring.push(DVec2::new(b.from, z0));
    }
    ring.dedup();
    // Straight runs (equal slots one above the other) keep only their ends.
    let mut polygon = Polygon::new(remove_straight_vertices(&ring, 1e-9));
    polygon.normalize_orientation();
    polygon
}
