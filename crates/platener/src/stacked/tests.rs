//! Slicing, loops, islands and shaft placement on models whose geometry is known exactly.
//! Areas are compared within 1e-6 mm² per mm² of section (float rounding and the 1 µm grid of
//! the booleans), positions within 1e-3 mm (one grid step).

use glam::{DVec2, DVec3};
use platener_geom::Polygon;
use platener_geom::polygon::total_area;
use proptest::prelude::*;

use super::fit::fit_slot;
use super::shafts::place;
use super::*;
use crate::mesh::Mesh;
use crate::read::Triangle;
use crate::settings::{StackAxis, StackedSettings};
use crate::weld::weld_soup;
use platener_fixtures::samples::{cuboid, sphere, torus, two_bodies, voxels};

fn mesh(tris: &[Triangle]) -> Mesh {
    let w = weld_soup(tris, 0.0);
    Mesh::build(w.vertices, &w.triangles, 1e-9)
}

/// Layer areas of `tris` sliced along `up` with layers `t` thick.
fn layer_areas(tris: &[Triangle], up: DVec3, t: f64) -> (Sliced, Vec<f64>) {
    let m = mesh(tris);
    let plan = SlicePlan::new(&m, up, AxisChoice::Given, t).expect("triangles");
    let sliced = slice(&m, &plan, 1e-6);
    // Keep every island, however small.
    let keep_all = crate::cuttable::Rule {
        min_area: 0.0,
        min_width: 0.0,
    };
    let islands = islands_of(&sliced, &keep_all).expect("on the grid");
    let areas = islands.islands.iter().map(|l| total_area(l)).collect();
    (sliced, areas)
}

fn rect(x0: f64, y0: f64, x1: f64, y1: f64) -> Polygon {
    Polygon::new(platener_geom::polygon::rect(x0, y0, x1, y1))
}

#[test]
fn a_box_gives_one_exact_rectangle_per_layer() {
    let (sliced, areas) = layer_areas(&cuboid(DVec3::ZERO, DVec3::new(10.0, 20.0, 30.0)), DVec3::Z, 3.0);
    assert_eq!(areas.len(), 10);
    for a in &areas {
        assert!((a - 200.0).abs() < 2e-4, "{a}");
    }
    assert_eq!(sliced.stats.bridged + sliced.stats.dropped, 0);
    assert_eq!(sliced.stats.closed, 10);
}

#[test]
fn faces_and_vertices_on_a_plane_count_as_just_above_it() {
    // A 10 × 10 × 1.5 slab with a 5 × 10 block on top up to z = 3; the plane of layer 2 is
    // z = 1.5, exactly the top face of the slab, which yields no segment: the section is the
    // one just below the plane, the whole slab.
    let tris = voxels(&[0.0, 5.0, 10.0], &[0.0, 10.0], &[0.0, 1.5, 3.0], |i, _, k| {
        k == 0 || i == 0
    });
    let (_, areas) = layer_areas(&tris, DVec3::Z, 1.0);
    assert_eq!(areas.len(), 3);
    for (a, want) in areas.iter().zip([100.0, 100.0, 50.0]) {
        assert!((a - want).abs() < 1e-4, "{areas:?}");
    }
    // An octahedron with its four equator vertices on the middle plane: the section there is
    // the equator square (diagonals 10 mm, 50 mm²), the planes 2 mm off give diagonals 6 mm.
    let p = |x: f64, y: f64, z: f64| DVec3::new(x, y, z);
    let (n, s) = (p(0.0, 0.0, 5.0), p(0.0, 0.0, -5.0));
    let eq = [p(5.0, 0.0, 0.0), p(0.0, 5.0, 0.0), p(-5.0, 0.0, 0.0), p(0.0, -5.0, 0.0)];
    let mut octa = Vec::new();
    for i in 0..4 {
        let (a, b) = (eq[i], eq[(i + 1) % 4]);
        octa.push([n, a, b]);
        octa.push([s, b, a]);
    }
    let (_, areas) = layer_areas(&octa, DVec3::Z, 2.0);
    assert_eq!(areas.len(), 5);
    for (a, want) in areas.iter().zip([2.0, 18.0, 50.0, 18.0, 2.0]) {
        assert!((a - want).abs() < 1e-4, "{areas:?}");
    }
}

#[test]
fn loops_close_across_a_missing_triangle() {
    // A 10 × 20 × 30 box whose faces are cut into 5 mm squares.
    let steps = |n: usize| (0..=n).map(|i| 5.0 * i as f64).collect::<Vec<_>>();
    let mut tris = voxels(&steps(2), &steps(4), &steps(6), |_, _, _| true);
    // Drop one triangle of a side wall: the planes through it meet an open chain.
    let side = tris
        .iter()
        .position(|t| t.iter().all(|p| p.x == 0.0) && t.iter().any(|p| p.z == 10.0))
        .expect("a triangle on x = 0");
    tris.remove(side);
    let (sliced, areas) = layer_areas(&tris, DVec3::Z, 3.0);
    assert!(sliced.stats.bridged > 0);
    assert_eq!(sliced.stats.dropped, 0);
    for a in &areas {
        assert!((a - 200.0).abs() < 2e-4, "{areas:?}");
    }
}

#[test]
fn overlapping_bodies_unite_and_cavities_become_holes() {
    let mut two = cuboid(DVec3::ZERO, DVec3::splat(10.0));
    two.extend(cuboid(DVec3::new(5.0, 0.0, 0.0), DVec3::new(15.0, 10.0, 10.0)));
    let (_, areas) = layer_areas(&two, DVec3::Z, 2.0);
    for a in &areas {
        assert!((a - 150.0).abs() < 1e-4, "{areas:?}");
    }
    // A closed box of 3 mm walls is a shell with a cavity shell inside.
    let hollow = platener_fixtures::samples::closed_box(100.0, 80.0, 60.0, 3.0);
    let (_, areas) = layer_areas(&hollow, DVec3::Z, 3.0);
    assert_eq!(areas.len(), 20);
    for a in &areas[1..19] {
        assert!((a - (8000.0 - 94.0 * 74.0)).abs() < 1e-3, "{areas:?}");
    }
    assert!((areas[0] - 8000.0).abs() < 1e-3);
}

#[test]
fn the_largest_flat_face_is_laid_down() {
    // A wedge whose largest face is its sloped top: the stack's up is into that face.
    let profile = [DVec2::new(0.0, 0.0), DVec2::new(80.0, 0.0), DVec2::new(0.0, 60.0)];
    let tris = platener_fixtures::samples::prism(&profile, 100.0);
    let m = mesh(&tris);
    let groups = crate::coplanar::group_faces(&m, 1f64.to_radians());
    let (up, choice) = choose_up(&m, Some(&groups), StackAxis::Auto);
    assert!(matches!(choice, AxisChoice::FlatFace { .. }));
    let slope = DVec3::new(60.0, 0.0, 80.0).normalize();
    assert!((up + slope).length() < 1e-9, "{up}");
    // A sphere has no flat face of note: z stays up.
    let ball = mesh(&sphere(DVec3::ZERO, 20.0, 48, 24));
    let groups = crate::coplanar::group_faces(&ball, 1f64.to_radians());
    assert_eq!(
        choose_up(&ball, Some(&groups), StackAxis::Auto),
        (DVec3::Z, AxisChoice::ModelZ)
    );
    assert_eq!(choose_up(&ball, Some(&groups), StackAxis::X).0, DVec3::X);
}

#[test]
fn generated_bodies_are_closed_and_wound_outwards() {
    use std::f64::consts::PI;
    let cases = [
        (sphere(DVec3::ZERO, 50.0, 96, 48), 4.0 / 3.0 * PI * 50f64.powi(3)),
        (
            torus(DVec3::ZERO, DVec3::Y, 40.0, 15.0, 96, 48),
            2.0 * PI * PI * 40.0 * 15.0 * 15.0,
        ),
        (
            two_bodies(10.0),
            4.0 / 3.0 * PI * 30f64.powi(3) + 2.0 * PI * PI * 40.0 * 15.0 * 15.0,
        ),
    ];
    for (tris, volume) in cases {
        let m = mesh(&tris);
        assert!(m.health.closed);
        assert_eq!(m.health.flipped_faces, 0);
        // Inscribed facets lose a little volume: within 2 %.
        let v = m.health.volume.expect("closed");
        assert!(v < volume && v > 0.98 * volume, "{v} vs {volume}");
    }
}

#[test]
fn a_slot_runs_along_a_long_region() {
    let region = [rect(0.0, 0.0, 60.0, 20.0)];
    let slot = fit_slot(&region, 1.5, 10.0, 100.0).expect("grid").expect("fits");
    assert!((slot.dir.x.abs() - 1.0).abs() < 1e-9, "{slot:?}");
    assert!((slot.width - 57.0).abs() < 1e-3, "{slot:?}");
    // The centre line is the region's middle line, within the sampling of the search.
    assert!((slot.start.y - 10.0).abs() < 20.0 / 48.0, "{slot:?}");
    assert!(
        fit_slot(&[rect(0.0, 0.0, 60.0, 2.9)], 1.5, 10.0, 100.0)
            .expect("grid")
            .is_none()
    );
    // Capped at the maximum width, about the middle.
    let capped = fit_slot(&region, 1.5, 10.0, 30.0).expect("grid").expect("fits");
    assert!((capped.width - 30.0).abs() < 1e-9);
    let mid = capped.start + capped.dir * 15.0;
    assert!((mid.x - 30.0).abs() < 1e-3, "{capped:?}");
}

#[test]
fn phase_one_runs_a_shaft_through_every_layer_the_overlap_allows() {
    // Four 40 × 40 squares, the fourth shifted by 20 mm, then one that overlaps nothing.
    let mut islands: Vec<Vec<Polygon>> = (0..3).map(|_| vec![rect(0.0, 0.0, 40.0, 40.0)]).collect();
    islands.push(vec![rect(20.0, 0.0, 60.0, 40.0)]);
    islands.push(vec![rect(100.0, 0.0, 140.0, 40.0)]);
    let s = StackedSettings::default();
    let placed = place(&islands, &s, 3.0).expect("grid");
    assert_eq!(placed.removed, 0);
    assert!(placed.unjoined.is_empty());
    assert_eq!(placed.shafts.len(), 1);
    let sh = &placed.shafts[0];
    assert_eq!(sh.phase, 1);
    assert_eq!(sh.bands.iter().map(|b| b.layer).collect::<Vec<_>>(), [0, 1, 2, 3]);
    assert!(sh.line.width >= s.shaft_min_width);
    // Its slot keeps the margin inside every island it passes through.
    let slot = sh.line.rect(0.0, sh.line.width, 1.5);
    for b in &sh.bands {
        let inner = platener_geom::offset::offset(&islands[b.layer][b.island..=b.island], -s.margin).expect("grid");
        let out = platener_geom::boolean::difference(std::slice::from_ref(&slot), &inner).expect("grid");
        assert!(total_area(&out) < 1e-6, "layer {}: {}", b.layer, total_area(&out));
    }
}

#[test]
fn phase_two_extends_a_shaft_flush_into_a_narrow_layer() {
    // Two 60 × 20 layers, then an 8 mm strip overlapping their right half: too narrow for a
    // slot with 3 mm margins, so the shaft of the first two layers is extended into it, its
    // slot cut where its columns are inside the strip: from the strip's end at x = 30.
    let islands = vec![
        vec![rect(0.0, 0.0, 60.0, 20.0)],
        vec![rect(0.0, 0.0, 60.0, 20.0)],
        vec![rect(30.0, 6.0, 80.0, 14.0)],
    ];
    let placed = place(&islands, &StackedSettings::default(), 3.0).expect("grid");
    assert!(placed.unjoined.is_empty());
    assert_eq!(placed.shafts.len(), 1);
    let sh = &placed.shafts[0];
    assert_eq!(sh.bands.len(), 3);
    let (full, top) = (sh.bands[1], sh.bands[2]);
    let at = |s: f64| sh.line.start + sh.line.dir * s;
    let (a, b) = (at(top.from).x.min(at(top.to).x), at(top.from).x.max(at(top.to).x));
    assert!((a - 30.0).abs() < 1e-3, "flush with the strip's end: {a}");
    assert!(
        (b - at(full.from).x.max(at(full.to).x)).abs() < 1e-9,
        "within the slot below: {b}"
    );
}

#[test]
fn islands_joined_by_nothing_are_reported() {
    // Layers overlapping by a 1 mm sliver: no slot fits even with relaxed margins.
    let islands = vec![vec![rect(0.0, 0.0, 40.0, 40.0)], vec![rect(39.0, 0.0, 79.0, 40.0)]];
    let placed = place(&islands, &StackedSettings::default(), 3.0).expect("grid");
    assert!(placed.shafts.is_empty());
    assert_eq!(placed.unjoined.len(), 1);
    assert!((placed.unjoined[0].overlap - 40.0).abs() < 1e-6);
}

#[test]
fn stacked_settings_are_checked_and_axes_parse() {
    assert!(StackedSettings::default().validate().is_ok());
    let bad = StackedSettings {
        shaft_min_width: 50.0,
        shaft_max_width: 40.0,
        ..StackedSettings::default()
    };
    assert!(bad.validate().is_err());
    let bad = StackedSettings {
        layer_thickness: Some(0.0),
        ..StackedSettings::default()
    };
    assert!(bad.validate().is_err());
    assert_eq!("Z".parse::<StackAxis>().ok(), Some(StackAxis::Z));
    assert_eq!("auto".parse::<StackAxis>().ok(), Some(StackAxis::Auto));
    assert!("w".parse::<StackAxis>().is_err());
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(24))]

    /// A box turned about the slicing axis and moved anywhere: `round(h / t)` layers, each the
    /// box's exact footprint.
    #[test]
    fn every_layer_of_a_box_is_its_footprint(
        w in 5.0f64..80.0, d in 5.0f64..80.0, h in 3.0f64..60.0,
        t in 0.8f64..6.0, angle in 0.0f64..6.3,
        ox in -100.0f64..100.0, oy in -100.0f64..100.0, oz in -100.0f64..100.0,
    ) {
        let (s, c) = angle.sin_cos();
        let turn = |p: DVec3| DVec3::new(c * p.x - s * p.y + ox, s * p.x + c * p.y + oy, p.z + oz);
        let tris: Vec<Triangle> = cuboid(DVec3::ZERO, DVec3::new(w, d, h))
            .into_iter()
            .map(|tri| tri.map(turn))
            .collect();
        let (sliced, areas) = layer_areas(&tris, DVec3::Z, t);
        prop_assert_eq!(sliced.plan.count, ((h / t).round() as usize).max(1));
        for a in &areas {
            // 1 µm grid on a perimeter of 2(w + d): at most 1e-3 · perimeter of area.
            prop_assert!((a - w * d).abs() < 1e-3 * 2.0 * (w + d), "{} vs {}", a, w * d);
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(16))]

    /// Any sphere in any sheet thickness: every overlapping pair of layers is joined, every
    /// shaft spans consecutive layers (at least two) and its outline is exactly its slots, and
    /// every layer loses to its slots the shafts' sections plus at most the pinches opened
    /// beside their ends (under a bridge wide, across the slot's thickness at each end), and
    /// stays a valid outline at a 0.2 mm kerf.
    #[test]
    fn spheres_stack_with_every_pair_joined_and_exact_slots(
        r in 20.0f64..60.0, t in 2.0f64..6.0,
        cx in -50.0f64..50.0, cy in -50.0f64..50.0, cz in -50.0f64..50.0,
    ) {
        let m = mesh(&sphere(DVec3::new(cx, cy, cz), r, 48, 24));
        let plan = SlicePlan::new(&m, DVec3::Z, AxisChoice::Given, t).expect("triangles");
        let sliced = slice(&m, &plan, 1e-6);
        let s = StackedSettings::default();
        let layers = islands_of(&sliced, &super::island_rule(t, &s)).expect("grid");
        let placed = place(&layers.islands, &s, t).expect("grid");
        prop_assert!(placed.unjoined.is_empty(), "{:?}", placed.unjoined);
        let bridge = placed.bridge;
        let stack = super::assemble::assemble(plan, t, layers, placed, sliced.stats).expect("grid");
        let mut lost: Vec<Vec<(f64, f64)>> = stack.layers.iter().map(|l| vec![(0.0, 0.0); l.islands.len()]).collect();
        for sh in &stack.shafts {
            let ks: Vec<usize> = sh.bands.iter().map(|b| b.layer).collect();
            prop_assert!(ks.len() >= 2);
            prop_assert!(ks.windows(2).all(|w| w[1] == w[0] + 1), "{:?}", ks);
            let slots: f64 = sh.bands.iter().map(|b| (b.to - b.from) * t).sum();
            prop_assert!((sh.polygon.area() - slots).abs() < 1e-6 * slots, "{} vs {}", sh.polygon.area(), slots);
            for b in &sh.bands {
                lost[b.layer][b.island].0 += (b.to - b.from) * t;
                lost[b.layer][b.island].1 += 1.0;
            }
        }
        for (l, lost) in stack.layers.iter().zip(&lost) {
            for (island, &(want, slots)) in l.islands.iter().zip(lost) {
                let got = island.outline.area() - island.polygon.area();
                // The 1 µm grid along the slot's perimeter.
                let grid = 1e-3 * (2.0 * want / t + 2.0 * t);
                let pinches = slots * 2.0 * bridge * t;
                prop_assert!(got > want - grid && got < want + pinches + grid, "{} vs {}", got, want);
                let findings = platener_geom::validity::validate(&island.polygon, 0.2);
                prop_assert!(findings.is_empty(), "layer {}: {:?}", l.number, findings);
            }
        }
    }
}

#[test]
fn a_loop_knows_the_share_of_its_length_cut_from_marked_triangles() {
    // A 10 × 30 × 20 box: each section is a loop 80 mm round …
    let tris = cuboid(DVec3::ZERO, DVec3::new(10.0, 30.0, 20.0));
    let m = mesh(&tris);
    let marked: Vec<bool> = m
        .triangles
        .iter()
        .map(|t| t.iter().all(|&v| m.vertices[v as usize].y == 0.0))
        .collect();
    let plan = SlicePlan::new(&m, DVec3::Z, AxisChoice::Given, 5.0).expect("triangles");
    let sliced = super::slice_marked(&m, &plan, 1e-6, &marked);
    assert_eq!(sliced.loops.len(), 4);
    for loops in &sliced.loops {
        let [l] = &loops[..] else {
            panic!("one loop per section")
        };
        // … the face y = 0 is 10 mm of the 80.
        assert!((l.marked - 10.0 / 80.0).abs() < 1e-12, "{}", l.marked);
    }
    // Unmarked slicing marks nothing.
    assert!(slice(&m, &plan, 1e-6).loops.iter().flatten().all(|l| l.marked == 0.0));
}
