//! A bent part made flat: the jointed outlines of its plates laid out as the `bends` step
//! placed them and united into one part, with its segments, bend lines and bend marks, and
//! for paper and card a glue flap on each seam. The `joints` step builds it to decide which
//! bent parts hold together once jointed; the `parts` step builds it to cut.

use glam::DVec2;
use platener_geom::GridError;
use platener_geom::boolean::{difference, union, union_all};
use platener_geom::polygon::Polygon;

use super::{BentPart, HalfPlane, Member, Seam};
use crate::plan::{Bend, BendStyle, EdgeLabel, Mark, Part, PartKind, Segment};
use crate::plates::Plates;

/// The bent part `bent` as part `id`: `outlines` are the plates' outlines with their joints,
/// `labels` their jointed edges (per plate, in its frame), `marks_of` a plate's own marks
/// (features) in its frame. Also says what went wrong on the way: the flat shape falling
/// into pieces (joints cutting a plate apart near a bend), a bend whose marks could not be
/// drawn.
pub fn flat_part(
    id: u32,
    bent: &BentPart,
    plates: &Plates,
    outlines: &[&Polygon],
    labels: &[Vec<(u32, [DVec2; 2])>],
    marks_of: &dyn Fn(u32, &Polygon) -> Vec<Mark>,
    style: BendStyle,
) -> Result<(Part, Vec<String>), GridError> {
    let t = plates.plates[bent.members[0].plate as usize].thickness;
    let flaps = matches!(style, BendStyle::Perforation | BendStyle::Score);
    let mut pieces = Vec::new();
    let mut developed = Vec::new();
    for (i, m) in bent.members.iter().enumerate() {
        let mut cuts = bent.cuts[i].clone();
        if flaps {
            cuts.extend(bent.seams.iter().filter_map(|s| seam_cut(s, i)));
        }
        let own = m.local(&plates.plates[m.plate as usize].polygon);
        let mut shape = vec![m.local(outlines[i])];
        for h in &cuts {
            shape = union(&shape, &reach_to_line(h, m, t, &own)?)?;
        }
        for h in cuts.iter().chain(bent.splits_of(i)) {
            shape = h.cut(m, t, &shape)?;
        }
        let flat: Vec<Polygon> = shape.iter().map(|p| m.place.apply_polygon(p)).collect();
        pieces.extend(flat.iter().cloned());
        developed.push(flat);
    }
    let mut extra_segments = Vec::new();
    if flaps {
        for seam in &bent.seams {
            let (flap, segment) = flap(seam, &bent.members, t);
            pieces.push(flap);
            extra_segments.push(segment);
        }
    }
    // Plates laid side by side meet along lines and at corners where their jointed outlines
    // only touch; closing by a tenth of the thickness makes one clean outline of them.
    let mut united = platener_geom::offset::closing(&union_all(&pieces)?, 0.1 * t)?;
    united.sort_by(|a, b| b.area().total_cmp(&a.area()));
    let mut notes = Vec::new();
    if united.len() > 1 {
        notes.push(format!(
            "bent part {id} fell apart into {} pieces when laid flat; only the largest is cut",
            united.len()
        ));
    }
    let polygon = united.into_iter().next().unwrap_or_default();
    let mut segments = Vec::with_capacity(bent.members.len());
    // Each member's largest piece is its segment (bends name them by member); other pieces
    // follow, then the flaps.
    for (i, m) in bent.members.iter().enumerate() {
        let mut pieces = segment(bent, i, m, (&developed[i], &polygon), t)?.into_iter();
        segments.extend(pieces.next());
        extra_segments.splice(0..0, pieces);
    }
    segments.extend(extra_segments);
    let bends = bent
        .bends
        .iter()
        .map(|b| Bend {
            line: b.line,
            angle_deg: b.enclosed_deg,
            style,
            pattern: b.zone.design.pattern,
            width: b.zone.width(),
            segments: b.members,
        })
        .collect();
    let mut marks = Vec::new();
    for (k, b) in bent.bends.iter().enumerate() {
        match crate::hinge::marks(&b.zone.design, b.line, &polygon) {
            Ok(m) => marks.extend(m),
            Err(e) => notes.push(format!("bent part {id}: bend {} has no marks: {e}", k + 1)),
        }
    }
    let mut part = Part::plate(id, t, polygon, bent.members[0].flat_frame());
    part.marks = marks;
    part.kind = PartKind::Bent;
    part.segments = segments;
    part.bends = bends;
    add_member_marks(&mut part, bent, outlines, labels, marks_of);
    Ok((part, notes))
}

/// The gap between a plate (`own`, in the member's frame) and a line it is cut at: plate
/// finding may have trimmed it up to a couple of thicknesses short of the line where its
/// neighbour's slab was, or it stops where a fillet's facets begin (`h.gap`), and the flat
/// part must be whole across the bend. The hull of its corners near the line and their feet
/// on the line, less the plate itself (so notches that joints cut near the line stay open).
fn reach_to_line(h: &HalfPlane, m: &Member, t: f64, own: &Polygon) -> Result<Vec<Polygon>, GridError> {
    let mid = m.mid(t);
    let origin = mid.to_2d(h.point);
    let into = DVec2::new(mid.u.dot(h.into), mid.v.dot(h.into)).normalize();
    let mut points = Vec::new();
    for q in &own.outer {
        let s = (*q - origin).dot(into);
        if s.abs() <= 2.0 * t + h.gap {
            points.extend([*q, *q - into * s]);
        }
    }
    if points.len() < 3 {
        return Ok(Vec::new());
    }
    let hull = Polygon::new(platener_geom::polygon::convex_hull(&points));
    if hull.area() <= 0.0 {
        return Ok(Vec::new());
    }
    difference(std::slice::from_ref(&hull), std::slice::from_ref(own))
}

/// The members' connection labels and own marks (features), laid into the flat part.
fn add_member_marks(
    part: &mut Part,
    bent: &BentPart,
    outlines: &[&Polygon],
    labels: &[Vec<(u32, [DVec2; 2])>],
    marks_of: &dyn Fn(u32, &Polygon) -> Vec<Mark>,
) {
    let t = part.thickness;
    for (i, m) in bent.members.iter().enumerate() {
        let local = |q: DVec2| if m.flipped { DVec2::new(q.x, -q.y) } else { q };
        let to_flat = |q: DVec2| m.place.apply(local(q));
        // A wall cut in two carries each label and mark on the half it lies on.
        let kept = |path: &[DVec2]| {
            let Some(q) = path.first() else { return true };
            let at = m.mid(t).to_model_2d(local(*q));
            bent.splits_of(i).all(|h| (at - h.point).dot(h.into) >= 0.0)
        };
        part.edge_labels.extend(
            labels[i]
                .iter()
                .filter(|(_, ends)| kept(&[(ends[0] + ends[1]) / 2.0]))
                .map(|&(connection, [a, b])| EdgeLabel {
                    connection,
                    segment: [to_flat(a), to_flat(b)],
                }),
        );
        part.marks.extend(
            marks_of(m.plate, outlines[i])
                .into_iter()
                .filter(|mark| kept(&mark.path))
                .map(|mut mark| {
                    mark.path = mark.path.iter().map(|q| to_flat(*q)).collect();
                    mark
                }),
        );
    }
}

/// Member `i`'s flat segments: its developed shape beyond the zone edge of each of its
/// bends, largest first (joints may leave more than one piece; all share the member's frame).
fn segment(
    bent: &BentPart,
    i: usize,
    m: &Member,
    (developed, flat): (&[Polygon], &Polygon),
    t: f64,
) -> Result<Vec<Segment>, GridError> {
    // The flat part's material near the member (closing the outline may have filled a
    // little beside the member's own shape), so segments and zones make up the whole part.
    let near = platener_geom::offset::offset(developed, 0.25 * t)?;
    let mine = platener_geom::boolean::intersection(&near, std::slice::from_ref(flat))?;
    let mut local: Vec<Polygon> = mine.iter().map(|p| m.place.inverse().apply_polygon(p)).collect();
    for b in bent.bends.iter().filter(|b| b.members.contains(&i)) {
        let side = usize::from(b.members[1] == i);
        local = b.tangents[side].cut(m, t, &local)?;
    }
    local.sort_by(|a, b| b.area().total_cmp(&a.area()));
    if local.is_empty() {
        local.push(Polygon::default());
    }
    let frame = m.flat_frame();
    Ok(local
        .iter()
        .map(|p| Segment {
            polygon: if p.outer.is_empty() {
                p.clone()
            } else {
                m.place.apply_polygon(p)
            },
            frame,
        })
        .collect())
}

/// The cut of member `i` at a seam it is on (paper and card: both sides end at the line
/// and a flap joins them).
fn seam_cut(seam: &Seam, i: usize) -> Option<HalfPlane> {
    let side = seam.members.iter().position(|&k| k == i)?;
    let c = &seam.meeting;
    Some(HalfPlane {
        point: c.point,
        axis: c.axis,
        into: c.into[side],
        gap: c.gap,
    })
}

/// The glue flap of a seam: a trapezoid on the first member's edge, folded along the seam to
/// lie against the inside of the second member's face; as a flat polygon and a segment.
fn flap(seam: &Seam, members: &[Member], t: f64) -> (Polygon, Segment) {
    let c = &seam.meeting;
    let (a, b) = (&members[seam.members[0]], &members[seam.members[1]]);
    let out = -c.into[0];
    let len = c.span.1 - c.span.0;
    let h = (0.25 * len).clamp(4.0 * t, 12.0).min(len / 3.0);
    let at = |along: f64, across: f64| a.to_flat(t, c.point + c.axis * along + out * across);
    let mut polygon = Polygon::new(vec![
        at(c.span.0, -0.01),
        at(c.span.1, -0.01),
        at(c.span.1 - h, h),
        at(c.span.0 + h, h),
    ]);
    polygon.normalize_orientation();
    // The flap folds like a sharp bend onto b's plane, then steps a thickness to its inside.
    let folded = super::fold_sharp(a, b, c, t);
    let inside = c.into[0].dot(folded.frame.n);
    let frame = folded.flat_frame().shifted(if inside >= 0.0 { t } else { -t });
    let segment = Segment {
        polygon: polygon.clone(),
        frame,
    };
    (polygon, segment)
}
