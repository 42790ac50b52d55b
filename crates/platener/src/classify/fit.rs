//! Least-squares refits of a primitive to its inliers: planes by the eigen-decomposition of
//! the points' covariance (no `z = Ax + By + C` restriction, so walls of any direction fit
//! alike), curved primitives by a few damped Gauss-Newton steps on the signed distances.
//! The minimal set a candidate came from is exact for three points and noisy for all the
//! others; the refit is what makes the parameters accurate.

use glam::{DMat3, DVec3};
use platener_geom::plane_fit::symmetric_eigen;

use super::surface::{Surface, basis};

/// Gauss-Newton steps: the start (a good candidate) is close, so a few steps converge.
const STEPS: usize = 8;

/// The shape of the same kind fitted to `points` (normals orient planes), or `None` when the
/// points do not determine one (too few, or degenerate).
pub fn refit(shape: &Surface, points: &[DVec3], normals: &[DVec3]) -> Option<Surface> {
    match shape {
        Surface::Plane { .. } => plane(points, normals),
        _ if points.len() < 8 => None,
        _ => gauss_newton(*shape, points),
    }
}

/// The simplest shape that explains `points` as well as `shape` does: a plane, else (for a
/// cone) a cylinder, when its RMS distance to the points is at most `eps / 2`, well inside
/// the tolerance band. A plane patch is also a piece of a huge cylinder or sphere, a
/// cylinder one of a very slender cone; without this rule the candidate that happened to
/// catch a few more noisy points would win.
pub fn simplest(shape: &Surface, points: &[DVec3], normals: &[DVec3], eps: f64) -> Surface {
    let rms = |s: &Surface| (cost(s, points) / points.len().max(1) as f64).sqrt();
    let mut simpler: Vec<Surface> = Vec::new();
    if !matches!(shape, Surface::Plane { .. }) {
        simpler.extend(plane(points, normals));
    }
    if let Surface::Cone { apex, axis, .. } = *shape
        && points.len() >= 8
    {
        let radius = points
            .iter()
            .map(|p| (*p - apex).reject_from_normalized(axis).length())
            .sum::<f64>()
            / points.len() as f64;
        let start = Surface::Cylinder {
            axis,
            point: apex - axis * axis.dot(apex),
            radius,
        };
        simpler.extend(gauss_newton(start, points));
    }
    simpler.into_iter().find(|s| rms(s) <= eps / 2.0).unwrap_or(*shape)
}

/// The least-squares plane: through the centroid, normal along the covariance's smallest
/// eigenvector, facing like the sum of the normals.
fn plane(points: &[DVec3], normals: &[DVec3]) -> Option<Surface> {
    if points.len() < 3 {
        return None;
    }
    let c = points.iter().copied().sum::<DVec3>() / points.len() as f64;
    let mut m = DMat3::ZERO;
    for p in points {
        let d = *p - c;
        m += DMat3::from_cols(d * d.x, d * d.y, d * d.z);
    }
    let (_, vecs) = symmetric_eigen(m);
    let n = vecs[0].try_normalize()?;
    let n = if n.dot(normals.iter().copied().sum::<DVec3>()) < 0.0 {
        -n
    } else {
        n
    };
    Some(Surface::Plane {
        normal: n,
        offset: n.dot(c),
    })
}

/// The shape `base` moved by the parameter step `x` (mm and radians, in a frame local to
/// `base`, so no parameter is redundant: the axis turns in two directions, the axis point
/// moves across the axis).
fn moved(base: &Surface, x: &[f64]) -> Surface {
    match *base {
        Surface::Sphere { center, radius } => Surface::Sphere {
            center: center + DVec3::new(x[0], x[1], x[2]),
            radius: radius + x[3],
        },
        Surface::Cylinder { axis, point, radius } => {
            let (u, v) = basis(axis);
            let a = (axis + u * x[0] + v * x[1]).normalize();
            let p = point + u * x[2] + v * x[3];
            Surface::Cylinder {
                axis: a,
                point: p - a * a.dot(p),
                radius: radius + x[4],
            }
        }
        Surface::Cone { apex, axis, half_angle } => {
            let (u, v) = basis(axis);
            let a = (axis + u * x[0] + v * x[1]).normalize();
            Surface::Cone {
                apex: apex + DVec3::new(x[2], x[3], x[4]),
                axis: a,
                half_angle: half_angle + x[5],
            }
        }
        Surface::Plane { .. } => *base,
    }
}

/// Number of free parameters of a curved shape.
fn dof(shape: &Surface) -> usize {
    match shape {
        Surface::Sphere { .. } => 4,
        Surface::Cylinder { .. } => 5,
        Surface::Cone { .. } => 6,
        Surface::Plane { .. } => 0,
    }
}

/// Sum of squared signed distances.
fn cost(shape: &Surface, points: &[DVec3]) -> f64 {
    points.iter().map(|p| shape.signed_distance(*p).powi(2)).sum()
}

/// Damped Gauss-Newton with a numeric Jacobian (central differences): steps that do not
/// lower the cost raise the damping; the result is never worse than the start.
fn gauss_newton(start: Surface, points: &[DVec3]) -> Option<Surface> {
    let k = dof(&start);
    let mut cur = start;
    let mut best = cost(&cur, points);
    let mut lambda = 1e-6;
    for _ in 0..STEPS {
        let (jtj, jtr) = normal_equations(&cur, points, k);
        let mut a = jtj;
        for i in 0..k {
            a[i][i] += lambda * (1.0 + jtj[i][i]);
        }
        let Some(dx) = solve(a, jtr, k) else { break };
        let step: Vec<f64> = dx.iter().map(|d| -d).collect();
        let next = moved(&cur, &step);
        let c = cost(&next, points);
        if c.is_finite() && c < best {
            cur = next;
            best = c;
            lambda *= 0.3;
        } else {
            lambda *= 10.0;
        }
    }
    valid(&cur).then_some(cur)
}

/// Whether the fitted parameters still describe a proper shape.
fn valid(shape: &Surface) -> bool {
    match *shape {
        Surface::Sphere { radius, .. } | Surface::Cylinder { radius, .. } => radius.is_finite() && radius > 0.0,
        Surface::Cone { half_angle, .. } => half_angle > 0.0 && half_angle < std::f64::consts::FRAC_PI_2,
        Surface::Plane { .. } => true,
    }
}

/// JᵀJ and Jᵀr of the signed distances at `shape`.
fn normal_equations(shape: &Surface, points: &[DVec3], k: usize) -> ([[f64; 6]; 6], [f64; 6]) {
    const H: f64 = 1e-6;
    let mut plus = [Surface::Plane {
        normal: DVec3::Z,
        offset: 0.0,
    }; 6];
    let mut minus = plus;
    for i in 0..k {
        let mut x = [0.0; 6];
        x[i] = H;
        plus[i] = moved(shape, &x);
        x[i] = -H;
        minus[i] = moved(shape, &x);
    }
    let mut jtj = [[0.0; 6]; 6];
    let mut jtr = [0.0; 6];
    for p in points {
        let r = shape.signed_distance(*p);
        let mut j = [0.0; 6];
        for i in 0..k {
            j[i] = (plus[i].signed_distance(*p) - minus[i].signed_distance(*p)) / (2.0 * H);
        }
        for a in 0..k {
            jtr[a] += j[a] * r;
            for b in 0..k {
                jtj[a][b] += j[a] * j[b];
            }
        }
    }
    (jtj, jtr)
}

/// Solves the k×k system `a·x = b` by Gaussian elimination with partial pivoting.
fn solve(mut a: [[f64; 6]; 6], mut b: [f64; 6], k: usize) -> Option<[f64; 6]> {
    for c in 0..k {
        let piv = (c..k).max_by(|&i, &j| a[i][c].abs().total_cmp(&a[j][c].abs()))?;
        if a[piv][c].abs() < 1e-300 {
            return None;
        }
        a.swap(c, piv);
        b.swap(c, piv);
        let pivot_row = a[c];
        for r in c + 1..k {
            let f = a[r][c] / pivot_row[c];
            for (x, p) in a[r][c..k].iter_mut().zip(&pivot_row[c..k]) {
                *x -= f * p;
            }
            b[r] -= f * b[c];
        }
    }
    let mut x = [0.0; 6];
    for c in (0..k).rev() {
        let s: f64 = (c + 1..k).map(|cc| a[c][cc] * x[cc]).sum();
        x[c] = (b[c] - s) / a[c][c];
    }
    x.iter().all(|v| v.is_finite()).then_some(x)
}
