use std::sync::Arc;

use glam::{DVec2, DVec3};
use platener_geom::polygon::rect;
use platener_geom::{Frame, Polygon};

use super::decimate::{TRIANGLE_LIMIT, under_limit};
use super::extrude::extrude;
use super::*;
use crate::plan::Part;
use crate::read::{self, Bounds};

/// Each directed edge (by index) once, its reverse once: closed and consistently wound.
fn assert_watertight(triangles: &[[u32; 3]]) {
    let mut edges: Vec<[u32; 2]> = triangles
        .iter()
        .flat_map(|&[a, b, c]| [[a, b], [b, c], [c, a]])
        .collect();
    edges.sort_unstable();
    let n = edges.len();
    edges.dedup();
    assert_eq!(edges.len(), n, "an edge used twice in one direction");
    for [a, b] in &edges {
        assert!(edges.binary_search(&[*b, *a]).is_ok(), "edge {a} → {b} has no partner");
    }
}

fn volume(positions: &[DVec3], triangles: &[[u32; 3]]) -> f64 {
    triangles
        .iter()
        .map(|t| {
            let [a, b, c] = t.map(|i| positions[i as usize]);
            a.dot(b.cross(c)) / 6.0
        })
        .sum()
}

fn plate_with_two_holes() -> Polygon {
    Polygon {
        outer: rect(0.0, 0.0, 80.0, 50.0),
        holes: vec![
            rect(10.0, 10.0, 20.0, 40.0),
            vec![DVec2::new(40.0, 10.0), DVec2::new(70.0, 25.0), DVec2::new(40.0, 40.0)],
        ],
    }
}

#[test]
fn an_extruded_plate_with_holes_is_closed_outward_and_of_its_volume() {
    let p = plate_with_two_holes();
    let (positions, triangles) = extrude(&p, 3.0).expect("extrudes");
    assert_watertight(&triangles);
    let want = p.area() * 3.0;
    let got = volume(&positions, &triangles);
    assert!((got - want).abs() < 1e-9 * want, "{got} vs {want}");
    // Both caps and the walls of three rings: 4 + 4 + 3 boundary edges, two triangles each.
    let cap = platener_geom::triangulate::triangulate(&p)
        .expect("on the grid")
        .triangles
        .len();
    assert_eq!(triangles.len(), 2 * cap + 2 * 11);
}

#[test]
fn an_inside_out_outline_still_makes_an_outward_solid() {
    let mut p = plate_with_two_holes();
    p.outer.reverse();
    p.holes[0].reverse();
    let (positions, triangles) = extrude(&p, 6.0).expect("extrudes");
    assert_watertight(&triangles);
    assert!((volume(&positions, &triangles) - p.area() * 6.0).abs() < 1e-6);
}

#[test]
fn the_assembly_is_deterministic_and_ordered_by_part_id() {
    let frame = Frame::on_plane(DVec3::new(1.0, 2.0, 3.0), DVec3::new(0.2, 0.3, 0.9));
    let parts = vec![
        Part::plate(2, 3.0, plate_with_two_holes(), frame),
        Part::plate(
            1,
            4.0,
            Polygon::new(rect(0.0, 0.0, 10.0, 10.0)),
            Frame::on_plane(DVec3::ZERO, DVec3::X),
        ),
    ];
    let a = assembly(&parts).expect("scene");
    let mut reversed = parts.clone();
    reversed.reverse();
    assert_eq!(a, assembly(&reversed).expect("scene"));
    assert_eq!(a.nodes, 3);
    let json = String::from_utf8_lossy(&a.glb[20..]).into_owned();
    assert!(json.find("\"part-1\"") < json.find("\"part-2\""));
    assert!(a.glb.len().is_multiple_of(4) && a.glb.starts_with(b"glTF"));
}

/// A flat square grid of `n` × `n` cells, two triangles each, as a read model.
fn grid_model(n: usize) -> read::Model {
    let p = |i: usize, j: usize| DVec3::new(i as f64 * 0.1, j as f64 * 0.1, ((i * j) % 7) as f64 * 0.01);
    let mut triangles = Vec::with_capacity(2 * n * n);
    for i in 0..n {
        for j in 0..n {
            triangles.push([p(i, j), p(i + 1, j), p(i + 1, j + 1)]);
            triangles.push([p(i, j), p(i + 1, j + 1), p(i, j + 1)]);
        }
    }
    read::Model {
        name: "grid".into(),
        format: None,
        bounds: Bounds::of(&triangles).expect("triangles"),
        print: crate::fabrication::print::estimate(&triangles),
        triangles: Arc::new(triangles),
        solids: 1,
        normals_against_winding: 0,
        unit_factor: 1.0,
        units: crate::Units::Mm,
        scale: 1.0,
    }
}

#[test]
fn a_model_over_the_limit_is_decimated_under_it_with_a_note() {
    let m = grid_model(520);
    assert!(m.triangles.len() > TRIANGLE_LIMIT);
    let s = model(&m).expect("scene");
    assert!(
        s.triangles <= TRIANGLE_LIMIT && s.triangles > TRIANGLE_LIMIT / 10,
        "{}",
        s.triangles
    );
    assert_eq!(
        s.notes,
        [format!(
            "decimated from {} to {} triangles for viewing",
            m.triangles.len(),
            s.triangles
        )]
    );
    assert_eq!(s.glb, model(&m).expect("scene").glb, "deterministic");
    let small = model(&grid_model(20)).expect("scene");
    assert_eq!((small.triangles, small.notes.len()), (800, 0));
}

#[test]
fn decimation_shrinks_the_grid_until_under_a_small_limit() {
    let m = grid_model(40);
    let indexed = (
        m.triangles.iter().flatten().copied().collect::<Vec<_>>(),
        (0..m.triangles.len() as u32)
            .map(|t| [3 * t, 3 * t + 1, 3 * t + 2])
            .collect::<Vec<_>>(),
    );
    let ((positions, triangles), note) = under_limit(indexed, 100);
    assert!(triangles.len() <= 100 && !triangles.is_empty());
    assert!(triangles.iter().flatten().all(|&i| (i as usize) < positions.len()));
    assert!(note.is_some());
}

#[test]
fn view_names_parse_back() {
    for v in View::ALL {
        assert_eq!(v.name().parse::<View>(), Ok(v));
        assert_eq!(v.to_string(), v.name());
    }
    assert!(matches!("x".parse::<View>(), Err(SceneError::UnknownView(_))));
}

/// A textured box of 261 000 triangles: each primitive's node is decimated to its share of the
/// limit, the note says so, and every k-th inlier keeps the points under their limit.
#[test]
fn a_classification_over_the_limits_is_drawn_decimated_and_thinned() {
    let soup = platener_fixtures::samples::textured_box(DVec3::new(120.0, 90.0, 70.0), 3.0, 0.3, 2.5);
    let welded = crate::weld::weld_soup(&soup, 1e-6);
    let mesh = crate::mesh::Mesh::build(welded.vertices, &welded.triangles, 1e-9);
    assert!(mesh.triangles.len() > TRIANGLE_LIMIT);
    let c = crate::classify::run(&mesh, &crate::classify::ClassifySettings::default()).expect("classifies");
    let inliers: usize = c.primitives.iter().map(|p| p.samples.len()).sum();
    assert!(inliers > POINT_LIMIT, "{inliers} inliers");
    let s = primitives(&mesh, &c).expect("scene");
    assert!(
        s.triangles <= TRIANGLE_LIMIT && s.triangles > TRIANGLE_LIMIT / 10,
        "{}",
        s.triangles
    );
    let stride = inliers.div_ceil(POINT_LIMIT);
    assert_eq!(
        s.notes,
        [
            format!(
                "decimated from {} to {} triangles for viewing",
                mesh.triangles.len(),
                s.triangles
            ),
            format!("1 in {stride} of the {inliers} inlier samples drawn as points")
        ]
    );
    assert_eq!(s.points, inliers.div_ceil(stride), "every {stride}-th of {inliers}");
    assert!(s.points <= POINT_LIMIT);
}
