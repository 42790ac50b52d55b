//! Step `interlocked`: the model as two families of upright slices crossing at right angles,
//! held by halved slots, glue-free by construction (Slicer for Fusion 360's "interlocked
//! slices"; Hildebrand, Bickel and Alexa, "crdbrd", 2012).
//!
//! Family A stands across the model's longer horizontal axis, family B across the other; both
//! are vertical, so every crossing is a vertical line and every slot runs up and down. The
//! modules follow the work in order:
//!
//! | module | what |
//! |---|---|
//! | `place` | where the slices lie (spacing, frames) and their cross-sections as islands |
//! | `cross` | every crossing: where its slots split the column, so that each A slice slides down onto the B slices |
//! | `held` | pieces after slotting, the crossings that hold them, pieces held by nothing left out |
//! | `parts` | the pieces as parts (named A1…, B1…, each slot marked with its partner), joints `halved` |
//!
//! **Insertion** (the constructibility crdbrd checks with a BSP order): at a crossing the B
//! slice keeps its material in the slot's column below a height h, the A slice above it. All
//! B slices stand first, then each A slice is lowered straight down: its material in every
//! column stays above the B material there all the way, so it meets B slices only in its
//! slots. One direction for all crossings makes the order trivial and needs no BSP; a
//! crossing whose slots would cut a slice apart moves h (the slot deeper in the other slice)
//! before it accepts a split, and a split slice's pieces are numbered apart (A3-1, A3-2).

mod cross;
mod held;
mod parts;
mod place;
#[cfg(test)]
mod tests;

use glam::DVec3;
use platener_geom::Polygon;
use serde::Serialize;

use crate::cleanup::Cleaned;
use crate::context::{StepContext, WarningKind};
use crate::error::{Error, ModelProblem, Result};
use crate::mesh::Mesh;
use crate::plan::PlanInput;
use crate::read::Model;
use crate::settings::Settings;

pub use cross::{Crossing, column_extent};
pub use held::{LeftOut, Why};
pub use place::{Family, default_spacing};

/// One piece of a slice as cut: part of a cross-section, minus its slots.
#[derive(Debug, Clone, Serialize)]
pub struct Piece {
    /// Family index: 0 for A, 1 for B.
    pub family: usize,
    /// The slice's index in its family (0-based; its number is one more).
    pub slice: usize,
    /// Its name, engraved on it: family letter, slice number, and the piece's number when the
    /// slice has several (A3, B2-1).
    pub name: String,
    /// The piece as cut, in the family's 2D frame (x across, y up).
    pub polygon: Polygon,
    /// Its part id in the plan.
    pub part: u32,
}

/// The snapshot of step `interlocked`.
#[derive(Debug, Clone, Serialize)]
pub struct Interlocked {
    /// The two families of slices (A then B).
    pub families: [Family; 2],
    /// Sheet thickness (and slot width), mm.
    pub thickness: f64,
    /// Distance between neighbouring slices of a family, mm.
    pub spacing: f64,
    /// Every piece, A before B, by slice then position; part ids in this order.
    pub pieces: Vec<Piece>,
    /// Every crossing that holds two pieces, with its slots.
    pub crossings: Vec<Crossing>,
    /// Pieces too small to cut, or held by no crossing, left out.
    pub left_out: Vec<LeftOut>,
    /// The order of assembly: part ids, B pieces first (stood up), then A pieces (lowered).
    pub order: Vec<u32>,
}

impl Interlocked {
    /// The direction an A piece moves in while it is put in place (model coordinates).
    pub const LOWER: DVec3 = DVec3::NEG_Z;
}

/// Step `interlocked`: the slices, their slots and the parts to cut (the method's `parts`
/// snapshot, made here: the slices are the parts).
pub fn run(
    model: &Model,
    cleaned: &Cleaned,
    mesh: &Mesh,
    settings: &Settings,
    cx: &mut StepContext<'_>,
) -> Result<(Interlocked, PlanInput)> {
    let geometry = |e: platener_geom::GridError| Error::model(&model.name, ModelProblem::OffGrid(e));
    let tolerance = settings.straight_tolerance.unwrap_or(cleaned.tolerances.straight);
    let thickness = settings.layer_thickness();
    let spacing = settings
        .interlocked
        .spacing
        .unwrap_or_else(|| default_spacing(mesh, thickness));
    if spacing < MIN_SPACING_PER_THICKNESS_SET * thickness {
        return Err(Error::Setting {
            name: "slice-spacing",
            message: format!(
                "slices {spacing} mm apart in {thickness} mm sheet would leave no material between their slots; \
                 choose at least {} mm",
                MIN_SPACING_PER_THICKNESS_SET * thickness
            ),
        });
    }
    let families =
        place::families(mesh, spacing).ok_or_else(|| Error::model(&model.name, ModelProblem::NothingToSlice))?;
    let rule = crate::stacked::island_rule(thickness, &settings.stacked);
    let sections = place::sections(mesh, &families, thickness, tolerance, &rule).map_err(geometry)?;
    fit_sheets(&families, &sections, settings)?;
    cx.check_cancel()?;
    let crossed = cross::cut(&families, &sections, thickness, settings.cut.kerf(), &rule).map_err(geometry)?;
    cx.check_cancel()?;
    let made = held::pieces(&families, crossed, thickness / 2.0, &rule).map_err(geometry)?;
    if made.pieces.is_empty() {
        return Err(Error::model(
            &model.name,
            ModelProblem::NoSlice {
                pieces: made.left_out.len(),
                min_area: rule.min_area,
                min_width: rule.min_width,
                spacing,
            },
        ));
    }
    let order = made.order();
    let interlocked = Interlocked {
        families,
        thickness,
        spacing,
        pieces: made.pieces,
        crossings: made.crossings,
        left_out: made.left_out,
        order,
    };
    for w in warnings(&interlocked) {
        cx.warn(WarningKind::CuttingPlan, w);
    }
    let (mut input, unnumbered) = parts::plan_input(&interlocked, model, settings).map_err(geometry)?;
    if !unnumbered.is_empty() {
        cx.warn(
            WarningKind::CuttingPlan,
            format!(
                "part(s) {} have room for their number nowhere (not on themselves, on a tab or on a piece they touch) and were left out",
                crate::labels::id_ranges(&unnumbered)
            ),
        );
    }
    crate::repair::clean_input(&mut input, cx);
    Ok((interlocked, input))
}

/// A set spacing below this many sheet thicknesses is refused: neighbouring slots would
/// leave less than a sheet of material between them.
pub const MIN_SPACING_PER_THICKNESS_SET: f64 = 2.0;

/// Refuses slices no sheet holds before the slots and the cutting plan.
fn fit_sheets(families: &[Family; 2], sections: &place::Sections, settings: &Settings) -> Result<()> {
    for (f, slices) in sections.islands.iter().enumerate() {
        for (k, islands) in slices.iter().enumerate() {
            for island in islands {
                let what = format!("slice {}{}", families[f].letter, k + 1);
                if let Some(message) = settings.cut.oversize(&what, &island.outer, 0.0) {
                    return Err(Error::Setting { name: "sheet", message });
                }
            }
        }
    }
    Ok(())
}

/// What the maker should know: pieces left out, slices split by their slots.
pub fn warnings(i: &Interlocked) -> Vec<String> {
    let mut out: Vec<String> = i.left_out.iter().map(LeftOut::describe).collect();
    let mut split: Vec<&str> = i
        .pieces
        .iter()
        .filter_map(|p| p.name.split_once('-'))
        .map(|(slice, _)| slice)
        .collect();
    split.dedup();
    if !split.is_empty() {
        out.push(format!(
            "slice(s) {} fall apart into pieces along the model's own gaps or their slots; each piece is numbered (-1, -2, …) and held by its own slots",
            split.join(", ")
        ));
    }
    out
}
