//! The reference square (`reference-square`, issue 34): a 100 mm square scored on each sheet,
//! clear of the parts, with "100 MM" engraved inside it, to check after importing a file that
//! the laser software kept its scale (a square of any other size means the import scaled it).
//!
//! It goes where the legend would ([`super::legend::free_spot`]): beside the parts, on the
//! sheet, growing the used area the least, never in the sheet's far corner. A sheet with no
//! such room gets none, and plan.json's `sheets[].reference_square` is then absent.

use glam::DVec2;

use crate::draw::font;
use crate::draw::svg::{Engraved, SvgGroup};

/// The square's side, mm.
pub const SIDE: f64 = 100.0;
/// The group id of the square on a sheet.
pub const REFERENCE_ID: &str = "reference-square";
/// Cap height of its text, mm.
const TEXT_SIZE: f64 = 5.0;

/// The reference square's group on a `width` × `height` sheet holding `groups` (parts and
/// legend), and its lowest and highest corner; `None` without room for it.
pub fn place(width: f64, height: f64, groups: &[SvgGroup]) -> Option<(SvgGroup, [DVec2; 2])> {
    let boxes: Vec<(DVec2, DVec2)> = groups.iter().filter_map(extent).collect();
    let at = super::legend::free_spot(DVec2::splat(SIDE), DVec2::new(width, height), &boxes)?;
    let corners = [
        at,
        at + DVec2::new(SIDE, 0.0),
        at + DVec2::splat(SIDE),
        at + DVec2::new(0.0, SIDE),
    ];
    let square = corners.iter().chain(&corners[..1]).copied().collect();
    let text = "100 MM";
    let origin = at
        + DVec2::new(
            (SIDE - font::text_width(text, TEXT_SIZE)) / 2.0,
            SIDE / 2.0 + TEXT_SIZE / 2.0,
        );
    let group = SvgGroup {
        id: REFERENCE_ID.into(),
        cut: Vec::new(),
        slits: Vec::new(),
        engrave: std::iter::once(Engraved::score(square))
            .chain(
                font::place_text(text, TEXT_SIZE, origin, DVec2::X)
                    .into_iter()
                    .map(Engraved::text),
            )
            .collect(),
    };
    Some((group, [at, at + DVec2::splat(SIDE)]))
}

/// The bounding box of everything `g` draws, if it draws anything.
pub(super) fn extent(g: &SvgGroup) -> Option<(DVec2, DVec2)> {
    let paths = g.cut.iter().chain(&g.slits).chain(g.engrave.iter().map(|e| &e.path));
    let (lo, hi) = platener_geom::boxes::bounds2(paths.flatten().copied());
    (lo.x <= hi.x).then_some((lo, hi))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn part(x0: f64, y0: f64, x1: f64, y1: f64) -> SvgGroup {
        SvgGroup {
            id: "part-1".into(),
            cut: vec![vec![
                DVec2::new(x0, y0),
                DVec2::new(x1, y0),
                DVec2::new(x1, y1),
                DVec2::new(x0, y1),
            ]],
            ..SvgGroup::default()
        }
    }

    #[test]
    fn the_square_is_100_mm_clear_of_every_part_and_on_the_sheet() {
        let groups = [part(5.0, 5.0, 300.0, 200.0), part(305.0, 5.0, 400.0, 390.0)];
        let (g, [lo, hi]) = place(600.0, 400.0, &groups).expect("room beside the parts");
        assert_eq!(hi - lo, DVec2::splat(SIDE));
        assert!(lo.x >= 0.0 && lo.y >= 0.0 && hi.x <= 600.0 && hi.y <= 400.0);
        for p in &groups {
            let (a, b) = extent(p).expect("a part");
            assert!(
                hi.x <= a.x || b.x <= lo.x || hi.y <= a.y || b.y <= lo.y,
                "{lo} {hi} meets {a} {b}"
            );
        }
        // A closed score square (5 points, back to the start) and the text inside it.
        let (text, square): (Vec<&Engraved>, Vec<&Engraved>) = g.engrave.iter().partition(|e| e.text);
        assert_eq!(square.len(), 1);
        assert_eq!(square[0].path.len(), 5);
        assert_eq!(square[0].path[0], square[0].path[4]);
        let text = SvgGroup {
            engrave: text.into_iter().cloned().collect(),
            ..SvgGroup::default()
        };
        let (tlo, thi) = extent(&text).expect("text");
        assert!(tlo.cmpge(lo).all() && thi.cmple(hi).all());
        assert!(g.cut.is_empty() && g.slits.is_empty(), "nothing of it is cut");
    }

    #[test]
    fn a_full_sheet_has_no_room_for_it() {
        assert!(place(600.0, 400.0, &[part(5.0, 5.0, 595.0, 395.0)]).is_none());
        assert!(place(90.0, 90.0, &[part(5.0, 5.0, 10.0, 10.0)]).is_none());
    }
}
