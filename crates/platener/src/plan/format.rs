//! plan.json, version 2, exactly as in the contract `shared/spec/plan-format.md`.
//!
//! Third-party programs rebuild the assembly from this file, so every field of the spec is
//! here under the spec's name, and nothing is renamed for Rust's sake. All lengths in mm.

use std::collections::BTreeMap;

use glam::DVec2;
use serde::{Deserialize, Serialize};

use super::error::PlanError;
use super::part::{JointKind, Mark, PartKind};
use super::settings::{CutSettings, SettingValue};

/// The value of `format`.
pub const FORMAT: &str = "platener-plan";
/// The value of `version`.
pub const VERSION: u32 = 2;

/// Which conversion method made the parts.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Method {
    /// Plates joined by joints.
    Plate,
    /// Stacked layers on shafts.
    Stacked,
    /// Upright slices crossing in halved slots (an extension of the spec's two values).
    Interlocked,
}

/// The whole plan.json.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Plan {
    /// Always [`FORMAT`].
    pub format: String,
    /// Always [`VERSION`].
    pub version: u32,
    /// "platener" and its version.
    pub generator: String,
    /// The model as converted.
    pub source: PlanSource,
    /// The method used.
    pub method: Method,
    /// The settings of the conversion.
    pub settings: PlanSettings,
    /// Every part, by ascending id.
    pub parts: Vec<PlanPart>,
    /// Every connection.
    pub joints: Vec<PlanJoint>,
    /// Every sheet, by index.
    pub sheets: Vec<PlanSheet>,
    /// Parts that rest on each other in the model but that no joint holds: only glue does
    /// (stacked layers no shaft joins). Not joints: the groups they connect are separate
    /// groups of the assembly. Omitted when empty (docs/decisions.md, "Stacked layers").
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub glued: Vec<Glue>,
    /// The order to assemble the parts in, one step per part (an extension of the spec,
    /// docs/cutting-plans.md; the `assembly` module makes it from the rest of the plan).
    /// Omitted when empty, so plans older than it still parse.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub assembly: Vec<AssemblyStep>,
}

/// One entry of `assembly`: a part added to those already placed, and how it goes in.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct AssemblyStep {
    /// The parts added in this step (one for now).
    pub parts: Vec<u32>,
    /// The unit direction the part moves in to reach its place, in model coordinates, each
    /// component rounded to 1e-6 (`[0, 0, -1]`: lowered from above).
    pub direction: [f64; 3],
    /// Indices into `joints` of the joints this step closes: those between the new part and
    /// parts already placed.
    pub joints: Vec<usize>,
    /// The placed parts the new part is glued to (pairs of `glued`); omitted when none.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub glued: Vec<u32>,
    /// Whether no tested direction was free: the part is interlocked with those placed and
    /// goes in along the least blocked direction (it must be sprung or forced in). Omitted
    /// when false.
    #[serde(default, skip_serializing_if = "is_false")]
    pub forced: bool,
    /// Of a plan in several separate objects (parts no joint or glue connects), the number
    /// of the one this part belongs to, from 1, lowest first: each is built on its own, one
    /// after another (an extension, issue 35). Omitted when the plan is one object.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub subassembly: Option<u32>,
}

fn is_false(b: &bool) -> bool {
    !*b
}

/// One entry of `glued`: two parts touching face to face over `area` mm², to be glued.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Glue {
    /// The two parts' ids, lower layer first.
    pub parts: [u32; 2],
    /// The area over which they touch, mm².
    pub area: f64,
}

/// `source`: the model as converted (after units and scale).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct PlanSource {
    /// The model's name.
    pub name: String,
    /// Its triangle count.
    pub triangles: u64,
    /// Smallest corner of its bounding box, mm.
    pub bbox_min: [f64; 3],
    /// Largest corner of its bounding box, mm.
    pub bbox_max: [f64; 3],
    /// The unit the file's numbers were taken in (`mm`, `cm`, `in`); plans older than this
    /// field were made in mm.
    #[serde(default)]
    pub units: crate::settings::Units,
    /// The extra scale applied to the file's numbers (1 in plans older than this field).
    #[serde(default = "one")]
    pub scale: f64,
}

fn one() -> f64 {
    1.0
}

/// `settings`: the sheet thicknesses, the cutting-plan settings (kerf resolved to a number)
/// and whatever the method records about itself.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct PlanSettings {
    /// The distinct part thicknesses, ascending, mm.
    pub thicknesses: Vec<f64>,
    /// Material, kerf, labels, sheet, margin, spacing, seed, speeds…
    #[serde(flatten)]
    pub cut: CutSettings,
    /// Method-specific settings (joint kind, finger width, units, scale…).
    #[serde(flatten)]
    pub method: BTreeMap<String, SettingValue>,
}

/// One part of `parts`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct PlanPart {
    /// Unique, 1-based; the number engraved on the part.
    pub id: u32,
    /// What it is.
    pub kind: PartKind,
    /// Its thickness, mm.
    pub thickness: f64,
    /// Nominal outer contour in the part's frame, counter-clockwise, not closed.
    pub outline: Vec<DVec2>,
    /// Nominal holes, each clockwise, not closed.
    pub holes: Vec<Vec<DVec2>>,
    /// Rows of `[R | t]`: model point = R · (x, y, z) + t.
    pub transform: [[f64; 4]; 3],
    /// Where the part sits on its sheet.
    pub sheet: SheetPlacement,
    /// Marks in the part's frame: `cut` (slits, cut through, red), `score` (bend lines and
    /// other engraving, blue) and `label`.
    pub marks: Vec<Mark>,
    /// For bent parts only: the plates merged into this part.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub merged: Vec<u32>,
    /// For bent parts only (version 2): the flat pieces between bend zones.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub segments: Vec<PlanSegment>,
    /// For bent parts only (version 2): the bends.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub bends: Vec<PlanBend>,
}

/// `parts[].segments[]` (version 2): a flat region of a bent part and where it sits.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct PlanSegment {
    /// Outer contour in the part's frame, counter-clockwise, not closed.
    pub outline: Vec<DVec2>,
    /// Holes, each clockwise, not closed.
    pub holes: Vec<Vec<DVec2>>,
    /// Rows of `[R | t]`, as the part's `transform`.
    pub transform: [[f64; 4]; 3],
}

/// `parts[].bends[]` (version 2): a bend line of a bent part.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct PlanBend {
    /// The line, two points in the part's frame.
    pub line: [DVec2; 2],
    /// The angle the two sides enclose once bent, degrees.
    pub angle: f64,
    /// How the material is made to bend there.
    pub style: super::part::BendStyle,
    /// Extension: a living hinge's slit pattern; absent for the lattice.
    #[serde(default, skip_serializing_if = "super::part::HingePattern::is_lattice")]
    pub pattern: super::part::HingePattern,
    /// Extension: the width of the bend zone on the flat part, centred on `line`, mm.
    #[serde(default)]
    pub width: f64,
    /// Extension: the indices (into `segments`) of the two segments the bend joins.
    #[serde(default)]
    pub segments: [usize; 2],
}

/// `parts[].sheet`: sheet point = R(rotation) · (x, y) + (`x`, `y`), rotation in degrees.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct SheetPlacement {
    /// Index into `sheets`.
    pub index: u32,
    /// Translation x on the sheet, mm.
    pub x: f64,
    /// Translation y on the sheet, mm.
    pub y: f64,
    /// Rotation in degrees, in [0, 360).
    pub rotation: f64,
}

impl SheetPlacement {
    /// Maps a point of the part's frame onto the sheet.
    pub fn apply(&self, p: DVec2) -> DVec2 {
        let (s, c) = self.rotation.to_radians().sin_cos();
        DVec2::new(c * p.x - s * p.y + self.x, s * p.x + c * p.y + self.y)
    }
}

/// One connection of `joints`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct PlanJoint {
    /// The two parts' ids (for `bend`: the plates before merging).
    pub parts: [u32; 2],
    /// The kind of joint.
    pub kind: JointKind,
    /// The angle enclosed by the plates, degrees.
    pub angle: f64,
    /// The connection number engraved on both parts.
    pub label: u32,
}

/// One sheet of `sheets`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct PlanSheet {
    /// 0-based index, as referenced by `parts[].sheet.index`.
    pub index: u32,
    /// Material thickness, mm.
    pub thickness: f64,
    /// Width, mm (SVG x).
    pub width: f64,
    /// Height, mm (SVG y).
    pub height: f64,
    /// The sheet's SVG file in the ZIP.
    pub file: String,
    /// Where the numbers of this sheet's parts too thin for them went (an extension of the
    /// spec, docs/cutting-plans.md); omitted when every number is on its own part.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub legend: Option<SheetLegend>,
    /// The 100 mm reference square's smallest and largest corner on the sheet, mm (an
    /// extension: with `reference-square` on, when the sheet had room for it).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub reference_square: Option<[[f64; 2]; 2]>,
}

/// `sheets[].legend`: the legend's lines and, when it is engraved on the sheet, its box.
///
/// The legend is engraved beside the parts it explains or not at all (no room there): a
/// legend in the sheet's far corner sends the laser across the sheet and falls off a smaller
/// real sheet. Either way the lines are here, so a reader can print them.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SheetLegend {
    /// The lines, as engraved (`7/8: NUMBER 7 ON PART 8`, `NUMBER ON A TAB: 3 5`).
    pub lines: Vec<String>,
    /// Whether the lines are engraved on the sheet (in its SVG's `<g id="legend">`).
    pub engraved: bool,
    /// The engraved text's box on the sheet, smallest corner, mm; absent when not engraved.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub min: Option<[f64; 2]>,
    /// The engraved text's box on the sheet, largest corner, mm; absent when not engraved.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub max: Option<[f64; 2]>,
}

impl Plan {
    /// The plan as pretty JSON (shortest round-trip floats, so output is deterministic).
    pub fn to_json(&self) -> Result<String, PlanError> {
        serde_json::to_string_pretty(self).map_err(|e| PlanError::write("plan.json", e))
    }

    /// The parts glue must hold (in `glued`), by ascending id, each once.
    pub fn glued_parts(&self) -> Vec<u32> {
        let mut ids: Vec<u32> = self.glued.iter().flat_map(|g| g.parts).collect();
        ids.sort_unstable();
        ids.dedup();
        ids
    }

    /// The groups of parts the joints hold together that only glue (`glued`) holds to
    /// another group: each group's ids ascending, groups by their lowest id. Empty when nothing
    /// is glued. This is what a checker counts as separate groups of the assembly.
    pub fn glued_groups(&self) -> Vec<Vec<u32>> {
        let mut ids: Vec<u32> = self.parts.iter().map(|p| p.id).collect();
        ids.sort_unstable();
        let index = |part: u32| ids.binary_search(&part).ok();
        // Each part's group: the lowest index it is joined to, by repeated relaxation over
        // the joints (plans are small; no union-find in a data module).
        let mut group: Vec<usize> = (0..ids.len()).collect();
        let root = |group: &[usize], mut i: usize| {
            while group[i] != i {
                i = group[i];
            }
            i
        };
        for j in &self.joints {
            if let (Some(a), Some(b)) = (index(j.parts[0]), index(j.parts[1])) {
                let (ra, rb) = (root(&group, a), root(&group, b));
                group[ra.max(rb)] = ra.min(rb);
            }
        }
        let mut roots: Vec<usize> = self
            .glued
            .iter()
            .flat_map(|g| g.parts)
            .filter_map(index)
            .map(|i| root(&group, i))
            .collect();
        roots.sort_unstable();
        roots.dedup();
        roots
            .into_iter()
            .map(|r| {
                (0..ids.len())
                    .filter(|&i| root(&group, i) == r)
                    .map(|i| ids[i])
                    .collect()
            })
            .collect()
    }

    /// What the maker needs to know about glue, in the words the CLI and the page show:
    /// "glue-free" or "needs glue: 3 parts in 2 groups" (issue 31): the parts glue must hold,
    /// and the groups the joints hold that glue puts together. Whether the parts hold together
    /// at all is `verify`'s to say.
    pub fn glue_note(&self) -> String {
        let parts = self.glued_parts().len();
        if parts == 0 {
            return "glue-free".to_string();
        }
        let groups = self.glued_groups().len();
        let plural = |n: usize, word: &str| {
            if n == 1 {
                format!("1 {word}")
            } else {
                format!("{n} {word}s")
            }
        };
        format!("needs glue: {} in {}", plural(parts, "part"), plural(groups, "group"))
    }
}
