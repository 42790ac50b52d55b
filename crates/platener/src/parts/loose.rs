//! Loose fragments: plates that no joint holds.
//!
//! A small face inside a wall (the side of a connector cut-out in an enclosure's end wall)
//! becomes a plate of its own that meets nothing: cut, it would be a loose chip the maker
//! cannot place. Such a plate, when it is small next to the plan's largest, is left out with
//! a warning naming it; a larger plate no joint holds is kept (it may be a body of its own)
//! and named in a warning too.

use crate::bends::Bends;
use crate::context::{StepContext, WarningKind};
use crate::joints::Joints;
use crate::plates::Plates;

/// A plate no joint holds is dropped below this share of the largest plate's area.
pub(crate) const FRAGMENT_SHARE: f64 = 0.1;

/// The part id of each plate (numbered from 1 in plate order, skipping dropped fragments),
/// `None` for a dropped one; warns about every plate no joint holds, but those `glued` on
/// (raised details of a thinner sheet). The plates of one bent part share its id (its first
/// plate's).
pub(super) fn part_ids(
    plates: &Plates,
    (joints, bends): (Option<&Joints>, Option<&Bends>),
    glued: &std::collections::BTreeSet<usize>,
    cx: &mut StepContext<'_>,
) -> Vec<Option<u32>> {
    let mut held = held(plates, joints);
    for &p in glued {
        held[p] = true;
    }
    let bent_of = |i: usize| bends.and_then(|b| b.member_of(i)).map(|(k, _)| k);
    let mut bent_ids: std::collections::BTreeMap<usize, u32> = std::collections::BTreeMap::new();
    for (i, h) in held.iter_mut().enumerate() {
        *h |= bent_of(i).is_some();
    }
    let largest = plates.plates.iter().map(|p| p.area).fold(0.0, f64::max);
    let absorbed = bends.map(Bends::absorbed).unwrap_or_default();
    let mut next = 0;
    let mut ids = Vec::with_capacity(plates.plates.len());
    for (i, p) in plates.plates.iter().enumerate() {
        // A fillet's facet whose arc zone a bent part bends in its place.
        if absorbed.contains(&(i as u32)) {
            ids.push(None);
            continue;
        }
        if let Some(id) = bent_of(i).and_then(|k| bent_ids.get(&k)) {
            ids.push(Some(*id));
            continue;
        }
        let (lo, hi) = p.polygon.bounds();
        let size = format!("{:.1} × {:.1} mm", hi.x - lo.x, hi.y - lo.y);
        if !held[i] && p.area < FRAGMENT_SHARE * largest {
            cx.warn(
                WarningKind::Joints,
                format!(
                    "plate {} ({size}) is held by no joint and is a small fragment: left out",
                    i + 1
                ),
            );
            ids.push(None);
            continue;
        }
        next += 1;
        if let Some(k) = bent_of(i) {
            bent_ids.insert(k, next);
        }
        if !held[i] {
            cx.warn_part(
                WarningKind::Joints,
                Some(next),
                format!("part {next} ({size}) is held by no joint: glue it or fix it in place"),
            );
        }
        ids.push(Some(next));
    }
    ids
}

/// Whether each plate is held: every plate when there are no joints to judge by (or only one
/// plate), else the plates of some connection.
fn held(plates: &Plates, joints: Option<&Joints>) -> Vec<bool> {
    let n = plates.plates.len();
    let Some(joints) = joints.filter(|_| n > 1) else {
        return vec![true; n];
    };
    let mut held = vec![false; n];
    for c in &joints.connections {
        for p in c.plates {
            held[p as usize] = true;
        }
    }
    held
}
