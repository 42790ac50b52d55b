use super::*;

#[test]
fn bevel_collapses_into_a_sharp_edge() {
    // Two 20 mm squares meeting at a right angle through a 0.5 mm 45° bevel strip.
    let p = |x: f64, y: f64, z: f64| DVec3::new(x, y, z);
    let top = [
        p(0.0, 0.0, 10.0),
        p(20.0, 0.0, 10.0),
        p(20.0, 19.5, 10.0),
        p(0.0, 19.5, 10.0),
    ];
    let bevel_lo = [p(0.0, 20.0, 9.5), p(20.0, 20.0, 9.5)];
    let side_lo = [p(0.0, 20.0, -10.0), p(20.0, 20.0, -10.0)];
    let soup = vec![
        [top[0], top[1], top[2]],
        [top[0], top[2], top[3]],
        [top[3], top[2], bevel_lo[1]],
        [top[3], bevel_lo[1], bevel_lo[0]],
        [bevel_lo[0], bevel_lo[1], side_lo[1]],
        [bevel_lo[0], side_lo[1], side_lo[0]],
    ];
    let w = weld_soup(&soup, 1.0);
    let v = &w.vertices;
    assert_eq!(w.vertices_before, 8);
    assert_eq!(v.len(), 6);
    assert_eq!(w.triangles_collapsed, 2, "both bevel triangles collapse");
    assert_eq!(w.triangles.len(), 4);
    // The merged corner lies at the mean of (y 19.5, z 10) and (y 20, z 9.5).
    let corner = v
        .iter()
        .find(|q| q.x == 0.0 && q.y > 19.0 && q.z > 9.0)
        .expect("merged corner");
    assert!((corner.y - 19.75).abs() < 1e-9 && (corner.z - 9.75).abs() < 1e-9);
}

#[test]
fn welding_never_closes_a_small_hole() {
    // A 60 × 60 × 3 plate with a 1.5 mm square hole: welding at 1.8 mm would close it.
    let xs = [0.0, 29.25, 30.75, 60.0];
    let plate = platener_fixtures::samples::voxels(&xs, &xs, &[0.0, 3.0], |i, j, _| !(i == 1 && j == 1));
    let exact = ExactSoup::new(&plate);
    assert_eq!(exact.counts.euler, 0, "a plate with one hole is a torus");
    assert_eq!(
        edge_counts(&exact.weld(1.8).triangles, 1000).euler,
        2,
        "unguarded, the hole closes"
    );
    let (w, refused) = exact.weld_keeping_topology(1.8);
    assert_eq!(refused, vec![1.8]);
    assert!((w.distance - 0.9).abs() < 1e-12);
    assert_eq!(edge_counts(&w.triangles, w.vertices.len()).euler, 0);
}

#[test]
fn euler_characteristic_of_simple_solids() {
    let cube = platener_fixtures::samples::cuboid(DVec3::ZERO, DVec3::ONE);
    assert_eq!(ExactSoup::new(&cube).counts.euler, 2);
    let hollow = platener_fixtures::samples::closed_box(10.0, 10.0, 10.0, 2.0);
    assert_eq!(ExactSoup::new(&hollow).counts.euler, 4, "two closed shells");
}

#[test]
fn thinnest_wall_is_measured_between_opposite_faces() {
    use platener_fixtures::samples::{closed_box, cuboid, open_box, rounded_box};
    let wall = |tris: &[[DVec3; 3]]| walls::thinnest_wall(tris).map(|w| (w * 1e6).round() / 1e6);
    // A board: its thickness.
    assert_eq!(wall(&cuboid(DVec3::ZERO, DVec3::new(120.0, 80.0, 1.6))), Some(1.6));
    // A tray with 2.5 mm walls and floor; a closed box with 4 mm walls (the cavity's faces
    // look inwards, so the walls, not the cavity, are measured).
    assert_eq!(wall(&open_box(100.0, 80.0, 50.0, 2.5)), Some(2.5));
    assert_eq!(wall(&closed_box(100.0, 80.0, 60.0, 4.0)), Some(4.0));
    // Rounded edges do not fool it: a 60 × 40 × 30 solid with 3 mm rounds is 30 mm thick.
    let rounded = rounded_box(DVec3::new(60.0, 40.0, 30.0), 3.0, 4);
    assert_eq!(wall(&rounded), Some(30.0));
    // Two boards side by side, not over each other: their faces do not overlap across the
    // 1 mm gap (a gap is not a wall), so each board's own 5 mm is the thinnest.
    let mut two = cuboid(DVec3::ZERO, DVec3::new(20.0, 20.0, 5.0));
    two.extend(cuboid(DVec3::new(21.0, 0.0, 0.0), DVec3::new(41.0, 20.0, 5.0)));
    assert_eq!(wall(&two), Some(5.0));
    // A single triangle has no wall.
    assert_eq!(wall(&[[DVec3::ZERO, DVec3::X, DVec3::Y]]), None);
}
