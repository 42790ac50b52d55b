//! The smallest part: one rule for every method (issue 32).
//!
//! A laser cuts far finer than a maker can handle. A strip of 3 mm plywood 1 mm wide cuts
//! cleanly and snaps when it is lifted out; a finger joint cut into a facet 5 mm wide leaves a
//! chip under a millimetre wide. So a part is kept only when it is **holdable**: somewhere at
//! least as wide as its sheet is thick (a stick t × t in section is as strong across as
//! through the sheet), and at least [`MIN_AREA`] of material, or a t × t square's when that
//! is more (36 mm² at 6 mm). A 4 × 40 mm leg at 2 mm passes, a 28 mm washer 4 mm wide at 3 mm
//! passes, a teapot's knob (a 6 mm disc at 3 mm) passes; a 0.7 mm chip at 1.5 mm, a 2 mm ring
//! at 3 mm and a 4 × 4 mm square do not.
//!
//! Why 25 mm² and not the 2t × 2t issue 32 suggested: 36 mm² at 3 mm dropped the teapot's
//! knob; 9 mm² at 1.5 mm admitted trimmed facets of a tessellated wall and turned a teacup's
//! 158 parts into 477 that took minutes to nest. 25 mm² was every method's floor before.
//!
//! Issue 32 asked for 2t at the narrowest. That refuses every washer, stick and rod the stacked
//! method builds well (a ring 4 mm wide in 3 mm sheet, 2.5 mm push rods at 3 mm): they carry no
//! fingers. A plate's fingers need t of material behind them, which is what the joints' neck
//! check (`parts::necks`, 2t) reports; the rule is the part's own size.
//!
//! The rule is checked on a part's outline as it will be cut, after its joints. The plate
//! method checks its plates and bent parts once the joints are cut, the stacked method (and
//! the classifier's layers) each layer's islands before shafts are placed. Joint pieces
//! (dovetail keys, shafts) are sized by their joints and exempt.

use std::collections::BTreeSet;

use platener_geom::{GridError, Polygon, offset};

use crate::plan::JointKind;

/// The least area of a part at any thickness, mm² (the plate and stacked settings' default).
pub const MIN_AREA: f64 = 25.0;

/// The least material kept between a peg's slot and the outline of a part it passes through,
/// mm: the stacked method's pegs and the plate method's standoffs (`parts::standoffs`).
pub const PEG_MIN_WALL: f64 = 1.0;

/// The width a part must reach somewhere, in sheet thicknesses.
pub const WIDTH_PER_THICKNESS: f64 = 1.0;

/// The side of the square whose area a part must have at least, in sheet thicknesses.
pub const SIDE_PER_THICKNESS: f64 = 1.0;

/// How far short of the width or area a part may fall and still pass, mm (and mm² per mm of
/// width): a 4 × 4 mm square at 2 mm is exactly the rule's area, and the 1 µm grid must not
/// decide it.
const SLACK: f64 = 0.02;

/// The smallest part a method may keep at one sheet thickness.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Rule {
    /// Somewhere at least this wide, mm.
    pub min_width: f64,
    /// At least this area, mm².
    pub min_area: f64,
}

/// Why a part is too small to keep.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum TooSmall {
    /// Less material than the rule's area.
    Area {
        /// The part's area, mm².
        area: f64,
    },
    /// Nowhere as wide as the rule's width.
    Narrow {
        /// The part's area, mm².
        area: f64,
    },
}

impl TooSmall {
    /// Says what is wrong with a part against `rule`, for a warning: "8.4 mm², nowhere 3.0 mm
    /// wide".
    pub fn describe(&self, rule: &Rule) -> String {
        match *self {
            TooSmall::Area { area } => format!("{area:.1} mm², under {:.1} mm²", rule.min_area),
            TooSmall::Narrow { area } => format!("{area:.1} mm², nowhere {:.1} mm wide", rule.min_width),
        }
    }
}

impl Rule {
    /// The rule for a sheet `thickness` mm thick, never below `floor_width` mm wide or
    /// `floor_area` mm² (a method's own settings may ask for more).
    pub fn for_sheet(thickness: f64, floor_width: f64, floor_area: f64) -> Rule {
        let side = SIDE_PER_THICKNESS * thickness;
        Rule {
            min_width: (WIDTH_PER_THICKNESS * thickness).max(floor_width),
            min_area: (side * side).max(floor_area),
        }
    }

    /// `Ok(())` when `p` is large enough to keep, else why not.
    ///
    /// # Errors
    /// When `p` does not fit the 1 µm grid.
    pub fn check(&self, p: &Polygon) -> Result<Result<(), TooSmall>, GridError> {
        let area = p.area();
        if area < self.min_area - SLACK * self.min_width || area <= 0.0 {
            return Ok(Err(TooSmall::Area { area }));
        }
        let inset = self.min_width / 2.0 - SLACK;
        if inset > 0.0 && offset::offset(std::slice::from_ref(p), -inset)?.is_empty() {
            return Ok(Err(TooSmall::Narrow { area }));
        }
        Ok(Ok(()))
    }

    /// Whether `p` is large enough to keep; an outline off the grid is not.
    pub fn keeps(&self, p: &Polygon) -> bool {
        matches!(self.check(p), Ok(Ok(())))
    }
}

/// The dovetail keys among the parts `joints` join (`(kind, [notched part, key])`): joint
/// pieces, sized by their joints, which the rule exempts like shafts.
pub fn dovetail_keys(joints: impl IntoIterator<Item = (JointKind, [u32; 2])>) -> BTreeSet<u32> {
    joints
        .into_iter()
        .filter(|(kind, _)| *kind == JointKind::Dovetail)
        .map(|(_, parts)| parts[1])
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec2;

    fn rect(w: f64, h: f64) -> Polygon {
        let mut p = Polygon::new(platener_geom::polygon::rect(0.0, 0.0, w, h));
        p.normalize_orientation();
        p
    }

    #[test]
    fn a_chair_leg_at_2_mm_is_kept_and_a_chip_is_not() {
        let rule = Rule::for_sheet(2.0, 0.0, MIN_AREA);
        assert_eq!(rule.min_width, 2.0);
        assert_eq!(rule.min_area, 25.0);
        assert!(
            rule.keeps(&rect(5.0, 5.0)),
            "the 5 × 5 mm square is exactly the rule's area"
        );
        assert!(rule.keeps(&rect(4.0, 40.0)), "a 4 × 40 mm leg");
        assert!(
            rule.keeps(&rect(2.0, 40.0)),
            "a 2 mm stick is as wide as the sheet is thick"
        );
        assert_eq!(
            rule.check(&rect(1.5, 40.0)).expect("on the grid"),
            Err(TooSmall::Narrow { area: 60.0 })
        );
        assert_eq!(
            rule.check(&rect(4.0, 4.0)).expect("on the grid"),
            Err(TooSmall::Area { area: 16.0 })
        );
    }

    #[test]
    fn a_plate_with_fingers_is_judged_by_its_widest_place() {
        let rule = Rule::for_sheet(6.0, 0.0, 0.0);
        // A 10 mm plate with 3 mm fingers along one side: the fingers are narrow, the plate not.
        let mut outline = vec![DVec2::new(0.0, 0.0), DVec2::new(30.0, 0.0), DVec2::new(30.0, 10.0)];
        for k in (0..5).rev() {
            let x = 6.0 * k as f64;
            outline.extend([
                DVec2::new(x + 6.0, 10.0),
                DVec2::new(x + 6.0, 13.0),
                DVec2::new(x + 3.0, 13.0),
                DVec2::new(x + 3.0, 10.0),
            ]);
        }
        outline.dedup();
        let mut p = Polygon::new(outline);
        p.normalize_orientation();
        assert!(rule.keeps(&p));
    }

    #[test]
    fn floors_raise_the_rule_never_lower_it() {
        let rule = Rule::for_sheet(3.0, 1.5, 25.0);
        assert_eq!((rule.min_width, rule.min_area), (3.0, 25.0));
        let rule = Rule::for_sheet(6.0, 1.5, 25.0);
        assert_eq!((rule.min_width, rule.min_area), (6.0, 36.0));
        let rule = Rule::for_sheet(1.0, 4.0, 50.0);
        assert_eq!((rule.min_width, rule.min_area), (4.0, 50.0));
    }

    proptest::proptest! {
        /// A w × h rectangle is kept exactly when it is somewhere t wide (its short side) and
        /// holds the rule's area, up to the grid's slack.
        #[test]
        fn a_rectangle_is_kept_when_wide_and_large_enough(
            w in 0.2f64..20.0, h in 0.2f64..80.0, t in 0.5f64..6.0,
        ) {
            let rule = Rule::for_sheet(t, 0.0, MIN_AREA);
            let wide = w.min(h) >= rule.min_width;
            let large = w * h >= rule.min_area;
            let clear = (w.min(h) - rule.min_width).abs() > 0.05 && (w * h - rule.min_area).abs() > 0.5;
            proptest::prop_assume!(clear);
            proptest::prop_assert_eq!(rule.keeps(&rect(w, h)), wide && large);
        }
    }
}
