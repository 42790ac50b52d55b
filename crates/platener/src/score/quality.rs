//! Joint quality: are the joints' angles the model's, and are the parts plates rather than
//! slivers?
//!
//! A finger joint cut for 154° between two plates that stand for faces at 180° does not close;
//! a tapered strip 2 mm wide breaks when it is pressed into its slots. Both are what welding a
//! precise model too far makes, and both pass every check of the assembly's volume. So:
//!
//! - each part's *model normal* is the area-weighted mean normal of the model's surface within
//!   the cover distance of the part that faces its way (within [`FACING`]), signs aligned;
//!   a part with no such surface has none, and its joints are not judged;
//! - a joint between plates (not a shaft) is off by Δ = |θ(part normals) − θ(model normals)|,
//!   θ the angle between two lines (0°–90°), and scores 1 / (1 + (Δ / [`ANGLE_SCALE`])²);
//! - a part's width w = 2·area / perimeter (exact for a long strip) scores min(1, w / 2t);
//! - the parts' volume inside the model, v, scores 1 − [`FIT_WEIGHT`]·(1 − min(1, v /
//!   [`INSIDE_FULL`])) (issue 32): a 3 mm sheet for a 1.5 mm wall puts half of every wall
//!   outside the model, which the surface, reproduced either way, does not see. Half weight:
//!   a tray whose walls came out thicker still assembles and holds, a frame whose joints are
//!   5° off does not close;
//! - the model's sharp edges the plan keeps ([`super::details`]): raised letters a blank part
//!   drops.

use glam::DVec3;
use serde::Serialize;

use crate::assembly::Solid;
use crate::assembly::sample::surface_samples;
use crate::mesh::Mesh;
use crate::plan::{JointKind, PartKind, Plan};

/// A model face counts for a part when its normal is within 30° of the part's.
pub const FACING: f64 = 30.0;
/// The angle error (degrees) that halves a joint's fidelity: 2° is about where a finger joint
/// in 3 mm plywood no longer closes without force.
pub const ANGLE_SCALE: f64 = 2.0;
/// The share of the parts' volume inside the model that counts as all of it: a true plan
/// loses a little to kerf-free nominal outlines, layers' steps and fingers at rounded corners.
pub const INSIDE_FULL: f64 = 0.9;
/// How much of the quality the volume outside the model can take at most.
pub const FIT_WEIGHT: f64 = 0.5;

/// A joint's angle in the plan against the model's.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct JointAngle {
    /// The joint's label.
    pub label: u32,
    /// The two parts.
    pub parts: [u32; 2],
    /// Angle between the parts' planes, degrees (0–90).
    pub plan: f64,
    /// Angle between the model faces they stand for, degrees (0–90).
    pub model: f64,
}

/// Whether the joints are true to the model and the parts are no slivers.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct QualityScore {
    /// `fidelity × slender × fit × details`.
    pub value: f64,
    /// Mean over the judged joints of 1 / (1 + (Δ/2°)²); 1 when none is judged.
    pub fidelity: f64,
    /// Joints judged (between plates that both stand for model faces).
    pub joints_judged: usize,
    /// The joint furthest from the model's angle, when one was judged.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub worst_joint: Option<JointAngle>,
    /// Share of the parts' volume inside the model, when it was measured.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub inside: Option<f64>,
    /// 1 − [`FIT_WEIGHT`]·(1 − min(1, inside / [`INSIDE_FULL`])); 1 when `inside` was not
    /// measured.
    pub fit: f64,
    /// Area-weighted mean of min(1, w / 2t) over the parts (shafts left out); 1 without parts.
    pub slender: f64,
    /// Parts narrower than their thickness (w < t), ascending.
    pub slivers: Vec<u32>,
    /// The model's sharp edges the plan keeps.
    pub details: super::details::DetailScore,
}

/// Measures the plan's joint quality against `mesh`; `reach` is the cover distance and
/// `inside` the share of the parts' volume inside the model (the assembly analysis'), when
/// known.
pub fn measure(mesh: &Mesh, plan: &Plan, reach: f64, inside: Option<f64>) -> QualityScore {
    let solids: Vec<Solid> = plan.parts.iter().map(Solid::from_part).collect();
    let normals = model_normals(mesh, &solids, reach);
    let index = |id: u32| solids.iter().position(|s| s.id == id);
    let mut angles: Vec<JointAngle> = Vec::new();
    for j in plan.joints.iter().filter(|j| j.kind != JointKind::Shaft) {
        let (Some(a), Some(b)) = (index(j.parts[0]), index(j.parts[1])) else {
            continue;
        };
        if let (Some(ma), Some(mb)) = (normals[a], normals[b]) {
            angles.push(JointAngle {
                label: j.label,
                parts: j.parts,
                plan: line_angle(solids[a].frame().n, solids[b].frame().n),
                model: line_angle(ma, mb),
            });
        }
    }
    let off = |a: &JointAngle| (a.plan - a.model).abs();
    let fidelity = if angles.is_empty() {
        1.0
    } else {
        angles
            .iter()
            .map(|a| 1.0 / (1.0 + (off(a) / ANGLE_SCALE).powi(2)))
            .sum::<f64>()
            / angles.len() as f64
    };
    let worst_joint = angles.iter().max_by(|a, b| off(a).total_cmp(&off(b))).cloned();
    let (slender, slivers) = slenderness(plan);
    let fit = inside.map_or(1.0, |v| 1.0 - FIT_WEIGHT * (1.0 - (v / INSIDE_FULL).clamp(0.0, 1.0)));
    let details = super::details::measure(mesh, plan, &solids, reach);
    QualityScore {
        value: fidelity * slender * fit * details.value,
        fidelity,
        inside,
        fit,
        joints_judged: angles.len(),
        worst_joint,
        slender,
        slivers,
        details,
    }
}

/// The angle between two lines with these directions, degrees in [0, 90].
fn line_angle(a: DVec3, b: DVec3) -> f64 {
    a.normalize_or_zero()
        .dot(b.normalize_or_zero())
        .abs()
        .min(1.0)
        .acos()
        .to_degrees()
}

/// Each part's model normal (see the module documentation), `None` where no model face
/// within `reach` faces the part's way.
fn model_normals(mesh: &Mesh, solids: &[Solid], reach: f64) -> Vec<Option<DVec3>> {
    let mut sums = vec![DVec3::ZERO; solids.len()];
    let facing = FACING.to_radians().cos();
    surface_samples(mesh, reach, |p, w, f| {
        let n = mesh.normals[f];
        for (s, sum) in solids.iter().zip(sums.iter_mut()) {
            let d = n.dot(s.frame().n);
            if d.abs() >= facing && s.within(p, reach) {
                *sum += n * d.signum() * w;
            }
        }
    });
    sums.into_iter()
        .map(|s| (s.length() > 0.0).then(|| s.normalize()))
        .collect()
}

/// The area-weighted slenderness of the parts (shafts left out) and the slivers.
fn slenderness(plan: &Plan) -> (f64, Vec<u32>) {
    let (mut weighted, mut total) = (0.0, 0.0);
    let mut slivers = Vec::new();
    for part in plan.parts.iter().filter(|p| p.kind != PartKind::Shaft) {
        let rings = std::iter::once(&part.outline).chain(&part.holes);
        let area = platener_geom::polygon::signed_area(&part.outline).abs()
            - part
                .holes
                .iter()
                .map(|h| platener_geom::polygon::signed_area(h).abs())
                .sum::<f64>();
        let perimeter: f64 = rings.map(|r| platener_geom::polygon::perimeter(r)).sum();
        if !(area > 0.0 && perimeter > 0.0) {
            continue;
        }
        let width = 2.0 * area / perimeter;
        if width < part.thickness {
            slivers.push(part.id);
        }
        weighted += area * (width / (2.0 * part.thickness)).min(1.0);
        total += area;
    }
    (if total > 0.0 { weighted / total } else { 1.0 }, slivers)
}
