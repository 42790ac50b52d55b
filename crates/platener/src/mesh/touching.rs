//! Which bodies of a model are one solid: bodies that touch or cross each other.
//!
//! Editors and slicers happily export a print as several overlapping bodies (a bracket and
//! the blocks unioned onto it, letters sunk into a plate). Printed, they are one piece; a plan
//! of them must hold together as one piece, so `verify` and the score must not count them as
//! separate solids. Two bodies are one solid when a vertex of one lies within [`TOUCH`] of the
//! other's surface, or an edge of one passes through a face of the other (two bars crossing in
//! a `+` have no vertex near the other bar, but their edges cross its faces).

use glam::DVec3;

/// Bodies closer than this (mm) touch: the snapping distance of separately stored copies.
pub const TOUCH: f64 = crate::weld::SNAP;

/// Above this many edge–triangle tests for one pair of bodies, overlapping bounding boxes are
/// taken as touching: the count of solids may then be too low, never too high, so `verify`
/// errs on the strict side rather than spending seconds on a pair.
const MAX_TESTS: usize = 20_000_000;

type Bounds = (DVec3, DVec3);

fn bounds_of(points: impl Iterator<Item = DVec3>) -> Bounds {
    platener_geom::boxes::bounds3(points)
}

fn overlap(a: &Bounds, b: &Bounds, pad: f64) -> Option<Bounds> {
    let lo = a.0.max(b.0) - DVec3::splat(pad);
    let hi = a.1.min(b.1) + DVec3::splat(pad);
    lo.cmple(hi).all().then_some((lo, hi))
}

fn in_box(p: DVec3, b: &Bounds) -> bool {
    p.cmpge(b.0).all() && p.cmple(b.1).all()
}

/// The number of solids among `top` bodies (faces per body), bodies that touch merged.
pub(super) fn count_solids(vertices: &[DVec3], triangles: &[[u32; 3]], top: &[&[u32]]) -> usize {
    let corners = |f: u32| triangles[f as usize].map(|v| vertices[v as usize]);
    let boxes: Vec<Bounds> = top
        .iter()
        .map(|faces| bounds_of(faces.iter().flat_map(|&f| corners(f))))
        .collect();
    let mut parent: Vec<usize> = (0..top.len()).collect();
    fn root(parent: &mut [usize], mut i: usize) -> usize {
        while parent[i] != i {
            parent[i] = parent[parent[i]];
            i = parent[i];
        }
        i
    }
    for a in 0..top.len() {
        for b in a + 1..top.len() {
            let Some(region) = overlap(&boxes[a], &boxes[b], TOUCH) else {
                continue;
            };
            let near = |faces: &[u32]| -> Vec<[DVec3; 3]> {
                faces
                    .iter()
                    .map(|&f| corners(f))
                    .filter(|t| overlap(&bounds_of(t.iter().copied()), &region, 0.0).is_some())
                    .collect()
            };
            let (ta, tb) = (near(top[a]), near(top[b]));
            let touching = ta.len() * tb.len() > MAX_TESTS || touches(&ta, &tb, &region) || touches(&tb, &ta, &region);
            if touching {
                let (ra, rb) = (root(&mut parent, a), root(&mut parent, b));
                parent[ra.max(rb)] = ra.min(rb);
            }
        }
    }
    (0..top.len()).filter(|&i| root(&mut parent, i) == i).count()
}

/// Whether a vertex of `from` lies within [`TOUCH`] of a triangle of `to`, or an edge of
/// `from` crosses one.
fn touches(from: &[[DVec3; 3]], to: &[[DVec3; 3]], region: &Bounds) -> bool {
    from.iter().any(|t| {
        (0..3).any(|i| {
            let (p, q) = (t[i], t[(i + 1) % 3]);
            (in_box(p, region) && to.iter().any(|u| distance_to_triangle(p, u) <= TOUCH))
                || to.iter().any(|u| segment_crosses(p, q, u))
        })
    })
}

/// Whether the segment `p`–`q` passes through the triangle (Möller–Trumbore, t in [0, 1]).
fn segment_crosses(p: DVec3, q: DVec3, [a, b, c]: &[DVec3; 3]) -> bool {
    let dir = q - p;
    let (e1, e2) = (*b - *a, *c - *a);
    let h = dir.cross(e2);
    let det = e1.dot(h);
    if det.abs() < 1e-12 * e1.length() * e2.length() * dir.length() {
        return false;
    }
    let s = p - *a;
    let u = s.dot(h) / det;
    let r = s.cross(e1);
    let v = dir.dot(r) / det;
    let t = e2.dot(r) / det;
    (0.0..=1.0).contains(&u) && v >= 0.0 && u + v <= 1.0 && (0.0..=1.0).contains(&t)
}

/// Distance from `p` to the triangle (closest point by regions, after Ericson).
fn distance_to_triangle(p: DVec3, [a, b, c]: &[DVec3; 3]) -> f64 {
    let (ab, ac, ap) = (*b - *a, *c - *a, p - *a);
    let (d1, d2) = (ab.dot(ap), ac.dot(ap));
    if d1 <= 0.0 && d2 <= 0.0 {
        return ap.length();
    }
    let bp = p - *b;
    let (d3, d4) = (ab.dot(bp), ac.dot(bp));
    if d3 >= 0.0 && d4 <= d3 {
        return bp.length();
    }
    let vc = d1 * d4 - d3 * d2;
    if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 {
        return (p - (*a + ab * (d1 / (d1 - d3)))).length();
    }
    let cp = p - *c;
    let (d5, d6) = (ab.dot(cp), ac.dot(cp));
    if d6 >= 0.0 && d5 <= d6 {
        return cp.length();
    }
    let vb = d5 * d2 - d1 * d6;
    if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 {
        return (p - (*a + ac * (d2 / (d2 - d6)))).length();
    }
    let va = d3 * d6 - d5 * d4;
    if va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0 {
        return (p - (*b + (*c - *b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6))))).length();
    }
    let denom = va + vb + vc;
    if denom.abs() < f64::MIN_POSITIVE {
        return ap.length().min(bp.length()).min(cp.length());
    }
    let closest = *a + ab * (vb / denom) + ac * (vc / denom);
    (p - closest).length()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Solids among boxes given as (min corner, size), each its own body. Corners are not
    /// shared between triangles: only positions matter here.
    fn solids(boxes: &[(DVec3, DVec3)]) -> usize {
        let (mut v, mut t, mut bodies) = (Vec::new(), Vec::new(), Vec::new());
        for &(min, size) in boxes {
            let first = t.len() as u32;
            for tri in platener_fixtures::samples::cuboid(min, min + size) {
                let base = v.len() as u32;
                v.extend(tri);
                t.push([base, base + 1, base + 2]);
            }
            bodies.push((first..t.len() as u32).collect::<Vec<u32>>());
        }
        let refs: Vec<&[u32]> = bodies.iter().map(|b| b.as_slice()).collect();
        count_solids(&v, &t, &refs)
    }

    #[test]
    fn apart_touching_and_crossing_bodies() {
        let unit = DVec3::splat(10.0);
        // Two cubes 1 mm apart are two solids.
        assert_eq!(solids(&[(DVec3::ZERO, unit), (DVec3::new(11.0, 0.0, 0.0), unit)]), 2);
        // Face to face, or a block sunk into the other, they are one.
        assert_eq!(
            solids(&[(DVec3::ZERO, unit), (DVec3::new(10.0, 2.0, 2.0), DVec3::splat(5.0))]),
            1
        );
        assert_eq!(
            solids(&[(DVec3::ZERO, unit), (DVec3::new(8.0, 2.0, 2.0), DVec3::splat(5.0))]),
            1
        );
        // Two bars crossing in a `+`: no vertex near the other, edges through its faces.
        let bar_x = (DVec3::new(-20.0, 4.0, 0.0), DVec3::new(50.0, 2.0, 2.0));
        let bar_y = (DVec3::new(4.0, -20.0, -1.0), DVec3::new(2.0, 50.0, 4.0));
        assert_eq!(solids(&[bar_x, bar_y]), 1);
        // A chain a–b–c is one solid; a fourth far away is another.
        let chain = [
            (DVec3::ZERO, unit),
            (DVec3::new(10.0, 0.0, 0.0), unit),
            (DVec3::new(20.0, 0.0, 0.0), unit),
            (DVec3::new(0.0, 50.0, 0.0), unit),
        ];
        assert_eq!(solids(&chain), 2);
    }

    #[test]
    fn distance_to_a_triangle_by_region() {
        let t = [DVec3::ZERO, DVec3::X * 4.0, DVec3::Y * 4.0];
        assert!((distance_to_triangle(DVec3::new(1.0, 1.0, 3.0), &t) - 3.0).abs() < 1e-12);
        assert!((distance_to_triangle(DVec3::new(-3.0, -4.0, 0.0), &t) - 5.0).abs() < 1e-12);
        assert!((distance_to_triangle(DVec3::new(2.0, -2.0, 0.0), &t) - 2.0).abs() < 1e-12);
        assert!((distance_to_triangle(DVec3::new(3.0, 3.0, 0.0), &t) - 2.0_f64.sqrt()).abs() < 1e-12);
    }
}
