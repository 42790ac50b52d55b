//! Test sets for the classifier: small labelled meshes (a box, a tube, a sphere, a cone
//! frustum) finely tessellated, roughened by a seeded noise of a given amplitude and moved by
//! a seeded rigid motion, with the primitives they were made of; and the score of a
//! classification against them (found within tolerance, phantoms). The tests, the bench and
//! the figures in docs/classifier.md all use these.

use glam::{DQuat, DVec3};
use platener_geom::rng::SplitMix64;
use serde::Serialize;

use platener::classify::{Classification, Surface};
use platener::mesh::Mesh;
use platener_geom::Triangle;

/// A labelled mesh: what it is made of.
#[derive(Debug, Clone)]
pub struct TestSet {
    /// Name for reports.
    pub name: String,
    /// The roughened, moved mesh.
    pub mesh: Mesh,
    /// Its primitives (moved like the mesh).
    pub truth: Vec<Surface>,
}

pub use crate::samples::patch;

/// A closed box `size` with faces cut into squares of about `cell`, normals out.
pub fn fine_box(size: DVec3, cell: f64) -> (Vec<Triangle>, Vec<Surface>) {
    let mut tris = Vec::new();
    let mut truth = Vec::new();
    for axis in 0..3 {
        let (u, v) = ((axis + 1) % 3, (axis + 2) % 3);
        let (nu, nv) = (steps(size[u], cell), steps(size[v], cell));
        for side in [0.0, 1.0] {
            let face = patch(nu, nv, |a, b| {
                let mut p = DVec3::ZERO;
                p[axis] = side * size[axis];
                p[u] = a * size[u];
                p[v] = b * size[v];
                p
            });
            // u × v is +axis: the far side faces out as made, the near side is turned.
            tris.extend(
                face.into_iter()
                    .map(|t| if side > 0.5 { t } else { [t[0], t[2], t[1]] }),
            );
            let mut n = DVec3::ZERO;
            n[axis] = if side > 0.5 { 1.0 } else { -1.0 };
            truth.push(Surface::Plane {
                normal: n,
                offset: side * size[axis],
            });
        }
    }
    (tris, truth)
}

/// Quads along a length of `len` cut into pieces of about `cell`.
fn steps(len: f64, cell: f64) -> usize {
    ((len / cell).round() as usize).max(1)
}

/// A point at `angle` (turns) and `radius` from the z axis, at height `z`.
fn polar(turns: f64, radius: f64, z: f64) -> DVec3 {
    let (s, c) = (turns * std::f64::consts::TAU).sin_cos();
    DVec3::new(radius * c, radius * s, z)
}

/// A solid of revolution about z between heights 0 and `h`: the outer wall runs from radius
/// `r0` (bottom) to `r1` (top); a bore of radius `bore` (0: none); `seg` segments round.
pub fn revolved(r0: f64, r1: f64, bore: f64, h: f64, seg: usize, cell: f64) -> Vec<Triangle> {
    let rings = steps(h, cell);
    let radial = steps(r0.max(r1) - bore, cell);
    let mut t = patch(seg, rings, |a, b| polar(a, r0 + (r1 - r0) * b, b * h));
    if bore > 0.0 {
        t.extend(
            patch(seg, rings, |a, b| polar(a, bore, b * h))
                .into_iter()
                .map(|x| [x[0], x[2], x[1]]),
        );
    }
    t.extend(
        patch(seg, radial, |a, b| polar(a, bore + (r1 - bore) * b, h))
            .into_iter()
            .map(|x| [x[0], x[2], x[1]]),
    );
    t.extend(patch(seg, radial, |a, b| polar(a, bore + (r0 - bore) * b, 0.0)));
    t
}

/// Displaces every vertex of the welded `soup` along its (area-weighted) vertex normal by a
/// seeded uniform amount in [−`amplitude`, `amplitude`] mm, then moves the whole by a
/// seeded rigid motion; the mesh and the motion.
pub fn roughen_and_move(soup: &[Triangle], amplitude: f64, seed: u64) -> (Mesh, DQuat, DVec3) {
    let w = platener::weld::weld_soup(soup, 1e-6);
    let mut normals = vec![DVec3::ZERO; w.vertices.len()];
    for t in &w.triangles {
        let [a, b, c] = t.map(|i| w.vertices[i as usize]);
        let n = (b - a).cross(c - a);
        for &i in t {
            normals[i as usize] += n;
        }
    }
    let mut rng = SplitMix64::new(seed);
    let (rot, shift) = motion(&mut rng);
    let vertices = w
        .vertices
        .iter()
        .zip(&normals)
        .map(|(v, n)| rot * (*v + n.normalize_or_zero() * amplitude * (2.0 * rng.unit() - 1.0)) + shift)
        .collect();
    (Mesh::build(vertices, &w.triangles, 1e-9), rot, shift)
}

/// A seeded rigid motion: a uniformly random rotation and a shift within 200 mm.
fn motion(rng: &mut SplitMix64) -> (DQuat, DVec3) {
    let q = loop {
        let v = glam::DVec4::new(rng.unit(), rng.unit(), rng.unit(), rng.unit()) * 2.0 - 1.0;
        let l = v.length();
        if l > 0.1 && l <= 1.0 {
            break DQuat::from_vec4(v / l);
        }
    };
    let shift = DVec3::new(rng.unit(), rng.unit(), rng.unit()) * 400.0 - 200.0;
    (q, shift)
}

/// `s` moved by the rigid motion `x ↦ rot·x + shift`.
pub fn moved(s: &Surface, rot: DQuat, shift: DVec3) -> Surface {
    match *s {
        Surface::Plane { normal, offset } => {
            let n = rot * normal;
            Surface::Plane {
                normal: n,
                offset: offset + n.dot(shift),
            }
        }
        Surface::Cylinder { axis, point, radius } => {
            let a = rot * axis;
            let p = rot * point + shift;
            Surface::Cylinder {
                axis: a,
                point: p - a * a.dot(p),
                radius,
            }
        }
        Surface::Sphere { center, radius } => Surface::Sphere {
            center: rot * center + shift,
            radius,
        },
        Surface::Cone { apex, axis, half_angle } => Surface::Cone {
            apex: rot * apex + shift,
            axis: rot * axis,
            half_angle,
        },
    }
}

/// The four test sets at `noise` mm for `seed`: a 100 × 80 × 60 box, a tube (radii 30 and
/// 20, 60 high), a sphere of radius 40 and a cone frustum (radii 40 and 15, 50 high), on
/// meshes of about 2 mm.
pub fn standard(noise: f64, seed: u64) -> Vec<TestSet> {
    let z = DVec3::Z;
    let plane = |n: DVec3, d: f64| Surface::Plane { normal: n, offset: d };
    let (box_tris, box_truth) = fine_box(DVec3::new(100.0, 80.0, 60.0), 2.0);
    let slope = (25.0f64 / 50.0).atan();
    let raw: Vec<(&str, Vec<Triangle>, Vec<Surface>)> = vec![
        ("box", box_tris, box_truth),
        (
            "tube",
            revolved(30.0, 30.0, 20.0, 60.0, 96, 2.0),
            vec![
                Surface::Cylinder {
                    axis: z,
                    point: DVec3::ZERO,
                    radius: 30.0,
                },
                Surface::Cylinder {
                    axis: z,
                    point: DVec3::ZERO,
                    radius: 20.0,
                },
                plane(z, 60.0),
                plane(-z, 0.0),
            ],
        ),
        (
            "sphere",
            crate::samples::sphere(DVec3::ZERO, 40.0, 128, 64),
            vec![Surface::Sphere {
                center: DVec3::ZERO,
                radius: 40.0,
            }],
        ),
        (
            "cone",
            revolved(40.0, 15.0, 0.0, 50.0, 112, 2.0),
            vec![
                Surface::Cone {
                    apex: DVec3::new(0.0, 0.0, 80.0),
                    axis: -z,
                    half_angle: slope,
                },
                plane(z, 50.0),
                plane(-z, 0.0),
            ],
        ),
    ];
    raw.into_iter()
        .enumerate()
        .map(|(i, (name, tris, truth))| {
            let (mesh, rot, shift) = roughen_and_move(&tris, noise, seed.wrapping_mul(31).wrapping_add(i as u64));
            TestSet {
                name: format!("{name} (noise {noise} mm, seed {seed})"),
                mesh,
                truth: truth.iter().map(|s| moved(s, rot, shift)).collect(),
            }
        })
        .collect()
}

/// How a classification did on a test set.
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize)]
pub struct Accuracy {
    /// Primitives of the truth.
    pub total: usize,
    /// Found with parameters within tolerance.
    pub found: usize,
    /// Detected primitives matching nothing and larger than 2 % of the surface.
    pub phantoms: usize,
    /// Largest share of the surface a detection matching nothing holds.
    pub worst_unmatched_share: f64,
    /// Largest normal / axis error among found planes and curved shapes, degrees.
    pub worst_angle_deg: f64,
    /// Largest relative radius error among found curved shapes.
    pub worst_radius_rel: f64,
}

/// The tolerances of the issue: plane normals within 0.5°, radii within 2 %; positions
/// within ε (planes) or 2 % of the radius (axes, centres); a cone's axis and half-angle
/// within 0.5°, its apex within 2ε (a 2 % radius error moves the apex of the test cone by
/// about 1.6 mm).
pub fn matches(truth: &Surface, got: &Surface, eps: f64) -> Option<(f64, f64)> {
    let angle = |a: DVec3, b: DVec3| a.dot(b).abs().clamp(0.0, 1.0).acos().to_degrees();
    let (deg, rel, ok) = match (*truth, *got) {
        (Surface::Plane { normal: n, offset: d }, Surface::Plane { normal: m, offset: e }) => {
            let deg = n.dot(m).clamp(-1.0, 1.0).acos().to_degrees();
            (deg, 0.0, deg <= 0.5 && (d - e).abs() <= eps)
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
        ) => {
            let (deg, rel) = (angle(a, b), (r - s).abs() / r);
            (
                deg,
                rel,
                deg <= 0.5 && rel <= 0.02 && (q - p).reject_from_normalized(a).length() <= 0.02 * r,
            )
        }
        (Surface::Sphere { center: c, radius: r }, Surface::Sphere { center: d, radius: s }) => {
            let rel = (r - s).abs() / r;
            (0.0, rel, rel <= 0.02 && (c - d).length() <= 0.02 * r)
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
        ) => {
            let deg = angle(a, b);
            let ha = (h - k).abs().to_degrees();
            (
                deg.max(ha),
                0.0,
                deg <= 0.5 && ha <= 0.5 && (p - q).length() <= 2.0 * eps,
            )
        }
        _ => return None,
    };
    ok.then_some((deg, rel))
}

/// How `c` did against the truth of `set`.
pub fn accuracy(set: &TestSet, c: &Classification) -> Accuracy {
    let eps = c.thresholds.eps;
    let mut s = Accuracy {
        total: set.truth.len(),
        ..Accuracy::default()
    };
    for t in &set.truth {
        let best = c
            .primitives
            .iter()
            .filter_map(|p| matches(t, &p.shape, eps))
            .min_by(|a, b| a.0.total_cmp(&b.0));
        if let Some((deg, rel)) = best {
            s.found += 1;
            s.worst_angle_deg = s.worst_angle_deg.max(deg);
            s.worst_radius_rel = s.worst_radius_rel.max(rel);
        }
    }
    for p in &c.primitives {
        if set.truth.iter().all(|t| matches(t, &p.shape, eps).is_none()) {
            let share = p.area / c.surface_area;
            s.worst_unmatched_share = s.worst_unmatched_share.max(share);
            s.phantoms += usize::from(share > 0.02);
        }
    }
    s
}
