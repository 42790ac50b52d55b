//! Parts their joints left smaller than the smallest part (issue 32).
//!
//! A plate passes the plates step's sieve on its own outline; its joints then cut fingers and
//! slots into it. On a thin curved wall cut from facets (a teacup's), a facet strip 5 mm wide
//! with fingers on both sides is left a chip under a millimetre wide. After the joints are cut
//! and the outlines cleaned, every plate and bent part is held to [`Rule`]; one that fails is
//! left out with its joints, and a warning names it with its size. Dovetail keys are joint
//! pieces, sized by their joint, and are not held to it; a key whose every joint went with a
//! part left out goes too (it would be a loose piece).

use std::collections::BTreeSet;

use rayon::prelude::*;

use crate::context::{StepContext, WarningKind};
use crate::cuttable::{Rule, dovetail_keys};
use crate::plan::{PartKind, PlanInput};

/// Leaves out the plates and bent parts of `input` smaller than the smallest part (at least
/// `min_area` mm² as well), with their joints, and says which in one warning per thickness.
pub(super) fn leave_out_small(input: &mut PlanInput, min_area: f64, cx: &mut StepContext<'_>) {
    let keys = dovetail_keys(input.joints.iter().map(|j| (j.kind, j.parts)));
    // (thickness bits, part id, what is wrong): thickness first, so each sheet's parts group.
    let mut small: Vec<(u64, u32, String)> = input
        .parts
        .par_iter()
        .filter(|p| matches!(p.kind, PartKind::Plate | PartKind::Bent) && !keys.contains(&p.id))
        .filter_map(|p| {
            let rule = Rule::for_sheet(p.thickness, 0.0, min_area);
            let why = rule.check(&p.polygon).ok()?.err()?;
            Some((p.thickness.to_bits(), p.id, why.describe(&rule)))
        })
        .collect();
    if small.is_empty() {
        return;
    }
    small.sort_by(|a, b| a.0.cmp(&b.0).then(a.1.cmp(&b.1)));
    let gone: BTreeSet<u32> = small.iter().map(|(_, id, _)| *id).collect();
    input.parts.retain(|p| !gone.contains(&p.id));
    input.joints.retain(|j| !j.parts.iter().any(|id| gone.contains(id)));
    let loose_keys: Vec<u32> = keys
        .into_iter()
        .filter(|k| !input.joints.iter().any(|j| j.parts.contains(k)))
        .collect();
    input.parts.retain(|p| !loose_keys.contains(&p.id));
    for group in small.chunk_by(|a, b| a.0 == b.0) {
        let thickness = f64::from_bits(group[0].0);
        let rule = Rule::for_sheet(thickness, 0.0, min_area);
        let list: Vec<String> = group.iter().map(|(_, id, why)| format!("{id} ({why})")).collect();
        cx.warn(
            WarningKind::CuttingPlan,
            format!(
                "{} part(s) of {thickness} mm are too small to cut and hold once their joints are cut, and are \
                 left out with their joints: {}. A part needs {:.1} mm of width somewhere and {:.1} mm² of material",
                group.len(),
                list.join(", "),
                rule.min_width,
                rule.min_area
            ),
        );
    }
    if !loose_keys.is_empty() {
        let ids: Vec<String> = loose_keys.iter().map(u32::to_string).collect();
        cx.warn(
            WarningKind::CuttingPlan,
            format!(
                "the dovetail key(s) {} held only parts left out as too small, and are left out with them",
                ids.join(", ")
            ),
        );
    }
}

#[cfg(test)]
mod tests {
    use glam::DVec3;
    use platener_geom::{Frame, Polygon};

    use super::*;
    use crate::context::Cancel;
    use crate::plan::{Joint, JointKind, Method, Part, SourceInfo};

    fn rect(w: f64, h: f64) -> Polygon {
        let mut p = Polygon::new(platener_geom::polygon::rect(0.0, 0.0, w, h));
        p.normalize_orientation();
        p
    }

    fn joint(parts: [u32; 2], kind: JointKind, label: u32) -> Joint {
        Joint {
            parts,
            kind,
            angle_deg: 90.0,
            label,
        }
    }

    #[test]
    fn a_chip_goes_with_its_joints_and_a_key_stays() {
        let frame = Frame::on_plane(DVec3::ZERO, DVec3::Z);
        let parts = vec![
            Part::plate(1, 3.0, rect(60.0, 40.0), frame),
            // 0.7 mm wide: what fingers on both sides leave of a 5 mm facet.
            Part::plate(2, 3.0, rect(0.7, 80.0), frame),
            // 4 × 4 mm: under 25 mm².
            Part::plate(3, 3.0, rect(4.0, 4.0), frame),
            // A dovetail key as small: a joint piece.
            Part::plate(4, 3.0, rect(4.0, 4.0), frame),
            // A key that holds only the chip: loose once the chip goes.
            Part::plate(5, 3.0, rect(4.0, 4.0), frame),
        ];
        let joints = vec![
            joint([1, 2], JointKind::Finger, 1),
            joint([1, 3], JointKind::Finger, 2),
            joint([1, 4], JointKind::Dovetail, 3),
            joint([2, 5], JointKind::Dovetail, 4),
        ];
        let source = SourceInfo {
            name: "chips".into(),
            triangles: 0,
            bbox_min: DVec3::ZERO,
            bbox_max: DVec3::ONE,
            units: crate::settings::Units::Mm,
            scale: 1.0,
            print: None,
        };
        let mut input = PlanInput::new(source, Method::Plate, parts, joints);
        let cancel = Cancel::default();
        let mut cx = StepContext::new("parts", "chips", &cancel);
        leave_out_small(&mut input, crate::cuttable::MIN_AREA, &mut cx);
        let ids: Vec<u32> = input.parts.iter().map(|p| p.id).collect();
        assert_eq!(ids, vec![1, 4]);
        let labels: Vec<u32> = input.joints.iter().map(|j| j.label).collect();
        assert_eq!(labels, vec![3]);
        let warnings = cx.into_warnings();
        assert_eq!(
            warnings.len(),
            2,
            "one warning for the 3 mm parts, one for the loose key"
        );
        assert!(
            warnings[1].message.contains("key(s) 5 held only"),
            "{}",
            warnings[1].message
        );
        let message = &warnings[0].message;
        assert!(message.starts_with("2 part(s) of 3 mm"), "{message}");
        assert!(message.contains("2 (56.0 mm², nowhere 3.0 mm wide)"), "{message}");
        assert!(message.contains("3 (16.0 mm², under 25.0 mm²)"), "{message}");
    }
}
