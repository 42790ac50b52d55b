//! Slots cut into a layer without pinching it.
//!
//! A slot cut flush with a layer's outline (phase 2) ends where its column leaves the island,
//! so one corner of the slot lies on the outline and the material beside it runs out to
//! nothing: the cut outline touches itself, or keeps a sliver narrower than the kerf that the
//! laser burns away or snaps off (the torus sample's bottom layer: a slot across a small oval
//! left its two halves joined at two points). Such material cannot be kept, so it goes: wherever
//! the material between a slot and the layer's outline (or a hole, or another slot) is narrower
//! than the *bridge* width, the notch is opened through it to the outside. An open notch is a
//! valid outline and the shaft still fits it: only material the shaft does not need is removed,
//! never added. Whether what is left is still one piece is the caller's question (phase 2 then
//! shortens the slot, leaving a real bridge, or gives the layer up).
//!
//! Placement and assembly cut through this one function, so the layer that placement checked
//! is the layer that gets cut.

use platener_geom::{GridError, Polygon, boolean, clean, offset};

use super::shafts::SLIVER;

/// The opening's radius stays this much (mm) under half the bridge, so material exactly as
/// wide as a bridge (a slot placed with the relaxed margin) is kept whole despite grid rounding.
const BRIDGE_SLACK: f64 = 0.01;
/// Material this narrow (mm) left where a pinch was opened is the grid's rounding: 20 steps.
const HAIR: f64 = 0.02;

/// `outline` minus `cuts`, with every stretch of material narrower than a cut's bridge (mm,
/// given with each cut: a peg keeps a thinner wall than a shaft) next to that cut removed: the
/// pieces left over (area above [`SLIVER`]), largest first.
pub(super) fn cut_slots(outline: &Polygon, cuts: &[(Polygon, f64)]) -> Result<Vec<Polygon>, GridError> {
    if cuts.is_empty() {
        return Ok(vec![outline.clone()]);
    }
    let rects: Vec<Polygon> = cuts.iter().map(|(c, _)| c.clone()).collect();
    let left = boolean::difference(std::slice::from_ref(outline), &rects)?;
    let mut pieces = open_pinches(left, cuts)?;
    pieces.retain(|p| p.area() > SLIVER);
    pieces.sort_by(|a, b| b.area().total_cmp(&a.area()));
    Ok(pieces)
}

/// `left` (a layer minus its slots) without the material narrower than each cut's bridge
/// within that bridge of the cut; unchanged when there is none.
fn open_pinches(left: Vec<Polygon>, cuts: &[(Polygon, f64)]) -> Result<Vec<Polygon>, GridError> {
    let mut bridges: Vec<f64> = cuts.iter().map(|(_, b)| *b).collect();
    bridges.sort_by(f64::total_cmp);
    bridges.dedup();
    let mut pinch = Vec::new();
    for bridge in bridges {
        let r = bridge / 2.0 - BRIDGE_SLACK;
        if r <= 0.0 {
            continue;
        }
        // The opening keeps everything `bridge` wide; intersected with `left` because a miter
        // opening can grow a chamfer back square.
        let opened = boolean::intersection(&offset::opening(&left, r)?, &left)?;
        let thin = boolean::difference(&left, &opened)?;
        // Only thin material beside a slot goes: the layer's own narrow tips stay as modelled.
        let these: Vec<Polygon> = cuts
            .iter()
            .filter(|(_, b)| *b == bridge)
            .map(|(c, _)| c.clone())
            .collect();
        let near = offset::offset(&boolean::union_all(&these)?, bridge)?;
        pinch.extend(boolean::intersection(&thin, &near)?);
    }
    // Grid crumbs at the slots' inner corners are rounding, not material.
    pinch.retain(|p| p.area() > SLIVER);
    if pinch.is_empty() {
        return Ok(left);
    }
    let mut out = Vec::new();
    for piece in boolean::difference(&left, &pinch)? {
        // The opening's edges differ from the outline's by a grid step: hairs and touches of
        // that size are repaired, nothing wider is changed.
        out.extend(clean::clean(&piece, HAIR)?);
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use glam::DVec2;
    use platener_geom::validity::validate;

    use super::*;

    fn rect(x0: f64, y0: f64, x1: f64, y1: f64) -> Polygon {
        Polygon::new(platener_geom::polygon::rect(x0, y0, x1, y1))
    }

    #[test]
    fn a_slot_whose_corner_touches_the_outline_is_opened_to_the_outside() {
        // A 20 × 10 plate whose right edge slants (x = 16 − y/5), so a slot ending at x = 14.8
        // touches it at its corner (14.8, 6) and leaves a wedge 0.4 mm wide at its other corner.
        let outline = Polygon::new(vec![
            DVec2::new(0.0, 0.0),
            DVec2::new(16.0, 0.0),
            DVec2::new(14.0, 10.0),
            DVec2::new(0.0, 10.0),
        ]);
        let slot = rect(5.0, 4.0, 14.8, 6.0);
        let raw = boolean::difference(std::slice::from_ref(&outline), std::slice::from_ref(&slot)).expect("grid");
        assert!(raw.iter().any(|p| !validate(p, 0.2).is_empty()), "the raw cut pinches");
        let pieces = cut_slots(&outline, &[(slot.clone(), 1.5)]).expect("grid");
        assert_eq!(pieces.len(), 1);
        assert!(validate(&pieces[0], 0.2).is_empty(), "{:?}", validate(&pieces[0], 0.2));
        assert!(pieces[0].holes.is_empty(), "the slot is a notch now");
        // Only the wedge went: the triangle (14.8, 6), (14.8, 4), (15.2, 4) of 0.4 mm².
        let lost = outline.area() - slot.area() - pieces[0].area();
        assert!((lost - 0.4).abs() < 0.05, "{lost}");
    }

    #[test]
    fn a_slot_with_a_full_bridge_is_cut_exactly() {
        let outline = rect(0.0, 0.0, 20.0, 10.0);
        let slot = rect(5.0, 4.0, 15.0, 6.0);
        let pieces = cut_slots(&outline, &[(slot.clone(), 1.5)]).expect("grid");
        assert_eq!(pieces.len(), 1);
        assert_eq!(pieces[0].holes.len(), 1);
        assert!((pieces[0].area() - (200.0 - 20.0)).abs() < 1e-6);
    }

    #[test]
    fn a_slot_across_a_narrow_strip_splits_it_instead_of_pinching() {
        // The slot reaches within 0.5 mm of both long sides: two pieces, not one pinched one.
        let outline = rect(0.0, 0.0, 20.0, 4.0);
        let slot = rect(8.0, 0.5, 11.0, 3.5);
        let pieces = cut_slots(&outline, &[(slot, 1.5)]).expect("grid");
        assert_eq!(pieces.len(), 2);
        assert!(pieces.iter().all(|p| validate(p, 0.2).is_empty()));
    }

    #[test]
    fn a_pegs_bridge_keeps_its_1_mm_wall_where_a_shafts_would_open_it() {
        // A 3 mm slot in a 5 mm strip leaves 1 mm walls: kept with a peg's 1 mm bridge, opened
        // (the strip split) with a shaft's 1.5 mm one.
        let outline = rect(0.0, 0.0, 5.0, 14.0);
        let slot = rect(1.0, 1.0, 4.0, 13.0);
        let peg = cut_slots(&outline, &[(slot.clone(), 1.0)]).expect("grid");
        assert_eq!(peg.len(), 1);
        assert_eq!(peg[0].holes.len(), 1);
        assert!((peg[0].area() - (70.0 - 36.0)).abs() < 1e-6);
        let shaft = cut_slots(&outline, &[(slot, 1.5)]).expect("grid");
        assert!(shaft.iter().all(|p| p.holes.is_empty()), "the walls are opened");
        assert!(shaft.iter().map(Polygon::area).sum::<f64>() < 70.0 - 36.0 - 10.0);
    }
}
