//! Tests of the hinge physics, patterns and swatch: figures, invariants and geometry.

use std::f64::consts::{FRAC_PI_2, PI};

use glam::DVec2;
use platener_geom::Polygon;
use platener_geom::polygon::rect;
use proptest::prelude::*;

use super::pattern::clip_segment;
use super::*;
use crate::plan::{BendStyle, HingePattern, Mark, MarkKind, Material};
use crate::swatches::hinge::hinge_swatch;

/// The design of a right-angle bend with no limit on its width.
fn unlimited(style: BendStyle, material: Material, t: f64) -> BendDesign {
    design(style, material, t, FRAC_PI_2, f64::INFINITY).expect("the style suits the material")
}

fn hinge(t: f64, turn: f64) -> BendDesign {
    design(BendStyle::LivingHinge, Material::Wood, t, turn, f64::INFINITY).expect("wood bends")
}

/// Signed distance of `p` from the line through `l`.
fn across(l: [DVec2; 2], p: DVec2) -> f64 {
    (l[1] - l[0]).normalize().perp().dot(p - l[0])
}

#[test]
fn square_links_in_3mm_plywood_need_23_for_a_right_angle() {
    let d = hinge(3.0, FRAC_PI_2);
    assert_eq!(d.links, 23, "{d:?}");
    assert_eq!((d.link_width, d.link_length), (3.0, 12.0));
    assert!((d.pitch - 3.2).abs() < 1e-12);
    assert!((d.zone_width - 23.0 * 3.2).abs() < 1e-9);
    assert!((d.neutral_radius - d.zone_width / FRAC_PI_2).abs() < 1e-9);
    assert!((d.slit_length - (2.0 * d.link_length + d.bridge)).abs() < 1e-12);
    assert_eq!(d.rows, d.links + 1);
    // The closed form for square links: n ≥ 0.676·Θ·G·t/(τ·l).
    let m = MaterialData::PLYWOOD;
    let closed = 0.676 * FRAC_PI_2 * m.shear_modulus * 3.0 / (m.shear_strength * 12.0);
    assert_eq!(closed.ceil() as u32, d.links);
}

#[test]
fn the_torsion_ratio_follows_the_table() {
    assert!((torsion_ratio(3.0, 3.0) - 0.676).abs() < 1e-3);
    assert!((torsion_ratio(1.5, 3.0) - 0.229 / 0.246).abs() < 1e-9);
    assert!((torsion_ratio(3.0, 1.5) - torsion_ratio(1.5, 3.0)).abs() < 1e-12);
    assert!((torsion_ratio(0.001, 3.0) - 1.0).abs() < 0.01);
    let mut last = 0.0;
    for k in 0..=100 {
        let c = torsion_ratio(3.0 - 2.9 * f64::from(k) / 100.0, 3.0);
        assert!(c >= last, "c must grow as the link narrows");
        last = c;
    }
}

#[test]
fn more_turn_needs_more_links_and_thicker_sheet_a_wider_zone() {
    let mut last = 0;
    for deg in (5..=180).step_by(5) {
        let d = hinge(3.0, f64::from(deg).to_radians());
        assert!(d.links >= last, "{deg}°");
        last = d.links;
    }
    assert!(hinge(3.0, PI).links > hinge(3.0, FRAC_PI_2).links);
    let mut last = 0.0;
    for t in [1.0, 1.5, 2.0, 3.0, 4.0, 5.0, 6.0] {
        let w = hinge(t, FRAC_PI_2).zone_width;
        assert!(w > last, "{t} mm");
        last = w;
    }
}

#[test]
fn a_tight_zone_takes_narrower_links_or_says_how_wide_it_must_be() {
    let square = hinge(3.0, FRAC_PI_2);
    let tight = design(
        BendStyle::LivingHinge,
        Material::Wood,
        3.0,
        FRAC_PI_2,
        0.7 * square.zone_width,
    )
    .expect("narrower links fit");
    assert!(tight.link_width < 3.0 && tight.link_width >= 1.5);
    assert!(tight.zone_width <= 0.7 * square.zone_width);
    // Narrower links twist further before over-stressing, but the kerf between them caps the
    // twist per link (a twisted b × t section must clear it), so the gain is the pitch.
    assert!(tight.pitch < square.pitch);
    match design(BendStyle::LivingHinge, Material::Wood, 3.0, FRAC_PI_2, 5.0) {
        Err(HingeError::TooWide { needed, max_width }) => assert!(needed > max_width && max_width == 5.0),
        other => panic!("expected TooWide, got {other:?}"),
    }
}

#[test]
fn bad_inputs_are_typed_errors() {
    let d = |style, material, t, turn| design(style, material, t, turn, f64::INFINITY);
    let kind = |r: Result<BendDesign, HingeError>| match r {
        Err(HingeError::Invalid { .. }) => "invalid",
        Err(HingeError::Unsuitable { .. }) => "unsuitable",
        Err(HingeError::TooSharp { .. }) => "too sharp",
        other => panic!("expected a refusal, got {other:?}"),
    };
    for t in [0.0, -1.0, f64::NAN, f64::INFINITY, 51.0] {
        assert_eq!(kind(d(BendStyle::LivingHinge, Material::Wood, t, 1.0)), "invalid");
    }
    let cases = [
        (BendStyle::LivingHinge, Material::Wood, 3.0, 0.0, "invalid"),
        (BendStyle::LivingHinge, Material::Paper, 0.3, 1.0, "unsuitable"),
        (BendStyle::Heat, Material::Wood, 3.0, 1.0, "unsuitable"),
        (BendStyle::Score, Material::Cardboard, 2.0, 1.0, "unsuitable"),
        (BendStyle::Heat, Material::Acrylic, 3.0, 2.0, "too sharp"),
    ];
    for (style, material, t, turn, expected) in cases {
        assert_eq!(kind(d(style, material, t, turn)), expected, "{style:?} {material:?}");
    }
    assert!(design(BendStyle::LivingHinge, Material::Wood, 3.0, 1.0, f64::NAN).is_err());
    assert_eq!(max_turn(BendStyle::LivingHinge, Material::Wood, 3.0), PI);
    assert_eq!(max_turn(BendStyle::Perforation, Material::Wood, 3.0), 0.0);
}

#[test]
fn folds_and_heat_bends_have_their_radius_and_one_line() {
    let p = unlimited(BendStyle::Perforation, Material::Cardboard, 1.5);
    assert!((p.neutral_radius - 0.75).abs() < 1e-12 && (p.zone_width - 0.75 * FRAC_PI_2).abs() < 1e-12);
    assert_eq!((p.rows, p.links, p.slit_length, p.bridge), (1, 0, 4.5, 1.5));
    let h = unlimited(BendStyle::Heat, Material::Acrylic, 3.0);
    assert!((h.neutral_radius - 4.5).abs() < 1e-12);
    // R·(1/cos 45° − 1) = R·(√2 − 1).
    assert!((h.corner_gap() - 4.5 * (2f64.sqrt() - 1.0)).abs() < 1e-12);
    assert_eq!(hinge(3.0, PI).corner_gap(), f64::INFINITY, "a U-turn has no corner");
    assert!(matches!(
        design(BendStyle::Heat, Material::Acrylic, 3.0, FRAC_PI_2, 1.0),
        Err(HingeError::TooWide { .. })
    ));
}

/// Checks every slit of `marks` lies on a row of `d` inside the zone, parallel to the line,
/// and at least the link width inside `clip` (on the 1 µm grid).
fn check_slits(d: &BendDesign, line: [DVec2; 2], clip: &Polygon, marks: &[Mark]) {
    assert!(!marks.is_empty());
    let dir = (line[1] - line[0]).normalize();
    for m in marks {
        assert_eq!((m.kind, m.path.len()), (MarkKind::Cut, 2));
        assert!(
            (m.path[1] - m.path[0]).normalize().perp_dot(dir).abs() < 1e-9,
            "parallel"
        );
        for k in 0..=10 {
            let p = m.path[0].lerp(m.path[1], f64::from(k) / 10.0);
            let off = across(line, p);
            assert!(off.abs() <= d.zone_width / 2.0 + 1e-9, "inside the zone");
            let row = (off + d.zone_width / 2.0) / d.pitch;
            assert!((row - row.round()).abs() < 1e-6, "on a row");
            assert!(
                clip.contains(p) && clip.boundary_distance(p) >= d.link_width - 2e-3,
                "{p}"
            );
        }
    }
}

fn l_shape() -> Polygon {
    let mut p = Polygon::new(vec![
        DVec2::new(0.0, 0.0),
        DVec2::new(200.0, 0.0),
        DVec2::new(200.0, 60.0),
        DVec2::new(90.0, 60.0),
        DVec2::new(90.0, 130.0),
        DVec2::new(0.0, 130.0),
    ]);
    p.holes.push({
        let mut h = rect(120.0, 20.0, 135.0, 40.0);
        h.reverse();
        h
    });
    p
}

#[test]
fn slits_stay_in_the_zone_and_inside_the_eroded_outline() {
    let d = hinge(3.0, FRAC_PI_2);
    let clip = l_shape();
    // A slanted line crossing the hole and the notch.
    let line = [DVec2::new(100.0, -10.0), DVec2::new(160.0, 140.0)];
    let m = marks(&d, line, &clip).expect("marks");
    check_slits(&d, line, &clip, &m);
    let rows: std::collections::BTreeSet<i64> = m
        .iter()
        .map(|s| ((across(line, s.path[0]) + d.zone_width / 2.0) / d.pitch).round() as i64)
        .collect();
    assert_eq!(rows.len(), d.rows as usize, "every row has slits");
    assert_eq!(marks(&d, line, &clip).expect("again"), m, "deterministic");
}

#[test]
fn neighbouring_rows_are_offset_by_half_a_period() {
    let d = hinge(3.0, FRAC_PI_2);
    let clip = Polygon::new(rect(0.0, 0.0, 120.0, 100.0));
    let line = [DVec2::new(60.0, 0.0), DVec2::new(60.0, 100.0)];
    let m = marks(&d, line, &clip).expect("marks");
    check_slits(&d, line, &clip, &m);
    let period = d.period();
    // The phase of each row from its whole (unclipped) slits' starts along the line.
    let phase = |row: i64| -> f64 {
        let starts: Vec<f64> = m
            .iter()
            .filter(|s| ((across(line, s.path[0]) + d.zone_width / 2.0) / d.pitch).round() as i64 == row)
            .filter(|s| (s.path[0].distance(s.path[1]) - d.slit_length).abs() < 1e-6)
            .map(|s| s.path[0].y.min(s.path[1].y).rem_euclid(period))
            .collect();
        assert!(!starts.is_empty(), "row {row} has a whole slit");
        assert!(starts.iter().all(|s| (s - starts[0]).abs() < 1e-6));
        starts[0]
    };
    for row in 0..i64::from(d.rows) - 1 {
        let shift = (phase(row + 1) - phase(row)).rem_euclid(period);
        assert!((shift - period / 2.0).abs() < 1e-6, "row {row}: {shift}");
    }
}

#[test]
fn perforations_dash_the_line_and_scores_span_the_part() {
    let clip = Polygon::new(rect(0.0, 0.0, 50.0, 30.0));
    let line = [DVec2::new(25.0, 0.0), DVec2::new(25.0, 30.0)];
    let p = unlimited(BendStyle::Perforation, Material::Cardboard, 1.5);
    let dashes = marks(&p, line, &clip).expect("dashes");
    assert!(dashes.len() >= 4);
    let cut: f64 = dashes.iter().map(|m| m.path[0].distance(m.path[1])).sum();
    for m in &dashes {
        assert_eq!(m.kind, MarkKind::Cut);
        assert!(
            m.path
                .iter()
                .all(|q| (q.x - 25.0).abs() < 1e-9 && q.y >= 1.5 - 1e-3 && q.y <= 28.5 + 1e-3)
        );
    }
    assert!(
        cut > 0.6 * 27.0 && cut <= 27.0 + 1e-6,
        "dash/tie = 3:1 of the 27 mm inside: {cut}"
    );
    let s = unlimited(BendStyle::Score, Material::Paper, 0.3);
    let score = marks(&s, line, &clip).expect("score");
    assert_eq!(score.len(), 1);
    assert_eq!(score[0].kind, MarkKind::Score);
    assert!((score[0].path[0].distance(score[0].path[1]) - 30.0).abs() < 1e-9);
}

#[test]
fn segments_are_clipped_to_polygons_with_holes() {
    let mut sq = Polygon::new(rect(0.0, 0.0, 10.0, 10.0));
    sq.holes.push({
        let mut h = rect(4.0, 4.0, 6.0, 6.0);
        h.reverse();
        h
    });
    let pieces = clip_segment(DVec2::new(-5.0, 5.0), DVec2::new(15.0, 5.0), std::slice::from_ref(&sq));
    assert_eq!(
        pieces,
        vec![
            [DVec2::new(0.0, 5.0), DVec2::new(4.0, 5.0)],
            [DVec2::new(6.0, 5.0), DVec2::new(10.0, 5.0)]
        ]
    );
    // Through a vertex, and along an edge.
    assert_eq!(
        clip_segment(DVec2::new(-1.0, -1.0), DVec2::new(3.0, 3.0), std::slice::from_ref(&sq)).len(),
        1
    );
    assert!(
        clip_segment(
            DVec2::new(-1.0, 20.0),
            DVec2::new(11.0, 20.0),
            std::slice::from_ref(&sq)
        )
        .is_empty()
    );
    let edge = clip_segment(
        DVec2::new(-1.0, 10.0),
        DVec2::new(11.0, 10.0),
        std::slice::from_ref(&sq),
    );
    assert!(edge.len() <= 1);
}

#[test]
fn the_swatch_is_at_true_size_with_red_slits() {
    let s = hinge_swatch(None, Material::Wood, 3.0, 90.0).expect("swatch");
    // Wood: a strip per pattern, the lattice first.
    assert_eq!(s.strips.len(), 2);
    let lattice = &s.strips[0];
    assert_eq!(lattice.design.pattern, HingePattern::Lattice);
    assert_eq!(lattice.design.links, 23);
    let (lo, hi) = lattice.strip.bounds();
    let d = &lattice.design;
    assert!(((hi.x - lo.x) - (2.0 * (lattice.line[0].x - lo.x) - d.zone_width) - d.zone_width).abs() < 1e-9);
    for st in &s.strips {
        check_slits(&st.design, st.line, &st.strip, &st.marks);
        let (lo, hi) = st.strip.bounds();
        assert!(s.width - hi.x >= 5.0 - 1e-9 && lo.x >= 5.0 - 1e-9);
    }
    // The flex below the lattice, 5 mm apart, and 5 mm to the sheet's bottom edge.
    let (top, bottom) = (s.strips[0].strip.bounds().1.y, s.strips[1].strip.bounds().0.y);
    assert!((bottom - top - 5.0).abs() < 1e-9);
    assert!((s.height - s.strips[1].strip.bounds().1.y - 5.0).abs() < 1e-9);
    let svg = s.svg();
    let w = crate::draw::svg::num(s.width);
    let h = crate::draw::svg::num(s.height);
    assert!(svg.contains(&format!("width=\"{w}mm\" height=\"{h}mm\" viewBox=\"0 0 {w} {h}\"")));
    let marks: usize = s.strips.iter().map(|st| st.marks.len()).sum();
    assert_eq!(svg.matches("#ff0000").count(), 2 + marks);
    assert!(lattice.marks.len() > 2 * d.rows as usize);
    assert!(svg.matches("#0000ff").count() > 20, "legend strokes");
    let heat = hinge_swatch(Some(BendStyle::Heat), Material::Acrylic, 3.0, 90.0).expect("heat");
    assert_eq!(heat.strips.len(), 1);
    assert_eq!(heat.svg().matches("#ff0000").count(), 1);
    // Acrylic takes the lattice only.
    let acrylic = hinge_swatch(Some(BendStyle::LivingHinge), Material::Acrylic, 3.0, 90.0).expect("acrylic");
    assert_eq!(acrylic.strips.len(), 1);
    assert!(hinge_swatch(None, Material::Wood, -3.0, 90.0).is_err());
}

#[test]
fn the_straight_flex_bends_at_five_thicknesses_where_the_lattice_has_no_room() {
    let quarter = FRAC_PI_2;
    // Unlimited room: the lattice, whose square links make a 73.6 mm zone at 3 mm.
    let wide = design(BendStyle::LivingHinge, Material::Wood, 3.0, quarter, f64::INFINITY).expect("wood");
    assert_eq!(wide.pattern, HingePattern::Lattice);
    // 30 mm of room: no lattice fits (its narrowest links still need more), the flex does,
    // at its 5 t radius rounded up to whole rows.
    let tight = design(BendStyle::LivingHinge, Material::Wood, 3.0, quarter, 30.0).expect("the flex fits");
    assert_eq!(tight.pattern, HingePattern::Straight);
    assert!((tight.zone_width - 24.0).abs() < 1e-9, "{}", tight.zone_width);
    assert!(tight.neutral_radius >= 15.0 && tight.neutral_radius < 15.0 + 1.5 / quarter);
    assert!((tight.slit_length - 12.0).abs() < 1e-9 && (tight.bridge - 3.0).abs() < 1e-9);
    assert!((tight.pitch - 1.5).abs() < 1e-9 && (tight.link_width - 1.3).abs() < 1e-9);
    // Less room than the flex needs: too wide, naming the narrower of the two.
    match design(BendStyle::LivingHinge, Material::Wood, 3.0, quarter, 20.0) {
        Err(HingeError::TooWide { needed, max_width }) => {
            assert!((needed - 24.0).abs() < 1e-9 && max_width == 20.0, "{needed}");
        }
        other => panic!("{other:?}"),
    }
    // Acrylic never takes the flex.
    assert!(design(BendStyle::LivingHinge, Material::Acrylic, 3.0, quarter, 30.0).is_err());
    assert!(design_pattern(HingePattern::Straight, Material::Acrylic, 3.0, quarter).is_none());
    // Its slits are drawn like the lattice's: staggered rows inside the part.
    let part = Polygon::new(rect(0.0, 0.0, 60.0, 50.0));
    let line = [DVec2::new(30.0, 0.0), DVec2::new(30.0, 50.0)];
    let m = marks(&tight, line, &part).expect("marks");
    check_slits(&tight, line, &part, &m);
}

proptest! {
    #[test]
    fn designs_fit_their_room_and_never_overstress_a_link(
        deg in 0.5f64..=90.0, t in 1.0f64..=6.0, room in 2.0f64..300.0,
    ) {
        let turn = deg.to_radians();
        match design(BendStyle::LivingHinge, Material::Wood, t, turn, room) {
            Ok(d) if d.pattern == HingePattern::Straight => {
                // The flex where the lattice has no room: its empirical radius, never tighter.
                prop_assert!(d.zone_width <= room);
                prop_assert!(d.neutral_radius >= 5.0 * t - 1e-9);
            }
            Ok(d) => {
                prop_assert!(d.zone_width <= room);
                let twist = MaterialData::PLYWOOD.max_link_twist(d.link_width, t, d.link_length);
                prop_assert!(f64::from(d.links) * twist >= turn);
                let phi = turn / f64::from(d.links);
                let swept = d.link_width * phi.cos() + t * phi.sin() - d.link_width;
                prop_assert!(swept <= MaterialData::PLYWOOD.kerf + 1e-12, "twisted links clear the kerf");
                prop_assert!(d.link_width >= t / 2.0 - 1e-12 && d.link_length <= 4.0 * t + 1e-12);
            }
            Err(HingeError::TooWide { needed, max_width }) => prop_assert!(needed > max_width),
            Err(e) => prop_assert!(false, "unexpected {e}"),
        }
    }
}

/// Issue 32: across a fillet a zone is widened to the fillet's arc. A hinge gets more rows
/// at its own pitch (its links twist less); a fold becomes creases of at most 15° spread
/// evenly over exactly the arc, drawn one dashed row each; a heat bend stays one line.
#[test]
fn a_zone_widened_to_a_fillet_keeps_its_pitch_or_spreads_its_creases() {
    let turn = std::f64::consts::FRAC_PI_2;
    let flex = design_pattern(HingePattern::Straight, Material::Wood, 3.0, turn).expect("flex");
    let wide = flex.widened(40.0);
    assert_eq!(wide.pitch, flex.pitch);
    assert!(wide.zone_width >= 40.0 && wide.zone_width < 40.0 + flex.pitch);
    assert_eq!(wide.rows, wide.links + 1);
    assert!((wide.neutral_radius - wide.zone_width / turn).abs() < 1e-9);
    assert_eq!(flex.widened(10.0), flex, "never narrower");
    let fold = unlimited(BendStyle::Perforation, Material::Cardboard, 1.5);
    let spread = fold.widened(17.0);
    assert_eq!(spread.rows, 6);
    assert!((spread.zone_width - 17.0).abs() < 1e-9 && (spread.pitch - 17.0 / 6.0).abs() < 1e-9);
    let line = [DVec2::new(0.0, 0.0), DVec2::new(100.0, 0.0)];
    let clip = Polygon::new(vec![
        DVec2::new(-5.0, -20.0),
        DVec2::new(105.0, -20.0),
        DVec2::new(105.0, 20.0),
        DVec2::new(-5.0, 20.0),
    ]);
    let marks = marks(&spread, line, &clip).expect("marks");
    let mut rows: Vec<i64> = marks.iter().map(|m| (m.path[0].y * 1000.0).round() as i64).collect();
    rows.sort_unstable();
    rows.dedup();
    let expected: Vec<i64> = (0..6)
        .map(|i| ((-8.5 + (f64::from(i) + 0.5) * 17.0 / 6.0) * 1000.0).round() as i64)
        .collect();
    assert_eq!(
        rows, expected,
        "one dashed row per crease, each in the middle of its share"
    );
    let heat = design(BendStyle::Heat, Material::Acrylic, 3.0, turn, f64::INFINITY).expect("heat");
    assert_eq!(heat.widened(30.0), heat);
}
