//! Necks: narrow material that holds two wider regions of a polygon together.
//!
//! A finger slot cut near a part's edge or near a hole leaves a strip of material between
//! them; a slot that almost cuts a corner off leaves a neck. Such a strip is what breaks
//! first when the part is handled, so issue 15 asks for no neck narrower than twice the
//! sheet's thickness. Narrow material alone is no neck: a finger is as narrow, but it is
//! attached on one side only. So a neck is a piece of what an opening by half the width
//! removes (the strip) that the opened polygon meets in two or more places: a strip between
//! two lobes, or between a hole and the edge.
//!
//! The width reported is found by bisection: the largest opening radius at which the strip is
//! still kept, doubled, to within [`WIDTH_STEPS`] halvings of the asked width.

use glam::DVec2;

use crate::grid::{GridError, STEP};
use crate::polygon::Polygon;
use crate::tolerance::CRUMB_AREA;
use crate::{boolean, offset};

/// Halvings of the search for a neck's width: 1/128 of the width asked for.
const WIDTH_STEPS: usize = 7;

/// How far (mm) a strip is grown to find where the opened polygon meets it: a few grid steps,
/// so a shared edge is found whatever the rounding.
const CONTACT: f64 = 4.0 * STEP;

/// A neck of a polygon: where it is and how wide.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Neck {
    /// A point of the strip (its first vertex), in the polygon's coordinates.
    pub at: DVec2,
    /// The strip's width (mm), to within 1/128 of the width asked for.
    pub width: f64,
    /// The strip's lower and upper bounding corner.
    pub bounds: (DVec2, DVec2),
}

/// Every neck of `polygon` narrower than `width` (mm), in the order the opening gives them.
pub fn necks(polygon: &Polygon, width: f64) -> Result<Vec<Neck>, GridError> {
    necks_except(polygon, width, &[])
}

/// The bounding boxes of `polygon`'s necks narrower than `width`, without measuring them:
/// what [`necks_except`] takes to leave known necks out.
pub fn neck_bounds(polygon: &Polygon, width: f64) -> Result<Vec<(DVec2, DVec2)>, GridError> {
    Ok(strips(polygon, width / 2.0, CRUMB_AREA)?
        .iter()
        .map(Polygon::bounds)
        .collect())
}

/// The necks of `polygon` narrower than `width` whose strip overlaps none of the boxes in
/// `known` (a plate's own necks, before joints were cut into it).
pub fn necks_except(polygon: &Polygon, width: f64, known: &[(DVec2, DVec2)]) -> Result<Vec<Neck>, GridError> {
    let mut out = Vec::new();
    for strip in strips(polygon, width / 2.0, CRUMB_AREA)? {
        let bounds = strip.bounds();
        if known.iter().any(|k| overlaps(*k, bounds)) {
            continue;
        }
        out.push(Neck {
            at: strip.outer.first().copied().unwrap_or_default(),
            width: neck_width(polygon, width, bounds)?,
            bounds,
        });
    }
    Ok(out)
}

/// The strips of `polygon` narrower than `2r` that the opening by `r` meets in two places or
/// more (pieces under `min_area` ignored): the necks, unmeasured. Short ones count too (a
/// pinch between two slanted edges), unlike the validity check's narrow material.
pub(crate) fn strips(polygon: &Polygon, r: f64, min_area: f64) -> Result<Vec<Polygon>, GridError> {
    let one = std::slice::from_ref(polygon);
    let opened = offset::opening(one, r)?;
    if opened.is_empty() {
        return Ok(Vec::new());
    }
    let lost = boolean::difference(one, &opened)?;
    let mut out = Vec::new();
    for strip in lost.into_iter().filter(|l| l.area() >= min_area) {
        let grown = offset::offset(std::slice::from_ref(&strip), CONTACT)?;
        let contacts = boolean::intersection(&grown, &opened)?
            .into_iter()
            .filter(|c| c.area() >= CONTACT * CONTACT)
            .count();
        if contacts >= 2 {
            out.push(strip);
        }
    }
    Ok(out)
}

/// The width of the neck whose strip at `width` has `bounds`: twice the largest radius at
/// which an opening still keeps it (no strip there overlaps `bounds`).
fn neck_width(polygon: &Polygon, width: f64, bounds: (DVec2, DVec2)) -> Result<f64, GridError> {
    let (mut kept, mut lost) = (0.0, width / 2.0);
    for _ in 0..WIDTH_STEPS {
        let r = (kept + lost) / 2.0;
        let here = strips(polygon, r, CRUMB_AREA)?
            .iter()
            .any(|s| overlaps(s.bounds(), bounds));
        if here {
            lost = r;
        } else {
            kept = r;
        }
    }
    Ok(kept + lost)
}

/// Whether two bounding boxes (lower, upper corner) overlap.
fn overlaps(a: (DVec2, DVec2), b: (DVec2, DVec2)) -> bool {
    a.0.x <= b.1.x && b.0.x <= a.1.x && a.0.y <= b.1.y && b.0.y <= a.1.y
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::polygon::rect;

    fn v(x: f64, y: f64) -> DVec2 {
        DVec2::new(x, y)
    }

    /// Two 20 mm squares joined by a 4 mm wide, 10 mm long strip: a neck 4 mm wide, found when
    /// asking for 6 mm and not for 3 mm.
    #[test]
    fn a_strip_between_two_squares_is_a_neck_of_its_width() {
        let p = Polygon::new(vec![
            v(0.0, 0.0),
            v(20.0, 0.0),
            v(20.0, 8.0),
            v(30.0, 8.0),
            v(30.0, 0.0),
            v(50.0, 0.0),
            v(50.0, 20.0),
            v(30.0, 20.0),
            v(30.0, 12.0),
            v(20.0, 12.0),
            v(20.0, 20.0),
            v(0.0, 20.0),
        ]);
        let found = necks(&p, 6.0).expect("grid");
        assert_eq!(found.len(), 1, "{found:?}");
        assert!((found[0].width - 4.0).abs() < 6.0 / 64.0, "{}", found[0].width);
        let (lo, hi) = found[0].bounds;
        assert!(lo.x >= 19.9 && hi.x <= 30.1 && lo.y >= 7.9 && hi.y <= 12.1, "{lo} {hi}");
        assert!(necks(&p, 3.0).expect("grid").is_empty());
    }

    /// A slot 1.5 mm from a plate's edge leaves a bridge between the slot and the edge: a
    /// neck 1.5 mm wide at 6 mm (twice a 3 mm sheet). Fingers 3 mm deep on the other side are
    /// narrow too, but held on one side only: no necks.
    #[test]
    fn a_slot_near_the_edge_leaves_a_neck_and_fingers_do_not() {
        let mut outer = vec![v(0.0, 0.0), v(60.0, 0.0), v(60.0, 40.0)];
        for k in 0..3 {
            let x = 50.0 - 20.0 * k as f64;
            outer.extend([v(x, 40.0), v(x, 43.0), v(x - 10.0, 43.0), v(x - 10.0, 40.0)]);
        }
        outer.push(v(0.0, 40.0));
        let plate = Polygon::new(outer.clone());
        assert!(necks(&plate, 6.0).expect("grid").is_empty(), "fingers are no necks");
        let mut slotted = Polygon {
            outer,
            holes: vec![rect(20.0, 1.5, 40.0, 4.5)],
        };
        slotted.normalize_orientation();
        let found = necks(&slotted, 6.0).expect("grid");
        assert_eq!(found.len(), 1, "{found:?}");
        assert!((found[0].width - 1.5).abs() < 6.0 / 64.0, "{}", found[0].width);
        assert!(found[0].bounds.1.y <= 1.6, "{:?}", found[0].bounds);
    }
}
