//! Connectivity of a primitive's inliers on a grid in its parameter space (Schnabel et al.,
//! section 4.4): a candidate plane also collects every coplanar patch elsewhere on the model,
//! a cylinder every coaxial ring; only the largest connected piece is one surface.

use glam::DVec2;

/// The indices (into `params`) of the points in the largest 8-connected component of the
/// occupied cells of side `cell`; the first coordinate wraps round with `period` when given
/// (a full cylinder is one piece across its seam). Ties go to the component holding the
/// lowest cell, so the answer never depends on anything but the input.
pub fn largest_component(params: &[DVec2], period: Option<f64>, cell: f64) -> Vec<usize> {
    if params.is_empty() {
        return Vec::new();
    }
    let wrap = period.map(|p| ((p / cell).round() as i64).max(1));
    let cell_of = |q: DVec2| {
        let x = (q.x / cell).floor() as i64;
        (wrap.map_or(x, |w| x.rem_euclid(w)), (q.y / cell).floor() as i64)
    };
    let point_cells: Vec<(i64, i64)> = params.iter().map(|q| cell_of(*q)).collect();
    let mut cells: Vec<(i64, i64)> = point_cells.clone();
    cells.sort_unstable();
    cells.dedup();
    let label = label_cells(&cells, wrap);
    let mut size = vec![0usize; cells.len()];
    let find = |c: &(i64, i64)| cells.binary_search(c).map(|i| label[i]).unwrap_or(usize::MAX);
    for c in &point_cells {
        size[find(c)] += 1;
    }
    // Labels are numbered in cell order, so the first maximum is the lowest-cell component.
    let best = (0..size.len()).fold(0, |b, i| if size[i] > size[b] { i } else { b });
    point_cells
        .iter()
        .enumerate()
        .filter(|(_, c)| find(c) == best)
        .map(|(i, _)| i)
        .collect()
}

/// Component labels of sorted, distinct `cells` (8-neighbourhood, wrapping x by `wrap`),
/// numbered in the order of their lowest cell.
fn label_cells(cells: &[(i64, i64)], wrap: Option<i64>) -> Vec<usize> {
    let mut label = vec![usize::MAX; cells.len()];
    let mut next = 0;
    let mut stack = Vec::new();
    for s in 0..cells.len() {
        if label[s] != usize::MAX {
            continue;
        }
        label[s] = next;
        stack.push(s);
        while let Some(i) = stack.pop() {
            let (x, y) = cells[i];
            for dx in -1..=1 {
                for dy in -1..=1 {
                    let nx = wrap.map_or(x + dx, |w| (x + dx).rem_euclid(w));
                    if let Ok(j) = cells.binary_search(&(nx, y + dy))
                        && label[j] == usize::MAX
                    {
                        label[j] = next;
                        stack.push(j);
                    }
                }
            }
        }
        next += 1;
    }
    label
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn two_patches_keep_the_larger() {
        let mut p: Vec<DVec2> = (0..10)
            .flat_map(|i| (0..10).map(move |j| DVec2::new(i as f64, j as f64)))
            .collect();
        p.extend((0..5).map(|i| DVec2::new(50.0 + i as f64, 0.0)));
        let keep = largest_component(&p, None, 1.0);
        assert_eq!(keep.len(), 100);
        assert!(keep.iter().all(|&i| i < 100));
    }

    #[test]
    fn wraps_round_the_period() {
        // Two runs either side of the seam of a 20-unit period are one ring piece.
        let p: Vec<DVec2> = [0.5, 1.5, 2.5, 17.5, 18.5, 19.5, 10.5]
            .iter()
            .map(|&x| DVec2::new(x, 0.0))
            .collect();
        let keep = largest_component(&p, Some(20.0), 1.0);
        assert_eq!(keep, vec![0, 1, 2, 3, 4, 5]);
        assert_eq!(largest_component(&p, None, 1.0), vec![0, 1, 2]);
    }
}
