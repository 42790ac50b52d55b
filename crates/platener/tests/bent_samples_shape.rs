//! The bent-plate samples (issue 19) are the solids their formulas say: closed, conforming,
//! wound outwards, of the exact volume and extent, with walls of the asked thickness measured
//! perpendicular to every facet.

use std::collections::BTreeMap;
use std::f64::consts::PI;

use platener::glam::{DVec2, DVec3};
use platener::read::Triangle;
use platener_fixtures::samples::{bent_samples, cone_shell, cup, rounded_tray, tube};
use proptest::prelude::*;

/// An exact key for a vertex: the samples share corners bit for bit.
fn key(p: DVec3) -> [u64; 3] {
    p.to_array().map(f64::to_bits)
}

/// Every edge is used exactly once in each direction (two triangles, opposite orientation),
/// and no triangle is degenerate. Returns the number of distinct edges.
fn assert_watertight(tris: &[Triangle], name: &str) -> usize {
    let mut directed: BTreeMap<([u64; 3], [u64; 3]), usize> = BTreeMap::new();
    for t in tris {
        let area = (t[1] - t[0]).cross(t[2] - t[0]).length() / 2.0;
        assert!(area > 1e-9, "{name}: degenerate triangle {t:?}");
        for i in 0..3 {
            *directed.entry((key(t[i]), key(t[(i + 1) % 3]))).or_default() += 1;
        }
    }
    for (&(a, b), &count) in &directed {
        assert_eq!(count, 1, "{name}: edge used {count} times in one direction");
        assert_eq!(directed.get(&(b, a)), Some(&1), "{name}: edge without its opposite");
    }
    directed.len() / 2
}

/// Signed volume (positive when the surface is wound outwards).
fn volume(tris: &[Triangle]) -> f64 {
    tris.iter().map(|t| t[0].dot(t[1].cross(t[2]))).sum::<f64>() / 6.0
}

fn bounds(tris: &[Triangle]) -> (DVec3, DVec3) {
    tris.iter().flatten().fold(
        (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)),
        |(lo, hi), &p| (lo.min(p), hi.max(p)),
    )
}

fn assert_close(got: f64, want: f64, rel: f64, what: &str) {
    assert!(
        (got - want).abs() <= rel * want.abs().max(1.0),
        "{what}: got {got}, want {want}"
    );
}

fn assert_box(tris: &[Triangle], lo: DVec3, hi: DVec3, name: &str) {
    let (l, h) = bounds(tris);
    for (g, w) in l
        .to_array()
        .into_iter()
        .zip(lo.to_array())
        .chain(h.to_array().into_iter().zip(hi.to_array()))
    {
        assert_close(g, w, 1e-9, &format!("{name} bounds"));
    }
}

/// Every slanted or vertical face (a wall facet) has a face of opposite normal exactly `wall`
/// away: the wall is `wall` thick measured perpendicular to its facet.
fn assert_walls(tris: &[Triangle], wall: f64, name: &str) {
    let planes: Vec<(DVec3, f64)> = tris
        .iter()
        .map(|t| {
            let n = (t[1] - t[0]).cross(t[2] - t[0]).normalize();
            (n, n.dot(t[0]))
        })
        .collect();
    let mut checked = 0;
    for &(n, c) in planes.iter().filter(|(n, _)| n.z.abs() < 0.999) {
        let found = planes
            .iter()
            .filter(|(m, _)| m.dot(n) < -1.0 + 1e-9)
            .map(|&(_, d)| c + d)
            .any(|gap| (gap - wall).abs() < 1e-9);
        assert!(found, "{name}: no face {wall} mm behind the face of normal {n}");
        checked += 1;
    }
    assert!(checked >= 8, "{name}: only {checked} wall faces");
}

/// Area of a regular n-gon of apothem `a`.
fn ngon_area(n: usize, a: f64) -> f64 {
    n as f64 * a * a * (PI / n as f64).tan()
}

/// Extent of a regular n-gon of circumradius `r` with a corner on +x.
fn ngon_box(n: usize, r: f64, h: f64) -> (DVec3, DVec3) {
    let corners: Vec<DVec2> = (0..n)
        .map(|i| DVec2::from_angle(2.0 * PI * i as f64 / n as f64) * r)
        .collect();
    let lo = corners.iter().fold(DVec2::splat(f64::INFINITY), |a, &p| a.min(p));
    let hi = corners.iter().fold(DVec2::splat(f64::NEG_INFINITY), |a, &p| a.max(p));
    (lo.extend(0.0), hi.extend(h))
}

fn check_tube(n: usize, r: f64, h: f64, wall: f64) {
    let name = format!("tube({n}, {r}, {h}, {wall})");
    let tris = tube(n, r, h, wall);
    // A ring of n facets: 4 bands of n quads.
    assert_eq!(tris.len(), 8 * n, "{name}");
    assert_watertight(&tris, &name);
    let a = r * (PI / n as f64).cos();
    assert_close(
        volume(&tris),
        h * (ngon_area(n, a) - ngon_area(n, a - wall)),
        1e-6,
        &name,
    );
    let (lo, hi) = ngon_box(n, r, h);
    assert_box(&tris, lo, hi, &name);
    assert_walls(&tris, wall, &name);
}

fn check_cup(n: usize, r: f64, h: f64, wall: f64) {
    let name = format!("cup({n}, {r}, {h}, {wall})");
    let tris = cup(n, r, h, wall);
    assert_watertight(&tris, &name);
    let a = r * (PI / n as f64).cos();
    let want = h * ngon_area(n, a) - (h - wall) * ngon_area(n, a - wall);
    assert_close(volume(&tris), want, 1e-6, &name);
    let (lo, hi) = ngon_box(n, r, h);
    assert_box(&tris, lo, hi, &name);
    assert_walls(&tris, wall, &name);
}

/// Volume of an n-gon frustum of apothems `a` (bottom) and `b` (top).
fn frustum(n: usize, a: f64, b: f64, h: f64) -> f64 {
    h / 3.0 * n as f64 * (PI / n as f64).tan() * (a * a + a * b + b * b)
}

fn check_cone(n: usize, rb: f64, rt: f64, h: f64, wall: f64) {
    let name = format!("cone_shell({n}, {rb}, {rt}, {h}, {wall})");
    let tris = cone_shell(n, rb, rt, h, wall);
    assert_eq!(tris.len(), 8 * n, "{name}");
    assert_watertight(&tris, &name);
    let cos = (PI / n as f64).cos();
    let (a, b) = (rb * cos, rt * cos);
    // The facet leans by atan((a − b)/h); a perpendicular wall is wall/cos(lean) across.
    let shift = wall / (((a - b) / h).atan()).cos();
    let want = frustum(n, a, b, h) - frustum(n, a - shift, b - shift, h);
    assert_close(volume(&tris), want, 1e-6, &name);
    let (lo, hi) = ngon_box(n, rb.max(rt), h);
    assert_box(&tris, lo, hi, &name);
    assert_walls(&tris, wall, &name);
}

#[test]
fn tubes_are_closed_rings_of_exact_volume() {
    for n in [3, 4, 6, 12, 24, 61] {
        check_tube(n, 50.0, 60.0, 3.0);
    }
    check_tube(8, 10.0, 5.0, 0.5);
}

#[test]
fn cups_are_closed_of_exact_volume() {
    for n in [3, 5, 8, 16, 40] {
        check_cup(n, 40.0, 50.0, 3.0);
    }
}

#[test]
fn cone_shells_are_closed_of_exact_volume_either_way_up() {
    for n in [3, 6, 24, 50] {
        check_cone(n, 60.0, 35.0, 50.0, 1.5);
    }
    check_cone(10, 20.0, 45.0, 30.0, 2.0);
}

#[test]
fn cone_shell_develops_into_less_than_a_turn() {
    // The defaults of the figures: 24 facets, r 60 → 35, 50 high. Each outer facet, extended
    // to the apex, is an isosceles triangle of apex angle 2·atan(half edge / slant apothem).
    let (n, rb, rt, h) = (24, 60.0, 35.0, 50.0);
    let tris = cone_shell(n, rb, rt, h, 1.5);
    let a = rb * (PI / n as f64).cos();
    let apex = h * rb / (rb - rt);
    let per_facet = 2.0 * (a * (PI / n as f64).tan() / (apex * apex + a * a).sqrt()).atan();
    let total = (n as f64 * per_facet).to_degrees();
    assert!((150.0..170.0).contains(&total), "{total}°");
    // The same angle measured on the mesh: the outer faces' normals lean by the half angle.
    let n0 = tris
        .iter()
        .map(|t| (t[1] - t[0]).cross(t[2] - t[0]).normalize())
        .find(|n| n.z > 1e-6 && n.z < 0.999)
        .expect("a slanted outer face");
    assert_close(n0.z, a / (apex * apex + a * a).sqrt(), 1e-9, "lean of the facets");
}

#[test]
fn rounded_tray_is_closed_of_exact_volume() {
    for (f, r, wall) in [(1, 10.0, 3.0), (2, 12.0, 2.0), (6, 15.0, 3.0), (9, 15.0, 1.0)] {
        let (w, d, h) = (120.0, 80.0, 40.0);
        let name = format!("rounded_tray({w}, {d}, {h}, {r}, {f}, {wall})");
        let tris = rounded_tray(w, d, h, r, f, wall);
        assert_watertight(&tris, &name);
        // The outline: a rectangle with its corners cut by f chords of a circle of radius r.
        let step = PI / 2.0 / f as f64;
        let outer = w * d - 4.0 * r * r + 2.0 * f as f64 * r * r * step.sin();
        let perimeter = 2.0 * (w + d - 4.0 * r) + 8.0 * f as f64 * r * (step / 2.0).sin();
        // Offsetting a convex polygon inwards by t takes perimeter·t and gives back
        // t²·Σ tan(exterior angle / 2): per corner f − 1 turns of `step` and two of step/2.
        let turns = 4.0 * ((f as f64 - 1.0) * (step / 2.0).tan() + 2.0 * (step / 4.0).tan());
        let inner = outer - perimeter * wall + turns * wall * wall;
        assert_close(volume(&tris), h * outer - (h - wall) * inner, 1e-6, &name);
        assert_box(&tris, DVec3::ZERO, DVec3::new(w, d, h), &name);
        assert_walls(&tris, wall, &name);
    }
}

#[test]
fn the_figure_samples_are_closed_and_outward() {
    let samples = bent_samples();
    assert_eq!(samples.len(), 6);
    for (name, tris) in samples {
        let w = platener::weld::weld_soup(&tris, 0.0);
        let m = platener::mesh::Mesh::build(w.vertices, &w.triangles, 1e-9);
        assert!(m.health.closed, "{name}");
        assert_eq!(m.health.flipped_faces, 0, "{name}");
        assert!(m.health.volume.expect("closed") > 0.0, "{name}");
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]

    #[test]
    fn any_tube_is_watertight_with_its_volume(n in 3usize..64, r in 5.0f64..200.0, h in 1.0f64..100.0, f in 0.02f64..0.5) {
        check_tube(n, r, h, r * (PI / n as f64).cos() * f);
    }

    #[test]
    fn any_cup_is_watertight_with_its_volume(n in 3usize..48, r in 5.0f64..200.0, f in 0.02f64..0.4) {
        let wall = r * (PI / n as f64).cos() * f;
        check_cup(n, r, 2.5 * wall + 10.0, wall);
    }

    #[test]
    fn any_cone_shell_is_watertight_with_its_volume(n in 3usize..48, rb in 20.0f64..100.0, rt in 20.0f64..100.0, h in 10.0f64..80.0) {
        check_cone(n, rb, rt, h, 1.0);
    }
}
