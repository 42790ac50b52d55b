//! Joints that only fit the right way (Kyub's FoolProofJoint): where an edge of one finger
//! joint would fit an edge of another (the same length, the same fingers) and the parts that
//! would swap are not twins, one of the two joints gets a *key finger* (one segment wider
//! than the rest, at a place along the edge no joint alike has) or two fingers fewer or more.
//!
//! What fits what is read by `verify`'s own check ([`crate::verify::acceptances`]) on the
//! plates as cut, so the step and the check never disagree. Fits between twins (a shelf of
//! identical shelves, a symmetric wall turned round) are harmless and left alone, so twins
//! stay twins unless one of their joints also fits wrongly. A joint that changes takes a cut
//! no joint alike has, so nothing fits it any more; but a changed joint can make two parts
//! that were twins differ, and their fits wrong: the check is read again, a few rounds at
//! most. Keys are counted from the joint's lower end in the model (lowest z, then y, then
//! x); one not in the middle also stops the edge going in turned end for end.

use std::collections::BTreeSet;

use glam::DVec3;

use crate::assembly::UnionFind;
use crate::verify::Acceptance;

/// A wider finger at one place along a joint; the other segments share the rest evenly.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct KeyFinger {
    /// The segment, counted from the start of the joint's range along its axis.
    pub at: usize,
    /// Its width over the even width (the joint's length over its segments).
    pub wide: f64,
}

/// A joint's new cut: its number of segments and its key finger, if any.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Variant {
    /// Fingers of both plates.
    pub segments: usize,
    /// The wider finger.
    pub key: Option<KeyFinger>,
}

/// Rounds of telling joints apart at most: a new key can break a twin another relied on.
pub(super) const ROUNDS: usize = 4;

/// Key widths tried, over the even width: 1.5 first (the others lose least).
const WIDE: [f64; 2] = [1.5, 2.0];
/// A key at least this much (mm) wider than the even width: five times the pattern
/// tolerance of `verify`, so two keys a segment apart never read as the same pattern.
const KEY_EXTRA_MIN: f64 = 1.0;
/// No key (nor even segment of a new count) wider than this many finger widths of the
/// settings.
const KEY_MAX: f64 = 2.0;
/// No other segment narrower than this share of the settings' finger width (nor than the
/// narrowest the joint allows).
const OTHERS_MIN: f64 = 0.5;

/// The `segments + 1` boundaries of the segments over `range`, ascending: even, or with the
/// key finger's segment wider and the others evenly narrower.
pub(super) fn boundaries(range: (f64, f64), segments: usize, key: Option<KeyFinger>) -> Vec<f64> {
    let len = range.1 - range.0;
    let even = len / segments as f64;
    let Some(k) = key.filter(|_| segments > 1) else {
        return (0..=segments).map(|s| range.0 + even * s as f64).collect();
    };
    let wide = k.wide * even;
    let other = (len - wide) / (segments - 1) as f64;
    let mut at = range.0;
    let mut out = Vec::with_capacity(segments + 1);
    out.push(at);
    for s in 0..segments {
        at += if s == k.at { wide } else { other };
        out.push(if s + 1 == segments { range.1 } else { at });
    }
    out
}

/// Whether places along `axis` count from its end: it runs down (then towards −y, then −x).
pub(super) fn from_high(axis: DVec3) -> bool {
    const FLAT: f64 = 1e-6;
    [axis.z, axis.y, axis.x]
        .into_iter()
        .find(|c| c.abs() > FLAT)
        .is_some_and(|c| c < 0.0)
}

/// What the choice knows of a connection.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Look {
    /// Its length along its axis, mm.
    pub len: f64,
    /// Its segments now.
    pub segments: usize,
    /// Its key finger now.
    pub key: Option<KeyFinger>,
    /// The narrowest segment it may have, mm.
    pub narrowest: f64,
    /// The finger width the settings ask for, mm.
    pub target: f64,
    /// Whether it may change: a row of fingers of its own, not adapted to keep a plate whole.
    pub free: bool,
    /// Whether its axis runs down (places count from its end): [`from_high`].
    pub from_high: bool,
}

/// A way to cut a joint: segments, and the key's place (counted from the joint's lower end)
/// and width.
type Cut = (usize, Option<(usize, f64)>);

/// A pattern up to turning end for end: segments, and the key's place from the nearer end
/// and its width in hundredths.
type Identity = (usize, Option<(usize, u32)>);

fn identity((n, key): Cut) -> Identity {
    (
        n,
        key.map(|(place, wide)| (place.min(n - 1 - place), (wide * 100.0).round() as u32)),
    )
}

impl Look {
    /// Whether `cut` keeps every segment of this joint within the limits.
    fn allows(&self, (n, key): Cut) -> bool {
        let even = self.len / n as f64;
        let lowest = self.narrowest.max(OTHERS_MIN * self.target);
        let Some((_, wide)) = key else {
            return even >= lowest && even <= KEY_MAX * self.target;
        };
        let other = (self.len - wide * even) / (n - 1) as f64;
        other >= lowest && wide * even <= KEY_MAX * self.target && (wide - 1.0) * even >= KEY_EXTRA_MIN
    }

    /// The joint's cut now.
    fn now(&self) -> Cut {
        let n = self.segments;
        let place = |at: usize| if self.from_high { n - 1 - at } else { at };
        (n, self.key.map(|k| (place(k.at), k.wide)))
    }

    /// Whether a joint's cut could read like this one's: lengths within twice `verify`'s
    /// length tolerance.
    fn alike(&self, other: &Look) -> bool {
        (self.len - other.len).abs() <= 2.0 * crate::verify::LENGTH_TOL
    }

    /// The ways this joint may be cut other than as it is now, in order of preference: a key
    /// at each place (one of each pair mirrored end for end, counted from the lower end),
    /// 1.5 wide then 2, then two segments fewer or more, even and keyed; within the limits.
    fn cuts(&self) -> Vec<Cut> {
        let mut out = Vec::new();
        for n in [self.segments, self.segments.saturating_sub(2), self.segments + 2] {
            if n < 3 {
                continue;
            }
            if n != self.segments {
                out.push((n, None));
            }
            for wide in WIDE {
                out.extend((0..n.div_ceil(2)).map(|p| (n, Some((p, wide)))));
            }
        }
        out.retain(|&c| self.allows(c) && identity(c) != identity(self.now()));
        out
    }

    /// `cut` as this joint has it: its key counted from its range's start.
    fn variant(&self, (n, key): Cut) -> Variant {
        Variant {
            segments: n,
            key: key.map(|(place, wide)| KeyFinger {
                at: if self.from_high { n - 1 - place } else { place },
                wide,
            }),
        }
    }
}

/// The new cut of each joint (`None`: as it is) so that no two joints' edges fit wrongly
/// (`found`, not interchangeable). Of each such pair one joint changes: the one that may,
/// else the one with fewer harmless fits (a twin among identical shelves stays one), else
/// the later; none where one of the two changes already. Each takes the first way of being
/// cut that no joint alike has: then none fits it, and the changes never undo each other.
/// Joints that fit each other wrongly, directly or through others, change all or none: where
/// one finds no way of its own (too many look-alikes on a short edge), none of them changes,
/// as new fingers would not make the plan foolproof.
pub(super) fn choose(looks: &[Look], found: &[Acceptance]) -> Vec<Option<Variant>> {
    let wrong: Vec<[usize; 2]> = found
        .iter()
        .filter(|a| !a.interchangeable())
        .map(|a| a.joints)
        .collect();
    let change = to_change(looks, found, &wrong);
    let mut identities: Vec<Identity> = looks.iter().map(|l| identity(l.now())).collect();
    let mut out = vec![None; looks.len()];
    let mut stuck = Vec::new();
    for &k in &change {
        let taken: BTreeSet<Identity> = (0..looks.len())
            .filter(|&j| j != k && looks[j].alike(&looks[k]))
            .map(|j| identities[j])
            .collect();
        match looks[k].cuts().into_iter().find(|&c| !taken.contains(&identity(c))) {
            Some(cut) => {
                identities[k] = identity(cut);
                out[k] = Some(looks[k].variant(cut));
            }
            None => stuck.push(k),
        }
    }
    let mut groups = UnionFind::new(looks.len());
    for [x, y] in wrong {
        groups.join(x, y);
    }
    let stuck: BTreeSet<usize> = stuck.into_iter().map(|k| groups.root(k)).collect();
    for (k, new) in out.iter_mut().enumerate() {
        if stuck.contains(&groups.root(k)) {
            *new = None;
        }
    }
    out
}

/// The joints to change: one of each pair in `wrong` (see [`choose`]).
fn to_change(looks: &[Look], found: &[Acceptance], wrong: &[[usize; 2]]) -> BTreeSet<usize> {
    let mut twins = vec![0usize; looks.len()];
    for a in found.iter().filter(|a| a.interchangeable()) {
        for k in a.joints {
            twins[k] += 1;
        }
    }
    let mut change = BTreeSet::new();
    for &[x, y] in wrong {
        if change.contains(&x) || change.contains(&y) {
            continue;
        }
        let pick = match (looks[x].free, looks[y].free) {
            (false, false) => continue,
            (true, false) => x,
            (false, true) => y,
            (true, true) if twins[x] < twins[y] => x,
            (true, true) => y,
        };
        change.insert(pick);
    }
    change
}
