//! Growing bent parts: candidates are taken one by one (the easiest bends first) and each
//! joins two groups of plates into one flat layout, unless the developed shapes would
//! overlap or the part would no longer fit on a sheet (Kruskal's algorithm with a veto). A
//! candidate whose plates are already in one group closes a ring: it stays a joint, the
//! seam where the tube is cut open; taking the easiest bends first leaves the seams where
//! bending is hardest and a joint easiest.

use glam::{DVec2, DVec3};
use platener_geom::GridError;
use platener_geom::boolean::{difference, intersection};
use platener_geom::polygon::{Polygon, total_area};
use platener_geom::rigid::mirror_y;

use super::find::Candidate;
use super::unfold::{Member, develop};
use super::zone::BendZone;
use crate::plates::Plate;

/// Where a member is cut at a bend line: the half of its mid-plane on the `into` side of the
/// line through `point`.
#[derive(Debug, Clone, Copy, serde::Serialize)]
pub struct HalfPlane {
    /// A point on the line, in the model.
    pub point: DVec3,
    /// The line's direction.
    pub axis: DVec3,
    /// Into the kept half, perpendicular to the line, in the member's plane.
    pub into: DVec3,
    /// How far short of the line the member's plate stops across a fillet, mm (0 at a
    /// corner): the flat part is filled up to the line over it, where the arc zone replaces
    /// the fillet's facets.
    pub gap: f64,
}

impl HalfPlane {
    /// A large quad covering the kept half of `mid`'s plane (in its 2D coordinates),
    /// reaching past every shape in `shapes`.
    pub fn quad(&self, mid: &platener_geom::Frame, shapes: &[Polygon]) -> Polygon {
        let origin = mid.to_2d(self.point);
        let along = DVec2::new(mid.u.dot(self.axis), mid.v.dot(self.axis)).normalize();
        let into = DVec2::new(mid.u.dot(self.into), mid.v.dot(self.into)).normalize();
        let (lo, hi) = platener_geom::polygon::bounds_of(shapes.iter().flat_map(|p| p.outer.iter().copied()));
        let reach = 2.0 * ((hi - lo).length() + (origin - (lo + hi) / 2.0).length()) + 1.0;
        let mut quad = Polygon::new(vec![
            origin - along * reach,
            origin + along * reach,
            origin + along * reach + into * reach,
            origin - along * reach + into * reach,
        ]);
        quad.normalize_orientation();
        quad
    }

    /// `shapes` (in `member`'s frame coordinates) cut to the kept half.
    pub fn cut(&self, member: &Member, thickness: f64, shapes: &[Polygon]) -> Result<Vec<Polygon>, GridError> {
        if shapes.iter().all(|p| p.outer.is_empty()) {
            return Ok(Vec::new());
        }
        let keep = self.quad(&member.mid(thickness), shapes);
        intersection(shapes, std::slice::from_ref(&keep))
    }
}

/// The plates' layout as it grows.
pub(crate) struct Layout<'a> {
    plates: &'a [Plate],
    candidates: &'a [Candidate],
    zones: &'a [Result<BendZone, String>],
    /// The sheet's sides, to keep every part cuttable.
    sheet: (f64, f64),
    pub members: Vec<Member>,
    pub group: Vec<usize>,
    pub groups: Vec<Vec<usize>>,
    pub cuts: Vec<Vec<HalfPlane>>,
    /// Per plate: where its flat segment begins at each of its bends (the zone's edge).
    tangents: Vec<Vec<HalfPlane>>,
    /// Each plate's developed shape (cut at its bend lines) on its group's flat.
    flat: Vec<Vec<Polygon>>,
    /// The candidates made bends, in the order taken, with the plate that stayed in place
    /// (the bend deduction moved the other).
    pub bends: Vec<(usize, usize)>,
    /// Why a candidate joining two groups was refused.
    pub refused: Vec<(usize, String)>,
    /// The candidates refused because the developed shapes would overlap, in the order
    /// taken: each with the plates of the staying group that the moving group would overlap
    /// and how many plates that group holds (what removing them could let in).
    pub blocked: Vec<Blocked>,
}

/// A candidate refused because the moving group, laid flat, would overlap plates of the
/// group it was to join.
#[derive(Debug, Clone)]
pub(crate) struct Blocked {
    /// The candidate.
    pub candidate: usize,
    /// The plates of the staying group it would overlap, ascending.
    pub by: Vec<usize>,
    /// How many plates the moving group holds.
    pub moving: usize,
}

impl<'a> Layout<'a> {
    pub fn new(
        plates: &'a [Plate],
        candidates: &'a [Candidate],
        zones: &'a [Result<BendZone, String>],
        sheet: (f64, f64),
    ) -> Self {
        let n = plates.len();
        Self {
            plates,
            candidates,
            zones,
            sheet,
            members: plates
                .iter()
                .enumerate()
                .map(|(i, p)| Member::alone(i as u32, p.frame))
                .collect(),
            group: (0..n).collect(),
            groups: (0..n).map(|i| vec![i]).collect(),
            cuts: vec![Vec::new(); n],
            tangents: vec![Vec::new(); n],
            flat: plates.iter().map(|p| vec![p.polygon.clone()]).collect(),
            bends: Vec::new(),
            refused: Vec::new(),
            blocked: Vec::new(),
        }
    }

    /// Takes the candidates in `order`.
    pub fn grow(mut self, order: &[usize]) -> Result<Self, GridError> {
        for &ci in order {
            let [a, b] = self.candidates[ci].plates;
            if self.group[a] == self.group[b] {
                continue;
            }
            match &self.zones[ci] {
                Err(why) => self.refused.push((ci, why.clone())),
                Ok(zone) => {
                    if let Err(why) = self.join(ci, *zone)? {
                        self.refused.push((ci, why));
                    }
                }
            }
        }
        Ok(self)
    }

    /// How good the layout is: fewer parts first, then larger ones (sum of squared areas).
    pub fn quality(&self) -> (usize, f64) {
        let parts = self.groups.iter().filter(|g| !g.is_empty()).count();
        let spread: f64 = self
            .groups
            .iter()
            .map(|g| g.iter().map(|&p| self.plates[p].area).sum::<f64>().powi(2))
            .sum();
        (parts, -spread)
    }

    /// Joins the groups of candidate `ci`'s plates across it, if nothing overlaps.
    fn join(&mut self, ci: usize, zone: BendZone) -> Result<Result<(), String>, GridError> {
        let c = &self.candidates[ci];
        let [a, b] = c.plates;
        let (parent, child) = if self.groups[self.group[a]].len() >= self.groups[self.group[b]].len() {
            (a, b)
        } else {
            (b, a)
        };
        let t = self.plates[parent].thickness;
        let moving = self.groups[self.group[child]].clone();
        let (members, mut shapes, k) = self.moved(&moving, parent, child, c, zone);
        let cut = |plate: usize| HalfPlane {
            point: c.point,
            axis: c.axis,
            into: c.into[c.side_of(plate)],
            gap: c.gap,
        };
        let (hp, hc) = (cut(parent), cut(child));
        let tangent = |h: HalfPlane| HalfPlane {
            point: h.point + h.into * zone.setback(),
            ..h
        };
        let (tp, tc) = (tangent(hp), tangent(hc));
        for (p, m, t_new) in [(parent, &self.members[parent], tp), (child, &members[k], tc)] {
            if !self.keeps_a_segment(p, m, t_new)? {
                return Ok(Err(format!(
                    "plate {} would be all bend zone, with no flat segment left",
                    p + 1
                )));
            }
        }
        let parent_shape = self.developed(parent, &self.members[parent], &[hp])?;
        shapes[k] = self.developed(child, &members[k], &[hc])?;
        let strip = self.strip(&self.members[parent], c, parent, t, zone.deduction());
        let staying: Vec<usize> = self.groups[self.group[parent]].clone();
        let pair = (parent, child, &parent_shape, &strip);
        let overlaps = self.overlaps(&staying, &moving, &shapes, pair, t)?;
        if let Some(&(p, q)) = overlaps.first() {
            let mut by: Vec<usize> = overlaps.iter().map(|&(p, _)| p).collect();
            by.sort_unstable();
            self.blocked.push(Blocked {
                candidate: ci,
                by,
                moving: moving.len(),
            });
            return Ok(Err(format!("laid flat, plate {} would overlap plate {}", q + 1, p + 1)));
        }
        if !self.fits(
            staying
                .iter()
                .map(|&p| if p == parent { &parent_shape } else { &self.flat[p] })
                .chain(&shapes),
        ) {
            return Ok(Err("the bent part would not fit on the sheet".into()));
        }
        self.flat[parent] = parent_shape;
        self.cuts[parent].push(hp);
        self.cuts[child].push(hc);
        self.tangents[parent].push(tp);
        self.tangents[child].push(tc);
        let (gp, gc) = (self.group[parent], self.group[child]);
        for ((p, m), s) in moving.iter().zip(members).zip(shapes) {
            self.members[*p] = m;
            self.flat[*p] = s;
            self.group[*p] = gp;
        }
        let moved = std::mem::take(&mut self.groups[gc]);
        self.groups[gp].extend(moved);
        self.bends.push((ci, parent));
        Ok(Ok(()))
    }

    /// The group `moving` (holding `child`) laid into `parent`'s flat across `c`, flipped if
    /// its frames face the other way: its members, their developed shapes, and the child's
    /// index among them.
    fn moved(
        &self,
        moving: &[usize],
        parent: usize,
        child: usize,
        c: &Candidate,
        zone: BendZone,
    ) -> (Vec<Member>, Vec<Vec<Polygon>>, usize) {
        let t = self.plates[parent].thickness;
        let mut members: Vec<Member> = moving.iter().map(|&p| self.members[p].clone()).collect();
        let mut shapes: Vec<Vec<Polygon>> = moving.iter().map(|&p| self.flat[p].clone()).collect();
        let k = moving
            .iter()
            .position(|&p| p == child)
            .expect("the child is in its group");
        let trial = develop(&self.members[parent], &members[k], c, t, zone.deduction());
        if trial.flipped != members[k].flipped {
            for (m, s) in members.iter_mut().zip(&mut shapes) {
                *m = m.flip(t);
                *s = s.iter().map(mirror_y).collect();
            }
        }
        let placed = develop(&self.members[parent], &members[k], c, t, zone.deduction());
        let motion = members[k].place.inverse().then(&placed.place);
        for (m, s) in members.iter_mut().zip(&mut shapes) {
            m.place = m.place.then(&motion);
            *s = s.iter().map(|p| motion.apply_polygon(p)).collect();
        }
        (members, shapes, k)
    }

    /// Per staying plate, the first moving plate whose developed shapes overlap it by more
    /// than t²/2 (pairs in `staying` order); the parent and the child may overlap inside
    /// `strip` (the bend deduction), and the parent is compared by its new shape.
    fn overlaps(
        &self,
        staying: &[usize],
        moving: &[usize],
        shapes: &[Vec<Polygon>],
        (parent, child, parent_shape, strip): (usize, usize, &Vec<Polygon>, &Polygon),
        t: f64,
    ) -> Result<Vec<(usize, usize)>, GridError> {
        let mut found = Vec::new();
        for &p in staying {
            let mine = if p == parent { parent_shape } else { &self.flat[p] };
            for (j, &q) in moving.iter().enumerate() {
                if !boxes_meet(mine, &shapes[j]) {
                    continue;
                }
                let mut shared = intersection(mine, &shapes[j])?;
                if p == parent && q == child {
                    shared = difference(&shared, std::slice::from_ref(strip))?;
                }
                if total_area(&shared) > 0.5 * t * t {
                    found.push((p, q));
                    break;
                }
            }
        }
        Ok(found)
    }

    /// Whether plate `p` keeps a flat segment of at least a fifth of its area beyond the zone
    /// edges of its bends and `more`: a plate that is all bend zone has no rigid piece to
    /// place it by.
    fn keeps_a_segment(&self, p: usize, member: &Member, more: HalfPlane) -> Result<bool, GridError> {
        let plate = &self.plates[p];
        let mut shape = vec![member.local(&plate.polygon)];
        for h in self.tangents[p].iter().chain([&more]) {
            shape = h.cut(member, plate.thickness, &shape)?;
        }
        Ok(total_area(&shape) >= 0.2 * plate.area)
    }

    /// Plate `p`'s shape cut at its bend lines and `more`, on the flat of `member`.
    fn developed(&self, p: usize, member: &Member, more: &[HalfPlane]) -> Result<Vec<Polygon>, GridError> {
        laid_flat(&self.plates[p], member, self.cuts[p].iter().chain(more))
    }

    /// The strip along the bend where the parent's and the child's developed shapes overlap
    /// by design (the bend deduction), on the flat.
    fn strip(&self, parent: &Member, c: &Candidate, p: usize, t: f64, deduction: f64) -> Polygon {
        let into = c.into[c.side_of(p)];
        let at = |along: f64, across: f64| parent.to_flat(t, c.point + c.axis * along + into * across);
        let (lo, hi) = (c.span.0 - 4.0 * t, c.span.1 + 4.0 * t);
        let (near, far) = (-0.05, deduction + 0.05);
        let mut strip = Polygon::new(vec![at(lo, near), at(hi, near), at(hi, far), at(lo, far)]);
        strip.normalize_orientation();
        strip
    }

    /// Whether the shapes' bounding box fits the sheet, either way round.
    fn fits<'s>(&self, shapes: impl Iterator<Item = &'s Vec<Polygon>>) -> bool {
        fits_sheet(shapes, self.sheet)
    }
}

/// `plate`'s shape as `member` keeps it (cut by `halves`), on the member's flat.
pub(crate) fn laid_flat<'h>(
    plate: &Plate,
    member: &Member,
    halves: impl IntoIterator<Item = &'h HalfPlane>,
) -> Result<Vec<Polygon>, GridError> {
    let mut shape = vec![member.local(&plate.polygon)];
    for h in halves {
        shape = h.cut(member, plate.thickness, &shape)?;
    }
    Ok(shape.iter().map(|s| member.place.apply_polygon(s)).collect())
}

/// Whether the bounding box of `shapes` fits a `sheet` (width, height), either way round.
pub(crate) fn fits_sheet<'s>(shapes: impl Iterator<Item = &'s Vec<Polygon>>, (w, h): (f64, f64)) -> bool {
    let (lo, hi) = platener_geom::polygon::bounds_of(shapes.flatten().flat_map(|p| p.outer.iter().copied()));
    let size = hi - lo;
    (size.x <= w && size.y <= h) || (size.x <= h && size.y <= w)
}

/// Whether the bounding boxes of two sets of shapes overlap.
fn boxes_meet(a: &[Polygon], b: &[Polygon]) -> bool {
    let bounds = |s: &[Polygon]| platener_geom::polygon::bounds_of(s.iter().flat_map(|p| p.outer.iter().copied()));
    let ((alo, ahi), (blo, bhi)) = (bounds(a), bounds(b));
    alo.cmple(bhi).all() && blo.cmple(ahi).all()
}
