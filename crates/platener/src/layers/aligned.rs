//! The stack jointed to the plates: plates aligned with the layers take part in shaft placement.
//!
//! A plate parallel to the layers, as thick as one and lying exactly where a layer of the stack
//! lies, is an island of that layer: a dome's lid lies where the layer under the dome's first
//! would, a teapot's flat lid plate where one of its body's layers is. Such plates join the
//! layers (one more layer under the bottom or over the top of the stack where needed) while the
//! stacked method's own placement threads shafts, so shafts pass through a plate exactly as
//! through a layer, with the same margins, and a stack whose layers no shaft would join still
//! gets a shaft into the plate it lies on. Afterwards the plates are taken out again: their
//! slots become holes in the plates, and every shaft through one is a tenon through it (joint
//! kind `slot`).

use platener_geom::{GridError, Polygon, boolean};

use crate::plan::{Part, PartKind};
use crate::plates::map_polygon;
use crate::stacked::{LayerIslands, SlicePlan, Stack};

/// A plate's faces count as lying on a layer's faces within this, mm.
const TOUCH: f64 = 0.05;

/// Where the aligned plates went among the layers.
#[derive(Debug, Clone, Default)]
pub(crate) struct Aligned {
    /// (layer, island, part index) of each plate taken in as an island.
    islands: Vec<(usize, usize, usize)>,
    /// Whether a layer was added under the stack (every layer index moved up by one).
    below: bool,
    /// Whether a layer was added over it.
    above: bool,
}

/// `plan` and `islands` with the plates of `parts` that lie where a layer does (or would, just
/// under or over the stack) added as islands of that layer.
pub(crate) fn take_in(
    plan: SlicePlan,
    mut islands: LayerIslands,
    parts: &[Part],
) -> (SlicePlan, LayerIslands, Aligned) {
    let found: Vec<(i64, usize)> = (0..parts.len())
        .filter_map(|i| slot_of(&parts[i], &plan).map(|k| (k, i)))
        .collect();
    let mut out = plan;
    let mut aligned = Aligned {
        below: found.iter().any(|(k, _)| *k < 0),
        above: found.iter().any(|(k, _)| *k == plan.count as i64),
        ..Aligned::default()
    };
    if aligned.above {
        islands.islands.push(Vec::new());
        out.count += 1;
    }
    if aligned.below {
        islands.islands.insert(0, Vec::new());
        islands.dropped.iter_mut().for_each(|d| d.layer += 1);
        islands.kept_small.iter_mut().for_each(|k| k.layer += 1);
        out.frame = out.frame.shifted(-plan.thickness);
        out.count += 1;
    }
    for (k, i) in found {
        let layer = (k + i64::from(aligned.below)) as usize;
        aligned.islands.push((layer, islands.islands[layer].len(), i));
        islands.islands[layer].push(seen(&parts[i], &plan));
    }
    (out, islands, aligned)
}

/// The layer (−1 under the stack, `count` over it) `part` lies in exactly: a plate parallel to
/// the layers and as thick as one, its faces on a layer's.
fn slot_of(part: &Part, plan: &SlicePlan) -> Option<i64> {
    let parallel = part.frame.n.dot(plan.frame.n).abs() > 1.0 - 1e-6;
    if part.kind != PartKind::Plate || !parallel || (part.thickness - plan.thickness).abs() > 1e-6 {
        return None;
    }
    let (lo, _) = super::heights_in(&part.polygon.outer, &part.frame, part.thickness, &plan.frame);
    let k = (lo / plan.thickness).round();
    let on_a_layer = (lo - k * plan.thickness).abs() < TOUCH;
    (on_a_layer && k >= -1.0 && k <= plan.count as f64).then_some(k as i64)
}

/// `part`'s outline seen down the stack of `plan`, in the stack's 2D frame.
fn seen(part: &Part, plan: &SlicePlan) -> Polygon {
    map_polygon(&part.polygon, &part.frame, &plan.frame)
}

/// Takes the plates [`take_in`] added out of `stack` again: their slots are cut into the plates
/// of `parts`, and the shafts through them are returned as tenons (shaft part, plate part).
pub(crate) fn take_out(stack: &mut Stack, aligned: &Aligned, parts: &mut [Part]) -> Result<Vec<[u32; 2]>, GridError> {
    let mut tenons = Vec::new();
    let mut ids = Vec::new();
    for &(k, i, at) in &aligned.islands {
        let island = &stack.layers[k].islands[i];
        ids.push(island.part);
        let slots = boolean::difference(
            std::slice::from_ref(&island.outline),
            std::slice::from_ref(&island.polygon),
        )?;
        if !slots.is_empty() {
            cut_into(&mut parts[at], &slots, &stack.plan)?;
        }
        for shaft in &stack.shafts {
            if shaft.bands.iter().any(|b| b.layer == k && b.island == i) {
                tenons.push([shaft.part, parts[at].id]);
            }
        }
    }
    stack.retain_parts(|part| !ids.contains(&part));
    tenons.retain(|t| stack.shafts.iter().any(|s| s.part == t[0]));
    if aligned.above {
        stack.remove_layer(stack.layers.len() - 1);
    }
    if aligned.below {
        stack.remove_layer(0);
    }
    Ok(tenons)
}

/// Cuts `slots` (in the stack's 2D frame) out of `plate`; the plate keeps its largest piece
/// (slots keep a margin from the outline, so there is one).
fn cut_into(plate: &mut Part, slots: &[Polygon], plan: &SlicePlan) -> Result<(), GridError> {
    let mapped: Vec<Polygon> = slots
        .iter()
        .map(|s| map_polygon(s, &plan.frame, &plate.frame))
        .collect();
    let cut = boolean::difference(std::slice::from_ref(&plate.polygon), &mapped)?;
    if let Some(largest) = cut.into_iter().max_by(|a, b| a.area().total_cmp(&b.area())) {
        plate.polygon = largest;
    }
    Ok(())
}
