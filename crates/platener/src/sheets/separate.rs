//! Shortening the last sheet by letting parts overlap and pushing them apart again.
//!
//! The left-first fill and its ruin and recreate (`compress`) move one part at a time into a
//! free spot, so a layout whose end is a row of discs never gets shorter: no single disc has a
//! free spot further left. Here the sheet is first made shorter than its parts need (every part
//! past the new end is pushed left onto the others), then the overlaps are removed by moving
//! one overlapping part at a time to where it overlaps least, with the weight of a pair that
//! keeps overlapping raised after each round (guided local search). When no overlap is left,
//! the shorter layout is kept and a shorter one asked for; when the rounds run out, the step
//! shrinks. This is the strip shrinking of sparrow (Gardeyn and Wauters, arXiv 2509.13329) in
//! a small form: the overlap of two parts is measured on the circles that fill each (its
//! poles), while the collision test itself stays exact (jagua-rs's engine), so a kept layout
//! has no overlap.
//!
//! Work is counted in evaluated positions, never in time, and every random choice comes from
//! the seed: the same parts and settings give the same layout on every machine.

use std::sync::Arc;

use glam::DVec2;
use jagua_rs::collision_detection::CDEngine;
use jagua_rs::collision_detection::hazards::Hazard;
use jagua_rs::collision_detection::hazards::collector::{BasicHazardCollector, HazardCollector};
use jagua_rs::collision_detection::hazards::filter::NoFilter;
use jagua_rs::geometry::Transformation;
use jagua_rs::geometry::geo_traits::TransformableFrom;
use jagua_rs::geometry::primitives::SPolygon;
use platener_geom::polygon::{ring_contains, ring_distance_squared, signed_area};
use platener_geom::rng::SplitMix64;

use super::blf::{Entity, GAP, Placed, cores_overlap, rect_ring, region_engine, right_edge};
use super::shape::{NestShape, Template};
use crate::plan::NestEffort;

/// The first step asked for: this share of the used length.
const FIRST_STEP: f64 = 0.01;
/// Steps never shrink below this, mm.
const MIN_STEP: f64 = 0.25;
/// Rounds of moves for one length before the step shrinks.
const ROUNDS: usize = 150;
/// A length fails when the total overlap has not fallen by this share for `Budget::stall` rounds.
const STALL_GAIN: f64 = 0.01;
/// Random positions tried over the whole sheet per move.
const GLOBAL_SAMPLES: usize = 24;
/// Random positions tried near the part's own per move.
const LOCAL_SAMPLES: usize = 16;
/// Halvings of the step when the best sample is refined by coordinate descent.
const REFINE_HALVINGS: usize = 8;
/// A pair's weight grows by this after each round it still overlaps.
const WEIGHT_GROWTH: f64 = 1.3;
/// Poles per orientation at most: the overlap proxy compares every pole with every other.
const MAX_POLES: usize = 10;
/// Poles stop once they cover this share of a shape.
const POLE_COVER: f32 = 0.85;
/// Grid points per side where poles are looked for.
const POLE_GRID: u32 = 24;

/// Circles as centre (from the template's box corner) and radius, mm.
type Circles = Vec<(DVec2, f64)>;

/// Each shape's poles per orientation, made for the shapes on the sheet only.
struct Poles(Vec<Option<Vec<Circles>>>);

impl Poles {
    fn new(shapes: &[NestShape], placed: &[Placed]) -> Self {
        let mut poles: Vec<Option<Vec<Circles>>> = vec![None; shapes.len()];
        for p in placed {
            if poles[p.key].is_none() {
                poles[p.key] = Some(shapes[p.key].templates.iter().map(template_poles).collect());
            }
        }
        Self(poles)
    }

    fn of(&self, key: usize, template: usize) -> &[(DVec2, f64)] {
        self.0[key].as_ref().map_or(&[], |t| &t[template])
    }
}

/// The circles filling `t`'s shape, largest first, from a grid over its box: each the
/// largest circle around a grid point that stays inside the shape and outside the circles
/// before it. The first is the template's core (its pole of inaccessibility). A grid is
/// coarse where jagua-rs's pole search is exact, and a thousand times cheaper: the circles
/// only measure how deep two shapes overlap, the exact test decides whether they do.
fn template_poles(t: &Template) -> Circles {
    let ring = ring_of(t);
    let cell = t.size / f64::from(POLE_GRID);
    let inside: Vec<(DVec2, f64)> = (0..POLE_GRID * POLE_GRID)
        .map(|k| cell * (DVec2::new(f64::from(k % POLE_GRID), f64::from(k / POLE_GRID)) + 0.5))
        .filter(|&p| ring_contains(&ring, p))
        .map(|p| (p, ring_distance_squared(&ring, p).sqrt()))
        .collect();
    let mut poles = vec![t.core];
    let area = signed_area(&ring).abs();
    let mut covered = std::f64::consts::PI * t.core.1 * t.core.1;
    while poles.len() < MAX_POLES && covered < f64::from(POLE_COVER) * area {
        let room = |&(p, d): &(DVec2, f64)| poles.iter().fold(d, |r, &(c, s)| r.min(p.distance(c) - s));
        let Some(next) = inside.iter().max_by(|a, b| room(a).total_cmp(&room(b))) else {
            break;
        };
        let r = room(next);
        if r < 0.25 * t.core.1 || r <= 0.0 {
            break;
        }
        covered += std::f64::consts::PI * r * r;
        poles.push((next.0, r));
    }
    poles
}

/// The outline of `t`'s shape (grown, turned, from its box corner), mm.
fn ring_of(t: &Template) -> Vec<DVec2> {
    t.shape
        .vertices()
        .iter()
        .map(|p| DVec2::new(f64::from(p.0), f64::from(p.1)))
        .collect()
}

/// How deep two placed shapes reach into each other, from their poles: the sum over pole pairs
/// of how far the circles overlap, times the smaller one's radius, and never less than a small
/// floor (the shapes collide even where no poles meet).
fn overlap(a: &[(DVec2, f64)], at: DVec2, b: &[(DVec2, f64)], bt: DVec2) -> f64 {
    let mut sum = 0.0;
    for &(ca, ra) in a {
        for &(cb, rb) in b {
            let reach = ra + rb - (ca + at).distance(cb + bt);
            if reach > 0.0 {
                sum += reach * ra.min(rb);
            }
        }
    }
    let floor = 0.1 * a.first().map_or(1.0, |p| p.1).min(b.first().map_or(1.0, |p| p.1));
    sum.max(floor)
}

/// How much work shortening the last sheet may take at a `nesting` level.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct Budget {
    /// The best layouts of the part orders that are shortened, each on its own (in parallel).
    pub starts: usize,
    /// Positions evaluated per start, at most.
    pub work: u64,
    /// Failed lengths in a row after which a start gives up.
    pub strikes: u32,
    /// Rounds without the total overlap falling by [`STALL_GAIN`] after which a length fails.
    pub stall: usize,
    /// Ruin and recreate attempts before (`compress`).
    pub attempts: u32,
}

/// The budget for `tries` part orders (the `nesting` level). `fast` shortens nothing. `good`
/// shortens the best layout: 8 ruin and recreate attempts (cheap, and they find the turn of a
/// lone part), then up to 800,000 positions, a length failing after 20 rounds without
/// progress and the search ending after 4 failures in a row, so a plan that cannot get shorter
/// (a box's six plates) costs some 30 ms. `best` shortens the 4 best layouts with 48 attempts,
/// 3 million positions, all 150 rounds per length and 8 failures in a row each, in parallel,
/// and keeps the shortest.
pub(crate) fn budget(tries: u32) -> Budget {
    match NestEffort::of(tries) {
        NestEffort::Fast => Budget {
            starts: 1,
            work: 0,
            strikes: 0,
            stall: 0,
            attempts: 0,
        },
        NestEffort::Good => Budget {
            starts: 1,
            work: 800_000,
            strikes: 4,
            stall: 20,
            attempts: 8,
        },
        NestEffort::Best => Budget {
            starts: 4,
            work: 3_000_000,
            strikes: 8,
            stall: ROUNDS,
            attempts: 48,
        },
    }
}

/// Shortens `placed` (the last sheet, free region `lo..hi`) within `budget`; the shorter
/// placements, or `None` when none was found.
pub(crate) fn shrink(
    shapes: &[NestShape],
    placed: &[Placed],
    (lo, hi): (DVec2, DVec2),
    (budget, seed): (Budget, u64),
    cancelled: &(dyn Fn() -> bool + Sync),
) -> Option<Vec<Placed>> {
    if placed.len() < 2 || budget.work == 0 {
        return None;
    }
    let poles = Poles::new(shapes, placed);
    let mut rng = SplitMix64::new(seed ^ 0x5E9A_4A7E_5E9A_4A7E);
    let mut best = placed.to_vec();
    let mut step = (right_edge(&best, lo.x) - lo.x) * FIRST_STEP;
    let mut left = budget.work;
    let mut improved = false;
    let mut strikes = 0u32;
    while left > 0 && !cancelled() {
        let now = right_edge(&best, lo.x);
        let end = now - step.max(MIN_STEP);
        let Some(mut sep) = Separation::new(shapes, &poles, &best, (lo, DVec2::new(end, hi.y))) else {
            break;
        };
        if sep.separate(budget.stall, &mut left, &mut rng, cancelled) {
            best = sep.items;
            improved = true;
            strikes = 0;
        } else {
            strikes += 1;
            if strikes >= budget.strikes {
                break;
            }
            step = (step * 0.7).max(MIN_STEP);
        }
    }
    improved.then_some(best)
}

/// What one move's evaluations reuse: the moved shape, the collisions found, the parts counted.
struct Scratch {
    shape: SPolygon,
    found: BasicHazardCollector<Entity>,
    counted: Vec<usize>,
}

/// Parts on a sheet that may overlap, and the pairs that do.
struct Separation<'a> {
    shapes: &'a [NestShape],
    poles: &'a Poles,
    cde: CDEngine<Entity>,
    lo: DVec2,
    hi: DVec2,
    items: Vec<Placed>,
    /// `n × n`: whether parts i and j overlap now.
    overlapping: Vec<bool>,
    /// `n × n`: the weight of the pair's overlap (guided local search).
    weights: Vec<f64>,
}

impl<'a> Separation<'a> {
    /// `placed` squeezed into `lo..hi`: parts reaching past it are pushed back inside.
    fn new(shapes: &'a [NestShape], poles: &'a Poles, placed: &[Placed], (lo, hi): (DVec2, DVec2)) -> Option<Self> {
        let (cde, _) = region_engine(&rect_ring(lo, hi))?;
        let n = placed.len();
        let mut sep = Self {
            shapes,
            poles,
            cde,
            lo,
            hi,
            items: Vec::with_capacity(n),
            overlapping: vec![false; n * n],
            weights: vec![1.0; n * n],
        };
        for (i, p) in placed.iter().enumerate() {
            let t = &shapes[p.key].templates[p.template];
            let pos = sep.clamp(t, p.pos)?;
            sep.items.push(at(p.key, p.template, t, pos));
            sep.register(i);
        }
        for i in 0..n {
            let hits = sep.hits(i, sep.items[i].template, sep.items[i].pos, &mut sep.scratch(i), true);
            for j in hits {
                sep.set_overlap(i, j, true);
            }
        }
        Some(sep)
    }

    /// `pos` moved inside the region for template `t`; `None` when `t` is larger than it.
    fn clamp(&self, t: &Template, pos: DVec2) -> Option<DVec2> {
        let (min, max) = (self.lo + DVec2::splat(GAP), self.hi - t.size - DVec2::splat(GAP));
        (max.x >= min.x && max.y >= min.y).then(|| pos.clamp(min, max))
    }

    fn scratch(&self, i: usize) -> SPolygon {
        let p = &self.items[i];
        self.shapes[p.key].templates[p.template].shape.clone()
    }

    fn register(&mut self, i: usize) {
        let p = &self.items[i];
        let t = &self.shapes[p.key].templates[p.template];
        let mut shape = t.shape.clone();
        shape.transform_from(&t.shape, &translation(p.pos));
        self.cde
            .register_hazard(Hazard::new(Entity::Placed(i), Arc::new(shape)));
    }

    fn set_overlap(&mut self, i: usize, j: usize, on: bool) {
        let n = self.items.len();
        self.overlapping[i * n + j] = on;
        self.overlapping[j * n + i] = on;
    }

    /// The parts template `template` of part `i` at `pos` overlaps, in index order (part `i`
    /// itself left out when `registered`). Positions are clamped inside the region, so the
    /// region's border is never among them.
    fn hits(&self, i: usize, template: usize, pos: DVec2, scratch: &mut SPolygon, registered: bool) -> Vec<usize> {
        let t = &self.shapes[self.items[i].key].templates[template];
        scratch.transform_from(&t.shape, &translation(pos));
        let mut found = BasicHazardCollector::new();
        self.cde.collect_poly_collisions(scratch, &NoFilter, &mut found);
        let mut hits: Vec<usize> = found
            .entities()
            .filter_map(|e| match e {
                Entity::Placed(j) if !(registered && *j == i) => Some(*j),
                _ => None,
            })
            .collect();
        hits.sort_unstable();
        hits
    }

    /// The weighted overlap of part `i` as `template` at `pos` with the parts it hits, or any
    /// value from `bound` up once it is clear the position is no better than that. Parts whose
    /// cores meet this one's are counted first without the collision engine (they overlap for
    /// sure, see `blf::Bin::cores_meet`), so most poor positions never reach it.
    fn cost(&self, i: usize, template: usize, pos: DVec2, bound: f64, s: &mut Scratch) -> f64 {
        let n = self.items.len();
        let t = &self.shapes[self.items[i].key].templates[template];
        let mine = self.poles.of(self.items[i].key, template);
        let (core, r) = (pos + t.core.0, t.core.1);
        let (lo, hi) = (pos, pos + t.size);
        let mut sum = 0.0;
        s.counted.clear();
        let add = |j: usize, sum: &mut f64| {
            let q = &self.items[j];
            *sum += self.weights[i * n + j] * overlap(mine, pos, self.poles.of(q.key, q.template), q.pos);
        };
        for (j, q) in self.items.iter().enumerate() {
            if j == i || q.pos.x >= hi.x || q.pos.y >= hi.y || q.max.x <= lo.x || q.max.y <= lo.y {
                continue;
            }
            let (qc, qr) = self.shapes[q.key].templates[q.template].core;
            if cores_overlap((core, r), (qc + q.pos, qr)) {
                add(j, &mut sum);
                s.counted.push(j);
                if sum >= bound {
                    return sum;
                }
            }
        }
        s.shape.transform_from(&t.shape, &translation(pos));
        s.found.clear();
        let counted = &s.counted;
        let _ = self
            .cde
            .collect_poly_collisions_until(&s.shape, &NoFilter, &mut s.found, |e| {
                if let Entity::Placed(j) = e
                    && j != i
                    && !counted.contains(&j)
                {
                    add(j, &mut sum);
                }
                sum >= bound
            });
        sum
    }

    /// Rounds of moves until no part overlaps another (`true`), or until the rounds or the work
    /// run out or `stall` rounds pass without the total overlap falling.
    fn separate(
        &mut self,
        stall: usize,
        work: &mut u64,
        rng: &mut SplitMix64,
        cancelled: &(dyn Fn() -> bool + Sync),
    ) -> bool {
        let n = self.items.len();
        let (mut least, mut since) = (f64::INFINITY, 0);
        for _ in 0..ROUNDS {
            let mut moving: Vec<usize> = (0..n).filter(|&i| self.overlaps_any(i)).collect();
            if moving.is_empty() {
                return true;
            }
            if *work == 0 || cancelled() {
                return false;
            }
            let total = self.total_overlap();
            if total < least * (1.0 - STALL_GAIN) {
                (least, since) = (total, 0);
            } else {
                since += 1;
                if since >= stall {
                    return false;
                }
            }
            for k in (1..moving.len()).rev() {
                moving.swap(k, (rng.next_u64() % (k as u64 + 1)) as usize);
            }
            for i in moving {
                if self.overlaps_any(i) {
                    self.move_part(i, work, rng);
                }
            }
            for i in 0..n {
                for j in 0..n {
                    if self.overlapping[i * n + j] {
                        self.weights[i * n + j] *= WEIGHT_GROWTH;
                    }
                }
            }
        }
        (0..n).all(|i| !self.overlaps_any(i))
    }

    /// The overlap of every overlapping pair, unweighted: what the rounds are to bring to 0.
    fn total_overlap(&self) -> f64 {
        let n = self.items.len();
        let mut sum = 0.0;
        for i in 0..n {
            for j in i + 1..n {
                if self.overlapping[i * n + j] {
                    let (a, b) = (&self.items[i], &self.items[j]);
                    sum += overlap(
                        self.poles.of(a.key, a.template),
                        a.pos,
                        self.poles.of(b.key, b.template),
                        b.pos,
                    );
                }
            }
        }
        sum
    }

    fn overlaps_any(&self, i: usize) -> bool {
        let n = self.items.len();
        self.overlapping[i * n..(i + 1) * n].iter().any(|&o| o)
    }

    /// Moves part `i` to the least weighted overlap found among random positions over the
    /// sheet and near its own, in any of its orientations, refined by coordinate descent.
    fn move_part(&mut self, i: usize, work: &mut u64, rng: &mut SplitMix64) {
        let key = self.items[i].key;
        let mut scratch = Scratch {
            shape: self.scratch(i),
            found: BasicHazardCollector::new(),
            counted: Vec::new(),
        };
        let _ = self.cde.deregister_hazard_by_entity(Entity::Placed(i));
        let templates = &self.shapes[key].templates;
        let (t0, p0) = (self.items[i].template, self.items[i].pos);
        let mut best = (self.cost(i, t0, p0, f64::INFINITY, &mut scratch), t0, p0);
        let mut evaluated = 1u64;
        for s in 0..GLOBAL_SAMPLES + LOCAL_SAMPLES {
            if best.0 == 0.0 {
                break;
            }
            let template = (rng.next_u64() % templates.len() as u64) as usize;
            let t = &templates[template];
            let wanted = if s < GLOBAL_SAMPLES {
                self.lo + (self.hi - self.lo - t.size) * DVec2::new(rng.unit(), rng.unit())
            } else {
                let reach = t.size.max_element() * 0.25;
                p0 + DVec2::new(rng.unit() - 0.5, rng.unit() - 0.5) * 2.0 * reach
            };
            let Some(pos) = self.clamp(t, wanted) else {
                continue;
            };
            let c = self.cost(i, template, pos, best.0, &mut scratch);
            evaluated += 1;
            if c < best.0 {
                best = (c, template, pos);
            }
        }
        let (mut cost, template, mut pos) = best;
        let t = &templates[template];
        let mut step = t.size.max_element() * 0.05;
        for _ in 0..REFINE_HALVINGS {
            if cost == 0.0 {
                break;
            }
            let mut moved = false;
            for d in [DVec2::NEG_X, DVec2::X, DVec2::NEG_Y, DVec2::Y] {
                let Some(q) = self.clamp(t, pos + d * step) else {
                    continue;
                };
                let c = self.cost(i, template, q, cost, &mut scratch);
                evaluated += 1;
                if c < cost {
                    (cost, pos, moved) = (c, q, true);
                    break;
                }
            }
            if !moved {
                step *= 0.5;
            }
        }
        *work = work.saturating_sub(evaluated);
        self.items[i] = at(key, template, t, pos);
        self.register(i);
        let hits = self.hits(i, template, pos, &mut scratch.shape, true);
        for j in 0..self.items.len() {
            if j != i {
                self.set_overlap(i, j, hits.binary_search(&j).is_ok());
            }
        }
    }
}

fn translation(pos: DVec2) -> Transformation {
    Transformation::from_translation((pos.x as f32, pos.y as f32))
}

/// Part `key` placed as template `t` (number `template`) with its box corner at `pos`.
fn at(key: usize, template: usize, t: &Template, pos: DVec2) -> Placed {
    Placed {
        key,
        template,
        pos,
        max: pos + t.size,
        pockets: t.pockets.iter().map(|p| *p + pos).collect(),
    }
}

#[cfg(test)]
mod tests {
    use glam::DVec2;
    use platener_geom::Polygon;
    use platener_geom::polygon::ring_distance_squared;

    use super::*;
    use crate::sheets::search::{first_fit, order};
    use crate::sheets::shape::nest_shape;
    use crate::sheets::tests::assert_free;

    /// A disc of radius `r` with 48 sides.
    fn disc(r: f64) -> Vec<DVec2> {
        (0..48)
            .map(|k| DVec2::from_angle(f64::from(k) * std::f64::consts::TAU / 48.0) * r)
            .collect()
    }

    /// The layers of a sphere (radius 50 mm, 3 mm apart) as discs: the set the left-first fill
    /// packs in columns and leaves ragged at the end.
    fn layers() -> Vec<NestShape> {
        (0..30)
            .map(|k| {
                let z = -45.0 + 3.1 * f64::from(k);
                let p = Polygon::new(disc((50.0f64 * 50.0 - z * z).sqrt().max(8.0)));
                nest_shape(&p, p.area(), 2.0, false).expect("a shape")
            })
            .collect()
    }

    /// The layers filled left-first into a 300 mm high strip: shapes, placements, strip.
    fn strip() -> (Vec<NestShape>, Vec<Placed>, (DVec2, DVec2)) {
        let shapes = layers();
        let items: Vec<usize> = (0..shapes.len()).collect();
        let region = (DVec2::ZERO, DVec2::new(3000.0, 300.0));
        let layout = first_fit(&shapes, &order(&shapes, &items, 0, 0), region.0, region.1, &|| false).expect("fits");
        (shapes, layout.sheets[0].clone(), region)
    }

    /// Shrinking a strip of discs makes it shorter, keeps every disc once, inside the strip
    /// and clear of the others, and gives the same layout for the same seed.
    #[test]
    fn a_shrunk_strip_of_discs_is_shorter_and_free_of_overlaps() {
        let (shapes, placed, region) = strip();
        let before = right_edge(&placed, 0.0);
        let budget = Budget {
            starts: 1,
            work: 60_000,
            strikes: 4,
            stall: 20,
            attempts: 0,
        };
        let after = shrink(&shapes, &placed, region, (budget, 3), &|| false).expect("shorter");
        let right = right_edge(&after, 0.0);
        assert!(right < before - 5.0, "{before} → {right}");
        let mut keys: Vec<usize> = after.iter().map(|p| p.key).collect();
        keys.sort_unstable();
        assert_eq!(keys, (0..shapes.len()).collect::<Vec<_>>(), "every disc once");
        assert_free(&shapes, &after, region);
        let again = shrink(&shapes, &placed, region, (budget, 3), &|| false).expect("shorter");
        assert_eq!(again, after, "the same seed, the same layout");
    }

    /// Nothing to do at `fast`, and a cancelled search stops at once with what it has.
    #[test]
    fn fast_and_cancelled_shrink_nothing() {
        let (shapes, placed, region) = strip();
        assert_eq!(budget(1).work, 0);
        assert!(shrink(&shapes, &placed, region, (budget(1), 3), &|| false).is_none());
        assert!(shrink(&shapes, &placed, region, (budget(8), 3), &|| true).is_none());
    }

    /// The poles of an L lie inside it, apart from each other, the first one its core, and
    /// together cover most of it.
    #[test]
    fn poles_fill_a_shape_without_leaving_it() {
        let shape = &crate::sheets::blf::tests::shapes()[1];
        for t in &shape.templates {
            let ring = ring_of(t);
            let poles = template_poles(t);
            assert_eq!(poles[0], t.core);
            assert!(poles.len() > 2, "an L needs more than its core: {poles:?}");
            for (k, &(c, r)) in poles.iter().enumerate() {
                assert!(ring_contains(&ring, c));
                assert!(
                    ring_distance_squared(&ring, c).sqrt() >= r - 0.05,
                    "pole {k} leaves the shape"
                );
                for &(d, s) in &poles[..k] {
                    assert!(c.distance(d) >= r + s - 0.05, "poles {k} overlap");
                }
            }
            let covered: f64 = poles.iter().map(|p| std::f64::consts::PI * p.1 * p.1).sum();
            assert!(covered > 0.6 * signed_area(&ring).abs(), "{covered}");
        }
    }

    /// The overlap measure grows as two discs are pushed into each other and has a floor
    /// while they touch at all.
    #[test]
    fn overlap_grows_with_depth() {
        let a = [(DVec2::ZERO, 10.0)];
        let depth = |d: f64| overlap(&a, DVec2::ZERO, &a, DVec2::new(20.0 - d, 0.0));
        assert!(depth(0.5) > 0.0 && depth(2.0) > depth(0.5) && depth(8.0) > depth(2.0));
        assert_eq!(depth(-3.0), 1.0, "the floor: a tenth of the smaller core's radius");
    }
}
