//! Axis-aligned boxes in the model: which pairs of things come near each other, found by a
//! sweep along x instead of comparing every pair (joints, claims and rejoining all ask it of
//! hundreds of plates). Also the one fold that bounds points, in 2D and 3D, which every
//! module asks for rather than writing its own.

use glam::{DVec2, DVec3};

/// A box by its lowest and highest corner.
pub type Box3 = (DVec3, DVec3);

/// A rectangle by its lowest and highest corner.
pub type Box2 = (DVec2, DVec2);

/// The bounds of `points`; with no points, the empty box (lowest corner at +∞, highest at
/// −∞), which contains nothing and leaves any box it is united with as it was.
pub fn bounds2(points: impl IntoIterator<Item = DVec2>) -> Box2 {
    points.into_iter().fold(
        (DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY)),
        |(lo, hi), p| (lo.min(p), hi.max(p)),
    )
}

/// [`bounds2`] in 3D.
pub fn bounds3(points: impl IntoIterator<Item = DVec3>) -> Box3 {
    points.into_iter().fold(
        (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)),
        |(lo, hi), p| (lo.min(p), hi.max(p)),
    )
}

/// The smallest rectangle holding every one of `boxes`; `None` when there are none.
pub fn enclosing2(boxes: impl IntoIterator<Item = Box2>) -> Option<Box2> {
    boxes.into_iter().reduce(|(a, b), (c, d)| (a.min(c), b.max(d)))
}

/// Whether boxes `a` and `b` come within `gap` of each other on every axis.
pub fn near(a: Box3, b: Box3, gap: f64) -> bool {
    (a.0 - DVec3::splat(gap)).cmple(b.1).all() && (b.0 - DVec3::splat(gap)).cmple(a.1).all()
}

/// The pairs `(i, j)`, `i < j`, of `boxes` that come within `gap` of each other, in sweep
/// order (by the lower x of the first box, then the second's).
pub fn near_pairs(boxes: &[Box3], gap: f64) -> Vec<(usize, usize)> {
    let mut order: Vec<usize> = (0..boxes.len()).collect();
    order.sort_by(|&a, &b| boxes[a].0.x.total_cmp(&boxes[b].0.x).then(a.cmp(&b)));
    let mut pairs = Vec::new();
    for (k, &i) in order.iter().enumerate() {
        for &j in &order[k + 1..] {
            if boxes[j].0.x > boxes[i].1.x + gap {
                break;
            }
            if near(boxes[i], boxes[j], gap) {
                pairs.push((i.min(j), i.max(j)));
            }
        }
    }
    pairs
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bounds_hold_every_point_and_no_points_give_the_empty_box() {
        let (lo, hi) = bounds2([DVec2::new(1.0, 5.0), DVec2::new(-2.0, 3.0)]);
        assert_eq!((lo, hi), (DVec2::new(-2.0, 3.0), DVec2::new(1.0, 5.0)));
        let (lo, hi) = bounds3(std::iter::empty());
        assert!(lo.x > hi.x, "empty");
        let a = (DVec2::new(0.0, 1.0), DVec2::new(2.0, 3.0));
        let b = (DVec2::new(-1.0, 2.0), DVec2::new(1.0, 5.0));
        assert_eq!(enclosing2([a, b]), Some((DVec2::new(-1.0, 1.0), DVec2::new(2.0, 5.0))));
        assert_eq!(enclosing2(std::iter::empty()), None);
    }

    fn cube(x: f64) -> Box3 {
        (DVec3::new(x, 0.0, 0.0), DVec3::new(x + 1.0, 1.0, 1.0))
    }

    #[test]
    fn pairs_within_the_gap_are_found_and_no_others() {
        // Cubes at x = 0, 1.5, 5: the first two are 0.5 apart, the third 2.5 from the second.
        let boxes = [cube(5.0), cube(0.0), cube(1.5)];
        assert_eq!(near_pairs(&boxes, 0.0), Vec::<(usize, usize)>::new());
        assert_eq!(near_pairs(&boxes, 0.5), vec![(1, 2)]);
        assert_eq!(near_pairs(&boxes, 2.5), vec![(1, 2), (0, 2)]);
        // Apart in y only: not near.
        let above = (DVec3::new(0.0, 3.0, 0.0), DVec3::new(1.0, 4.0, 1.0));
        assert!(!near(cube(0.0), above, 1.0) && near(cube(0.0), above, 2.0));
    }
}
