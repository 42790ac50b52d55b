//! Closing a wrap across a fillet. A ring of walls joined by fillets (a rounded tray) bends
//! at every fillet but one: the last closes the ring and stays a seam. At a sharp corner a
//! joint closes the seam; across a fillet the walls stop short of each other and nothing
//! would (the tray kept one open corner). So the ring is cut open in the middle of one of
//! the seam's walls instead: that wall becomes two members of the part, one at each end of
//! the flat strip, and the fillet bends like the others. The two halves butt where the wall
//! was cut, each held by the joints along its edges (a tray's bottom), as the ends of a
//! maker's flex box are.

use glam::DVec3;
use platener_geom::GridError;
use platener_geom::boolean::intersection;
use platener_geom::polygon::{Polygon, total_area};

use super::find::Candidate;
use super::grow::{HalfPlane, fits_sheet, laid_flat};
use super::unfold::{Member, develop};
use super::zone::BendZone;
use super::{BentPart, Split, bend_line};
use crate::plates::Plate;

/// Closes every seam of `part` that lies across a fillet and has a zone (`zone_of` the
/// candidate), when the wall cut in two lays flat without overlapping the rest and the part
/// still fits the `sheet`.
pub(crate) fn close_fillet_seams(
    part: &mut BentPart,
    plates: &[Plate],
    zone_of: &dyn Fn(&Candidate) -> Result<BendZone, String>,
    sheet: (f64, f64),
) -> Result<(), GridError> {
    let mut k = 0;
    while k < part.seams.len() {
        let seam = &part.seams[k];
        let split = part.splits.iter().any(|s| seam.members.contains(&s.member));
        match zone_of(&seam.meeting) {
            Ok(zone) if seam.meeting.gap > 0.0 && !split => {
                if let Some(closed) = closed(part, k, zone, plates, sheet)? {
                    *part = closed;
                    continue;
                }
            }
            _ => {}
        }
        k += 1;
    }
    Ok(())
}

/// `part` with seam `k` bent by `zone` and the larger of its two walls cut in two, or `None`
/// when that does not lay flat.
fn closed(
    part: &BentPart,
    k: usize,
    zone: BendZone,
    plates: &[Plate],
    sheet: (f64, f64),
) -> Result<Option<BentPart>, GridError> {
    let seam = &part.seams[k];
    let c = &seam.meeting;
    let area = |i: usize| plates[part.members[i].plate as usize].area;
    let (x, y) = if area(seam.members[0]) >= area(seam.members[1]) {
        (seam.members[0], seam.members[1])
    } else {
        (seam.members[1], seam.members[0])
    };
    let (px, py) = (part.members[x].plate as usize, part.members[y].plate as usize);
    let plate = &plates[px];
    let t = plate.thickness;
    let into_x = c.into[c.side_of(px)];
    let Some(middle) = middle(plate, c.point, into_x) else {
        return Ok(None);
    };
    let half = |into: DVec3| HalfPlane {
        point: middle,
        axis: c.axis,
        into,
        gap: 0.0,
    };
    let at_line = |p: usize| HalfPlane {
        point: c.point,
        axis: c.axis,
        into: c.into[c.side_of(p)],
        gap: c.gap,
    };
    let twin = develop(
        &part.members[y],
        &Member::alone(px as u32, plate.frame),
        c,
        t,
        zone.deduction(),
    );
    let mut out = part.clone();
    let xt = out.members.len();
    out.members.push(twin);
    out.cuts.push(vec![at_line(px)]);
    out.cuts[y].push(at_line(py));
    out.splits.push(Split {
        member: x,
        keep: half(into_x),
    });
    out.splits.push(Split {
        member: xt,
        keep: half(-into_x),
    });
    let index = |p: usize| if p == px { xt } else { y };
    out.bends.push(bend_line(
        c,
        zone,
        py,
        &out.members[y],
        [index(c.plates[0]), index(c.plates[1])],
    ));
    out.seams.remove(k);
    let flats = flats(&out, plates)?;
    if !fits_sheet(flats.iter(), sheet) {
        return Ok(None);
    }
    for (i, shape) in flats.iter().enumerate() {
        if i != xt && total_area(&intersection(shape, &flats[xt])?) > 0.5 * t * t {
            return Ok(None);
        }
    }
    Ok(Some(out))
}

/// The line across `plate` (parallel to a bend line through `point`, `into` pointing away
/// from it) halfway through the plate's extent along `into`, as a point on it.
fn middle(plate: &Plate, point: DVec3, into: DVec3) -> Option<DVec3> {
    let mid = plate.thickness / 2.0;
    let (lo, hi) = plate.polygon.outer.iter().fold((f64::MAX, f64::MIN), |(lo, hi), q| {
        let s = (plate.frame.to_model(q.extend(mid)) - point).dot(into);
        (lo.min(s), hi.max(s))
    });
    (lo < hi).then(|| point + into * (lo + hi) / 2.0)
}

/// Every member's plate cut at its bend lines and split line, laid on the flat part.
fn flats(part: &BentPart, plates: &[Plate]) -> Result<Vec<Vec<Polygon>>, GridError> {
    part.members
        .iter()
        .enumerate()
        .map(|(i, m)| {
            laid_flat(
                &plates[m.plate as usize],
                m,
                part.cuts[i].iter().chain(part.splits_of(i)),
            )
        })
        .collect()
}
