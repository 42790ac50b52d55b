//! The one assembly analysis: which parts the joints really hold together, which joints do
//! not meet, which parts share volume, and how much of the model's surface the parts stand
//! for. `convert` (its report and the best method), the score and `verify` all read this one
//! result, so they cannot disagree about a plan.

use serde::Serialize;

use super::{Solid, UnionFind, sample};
use crate::mesh::Mesh;
use crate::plan::{JointKind, Plan, PlanJoint};

/// Model surface within half the thickest part's thickness plus this (mm) of a part counts as
/// covered: a wall cut from a sheet sits at most half a sheet from the face it stands for, and
/// the weld and the kerf move faces by less than half a millimetre.
pub const COVER_SLACK: f64 = 0.5;

/// Two parts that share volume.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Interference {
    /// The parts' ids.
    pub parts: [u32; 2],
    /// Shared volume, mm³.
    pub volume: f64,
    /// Whether the overlap is intended: the two parts are joined by a JimJoint, whose barbs
    /// squeeze through and snap behind the partner, or by a tab in a slot with crush ribs
    /// (the `crush_ribs` setting), which the tab crushes going in.
    pub intended: bool,
}

/// What the plan's parts make when assembled, measured once for everyone who judges the plan.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Analysis {
    /// Parts rebuilt from the plan.
    pub parts: usize,
    /// Their total volume, mm³.
    pub parts_volume: f64,
    /// The sampling step, mm (a third of the thinnest part, at most 1 mm).
    pub step: f64,
    /// Pairs of parts that share volume, largest first (the intended overlap of JimJoints'
    /// barbs included).
    pub interference: Vec<Interference>,
    /// Shared volume over the parts' volume, JimJoints' barbs left out (they overlap on
    /// purpose: they squeeze through and snap behind the partner).
    pub interference_share: f64,
    /// Groups of parts held together by joints that meet: part ids ascending, groups by their
    /// first id. A part no joint holds is a group of its own.
    pub groups: Vec<Vec<u32>>,
    /// Labels of joints whose two parts do not meet (they hold nothing).
    pub joints_not_meeting: Vec<u32>,
    /// The model's separate solids, when the model was given (at least 1).
    pub model_solids: Option<usize>,
    /// The distance within which a part covers the model's surface, mm.
    pub cover_distance: f64,
    /// Share of the model's surface within `cover_distance` of a part, when the model was given.
    pub surface_covered: Option<f64>,
    /// Share of the parts' volume inside the model, when the model was given: the tie-break
    /// between methods scored alike (measured on the same cells as the rest, at most
    /// [`sample::VOLUME_SAMPLES`] of them).
    pub volume_inside: Option<f64>,
}

impl Analysis {
    /// The number of groups the joints hold together.
    pub fn group_count(&self) -> usize {
        self.groups.len()
    }

    /// The fewest groups the parts may form: one per solid of the model (1 without a model).
    pub fn allowed_groups(&self) -> usize {
        self.model_solids.unwrap_or(1).max(1)
    }

    /// Groups beyond those the model has: the smaller groups, part ids ascending (the largest
    /// `allowed_groups` groups are the model's own).
    pub fn extra_groups(&self) -> Vec<&[u32]> {
        let mut by_size: Vec<&[u32]> = self.groups.iter().map(Vec::as_slice).collect();
        // Stable: equal sizes keep the order of their first id.
        by_size.sort_by_key(|g| std::cmp::Reverse(g.len()));
        let mut extra: Vec<&[u32]> = by_size.into_iter().skip(self.allowed_groups()).collect();
        extra.sort_by_key(|g| g[0]);
        extra
    }

    /// How much of the assembly hangs together: (parts − groups) / (parts − solids), the share
    /// of the connections needed to make one group per solid of the model; 1 when there are no
    /// more parts than solids, 0 for no parts.
    pub fn connectivity(&self) -> f64 {
        let (n, g, s) = (self.parts, self.group_count(), self.allowed_groups());
        match n {
            0 => 0.0,
            _ if n <= s => 1.0,
            // A spanning forest of g trees over n parts has n − g connections.
            _ => (n.saturating_sub(g) as f64 / (n - s) as f64).min(1.0),
        }
    }
}

/// The distance within which a part covers the model's surface for `plan`.
pub fn cover_distance(plan: &Plan) -> f64 {
    plan.parts.iter().map(|p| p.thickness).fold(0.0, f64::max) / 2.0 + COVER_SLACK
}

/// Analyses the assembly `plan` describes, against `model` when given (its solids and how much
/// of its surface the parts cover).
pub fn analyse(plan: &Plan, model: Option<&Mesh>) -> Analysis {
    let solids: Vec<Solid> = plan.parts.iter().map(Solid::from_part).collect();
    let step = sample::step_for(&solids);
    let cells: Vec<_> = solids.iter().map(|s| sample::cells(s, step)).collect();
    let parts_volume: f64 = solids.iter().map(|s| s.volume).sum();
    let mut interference = sample::interference(&solids, &cells);
    for i in &mut interference {
        let pair = i.parts;
        let ribs = plan.settings.cut.crush_ribs;
        i.intended = plan.joints.iter().any(|j| {
            let squeezed = j.kind == JointKind::Jim || (ribs && j.kind == JointKind::Slot);
            squeezed && (j.parts == pair || j.parts == [pair[1], pair[0]])
        });
    }
    interference.sort_by(|a, b| b.volume.total_cmp(&a.volume).then(a.parts.cmp(&b.parts)));
    let shared: f64 = interference.iter().filter(|i| !i.intended).map(|i| i.volume).sum();
    let interference_share = if parts_volume > 0.0 {
        (shared / parts_volume).max(0.0) + 0.0 /* −0 → +0 */
    } else {
        0.0
    };
    let (groups, joints_not_meeting) = held_together(plan, &solids, &cells, step);
    let cover = cover_distance(plan);
    Analysis {
        parts: solids.len(),
        parts_volume,
        step,
        interference,
        interference_share,
        groups,
        joints_not_meeting,
        model_solids: model.map(|m| m.health.solids.max(1)),
        cover_distance: cover,
        surface_covered: model.map(|m| sample::surface_covered(m, &solids, cover)),
        volume_inside: model.map(|m| sample::volume_inside(m, &cells)),
    }
}

/// Whether `joint` is a bend between plates merged into one bent part of the plan.
fn merged_plates(plan: &Plan, joint: &PlanJoint) -> bool {
    joint.kind == JointKind::Bend
        && plan
            .parts
            .iter()
            .any(|p| joint.parts.iter().all(|id| p.merged.contains(id)))
}

/// The groups of parts the joints that meet hold together, and the joints whose parts do not
/// meet (or name a part the plan does not have; bends between merged plates excepted).
fn held_together(
    plan: &Plan,
    solids: &[Solid],
    cells: &[(Vec<glam::DVec3>, f64)],
    step: f64,
) -> (Vec<Vec<u32>>, Vec<u32>) {
    let index = |id: u32| solids.iter().position(|s| s.id == id);
    let mut group = UnionFind::new(solids.len());
    let mut not_meeting = Vec::new();
    for j in &plan.joints {
        let (Some(a), Some(b)) = (index(j.parts[0]), index(j.parts[1])) else {
            // A bend joint names the plates merged into a bent part, not parts: the part is
            // one piece already, so it joins nothing.
            if !merged_plates(plan, j) {
                not_meeting.push(j.label);
            }
            continue;
        };
        if a == b {
            // A seam (finger or flap) closing a bent part on itself: nothing to join.
            continue;
        }
        // Sampled inside each part in turn: a slot opening onto one part's edge may only be
        // seen from the other.
        let (sa, sb) = (&solids[a], &solids[b]);
        if sample::meet(sa, &cells[a].0, sb, step) || sample::meet(sb, &cells[b].0, sa, step) {
            group.join(a, b);
        } else {
            not_meeting.push(j.label);
        }
    }
    let mut members: std::collections::BTreeMap<usize, Vec<u32>> = std::collections::BTreeMap::new();
    for (i, s) in solids.iter().enumerate() {
        members.entry(group.root(i)).or_default().push(s.id);
    }
    let mut groups: Vec<Vec<u32>> = members.into_values().collect();
    for g in &mut groups {
        g.sort_unstable();
    }
    groups.sort_by_key(|g| g[0]);
    (groups, not_meeting)
}
