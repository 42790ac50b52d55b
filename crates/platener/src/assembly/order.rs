//! The order to assemble a plan in, from its geometry alone: plan.json's `assembly`.
//!
//! Assembly by disassembly (as in assembly planning since Homem de Mello and Sanderson's
//! AND/OR graphs, 1990, with the directional blocking of Wilson and Latombe, 1994): from the
//! assembled model, repeatedly take away a part that can leave the others along a straight
//! line ([`super::sweep`]), then read the removals backwards. A part goes in along `d` exactly
//! when it can leave along `−d`. The directions tried for a part are the model's axes and
//! its own frame's axes (normal and in-plane), both ways; nothing else (no rotations, no
//! two-handed sub-assemblies).
//!
//! Among the parts free to leave, the first taken away is, in turn: not the part the model
//! stands on (its base, placed first); of the interlocked method, an A slice (B slices are
//! stood up first, A slices lowered onto them); the highest (the centre of its extent along
//! "up"; of stacked layers their top, a shaft before the layer it ends in, so a shaft goes in
//! once the layers it passes through are placed); the farthest from its group's centre; the
//! highest id (so equal parts are placed by ascending id). "Up" is the model's +z, or a
//! stacked plan's stacking axis. A part that no tested direction frees (truly interlocked)
//! is still taken, the least blocked one along its least blocked direction, and its step is
//! marked `forced`: every part appears exactly once. Parts no joint or glue connects form
//! groups (the separate objects of a plan, numbered as `subassembly` when there are several)
//! assembled one after another, lowest first, each on its own: only parts of its own group
//! are in a part's way (the boxes of a grid of boxes, side by side, would otherwise block each
//! other's walls coming in from far away).

use std::cmp::Reverse;
use std::collections::{BTreeMap, HashMap};

use glam::{DVec2, DVec3};
use platener_geom::polygon::signed_area;

use super::sweep::blocks;
use super::{Solid, UnionFind};
use crate::plan::format::AssemblyStep;
use crate::plan::{JointKind, Method, PartKind, Plan};

/// Heights and distances are compared as integer keys on this grid, mm: parts level within
/// it count as level (a total order, no tolerance inside the comparator).
const KEY_GRID: f64 = 0.1;

/// Parts whose lowest point is within this share of the group's thinnest thickness of the
/// group's lowest point reach the table, and the base is one of them: the next layer of a
/// stack, a thickness up, does not; the corner of a leaning plate poking through the base (by
/// thickness × cos(angle): 1.3 mm of 3 at 65°) does not hide the base.
const BASE_BAND: f64 = 0.9;

/// A stacking axis whose z component is under this lies flat.
const FLAT_AXIS: f64 = 1e-6;

/// Two candidate directions closer than this (1 − cosine) are one.
const SAME_DIRECTION: f64 = 1e-9;

/// The assembly steps of `plan`, one part each, every part once (see the module's notes).
pub fn order(plan: &Plan) -> Vec<AssemblyStep> {
    if plan.parts.is_empty() {
        return Vec::new();
    }
    let solids: Vec<Solid> = plan.parts.iter().map(Solid::from_part).collect();
    let up = up_axis(plan, &solids);
    let pairs = joint_pairs(plan);
    let infos: Vec<Info> = solids.iter().map(|s| Info::of(s, up)).collect();
    let groups = groups(plan, &pairs, &infos);
    let mut keys = vec![Key::default(); solids.len()];
    for group in &groups {
        group_keys(plan, (&solids, &infos), group, (&pairs, up), &mut keys);
    }
    let mut directions = vec![Vec::new(); solids.len()];
    for group in &groups {
        let centre = group_centre(group, &infos);
        for &i in group {
            directions[i] = candidates(up, &solids[i], centre - infos[i].centre);
        }
    }
    let mut world = World::new(&solids, directions);
    let mut removed = Vec::with_capacity(solids.len());
    // Only the parts of the same group are ever in the way: each group is built on its own.
    for (number, group) in groups.iter().enumerate().rev() {
        let subassembly = (groups.len() > 1).then_some(number as u32 + 1);
        let mut left = group.clone();
        left.sort_by_key(|&i| keys[i]);
        while !left.is_empty() {
            let free = (0..left.len()).find_map(|k| world.free(left[k], &left).map(|d| (k, d)));
            let (k, d, forced) = match free {
                Some((k, d)) => (k, d, false),
                None => {
                    let (k, d) = world.least_blocked(&left);
                    (k, d, true)
                }
            };
            removed.push(Removal {
                part: left.remove(k),
                direction: d,
                forced,
                subassembly,
            });
        }
    }
    removed.reverse();
    steps(plan, &pairs, &removed)
}

/// A part taken away, read backwards a step: the part (index), the way it goes in, whether
/// forced, and its group's number when there are several.
struct Removal {
    part: usize,
    direction: DVec3,
    forced: bool,
    subassembly: Option<u32>,
}

/// The steps of the assembly order `placed`: each with the joints and glue it closes.
fn steps(plan: &Plan, pairs: &[Option<[usize; 2]>], placed: &[Removal]) -> Vec<AssemblyStep> {
    let index = part_index(plan);
    let mut done = vec![false; plan.parts.len()];
    placed
        .iter()
        .map(|r| {
            let (i, d) = (r.part, r.direction);
            let joints = (0..pairs.len())
                .filter(|&j| pairs[j].is_some_and(|[a, b]| (a == i && done[b]) || (b == i && done[a])))
                .collect();
            let mut glued: Vec<u32> = plan
                .glued
                .iter()
                .filter_map(|g| {
                    let [a, b] = g.parts.map(|id| index.get(&id).copied());
                    match (a, b) {
                        (Some(a), Some(b)) if a == i && done[b] => Some(plan.parts[b].id),
                        (Some(a), Some(b)) if b == i && done[a] => Some(plan.parts[a].id),
                        _ => None,
                    }
                })
                .collect();
            glued.sort_unstable();
            glued.dedup();
            done[i] = true;
            AssemblyStep {
                parts: vec![plan.parts[i].id],
                direction: d.to_array().map(|c| (c * 1e6).round() / 1e6 + 0.0),
                joints,
                glued,
                forced: r.forced,
                subassembly: r.subassembly,
            }
        })
        .collect()
}

/// Part id → index into `plan.parts`.
fn part_index(plan: &Plan) -> BTreeMap<u32, usize> {
    plan.parts.iter().enumerate().map(|(i, p)| (p.id, i)).collect()
}

/// Each joint's two parts as indices into `plan.parts`, when they are two different parts:
/// a bend joint names the plates a bent part merged (`merged`), so it joins nothing.
fn joint_pairs(plan: &Plan) -> Vec<Option<[usize; 2]>> {
    let index = part_index(plan);
    let mut merged = BTreeMap::new();
    for (i, p) in plan.parts.iter().enumerate() {
        for &m in &p.merged {
            merged.entry(m).or_insert(i);
        }
    }
    plan.joints
        .iter()
        .map(|j| {
            let find = |id: u32| match j.kind {
                JointKind::Bend => merged.get(&id).copied(),
                _ => index.get(&id).or_else(|| merged.get(&id)).copied(),
            };
            match j.parts.map(find) {
                [Some(a), Some(b)] if a != b => Some([a, b]),
                _ => None,
            }
        })
        .collect()
}

/// "Up": +z, or of a stacked plan its stacking axis (the layers' normal), turned to point up,
/// or, when it lies flat, from the lowest-numbered layer towards the highest.
fn up_axis(plan: &Plan, solids: &[Solid]) -> DVec3 {
    if plan.method != Method::Stacked {
        return DVec3::Z;
    }
    let layers: Vec<&Solid> = plan
        .parts
        .iter()
        .zip(solids)
        .filter(|(p, _)| p.kind == PartKind::Layer)
        .map(|(_, s)| s)
        .collect();
    let (Some(first), Some(last)) = (layers.first(), layers.last()) else {
        return DVec3::Z;
    };
    let n = first.frame().n;
    let rising = if n.z.abs() > FLAT_AXIS {
        n.z > 0.0
    } else {
        (last.lo + last.hi - first.lo - first.hi).dot(n) >= 0.0
    };
    if rising { n } else { -n }
}

/// What the order needs to know of a part's place.
struct Info {
    /// Lowest and highest point along "up", mm.
    extent: (f64, f64),
    /// Centre of its model box.
    centre: DVec3,
    /// The part's id.
    id: u32,
}

impl Info {
    fn of(s: &Solid, up: DVec3) -> Self {
        let heights = |piece: &platener_geom::slab::Slab| {
            piece
                .polygon
                .outer
                .iter()
                .flat_map(|q| [0.0, piece.thickness].map(|z| up.dot(piece.frame.to_model(q.extend(z)))))
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), h| (lo.min(h), hi.max(h)))
        };
        let each: Vec<(f64, f64)> = s.pieces.iter().map(heights).collect();
        let extent = each.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), e| {
            (lo.min(e.0), hi.max(e.1))
        });
        Self {
            extent,
            centre: (s.lo + s.hi) / 2.0,
            id: s.id,
        }
    }
}

/// `x` on the key grid.
fn grid(x: f64) -> i64 {
    (x / KEY_GRID).round() as i64
}

/// The groups of parts the joints or glue connect (part indices ascending): the separate
/// objects the maker ends up with, lowest group first (by its lowest point along "up", then
/// its lowest id).
fn groups(plan: &Plan, pairs: &[Option<[usize; 2]>], infos: &[Info]) -> Vec<Vec<usize>> {
    let mut uf = UnionFind::new(plan.parts.len());
    for [a, b] in pairs.iter().flatten() {
        uf.join(*a, *b);
    }
    let index = part_index(plan);
    for g in &plan.glued {
        if let [Some(&a), Some(&b)] = g.parts.map(|id| index.get(&id)) {
            uf.join(a, b);
        }
    }
    let mut by_root: BTreeMap<usize, Vec<usize>> = BTreeMap::new();
    for i in 0..plan.parts.len() {
        by_root.entry(uf.root(i)).or_default().push(i);
    }
    let mut groups: Vec<Vec<usize>> = by_root.into_values().collect();
    groups.sort_by_key(|g| {
        let bottom = g.iter().map(|&i| infos[i].extent.0).fold(f64::INFINITY, f64::min);
        (grid(bottom), g.iter().map(|&i| infos[i].id).min())
    });
    groups
}

/// The centre of a group's parts' boxes.
fn group_centre(group: &[usize], infos: &[Info]) -> DVec3 {
    group.iter().map(|&i| infos[i].centre).sum::<DVec3>() / group.len().max(1) as f64
}

/// A part's removal key: the smallest is taken away first (placed last).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, PartialOrd, Ord)]
struct Key {
    /// 0 for an interlocked plan's A slices (taken away before the B slices), else 1.
    rank: u8,
    /// Whether it is its group's base.
    base: bool,
    /// Its height on the key grid (centre, or of stacked plans its top), highest first.
    height: Reverse<i64>,
    /// 0 for a stacked plan's shafts (out before the layer they end in), else 1.
    shaft: u8,
    /// Its distance from its group's centre on the key grid, farthest first.
    outside: Reverse<i64>,
    /// Its id, highest first.
    id: Reverse<u32>,
}

/// The removal keys of one group's parts (see [`Key`]); the base is, of the parts that reach
/// down to the group's bottom (within [`BASE_BAND`]; of the highest rank), the one with the
/// largest [`footprint`] there, then the lowest id.
fn group_keys(
    plan: &Plan,
    (solids, infos): (&[Solid], &[Info]),
    group: &[usize],
    (pairs, up): (&[Option<[usize; 2]>], DVec3),
    keys: &mut [Key],
) {
    let stacked = plan.method == Method::Stacked;
    let rank = |i: usize| {
        let a_slice = plan.method == Method::Interlocked
            && plan
                .joints
                .iter()
                .zip(pairs)
                .any(|(j, p)| j.kind == JointKind::Halved && p.is_some_and(|[a, _]| a == i));
        u8::from(!a_slice)
    };
    let centre = group_centre(group, infos);
    for &i in group {
        let info = &infos[i];
        let height = if stacked {
            info.extent.1
        } else {
            (info.extent.0 + info.extent.1) / 2.0
        };
        keys[i] = Key {
            rank: rank(i),
            base: false,
            height: Reverse(grid(height)),
            shaft: u8::from(!(stacked && plan.parts[i].kind == PartKind::Shaft)),
            outside: Reverse(grid(info.centre.distance(centre))),
            id: Reverse(info.id),
        };
    }
    let top_rank = group.iter().map(|&i| keys[i].rank).max().unwrap_or(0);
    let bottom = group.iter().map(|&i| infos[i].extent.0).fold(f64::INFINITY, f64::min);
    let thinnest = group.iter().map(|&i| solids[i].thickness).fold(f64::INFINITY, f64::min);
    let table = bottom + BASE_BAND * thinnest;
    let base = group
        .iter()
        .copied()
        .filter(|&i| keys[i].rank == top_rank && infos[i].extent.0 <= table)
        .map(|i| (i, footprint(&solids[i], up, table)))
        .max_by(|(a, fa), (b, fb)| fa.total_cmp(fb).then(infos[*b].id.cmp(&infos[*a].id)))
        .map(|(i, _)| i);
    if let Some(b) = base {
        keys[b].base = true;
    }
}

/// The area a part stands on when the table is at height `below` along `up`: of each piece,
/// the part of its outline whose lower face lies below that height, projected on the table
/// (× |n · up|), mm². A plate lying at the bottom stands on all of it, a tilted or upright one
/// on a strip along its lowest edge at most (nothing at all when upright).
fn footprint(solid: &Solid, up: DVec3, below: f64) -> f64 {
    solid
        .pieces
        .iter()
        .map(|piece| {
            let f = &piece.frame;
            // The lower face's height at the local point q: a · q + c.
            let a = DVec2::new(up.dot(f.u), up.dot(f.v));
            let c = up.dot(f.origin) + (piece.thickness * up.dot(f.n)).min(0.0);
            let rings = std::iter::once(&piece.polygon.outer).chain(&piece.polygon.holes);
            let area: f64 = rings.map(|r| signed_area(&below_line(r, a, below - c))).sum();
            area.max(0.0) * up.dot(f.n).abs()
        })
        .sum()
}

/// The part of `ring` where `a · q ≤ limit` (Sutherland–Hodgman against one line: the signed
/// area is right for any simple ring, convex or not).
fn below_line(ring: &[DVec2], a: DVec2, limit: f64) -> Vec<DVec2> {
    let mut out = Vec::with_capacity(ring.len() + 2);
    for (i, &p) in ring.iter().enumerate() {
        let q = ring[(i + 1) % ring.len()];
        let (dp, dq) = (a.dot(p) - limit, a.dot(q) - limit);
        if dp <= 0.0 {
            out.push(p);
        }
        if (dp <= 0.0) != (dq <= 0.0) {
            out.push(p + (q - p) * (dp / (dp - dq)));
        }
    }
    out
}

/// The directions a part may go in along, in order of preference: down (along −up, then −z),
/// then its normal, the model's x and y, its in-plane axes and z, each first the way towards
/// its group's centre (`inward`); repeated directions once.
fn candidates(up: DVec3, solid: &Solid, inward: DVec3) -> Vec<DVec3> {
    let f = solid.frame();
    let mut out: Vec<DVec3> = vec![-up, -DVec3::Z];
    for e in [f.n, DVec3::X, DVec3::Y, f.u, f.v, DVec3::Z] {
        let e = if e.dot(inward) >= 0.0 { e } else { -e };
        out.extend([e, -e]);
    }
    let mut unique: Vec<DVec3> = Vec::with_capacity(out.len());
    for d in out {
        if !unique.iter().any(|u| u.dot(d) > 1.0 - SAME_DIRECTION) {
            unique.push(d);
        }
    }
    unique
}

/// The parts, their directions and every blocking test made so far.
struct World<'a> {
    solids: &'a [Solid],
    directions: Vec<Vec<DVec3>>,
    /// Whether part `j` blocks part `i` going in along its direction `k`, by `(i, j, k)`.
    blocked: HashMap<(usize, usize, usize), bool>,
}

impl<'a> World<'a> {
    fn new(solids: &'a [Solid], directions: Vec<Vec<DVec3>>) -> Self {
        Self {
            solids,
            directions,
            blocked: HashMap::new(),
        }
    }

    /// Whether part `j` is in the way of part `i` going in along its `k`-th direction.
    fn blocks(&mut self, i: usize, j: usize, k: usize) -> bool {
        let (solids, away) = (self.solids, -self.directions[i][k]);
        *self
            .blocked
            .entry((i, j, k))
            .or_insert_with(|| blocks(&solids[i], away, &solids[j]))
    }

    /// The first direction along which part `i` goes in past the `others`, if any.
    fn free(&mut self, i: usize, others: &[usize]) -> Option<DVec3> {
        (0..self.directions[i].len())
            .find(|&k| others.iter().all(|&j| j == i || !self.blocks(i, j, k)))
            .map(|k| self.directions[i][k])
    }

    /// Of `left` (in order of preference), the part and direction with the fewest others of
    /// `left` in the way: its index in `left` and the direction.
    fn least_blocked(&mut self, left: &[usize]) -> (usize, DVec3) {
        let mut best = (usize::MAX, 0, DVec3::NEG_Z);
        for (n, &i) in left.iter().enumerate() {
            for k in 0..self.directions[i].len() {
                let count = left.iter().filter(|&&j| j != i && self.blocks(i, j, k)).count();
                if count < best.0 {
                    best = (count, n, self.directions[i][k]);
                }
            }
        }
        (best.1, best.2)
    }
}

#[cfg(test)]
#[path = "order_tests.rs"]
mod tests;
