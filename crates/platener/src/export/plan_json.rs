//! Building plan.json and the sheets' drawings from the steps' snapshots.

use std::collections::BTreeMap;

use glam::DVec2;

use super::legend::Legend;
use crate::draw::svg::{Engraved, SvgGroup, num};
use platener_geom::Polygon;

use crate::kerf::{CutPaths, open_ring};
use crate::labels::Labels;
use crate::plan::format::{FORMAT, VERSION};
use crate::plan::{
    Bend, CutSettings, MarkKind, Plan, PlanBend, PlanInput, PlanJoint, PlanPart, PlanSegment, PlanSettings, PlanSheet,
    PlanSource, Segment, SettingValue, SheetPlacement,
};
use crate::sheets::Nesting;

/// "platener" and the crate's version, as in plan.json's `generator`.
pub fn generator() -> String {
    format!("platener {}", env!("CARGO_PKG_VERSION"))
}

/// The model name made safe for file names: letters, digits, `.`, `_` and `-` kept, anything
/// else becomes `-`; never empty.
pub fn file_stem(name: &str) -> String {
    let s: String = name
        .chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || matches!(c, '.' | '_' | '-') {
                c
            } else {
                '-'
            }
        })
        .collect();
    let s = s.trim_matches(|c| c == '-' || c == '.').to_string();
    if s.is_empty() { "plan".into() } else { s }
}

/// File names (without extension) of the sheets: `{stem}-{thickness}mm-{n}`, `n` counting
/// from 1 within each thickness, as in the spec's `birdhouse-3mm-1.svg`; a measured sheet by
/// its nominal thickness ([`CutSettings::nominal`]).
pub fn sheet_stems(stem: &str, nesting: &Nesting, settings: &CutSettings) -> Vec<String> {
    let mut out = Vec::with_capacity(nesting.sheets.len());
    let mut count = 0;
    let mut last = f64::NAN;
    for s in &nesting.sheets {
        if s.thickness != last {
            count = 0;
            last = s.thickness;
        }
        count += 1;
        out.push(format!("{stem}-{}mm-{count}", num(settings.nominal(s.thickness))));
    }
    out
}

/// The settings block of plan.json and report.json.
pub fn plan_settings(input: &PlanInput) -> PlanSettings {
    let mut cut = input.settings.clone();
    cut.kerf = Some(input.settings.kerf());
    PlanSettings {
        thicknesses: input.thicknesses(),
        cut,
        method: method_settings(input),
    }
}

/// plan.json for the given snapshots (parts in ascending id order).
/// `extras` are the sheets' legends and reference squares' corners, in the sheets' order.
pub fn build_plan(
    input: &PlanInput,
    cut: &CutPaths,
    labels: &Labels,
    nesting: &Nesting,
    stems: &[String],
    (legends, squares): (&[Option<Legend>], &[Option<[glam::DVec2; 2]>]),
) -> Plan {
    let mut order: Vec<usize> = (0..input.parts.len()).collect();
    order.sort_by_key(|&i| input.parts[i].id);
    let parts = order
        .into_iter()
        .map(|i| {
            let part = &input.parts[i];
            let nominal = &cut.parts[i].nominal;
            let mut marks = part.marks.clone();
            marks.extend(labels.parts[i].marks.iter().cloned());
            PlanPart {
                id: part.id,
                kind: part.kind,
                thickness: part.thickness,
                outline: nominal.outer.clone(),
                holes: nominal.holes.clone(),
                transform: part.frame.matrix(),
                sheet: nesting.placements[i],
                marks,
                merged: part.merged.clone(),
                segments: part.segments.iter().map(plan_segment).collect(),
                bends: part.bends.iter().map(plan_bend).collect(),
            }
        })
        .collect();
    let joints = input
        .joints
        .iter()
        .map(|j| PlanJoint {
            parts: j.parts,
            kind: j.kind,
            angle: j.angle_deg,
            label: j.label,
        })
        .collect();
    let sheets = nesting
        .sheets
        .iter()
        .zip(stems)
        .enumerate()
        .map(|(i, (s, stem))| PlanSheet {
            index: s.index,
            thickness: s.thickness,
            width: s.width,
            height: s.height,
            file: format!("{stem}.svg"),
            legend: legends.get(i).and_then(Option::as_ref).map(Legend::plan),
            reference_square: squares.get(i).copied().flatten().map(|c| c.map(|p| [p.x, p.y])),
        })
        .collect();
    let src = &input.source;
    let mut plan = Plan {
        format: FORMAT.into(),
        version: VERSION,
        generator: generator(),
        source: PlanSource {
            name: src.name.clone(),
            triangles: src.triangles,
            bbox_min: src.bbox_min.to_array(),
            bbox_max: src.bbox_max.to_array(),
            units: src.units,
            scale: src.scale,
        },
        method: input.method,
        settings: plan_settings(input),
        parts,
        joints,
        sheets,
        glued: input.glued.clone(),
        assembly: Vec::new(),
    };
    // The order is made from the finished plan alone, as a reader of plan.json would.
    plan.assembly = crate::assembly::order(&plan);
    plan
}

/// A bent part's segment as in plan.json: rings as the outline's (outer counter-clockwise,
/// holes clockwise, not closed) and the frame as transform rows.
fn plan_segment(segment: &Segment) -> PlanSegment {
    let mut polygon = Polygon {
        outer: open_ring(&segment.polygon.outer),
        holes: segment.polygon.holes.iter().map(|h| open_ring(h)).collect(),
    };
    polygon.normalize_orientation();
    PlanSegment {
        outline: polygon.outer,
        holes: polygon.holes,
        transform: segment.frame.matrix(),
    }
}

/// A bent part's bend as in plan.json.
fn plan_bend(bend: &Bend) -> PlanBend {
    PlanBend {
        line: bend.line,
        angle: bend.angle_deg,
        style: bend.style,
        pattern: bend.pattern,
        width: bend.width,
        segments: bend.segments,
    }
}

fn moved(points: &[DVec2], p: &SheetPlacement) -> Vec<DVec2> {
    points.iter().map(|q| p.apply(*q)).collect()
}

/// The drawing of each sheet: one group per part (ascending id), cut rings and engraving moved
/// by the part's placement.
pub fn sheet_groups(input: &PlanInput, cut: &CutPaths, labels: &Labels, nesting: &Nesting) -> Vec<Vec<SvgGroup>> {
    let mut groups: Vec<Vec<(u32, SvgGroup)>> = vec![Vec::new(); nesting.sheets.len()];
    for (i, part) in input.parts.iter().enumerate() {
        let p = &nesting.placements[i];
        let c = &cut.parts[i];
        // Cut marks come from the kerf step's slits; every other mark is engraved.
        let engrave = part
            .marks
            .iter()
            .chain(&labels.parts[i].marks)
            .filter(|m| m.kind != MarkKind::Cut)
            .map(|m| Engraved {
                path: moved(&m.path, p),
                text: m.kind == MarkKind::Label,
            })
            .collect();
        let g = SvgGroup {
            id: format!("part-{}", part.id),
            cut: std::iter::once(&c.cut.outer)
                .chain(&c.cut.holes)
                .map(|r| moved(r, p))
                .collect(),
            slits: c.slits.iter().map(|l| moved(l, p)).collect(),
            engrave,
        };
        groups[p.index as usize].push((part.id, g));
    }
    groups
        .into_iter()
        .map(|mut gs| {
            gs.sort_by_key(|(id, _)| *id);
            gs.into_iter().map(|(_, g)| g).collect()
        })
        .collect()
}

/// The method's settings for plan.json, without keys the plan's own settings already use: the
/// settings object is flattened, and a repeated key would make plan.json invalid.
fn method_settings(input: &PlanInput) -> BTreeMap<String, SettingValue> {
    let taken: Vec<String> = match serde_json::to_value(&input.settings) {
        Ok(serde_json::Value::Object(map)) => map.keys().cloned().collect(),
        _ => Vec::new(),
    };
    input
        .method_settings
        .iter()
        .filter(|(k, _)| k.as_str() != "thicknesses" && !taken.contains(k))
        .map(|(k, v)| (k.clone(), v.clone()))
        .collect()
}
