//! Axis-aligned boxes in the model: which pairs of things come near each other, found by a
//! sweep along x instead of comparing every pair (joints, claims and rejoining all ask it of
//! hundreds of plates).

use glam::DVec3;

/// A box by its lowest and highest corner.
pub type Box3 = (DVec3, DVec3);

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
