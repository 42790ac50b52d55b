//! Islands too small to cut that hold the stack together are kept, enlarged until cuttable.
//!
//! Dropping every island under the minimum area or width (a teapot lid's knob neck, a thin
//! stem) leaves what rests on it floating: the knob above has nothing below it in the plan,
//! though the model holds it. So the small islands are looked at across layers: islands of
//! adjacent layers *touch* when their outlines overlap by more than [`MIN_OVERLAP`]. The kept
//! islands fall into groups that touch; a run of small islands (small islands touching each
//! other) that touches two or more such groups is what connects them, and is kept. A small
//! island touching one group only (a dome's crumb on top, a thin fin) still holds nothing and
//! stays dropped. Runs are taken bottom up (by their first island), and groups they join are
//! merged, so a second run between the same groups is not kept for nothing.
//!
//! A kept small island is grown outwards until it is cuttable: by half the minimum width when
//! it is nowhere that wide (an inward offset by the same amount then recovers it), and enough
//! for the minimum area (from area + perimeter·r + π·r² ≥ minimum). Growing only adds overlap
//! with its neighbours. Where it then overlaps an island of its own layer, the two are united.

use glam::DVec2;
use platener_geom::polygon::{perimeter, total_area};
use platener_geom::{GridError, Polygon, boolean, offset};

use super::shafts::{MIN_OVERLAP, boxes_meet};
use crate::assembly::UnionFind;
use crate::cuttable::{Rule, TooSmall};

/// An island too small to cut that was kept because it holds other layers together.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct KeptIsland {
    /// Its layer (0-based).
    pub layer: usize,
    /// Its area as sliced, mm².
    pub area: f64,
    /// Its area once enlarged to be cuttable, mm².
    pub enlarged: f64,
}

/// A small island as [`super::islands::islands_of`] set it aside: its layer and shape.
#[derive(Debug, Clone)]
pub(crate) struct Small {
    pub layer: usize,
    pub polygon: Polygon,
}

/// Keeps the `small` islands that connect groups of `layers`' islands (see the module docs),
/// enlarged; returns what was kept, bottom up, and per small island whether it was kept (the
/// rest stay dropped).
pub(crate) fn keep_supporting(
    layers: &mut [Vec<Polygon>],
    small: &[Small],
    rule: &Rule,
) -> Result<(Vec<KeptIsland>, Vec<bool>), GridError> {
    let nodes = Nodes::new(layers, small);
    let edges = touching_pairs(&nodes, layers.len())?;
    let mut groups = UnionFind::new(nodes.len());
    let mut runs = UnionFind::new(nodes.len());
    for &(a, b) in &edges {
        match (nodes.is_small(a), nodes.is_small(b)) {
            (false, false) => groups.join(a, b),
            (true, true) => runs.join(a, b),
            _ => {}
        }
    }
    // (run, kept island it touches), runs by their first (lowest) small island.
    let mut contacts: Vec<(usize, usize)> = edges
        .iter()
        .filter_map(|&(a, b)| match (nodes.is_small(a), nodes.is_small(b)) {
            (true, false) => Some((runs.root(a), b)),
            (false, true) => Some((runs.root(b), a)),
            _ => None,
        })
        .collect();
    contacts.sort_unstable();
    contacts.dedup();
    let mut chosen_runs = Vec::new();
    for chunk in contacts.chunk_by(|x, y| x.0 == y.0) {
        let mut touched: Vec<usize> = chunk.iter().map(|&(_, k)| groups.root(k)).collect();
        touched.sort_unstable();
        touched.dedup();
        if touched.len() >= 2 {
            for w in touched.windows(2) {
                groups.join(w[0], w[1]);
            }
            chosen_runs.push(chunk[0].0);
        }
    }
    let first_small = nodes.kept;
    let chosen: Vec<bool> = (0..small.len())
        .map(|i| chosen_runs.contains(&runs.root(first_small + i)))
        .collect();
    let mut kept = Vec::new();
    for (sm, _) in small.iter().zip(&chosen).filter(|(_, c)| **c) {
        let grown = enlarge(&sm.polygon, rule)?;
        kept.push(KeptIsland {
            layer: sm.layer,
            area: sm.polygon.area(),
            enlarged: total_area(&grown),
        });
        merge_into(&mut layers[sm.layer], grown)?;
    }
    Ok((kept, chosen))
}

/// Every island, the kept ones first (layer by layer), then the small ones.
struct Nodes<'a> {
    all: Vec<(usize, &'a Polygon)>,
    kept: usize,
}

impl<'a> Nodes<'a> {
    fn new(islands: &'a [Vec<Polygon>], small: &'a [Small]) -> Self {
        let mut all: Vec<(usize, &Polygon)> = islands
            .iter()
            .enumerate()
            .flat_map(|(k, l)| l.iter().map(move |p| (k, p)))
            .collect();
        let kept = all.len();
        all.extend(small.iter().map(|s| (s.layer, &s.polygon)));
        Self { all, kept }
    }
    fn len(&self) -> usize {
        self.all.len()
    }
    fn layer(&self, i: usize) -> usize {
        self.all[i].0
    }
    fn polygon(&self, i: usize) -> &Polygon {
        self.all[i].1
    }
    fn is_small(&self, i: usize) -> bool {
        i >= self.kept
    }
}

/// Every pair of islands of adjacent layers that touch, as node indices (lower first).
fn touching_pairs(nodes: &Nodes<'_>, layer_count: usize) -> Result<Vec<(usize, usize)>, GridError> {
    let mut per_layer: Vec<Vec<usize>> = vec![Vec::new(); layer_count];
    for i in 0..nodes.len() {
        per_layer[nodes.layer(i)].push(i);
    }
    let mut edges = Vec::new();
    for k in 1..layer_count {
        for &a in &per_layer[k - 1] {
            for &b in &per_layer[k] {
                if touch(nodes.polygon(a), nodes.polygon(b))? {
                    edges.push((a.min(b), a.max(b)));
                }
            }
        }
    }
    Ok(edges)
}

/// Whether two islands of adjacent layers overlap by more than [`MIN_OVERLAP`].
fn touch(a: &Polygon, b: &Polygon) -> Result<bool, GridError> {
    if !boxes_meet(a, b) {
        return Ok(false);
    }
    let overlap = boolean::intersection(std::slice::from_ref(a), std::slice::from_ref(b))?;
    Ok(total_area(&overlap) > MIN_OVERLAP)
}

/// `p` grown outwards until it is at least the rule's width and area (see the module docs).
fn enlarge(p: &Polygon, rule: &Rule) -> Result<Vec<Polygon>, GridError> {
    let wide = !matches!(rule.check(p)?, Err(TooSmall::Narrow { .. }));
    let mut r = if wide { 0.0 } else { rule.min_width / 2.0 };
    let mut grown = grow(p, r)?;
    // The area bound is exact for convex shapes and conservative otherwise; a few rounds cover
    // the concave ones whose grown corners merge.
    for _ in 0..4 {
        let area = total_area(&grown);
        if area >= rule.min_area {
            break;
        }
        let length: f64 = grown.iter().map(|g| perimeter(&g.outer)).sum();
        let need = rule.min_area - area;
        let pi = std::f64::consts::PI;
        r += (-length + (length * length + 4.0 * pi * need).sqrt()) / (2.0 * pi) + 1e-3;
        grown = grow(p, r)?;
    }
    Ok(grown)
}

fn grow(p: &Polygon, r: f64) -> Result<Vec<Polygon>, GridError> {
    if r <= 0.0 {
        return Ok(vec![p.clone()]);
    }
    offset::offset(std::slice::from_ref(p), r)
}

/// Adds `grown` to a layer's islands, united with those it overlaps, keeping the layer's order
/// (by the lowest corner of the bounds, x then y).
fn merge_into(layer: &mut Vec<Polygon>, grown: Vec<Polygon>) -> Result<(), GridError> {
    let (mut touching, rest): (Vec<Polygon>, Vec<Polygon>) = std::mem::take(layer)
        .into_iter()
        .partition(|q| grown.iter().any(|g| boxes_meet(g, q)));
    touching.extend(grown);
    let mut merged = boolean::union_all(&touching)?;
    for m in &mut merged {
        m.normalize_orientation();
    }
    *layer = rest;
    layer.extend(merged);
    layer.sort_by(|a, b| {
        let (pa, pb): (DVec2, DVec2) = (a.bounds().0, b.bounds().0);
        pa.x.total_cmp(&pb.x).then(pa.y.total_cmp(&pb.y))
    });
    Ok(())
}

#[cfg(test)]
mod tests {
    use platener_geom::polygon::rect;

    use super::*;

    fn square(c: f64, half: f64) -> Polygon {
        let mut p = Polygon::new(rect(c - half, c - half, c + half, c + half));
        p.normalize_orientation();
        p
    }

    fn small(layer: usize, polygon: Polygon) -> Small {
        Small { layer, polygon }
    }

    #[test]
    fn a_neck_between_two_layers_is_kept_and_grown_to_the_minimum_area() {
        // The rule at 0.75 mm sheets: 1.5 mm wide, 25 mm² as floors.
        let s = Rule::for_sheet(0.75, 1.5, 25.0);
        let mut layers = vec![vec![square(0.0, 20.0)], Vec::new(), vec![square(0.0, 20.0)]];
        let neck = square(0.0, 1.5); // 9 mm², under the 25 mm² minimum
        let (kept, chosen) = keep_supporting(&mut layers, &[small(1, neck.clone())], &s).expect("grid");
        assert_eq!(chosen, vec![true]);
        assert_eq!(kept.len(), 1);
        assert!((kept[0].area - 9.0).abs() < 1e-6, "{kept:?}");
        assert_eq!(layers[1].len(), 1);
        let grown = &layers[1][0];
        // Grown just enough: a 3 mm square grown by r has area 9 + 12r + πr² = 25 at r ≈ 1.06;
        // the offset's polygonal corners lie between that and the mitred (3 + 2r)² = 26.1.
        assert!(grown.area() >= 25.0 && grown.area() < 26.2, "{}", grown.area());
        assert!((kept[0].enlarged - grown.area()).abs() < 1e-9);
        let inside = boolean::difference(&[neck], std::slice::from_ref(grown)).expect("grid");
        assert!(total_area(&inside) < 1e-6, "the neck lies inside what is cut");
    }

    #[test]
    fn a_crumb_on_top_holds_nothing_and_stays_dropped() {
        // The rule at 0.75 mm sheets: 1.5 mm wide, 25 mm² as floors.
        let s = Rule::for_sheet(0.75, 1.5, 25.0);
        let mut layers = vec![vec![square(0.0, 20.0)], Vec::new()];
        let (kept, chosen) = keep_supporting(&mut layers, &[small(1, square(0.0, 1.5))], &s).expect("grid");
        assert_eq!(chosen, vec![false]);
        assert!(kept.is_empty());
        assert!(layers[1].is_empty());
    }

    #[test]
    fn a_neck_two_layers_tall_and_too_thin_is_kept_whole() {
        // The rule at 0.75 mm sheets: 1.5 mm wide, 25 mm² as floors.
        let s = Rule::for_sheet(0.75, 1.5, 25.0);
        let mut layers = vec![vec![square(0.0, 20.0)], Vec::new(), Vec::new(), vec![square(0.0, 20.0)]];
        // 1 mm wide and 40 mm² in area: too thin for the 1.5 mm minimum width.
        let mut thin = Polygon::new(rect(-20.0, -0.5, 20.0, 0.5));
        thin.normalize_orientation();
        let smalls = [small(1, thin.clone()), small(2, thin)];
        let (kept, chosen) = keep_supporting(&mut layers, &smalls, &s).expect("grid");
        assert_eq!(chosen, vec![true, true]);
        assert_eq!(kept.len(), 2);
        for (k, layer) in layers.iter().enumerate().skip(1).take(2) {
            assert_eq!(layer.len(), 1);
            let cuttable = offset::offset(layer, -s.min_width / 2.0).expect("grid");
            assert!(!cuttable.is_empty(), "layer {k} is now wide enough to cut");
            // Grown by half the minimum width on every side: 41.5 × 2.5 mm with round corners.
            let (lo, hi) = layer[0].bounds();
            assert!(((hi - lo) - DVec2::new(41.5, 2.5)).length() < 1e-2, "{:?}", hi - lo);
        }
    }

    #[test]
    fn two_necks_between_the_same_layers_keep_only_the_first() {
        // The rule at 0.75 mm sheets: 1.5 mm wide, 25 mm² as floors.
        let s = Rule::for_sheet(0.75, 1.5, 25.0);
        let mut layers = vec![vec![square(0.0, 20.0)], Vec::new(), vec![square(0.0, 20.0)]];
        let smalls = [small(1, square(-10.0, 1.5)), small(1, square(10.0, 1.5))];
        let (kept, chosen) = keep_supporting(&mut layers, &smalls, &s).expect("grid");
        assert_eq!(chosen, vec![true, false]);
        assert_eq!(kept.len(), 1);
    }
}
