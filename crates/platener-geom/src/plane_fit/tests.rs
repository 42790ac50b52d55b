use glam::{DMat3, DVec3};

use super::*;

fn plane_through(n: DVec3, p: DVec3) -> (DVec3, f64) {
    let n = n.normalize();
    (n, n.dot(p))
}

#[test]
fn eigen_of_a_diagonal_and_a_rotated_matrix() {
    let (values, vectors) = symmetric_eigen(DMat3::from_diagonal(DVec3::new(3.0, 1.0, 2.0)));
    assert_eq!(values, [1.0, 2.0, 3.0]);
    assert_eq!(vectors[0], DVec3::Y);
    assert_eq!(vectors[2], DVec3::X);
    let r = DMat3::from_axis_angle(DVec3::new(1.0, 2.0, 3.0).normalize(), 0.7);
    let m = r * DMat3::from_diagonal(DVec3::new(5.0, 0.5, 2.0)) * r.transpose();
    let (values, vectors) = symmetric_eigen(m);
    for (got, want) in values.iter().zip([0.5, 2.0, 5.0]) {
        assert!((got - want).abs() < 1e-12, "{values:?}");
    }
    for (i, v) in vectors.iter().enumerate() {
        assert!((m * *v - *v * values[i]).length() < 1e-12);
    }
}

#[test]
fn corner_of_three_planes_is_exact() {
    let corner = DVec3::new(10.0, -4.0, 7.5);
    let mut q = Qef::default();
    for n in [DVec3::X, DVec3::new(0.0, 1.0, 0.2), DVec3::new(0.3, -0.1, 1.0)] {
        let (n, d) = plane_through(n, corner);
        q.add(n, d, 1.0);
    }
    // A welded vertex up to 2 mm away goes back to the corner.
    let got = q.solve(corner + DVec3::new(1.2, -0.8, 1.5));
    assert!((got - corner).length() < 1e-9, "{got}");
}

#[test]
fn two_planes_give_the_nearest_point_of_their_line() {
    // Planes x = 1 and y = 2 meet in the line (1, 2, t): z stays where it was.
    let mut q = Qef::default();
    q.add(DVec3::X, 1.0, 1.0);
    q.add(DVec3::Y, 2.0, 1.0);
    let got = q.solve(DVec3::new(1.7, 1.1, 5.25));
    assert!((got - DVec3::new(1.0, 2.0, 5.25)).length() < 1e-12, "{got}");
}

#[test]
fn near_parallel_planes_do_not_blow_up() {
    // Two planes 0.5° apart through nearly the same line: the exact intersection is far
    // away along x; the truncated solve stays next to the start and on both planes' average.
    let start = DVec3::new(3.0, 0.0, 0.01);
    let mut q = Qef::default();
    q.add(DVec3::Z, 0.0, 1.0);
    let tilted = DVec3::new(0.5f64.to_radians().sin(), 0.0, 0.5f64.to_radians().cos());
    q.add(tilted, 0.02, 1.0);
    let got = q.solve(start);
    assert!((got - start).length() < 0.05, "{got}");
    assert!((got.x - start.x).abs() < 1e-3, "{got}");
    // One plane: the projection.
    let mut one = Qef::default();
    one.add(DVec3::Z, 2.0, 1.0);
    assert!((one.solve(DVec3::new(1.0, 2.0, 3.0)) - DVec3::new(1.0, 2.0, 2.0)).length() < 1e-12);
    // No plane, or parallel copies of one plane: never NaN.
    assert_eq!(Qef::default().solve(DVec3::ONE), DVec3::ONE);
    let mut twice = Qef::default();
    twice.add(DVec3::Y, 1.0, 1.0);
    twice.add(DVec3::Y, 1.0, 3.0);
    assert!((twice.solve(DVec3::ZERO) - DVec3::Y).length() < 1e-12);
}

#[test]
fn coplanar_triangles_give_their_exact_plane() {
    let mut fit = PlaneFit::default();
    fit.add([
        DVec3::new(0.0, 0.0, 3.0),
        DVec3::new(10.0, 0.0, 3.0),
        DVec3::new(0.0, 5.0, 3.0),
    ]);
    fit.add([
        DVec3::new(10.0, 0.0, 3.0),
        DVec3::new(10.0, 5.0, 3.0),
        DVec3::new(0.0, 5.0, 3.0),
    ]);
    assert_eq!(fit.plane(), Some((DVec3::Z, 3.0)));
    assert_eq!(fit.area(), 50.0);
    // Wound the other way: the plane faces the other side.
    let mut down = PlaneFit::default();
    down.add([
        DVec3::new(0.0, 0.0, 3.0),
        DVec3::new(0.0, 5.0, 3.0),
        DVec3::new(10.0, 0.0, 3.0),
    ]);
    assert_eq!(down.plane(), Some((-DVec3::Z, -3.0)));
    // No area: no plane.
    let mut none = PlaneFit::default();
    none.add([DVec3::ZERO, DVec3::X, DVec3::X * 2.0]);
    assert_eq!(none.plane(), None);
}

#[test]
fn a_bent_pair_fits_the_least_squares_plane() {
    // Two unit squares hinged along x = 0, each tilted ±1° about the y axis: the fit is
    // the plane z = 0 between them, not either one.
    let a = 1f64.to_radians();
    let (s, c) = a.sin_cos();
    let mut fit = PlaneFit::default();
    for side in [-1.0, 1.0] {
        let p = |x: f64, y: f64| DVec3::new(side * x * c, y, x * s);
        let t = [p(0.0, 0.0), p(1.0, 0.0), p(1.0, 1.0)];
        let u = [p(0.0, 0.0), p(1.0, 1.0), p(0.0, 1.0)];
        if side > 0.0 {
            fit.add(t);
            fit.add(u);
        } else {
            fit.add([t[0], t[2], t[1]]);
            fit.add([u[0], u[2], u[1]]);
        }
    }
    let (n, _) = fit.plane().expect("a plane");
    assert!(n.angle_between(DVec3::Z) < 1e-9, "{n}");
}
