//! When layers overlap too little even for a peg: a *boss* on both, so a peg holds them.
//!
//! A thin part that leaves the body at a slant (the teapot's spout, 21.5 mm² of overlap
//! between its foot and the body's layer below, a narrow crescent) has no room for a peg's
//! square and its two walls, and the peg phase leaves it to glue. A maker would add a little
//! material there for a dowel; so does this step. After placement, for every overlapping pair
//! whose islands no shaft group holds together, a square the side of a peg and its walls
//! ([`boss_side`]) is placed where it covers the most of the two islands (so it adds the least
//! material outside the model) and added to both; then the shafts are placed again, and the
//! peg phase finds its room. A boss keeps [`GAP`] from the layers' other islands (the parts
//! beside it do not overlap) and stays within [`MAX_ADDED`] of a square's area outside the two islands; a
//! boss whose pair the shafts still do not hold is taken back (it would only add material).
//!
//! The square is tried at the points of a grid over the overlap farthest inside it, turned
//! to each direction the peg's slot is looked for in (`fit`'s directions: in a square turned
//! otherwise the peg is never found); the first best, in that fixed order, wins, so the
//! result is deterministic.

use glam::DVec2;
use platener_geom::polygon::total_area;
use platener_geom::{GridError, Polygon, boolean, offset};
use serde::Serialize;

use super::Unjoined;
use super::fit::DIRECTIONS;
use super::peg::{IslandGroups, PEG_MIN_WALL};
use super::shafts::{Placed, boxes_meet};

/// Free room kept between a boss and the layer's other islands, mm: they are cut as separate
/// parts, so they only must not overlap (the teapot's spout foot lies under 1 mm from
/// the body's layer beside it).
const GAP: f64 = 0.2;
/// Room beyond the peg and its walls, mm: the grid and the peg's slack fit in it.
const SLACK: f64 = 0.1;
/// Steps of the centre grid across the square's side.
const GRID: f64 = 6.0;
/// The most grid points looked at over one overlap.
const MAX_POINTS: f64 = 4096.0;
/// The centres tried, the farthest inside the overlap.
const CENTRES: usize = 12;
/// The most material a boss may add outside its two islands together, in squares' areas.
const MAX_ADDED: f64 = 1.0;

/// A boss added to two overlapping islands of adjacent layers so a peg holds them.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Boss {
    /// The lower layer's index (0-based).
    pub layer: usize,
    /// The island in the lower layer.
    pub lower: usize,
    /// The island in the layer above.
    pub upper: usize,
    /// Their overlap as sliced, mm².
    pub overlap: f64,
    /// The square's side, mm.
    pub side: f64,
    /// Material added to the two islands together, mm² (outside the model's sections).
    pub added: f64,
    /// The square, in the stack's 2D frame.
    pub square: Polygon,
}

/// The side of a boss for a peg `thickness` thick: the peg, its walls and [`SLACK`].
pub(crate) fn boss_side(thickness: f64) -> f64 {
    thickness + 2.0 * PEG_MIN_WALL + SLACK
}

/// Adds a boss (see the module docs) to both islands of every pair `placed` leaves unheld,
/// bottom up, each pair of groups once; returns the bosses.
pub(crate) fn add_bosses(
    islands: &mut [Vec<Polygon>],
    placed: &Placed,
    thickness: f64,
) -> Result<Vec<Boss>, GridError> {
    let side = boss_side(thickness);
    let mut groups = IslandGroups::of(islands, &placed.shafts);
    let mut out = Vec::new();
    for u in &placed.unjoined {
        if groups.same(u.layer, u.lower, u.upper) {
            continue;
        }
        let below = out
            .iter()
            .rev()
            .find(|x: &&Boss| x.layer + 1 == u.layer && x.upper == u.lower);
        let Some((square, added)) = square_for(islands, placed, u, below, (side, thickness / 2.0))? else {
            continue;
        };
        let boss = Boss {
            layer: u.layer,
            lower: u.lower,
            upper: u.upper,
            overlap: u.overlap,
            side,
            added,
            square,
        };
        apply(islands, &boss)?;
        groups.join(u.layer, u.lower, u.upper);
        out.push(boss);
    }
    Ok(out)
}

/// Adds `boss`'s square to its two islands.
pub(crate) fn apply(islands: &mut [Vec<Polygon>], boss: &Boss) -> Result<(), GridError> {
    for (k, i) in [(boss.layer, boss.lower), (boss.layer + 1, boss.upper)] {
        islands[k][i] = united(&islands[k][i], &boss.square)?;
    }
    Ok(())
}

/// The square for pair `u` and the area it adds: the square of the boss `below` when it suits
/// (one peg then runs through the three layers, a handle's pieces one above the other, where
/// squares side by side would need room for two), else the best one; either only if it adds
/// at most [`MAX_ADDED`] squares and keeps clear of the layers' other islands.
fn square_for(
    islands: &[Vec<Polygon>],
    placed: &Placed,
    u: &Unjoined,
    below: Option<&Boss>,
    (side, half): (f64, f64),
) -> Result<Option<(Polygon, f64)>, GridError> {
    let (a, b) = (&islands[u.layer][u.lower], &islands[u.layer + 1][u.upper]);
    let fits = |(square, added): &(Polygon, f64)| -> Result<bool, GridError> {
        Ok(*added <= MAX_ADDED * side * side && clear_of_others(islands, u.layer, [u.lower, u.upper], square)?)
    };
    if let Some(x) = below {
        let on_b = covered(&x.square, b)?;
        let same = (x.square.clone(), 2.0 * side * side - covered(&x.square, a)? - on_b);
        if on_b > 0.0 && fits(&same)? {
            return Ok(Some(same));
        }
    }
    let slots = slots_in(placed, u.layer, half);
    match best_square(a, b, &slots, side, placed.bridge)? {
        Some(best) if fits(&best)? => Ok(Some(best)),
        _ => Ok(None),
    }
}

/// The slots `placed` cuts into layers `k` and `k + 1`, shafts `2·half` thick.
fn slots_in(placed: &Placed, k: usize, half: f64) -> Vec<Polygon> {
    placed
        .shafts
        .iter()
        .flat_map(|s| {
            s.bands
                .iter()
                .filter(|b| b.layer == k || b.layer == k + 1)
                .map(move |b| s.line.rect(b.from, b.to, half))
        })
        .collect()
}

/// The square of `side` covering the most of `a` and `b` together, and the area it adds to
/// them, centred half a side and `clear` away from `slots` (a peg in the square then keeps
/// `clear` to them); `None` when they do not overlap there.
fn best_square(
    a: &Polygon,
    b: &Polygon,
    slots: &[Polygon],
    side: f64,
    clear: f64,
) -> Result<Option<(Polygon, f64)>, GridError> {
    let mut overlap = boolean::intersection(std::slice::from_ref(a), std::slice::from_ref(b))?;
    if !slots.is_empty() {
        let keep_off = offset::offset(&boolean::union_all(slots)?, side / 2.0 + clear)?;
        overlap = boolean::difference(&overlap, &keep_off)?;
    }
    // A square is its own quarter turn: the slot directions within one quarter.
    let turns: Vec<DVec2> = (0..DIRECTIONS / 2)
        .map(|i| DVec2::from_angle(std::f64::consts::PI * i as f64 / DIRECTIONS as f64))
        .collect();
    let mut best: Option<(Polygon, f64)> = None;
    for centre in centres(&overlap, side) {
        for &d in &turns {
            let square = square_at(centre, d, side);
            let added = 2.0 * side * side - covered(&square, a)? - covered(&square, b)?;
            if best.as_ref().is_none_or(|(_, x)| added.total_cmp(x).is_lt()) {
                best = Some((square, added));
            }
        }
    }
    Ok(best)
}

/// Candidate centres: of the points of a grid `side / GRID` apart (coarser over a large
/// region, at most [`MAX_POINTS`]) inside `region`, the [`CENTRES`] farthest from its
/// boundary, where the overlap is widest; the grid's order breaks ties.
fn centres(region: &[Polygon], side: f64) -> Vec<DVec2> {
    let (lo, hi) = region.iter().map(Polygon::bounds).fold(
        (DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY)),
        |(a, b), (c, d)| (a.min(c), b.max(d)),
    );
    let size = hi - lo;
    let step = (side / GRID).max((size.x * size.y / MAX_POINTS).sqrt());
    let (nx, ny) = ((size.x / step) as usize, (size.y / step) as usize);
    let mut inside: Vec<(f64, DVec2)> = Vec::new();
    for j in 0..=ny {
        for i in 0..=nx {
            let p = lo + DVec2::new((i as f64 + 0.5) * step, (j as f64 + 0.5) * step);
            if let Some(r) = region.iter().find(|r| r.contains(p)) {
                inside.push((r.boundary_distance_squared(p), p));
            }
        }
    }
    inside.sort_by(|a, b| b.0.total_cmp(&a.0));
    inside.into_iter().take(CENTRES).map(|(_, p)| p).collect()
}

/// A square of `side` centred on `centre` with one side along `d`, counter-clockwise.
fn square_at(centre: DVec2, d: DVec2, side: f64) -> Polygon {
    let (u, v) = (d * (side / 2.0), d.perp() * (side / 2.0));
    Polygon::new(vec![centre - u - v, centre + u - v, centre + u + v, centre - u + v])
}

/// The area of `square` inside `island`, mm².
fn covered(square: &Polygon, island: &Polygon) -> Result<f64, GridError> {
    let inside = boolean::intersection(std::slice::from_ref(square), std::slice::from_ref(island))?;
    Ok(total_area(&inside))
}

/// Whether `square` keeps [`GAP`] from the islands of layers `k` and `k + 1` other than
/// `own` (one index per layer).
fn clear_of_others(islands: &[Vec<Polygon>], k: usize, own: [usize; 2], square: &Polygon) -> Result<bool, GridError> {
    let grown = offset::offset(std::slice::from_ref(square), GAP)?;
    for (layer, mine) in [(k, own[0]), (k + 1, own[1])] {
        for (i, other) in islands[layer].iter().enumerate() {
            if i == mine || !grown.iter().any(|g| boxes_meet(g, other)) {
                continue;
            }
            let meet = boolean::intersection(&grown, std::slice::from_ref(other))?;
            if total_area(&meet) > 0.0 {
                return Ok(false);
            }
        }
    }
    Ok(true)
}

/// `island` united with `square` (which overlaps it): one polygon, holes kept.
fn united(island: &Polygon, square: &Polygon) -> Result<Polygon, GridError> {
    let mut merged = boolean::union_all(&[island.clone(), square.clone()])?;
    merged.sort_by(|x, y| y.area().total_cmp(&x.area()));
    let mut one = merged.into_iter().next().unwrap_or_else(|| island.clone());
    one.normalize_orientation();
    Ok(one)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::stacked::peg::tests::rect;

    #[test]
    fn the_square_covers_the_most_of_both_islands() {
        // Two 3 mm wide strips crossing at right angles: a 3×3 overlap. A 5.1 mm square along
        // them adds 2 · 5.1 · 2.1 = 21.4 mm²; turned 45° it adds less, 2 · (5.1² − 2 · (3 · h −
        // 1.5²)) = 17.7 mm² (h, half its diagonal): the best turns.
        let a = rect(0.0, 0.0, 40.0, 3.0);
        let b = rect(10.0, -20.0, 13.0, 20.0);
        let (sq, added) = best_square(&a, &b, &[], 5.1, 1.5).expect("grid").expect("a square");
        let h = 5.1 / 2f64.sqrt();
        let expect = 2.0 * (5.1 * 5.1 - 2.0 * (3.0 * h - 2.25));
        assert!(
            added < 2.0 * 5.1 * 2.1 && (added - expect).abs() < 0.5,
            "{added} against {expect}"
        );
        let edge = sq.outer[1] - sq.outer[0];
        assert!((edge.x.abs() - edge.y.abs()).abs() < 1e-9, "{edge}");
        let inside_both = covered(&sq, &a).expect("grid") + covered(&sq, &b).expect("grid");
        assert!((2.0 * 5.1 * 5.1 - inside_both - added).abs() < 1e-6);
        // Its centre lies in the overlap.
        let c = sq.outer.iter().copied().sum::<DVec2>() / 4.0;
        assert!((10.0..=13.0).contains(&c.x) && (0.0..=3.0).contains(&c.y), "{c}");
        // Disjoint islands: none.
        assert!(
            best_square(&a, &rect(50.0, 0.0, 60.0, 10.0), &[], 5.1, 1.5)
                .expect("grid")
                .is_none()
        );
    }
}
