use glam::DVec3;

use super::*;
use crate::weld::weld_soup;
use platener_fixtures::samples::cuboid;

fn build(soup: &[[DVec3; 3]]) -> Mesh {
    let w = weld_soup(soup, 0.0);
    Mesh::build(w.vertices, &w.triangles, 1e-9)
}

#[test]
fn cuboid_is_closed_with_its_volume() {
    let m = build(&cuboid(DVec3::ZERO, DVec3::new(10.0, 20.0, 30.0)));
    assert_eq!(m.triangles.len(), 12);
    assert_eq!(m.topology.edges.len(), 18);
    let h = &m.health;
    assert!(h.closed);
    assert_eq!(
        (h.open_edges, h.non_manifold_edges, h.components, h.flipped_faces),
        (0, 0, 1, 0)
    );
    assert!((h.volume.expect("closed") - 6000.0).abs() < 1e-9);
    assert!((m.surface_area - 2.0 * (200.0 + 300.0 + 600.0)).abs() < 1e-9);
}

#[test]
fn one_flipped_face_is_turned_round() {
    let mut soup = cuboid(DVec3::ZERO, DVec3::splat(4.0));
    for start in [0, 5, 11] {
        let mut s = soup.clone();
        s[start].swap(1, 2);
        let m = build(&s);
        assert_eq!(m.health.flipped_faces, 1, "flipped face {start}");
        assert!(m.health.volume.expect("closed") > 0.0);
    }
    // Wholly inside out: every face turned, volume positive.
    soup.iter_mut().for_each(|t| t.swap(1, 2));
    let m = build(&soup);
    assert_eq!(m.health.flipped_faces, 12);
    assert!((m.health.volume.expect("closed") - 64.0).abs() < 1e-9);
    // Every normal points away from the centre.
    for f in 0..12 {
        let [a, b, c] = m.corners(f);
        assert!(m.normals[f].dot((a + b + c) / 3.0 - DVec3::splat(2.0)) > 0.0);
    }
}

#[test]
fn holes_and_bodies_are_counted() {
    let mut soup = cuboid(DVec3::ZERO, DVec3::ONE);
    soup.pop();
    let m = build(&soup);
    assert_eq!(m.health.open_edges, 3);
    assert!(!m.health.closed && m.health.volume.is_none());
    let mut two = cuboid(DVec3::ZERO, DVec3::ONE);
    two.extend(cuboid(DVec3::splat(5.0), DVec3::splat(6.0)));
    assert_eq!(build(&two).health.components, 2);
}

#[test]
fn three_faces_on_one_edge_are_non_manifold() {
    let p = |x: f64, y: f64, z: f64| DVec3::new(x, y, z);
    let soup = vec![
        [p(0.0, 0.0, 0.0), p(1.0, 0.0, 0.0), p(0.5, 1.0, 0.0)],
        [p(1.0, 0.0, 0.0), p(0.0, 0.0, 0.0), p(0.5, -1.0, 0.0)],
        [p(0.0, 0.0, 0.0), p(1.0, 0.0, 0.0), p(0.5, 0.0, 1.0)],
    ];
    let m = build(&soup);
    assert_eq!(m.health.non_manifold_edges, 1);
    assert_eq!(m.health.open_edges, 6);
}

#[test]
fn a_cavity_keeps_its_normals_pointing_into_the_void() {
    let soup = platener_fixtures::samples::closed_box(100.0, 80.0, 60.0, 3.0);
    let want = 100.0 * 80.0 * 60.0 - 94.0 * 74.0 * 54.0;
    let m = build(&soup);
    assert_eq!((m.health.components, m.health.flipped_faces), (2, 0));
    assert!((m.health.volume.expect("closed") - want).abs() < 1e-6);
    // Turn the whole model inside out: both shells are put right again.
    let inverted: Vec<_> = soup.iter().map(|t| [t[0], t[2], t[1]]).collect();
    let m = build(&inverted);
    assert_eq!(m.health.flipped_faces, soup.len());
    assert!((m.health.volume.expect("closed") - want).abs() < 1e-6);
}

#[test]
fn corners_follow_flipped_faces() {
    // After orientation, each face's corner c must still run along its edge c.
    let mut soup = cuboid(DVec3::ZERO, DVec3::splat(4.0));
    soup[3].swap(1, 2);
    soup[7].swap(0, 1);
    let m = build(&soup);
    for (f, t) in m.triangles.iter().enumerate() {
        for c in 0..3 {
            let mut want = [t[c], t[(c + 1) % 3]];
            want.sort_unstable();
            assert_eq!(m.topology.edges[m.topology.face_edges[f][c] as usize], want);
        }
    }
    for e in 0..m.topology.edges.len() as u32 {
        for &fc in m.topology.edge_corners(e) {
            assert_eq!(m.topology.face_edges[(fc / 3) as usize][(fc % 3) as usize], e);
        }
    }
}
