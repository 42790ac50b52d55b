//! Left-first fill of one region (a sheet, a strip or a hole) with jagua-rs collision checks.
//!
//! Our placement heuristic, after the bottom-left-fill family (Burke et al. 2006 "A new
//! bottom-left-fill heuristic algorithm for the two-dimensional irregular packing problem"):
//! candidate positions put the part's box against the region's left or top border or against
//! the right or bottom side of a placed part's box; for each orientation the feasible candidate
//! furthest left (then highest) wins and is compacted, sliding left and up by bisection until it
//! touches something. The orientation whose right edge ends furthest left (then whose bottom
//! edge ends highest) is kept. Filling from the left leaves the free material as one strip
//! along the right-hand side of the sheet, which is what "used sheet area" measures.

use std::sync::Arc;

use glam::DVec2;
use jagua_rs::collision_detection::hazards::filter::NoFilter;
use jagua_rs::collision_detection::hazards::{Hazard, HazardEntity};
use jagua_rs::collision_detection::{CDEConfig, CDEngine};
use jagua_rs::geometry::Transformation;
use jagua_rs::geometry::fail_fast::SPSurrogateConfig;
use jagua_rs::geometry::geo_enums::GeoPosition;
use jagua_rs::geometry::geo_traits::TransformableFrom;
use jagua_rs::geometry::primitives::{Rect, SPolygon};
use platener_geom::polygon::bounds_of;

use super::shape::{NestShape, Template, to_spolygon};

/// Gap (mm) added to candidate positions so touching boxes are not counted as colliding: the
/// spacing is already inside the grown shapes, this only keeps the f32 engine off the edge.
pub(crate) const GAP: f64 = 0.005;
/// Bisection stops when the interval is this small, mm.
const SLIDE_TOLERANCE: f64 = 0.05;
/// Rounds of sliding left then up.
const SLIDE_ROUNDS: usize = 3;
/// Right edges closer than this (mm) count as equal when comparing orientations.
const SCORE_TOLERANCE: f64 = 0.5;
/// Two cores must overlap by more than this (mm) to refuse a position without the engine:
/// far above f32 rounding on a sheet, so the engine would find the overlap too.
const CORE_OVERLAP: f64 = 0.05;

/// What a hazard in our collision engine stands for.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub(crate) enum Entity {
    /// Everything outside the region.
    Exterior,
    /// A placed part (its slot in the bin).
    Placed(usize),
}

impl HazardEntity for Entity {
    fn scope(&self) -> GeoPosition {
        match self {
            Entity::Exterior => GeoPosition::Exterior,
            Entity::Placed(_) => GeoPosition::Interior,
        }
    }

    fn is_dynamic(&self) -> bool {
        matches!(self, Entity::Placed(_))
    }
}

/// One placed part in a bin.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Placed {
    /// The caller's key for the part.
    pub key: usize,
    /// Which template (orientation) of its shape.
    pub template: usize,
    /// Where the template's box corner sits, mm.
    pub pos: DVec2,
    /// The far corner of its box, mm.
    pub max: DVec2,
    /// Its pockets (inner corners), mm.
    pub pockets: Vec<DVec2>,
}

/// A region being filled.
pub(crate) struct Bin {
    cde: CDEngine<Entity>,
    lo: DVec2,
    hi: DVec2,
    /// What has been placed, in order.
    pub placed: Vec<Placed>,
    /// Each placed part's core (its template's [`Template::core`], as placed): centre, radius.
    cores: Vec<(DVec2, f64)>,
}

fn engine_config() -> CDEConfig {
    CDEConfig {
        quadtree_depth: 5,
        cd_threshold: 16,
        item_surrogate_config: SPSurrogateConfig::none(),
    }
}

/// Whether two cores (centre, radius, as placed) overlap by more than [`CORE_OVERLAP`]: then
/// the shapes they lie in overlap too, whatever their outlines.
pub(crate) fn cores_overlap((a, r): (DVec2, f64), (b, s): (DVec2, f64)) -> bool {
    let reach = r + s - CORE_OVERLAP;
    reach > 0.0 && a.distance_squared(b) < reach * reach
}

/// A collision engine whose one static hazard is everything outside the polygon `ring`
/// (counter-clockwise, mm), and the ring's box.
pub(crate) fn region_engine(ring: &[DVec2]) -> Option<(CDEngine<Entity>, (DVec2, DVec2))> {
    let outer = to_spolygon(ring)?;
    let (lo, hi) = bounds_of(ring.iter().copied());
    let pad = ((hi - lo).max_element() * 0.01).max(1.0);
    let bbox = Rect::try_new(
        (lo.x - pad) as f32,
        (lo.y - pad) as f32,
        (hi.x + pad) as f32,
        (hi.y + pad) as f32,
    )
    .ok()?
    .inflate_to_square();
    let cde = CDEngine::new(
        bbox,
        vec![Hazard::new(Entity::Exterior, Arc::new(outer))],
        engine_config(),
    );
    Some((cde, (lo, hi)))
}

/// The counter-clockwise rectangle from `lo` to `hi`.
pub(crate) fn rect_ring(lo: DVec2, hi: DVec2) -> [DVec2; 4] {
    [lo, DVec2::new(hi.x, lo.y), hi, DVec2::new(lo.x, hi.y)]
}

impl Bin {
    /// A bin whose free region is the polygon `ring` (counter-clockwise, mm).
    pub fn new(ring: &[DVec2]) -> Option<Self> {
        let (cde, (lo, hi)) = region_engine(ring)?;
        Some(Self {
            cde,
            lo,
            hi,
            placed: Vec::new(),
            cores: Vec::new(),
        })
    }

    /// A rectangular bin from `lo` to `hi`.
    pub fn rect(lo: DVec2, hi: DVec2) -> Option<Self> {
        Self::new(&rect_ring(lo, hi))
    }

    /// The free region's box.
    pub fn bounds(&self) -> (DVec2, DVec2) {
        (self.lo, self.hi)
    }

    /// Whether template `t` may sit at `pos`: inside the region and clear of every placed part.
    #[cfg(test)]
    pub fn is_free(&self, t: &Template, pos: DVec2) -> bool {
        self.feasible(t, pos, &mut t.shape.clone())
    }

    fn feasible(&self, t: &Template, pos: DVec2, scratch: &mut SPolygon) -> bool {
        if pos.x < self.lo.x
            || pos.y < self.lo.y
            || pos.x + t.size.x > self.hi.x - GAP
            || pos.y + t.size.y > self.hi.y - GAP
        {
            return false;
        }
        !self.cores_meet(t, pos) && !self.collides(t, pos, scratch)
    }

    /// Whether template `t` at `pos` has its core overlapping a placed part's core: then the
    /// shapes overlap, whatever their outlines. Most candidates of a left-first fill lie on
    /// placed parts, and this refuses them for a few multiplications each instead of the
    /// engine's walk of every edge through its quadtree (3–4× faster fills, the same layouts).
    fn cores_meet(&self, t: &Template, pos: DVec2) -> bool {
        let core = (pos + t.core.0, t.core.1);
        self.cores.iter().any(|&placed| cores_overlap(core, placed))
    }

    /// The collision engine's answer: whether template `t` at `pos` overlaps a placed part or
    /// leaves the region.
    fn collides(&self, t: &Template, pos: DVec2, scratch: &mut SPolygon) -> bool {
        let moved = Transformation::from_translation((pos.x as f32, pos.y as f32));
        scratch.transform_from(&t.shape, &moved);
        self.cde.detect_poly_collision(scratch, &NoFilter)
    }

    /// Slides `pos` along `dir` (−x or −y) as far as it stays feasible, by bisection.
    fn slide(&self, t: &Template, pos: DVec2, dir: DVec2, scratch: &mut SPolygon) -> DVec2 {
        let room = if dir.x != 0.0 {
            pos.x - self.lo.x
        } else {
            pos.y - self.lo.y
        } - GAP;
        if room <= SLIDE_TOLERANCE {
            return pos;
        }
        if self.feasible(t, pos + dir * room, scratch) {
            return pos + dir * room;
        }
        let (mut ok, mut bad) = (0.0, room);
        while bad - ok > SLIDE_TOLERANCE {
            let mid = 0.5 * (ok + bad);
            if self.feasible(t, pos + dir * mid, scratch) {
                ok = mid;
            } else {
                bad = mid;
            }
        }
        pos + dir * ok
    }

    /// The best feasible position of template `t` whose right edge ends before `bound`.
    fn best_for(&self, t: &Template, bound: f64, scratch: &mut SPolygon) -> Option<DVec2> {
        let mut xs: Vec<f64> = std::iter::once(self.lo.x + GAP)
            .chain(self.placed.iter().map(|p| p.max.x + GAP))
            .filter(|x| x + t.size.x <= self.hi.x - GAP && x + t.size.x < bound)
            .collect();
        let mut ys: Vec<f64> = std::iter::once(self.lo.y + GAP)
            .chain(self.placed.iter().map(|p| p.max.y + GAP))
            .filter(|y| y + t.size.y <= self.hi.y - GAP)
            .collect();
        xs.sort_by(f64::total_cmp);
        xs.dedup();
        ys.sort_by(f64::total_cmp);
        ys.dedup();
        // Box corners anchored at the placed parts' pockets (any of the four corners), merged
        // into the column order of the grid candidates.
        let g = DVec2::splat(GAP);
        let mut anchors: Vec<DVec2> = self
            .placed
            .iter()
            .flat_map(|p| &p.pockets)
            .flat_map(|v| {
                let (sx, sy) = (DVec2::new(t.size.x, 0.0), DVec2::new(0.0, t.size.y));
                [
                    *v + g,
                    *v - t.size - g,
                    *v - sx + DVec2::new(-GAP, GAP),
                    *v - sy + DVec2::new(GAP, -GAP),
                ]
            })
            .filter(|p| p.x + t.size.x < bound)
            .collect();
        anchors.sort_by(|a, b| a.x.total_cmp(&b.x).then(a.y.total_cmp(&b.y)));
        let mut anchors = anchors.into_iter().peekable();
        let mut start = None;
        'columns: for x in xs.into_iter().chain(std::iter::once(f64::INFINITY)) {
            while let Some(a) = anchors.next_if(|a| a.x < x) {
                if self.feasible(t, a, scratch) {
                    start = Some(a);
                    break 'columns;
                }
            }
            if let Some(p) = ys
                .iter()
                .map(|&y| DVec2::new(x, y))
                .find(|p| x.is_finite() && self.feasible(t, *p, scratch))
            {
                start = Some(p);
                break;
            }
        }
        let start = start?;
        let mut pos = start;
        for _ in 0..SLIDE_ROUNDS {
            let before = pos;
            pos = self.slide(t, pos, DVec2::NEG_X, scratch);
            pos = self.slide(t, pos, DVec2::NEG_Y, scratch);
            if pos.distance(before) < SLIDE_TOLERANCE {
                break;
            }
        }
        Some(pos)
    }

    /// Finds the best orientation and position for `shape`; places it under `key` and returns
    /// the placement, or `None` when it fits nowhere.
    pub fn place(&mut self, key: usize, shape: &NestShape) -> Option<Placed> {
        self.place_before(key, shape, f64::INFINITY)
    }

    /// [`Self::place`] with the part's right edge before `limit`.
    pub fn place_before(&mut self, key: usize, shape: &NestShape, limit: f64) -> Option<Placed> {
        let mut best: Option<(f64, f64, usize, DVec2)> = None;
        for (i, t) in shape.templates.iter().enumerate() {
            if t.size.x > self.hi.x - self.lo.x - 2.0 * GAP || t.size.y > self.hi.y - self.lo.y - 2.0 * GAP {
                continue;
            }
            let mut scratch = t.shape.clone();
            let bound = best.map_or(limit, |b| (b.0 + SCORE_TOLERANCE).min(limit));
            let Some(pos) = self.best_for(t, bound, &mut scratch) else {
                continue;
            };
            let (right, bottom) = (pos.x + t.size.x, pos.y + t.size.y);
            let better = match best {
                None => true,
                Some((r, b, _, _)) => right < r - SCORE_TOLERANCE || (right < r + SCORE_TOLERANCE && bottom < b),
            };
            if better {
                best = Some((right, bottom, i, pos));
            }
        }
        let (_, _, template, pos) = best?;
        let t = &shape.templates[template];
        let placed = Placed {
            key,
            template,
            pos,
            max: pos + t.size,
            pockets: t.pockets.iter().map(|p| *p + pos).collect(),
        };
        self.put(placed.clone(), shape);
        Some(placed)
    }

    /// Places `placed` (a placement of `shape` found before, in a bin like this) as it is.
    pub fn put(&mut self, placed: Placed, shape: &NestShape) {
        let t = &shape.templates[placed.template];
        let moved = Transformation::from_translation((placed.pos.x as f32, placed.pos.y as f32));
        let mut placed_shape = t.shape.clone();
        placed_shape.transform_from(&t.shape, &moved);
        let slot = self.placed.len();
        self.cores.push((placed.pos + t.core.0, t.core.1));
        self.cde
            .register_hazard(Hazard::new(Entity::Placed(slot), Arc::new(placed_shape)));
        self.placed.push(placed);
    }

    /// The right edge of the rightmost placed box, or the region's left edge when empty.
    pub fn used_right(&self) -> f64 {
        right_edge(&self.placed, self.lo.x)
    }
}

/// The right edge of the rightmost box of `placed`, or `left` when there is none.
pub(crate) fn right_edge(placed: &[Placed], left: f64) -> f64 {
    placed.iter().map(|p| p.max.x).fold(left, f64::max)
}

#[cfg(test)]
pub(crate) mod tests {
    use glam::DVec2;
    use platener_geom::Polygon;
    use proptest::prelude::*;

    use super::Bin;
    use crate::sheets::shape::{NestShape, nest_shape};

    /// A disc of radius `r` (48 sides), an L and a plate with a notch: shapes whose cores are
    /// most of them, a corner of them, and off their middle.
    pub(crate) fn shapes() -> Vec<NestShape> {
        let disc: Vec<DVec2> = (0..48)
            .map(|k| DVec2::from_angle(f64::from(k) * std::f64::consts::TAU / 48.0) * 30.0)
            .collect();
        let l = [
            (0.0, 0.0),
            (80.0, 0.0),
            (80.0, 20.0),
            (20.0, 20.0),
            (20.0, 60.0),
            (0.0, 60.0),
        ];
        let notched = [
            (0.0, 0.0),
            (70.0, 0.0),
            (70.0, 40.0),
            (40.0, 40.0),
            (40.0, 15.0),
            (30.0, 15.0),
            (30.0, 40.0),
            (0.0, 40.0),
        ];
        let ring = |pts: &[(f64, f64)]| pts.iter().map(|&(x, y)| DVec2::new(x, y)).collect::<Vec<_>>();
        [disc, ring(&l), ring(&notched)]
            .into_iter()
            .map(|outer| {
                let p = Polygon::new(outer);
                nest_shape(&p, p.area(), 2.0, false).expect("a shape")
            })
            .collect()
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(256))]
        /// Where the cores of two shapes overlap, the collision engine finds the shapes
        /// overlapping too: refusing such positions early never refuses a free one.
        #[test]
        fn meeting_cores_are_always_a_collision(
            which in 0usize..3,
            turn in 0usize..4,
            x in 0.0f64..260.0,
            y in 0.0f64..160.0,
        ) {
            let shapes = shapes();
            let mut bin = Bin::rect(DVec2::ZERO, DVec2::new(300.0, 200.0)).expect("a bin");
            for (k, s) in shapes.iter().enumerate() {
                bin.place(k, s).expect("room for three");
            }
            let t = &shapes[which].templates[turn % shapes[which].templates.len()];
            let mut scratch = t.shape.clone();
            if bin.cores_meet(t, DVec2::new(x, y)) {
                prop_assert!(bin.collides(t, DVec2::new(x, y), &mut scratch));
            }
        }
    }

    /// The check is not vacuous: a shape dropped onto a placed twin meets its core.
    #[test]
    fn a_shape_on_its_twin_meets_its_core() {
        let shapes = shapes();
        let mut bin = Bin::rect(DVec2::ZERO, DVec2::new(300.0, 200.0)).expect("a bin");
        let placed = bin.place(0, &shapes[0]).expect("room");
        let t = &shapes[0].templates[placed.template];
        let on = placed.pos + DVec2::new(5.0, 5.0);
        assert!(bin.cores_meet(t, on));
        assert!(bin.collides(t, on, &mut t.shape.clone()));
        assert!(!bin.cores_meet(t, placed.max + DVec2::splat(1.0)));
    }
}
