//! The plan: parts with their outlines and transforms, joints and sheets, as in plan.json.
//!
//! [`PlanInput`] is what a method (plate or stacked) hands to the cutting-plan steps: its
//! [`Part`]s and [`Joint`]s, the model they came from and the [`CutSettings`]. It is the
//! pipeline's `parts` snapshot. [`format`] is plan.json itself, written by the `export` step.

pub mod bent;
mod error;
pub mod format;
pub mod laser;
mod part;
pub mod samples;
mod settings;
pub mod stock;

use std::collections::{BTreeMap, BTreeSet};

use glam::DVec3;
use serde::Serialize;

pub use bent::BentError;
pub use error::PlanError;
pub use format::{
    Glue, Method, Plan, PlanBend, PlanJoint, PlanPart, PlanSegment, PlanSettings, PlanSheet, PlanSource, SheetLegend,
    SheetPlacement,
};
pub use laser::{Laser, LaserKind, LaserSpeeds};
pub use part::{
    Bend, BendStyle, EdgeLabel, HingePattern, Joint, JointKind, Mark, MarkKind, MarkSide, Part, PartKind, Segment,
    score_rings,
};
pub use settings::{
    ColorProfile, CutSettings, Fit, LabelMode, MAX_KERF, MAX_MARGIN, Material, MeasuredThickness, NestEffort,
    SPACING_RANGE, SettingValue, SheetSize,
};
pub use stock::StockSheet;

/// The model the parts were made from, for plan.json's `source`.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SourceInfo {
    /// The model's name; also the stem of the sheet files.
    pub name: String,
    /// Its triangle count.
    pub triangles: u64,
    /// Smallest corner of its bounding box, mm.
    pub bbox_min: DVec3,
    /// Largest corner of its bounding box, mm.
    pub bbox_max: DVec3,
    /// The unit the file's numbers were taken in.
    pub units: crate::settings::Units,
    /// The extra scale applied to them.
    pub scale: f64,
    /// Printing it instead; `None` for parts made without a model (tests).
    pub print: Option<PrintEstimate>,
}

/// How long printing the model on an FDM printer would take (`fabrication::print`), what a
/// plan's laser time is measured against.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct PrintEstimate {
    /// Seconds, with the reference slicer profile.
    pub seconds: f64,
    /// Layers of 0.2 mm.
    pub layers: u32,
    /// Plastic extruded, mm³.
    pub filament_mm3: f64,
    /// The model's volume, mm³.
    pub volume_mm3: f64,
}

/// Everything the cutting-plan steps start from (the pipeline's `parts` snapshot).
#[derive(Debug, Clone)]
pub struct PlanInput {
    /// The model the parts come from.
    pub source: SourceInfo,
    /// The method that made them.
    pub method: Method,
    /// The parts, any order; ids unique.
    pub parts: Vec<Part>,
    /// The connections between parts.
    pub joints: Vec<Joint>,
    /// How to cut, label, nest and export them.
    pub settings: CutSettings,
    /// Method settings recorded in plan.json's `settings` (joint kind, units…).
    pub method_settings: BTreeMap<String, SettingValue>,
    /// What the method reports about itself (the plate method: its coverage report), copied
    /// into report.json as `method_report`.
    pub method_report: Option<serde_json::Value>,
    /// Parts only glue holds together (plan.json's `glued`).
    pub glued: Vec<Glue>,
}

impl PlanInput {
    /// An input with default settings and no earlier steps.
    pub fn new(source: SourceInfo, method: Method, parts: Vec<Part>, joints: Vec<Joint>) -> Self {
        Self {
            source,
            method,
            parts,
            joints,
            settings: CutSettings::default(),
            method_settings: BTreeMap::new(),
            method_report: None,
            glued: Vec::new(),
        }
    }

    /// Checks the settings and that every part has a unique id, a positive thickness and
    /// finite coordinates, so later steps can trust them.
    pub fn validate(&self) -> Result<(), PlanError> {
        self.settings.validate()?;
        let mut ids = BTreeSet::new();
        for part in &self.parts {
            let bad = |message: String| Err(PlanError::Part { part: part.id, message });
            if part.id == 0 || !ids.insert(part.id) {
                return bad("ids must be unique and start at 1".into());
            }
            if !(part.thickness.is_finite() && part.thickness > 0.0) {
                return bad(format!("thickness {} is not a positive number of mm", part.thickness));
            }
            let p = &part.polygon;
            let finite = std::iter::once(&p.outer)
                .chain(&p.holes)
                .flatten()
                .chain(part.marks.iter().flat_map(|m| &m.path))
                .all(|v| v.is_finite());
            if !finite {
                return bad("a coordinate is not a finite number".into());
            }
            if p.outer.len() < 3 || p.area() <= 0.0 {
                return bad("the outline has no area".into());
            }
        }
        Ok(())
    }

    /// The distinct part thicknesses, ascending.
    pub fn thicknesses(&self) -> Vec<f64> {
        let mut t: Vec<f64> = self.parts.iter().map(|p| p.thickness).collect();
        t.sort_by(f64::total_cmp);
        t.dedup();
        t
    }
}
