//! Planes fitted to triangles, and points fitted to planes.
//!
//! Welding moves vertices; the planes a model was drawn with do not move. [`PlaneFit`] finds
//! the plane of a set of triangles (exact when they are coplanar, an area-weighted
//! least-squares plane otherwise), and [`Qef`] finds the point nearest to a set of planes
//! (a corner of three planes, a point on the line of two), staying at a given point along
//! directions the planes do not fix. Both rest on one symmetric 3×3 eigen-solve
//! ([`symmetric_eigen`], cyclic Jacobi rotations: exact for diagonal matrices, no iteration
//! limit surprises at 3×3).

use glam::{DMat3, DVec3};

/// Eigenvalues below this share of the largest are treated as zero by [`Qef::solve`]: two
/// planes closer than about 11° in angle (tan²(θ/2) < 0.01) fix one direction, not two, so a
/// point is never pushed far along their almost-parallel line of intersection.
pub const QEF_CUTOFF: f64 = 0.01;

/// Eigenvalues (ascending) and unit eigenvectors (matching columns) of a symmetric matrix.
pub fn symmetric_eigen(m: DMat3) -> ([f64; 3], [DVec3; 3]) {
    let mut a = m.to_cols_array_2d();
    let mut v = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    for _sweep in 0..32 {
        let off = a[0][1].abs() + a[0][2].abs() + a[1][2].abs();
        let scale = a[0][0].abs() + a[1][1].abs() + a[2][2].abs();
        if off <= 1e-300 || off <= f64::EPSILON * 1e-3 * scale {
            break;
        }
        for (p, q) in [(0, 1), (0, 2), (1, 2)] {
            rotate(&mut a, &mut v, p, q);
        }
    }
    let mut order = [0usize, 1, 2];
    order.sort_by(|&i, &j| a[i][i].total_cmp(&a[j][j]).then(i.cmp(&j)));
    let values = order.map(|i| a[i][i]);
    let vectors = order.map(|i| DVec3::new(v[i][0], v[i][1], v[i][2]).normalize_or_zero());
    (values, vectors)
}

/// One Jacobi rotation zeroing `a[p][q]` (columns of `v` collect the eigenvectors; `v[k]` is
/// column k).
fn rotate(a: &mut [[f64; 3]; 3], v: &mut [[f64; 3]; 3], p: usize, q: usize) {
    let apq = a[p][q];
    if apq == 0.0 {
        return;
    }
    let theta = (a[q][q] - a[p][p]) / (2.0 * apq);
    // The smaller of the two rotations that zero a[p][q] (signum(0) is 1: a 45° turn).
    let t = theta.signum() / (theta.abs() + (theta * theta + 1.0).sqrt());
    let c = 1.0 / (t * t + 1.0).sqrt();
    let s = t * c;
    for row in a.iter_mut() {
        let (akp, akq) = (row[p], row[q]);
        row[p] = c * akp - s * akq;
        row[q] = s * akp + c * akq;
    }
    let (rp, rq) = (a[p], a[q]);
    a[p] = std::array::from_fn(|k| c * rp[k] - s * rq[k]);
    a[q] = std::array::from_fn(|k| s * rp[k] + c * rq[k]);
    let (vp, vq) = (v[p], v[q]);
    v[p] = std::array::from_fn(|k| c * vp[k] - s * vq[k]);
    v[q] = std::array::from_fn(|k| s * vp[k] + c * vq[k]);
}

/// The plane of a set of triangles, accumulated one triangle at a time.
#[derive(Debug, Clone, Copy)]
pub struct PlaneFit {
    area: f64,
    /// Σ area × unit normal (orientation of the fit).
    normal_sum: DVec3,
    /// Σ area × centroid.
    first: DVec3,
    /// Σ of the exact second moment ∫ x xᵀ dA over each triangle.
    second: DMat3,
}

impl PlaneFit {
    /// Adds triangle `t` (its winding gives its side).
    pub fn add(&mut self, t: [DVec3; 3]) {
        let cross = (t[1] - t[0]).cross(t[2] - t[0]);
        let area = 0.5 * cross.length();
        if area.is_nan() || area <= 0.0 {
            return;
        }
        let sum = t[0] + t[1] + t[2];
        // ∫ x xᵀ dA over a triangle = A/12 (Σ vᵢvᵢᵀ + s sᵀ), s = Σ vᵢ.
        let outer = |a: DVec3| DMat3::from_cols(a * a.x, a * a.y, a * a.z);
        let second = (outer(t[0]) + outer(t[1]) + outer(t[2]) + outer(sum)) * (area / 12.0);
        self.area += area;
        self.normal_sum += cross * 0.5;
        self.first += sum * (area / 3.0);
        self.second += second;
    }

    /// Total area added.
    pub fn area(&self) -> f64 {
        self.area
    }

    /// The plane as (unit normal, offset `n · x`), the normal on the side the triangles face;
    /// `None` without area. The least-squares normal is the direction of least spread of the
    /// triangles' points about their centroid; when that direction is ambiguous (all points
    /// near one line) the area-weighted mean normal is used instead.
    pub fn plane(&self) -> Option<(DVec3, f64)> {
        if self.area.is_nan() || self.area <= 0.0 {
            return None;
        }
        let mean_normal = self.normal_sum.try_normalize()?;
        let c = self.first / self.area;
        let outer_c = DMat3::from_cols(c * c.x, c * c.y, c * c.z);
        let cov = self.second * (1.0 / self.area) - outer_c;
        let (values, vectors) = symmetric_eigen(cov);
        // The smallest spread must be clearly below the middle one, else the fit has no
        // preferred normal (a sliver); exactly coplanar triangles give values[0] ≈ 0.
        let fitted = (values[1] > 0.0 && values[0] <= 0.25 * values[1]).then(|| {
            let n = vectors[0];
            if n.dot(mean_normal) < 0.0 { -n } else { n }
        });
        // Coplanar triangles: their common normal, free of the eigen-solve's rounding (an
        // axis-aligned face keeps an exactly axis-aligned normal).
        let n = match fitted {
            Some(n) if n.dot(mean_normal) < 1.0 - 1e-12 => n,
            _ => mean_normal,
        };
        Some((n, n.dot(c)))
    }
}

// Not derived: `DMat3::default()` is the identity, not zero.
impl Default for PlaneFit {
    fn default() -> Self {
        Self {
            area: 0.0,
            normal_sum: DVec3::ZERO,
            first: DVec3::ZERO,
            second: DMat3::ZERO,
        }
    }
}

/// A quadratic error function: the sum of squared distances to a set of planes.
#[derive(Debug, Clone, Copy)]
pub struct Qef {
    ata: DMat3,
    atb: DVec3,
    planes: usize,
}

impl Default for Qef {
    fn default() -> Self {
        Self {
            ata: DMat3::ZERO,
            atb: DVec3::ZERO,
            planes: 0,
        }
    }
}

impl Qef {
    /// Adds the plane `n · x = d` (`n` a unit vector) with weight `w`.
    pub fn add(&mut self, n: DVec3, d: f64, w: f64) {
        self.ata += DMat3::from_cols(n * n.x, n * n.y, n * n.z) * w;
        self.atb += n * (d * w);
        self.planes += 1;
    }

    /// Planes added.
    pub fn len(&self) -> usize {
        self.planes
    }

    /// Whether no plane was added.
    pub fn is_empty(&self) -> bool {
        self.planes == 0
    }

    /// The point nearest to every plane, starting from `near`: along each direction the
    /// planes fix (eigenvalue above [`QEF_CUTOFF`] × the largest) the least-squares
    /// solution, along the others `near` unchanged. Three planes meeting at a corner give the
    /// corner, two give the point of their line nearest `near`, one the projection of `near`.
    pub fn solve(&self, near: DVec3) -> DVec3 {
        let (values, vectors) = symmetric_eigen(self.ata);
        let largest = values[2];
        if largest.is_nan() || largest <= 0.0 {
            return near;
        }
        let residual = self.atb - self.ata * near;
        let mut x = near;
        for (value, v) in values.iter().zip(vectors) {
            if *value > QEF_CUTOFF * largest {
                x += v * (v.dot(residual) / value);
            }
        }
        x
    }
}

#[cfg(test)]
mod tests;
