//! The four surface primitives RANSAC looks for: their distance and normal at a point, the
//! parameter-space coordinates the connectivity bitmap needs, and construction from the
//! minimal sets of Schnabel, Wahl and Klein (2007), which use the samples' normals so that
//! two or three points suffice (fewer points per draw, far fewer draws).

use glam::{DMat3, DVec2, DVec3};
use serde::Serialize;

/// A primitive surface in model coordinates (mm).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum Surface {
    /// Points `p` with `normal · p = offset`; `normal` points out of the solid.
    Plane {
        /// Unit normal.
        normal: DVec3,
        /// Distance of the plane from the origin along `normal`.
        offset: f64,
    },
    /// Points at `radius` from the line through `point` along `axis`.
    Cylinder {
        /// Unit axis direction.
        axis: DVec3,
        /// A point on the axis (the one nearest the origin).
        point: DVec3,
        /// Radius, mm.
        radius: f64,
    },
    /// Points at `radius` from `center`.
    Sphere {
        /// Centre.
        center: DVec3,
        /// Radius, mm.
        radius: f64,
    },
    /// The half-cone from `apex` opening along `axis` with `half_angle` (radians).
    Cone {
        /// Apex.
        apex: DVec3,
        /// Unit axis, pointing into the opening.
        axis: DVec3,
        /// Angle between axis and surface lines, radians, in (0, π/2).
        half_angle: f64,
    },
}

/// Which primitive a [`Surface`] is (for counts and comparisons).
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum SurfaceKind {
    /// [`Surface::Plane`].
    Plane,
    /// [`Surface::Cylinder`].
    Cylinder,
    /// [`Surface::Sphere`].
    Sphere,
    /// [`Surface::Cone`].
    Cone,
}

impl SurfaceKind {
    /// The kind's name as its JSON has it (`plane`, `cylinder`, …), for names a viewer shows.
    pub fn name(self) -> &'static str {
        match self {
            SurfaceKind::Plane => "plane",
            SurfaceKind::Cylinder => "cylinder",
            SurfaceKind::Sphere => "sphere",
            SurfaceKind::Cone => "cone",
        }
    }
}

/// A point with its unit normal: what every minimal set is made of.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Oriented {
    /// Position, mm.
    pub p: DVec3,
    /// Unit normal.
    pub n: DVec3,
}

/// Two orthonormal vectors perpendicular to unit `a` (a stable choice: the same `a` always
/// gives the same pair, so parameter grids are reproducible).
pub fn basis(a: DVec3) -> (DVec3, DVec3) {
    let u = a.any_orthonormal_vector();
    (u, a.cross(u))
}

impl Surface {
    /// Whether `other` is the same surface within `eps` (positions, radii) and the angle
    /// whose cosine is `cos_alpha` (directions): what RANSAC treats as one candidate.
    pub fn same_as(&self, other: &Surface, eps: f64, cos_alpha: f64) -> bool {
        let line_gap = |p: DVec3, a: DVec3, q: DVec3| {
            let d = q - p;
            (d - a * d.dot(a)).length()
        };
        match (*self, *other) {
            (Surface::Plane { normal: n, offset: o }, Surface::Plane { normal: m, offset: p }) => {
                let dot = n.dot(m);
                dot.abs() >= cos_alpha && (o - p * dot.signum()).abs() <= eps
            }
            (
                Surface::Cylinder {
                    axis: a,
                    point: p,
                    radius: r,
                },
                Surface::Cylinder {
                    axis: b,
                    point: q,
                    radius: s,
                },
            ) => a.dot(b).abs() >= cos_alpha && (r - s).abs() <= eps && line_gap(p, a, q) <= eps,
            (Surface::Sphere { center: c, radius: r }, Surface::Sphere { center: d, radius: s }) => {
                (c - d).length() <= eps && (r - s).abs() <= eps
            }
            (
                Surface::Cone {
                    apex: p,
                    axis: a,
                    half_angle: h,
                },
                Surface::Cone {
                    apex: q,
                    axis: b,
                    half_angle: k,
                },
            ) => (p - q).length() <= eps && a.dot(b) >= cos_alpha && (h - k).abs() <= cos_alpha.acos(),
            _ => false,
        }
    }

    /// Which primitive this is.
    pub fn kind(&self) -> SurfaceKind {
        match self {
            Surface::Plane { .. } => SurfaceKind::Plane,
            Surface::Cylinder { .. } => SurfaceKind::Cylinder,
            Surface::Sphere { .. } => SurfaceKind::Sphere,
            Surface::Cone { .. } => SurfaceKind::Cone,
        }
    }

    /// Signed distance of `p` from the surface (positive on the side the plane normal, or
    /// the radial direction, points to); least squares minimises its square.
    pub fn signed_distance(&self, p: DVec3) -> f64 {
        self.prepared().signed_distance(p)
    }

    /// Unsigned distance of `p` from the surface.
    pub fn distance(&self, p: DVec3) -> f64 {
        self.signed_distance(p).abs()
    }

    /// Unit normal of the surface nearest `p`: the plane's normal, or pointing away from the
    /// axis / centre (the side a solid cylinder's outside is on).
    pub fn normal_at(&self, p: DVec3) -> DVec3 {
        self.prepared().normal_at(p)
    }

    /// Whether `q` (with its normal) lies on the surface: within `eps` and with a normal
    /// within the angle whose cosine is `cos_alpha`. A plane's side counts (the two faces of
    /// a thin wall are different planes); curved surfaces accept either direction (a bore's
    /// normals point to its axis).
    pub fn accepts(&self, q: &Oriented, eps: f64, cos_alpha: f64) -> bool {
        self.prepared().accepts(q, eps, cos_alpha)
    }

    /// The shape with its cone's sine and cosine computed once: RANSAC tests each candidate
    /// on thousands of samples, and the two were a sixth of its time on a model of cones.
    pub fn prepared(&self) -> Prepared {
        let sin_cos = match *self {
            Surface::Cone { half_angle, .. } => half_angle.sin_cos(),
            _ => (0.0, 1.0),
        };
        Prepared { shape: *self, sin_cos }
    }

    /// Coordinates of `p` in the primitive's parameter space, in mm along the surface, and
    /// the period of the first coordinate when it wraps round (cylinders, cones, spheres).
    /// Spheres use the equal-area cylindrical map (longitude·r, sin(latitude)·r); cones are
    /// unrolled at `ref_radius` (their mean radius), cylinders at their radius.
    pub fn parameters(&self, p: DVec3, ref_radius: f64) -> (DVec2, Option<f64>) {
        match *self {
            Surface::Plane { normal, .. } => {
                let (u, v) = basis(normal);
                (DVec2::new(u.dot(p), v.dot(p)), None)
            }
            Surface::Cylinder { axis, point, radius } => {
                let (a, h) = angle_height(p - point, axis);
                (DVec2::new(a * radius, h), Some(std::f64::consts::TAU * radius))
            }
            Surface::Sphere { center, radius } => {
                let (a, _) = angle_height(p - center, DVec3::Z);
                let z = ((p - center).normalize_or(DVec3::Z).z).clamp(-1.0, 1.0);
                (DVec2::new(a * radius, z * radius), Some(std::f64::consts::TAU * radius))
            }
            Surface::Cone { apex, axis, .. } => {
                let (a, _) = angle_height(p - apex, axis);
                let s = (p - apex).length();
                (DVec2::new(a * ref_radius, s), Some(std::f64::consts::TAU * ref_radius))
            }
        }
    }

    /// The radius the parameter map of a cone uses for `points`: their mean distance from the
    /// axis (other shapes ignore it).
    pub fn reference_radius(&self, points: impl Iterator<Item = DVec3>) -> f64 {
        let Surface::Cone { apex, axis, .. } = *self else {
            return 0.0;
        };
        let (sum, n) = points.fold((0.0, 0usize), |(s, n), p| {
            (s + (p - apex).reject_from_normalized(axis).length(), n + 1)
        });
        if n == 0 { 0.0 } else { sum / n as f64 }
    }
}

/// A [`Surface`] ready to test many points ([`Surface::prepared`]).
#[derive(Debug, Clone, Copy)]
pub struct Prepared {
    shape: Surface,
    /// A cone's half angle's sine and cosine.
    sin_cos: (f64, f64),
}

impl Prepared {
    /// See [`Surface::signed_distance`].
    pub fn signed_distance(&self, p: DVec3) -> f64 {
        match self.shape {
            Surface::Plane { normal, offset } => normal.dot(p) - offset,
            Surface::Cylinder { axis, point, radius } => (p - point).reject_from_normalized(axis).length() - radius,
            Surface::Sphere { center, radius } => (p - center).length() - radius,
            Surface::Cone { apex, axis, .. } => {
                let v = p - apex;
                let h = v.dot(axis);
                let rho = v.reject_from_normalized(axis).length();
                let (s, c) = self.sin_cos;
                if h * c + rho * s >= 0.0 {
                    rho * c - h * s
                } else {
                    v.length()
                }
            }
        }
    }

    /// See [`Surface::normal_at`].
    pub fn normal_at(&self, p: DVec3) -> DVec3 {
        match self.shape {
            Surface::Plane { normal, .. } => normal,
            Surface::Cylinder { axis, point, .. } => radial(p - point, axis),
            Surface::Sphere { center, .. } => (p - center).normalize_or(DVec3::Z),
            Surface::Cone { apex, axis, .. } => {
                let (s, c) = self.sin_cos;
                radial(p - apex, axis) * c - axis * s
            }
        }
    }

    /// See [`Surface::accepts`].
    pub fn accepts(&self, q: &Oriented, eps: f64, cos_alpha: f64) -> bool {
        if self.signed_distance(q.p).abs() > eps {
            return false;
        }
        let d = self.normal_at(q.p).dot(q.n);
        match self.shape {
            Surface::Plane { .. } => d >= cos_alpha,
            _ => d.abs() >= cos_alpha,
        }
    }
}

/// The unit direction of `v` away from the axis `axis` (any perpendicular on the axis).
fn radial(v: DVec3, axis: DVec3) -> DVec3 {
    let r = v.reject_from_normalized(axis);
    r.try_normalize().unwrap_or_else(|| axis.any_orthonormal_vector())
}

/// Angle round `axis` (in (−π, π]) and height along it of `v`.
fn angle_height(v: DVec3, axis: DVec3) -> (f64, f64) {
    let (u, w) = basis(axis);
    (v.dot(w).atan2(v.dot(u)), v.dot(axis))
}

/// The plane through three points, facing like the first point's normal.
pub fn plane_from(q: &[Oriented; 3]) -> Option<Surface> {
    let n = (q[1].p - q[0].p).cross(q[2].p - q[0].p).try_normalize()?;
    let n = if n.dot(q[0].n) < 0.0 { -n } else { n };
    Some(Surface::Plane {
        normal: n,
        offset: n.dot(q[0].p),
    })
}

/// The cylinder through two points with normals: the axis is perpendicular to both normals,
/// the centre where the normal lines cross in the plane across the axis.
pub fn cylinder_from(a: &Oriented, b: &Oriented) -> Option<Surface> {
    let axis = a.n.cross(b.n);
    if axis.length() < 1e-3 {
        return None;
    }
    let axis = axis.normalize();
    let (t, _) = closest_on_lines(a.p, a.n, b.p, b.n)?;
    let c = a.p + a.n * t;
    let point = c - axis * axis.dot(c);
    let ra = (a.p - point).reject_from_normalized(axis).length();
    let rb = (b.p - point).reject_from_normalized(axis).length();
    Some(Surface::Cylinder {
        axis,
        point,
        radius: 0.5 * (ra + rb),
    })
}

/// The sphere through two points with normals: centre midway between the closest points
/// of the two normal lines.
pub fn sphere_from(a: &Oriented, b: &Oriented) -> Option<Surface> {
    let (t, s) = closest_on_lines(a.p, a.n, b.p, b.n)?;
    let center = 0.5 * (a.p + a.n * t + b.p + b.n * s);
    let radius = 0.5 * ((a.p - center).length() + (b.p - center).length());
    Some(Surface::Sphere { center, radius })
}

/// The cone through three points with normals: the apex is the common point of the three
/// tangent planes, the axis the normal of the plane through the unit directions from the
/// apex to the points.
pub fn cone_from(q: &[Oriented; 3]) -> Option<Surface> {
    let m = DMat3::from_cols(q[0].n, q[1].n, q[2].n).transpose();
    if m.determinant().abs() < 1e-6 {
        return None;
    }
    let rhs = DVec3::new(q[0].n.dot(q[0].p), q[1].n.dot(q[1].p), q[2].n.dot(q[2].p));
    let apex = m.inverse() * rhs;
    let d = q.map(|o| (o.p - apex).normalize_or_zero());
    let axis = (d[1] - d[0]).cross(d[2] - d[0]).try_normalize()?;
    let axis = if axis.dot(d[0]) < 0.0 { -axis } else { axis };
    let half_angle = d.iter().map(|v| v.dot(axis).clamp(-1.0, 1.0).acos()).sum::<f64>() / 3.0;
    Some(Surface::Cone { apex, axis, half_angle })
}

/// Parameters (t, s) of the closest points of the lines `p + t·u` and `q + s·v`; `None` for
/// (nearly) parallel lines.
fn closest_on_lines(p: DVec3, u: DVec3, q: DVec3, v: DVec3) -> Option<(f64, f64)> {
    let w = p - q;
    let (a, b, c, d, e) = (u.dot(u), u.dot(v), v.dot(v), u.dot(w), v.dot(w));
    let den = a * c - b * b;
    if den < 1e-9 {
        return None;
    }
    Some(((b * e - c * d) / den, (a * e - b * d) / den))
}
