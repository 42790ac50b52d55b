//! Cut order (issue 34): the order of a sheet's paths, for lasers that follow the file.
//!
//! A part whose outline is cut before its holes has dropped or shifted when the holes are cut;
//! engraving a part after it is cut out engraves a loose part. So each part's paths go
//! engraving first, then its slits, then its holes, then its outline; a part lying in another
//! part's hole (nested there on the sheet) comes before that part, whose outline would free it.
//! The parts follow one another along a short path: nearest neighbour from the sheet's origin,
//! improved by 2-opt moves that keep every nested part before its host. Within a part each
//! path starts where the head is nearest: an open path from its nearer end, a closed one at its
//! nearest corner (a vertex where the outline turns by at least [`CORNER_TURN_DEG`], if it has
//! one), where the pierce mark and the seam do not show on a straight edge.
//!
//! The spec keeps one `<g id="part-ID">` per part holding its paths, so the order is per part,
//! not pass by pass over the whole sheet: everything a part needs before its outline frees it
//! still comes first, which is what matters to the part.

use glam::DVec2;
use platener_geom::polygon::ring_contains;
use serde::Serialize;

use crate::draw::svg::SvgGroup;

/// A vertex where a ring turns by at least this much is a corner to start a cut at.
pub const CORNER_TURN_DEG: f64 = 20.0;

/// 2-opt passes over a sheet's parts at most (each pass tries every pair; it stops early
/// when a pass improves nothing).
const TWO_OPT_PASSES: usize = 8;

/// What cutting one sheet in file order costs the laser's head.
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize)]
pub struct CutPath {
    /// Length of cut paths (rings and slits), mm.
    pub cut_length: f64,
    /// Length of engraving, mm.
    pub engrave_length: f64,
    /// Length the head moves with the beam off, from the sheet's origin through every path, mm.
    pub travel_length: f64,
    /// Cut paths started (each pierces the sheet).
    pub pierces: usize,
}

impl CutPath {
    /// The figures the laser's time is made of.
    pub fn sheet_path(&self) -> crate::fabrication::SheetPath {
        crate::fabrication::SheetPath {
            cut: self.cut_length,
            engrave: self.engrave_length,
            travel: self.travel_length,
            pierces: self.pierces,
        }
    }
}

/// Orders the parts of one sheet and the paths within each (see the module docs), and
/// measures the result.
pub fn order_sheet(groups: Vec<SvgGroup>) -> (Vec<SvgGroup>, CutPath) {
    let sequence = part_sequence(&groups);
    let mut slots: Vec<Option<SvgGroup>> = groups.into_iter().map(Some).collect();
    let mut head = DVec2::ZERO;
    let mut path = CutPath::default();
    let mut out = Vec::with_capacity(slots.len());
    for k in sequence {
        let Some(mut g) = slots[k].take() else { continue };
        order_group(&mut g, &mut head, &mut path);
        out.push(g);
    }
    (out, path)
}

/// The order of the parts: nested parts before their hosts, along a short path.
fn part_sequence(groups: &[SvgGroup]) -> Vec<usize> {
    let anchors: Vec<DVec2> = groups.iter().map(anchor).collect();
    let before = nesting_constraints(groups);
    let mut sequence = nearest_neighbour(&anchors, &before);
    two_opt(&mut sequence, &anchors, &before);
    sequence
}

/// Where a part is, for ordering the parts: the middle of its paths' bounds.
fn anchor(g: &SvgGroup) -> DVec2 {
    let paths = g.cut.iter().chain(&g.slits).chain(g.engrave.iter().map(|e| &e.path));
    let (lo, hi) = platener_geom::boxes::bounds2(paths.flatten().copied());
    if lo.x.is_finite() { (lo + hi) / 2.0 } else { DVec2::ZERO }
}

/// `before[b]` lists the parts that must come before part `b`: those lying in one of its
/// holes (a point of their outline inside the hole).
fn nesting_constraints(groups: &[SvgGroup]) -> Vec<Vec<usize>> {
    let mut before = vec![Vec::new(); groups.len()];
    for (b, host) in groups.iter().enumerate() {
        for hole in host.cut.iter().skip(1) {
            for (a, guest) in groups.iter().enumerate() {
                let inside = a != b
                    && guest
                        .cut
                        .first()
                        .and_then(|r| r.first())
                        .is_some_and(|p| ring_contains(hole, *p));
                if inside {
                    before[b].push(a);
                }
            }
        }
    }
    before
}

/// Greedy order from the origin: the nearest part whose nested parts are all placed.
fn nearest_neighbour(anchors: &[DVec2], before: &[Vec<usize>]) -> Vec<usize> {
    let n = anchors.len();
    let mut placed = vec![false; n];
    let mut sequence = Vec::with_capacity(n);
    let mut head = DVec2::ZERO;
    while sequence.len() < n {
        let ready = (0..n).filter(|&k| !placed[k] && before[k].iter().all(|&a| placed[a]));
        let next = ready
            .min_by(|&a, &b| {
                head.distance(anchors[a])
                    .total_cmp(&head.distance(anchors[b]))
                    .then(a.cmp(&b))
            })
            // Nested parts in a cycle (not possible on a valid nesting): take the lowest left.
            .or_else(|| (0..n).find(|&k| !placed[k]))
            .expect("a part is left");
        placed[next] = true;
        sequence.push(next);
        head = anchors[next];
    }
    sequence
}

/// Length of the open tour from the origin through `sequence`'s anchors.
#[cfg(test)]
fn tour(sequence: &[usize], anchors: &[DVec2]) -> f64 {
    let mut head = DVec2::ZERO;
    let mut total = 0.0;
    for &k in sequence {
        total += head.distance(anchors[k]);
        head = anchors[k];
    }
    total
}

/// Whether every part comes after the parts nested in it.
fn keeps_nesting(sequence: &[usize], before: &[Vec<usize>]) -> bool {
    let mut position = vec![0; sequence.len()];
    for (i, &k) in sequence.iter().enumerate() {
        position[k] = i;
    }
    before
        .iter()
        .enumerate()
        .all(|(b, guests)| guests.iter().all(|&a| position[a] < position[b]))
}

/// 2-opt on the open tour: reverses a stretch when that shortens it and keeps the nesting.
fn two_opt(sequence: &mut [usize], anchors: &[DVec2], before: &[Vec<usize>]) {
    let n = sequence.len();
    let at = |s: &[usize], i: usize| if i == 0 { DVec2::ZERO } else { anchors[s[i - 1]] };
    for _ in 0..TWO_OPT_PASSES {
        let mut improved = false;
        for i in 0..n {
            for j in i + 1..n {
                // Reversing i..=j replaces the edges (i−1 → i) and (j → j+1).
                let (a, b, c) = (at(sequence, i), anchors[sequence[i]], anchors[sequence[j]]);
                let d = sequence.get(j + 1).map(|&k| anchors[k]);
                let old = a.distance(b) + d.map_or(0.0, |d| c.distance(d));
                let new = a.distance(c) + d.map_or(0.0, |d| b.distance(d));
                if new < old - 1e-9 {
                    sequence[i..=j].reverse();
                    if keeps_nesting(sequence, before) {
                        improved = true;
                    } else {
                        sequence[i..=j].reverse();
                    }
                }
            }
        }
        if !improved {
            break;
        }
    }
}

/// Orders one part's paths (engraving, slits, holes, outline), each starting nearest the
/// head, and adds them to `path`.
fn order_group(g: &mut SvgGroup, head: &mut DVec2, path: &mut CutPath) {
    g.engrave = order_open(std::mem::take(&mut g.engrave), head, path, false);
    g.slits = order_open(std::mem::take(&mut g.slits), head, path, true);
    let mut rings = std::mem::take(&mut g.cut);
    let outline = (!rings.is_empty()).then(|| rings.remove(0));
    let mut ordered = order_closed(rings, head, path);
    if let Some(outline) = outline {
        ordered.extend(order_closed(vec![outline], head, path));
    }
    g.cut = ordered;
}

/// Open polylines (slits, or engraving of either kind), nearest first, each from its nearer
/// end.
fn order_open<P>(mut lines: Vec<P>, head: &mut DVec2, path: &mut CutPath, cut: bool) -> Vec<P>
where
    P: AsRef<Vec<DVec2>> + AsMut<Vec<DVec2>>,
{
    let mut out = Vec::with_capacity(lines.len());
    while !lines.is_empty() {
        let end_distance = |l: &P| {
            let l = l.as_ref();
            let (a, b) = (l.first().copied().unwrap_or(*head), l.last().copied().unwrap_or(*head));
            head.distance(a).min(head.distance(b))
        };
        let k = (0..lines.len())
            .min_by(|&a, &b| {
                end_distance(&lines[a])
                    .total_cmp(&end_distance(&lines[b]))
                    .then(a.cmp(&b))
            })
            .expect("a line is left");
        let mut item = lines.remove(k);
        let line = item.as_mut();
        let (Some(&first), Some(&last)) = (line.first(), line.last()) else {
            continue;
        };
        if head.distance(last) < head.distance(first) {
            line.reverse();
        }
        let length: f64 = line.windows(2).map(|w| w[0].distance(w[1])).sum();
        path.travel_length += head.distance(line[0]);
        if cut {
            path.cut_length += length;
            path.pierces += 1;
        } else {
            path.engrave_length += length;
        }
        *head = *line.last().expect("not empty");
        out.push(item);
    }
    out
}

/// Closed rings, nearest first, each rotated to start at its corner nearest the head (the
/// head comes back there when the ring closes).
fn order_closed(mut rings: Vec<Vec<DVec2>>, head: &mut DVec2, path: &mut CutPath) -> Vec<Vec<DVec2>> {
    let mut out = Vec::with_capacity(rings.len());
    while !rings.is_empty() {
        let nearest = |r: &Vec<DVec2>| start_corner(r, *head).map_or(f64::INFINITY, |i| head.distance(r[i]));
        let k = (0..rings.len())
            .min_by(|&a, &b| nearest(&rings[a]).total_cmp(&nearest(&rings[b])).then(a.cmp(&b)))
            .expect("a ring is left");
        let mut ring = rings.remove(k);
        let Some(start) = start_corner(&ring, *head) else {
            continue;
        };
        ring.rotate_left(start);
        let n = ring.len();
        let length: f64 = (0..n).map(|i| ring[i].distance(ring[(i + 1) % n])).sum();
        path.travel_length += head.distance(ring[0]);
        path.cut_length += length;
        path.pierces += 1;
        *head = ring[0];
        out.push(ring);
    }
    out
}

/// The index of the corner of `ring` nearest `head` (any vertex, if the ring turns nowhere by
/// [`CORNER_TURN_DEG`]: a circle); `None` for an empty ring.
fn start_corner(ring: &[DVec2], head: DVec2) -> Option<usize> {
    let n = ring.len();
    let min_turn = CORNER_TURN_DEG.to_radians();
    let turn = |i: usize| {
        let (a, b, c) = (ring[(i + n - 1) % n], ring[i], ring[(i + 1) % n]);
        (b - a).angle_to(c - b).abs()
    };
    let by_distance = |a: &usize, b: &usize| {
        head.distance(ring[*a])
            .total_cmp(&head.distance(ring[*b]))
            .then(a.cmp(b))
    };
    (0..n)
        .filter(|&i| n >= 3 && turn(i) >= min_turn)
        .min_by(by_distance)
        .or_else(|| (0..n).min_by(by_distance))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn square(x: f64, y: f64, s: f64) -> Vec<DVec2> {
        vec![
            DVec2::new(x, y),
            DVec2::new(x + s, y),
            DVec2::new(x + s, y + s),
            DVec2::new(x, y + s),
        ]
    }

    fn part(id: u32, rings: Vec<Vec<DVec2>>, engrave: Vec<Vec<DVec2>>) -> SvgGroup {
        SvgGroup {
            id: format!("part-{id}"),
            cut: rings,
            slits: Vec::new(),
            engrave: engrave.into_iter().map(crate::draw::svg::Engraved::text).collect(),
        }
    }

    #[test]
    fn a_part_in_a_hole_comes_first_and_holes_before_outlines() {
        // Part 1: a 100 mm frame with a 60 mm window; part 2 sits in the window; part 3 far away.
        let frame = part(1, vec![square(0.0, 0.0, 100.0), square(20.0, 20.0, 60.0)], Vec::new());
        let inner = part(
            2,
            vec![square(30.0, 30.0, 40.0)],
            vec![vec![DVec2::new(35.0, 50.0), DVec2::new(65.0, 50.0)]],
        );
        let far = part(3, vec![square(200.0, 0.0, 20.0)], Vec::new());
        let (ordered, path) = order_sheet(vec![frame, inner, far]);
        let ids: Vec<&str> = ordered.iter().map(|g| g.id.as_str()).collect();
        let (two, one) = (
            ids.iter().position(|i| *i == "part-2").expect("drawn"),
            ids.iter().position(|i| *i == "part-1").expect("drawn"),
        );
        assert!(two < one, "{ids:?}");
        let frame = &ordered[one];
        assert_eq!(frame.cut.len(), 2);
        assert!(
            (platener_geom::polygon::signed_area(&frame.cut[1]).abs() - 10_000.0).abs() < 1e-9,
            "outline last"
        );
        assert_eq!(path.pierces, 4);
        assert!((path.cut_length - (400.0 + 240.0 + 160.0 + 80.0)).abs() < 1e-9);
        assert!((path.engrave_length - 30.0).abs() < 1e-9);
    }

    #[test]
    fn rings_start_at_the_corner_nearest_the_head() {
        let mut head = DVec2::new(100.0, 100.0);
        let mut path = CutPath::default();
        let rings = order_closed(vec![square(0.0, 0.0, 10.0)], &mut head, &mut path);
        assert_eq!(rings[0][0], DVec2::new(10.0, 10.0));
        assert_eq!(rings[0][1], DVec2::new(0.0, 10.0), "the ring keeps its direction");
        assert!((path.travel_length - DVec2::new(90.0, 90.0).length()).abs() < 1e-9);
        // A 64-gon turns by 5.6° at each vertex: no corner, so the nearest vertex.
        let circle: Vec<DVec2> = (0..64)
            .map(|k| DVec2::from_angle(std::f64::consts::TAU * f64::from(k) / 64.0) * 10.0)
            .collect();
        let mut head = DVec2::new(-50.0, 0.0);
        let rings = order_closed(vec![circle], &mut head, &mut CutPath::default());
        assert!((rings[0][0] - DVec2::new(-10.0, 0.0)).length() < 1e-9);
    }

    #[test]
    fn two_opt_shortens_a_crossing_tour() {
        let anchors = [
            DVec2::new(10.0, 0.0),
            DVec2::new(10.0, 10.0),
            DVec2::new(20.0, 0.0),
            DVec2::new(20.0, 10.0),
        ];
        let before = vec![Vec::new(); 4];
        let mut sequence = vec![0, 3, 1, 2];
        let crossing = tour(&sequence, &anchors);
        two_opt(&mut sequence, &anchors, &before);
        assert!(tour(&sequence, &anchors) < crossing - 1.0, "{sequence:?}");
    }
}
