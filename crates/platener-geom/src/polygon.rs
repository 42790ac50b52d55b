//! Polygons with holes in a plane's 2D frame.
//!
//! Convention (as in plan.json): the outer ring is counter-clockwise, holes are clockwise,
//! rings are not closed (last ≠ first). Areas are exact up to float rounding (shoelace).

use glam::DVec2;
use serde::Serialize;

/// A closed ring of points, not repeating the first at the end.
pub type Ring = Vec<DVec2>;

/// One polygon: an outer ring and its holes.
#[derive(Debug, Clone, PartialEq, Serialize, Default)]
pub struct Polygon {
    /// Outer boundary, counter-clockwise.
    pub outer: Ring,
    /// Holes, each clockwise.
    pub holes: Vec<Ring>,
}

/// Twice the signed area of a ring: positive when counter-clockwise.
pub fn signed_area2(ring: &[DVec2]) -> f64 {
    let n = ring.len();
    if n < 3 {
        return 0.0;
    }
    // Relative to the first point: keeps precision far from the origin.
    let o = ring[0];
    let mut sum = 0.0;
    for i in 1..n - 1 {
        sum += (ring[i] - o).perp_dot(ring[i + 1] - o);
    }
    sum
}

/// The axis-aligned rectangle from (x0, y0) to (x1, y1), counter-clockwise when x0 < x1 and
/// y0 < y1.
pub fn rect(x0: f64, y0: f64, x1: f64, y1: f64) -> Ring {
    vec![
        DVec2::new(x0, y0),
        DVec2::new(x1, y0),
        DVec2::new(x1, y1),
        DVec2::new(x0, y1),
    ]
}

/// Signed area of a ring (positive when counter-clockwise).
pub fn signed_area(ring: &[DVec2]) -> f64 {
    0.5 * signed_area2(ring)
}

/// Perimeter of a closed ring.
pub fn perimeter(ring: &[DVec2]) -> f64 {
    let n = ring.len();
    (0..n).map(|i| ring[i].distance(ring[(i + 1) % n])).sum()
}

/// A point strictly inside `ring` (any orientation): the middle of the widest stretch inside
/// it along the horizontal line through the middle of its height. `None` for a ring with no
/// area.
pub fn interior_point(ring: &[DVec2]) -> Option<DVec2> {
    let (lo, hi) = bounds_of(ring.iter().copied());
    // Off the middle by an odd fraction, so the line misses vertices of regular shapes.
    let y = lo.y + (hi.y - lo.y) * 0.500_173;
    let mut xs: Vec<f64> = Vec::new();
    for i in 0..ring.len() {
        let (a, b) = (ring[i], ring[(i + 1) % ring.len()]);
        if (a.y <= y) != (b.y <= y) {
            xs.push(a.x + (y - a.y) / (b.y - a.y) * (b.x - a.x));
        }
    }
    xs.sort_by(f64::total_cmp);
    xs.chunks_exact(2)
        .map(|pair| (pair[1] - pair[0], pair))
        .filter(|(width, _)| *width > 0.0)
        .max_by(|a, b| a.0.total_cmp(&b.0))
        .map(|(_, pair)| DVec2::new((pair[0] + pair[1]) / 2.0, y))
}

/// Even-odd point-in-ring test (the boundary counts as either side).
pub fn ring_contains(ring: &[DVec2], p: DVec2) -> bool {
    let n = ring.len();
    let mut inside = false;
    let mut j = n.wrapping_sub(1);
    for i in 0..n {
        let (a, b) = (ring[i], ring[j]);
        if (a.y > p.y) != (b.y > p.y) {
            let x = a.x + (p.y - a.y) * (b.x - a.x) / (b.y - a.y);
            if p.x < x {
                inside = !inside;
            }
        }
        j = i;
    }
    inside
}

/// Axis-aligned bounds `(min, max)` of some points (a ring's, say); `(+∞, −∞)` when there
/// are none.
pub fn bounds_of(points: impl IntoIterator<Item = DVec2>) -> (DVec2, DVec2) {
    crate::boxes::bounds2(points)
}

/// Squared distance from `p` to the segment `ab` (a point when `a == b`).
pub fn segment_distance_squared(a: DVec2, b: DVec2, p: DVec2) -> f64 {
    let d = b - a;
    let len2 = d.length_squared();
    let t = if len2 > 0.0 {
        ((p - a).dot(d) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    (a + d * t).distance_squared(p)
}

/// Squared distance from `p` to the edges of the closed `ring` (+∞ for an empty ring).
pub fn ring_distance_squared(ring: &[DVec2], p: DVec2) -> f64 {
    let n = ring.len();
    (0..n)
        .map(|i| segment_distance_squared(ring[i], ring[(i + 1) % n], p))
        .fold(f64::INFINITY, f64::min)
}

impl Polygon {
    /// A polygon without holes.
    pub fn new(outer: Ring) -> Self {
        Self {
            outer,
            holes: Vec::new(),
        }
    }

    /// Area: outer minus holes (holes given clockwise or not, their absolute area is removed).
    pub fn area(&self) -> f64 {
        signed_area(&self.outer).abs() - self.holes.iter().map(|h| signed_area(h).abs()).sum::<f64>()
    }

    /// Whether `p` is inside the outer ring and outside every hole.
    pub fn contains(&self, p: DVec2) -> bool {
        ring_contains(&self.outer, p) && !self.holes.iter().any(|h| ring_contains(h, p))
    }

    /// Distance from `p` to the polygon: 0 inside, else to the nearest point of its boundary.
    pub fn distance_to(&self, p: DVec2) -> f64 {
        if self.contains(p) {
            0.0
        } else {
            self.boundary_distance(p)
        }
    }

    /// Distance from `p` to the nearest point of the polygon's boundary, inside or out.
    pub fn boundary_distance(&self, p: DVec2) -> f64 {
        self.boundary_distance_squared(p).sqrt()
    }

    /// Squared distance from `p` to the nearest point of the polygon's boundary (outer ring
    /// and holes): compare it with a squared length to avoid the square root.
    pub fn boundary_distance_squared(&self, p: DVec2) -> f64 {
        std::iter::once(&self.outer)
            .chain(&self.holes)
            .map(|ring| ring_distance_squared(ring, p))
            .fold(f64::INFINITY, f64::min)
    }

    /// Number of vertices over all rings.
    pub fn vertex_count(&self) -> usize {
        self.outer.len() + self.holes.iter().map(Vec::len).sum::<usize>()
    }

    /// Axis-aligned bounds `(min, max)` of the outer ring.
    pub fn bounds(&self) -> (DVec2, DVec2) {
        bounds_of(self.outer.iter().copied())
    }

    /// Puts the rings in the plan.json orientation: outer counter-clockwise, holes clockwise.
    pub fn normalize_orientation(&mut self) {
        if signed_area2(&self.outer) < 0.0 {
            self.outer.reverse();
        }
        for h in &mut self.holes {
            if signed_area2(h) > 0.0 {
                h.reverse();
            }
        }
    }
}

/// The convex hull of some points, counter-clockwise (Andrew's monotone chain), without
/// collinear points. Fewer than three distinct points give what there is.
pub fn convex_hull(points: &[DVec2]) -> Ring {
    let mut pts: Vec<DVec2> = points.to_vec();
    pts.sort_by(|a, b| a.x.total_cmp(&b.x).then(a.y.total_cmp(&b.y)));
    pts.dedup();
    if pts.len() < 3 {
        return pts;
    }
    let mut hull: Ring = Vec::with_capacity(pts.len() + 1);
    for pass in 0..2 {
        let start = hull.len();
        let iter: Box<dyn Iterator<Item = &DVec2>> = if pass == 0 {
            Box::new(pts.iter())
        } else {
            Box::new(pts.iter().rev())
        };
        for &p in iter {
            while hull.len() >= start + 2
                && (hull[hull.len() - 1] - hull[hull.len() - 2]).perp_dot(p - hull[hull.len() - 2]) <= 0.0
            {
                hull.pop();
            }
            hull.push(p);
        }
        hull.pop();
    }
    hull
}

/// Total area of several polygons.
pub fn total_area(polygons: &[Polygon]) -> f64 {
    polygons.iter().map(Polygon::area).sum()
}

/// Removes vertices lying on straight runs: a vertex goes when it is within `tolerance` of the
/// segment between its neighbours *and* between them (so a spike that folds back is kept).
/// Runs in linear time with a stack; the ring's wrap-around is handled.
pub fn remove_straight_vertices(ring: &[DVec2], tolerance: f64) -> Ring {
    let between = |a: DVec2, b: DVec2, c: DVec2| {
        let ac = c - a;
        let len2 = ac.length_squared();
        if len2 == 0.0 {
            return false;
        }
        let t = (b - a).dot(ac) / len2;
        t > 0.0 && t < 1.0 && ac.perp_dot(b - a).abs() / len2.sqrt() <= tolerance
    };
    let mut out: Ring = Vec::with_capacity(ring.len());
    for &p in ring {
        while out.len() >= 2 && between(out[out.len() - 2], out[out.len() - 1], p) {
            out.pop();
        }
        out.push(p);
    }
    // Close the ring: the last and first vertices may lie on the run through the seam.
    loop {
        let n = out.len();
        if n < 3 {
            break;
        }
        if between(out[n - 2], out[n - 1], out[0]) {
            out.pop();
        } else if between(out[n - 1], out[0], out[1]) {
            out.remove(0);
        } else {
            break;
        }
    }
    out
}

#[cfg(test)]
mod tests {
    #[test]
    fn an_interior_point_lies_inside_a_u_and_a_clockwise_square() {
        // A U open at the top: the middle line crosses both arms; the wider arm's middle wins.
        let u = vec![
            DVec2::new(0.0, 0.0),
            DVec2::new(30.0, 0.0),
            DVec2::new(30.0, 20.0),
            DVec2::new(26.0, 20.0),
            DVec2::new(26.0, 4.0),
            DVec2::new(6.0, 4.0),
            DVec2::new(6.0, 20.0),
            DVec2::new(0.0, 20.0),
        ];
        let p = interior_point(&u).expect("a point");
        assert!(ring_contains(&u, p) && (p.x - 3.0).abs() < 1e-9, "{p}");
        let mut square = rect(0.0, 0.0, 10.0, 10.0);
        square.reverse();
        let q = interior_point(&square).expect("a point");
        assert!((q.x - 5.0).abs() < 1e-9 && ring_contains(&square, q), "{q}");
        assert_eq!(interior_point(&[DVec2::ZERO, DVec2::X]), None);
    }

    #[test]
    fn straight_runs_go_spikes_stay() {
        let ring = vec![
            DVec2::new(0.0, 0.0),
            DVec2::new(5.0, 0.0),
            DVec2::new(10.0, 0.0),
            DVec2::new(10.0, 10.0),
            DVec2::new(5.0, 10.0 + 1e-9),
            DVec2::new(0.0, 10.0),
            DVec2::new(0.0, 5.0),
        ];
        let out = remove_straight_vertices(&ring, 1e-6);
        assert_eq!(
            out,
            vec![
                DVec2::new(0.0, 0.0),
                DVec2::new(10.0, 0.0),
                DVec2::new(10.0, 10.0),
                DVec2::new(0.0, 10.0)
            ]
        );
        // A vertex that folds back along the same line is not "between" its neighbours.
        let spike = vec![
            DVec2::new(0.0, 0.0),
            DVec2::new(10.0, 0.0),
            DVec2::new(5.0, 0.0),
            DVec2::new(5.0, 5.0),
        ];
        assert_eq!(remove_straight_vertices(&spike, 1e-6).len(), 4);
    }

    use super::*;

    fn square(x: f64, y: f64, s: f64) -> Ring {
        vec![
            DVec2::new(x, y),
            DVec2::new(x + s, y),
            DVec2::new(x + s, y + s),
            DVec2::new(x, y + s),
        ]
    }

    #[test]
    fn area_with_hole() {
        let mut p = Polygon {
            outer: square(0.0, 0.0, 10.0),
            holes: vec![square(2.0, 2.0, 3.0)],
        };
        p.normalize_orientation();
        assert!((p.area() - 91.0).abs() < 1e-12);
        assert!(signed_area(&p.holes[0]) < 0.0);
        assert!(p.contains(DVec2::new(1.0, 1.0)));
        assert!(!p.contains(DVec2::new(3.0, 3.0)));
    }

    #[test]
    fn hull_of_a_square_with_inner_points() {
        let mut pts = square(0.0, 0.0, 4.0);
        pts.extend([DVec2::new(1.0, 1.0), DVec2::new(2.0, 0.0), DVec2::new(3.0, 2.0)]);
        let h = convex_hull(&pts);
        assert_eq!(h.len(), 4);
        assert!((signed_area(&h) - 16.0).abs() < 1e-12);
    }

    #[test]
    fn far_from_origin_area_keeps_precision() {
        let r = square(1.0e5, -1.0e5, 0.001);
        assert!((signed_area(&r) - 1e-6).abs() < 1e-12);
    }
}
