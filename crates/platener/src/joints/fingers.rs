//! Cutting joint regions into fingers, tabs and slots, and applying them to the plates.

use glam::DVec2;
use platener_geom::boolean::{difference, intersection, union_all};
use platener_geom::offset::{closing, offset, opening};
use platener_geom::polygon::total_area;
use platener_geom::tolerance::GRID_NOISE_AREA;
use platener_geom::{GridError, Polygon};

use super::connect::{Region, band};
use super::distinct::{self, KeyFinger, Look, Variant};
use super::{Connection, ConnectionKind, JointSettings, JointStyle, Joints, Key};
use crate::plates::Plate;
use crate::verify::EdgeJoint;

/// Number of segments for a joint `len` long: the odd count nearest to `len / width`, never
/// narrower than `min_feature`, and at least three (a tab between two fingers) when there is room.
pub(super) fn segment_count(len: f64, width: f64, min_feature: f64) -> usize {
    let mut n = ((len / width).round() as usize).max(1);
    if n.is_multiple_of(2) {
        n = if len / (n + 1) as f64 >= min_feature {
            n + 1
        } else {
            n - 1
        };
    }
    while n > 1 && len / (n as f64) < min_feature {
        n -= 2;
    }
    if n == 1 && len / 3.0 >= min_feature {
        n = 3;
    }
    n
}

/// The jointed edge of `plate` along `region`: the region's boundary line nearest the plate's
/// own middle, over the region's length.
fn edge_of(plate: &Plate, region: &Polygon, axis: glam::DVec3) -> [DVec2; 2] {
    let f = &plate.frame;
    let along = DVec2::new(axis.dot(f.u), axis.dot(f.v)).normalize_or_zero();
    let across = along.perp();
    let (mut a0, mut a1, mut q0, mut q1) = (f64::INFINITY, f64::NEG_INFINITY, f64::INFINITY, f64::NEG_INFINITY);
    for p in &region.outer {
        a0 = a0.min(along.dot(*p));
        a1 = a1.max(along.dot(*p));
        q0 = q0.min(across.dot(*p));
        q1 = q1.max(across.dot(*p));
    }
    let (lo, hi) = plate.polygon.bounds();
    let mid = across.dot((lo + hi) / 2.0);
    let q = if (mid - q0).abs() < (mid - q1).abs() { q0 } else { q1 };
    [along * a0 + across * q, along * a1 + across * q]
}

/// The barb of a JimJoint finger on `plate`: the finger between `s0` and `s1` along the axis,
/// widened by `barb` on both sides towards its tip (the side of the region away from the
/// plate), clipped to the joint region.
fn barb(
    plate: &Plate,
    region: &Polygon,
    axis: glam::DVec3,
    s0: f64,
    s1: f64,
    barb: f64,
) -> Result<Vec<Polygon>, GridError> {
    let f = &plate.frame;
    let along = DVec2::new(axis.dot(f.u), axis.dot(f.v)).normalize_or_zero();
    let across = along.perp();
    let c = axis.dot(f.origin);
    let [base0, _] = edge_of(plate, region, axis);
    let q_base = across.dot(base0);
    let (q0, q1) = region
        .outer
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), p| {
            (lo.min(across.dot(*p)), hi.max(across.dot(*p)))
        });
    let q_tip = if (q_base - q0).abs() < (q_base - q1).abs() {
        q1
    } else {
        q0
    };
    let at = |a: f64, q: f64| along * (a - c) + across * q;
    let mut wedge = Polygon::new(vec![
        at(s0, q_base),
        at(s1, q_base),
        at(s1 + barb, q_tip),
        at(s0 - barb, q_tip),
    ]);
    wedge.normalize_orientation();
    platener_geom::boolean::intersection(std::slice::from_ref(region), &[wedge])
}

/// Gaps narrower than this (mm) between a plate and its joint regions are grid noise.
pub(super) const HAIRLINE: f64 = 0.01;

/// The union of a plate and its joint regions. A region computed through another plate's
/// frame can miss its plate by a grid step; a closing (with sharp miter corners) fills such
/// hairlines without moving any real edge.
fn joined(pieces: &[Polygon]) -> Result<Vec<Polygon>, GridError> {
    let union = union_all(pieces)?;
    if union.len() <= 1 {
        return Ok(union);
    }
    closing(&union, HAIRLINE)
}

/// How one connection is cut.
#[derive(Debug, Clone, Copy, PartialEq)]
struct FingerLayout {
    /// Fingers of both plates (2 for a halved joint).
    segments: usize,
    /// The joint's shorter fingers ([`Region::short`]), because the full ones would cut a
    /// plate apart.
    short: bool,
    /// When fingers would cut a plate apart: that plate keeps the whole joint region and the
    /// other butts against it.
    keeper: Option<usize>,
    /// At a corner, plate b owns the first segment (a does otherwise): with two segments, a
    /// lap, the plate that would be cut apart keeps the end it needs.
    b_first: bool,
    /// A wider finger that tells the joint apart from look-alikes ([`super::distinct`]).
    key: Option<KeyFinger>,
}

impl FingerLayout {
    /// Full fingers, `segments` of them, owned in turn from plate a.
    fn of(segments: usize) -> Self {
        Self {
            segments,
            short: false,
            keeper: None,
            b_first: false,
            key: None,
        }
    }
}

/// What a connection takes from and adds to its two plates (`[a, b]`).
#[derive(Debug, Clone, Default)]
struct Cut {
    remove: [Vec<Polygon>; 2],
    add: [Vec<Polygon>; 2],
    /// Dovetail keys, in the dovetailed plate's frame.
    keys: Vec<Polygon>,
}

/// A dovetail's shape: how far each flank spreads towards the tip, and how wide the key
/// beside it stays at the tip (a key must not end in a point a laser cannot cut).
struct Dovetail {
    spread: f64,
    key: f64,
}

impl Dovetail {
    /// Flanks at 1:4 over the notched plate's thickness; keys at least the smallest feature.
    fn new(plates: &[Plate], r: &Region) -> Self {
        let t = plates[r.a].thickness.max(plates[r.b].thickness);
        let notched = if dovetailed(r) == r.a { r.b } else { r.a };
        Self {
            spread: plates[notched].thickness / 4.0,
            key: min_feature(t),
        }
    }

    /// The narrowest segment that leaves the notched plate a finger of `min_feature` between
    /// two dovetails with their keys.
    fn min_segment(&self, min_feature: f64) -> f64 {
        2.0 * (self.spread + self.key) + min_feature
    }
}

/// The plate that gets the dovetails: the one owning the inner segments (the second plate at
/// a corner, the ending plate's tabs at a T).
fn dovetailed(r: &Region) -> usize {
    match (r.kind, r.through) {
        (ConnectionKind::Tee, Some(through)) if through == r.b => r.a,
        _ => r.b,
    }
}

/// The smallest feature a laser cuts reliably in plates up to `t` thick: half the thickness,
/// at least 1 mm (the rule).
fn min_feature(t: f64) -> f64 {
    (t / 2.0).max(1.0)
}

/// The plan of a connection before any plate is found to fall apart.
fn first_plan(plates: &[Plate], r: &Region, settings: &JointSettings, style: JointStyle) -> FingerLayout {
    if let Some(j) = &r.junction {
        // One row of fingers for the whole line, the same for each of its connections.
        let t = j.plates.iter().map(|&p| plates[p].thickness).fold(0.0, f64::max);
        let (len, narrowest) = (j.range.1 - j.range.0, min_feature(t));
        let mut segments = segment_count(len, settings.finger_factor * t, narrowest);
        if segments < j.plates.len() && len / j.plates.len() as f64 >= narrowest {
            segments = j.plates.len();
        }
        return FingerLayout::of(segments);
    }
    let (narrowest, target) = widths(plates, r, settings, style);
    let segments = match r.kind {
        ConnectionKind::Cross => 2,
        _ => segment_count(r.range.1 - r.range.0, target, narrowest),
    };
    FingerLayout::of(segments)
}

/// The narrowest segment a connection (not on a junction) may have, and the finger width
/// the settings ask for.
fn widths(plates: &[Plate], r: &Region, settings: &JointSettings, style: JointStyle) -> (f64, f64) {
    let t = plates[r.a].thickness.max(plates[r.b].thickness);
    let narrowest = match style {
        JointStyle::Dovetail => Dovetail::new(plates, r).min_segment(min_feature(t)),
        _ => min_feature(t),
    };
    (narrowest, settings.finger_factor * t)
}

/// The plate that owns segment `s` of connection `r` under `plan` (the other gives it up).
fn segment_owner(r: &Region, plan: FingerLayout, s: usize) -> usize {
    match (&r.junction, r.kind) {
        (Some(j), _) => j.owner(s, r.a, r.b),
        (None, ConnectionKind::Corner) => [r.a, r.b][(s + plan.b_first as usize) % 2],
        (None, ConnectionKind::Tee) => {
            let through = r.through.unwrap_or(r.a);
            let ending = if through == r.a { r.b } else { r.a };
            [through, ending][s % 2]
        }
        (None, ConnectionKind::Cross) => {
            let low = r.slot_low.unwrap_or(r.b);
            let high = if low == r.a { r.b } else { r.a };
            [high, low][s.min(1)]
        }
    }
}

/// The fingers, tabs and slots of one connection under `plan`.
fn cut(plates: &[Plate], r: &Region, plan: FingerLayout, style: JointStyle) -> Result<Cut, GridError> {
    let (pa, pb) = (&plates[r.a], &plates[r.b]);
    let mut out = Cut::default();
    if let Some(keeper) = plan.keeper {
        // A butt joint: the other plate gives up the whole region.
        let everything = (r.range.0 - 1e3, r.range.1 + 1e3);
        out.remove = if keeper == r.a {
            [Vec::new(), band(pb, &r.in_b, r.axis, everything.0, everything.1)?]
        } else {
            [band(pa, &r.in_a, r.axis, everything.0, everything.1)?, Vec::new()]
        };
        return Ok(out);
    }
    let segments = plan.segments;
    // On a junction the fingers are the line's and plain: barbs and dovetail keys would reach
    // into the third plate.
    let (axis, range, style) = match &r.junction {
        Some(j) => (j.axis, j.range, JointStyle::Finger),
        None => (r.axis, r.range, style),
    };
    let step = (range.1 - range.0) / segments as f64;
    let bounds = distinct::boundaries(range, segments, plan.key);
    let dovetail = (style == JointStyle::Dovetail && r.kind != ConnectionKind::Cross).then(|| Dovetail::new(plates, r));
    let male = dovetailed(r);
    for s in 0..segments {
        let owner = segment_owner(r, plan, s);
        let (a0, a1) = (bounds[s], bounds[s + 1]);
        // The first and last segments reach past the range (the region's ends).
        let s0 = if s == 0 { a0 - 1e3 } else { a0 };
        let s1 = if s + 1 == segments { a1 + 1e3 } else { a1 };
        // A dovetail's partner gives up room for its tip and both keys.
        let room = match &dovetail {
            Some(d) if owner == male => d.spread + d.key,
            _ => 0.0,
        };
        if owner == r.a {
            out.remove[1].extend(band(pb, &r.in_b, axis, s0 - room, s1 + room)?);
        } else {
            out.remove[0].extend(band(pa, &r.in_a, axis, s0 - room, s1 + room)?);
        }
        if let Some(d) = dovetail.as_ref().filter(|_| owner == male) {
            let (p, region, side) = if male == r.a {
                (pa, &r.in_a, 0)
            } else {
                (pb, &r.in_b, 1)
            };
            let tail = barb(p, region, r.axis, a0, a1, d.spread)?;
            let mut solid = band(p, region, r.axis, a0, a1)?;
            solid.extend(tail.iter().cloned());
            out.keys
                .extend(difference(&band(p, region, r.axis, a0 - room, a1 + room)?, &solid)?);
            out.add[side].extend(tail);
        }
        // JimJoint: the owner's finger widens towards its tip, into its partner's fingers.
        if style == JointStyle::Jim && r.kind != ConnectionKind::Cross {
            let (p, region, side) = if owner == r.a {
                (pa, &r.in_a, 0)
            } else {
                (pb, &r.in_b, 1)
            };
            let b = (0.1 * step).min(0.25 * pa.thickness.min(pb.thickness));
            out.add[side].extend(barb(p, region, r.axis, a0, a1, b)?);
        }
    }
    Ok(out)
}

/// A plate's final pieces, largest first: its grown `outline` without `remove`, with `add`,
/// and without slivers narrower than `min_feature` where the joints changed it (a laser
/// cannot cut them; they come from joints of plates that meet slightly off square).
fn finish(
    plate: &Plate,
    outline: &[Polygon],
    remove: &[Polygon],
    add: &[Polygon],
    min_feature: f64,
) -> Result<Vec<Polygon>, GridError> {
    let mut pieces = difference(outline, remove)?;
    if !add.is_empty() {
        pieces.extend(add.iter().cloned());
        pieces = union_all(&pieces)?;
    }
    // Regions computed through different frames leave hairlines where their edges should
    // meet (a spike of zero width along a plate's edge beside a notch): gone.
    pieces = opening(&pieces, HAIRLINE)?;
    // …and hairline holes where a joint region fills a notch the other plate left in the
    // plate's faces (a crossing over part of its height) a few µm off its sides.
    for p in &mut pieces {
        p.holes.retain(|h| {
            let mut hole = Polygon::new(h.clone());
            hole.normalize_orientation();
            !opening(&[hole], HAIRLINE).is_ok_and(|o| o.is_empty())
        });
    }
    let r = 0.499 * min_feature;
    let opened = intersection(&opening(&pieces, r)?, &pieces)?;
    let mut slivers = difference(&pieces, &opened)?;
    slivers.retain(|p| p.area() > GRID_NOISE_AREA);
    if !slivers.is_empty() {
        // Only where the joints changed the plate: its growth and what its partners took.
        let mut changed = difference(outline, std::slice::from_ref(&plate.polygon))?;
        changed.extend(remove.iter().cloned());
        let zone = offset(&changed, 2.0 * r)?;
        pieces = difference(&pieces, &intersection(&slivers, &zone)?)?;
    }
    pieces = of_plate(plate, pieces)?;
    // Debris: pieces with nothing a laser could cut (the sliver's rim left by the grid).
    let mut kept = Vec::with_capacity(pieces.len());
    for (n, p) in pieces.into_iter().enumerate() {
        if n == 0 || total_area(&opening(std::slice::from_ref(&p), r)?) > GRID_NOISE_AREA {
            kept.push(p);
        }
    }
    Ok(kept)
}

/// The pieces of `plate`'s outline that hold some of the plate, largest first. A finger cut
/// off at a corner by the notch of the other edge lies wholly outside the plate: it is
/// dropped (the plate itself is whole; its partner's notch stays empty).
pub(super) fn of_plate(plate: &Plate, mut pieces: Vec<Polygon>) -> Result<Vec<Polygon>, GridError> {
    if pieces.len() > 1 {
        let mut kept = Vec::with_capacity(pieces.len());
        for p in pieces {
            let inside = total_area(&intersection(
                std::slice::from_ref(&p),
                std::slice::from_ref(&plate.polygon),
            )?);
            kept.push((inside, p));
        }
        // The piece with most of the plate stays whatever happens (a stable sort: ties keep
        // their order).
        kept.sort_by(|a, b| b.0.total_cmp(&a.0));
        pieces = kept
            .into_iter()
            .enumerate()
            .filter(|(k, (inside, _))| *k == 0 || *inside > GRID_NOISE_AREA)
            .map(|(_, (_, p))| p)
            .collect();
    }
    pieces.sort_by(|a, b| b.area().total_cmp(&a.area()));
    Ok(pieces)
}

/// The widest corner at which a butt joint is left as it is: past it a lap is tried first.
const BUTT_MAX_DEG: f64 = 135.0;

/// What a plate in `pieces` (largest first) loses: how many pieces fall off, and their area
/// (compared in that order, areas to a hundredth of a mm²).
fn loss(pieces: &[Polygon]) -> (usize, i64) {
    let dropped: f64 = pieces.iter().skip(1).map(Polygon::area).sum();
    (pieces.len().saturating_sub(1), (dropped * 100.0).round() as i64)
}

/// Everything its connections (`touching`: connection, side) take from and add to a plate.
fn gathered(cuts: &[Cut], touching: &[(usize, usize)]) -> (Vec<Polygon>, Vec<Polygon>) {
    let (mut remove, mut add) = (Vec::new(), Vec::new());
    for &(k, side) in touching {
        remove.extend(cuts[k].remove[side].iter().cloned());
        add.extend(cuts[k].add[side].iter().cloned());
    }
    (remove, add)
}

/// The joint `r` as `plan` cuts it: with its shorter fingers if the plan says so.
fn variant(r: &Region, plan: FingerLayout) -> Region {
    match (plan.short, r.shortened()) {
        (true, Some(short)) => short,
        _ => r.clone(),
    }
}

/// A plate's outline grown into its joint regions (`touching`: connection, side), each as
/// its current variant in `used`.
fn outline(plate: &Plate, used: &[Region], touching: &[(usize, usize)]) -> Result<Vec<Polygon>, GridError> {
    let mut grown = vec![plate.polygon.clone()];
    for &(k, side) in touching {
        grown.extend(
            if side == 0 { &used[k].reach_a } else { &used[k].reach_b }
                .iter()
                .cloned(),
        );
    }
    joined(&grown)
}

/// Cuts every joint `regions` names into its two plates: fingers, tabs and slots, adapted
/// where they would cut a plate apart, then the claims settled and the joints labelled.
pub(super) fn apply(
    plates: &[Plate],
    regions: Vec<Region>,
    settings: &JointSettings,
    style: JointStyle,
) -> Result<(Joints, Vec<String>), GridError> {
    let mut cutting = Cutting::new(plates, regions, settings, style)?;
    cutting.shorten_where_split()?;
    cutting.adapt()?;
    cutting.tell_apart()?;
    cutting.into_joints()
}

/// A jointed edge of a plate (a segment in its frame) and the joint's label.
type LabelledEdge = (u32, [DVec2; 2]);

/// The joints of all plates being cut: what each connection's plan is so far, and what each
/// plate looks like under them. Plates and joints depend on each other (a plate's pieces
/// depend on all its joints, a joint adapts to keep a plate whole), so the phases share this
/// state instead of passing a dozen vectors around.
struct Cutting<'a> {
    plates: &'a [Plate],
    regions: Vec<Region>,
    settings: &'a JointSettings,
    style: JointStyle,
    /// Per plate: its connections and its side (0 = a, 1 = b) in each.
    touching: Vec<Vec<(usize, usize)>>,
    /// Each joint as its current variant (shorter fingers or not).
    used: Vec<Region>,
    /// Each plate grown into its joint regions (each joint as its current variant).
    outlines: Vec<Vec<Polygon>>,
    /// How each connection is cut now.
    plans: Vec<FingerLayout>,
    /// What each connection takes from and adds to its plates under its plan.
    cuts: Vec<Cut>,
    /// The plate each connection last adapted for, if it did.
    adapted_for: Vec<Option<usize>>,
    /// Each plate's pieces, kept until an adaptation changes one of its connections.
    finished: Vec<Option<Vec<Polygon>>>,
}

impl<'a> Cutting<'a> {
    /// Every plate grown into its joint regions, and every joint cut by its first plan: the
    /// plates grow first, so that each then gives up the segments its partners own.
    fn new(
        plates: &'a [Plate],
        regions: Vec<Region>,
        settings: &'a JointSettings,
        style: JointStyle,
    ) -> Result<Self, GridError> {
        let mut touching: Vec<Vec<(usize, usize)>> = vec![Vec::new(); plates.len()];
        for (k, r) in regions.iter().enumerate() {
            touching[r.a].push((k, 0));
            touching[r.b].push((k, 1));
        }
        let used: Vec<Region> = regions.clone();
        let outlines: Vec<Vec<Polygon>> = plates
            .iter()
            .zip(&touching)
            .map(|(p, mine)| outline(p, &used, mine))
            .collect::<Result<_, _>>()?;
        let plans: Vec<FingerLayout> = regions.iter().map(|r| first_plan(plates, r, settings, style)).collect();
        let cuts: Vec<Cut> = regions
            .iter()
            .zip(&plans)
            .map(|(r, &plan)| cut(plates, r, plan, style))
            .collect::<Result<_, _>>()?;
        Ok(Self {
            plates,
            adapted_for: vec![None; regions.len()],
            finished: vec![None; plates.len()],
            regions,
            settings,
            style,
            touching,
            used,
            outlines,
            plans,
            cuts,
        })
    }

    /// Plate `i`'s pieces, largest first, under the joints' current cuts.
    fn whole(&self, i: usize) -> Result<Vec<Polygon>, GridError> {
        let (remove, add) = gathered(&self.cuts, &self.touching[i]);
        finish(
            &self.plates[i],
            &self.outlines[i],
            &remove,
            &add,
            min_feature(self.plates[i].thickness),
        )
    }

    /// Plate `i`'s pieces: kept from before if nothing changed them since, else anew.
    fn pieces(&mut self, i: usize) -> Result<Vec<Polygon>, GridError> {
        self.finished[i].take().map_or_else(|| self.whole(i), Ok)
    }

    /// Shorter fingers first, on every joint of a plate the full ones cut apart, all at
    /// once: on a low-poly model a facet falls apart under several neighbours' fingers
    /// together, and no one joint mends it alone. Shorter fingers can split a neighbour in
    /// turn, so again (three rounds at most).
    fn shorten_where_split(&mut self) -> Result<(), GridError> {
        for _ in 0..3 {
            let shortened = self.joints_of_split_plates()?;
            if shortened.is_empty() {
                break;
            }
            self.shorten(&shortened)?;
        }
        Ok(())
    }

    /// The joints (connection, the plate it shortens for) that have shorter fingers not yet
    /// used and belong to a plate that falls apart; every plate's pieces are kept.
    fn joints_of_split_plates(&mut self) -> Result<Vec<(usize, usize)>, GridError> {
        let mut shortened: Vec<(usize, usize)> = Vec::new();
        for i in 0..self.plates.len() {
            let pieces = self.pieces(i)?;
            if pieces.len() > 1 {
                for &(k, _) in &self.touching[i] {
                    if self.regions[k].short.is_some()
                        && !self.plans[k].short
                        && !shortened.iter().any(|&(q, _)| q == k)
                    {
                        shortened.push((k, i));
                    }
                }
            }
            self.finished[i] = Some(pieces);
        }
        Ok(shortened)
    }

    /// Switches the joints `shortened` to their shorter fingers, and regrows the plates they
    /// touch.
    fn shorten(&mut self, shortened: &[(usize, usize)]) -> Result<(), GridError> {
        for &(k, i) in shortened {
            self.plans[k].short = true;
            self.used[k] = variant(&self.regions[k], self.plans[k]);
            self.cuts[k] = cut(self.plates, &self.used[k], self.plans[k], self.style)?;
            self.adapted_for[k] = Some(i);
            for p in [self.regions[k].a, self.regions[k].b] {
                self.finished[p] = None;
            }
        }
        for p in 0..self.plates.len() {
            if self.finished[p].is_none() {
                self.outlines[p] = outline(&self.plates[p], &self.used, &self.touching[p])?;
            }
        }
        Ok(())
    }

    /// Plate by plate, each connection that cuts it, in order, adapts until the plate holds
    /// together: shorter fingers, then fewer, wider ones, a lap, else the plate keeps the
    /// whole joint region.
    fn adapt(&mut self) -> Result<(), GridError> {
        for i in 0..self.plates.len() {
            let mut pieces = self.pieces(i)?;
            for (k, side) in self.touching[i].clone() {
                if pieces.len() <= 1 {
                    break;
                }
                if self.cuts[k].remove[side].is_empty() || self.plans[k].keeper.is_some() {
                    continue;
                }
                pieces = self.adapt_joint(i, k, pieces)?;
            }
            self.finished[i] = Some(pieces);
        }
        Ok(())
    }

    /// What joint `k` may become for plate `i`, in the order tried (all from its plan before
    /// the first try): shorter fingers, three wider ones, a lap either way round, and plate
    /// `i` keeping the whole region.
    fn candidates(&self, i: usize, k: usize) -> [Option<FingerLayout>; 5] {
        let (r, now) = (&self.regions[k], self.plans[k]);
        // A junction's row of fingers is shared by its connections: it cannot widen for one.
        let wider = now.segments > 3 && r.kind != ConnectionKind::Cross && r.junction.is_none();
        let shorter = (r.short.is_some() && !now.short).then_some(FingerLayout { short: true, ..now });
        let fewer = wider.then_some(FingerLayout { segments: 3, ..now });
        // At a shallow angle a butt joint meets its partner along a line only (two ends cut
        // square to plates far from square to each other). A lap (one finger each, the plate
        // keeping either end in turn) interlocks and meets it over the whole cross-section.
        let lap = |b_first| {
            let shallow = r.kind == ConnectionKind::Corner && r.angle_deg > BUTT_MAX_DEG;
            (shallow && r.junction.is_none() && now.segments > 2).then_some(FingerLayout {
                segments: 2,
                b_first,
                ..now
            })
        };
        let keep = Some(FingerLayout { keeper: Some(i), ..now });
        [shorter, fewer, lap(false), lap(true), keep]
    }

    /// Tries joint `k`'s [candidates](Self::candidates) for plate `i` (now in `pieces`) until
    /// the plate holds together; returns its pieces then.
    fn adapt_joint(&mut self, i: usize, k: usize, mut pieces: Vec<Polygon>) -> Result<Vec<Polygon>, GridError> {
        let r = &self.regions[k];
        let other = if i == r.a { r.b } else { r.a };
        let other_loss = loss(&self.whole(other)?);
        for tried in self.candidates(i, k) {
            let Some(plan) = tried else { continue };
            if pieces.len() <= 1 {
                break;
            }
            if let Some(better) = self.try_plan(i, k, plan, (&pieces, other, other_loss))? {
                pieces = better;
            }
        }
        Ok(pieces)
    }

    /// Cuts joint `k` by `plan` and keeps it if plate `i` loses less than it does now (in
    /// `pieces`) and its partner `other` no more than `other_loss`: returns `i`'s new pieces.
    /// Otherwise everything is put back.
    fn try_plan(
        &mut self,
        i: usize,
        k: usize,
        mut plan: FingerLayout,
        (pieces, other, other_loss): (&[Polygon], usize, (usize, i64)),
    ) -> Result<Option<Vec<Polygon>>, GridError> {
        // Wider fingers and keeping the region build on shorter fingers taken before.
        plan.short |= self.plans[k].short;
        let (a, b) = (self.regions[k].a, self.regions[k].b);
        let before = (
            self.used[k].clone(),
            self.cuts[k].clone(),
            self.outlines[a].clone(),
            self.outlines[b].clone(),
        );
        self.used[k] = variant(&self.regions[k], plan);
        self.cuts[k] = cut(self.plates, &self.used[k], plan, self.style)?;
        if plan.short != self.plans[k].short {
            self.outlines[a] = outline(&self.plates[a], &self.used, &self.touching[a])?;
            self.outlines[b] = outline(&self.plates[b], &self.used, &self.touching[b])?;
        }
        let p = self.whole(i)?;
        // Better for this plate, and not worse for its partner.
        if loss(&p) < loss(pieces) && loss(&self.whole(other)?) <= other_loss {
            self.plans[k] = plan;
            self.adapted_for[k] = Some(i);
            self.finished[other] = None;
            Ok(Some(p))
        } else {
            (self.used[k], self.cuts[k], self.outlines[a], self.outlines[b]) = before;
            Ok(None)
        }
    }

    /// Joints whose edges would fit another joint's, where the parts that would swap are not
    /// twins, get a key finger or other fingers ([`distinct`]), as `verify`'s check reads the
    /// plates cut so far. A plate that a new cut would cost more keeps its joints as they
    /// were (and so do their partners).
    fn tell_apart(&mut self) -> Result<(), GridError> {
        for _ in 0..distinct::ROUNDS {
            if !self.tell_apart_once()? {
                break;
            }
        }
        Ok(())
    }

    /// One round of [`Self::tell_apart`]: whether any connection changed.
    fn tell_apart_once(&mut self) -> Result<bool, GridError> {
        let slabs = (0..self.plates.len())
            .map(|i| {
                Ok(self
                    .pieces_kept(i)?
                    .into_iter()
                    .next()
                    .map(|o| self.plates[i].slab_of(o)))
            })
            .collect::<Result<Vec<_>, GridError>>()?;
        // Halved joints are no finger joints: the check leaves them out.
        let read: Vec<usize> = (0..self.regions.len())
            .filter(|&k| self.regions[k].kind != ConnectionKind::Cross)
            .collect();
        let joints: Vec<EdgeJoint> = read.iter().map(|&k| self.edge_joint(k)).collect();
        let (_, mut found) = crate::verify::acceptances(&slabs, &joints);
        if found.iter().all(|a| a.interchangeable()) {
            return Ok(false);
        }
        for a in &mut found {
            a.joints = a.joints.map(|j| read[j]);
        }
        let looks: Vec<Look> = (0..self.regions.len()).map(|k| self.look(k)).collect();
        let chosen = distinct::choose(&looks, &found);
        let before = self.plans.clone();
        let was = (0..self.plates.len())
            .map(|i| Ok(loss(&self.pieces_kept(i)?)))
            .collect::<Result<Vec<_>, GridError>>()?;
        let mut changed = false;
        for (k, variant) in chosen.into_iter().enumerate() {
            if let Some(Variant { segments, key }) = variant {
                self.recut(
                    k,
                    FingerLayout {
                        segments,
                        key,
                        ..before[k]
                    },
                )?;
                changed = true;
            }
        }
        self.keep_plates_whole(&before, &was)?;
        Ok(changed && self.plans != before)
    }

    /// Plate `i`'s pieces, kept for later.
    fn pieces_kept(&mut self, i: usize) -> Result<Vec<Polygon>, GridError> {
        let pieces = self.pieces(i)?;
        self.finished[i] = Some(pieces.clone());
        Ok(pieces)
    }

    /// Connection `k` as `verify`'s check of edges reads it.
    fn edge_joint(&self, k: usize) -> EdgeJoint {
        let r = &self.regions[k];
        let plain = r.kind == ConnectionKind::Cross || self.plans[k].keeper.is_some() || r.junction.is_some();
        EdgeJoint {
            parts: [r.a, r.b],
            dovetail: self.style == JointStyle::Dovetail && !plain,
        }
    }

    /// What telling connection `k` apart needs to know: it may change unless it is no row
    /// of fingers of its own (a halved joint, a butt joint, a junction's shared row, a lap)
    /// or adapted to keep a plate whole.
    fn look(&self, k: usize) -> Look {
        let (r, plan) = (&self.regions[k], self.plans[k]);
        let own_row = r.kind != ConnectionKind::Cross && r.junction.is_none() && plan.keeper.is_none();
        let (narrowest, target) = widths(self.plates, r, self.settings, self.style);
        Look {
            len: r.range.1 - r.range.0,
            segments: plan.segments,
            key: plan.key,
            narrowest,
            target,
            free: own_row && plan.segments >= 3 && self.adapted_for[k].is_none(),
            from_high: distinct::from_high(r.axis),
        }
    }

    /// Cuts connection `k` by `plan`; its plates are to be finished again.
    fn recut(&mut self, k: usize, plan: FingerLayout) -> Result<(), GridError> {
        self.plans[k] = plan;
        self.cuts[k] = cut(self.plates, &self.used[k], plan, self.style)?;
        for p in [self.regions[k].a, self.regions[k].b] {
            self.finished[p] = None;
        }
        Ok(())
    }

    /// Finishes every plate a new cut changed; one that loses more than it did (`was`) gets
    /// its connections' plans of `before` back, and its partners are finished again.
    fn keep_plates_whole(&mut self, before: &[FingerLayout], was: &[(usize, i64)]) -> Result<(), GridError> {
        let mut i = 0;
        while i < self.plates.len() {
            if self.finished[i].is_some() {
                i += 1;
                continue;
            }
            let pieces = self.whole(i)?;
            if loss(&pieces) <= was[i] {
                self.finished[i] = Some(pieces);
                i += 1;
                continue;
            }
            for (k, _) in self.touching[i].clone() {
                if self.plans[k] != before[k] {
                    self.recut(k, before[k])?;
                }
            }
            // A partner finished under the new cut is to be finished again: from the start.
            i = 0;
        }
        Ok(())
    }

    /// Every plate's final outline (the largest of its pieces), and a warning for each plate
    /// that falls apart all the same. A plate whose partner adapted after it was finished is
    /// finished again.
    fn final_outlines(&mut self) -> Result<(Vec<Polygon>, Vec<String>), GridError> {
        let mut outlines = Vec::with_capacity(self.plates.len());
        let mut split = Vec::new();
        for i in 0..self.plates.len() {
            let pieces = self.pieces(i)?;
            if pieces.len() > 1 {
                let dropped: f64 = pieces[1..].iter().map(Polygon::area).sum();
                let share = 100.0 * dropped / pieces.iter().map(Polygon::area).sum::<f64>();
                split.push(format!(
                    "plate {} would fall into {} pieces at its joints; the largest is kept ({dropped:.1} mm², {share:.1} % of the plate, dropped)",
                    i + 1,
                    pieces.len()
                ));
            }
            outlines.push(
                pieces
                    .into_iter()
                    .next()
                    .unwrap_or_else(|| self.plates[i].polygon.clone()),
            );
        }
        Ok((outlines, split))
    }

    /// The joints as the plan gets them: claims settled between the final outlines, every
    /// joint labelled, its connection, edges and keys, and the warnings.
    fn into_joints(mut self) -> Result<(Joints, Vec<String>), GridError> {
        let (mut outlines, split) = self.final_outlines()?;
        let gave_way = super::claims::settle(self.plates, &mut outlines, &super::claims::decided(&self.used))?;
        if self.settings.crush_ribs {
            self.add_ribs(&mut outlines)?;
        }
        let (labels, unjoined) = super::claims::labels(self.plates, &outlines, &self.used, &gave_way, min_feature)?;
        let mut warnings = self.warnings(&labels, &unjoined);
        warnings.extend(split);
        let (connections, edges) = self.connections(&labels);
        let joints = Joints {
            outlines,
            connections,
            edges,
            keys: self.keys(&labels),
            regions: self.regions(&labels),
            held_bends: Vec::new(),
            refused_bends: Vec::new(),
        };
        Ok((joints, warnings))
    }

    /// The crush ribs of every tee's slots joined to the plate they are cut in
    /// ([`super::ribs`]): the slots are the segments the ending plate's tabs take from the
    /// plate it ends against.
    fn add_ribs(&self, outlines: &mut [Polygon]) -> Result<(), GridError> {
        for (r, &plan) in self.used.iter().zip(&self.plans) {
            let Some(host) = r.through.filter(|_| r.kind == ConnectionKind::Tee) else {
                continue;
            };
            if plan.keeper.is_some() || r.junction.is_some() {
                continue;
            }
            let ending = if host == r.a { r.b } else { r.a };
            let bounds = distinct::boundaries(r.range, plan.segments, plan.key);
            let slots: Vec<(f64, f64)> = (0..plan.segments)
                .filter(|&s| segment_owner(r, plan, s) == ending)
                .map(|s| (bounds[s], bounds[s + 1]))
                .collect();
            let region = if host == r.a { &r.in_a } else { &r.in_b };
            let ribs = super::ribs::ribs(&self.plates[host], region, r.axis, &slots)?;
            outlines[host] = super::ribs::with_ribs(&outlines[host], &ribs)?;
        }
        Ok(())
    }

    /// Each labelled joint's region on both plates and the plate that claimed its ends (the
    /// first segment's owner, or the keeper of a butt joint), for the debug view.
    fn regions(&self, labels: &[Option<u32>]) -> Vec<super::JointRegion> {
        let joints = self.used.iter().zip(&self.plans).zip(labels);
        joints
            .filter_map(|((r, plan), label)| {
                let claimed = plan.keeper.unwrap_or_else(|| segment_owner(r, *plan, 0));
                Some(super::JointRegion {
                    label: (*label)?,
                    plates: [r.a as u32, r.b as u32],
                    polygons: [r.in_a.clone(), r.in_b.clone()],
                    claimed_by: claimed as u32,
                })
            })
            .collect()
    }

    /// Warnings for the places left unjoined and for each labelled joint that adapted.
    fn warnings(&self, labels: &[Option<u32>], unjoined: &[String]) -> Vec<String> {
        let mut warnings = Vec::new();
        if !unjoined.is_empty() {
            warnings.push(format!(
                "{} places where two plates meet are not joined: other joints there already hold all of the volume (plates {})",
                unjoined.len(),
                unjoined.join(", ")
            ));
        }
        for (k, r) in self.regions.iter().enumerate() {
            let (Some(i), Some(label)) = (self.adapted_for[k], labels[k]) else {
                continue;
            };
            let widened = self.plans[k].segments != first_plan(self.plates, r, self.settings, self.style).segments;
            warnings.push(adapted(label, r, self.plans[k], widened, i));
        }
        warnings
    }

    /// The labelled joints' connections, and per plate its jointed edges with their labels.
    fn connections(&self, labels: &[Option<u32>]) -> (Vec<Connection>, Vec<Vec<LabelledEdge>>) {
        let plates = self.plates;
        let mut connections = Vec::with_capacity(self.regions.len());
        let mut edges: Vec<Vec<LabelledEdge>> = vec![Vec::new(); plates.len()];
        for ((r, plan), label) in self.used.iter().zip(&self.plans).zip(labels) {
            let Some(label) = *label else { continue };
            edges[r.a].push((label, edge_of(&plates[r.a], &r.in_a, r.axis)));
            edges[r.b].push((label, edge_of(&plates[r.b], &r.in_b, r.axis)));
            connections.push(Connection {
                plates: [r.a as u32, r.b as u32],
                kind: r.kind,
                style: if r.kind == ConnectionKind::Cross || plan.keeper.is_some() || r.junction.is_some() {
                    JointStyle::Finger
                } else {
                    self.style
                },
                angle_deg: r.angle_deg,
                line: [
                    r.center + r.axis * (r.range.0 - r.axis.dot(r.center)),
                    r.center + r.axis * (r.range.1 - r.axis.dot(r.center)),
                ],
                segments: if plan.keeper.is_some() { 1 } else { plan.segments },
                label,
            });
        }
        (connections, edges)
    }

    /// The dovetail keys of the labelled joints (extra parts), without grid noise.
    fn keys(&self, labels: &[Option<u32>]) -> Vec<Key> {
        self.used
            .iter()
            .zip(&self.cuts)
            .zip(labels)
            .filter_map(|((r, c), label)| label.map(|label| (r, c, label)))
            .flat_map(|(r, c, label)| {
                let male = dovetailed(r);
                let notched = if male == r.a { r.b } else { r.a };
                c.keys
                    .iter()
                    .filter(|p| p.area() > GRID_NOISE_AREA)
                    .map(move |outline| Key {
                        plate: male as u32,
                        notched: notched as u32,
                        outline: outline.clone(),
                        label,
                    })
            })
            .collect()
    }
}

/// The warning for a connection whose joint adapted so that plate `i` stays whole.
fn adapted(n: u32, r: &Region, plan: FingerLayout, widened: bool, i: usize) -> String {
    let plate = i + 1;
    let other = if i == r.a { r.b } else { r.a } + 1;
    match (plan.keeper, r.kind) {
        (None, ConnectionKind::Corner) if plan.segments == 2 => {
            let shorter = if plan.short { "shorter " } else { "" };
            format!("connection {n}: one {shorter}finger on each plate (a lap) so that plate {plate} holds together")
        }
        (None, _) => {
            let how = match (plan.short, widened) {
                (true, true) => format!("{} shorter and wider fingers", plan.segments),
                (true, false) => "shorter fingers".to_string(),
                _ => format!("{} wider fingers", plan.segments),
            };
            format!("connection {n}: {how} so that plate {plate} holds together")
        }
        (Some(_), ConnectionKind::Tee) if r.through != Some(i) => {
            format!("connection {n}: tabs would cut plate {plate} apart; it gets one long tab through plate {other}")
        }
        (Some(_), _) => format!(
            "connection {n}: the joint would cut plate {plate} apart; it stays whole and plate {other} butts against it (glue it)"
        ),
    }
}
