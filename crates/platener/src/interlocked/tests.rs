//! Slices, slots and pieces on models whose geometry is known: a sphere, a torus lying flat,
//! random ellipsoids. The insertion check is geometric: for every A piece and B piece whose
//! slices cross, the A piece's material in their column lies above the B piece's, so the A
//! piece lowered from above meets the B piece only in its slot.

use glam::DVec3;
use proptest::prelude::*;

use super::cross::{column, cut};
use super::held::{Made, pieces};
use super::place::{self, Family, families, sections};
use super::*;
use crate::cuttable::Rule;
use crate::read::Triangle;
use crate::weld::weld_soup;
use platener_fixtures::samples::{ellipsoid, sphere, torus};

/// Heights closer than this count as equal (the booleans' 1 µm grid, with room).
const EPS: f64 = 1e-3;

fn made(tris: &[Triangle], t: f64, spacing: f64) -> ([Family; 2], Made) {
    let w = weld_soup(tris, 0.0);
    let mesh = Mesh::build(w.vertices, &w.triangles, 1e-9);
    let families = families(&mesh, spacing).expect("triangles");
    let rule = Rule::for_sheet(t, 0.0, 0.0);
    let sections = sections(&mesh, &families, t, 1e-6, &rule).expect("on the grid");
    let crossed = cut(&families, &sections, t, 0.2, &rule).expect("on the grid");
    (
        families,
        pieces(&families, crossed, t / 2.0, &rule).expect("on the grid"),
    )
}

/// Every A piece lowered from above clears every B piece outside its slots: in each crossing
/// column, A's lowest material is no lower than B's highest. Returns the columns where both
/// had material.
fn assert_insertion_clear(families: &[Family; 2], made: &Made, t: f64) -> usize {
    let mut met = 0;
    for a in made.pieces.iter().filter(|p| p.family == 0) {
        for b in made.pieces.iter().filter(|p| p.family == 1) {
            let at = column(families, a.slice, b.slice);
            let ea = column_extent(std::slice::from_ref(&a.polygon), at[0], t / 2.0).expect("grid");
            let eb = column_extent(std::slice::from_ref(&b.polygon), at[1], t / 2.0).expect("grid");
            if let (Some(lo), Some(hi)) = (ea.first(), eb.last()) {
                met += 1;
                assert!(
                    lo[0] >= hi[1] - EPS,
                    "{} meets {} below its slot: {ea:?} over {eb:?}",
                    a.name,
                    b.name
                );
            }
        }
    }
    met
}

/// Every piece is held by at least one crossing, and every crossing names two pieces.
fn assert_all_held(made: &Made) {
    for p in &made.pieces {
        assert!(
            made.crossings.iter().any(|c| c.parts.contains(&p.part)),
            "{} is held by nothing",
            p.name
        );
    }
    for c in &made.crossings {
        let family = |id: u32| made.pieces.iter().find(|p| p.part == id).map(|p| p.family);
        assert_eq!((family(c.parts[0]), family(c.parts[1])), (Some(0), Some(1)));
    }
}

#[test]
fn a_sphere_is_eight_by_eight_slices_halved_at_its_equator() {
    let (families, made) = made(&sphere(DVec3::ZERO, 40.0, 96, 48), 3.0, 10.0);
    assert_eq!(families.map(|f| f.count()), [8, 8]);
    for (f, k) in [(0, 0), (0, 7), (1, 3)] {
        let expected = -35.0 + 10.0 * k as f64;
        assert!(
            (families[f].offset(k) - expected).abs() < 1e-9,
            "{}",
            families[f].offset(k)
        );
    }
    assert_eq!(made.pieces.len(), 16);
    assert!(made.left_out.is_empty(), "{:?}", made.left_out);
    // Columns at (±5…±35, ±5…±35) strictly inside the sphere: 52 of 64.
    assert_eq!(made.crossings.len(), 52);
    for c in &made.crossings {
        // The sections are symmetric about z = 0: the split is the equator.
        assert!(c.split.abs() < EPS, "{c:?}");
        let [lo, hi] = c.shared.expect("material on both sides");
        assert!((lo + hi).abs() < EPS && hi > 0.0, "{c:?}");
    }
    // Each slot takes half the column, t wide: the pieces lose exactly their slots.
    let lost: f64 = made
        .crossings
        .iter()
        .filter_map(|c| c.shared)
        .map(|[lo, hi]| 3.0 * (hi - lo))
        .sum();
    // A slice's material is its section at the face farther from the centre.
    let section_area = |k: usize| {
        let r2 = 40.0f64.powi(2) - (families[0].offset(k).abs() + 1.5 - place::FACE_INSET).powi(2);
        std::f64::consts::PI * r2
    };
    let sections: f64 = (0..8).map(section_area).sum::<f64>() * 2.0;
    let kept: f64 = made.pieces.iter().map(|p| p.polygon.area()).sum();
    // The tessellated sphere is a little smaller than the true one (96 × 48 facets: < 0.3 %);
    // a slot runs from the split to the piece's own edge in its strip, which is a little
    // beyond the shared range where the edge curves (< 0.3 %).
    let relative = (kept + lost - sections) / sections;
    assert!(relative.abs() < 0.006, "kept {kept} + slots {lost} against {sections}");
    assert_all_held(&made);
    assert_eq!(assert_insertion_clear(&families, &made, 3.0), 52);
    assert_eq!(made.order().len(), 16);
    assert!(
        made.order()[..8]
            .iter()
            .all(|id| made.pieces[*id as usize - 1].family == 1)
    );
}

#[test]
fn a_torus_lying_flat_gives_two_pieces_per_slice_through_its_hole() {
    let (families, made) = made(
        &torus(DVec3::new(0.0, 0.0, 15.0), DVec3::Z, 40.0, 15.0, 64, 24),
        3.0,
        10.0,
    );
    assert_eq!(families.map(|f| f.count()), [11, 11]);
    // Slices at ±5 … ±15 through the hole (radius 25) are cut in two; the others are one.
    for (f, family) in families.iter().enumerate() {
        for k in 0..11 {
            let n = made.pieces.iter().filter(|p| (p.family, p.slice) == (f, k)).count();
            let through_hole = family.offset(k).abs() < 25.0;
            assert_eq!(n, if through_hole { 2 } else { 1 }, "slice {}{}", family.letter, k + 1);
        }
    }
    assert!(made.pieces.iter().any(|p| p.name == "A6-1") && made.pieces.iter().any(|p| p.name == "A6-2"));
    assert_all_held(&made);
    assert!(assert_insertion_clear(&families, &made, 3.0) > 40);
}

#[test]
fn a_piece_no_slice_of_the_other_family_meets_is_left_out_and_said() {
    // A 60 mm ball and, 24 mm away along x, an 8 × 6 mm rod standing between two B planes.
    let mut tris = sphere(DVec3::ZERO, 30.0, 48, 24);
    tris.extend(platener_fixtures::samples::cuboid(
        DVec3::new(54.0, -3.0, -20.0),
        DVec3::new(62.0, 3.0, 20.0),
    ));
    let (_, made) = made(&tris, 3.0, 10.0);
    let unheld: Vec<&LeftOut> = made.left_out.iter().filter(|l| l.why == Why::Unheld).collect();
    assert!(!unheld.is_empty(), "{:?}", made.left_out);
    assert!(unheld[0].describe().contains("crosses no slice of the other family"));
    assert_all_held(&made);
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 12, .. ProptestConfig::default() })]

    /// Random ellipsoids: every piece held, every A piece lowered clear of every B piece.
    #[test]
    fn random_ellipsoids_interlock_and_insert(
        rx in 20.0f64..60.0, ry in 20.0f64..60.0, rz in 15.0f64..50.0,
        cx in -20.0f64..20.0, spacing in 9.0f64..16.0,
    ) {
        let tris = ellipsoid(DVec3::new(cx, 0.0, rz), DVec3::new(rx, ry, rz), 48, 24);
        let (families, made) = made(&tris, 3.0, spacing);
        prop_assert!(!made.pieces.is_empty());
        assert_all_held(&made);
        prop_assert!(assert_insertion_clear(&families, &made, 3.0) > 0);
        // An ellipsoid's sections are convex: no slice falls apart.
        prop_assert!(made.pieces.iter().all(|p| !p.name.contains('-')));
    }
}

#[test]
fn a_hollow_box_is_sliced_solid_and_a_standing_torus_keeps_its_middle() {
    // A closed 100 × 80 × 60 box with 3 mm walls: its slices' holes are the box's hollow,
    // enclosed along the slices' normals, so each slice is the whole 80 × 60 (A) or
    // 100 × 60 (B) rectangle less its slots, not a ring of walls.
    let (_, boxed) = made(
        &platener_fixtures::samples::closed_box(100.0, 80.0, 60.0, 3.0),
        3.0,
        10.0,
    );
    // Each slot is 3 mm wide and half the 60 mm height.
    for p in &boxed.pieces {
        let full = if p.family == 0 { 80.0 * 60.0 } else { 100.0 * 60.0 };
        let slots = boxed.crossings.iter().filter(|c| c.parts.contains(&p.part)).count();
        assert_eq!(slots, if p.family == 0 { 8 } else { 10 }, "{}", p.name);
        assert!(p.polygon.holes.is_empty(), "{}", p.name);
        let expected = full - slots as f64 * 3.0 * 30.0;
        assert!(
            (p.polygon.area() - expected).abs() < 0.01,
            "{}: {} against {expected}",
            p.name,
            p.polygon.area()
        );
    }
    // A torus standing on its rim (axis y): the B slices (across y) through its middle are
    // rings, whose hole is open along y and stays (their slots then open it at the top).
    let tris = torus(DVec3::new(0.0, 0.0, 55.0), DVec3::Y, 40.0, 15.0, 64, 24);
    let w = weld_soup(&tris, 0.0);
    let mesh = Mesh::build(w.vertices, &w.triangles, 1e-9);
    let families = families(&mesh, 10.0).expect("triangles");
    assert_eq!(families[1].plan.frame.n.abs(), DVec3::Y);
    let cut = sections(&mesh, &families, 3.0, 1e-6, &Rule::for_sheet(3.0, 0.0, 0.0)).expect("grid");
    for (k, islands) in cut.islands[1].iter().enumerate() {
        assert_eq!(islands.len(), 1, "B{}", k + 1);
        assert_eq!(islands[0].holes.len(), 1, "B{}", k + 1);
    }
}
