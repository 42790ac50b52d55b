use super::*;
use proptest::prelude::*;

#[test]
fn merges_close_points_to_weighted_mean() {
    let pts = [[0.0, 0.0, 0.0], [0.3, 0.0, 0.0], [10.0, 0.0, 0.0]];
    let w = weld(&pts, &[1.0, 3.0, 1.0], 1.0);
    assert_eq!(w.points.len(), 2);
    assert_eq!(w.map, vec![0, 0, 1]);
    assert!((w.points[0][0] - 0.225).abs() < 1e-12);
    assert_eq!(w.weights, vec![4.0, 1.0]);
}

#[test]
fn does_not_chain_a_fine_line() {
    // 1001 points 0.1 apart on a 100 mm line, welded at 1 mm: about 50-100 points remain,
    // spread over the whole line (leader clustering never chains).
    let pts: Vec<[f64; 2]> = (0..=1000).map(|i| [i as f64 * 0.1, 0.0]).collect();
    let w = weld(&pts, &vec![1.0; pts.len()], 1.0);
    assert!(w.points.len() >= 50 && w.points.len() <= 101, "{}", w.points.len());
    let max_x = w.points.iter().map(|p| p[0]).fold(f64::MIN, f64::max);
    assert!(max_x > 98.0);
}

#[test]
fn zero_distance_merges_exact_duplicates_only() {
    let pts = [[1.0, 2.0], [1.0, 2.0], [1.0, 2.000001], [-0.0, 0.0], [0.0, 0.0]];
    let w = weld(&pts, &[1.0; 5], 0.0);
    assert_eq!(w.map, vec![0, 0, 1, 2, 2]);
}

proptest! {
    #[test]
    fn welding_twice_changes_nothing(
        pts in prop::collection::vec((-50.0f64..50.0, -50.0f64..50.0, -50.0f64..50.0), 1..300),
        d in 0.5f64..5.0,
    ) {
        let pts: Vec<[f64; 3]> = pts.into_iter().map(|(x, y, z)| [x, y, z]).collect();
        let once = weld(&pts, &vec![1.0; pts.len()], d);
        let twice = weld(&once.points, &once.weights, d);
        prop_assert_eq!(&twice.points, &once.points);
        // No two results closer than the distance, and every input near its cluster.
        for (i, p) in pts.iter().enumerate() {
            let c = &once.points[once.map[i] as usize];
            prop_assert!(dist2(p, c).sqrt() < 2.0 * d * (MAX_ROUNDS as f64));
        }
    }

    #[test]
    fn translation_by_whole_cells_gives_the_same_clusters(
        pts in prop::collection::vec((-3200i32..3200, -3200i32..3200), 1..200),
        shift in (-100i32..100, -100i32..100),
    ) {
        // Points on a 1/64 mm lattice and shifts by whole 4 mm cells: every sum is exact in
        // f64, so the clustering must be exactly the same, moved.
        let a: Vec<[f64; 2]> = pts.iter().map(|&(x, y)| [x as f64 / 64.0, y as f64 / 64.0]).collect();
        let (sx, sy) = (shift.0 as f64 * 4.0, shift.1 as f64 * 4.0);
        let b: Vec<[f64; 2]> = a.iter().map(|p| [p[0] + sx, p[1] + sy]).collect();
        let wa = weld(&a, &vec![1.0; a.len()], 2.0);
        let wb = weld(&b, &vec![1.0; b.len()], 2.0);
        prop_assert_eq!(&wa.map, &wb.map);
        for (p, q) in wa.points.iter().zip(&wb.points) {
            prop_assert!((p[0] + sx - q[0]).abs() < 1e-9 && (p[1] + sy - q[1]).abs() < 1e-9);
        }
    }
}

#[test]
fn connected_welding_keeps_unconnected_neighbours_apart() {
    // Two parallel rows 1 mm apart (a thin wall's faces), each row a chain of edges 0.5 apart.
    let mut pts = Vec::new();
    let mut edges = Vec::new();
    for row in 0..2 {
        for i in 0..10 {
            pts.push([i as f64 * 0.5, row as f64, 0.0]);
            if i > 0 {
                let k = (row * 10 + i) as u32;
                edges.push([k - 1, k]);
            }
        }
    }
    let w = weld_connected(&pts, &vec![1.0; pts.len()], 1.2, &edges);
    // Each row coarsens along itself, but no cluster mixes the rows.
    for (i, &c) in w.map.iter().enumerate() {
        let row = i / 10;
        assert!(
            w.map
                .iter()
                .enumerate()
                .filter(|&(_, &d)| d == c)
                .all(|(j, _)| j / 10 == row)
        );
    }
    assert!(w.points.len() < pts.len() && w.points.len() >= 4);
    // Unconstrained welding at the same distance mixes them.
    let free = weld(&pts, &vec![1.0; pts.len()], 1.2);
    assert!(free.map[0] == free.map[10]);
    // Idempotent.
    let remapped: Vec<[u32; 2]> = edges
        .iter()
        .map(|e| [w.map[e[0] as usize], w.map[e[1] as usize]])
        .collect();
    let again = weld_connected(&w.points, &w.weights, 1.2, &remapped);
    assert_eq!(again.points, w.points);
}
