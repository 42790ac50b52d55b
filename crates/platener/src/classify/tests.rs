//! Unit tests of the classifier's pieces and of whole runs on small models.

use glam::{DVec2, DVec3};
use proptest::prelude::*;

use super::fit::{refit, simplest};
use super::sample::sample_surface;
use super::surface::{Oriented, Surface, cone_from, cylinder_from, plane_from, sphere_from};
use super::*;
use platener_fixtures::samples;

/// The welded mesh of a triangle soup.
fn mesh_of(soup: &[crate::read::Triangle]) -> Mesh {
    let w = crate::weld::weld_soup(soup, 1e-6);
    Mesh::build(w.vertices, &w.triangles, 1e-9)
}

/// A point of `s` with its normal at surface parameters (a, b) in [0, 1)².
fn on(s: &Surface, a: f64, b: f64) -> Oriented {
    let turn = a * std::f64::consts::TAU;
    let p = match *s {
        Surface::Cylinder { axis, point, radius } => {
            let (u, v) = surface::basis(axis);
            point + (u * turn.cos() + v * turn.sin()) * radius + axis * (b * 100.0 - 50.0)
        }
        Surface::Sphere { center, radius } => {
            let lat = (b - 0.5) * 2.8;
            center + DVec3::new(lat.cos() * turn.cos(), lat.cos() * turn.sin(), lat.sin()) * radius
        }
        Surface::Cone { apex, axis, half_angle } => {
            let (u, v) = surface::basis(axis);
            let s = 10.0 + b * 80.0;
            apex + (axis * half_angle.cos() + (u * turn.cos() + v * turn.sin()) * half_angle.sin()) * s
        }
        Surface::Plane { normal, offset } => {
            let (u, v) = surface::basis(normal);
            normal * offset + u * (a * 100.0) + v * (b * 100.0)
        }
    };
    Oriented { p, n: s.normal_at(p) }
}

/// A unit direction from two angles.
fn dir(t: f64, p: f64) -> DVec3 {
    DVec3::new(p.sin() * t.cos(), p.sin() * t.sin(), p.cos())
}

proptest! {
    /// Minimal sets of exact points give back the shape they lie on.
    #[test]
    fn minimal_sets_recover_their_shape(t in 0.0..std::f64::consts::TAU, p in 0.1..3.0f64, r in 2.0..80.0f64,
                                        c in prop::array::uniform3(-50.0..50.0f64),
                                        a in prop::array::uniform3(0.0..1.0f64), b in prop::array::uniform3(0.0..1.0f64),
                                        h in 0.1..1.3f64) {
        let axis = dir(t, p);
        let c = DVec3::from(c);
        // Points of a minimal set a clear distance apart round the surface.
        let spread = |i: usize| (a[i] / 3.0 + i as f64 / 3.0, b[i]);
        let cyl = Surface::Cylinder { axis, point: c - axis * axis.dot(c), radius: r };
        let q: Vec<Oriented> = (0..3).map(|i| { let (x, y) = spread(i); on(&cyl, x, y) }).collect();
        let Some(Surface::Cylinder { axis: a2, point, radius }) = cylinder_from(&q[0], &q[1]) else { panic!("no cylinder") };
        prop_assert!(a2.cross(axis).length() < 1e-6);
        prop_assert!((radius - r).abs() < 1e-6 * r);
        prop_assert!((point - c).reject_from_normalized(axis).length() < 1e-6 * r);

        let sph = Surface::Sphere { center: c, radius: r };
        let q: Vec<Oriented> = (0..2).map(|i| { let (x, y) = spread(i); on(&sph, x, y) }).collect();
        let Some(Surface::Sphere { center, radius }) = sphere_from(&q[0], &q[1]) else { panic!("no sphere") };
        prop_assert!((center - c).length() < 1e-6 * r && (radius - r).abs() < 1e-6 * r);

        let cone = Surface::Cone { apex: c, axis, half_angle: h };
        let q: Vec<Oriented> = (0..3).map(|i| { let (x, y) = spread(i); on(&cone, x, y) }).collect();
        let Some(Surface::Cone { apex, axis: a3, half_angle }) = cone_from(&[q[0], q[1], q[2]]) else { panic!("no cone") };
        prop_assert!((apex - c).length() < 1e-5 * r.max(1.0), "apex {apex} vs {c}");
        prop_assert!(a3.dot(axis) > 1.0 - 1e-9 && (half_angle - h).abs() < 1e-6);

        let pl = Surface::Plane { normal: axis, offset: r };
        let q: Vec<Oriented> = (0..3).map(|i| on(&pl, a[i], b[i])).collect();
        if let Some(Surface::Plane { normal, offset }) = plane_from(&[q[0], q[1], q[2]]) {
            prop_assert!(normal.dot(axis) > 1.0 - 1e-9 && (offset - r).abs() < 1e-6);
        }
        // Every point of each shape is at distance 0 and accepted.
        for s in [cyl, sph, cone, pl] {
            let o = on(&s, a[0], b[0]);
            prop_assert!(s.distance(o.p) < 1e-9 && s.accepts(&o, 1e-6, 0.999_999));
        }
    }

    /// Gauss-Newton brings a perturbed start back to the shape exact points lie on.
    #[test]
    fn refit_converges(t in 0.0..std::f64::consts::TAU, p in 0.2..2.9f64, r in 10.0..60.0f64, d in prop::array::uniform3(-1.0..1.0f64)) {
        let axis = dir(t, p);
        let d = DVec3::from(d);
        for truth in [
            Surface::Cylinder { axis, point: DVec3::ZERO, radius: r },
            Surface::Sphere { center: DVec3::ONE, radius: r },
            Surface::Cone { apex: DVec3::ONE, axis, half_angle: 0.5 },
        ] {
            let pts: Vec<DVec3> = (0..400).map(|i| on(&truth, (i % 20) as f64 / 20.0 + 0.01, (i / 20) as f64 / 20.0).p).collect();
            let start = match truth {
                Surface::Cylinder { axis, point, radius } => Surface::Cylinder { axis: (axis + d * 0.02).normalize(), point: point + d, radius: radius + 1.0 },
                Surface::Sphere { center, radius } => Surface::Sphere { center: center + d, radius: radius - 1.0 },
                Surface::Cone { apex, axis, half_angle } => Surface::Cone { apex: apex + d, axis: (axis + d * 0.02).normalize(), half_angle: half_angle + 0.02 },
                Surface::Plane { .. } => truth,
            };
            let fitted = refit(&start, &pts, &[]).expect("a fit");
            let worst = pts.iter().map(|q| fitted.distance(*q)).fold(0.0, f64::max);
            prop_assert!(worst < 1e-4, "{fitted:?} leaves {worst} mm");
        }
    }
}

#[test]
fn a_plane_patch_is_not_a_huge_cylinder() {
    let pts: Vec<DVec3> = (0..100)
        .map(|i| DVec3::new((i % 10) as f64 * 10.0, (i / 10) as f64 * 10.0, 0.0))
        .collect();
    let normals = vec![DVec3::Z; pts.len()];
    let huge = Surface::Cylinder {
        axis: DVec3::X,
        point: DVec3::new(0.0, 50.0, -5000.0),
        radius: 5000.0,
    };
    let s = simplest(&huge, &pts, &normals, 1.0);
    let Surface::Plane { normal, offset } = s else {
        panic!("{s:?}")
    };
    assert!(normal.dot(DVec3::Z) > 1.0 - 1e-12 && offset.abs() < 1e-9);
    // A real cylinder stays one.
    let cyl = Surface::Cylinder {
        axis: DVec3::Z,
        point: DVec3::ZERO,
        radius: 20.0,
    };
    let pts: Vec<DVec3> = (0..100)
        .map(|i| on(&cyl, i as f64 / 100.0, (i % 7) as f64 / 7.0).p)
        .collect();
    assert_eq!(simplest(&cyl, &pts, &normals, 1.0), cyl);
}

#[test]
fn samples_follow_area_and_seed() {
    // Two triangles of areas 1 and 3 (mm²), far apart.
    let soup = [
        [DVec3::ZERO, DVec3::X, DVec3::Y * 2.0],
        [
            DVec3::Z * 10.0,
            DVec3::Z * 10.0 + DVec3::X * 2.0,
            DVec3::Z * 10.0 + DVec3::Y * 3.0,
        ],
    ];
    let m = Mesh::build(soup.iter().flatten().copied().collect(), &[[0, 1, 2], [3, 4, 5]], 1e-9);
    let s = sample_surface(&m, 4000, 7);
    let on_second = s.iter().filter(|x| x.1 == 1).count();
    // Stratified by area: exactly three quarters, give or take the one straddling slice.
    assert!((2999..=3001).contains(&on_second), "{on_second}");
    for (p, t) in &s {
        let [a, b, c] = m.corners(*t as usize);
        let n = (b - a).cross(c - a).normalize();
        assert!(n.dot(*p - a).abs() < 1e-9, "off its triangle");
        let inside = [(a, b), (b, c), (c, a)]
            .iter()
            .all(|(u, v)| (*v - *u).cross(*p - *u).dot(n) >= -1e-9);
        assert!(inside);
    }
    assert_eq!(s, sample_surface(&m, 4000, 7));
    assert_ne!(s, sample_surface(&m, 4000, 8));
}

#[test]
fn an_l_extrusion_is_a_prism() {
    let l = [
        (0.0, 0.0),
        (60.0, 0.0),
        (60.0, 15.0),
        (15.0, 15.0),
        (15.0, 50.0),
        (0.0, 50.0),
    ]
    .map(|(x, z)| DVec2::new(x, z));
    let m = mesh_of(&samples::prism(&l, 40.0));
    let c = run(&m, &ClassifySettings::default()).expect("classified");
    assert_eq!(c.primitives.len(), 8, "{:?}", c.primitives);
    let prisms: Vec<_> = c.volumes.iter().filter(|v| v.kind == VolumeKind::Prism).collect();
    assert_eq!(prisms.len(), 1, "{:?}", c.volumes);
    assert_eq!(prisms[0].primitives.len(), 8);
    let axis = prisms[0].axis.expect("an axis");
    assert!(axis.y.abs() > 1.0 - 1e-8, "the extrusion runs along y: {axis}");
}

#[test]
fn a_hollow_box_finds_its_outside_as_a_box() {
    let m = mesh_of(&samples::closed_box(100.0, 80.0, 60.0, 3.0));
    let c = run(&m, &ClassifySettings::default()).expect("classified");
    assert_eq!(
        c.primitives
            .iter()
            .filter(|p| p.shape.kind() == SurfaceKind::Plane)
            .count(),
        12
    );
    assert_eq!(c.primitives.len(), 12);
    let boxes: Vec<_> = c.volumes.iter().filter(|v| v.kind == VolumeKind::Box).collect();
    assert_eq!(boxes.len(), 1);
    // The outer box: its planes are the ones facing away from the centre at the outside.
    let centre = DVec3::new(50.0, 40.0, 30.0);
    for &k in &boxes[0].primitives {
        let Surface::Plane { normal, offset } = c.primitives[k as usize].shape else {
            panic!()
        };
        let out = offset - normal.dot(centre);
        assert!(
            (out - 50.0).abs() < 1e-6 || (out - 40.0).abs() < 1e-6 || (out - 30.0).abs() < 1e-6,
            "{out}"
        );
    }
    // The cavity's six walls are left as surfaces of the graph.
    assert_eq!(c.graph.nodes.iter().filter(|n| n.kind == NodeKind::Surface).count(), 6);
}

#[test]
fn bad_input_is_an_error() {
    let m = mesh_of(&samples::cuboid(DVec3::ZERO, DVec3::ONE));
    let bad = ClassifySettings {
        thickness: f64::NAN,
        ..ClassifySettings::default()
    };
    assert!(matches!(
        run(&m, &bad),
        Err(ClassifyError::Setting { name: "thickness", .. })
    ));
    let bad = ClassifySettings {
        samples: 5,
        ..ClassifySettings::default()
    };
    assert!(matches!(
        run(&m, &bad),
        Err(ClassifyError::Setting { name: "samples", .. })
    ));
    let empty = Mesh::build(Vec::new(), &[], 1e-9);
    assert_eq!(
        run(&empty, &ClassifySettings::default()).err(),
        Some(ClassifyError::NoSurface)
    );
}
