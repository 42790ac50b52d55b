//! Finding where plates meet: each plate grown across its neighbour's slab, and the volume two
//! grown plates share.

use glam::{DVec2, DVec3};
use platener_geom::boolean::{difference, intersection, union_all};
use platener_geom::boxes::{Box3, near_pairs};
use platener_geom::offset::{closing, offset};
use platener_geom::polygon::total_area;
use platener_geom::slab::{Slab, strip_in_box};
use platener_geom::{GridError, Polygon};

use super::junction::{self, Junction};
use super::{ConnectionKind, JointSettings};
use super::{along, bridge, cap};
use crate::plates::Plate;

/// A shared volume of two grown plates, before it is trimmed along the joint line.
pub(super) struct Overlap {
    pub a: usize,
    pub b: usize,
    pub in_a: Polygon,
    pub in_b: Polygon,
    pub axis: DVec3,
    /// The junction line (three or more plates) it runs along, if any.
    pub line: Option<usize>,
    /// Where both plates run along the line (positions along `axis`); `in_a` and `in_b` span
    /// it, or more where a corner is closed ([`close_corners`]).
    pub shared_span: (f64, f64),
    /// `in_a` and `in_b` before they were cut to `shared_span`.
    pub uncut: (Polygon, Polygon),
}

impl Overlap {
    /// A point on its line: the middle of its region in plate a, at mid-thickness.
    pub fn centre(&self, plates: &[Plate]) -> DVec3 {
        let (lo, hi) = self.in_a.bounds();
        at(&plates[self.a], (lo + hi) / 2.0)
    }

    /// Its region in plate `p` (a or b).
    pub fn in_plate(&self, p: usize) -> &Polygon {
        if self.a == p { &self.in_a } else { &self.in_b }
    }

    /// The other plate of the joint, if `p` is one of its two.
    pub fn other(&self, p: usize) -> Option<usize> {
        if self.a == p {
            Some(self.b)
        } else if self.b == p {
            Some(self.a)
        } else {
            None
        }
    }
}

/// How far plate `p` reaches along `axis` at its joint with `other`: its own outline, and the
/// regions of its connections to third plates across that axis (a box corner).
fn reach_along(plates: &[Plate], raw: &[Overlap], p: usize, other: usize, axis: DVec3) -> (f64, f64) {
    let plate = &plates[p];
    let mut r = extent(plate, &plate.polygon, axis);
    for x in raw {
        let (mine, third) = if x.a == p {
            (&x.in_a, x.b)
        } else if x.b == p {
            (&x.in_b, x.a)
        } else {
            continue;
        };
        if third == other || x.axis.dot(axis).abs() > 0.5 {
            continue;
        }
        let e = extent(plate, mine, axis);
        r = (r.0.min(e.0), r.1.max(e.1));
    }
    r
}

fn largest(polys: Vec<Polygon>) -> Option<Polygon> {
    polys.into_iter().max_by(|a, b| a.area().total_cmp(&b.area()))
}

/// The part of `region` (in `plate`'s plane) between `s0` and `s1` along the axis `axis`,
/// which lies in the plate's plane.
pub(super) fn band(plate: &Plate, region: &Polygon, axis: DVec3, s0: f64, s1: f64) -> Result<Vec<Polygon>, GridError> {
    let f = &plate.frame;
    let n2 = DVec2::new(axis.dot(f.u), axis.dot(f.v));
    let c = axis.dot(f.origin);
    let (lo, hi) = region.bounds();
    match strip_in_box(lo - DVec2::ONE, hi + DVec2::ONE, n2, s0 - c, s1 - c) {
        Some(strip) => intersection(std::slice::from_ref(region), &[strip]),
        None => Ok(Vec::new()),
    }
}

/// A joint region shared by two plates.
#[derive(Debug, Clone)]
pub(super) struct Region {
    /// The plates, `a < b` (a ranks higher).
    pub a: usize,
    /// See `a`.
    pub b: usize,
    /// The region in a's plane.
    pub in_a: Polygon,
    /// The region in b's plane.
    pub in_b: Polygon,
    /// What a grows by towards b: the region, and at acute corners the wedge between a's end
    /// and b's slab, which lies in a's layer only.
    pub reach_a: Vec<Polygon>,
    /// See `reach_a`.
    pub reach_b: Vec<Polygon>,
    /// How they meet.
    pub kind: ConnectionKind,
    /// For a T: the plate that passes through.
    pub through: Option<usize>,
    /// For a halved joint: the plate whose slot opens at the low end of `range` (its
    /// material across the joint ends there); the other's opens at the high end.
    pub slot_low: Option<usize>,
    /// The enclosed angle, degrees.
    pub angle_deg: f64,
    /// Unit direction of the joint line (na × nb).
    pub axis: DVec3,
    /// Extent along `axis` (model coordinates projected on it).
    pub range: (f64, f64),
    /// A point on the joint (the region's centre in the model).
    pub center: DVec3,
    /// The line it shares with other plates' connections, if three or more plates meet on it.
    pub junction: Option<Junction>,
    /// Shorter fingers for the same joint (a corner at a shallow or sharp angle), for when the
    /// full ones would cut a plate apart.
    pub short: Option<Box<Reach>>,
}

/// How far a joint region reaches into each plate: the region in each plate's plane and
/// what each plate grows by.
#[derive(Debug, Clone)]
pub(super) struct Reach {
    /// The region in a's plane.
    pub in_a: Polygon,
    /// The region in b's plane.
    pub in_b: Polygon,
    /// What a grows by (see [`Region::reach_a`]).
    pub reach_a: Vec<Polygon>,
    /// What b grows by.
    pub reach_b: Vec<Polygon>,
}

impl Region {
    /// The joint with its shorter fingers, if it has them.
    pub fn shortened(&self) -> Option<Region> {
        let s = self.short.as_deref()?;
        Some(Region {
            in_a: s.in_a.clone(),
            in_b: s.in_b.clone(),
            reach_a: s.reach_a.clone(),
            reach_b: s.reach_b.clone(),
            short: None,
            ..self.clone()
        })
    }
}

/// Where a 2D point of a plate's plane is in the model, at mid-thickness.
pub(super) fn at(plate: &Plate, p: DVec2) -> DVec3 {
    plate.frame.to_model(DVec3::new(p.x, p.y, plate.thickness / 2.0))
}

/// Where `poly` (in `plate`'s plane) lies along `axis`, in model coordinates.
pub(super) fn extent(plate: &Plate, poly: &Polygon, axis: DVec3) -> (f64, f64) {
    extent_of(plate, std::slice::from_ref(poly), axis)
}

/// Where all of `polys` (in `plate`'s plane) lie along `axis`.
fn extent_of(plate: &Plate, polys: &[Polygon], axis: DVec3) -> (f64, f64) {
    along::span(
        polys
            .iter()
            .flat_map(|poly| poly.outer.iter().map(|p| axis.dot(at(plate, *p)))),
    )
}

fn centroid(plate: &Plate, poly: &Polygon) -> DVec3 {
    let (lo, hi) = poly.bounds();
    at(plate, (lo + hi) / 2.0)
}

/// `b`'s slab seen in a's plane where the sine of the angle between their normals is `sin`:
/// how far `a` must grow to cross it.
fn crossing_at(a: &Plate, b: &Plate, sin: f64) -> f64 {
    let cos = (1.0 - sin * sin).max(0.0).sqrt();
    (b.thickness + a.thickness * cos) / sin.max(1e-9)
}

/// How far `a` grows towards `b` to find where they meet: across `b`'s layer, and a
/// thickness more, as a plate may end that far short of it (plate finding trims a plate back
/// by up to about a thickness, and a filleted corner leaves a gap of its radius). At most as
/// far as the crossing where the normals are [`cap::CAP_DEG`] apart: no finger reaches
/// further (towards parallel plates the crossing grows without bound), and that crossing
/// already spans such gaps.
pub(super) fn growth(a: &Plate, b: &Plate) -> f64 {
    let crossing = crossing_at(a, b, a.frame.n.cross(b.frame.n).length());
    (crossing + a.thickness.min(b.thickness)).min(crossing_at(a, b, cap::CAP_DEG.to_radians().sin()))
}

/// Direction from the joint line into the plate, in its plane.
pub(super) fn into_plate(plate: &Plate, axis: DVec3, joint: DVec3) -> DVec3 {
    let d = plate.frame.n.cross(axis).normalize();
    if d.dot(centroid(plate, &plate.polygon) - joint) >= 0.0 {
        d
    } else {
        -d
    }
}

/// How far `plate` grows towards a joint `region`: its outline grown by `grow`, within the
/// joint's `range` along `axis`, from the plate's middle to the far side of the region, and
/// within `grow` of the region (holes and notches elsewhere stay open). Where the plates meet
/// at a right or obtuse angle this is the region itself; at acute angles, or where a plate
/// ends short of the corner (trimmed, or a fillet), the gap between the plate and the region
/// (inside the model, in this plate's layer only) is added.
fn extension(
    plate: &Plate,
    region: &Polygon,
    axis: DVec3,
    range: (f64, f64),
    grow: f64,
) -> Result<Vec<Polygon>, GridError> {
    let f = &plate.frame;
    let along = DVec2::new(axis.dot(f.u), axis.dot(f.v));
    let across = along.perp();
    let c = axis.dot(f.origin);
    let (lo, hi) = plate.polygon.bounds();
    let mid = across.dot((lo + hi) / 2.0);
    let (q0, q1) = region
        .outer
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), p| {
            (a.min(across.dot(*p)), b.max(across.dot(*p)))
        });
    let far = if (q0 - mid).abs() > (q1 - mid).abs() { q0 } else { q1 };
    let grown = offset(std::slice::from_ref(&plate.polygon), grow)?;
    let (glo, ghi) = grown.iter().fold((lo, hi), |(a, b), p| {
        let (l, h) = p.bounds();
        (a.min(l), b.max(h))
    });
    let (Some(in_range), Some(towards)) = (
        strip_in_box(glo - DVec2::ONE, ghi + DVec2::ONE, along, range.0 - c, range.1 - c),
        strip_in_box(glo - DVec2::ONE, ghi + DVec2::ONE, across, mid.min(far), mid.max(far)),
    ) else {
        return Ok(vec![region.clone()]);
    };
    let near_region = offset(std::slice::from_ref(region), grow)?;
    let mut out = intersection(
        &intersection(&intersection(&grown, &[in_range])?, &[towards])?,
        &near_region,
    )?;
    out.push(region.clone());
    Ok(out)
}

/// `polygons` in `plate`'s frame, as slabs of its thickness.
fn slabs(plate: &Plate, polygons: Vec<Polygon>) -> Vec<Slab> {
    polygons.into_iter().map(|p| plate.slab_of(p)).collect()
}

/// The columns of `a` whose volume meets `b`'s: each plate's slabs as given.
fn meeting(a: &[Slab], b: &[Slab]) -> Result<Vec<Polygon>, GridError> {
    let mut out = Vec::new();
    for sa in a {
        for sb in b {
            out.extend(sa.columns_meeting(sb, 1e-3)?);
        }
    }
    Ok(out)
}

/// A plate as far as it reaches a joint: its outline (on a second pass with its joints to
/// other plates), and that grown by the thinnest sheet's thickness.
struct Reaching {
    shape: Vec<Polygon>,
    near: Vec<Polygon>,
}

/// The stretches where plates `a` and `b`, each grown across the other's slab (minus `keep_out`
/// in its own plane), share volume: the columns of each that meet the other.
fn shared(
    plates: &[Plate],
    reaching: &[Reaching],
    a: usize,
    b: usize,
    keep_out_a: &[Polygon],
    keep_out_b: &[Polygon],
) -> Result<Vec<Overlap>, GridError> {
    let (pa, pb) = (&plates[a], &plates[b]);
    let grown = |p: &Plate, by: f64, keep_out: &[Polygon]| -> Result<Vec<Slab>, GridError> {
        let mut g = offset(std::slice::from_ref(&p.polygon), by)?;
        if !keep_out.is_empty() {
            g = difference(&g, keep_out)?;
        }
        Ok(slabs(p, g))
    };
    let (ga, gb) = (
        grown(pa, growth(pa, pb), keep_out_a)?,
        grown(pb, growth(pb, pa), keep_out_b)?,
    );
    let mut in_a = meeting(&ga, &gb)?;
    let mut in_b = meeting(&gb, &ga)?;

    // Where the plates themselves (grown a little) meet: only there is it a joint (the "real
    // segment"); grown plates also share volume where they merely pass each other's corners.
    let contact = meeting(
        &slabs(pa, reaching[a].near.clone()),
        &slabs(pb, reaching[b].near.clone()),
    )?;
    let min_area = (pa.thickness.min(pb.thickness) / 2.0).powi(2);
    let min_length = pa.thickness.max(pb.thickness) / 2.0;
    in_a.retain(|p| p.area() > min_area);
    in_b.retain(|p| p.area() > min_area);
    let axis = pa.frame.n.cross(pb.frame.n).normalize();
    let near = centroid(pa, &pa.polygon);
    let both = along::common(
        &along::stretches(pa, &reaching[a].shape, pb, axis, near)?,
        &along::stretches(pb, &reaching[b].shape, pa, axis, near)?,
    );
    // Disjoint stretches are separate connections: pair the pieces by their extent along the
    // joint line.
    let mut out = Vec::new();
    for ra in &in_a {
        let range_a = extent(pa, ra, axis);
        let Some(rb) = in_b.iter().find(|rb| {
            let r = extent(pb, rb, axis);
            r.0 < range_a.1 && range_a.0 < r.1
        }) else {
            continue;
        };
        let touching = intersection(&contact, std::slice::from_ref(ra))?;
        let near_each_other = extent_of(pa, &touching, axis);
        // Only where both plates run along the line (not where they merely touch at a vertex).
        let Some(real) = along::hull_within(&both, near_each_other).filter(|r| r.1 - r.0 >= min_length) else {
            continue;
        };
        let (Some(in_a), Some(in_b)) = (
            largest(band(pa, ra, axis, real.0, real.1)?),
            largest(band(pb, rb, axis, real.0, real.1)?),
        ) else {
            continue;
        };
        out.push(Overlap {
            a,
            b,
            in_a,
            in_b,
            axis,
            line: None,
            shared_span: real,
            uncut: (ra.clone(), rb.clone()),
        });
    }
    Ok(out)
}

/// The joints of `a` and of `b` with the same third plate across the end of their line (a box
/// corner: plate finding leaves the corner's cube to one of the three, or to none).
fn corner_plates<'r>(raw: &'r [Overlap], r: &Overlap) -> Vec<(&'r Overlap, &'r Overlap)> {
    let steep = |x: &Overlap| x.axis.dot(r.axis).abs() <= 0.5;
    let mut out = Vec::new();
    for x in raw.iter().filter(|x| steep(x)) {
        let Some(c) = x.other(r.a).filter(|&c| c != r.b) else {
            continue;
        };
        for y in raw.iter().filter(|y| steep(y) && y.other(r.b) == Some(c)) {
            out.push((x, y));
        }
    }
    out
}

/// Each joint runs on past where both plates are over a corner that a third plate closes
/// with both, so that the fingers of the three joints decide who owns the corner's cube.
/// Elsewhere a joint ends where one of its plates does: on a low-poly ball four facets meet
/// at a vertex and only neighbours along an edge are joined, so a joint running on would
/// reach into a facet it has no joint with.
fn close_corners(plates: &[Plate], raw: &mut [Overlap]) -> Result<(), GridError> {
    let mut ends = Vec::with_capacity(raw.len());
    for r in raw.iter() {
        let t = plates[r.a].thickness.max(plates[r.b].thickness);
        let (mut s0, mut s1) = r.shared_span;
        for (x, y) in corner_plates(raw, r) {
            let ea = extent(&plates[r.a], x.in_plate(r.a), r.axis);
            let eb = extent(&plates[r.b], y.in_plate(r.b), r.axis);
            let e = (ea.0.min(eb.0), ea.1.max(eb.1));
            if e.0 <= r.shared_span.0 + t && e.1 >= r.shared_span.0 - t {
                s0 = s0.min(e.0);
            }
            if e.0 <= r.shared_span.1 + t && e.1 >= r.shared_span.1 - t {
                s1 = s1.max(e.1);
            }
        }
        ends.push((s0, s1));
    }
    for (r, (s0, s1)) in raw.iter_mut().zip(ends) {
        if (s0, s1) == r.shared_span {
            continue;
        }
        let (pa, pb) = (&plates[r.a], &plates[r.b]);
        if let (Some(a), Some(b)) = (
            largest(band(pa, &r.uncut.0, r.axis, s0, s1)?),
            largest(band(pb, &r.uncut.1, r.axis, s0, s1)?),
        ) {
            (r.in_a, r.in_b) = (a, b);
        }
    }
    Ok(())
}

/// Every joint region between the plates.
pub(super) fn find(plates: &[Plate], settings: &JointSettings) -> Result<Vec<Region>, GridError> {
    let mut finding = Finding::new(plates)?;
    finding.meet_pairwise(settings)?;
    finding.drop_bridges()?;
    finding.reach_through_joints()?;
    let lines = finding.junction_lines();
    finding.redo_junctions(&lines)?;
    finding.raw.sort_by_key(|r| (r.a, r.b));
    close_corners(plates, &mut finding.raw)?;
    let mut regions = Vec::with_capacity(finding.raw.len());
    // The junction line of each region.
    let mut lines_of = Vec::with_capacity(finding.raw.len());
    for r in &finding.raw {
        if let Some(region) = finding.region(r)? {
            regions.push(region);
            lines_of.push(r.line);
        }
    }
    on_lines(&mut regions, &lines_of, &lines);
    Ok(regions)
}

/// Where plates meet, as found so far: the shared volumes of pairs of plates, from first
/// finding them pair by pair to the joints on junction lines. Each phase reads what the
/// earlier ones found, so they share this state.
struct Finding<'a> {
    plates: &'a [Plate],
    /// The thinnest plate's thickness.
    t_min: f64,
    /// The thickest plate's thickness.
    t_max: f64,
    /// The furthest a plate grows towards a joint (the crossing of two layers, capped).
    reach: f64,
    /// How far each plate reaches a joint.
    reaching: Vec<Reaching>,
    /// The shared volumes found.
    raw: Vec<Overlap>,
    /// Pairs of plates near each other that share no volume on the first pass.
    unreached: Vec<(usize, usize)>,
    /// How many of `raw` were found pair by pair (the rest through other joints).
    strict: usize,
}

impl<'a> Finding<'a> {
    /// Each plate reaching joints with its own outline.
    fn new(plates: &'a [Plate]) -> Result<Self, GridError> {
        let t_max = plates.iter().map(|p| p.thickness).fold(0.0, f64::max);
        let t_min = plates.iter().map(|p| p.thickness).fold(f64::INFINITY, f64::min);
        let mut finding = Self {
            plates,
            t_min,
            t_max,
            reach: 2.0 * t_max / cap::CAP_DEG.to_radians().sin(),
            reaching: Vec::with_capacity(plates.len()),
            raw: Vec::new(),
            unreached: Vec::new(),
            strict: 0,
        };
        for p in plates {
            let reaching = finding.reaching_as(vec![p.polygon.clone()])?;
            finding.reaching.push(reaching);
        }
        Ok(finding)
    }

    /// A plate as far as it reaches joints with `shape`: whatever lies within twice the
    /// thinnest sheet's thickness reaches a joint region. Plates end at the region's edge or
    /// inside it, but plate finding trims a plate back by up to about a thickness where it
    /// overlapped another (a quarter of it lost two of the four joints of plycutter's
    /// PlyTest), and at a filleted corner both plates end short of it (the smartphone
    /// stand's 2 mm fillets: 3.4 mm).
    fn reaching_as(&self, shape: Vec<Polygon>) -> Result<Reaching, GridError> {
        Ok(Reaching {
            near: offset(&shape, 2.0 * self.t_min)?,
            shape,
        })
    }

    /// The shared volumes of every pair of plates near each other and not too close to
    /// parallel; the pairs that share none are kept for a second look.
    fn meet_pairwise(&mut self, settings: &JointSettings) -> Result<(), GridError> {
        let sin_min = settings.min_angle_deg.to_radians().sin();
        let bounds: Vec<Box3> = self.plates.iter().map(Plate::bounds).collect();
        let mut pairs = near_pairs(&bounds, self.reach);
        pairs.sort_unstable();
        for (a, b) in pairs {
            let (pa, pb) = (&self.plates[a], &self.plates[b]);
            if pa.frame.n.cross(pb.frame.n).length() < sin_min {
                continue;
            }
            let found = shared(self.plates, &self.reaching, a, b, &[], &[])?;
            if found.is_empty() {
                self.unreached.push((a, b));
            }
            self.raw.extend(found);
        }
        Ok(())
    }

    /// Drops the shared volumes that only bridge a gap (see [`bridge::bridging`]).
    fn drop_bridges(&mut self) -> Result<(), GridError> {
        let bridges = bridge::bridging(self.plates, &self.raw, self.t_min / 2.0)?;
        self.raw = std::mem::take(&mut self.raw)
            .into_iter()
            .zip(bridges)
            .filter(|(_, b)| !b)
            .map(|(r, _)| r)
            .collect();
        Ok(())
    }

    /// A plate may reach a joint only through its joints with others: a wall ending against
    /// one side of a V still meets the board the V stands on, on the same line. The pairs
    /// that shared nothing are tried again with such plates grown by their joints.
    fn reach_through_joints(&mut self) -> Result<(), GridError> {
        let plates = self.plates;
        let mut via: Vec<Vec<Polygon>> = plates.iter().map(|p| vec![p.polygon.clone()]).collect();
        for r in &self.raw {
            via[r.a].push(r.in_a.clone());
            via[r.b].push(r.in_b.clone());
        }
        self.strict = self.raw.len();
        let mut regrown = vec![false; plates.len()];
        for (a, b) in self.unreached.clone() {
            for p in [a, b] {
                if !regrown[p] && via[p].len() > 1 {
                    self.reaching[p] = self.reaching_as(union_all(&via[p])?)?;
                    regrown[p] = true;
                }
            }
            if regrown[a] || regrown[b] {
                let found = shared(plates, &self.reaching, a, b, &[], &[])?;
                self.raw.extend(found);
            }
        }
        Ok(())
    }

    /// Three or more plates on one line: each reaches past the line only as far as the model
    /// goes, and their connections take turns in one row of fingers. Joints found through
    /// other joints are kept only on such a line.
    fn junction_lines(&mut self) -> Vec<junction::Line> {
        let lines = junction::lines(self.plates, &self.raw, self.t_min / 2.0);
        if self.raw.len() <= self.strict {
            return lines;
        }
        let on_line: std::collections::BTreeSet<usize> = lines.iter().flat_map(|l| l.members.iter().copied()).collect();
        let mut k = 0;
        let strict = self.strict;
        self.raw.retain(|_| {
            k += 1;
            k <= strict || on_line.contains(&(k - 1))
        });
        junction::lines(self.plates, &self.raw, self.t_min / 2.0)
    }

    /// The joints of each pair of plates on a junction line, found again with each plate
    /// kept from reaching beyond the line (unless it passes through it).
    fn redo_junctions(&mut self, lines: &[junction::Line]) -> Result<(), GridError> {
        let (plates, reach) = (self.plates, self.reach);
        let mut redone = Vec::new();
        for (id, line) in lines.iter().enumerate() {
            // A plate passing through the line keeps its own outline on both sides.
            let beyond = |w: usize| -> Vec<Polygon> {
                if junction::passes(&plates[w], line) {
                    return Vec::new();
                }
                let exit = junction::exit(plates, line, w, reach);
                vec![junction::beyond(&plates[w], line, exit, reach)]
            };
            let mut pairs: Vec<(usize, usize)> = line.members.iter().map(|&i| (self.raw[i].a, self.raw[i].b)).collect();
            pairs.sort_unstable();
            pairs.dedup();
            for (a, b) in pairs {
                redone.push((a, b, shared(plates, &self.reaching, a, b, &beyond(a), &beyond(b))?, id));
            }
        }
        self.raw
            .retain(|r| !redone.iter().any(|(a, b, _, _)| (*a, *b) == (r.a, r.b)));
        for (_, _, stretches, id) in redone {
            self.raw
                .extend(stretches.into_iter().map(|r| Overlap { line: Some(id), ..r }));
        }
        Ok(())
    }

    /// The joint region of the shared volume `r`: trimmed to where both plates run along
    /// the line, its kind, angle and how far each plate grows into it. `None` when less than
    /// half the thickest sheet's thickness of it is left.
    fn region(&self, r: &Overlap) -> Result<Option<Region>, GridError> {
        let (plates, raw) = (self.plates, &self.raw);
        let (pa, pb) = (&plates[r.a], &plates[r.b]);
        // Growing in every direction also lengthened the joint past the plates' ends; along the
        // joint line a plate only reaches as far as it is, or as another connection (a box
        // corner's third plate) takes it.
        let (la, lb) = (
            reach_along(plates, raw, r.a, r.b, r.axis),
            reach_along(plates, raw, r.b, r.a, r.axis),
        );
        let own = extent(pa, &r.in_a, r.axis);
        let range = (la.0.max(lb.0).max(own.0), la.1.min(lb.1).min(own.1));
        if range.1 - range.0 < self.t_max / 2.0 {
            return Ok(None);
        }
        let (Some(ra), Some(rb)) = (
            largest(band(pa, &r.in_a, r.axis, range.0, range.1)?),
            largest(band(pb, &r.in_b, r.axis, range.0, range.1)?),
        ) else {
            return Ok(None);
        };
        let (kind, through) = kind_of(r, (pa, &ra), (pb, &rb))?;
        let (mut ra, mut rb, mut slot_low, mut range) = (ra, rb, None, range);
        if kind == ConnectionKind::Cross {
            let h = halving(r, (pa, &ra), (pb, &rb), range, self.t_min / 2.0)?;
            slot_low = Some(h.low);
            if let (Some(a), Some(b)) = (
                largest(band(pa, &r.in_a, r.axis, h.span.0, h.span.1)?),
                largest(band(pb, &r.in_b, r.axis, h.span.0, h.span.1)?),
            ) {
                (ra, rb, range) = (a, b, h.span);
            }
            if let Some((long, reach)) = h.through {
                let (p, region) = if long == r.a { (pa, &mut ra) } else { (pb, &mut rb) };
                let mut reaching = column(p, region, r.axis, 0.0)?;
                reaching.push(region.clone());
                if let Some(whole) = largest(union_all(&reaching)?)
                    && let Some(longer) = largest(band(p, &whole, r.axis, reach.0, reach.1)?)
                {
                    *region = longer;
                }
            }
        }
        // Towards 180° (and 0°) the layers' crossing is long: fingers reach only as far past
        // the middle line as at 150°, and a shorter variant stands by for plates the full
        // one would cut apart.
        let (ra, rb, short) = if kind == ConnectionKind::Corner {
            let near = centroid(pa, &ra);
            let (ra, rb) = cap::capped(pa, pb, r.axis, near, (&ra, &rb), cap::CAP_DEG)?.unwrap_or((ra, rb));
            let short = cap::capped(pa, pb, r.axis, near, (&ra, &rb), cap::SHORT_DEG)?;
            (ra, rb, short)
        } else {
            (ra, rb, None)
        };
        let center = centroid(pa, &ra);
        let reach = |sa: Polygon, sb: Polygon| -> Result<Reach, GridError> {
            Ok(Reach {
                reach_a: extension(pa, &sa, r.axis, range, growth(pa, pb))?,
                reach_b: extension(pb, &sb, r.axis, range, growth(pb, pa))?,
                in_a: sa,
                in_b: sb,
            })
        };
        let short = short.map(|(sa, sb)| reach(sa, sb)).transpose()?;
        let Reach {
            in_a,
            in_b,
            reach_a,
            reach_b,
        } = reach(ra, rb)?;
        Ok(Some(Region {
            a: r.a,
            b: r.b,
            in_a,
            in_b,
            reach_a,
            reach_b,
            short: short.map(Box::new),
            kind,
            through,
            slot_low,
            angle_deg: angle_of(kind, pa, pb, r.axis, center),
            axis: r.axis,
            range,
            center,
            junction: None,
        }))
    }
}

/// Whether `region` (in `p`'s plane) lies within the plate's own outline.
fn passes(p: &Plate, region: &Polygon) -> Result<bool, GridError> {
    let outside = total_area(&difference(
        std::slice::from_ref(region),
        std::slice::from_ref(&p.polygon),
    )?);
    Ok(outside < 1e-6 * region.area().max(1.0))
}

/// An interval along a joint's axis (model coordinates projected on it).
type Span = (f64, f64);

/// Plate `p`'s outline in the column of `region`'s width across the joint (narrowed by
/// `inset` of that width on each side), in pieces.
fn column(p: &Plate, region: &Polygon, axis: DVec3, inset: f64) -> Result<Vec<Polygon>, GridError> {
    let f = &p.frame;
    let across = axis.cross(f.n);
    let (w0, w1) = along::span(region.outer.iter().map(|q| across.dot(at(p, *q))));
    let inset = inset * (w1 - w0);
    let n2 = DVec2::new(across.dot(f.u), across.dot(f.v));
    let c = across.dot(f.origin);
    let (lo, hi) = p.polygon.bounds();
    match strip_in_box(lo - DVec2::ONE, hi + DVec2::ONE, n2, w0 + inset - c, w1 - inset - c) {
        Some(strip) => intersection(std::slice::from_ref(&p.polygon), &[strip]),
        None => Ok(Vec::new()),
    }
}

/// Where plate `p`'s material across the joint starts and ends along `axis`: the shared
/// `range` (the other plate left a notch there in the plate's faces) and the pieces of the
/// plate's column that reach it within `tol`, in the middle of the column (its sides run
/// along the other plate's faces). Also the range widened to touch those pieces (growing
/// the plates may stop a few µm short of them).
fn column_extent(
    p: &Plate,
    region: &Polygon,
    axis: DVec3,
    range: (f64, f64),
    tol: f64,
) -> Result<[Span; 2], GridError> {
    let mut extents: Vec<(f64, f64)> = column(p, region, axis, 0.25)?
        .iter()
        .map(|piece| extent(p, piece, axis))
        .collect();
    extents.sort_by(|x, y| x.0.total_cmp(&y.0));
    let (mut e, mut touch) = (range, range);
    // Pieces beyond one that reaches the range reach it through that one: two passes, up
    // and down.
    for x in extents.iter().chain(extents.iter().rev()) {
        if x.0 <= e.1 + tol && x.1 >= e.0 - tol {
            e = (e.0.min(x.0), e.1.max(x.1));
        }
        if x.1 <= range.0 && x.1 >= range.0 - tol {
            touch.0 = touch.0.min(x.1);
        }
        if x.0 >= range.1 && x.0 <= range.1 + tol {
            touch.1 = touch.1.max(x.0);
        }
    }
    Ok([e, touch])
}

/// How two plates cross: which takes the slot from the low end of the shared `range`, and
/// whether the other's slot must run on past the range to its own edge.
struct Halving {
    /// The plate whose slot opens at the low end.
    low: usize,
    /// The shared range, out to the plates' own ends where they end at it.
    span: (f64, f64),
    /// The plate whose material runs on past both ends of the range, and how far the joint
    /// region in it must reach to open its slot at its nearer end.
    through: Option<(usize, (f64, f64))>,
}

/// Which plate of a crossing takes the slot from the low end of the shared `range`: each
/// slot must open at an end of the plate's own material across the joint, so that the parts
/// slide together and each slot runs to the middle of the shared height. Plates of equal
/// height may go either way: b's slot at the low end, as always. Where one plate's crossing
/// lies within the other's, the longer one's slot runs from its nearer end (the part of it
/// beyond the shorter plate is left open; a T would cut the shorter plate in two).
fn halving(
    r: &Overlap,
    (pa, ra): (&Plate, &Polygon),
    (pb, rb): (&Plate, &Polygon),
    range: (f64, f64),
    tol: f64,
) -> Result<Halving, GridError> {
    let ([ea, ta], [eb, tb]) = (
        column_extent(pa, ra, r.axis, range, tol)?,
        column_extent(pb, rb, r.axis, range, tol)?,
    );
    let ends = |e: (f64, f64)| (e.0 > range.0 - tol, e.1 < range.1 + tol);
    let ((a_low, a_high), (b_low, b_high)) = (ends(ea), ends(eb));
    // The joint spans the crossing to the plates' own ends (the range found by growing them
    // may stop a few µm short, which would leave a hairline of the notch as a hole).
    let snap = |at: f64, e: [f64; 2], ending: [bool; 2], pick: fn(f64, f64) -> f64| {
        (0..2).filter(|&k| ending[k]).fold(at, |x, k| pick(x, e[k]))
    };
    let span = (
        snap(ta.0.min(tb.0), [ea.0, eb.0], [a_low, b_low], f64::min),
        snap(ta.1.max(tb.1), [ea.1, eb.1], [a_high, b_high], f64::max),
    );
    let fixed = |low| Halving {
        low,
        span,
        through: None,
    };
    if b_low && a_high {
        return Ok(fixed(r.b));
    }
    if a_low && b_high {
        return Ok(fixed(r.a));
    }
    let (long, e, other) = if ea.1 - ea.0 >= eb.1 - eb.0 {
        (r.a, ea, r.b)
    } else {
        (r.b, eb, r.a)
    };
    Ok(if range.0 - e.0 <= e.1 - range.1 {
        Halving {
            low: long,
            span,
            through: Some((long, (e.0, span.1))),
        }
    } else {
        Halving {
            low: other,
            span,
            through: Some((long, (span.0, e.1))),
        }
    })
}

/// Whether `region` (in `p`'s plane) lies within the plate's outline once notches narrower
/// than the region is wide are closed: a plate crossing another over less than its full
/// height is found with a notch where the other interrupts its faces.
fn passes_notched(p: &Plate, region: &Polygon, axis: DVec3) -> Result<bool, GridError> {
    let across = axis.cross(p.frame.n);
    let (w0, w1) = along::span(region.outer.iter().map(|q| across.dot(at(p, *q))));
    let closed = closing(std::slice::from_ref(&p.polygon), 0.75 * (w1 - w0))?;
    let outside = total_area(&difference(std::slice::from_ref(region), &closed)?);
    Ok(outside < 1e-3 * region.area().max(1.0))
}

/// How the plates of `r` meet, from whether each one's region lies within its outline (a
/// plate passing through) or not (a plate ending there); for a T, the plate passing through.
fn kind_of(
    r: &Overlap,
    (pa, ra): (&Plate, &Polygon),
    (pb, rb): (&Plate, &Polygon),
) -> Result<(ConnectionKind, Option<usize>), GridError> {
    let passes = |p: &Plate, region: &Polygon| -> Result<bool, GridError> {
        Ok(passes(p, region)? || passes_notched(p, region, r.axis)?)
    };
    Ok(match (passes(pa, ra)?, passes(pb, rb)?) {
        (false, false) => (ConnectionKind::Corner, None),
        (true, false) => (ConnectionKind::Tee, Some(r.a)),
        (false, true) => (ConnectionKind::Tee, Some(r.b)),
        (true, true) => (ConnectionKind::Cross, None),
    })
}

/// The angle (degrees) the plates enclose at a joint of `kind` along `axis` through `center`.
fn angle_of(kind: ConnectionKind, pa: &Plate, pb: &Plate, axis: DVec3, center: DVec3) -> f64 {
    match kind {
        ConnectionKind::Corner => {
            let (da, db) = (into_plate(pa, axis, center), into_plate(pb, axis, center));
            da.dot(db).clamp(-1.0, 1.0).acos().to_degrees()
        }
        // The plate ending against a face makes two angles with it; the smaller is named.
        _ => pa.frame.n.dot(pb.frame.n).abs().clamp(0.0, 1.0).acos().to_degrees(),
    }
}

/// Each junction spans its connections' final extents (the raw ones reach past the plates):
/// every region on line `id` (`lines_of`) gets it.
fn on_lines(regions: &mut [Region], lines_of: &[Option<usize>], lines: &[junction::Line]) {
    for (id, line) in lines.iter().enumerate() {
        let mine: Vec<usize> = (0..regions.len()).filter(|&k| lines_of[k] == Some(id)).collect();
        let range = mine.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |acc, &k| {
            let r: &Region = &regions[k];
            let (lo, hi) = junction::flipped_unless(r.range, r.axis.dot(line.axis) > 0.0);
            (acc.0.min(lo), acc.1.max(hi))
        });
        let junction = Junction {
            plates: line.plates.clone(),
            axis: line.axis,
            range,
        };
        for k in mine {
            regions[k].junction = Some(junction.clone());
        }
    }
}
