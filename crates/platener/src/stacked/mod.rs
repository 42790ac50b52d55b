//! Step `stacked` (the thesis' StackedPlates): the model sliced into layers joined by shafts.
//!
//! Models without flat plates (animals, busts, vases) are rebuilt like a coarse 3D print: the
//! model is cut into layers one sheet thickness apart, each layer's outline being the exact
//! cross-section at its mid-plane, and the layers are threaded onto shafts, plates standing
//! perpendicular to them that pass through matching slots, so the stack goes together in
//! register. The modules follow the work in order:
//!
//! | module | what |
//! |---|---|
//! | `orient` | the slicing direction and where the layers are ([`SlicePlan`]) |
//! | `slice` | triangles bucketed by their height range, one segment per triangle and plane |
//! | `loops` | segments chained into closed loops through shared mesh edges |
//! | `islands` | loops → polygons with holes (even-odd), too small islands dropped |
//! | `support` | too small islands that hold other layers together kept, enlarged |
//! | `fit` | the longest slot that fits a region |
//! | `shafts` | the three phases of shaft placement |
//! | `extend` | phase 2: a shaft extended flush into a layer left unjoined |
//! | `peg` | a short shaft with thin walls for layers only glue would hold |
//! | `boss` | the last resort: a boss on both layers where even a peg finds no room |
//! | `notch` | slots cut into a layer, notches opened where they would pinch it |
//! | `assemble` | slots cut into the layers, shaft outlines, frames |
//! | `glued` | groups of parts no shaft holds together, only glue |
//! | `raised` | lettering and relief standing on a layer's exposed face, engraved there |
//! | `marks` | layer and shaft numbers with alignment arrows |
//! | `tabs` | a tab for the number of a layer too thin for its digits |
//! | `parts` | the [`Stack`] as parts and joints for the cutting plan |
//! | `select` | part of a stack kept, numbered after other parts (the classifier's layers) |
//!
//! The decisions (orientation rule, shaft phases, margins) are in docs/stacked.md.

mod assemble;
mod boss;
mod extend;
mod fit;
mod glued;
mod islands;
mod marks;
mod notch;
mod orient;
mod parts;
mod peg;
mod raised;
mod select;
mod shafts;
mod support;
mod tabs;

use glam::{DVec2, DVec3};
use platener_geom::{Frame, Polygon};
use serde::Serialize;

use crate::cleanup::Cleaned;
use crate::context::{StepContext, WarningKind};
use crate::coplanar::PlanarGroups;
use crate::error::{Error, ModelProblem, Result};
use crate::mesh::Mesh;
use crate::plan::PlanInput;
use crate::read::Model;
use crate::settings::Settings;

pub(crate) use crate::slicing::slice_marked;
pub use crate::slicing::{AxisChoice, LoopStats, SliceLoop, SlicePlan, Sliced, slice};
pub use boss::Boss;
pub(crate) use glued::shaft_groups;
pub use islands::{DroppedIsland, LayerIslands, island_rule, islands_of};
pub(crate) use islands::{islands_from, keep_cuttable};
pub(crate) use marks::{tag, text_near};
pub use orient::choose_up;
pub use parts::{Numbers, plan_input};
pub use peg::PEG_MIN_WALL;
pub use raised::Raised;
pub use support::KeptIsland;
pub use tabs::{TAB_SIZE, tab_size};
pub(crate) use tabs::{add_keeping_number, number_fits, with_tab_where};

/// One island of a layer: a connected piece of the cross-section, cut as one part.
#[derive(Debug, Clone, Serialize)]
pub struct Island {
    /// The cross-section at the layer's mid-plane, in the stack's 2D frame.
    pub outline: Polygon,
    /// The part as cut: the outline minus the slots of the shafts passing through it.
    pub polygon: Polygon,
    /// Its part id in the plan.
    pub part: u32,
}

/// One layer: every island of the model's cross-section at its mid-plane.
#[derive(Debug, Clone, Serialize)]
pub struct Layer {
    /// 1 for the bottom layer (engraved on it).
    pub number: u32,
    /// Height of its bottom face in the stack frame, mm.
    pub z: f64,
    /// Its islands, ordered by position (x, then y, of their lowest corner).
    pub islands: Vec<Island>,
}

/// Where a shaft passes through one layer: `island` of layer `layer` (0-based), over the
/// stretch `from..to` of the shaft's centre line.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Band {
    /// Layer index (0-based; its number is one more).
    pub layer: usize,
    /// Island index in that layer.
    pub island: usize,
    /// Start of the slot along the shaft's centre line, mm from [`Shaft::start`].
    pub from: f64,
    /// End of the slot along the centre line, mm.
    pub to: f64,
}

/// A shaft: a plate standing perpendicular to the layers, through a slot in each of them.
#[derive(Debug, Clone, Serialize)]
pub struct Shaft {
    /// Where the centre line starts, in the stack's 2D frame.
    pub start: DVec2,
    /// Unit direction of the centre line in the stack's 2D frame.
    pub direction: DVec2,
    /// Length of the full slot along the centre line, mm (bands lie within `0..width`).
    pub width: f64,
    /// The layers it passes through, bottom first, consecutive.
    pub bands: Vec<Band>,
    /// The phase that placed it: 1 (connect), 2 (relaxed margin for a pair left unjoined),
    /// 3 (a peg, the last resort for layers that would only be glued).
    pub phase: u8,
    /// Its outline in its own frame: x along the centre line, y up the stack.
    pub polygon: Polygon,
    /// Where it sits: local z from 0 to the shaft thickness spans the slot's width.
    pub frame: Frame,
    /// Its part id in the plan.
    pub part: u32,
}

/// Two overlapping islands of adjacent layers that no shaft joins, and why.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Unjoined {
    /// The lower layer's index.
    pub layer: usize,
    /// The island in the lower layer.
    pub lower: usize,
    /// The island in the layer above.
    pub upper: usize,
    /// Area of their overlap, mm².
    pub overlap: f64,
}

/// The snapshot of step `stacked`.
#[derive(Debug, Clone, Serialize)]
pub struct Stack {
    /// Where the layers are and how the direction was chosen.
    pub plan: SlicePlan,
    /// Shaft thickness, mm.
    pub shaft_thickness: f64,
    /// The layers, bottom first (layers without islands included, so index = number − 1).
    pub layers: Vec<Layer>,
    /// The shafts.
    pub shafts: Vec<Shaft>,
    /// Islands too small to cut.
    pub dropped: Vec<DroppedIsland>,
    /// Islands too small to cut on their own, kept (enlarged) because other layers rest on them.
    pub kept_small: Vec<KeptIsland>,
    /// Overlapping islands left without a shaft.
    pub unjoined: Vec<Unjoined>,
    /// Bosses added where only glue would have held two layers (they hold a peg).
    pub bosses: Vec<Boss>,
    /// Shafts removed in phase 3 because they joined fewer than two layers.
    pub shafts_removed: usize,
    /// How the slice loops closed.
    pub loops: LoopStats,
    /// Lettering and relief standing on the layers' exposed faces, engraved there.
    pub raised: Vec<Raised>,
}

impl Stack {
    /// The frame of layer `k` (0-based): local z from 0 to the thickness spans the layer.
    pub fn layer_frame(&self, k: usize) -> Frame {
        self.plan.layer_frame(k)
    }

    /// The layer thickness, mm.
    pub fn layer_thickness(&self) -> f64 {
        self.plan.thickness
    }

    /// The slicing direction (the stack's up) in model coordinates.
    pub fn up(&self) -> DVec3 {
        self.plan.frame.n
    }
}

/// Step `stacked`: the model sliced into layers joined by shafts, and those as the parts to
/// cut (the stacked method's `parts` snapshot, made here: the layers are the parts).
pub fn run(
    model: &Model,
    cleaned: &Cleaned,
    mesh: &Mesh,
    groups: Option<&PlanarGroups>,
    settings: &Settings,
    cx: &mut StepContext<'_>,
) -> Result<(Stack, PlanInput)> {
    let tolerance = settings.straight_tolerance.unwrap_or(cleaned.tolerances.straight);
    let (up, choice) = choose_up(mesh, groups, settings.stacked.axis);
    let plan = SlicePlan::new(mesh, up, choice, settings.layer_thickness())
        .ok_or_else(|| Error::model(&model.name, ModelProblem::NothingToSlice))?;
    let sliced = slice(mesh, &plan, tolerance);
    cx.check_cancel()?;
    let geometry = |e: platener_geom::GridError| Error::model(&model.name, ModelProblem::OffGrid(e));
    let rule = island_rule(plan.thickness, &settings.stacked);
    let layers = islands_of(&sliced, &rule).map_err(geometry)?;
    if layers.islands.iter().all(Vec::is_empty) {
        return Err(Error::model(
            &model.name,
            ModelProblem::NoLayer {
                islands: layers.dropped.len(),
                min_area: rule.min_area,
                min_width: rule.min_width,
                height: plan.thickness * plan.count as f64,
            },
        ));
    }
    fit_sheets(&layers, settings)?;
    cx.check_cancel()?;
    let mut stack = build(&model.name, plan, layers, sliced.stats, settings, cx)?;
    cx.check_cancel()?;
    stack.raised = raised::details(mesh, &stack, tolerance).map_err(geometry)?;
    let input = parts_of(&stack, model, settings, cx)?;
    Ok((stack, input))
}

/// Refuses layers no sheet holds before the shafts and the cutting plan (the nesting would
/// say the same seconds later).
fn fit_sheets(layers: &LayerIslands, settings: &Settings) -> Result<()> {
    for (k, islands) in layers.islands.iter().enumerate() {
        for island in islands {
            let what = format!("layer {}", k + 1);
            if let Some(message) = settings.cut.oversize(&what, &island.outer, 0.0) {
                return Err(Error::Setting { name: "sheet", message });
            }
        }
    }
    Ok(())
}

/// The parts of `stack` for the cutting plan, their outlines cleaned, with the stack's warnings
/// (dropped islands, unjoined layers, numbers moved to tabs) told to `cx`.
pub(crate) fn parts_of(
    stack: &Stack,
    model: &Model,
    settings: &Settings,
    cx: &mut StepContext<'_>,
) -> Result<PlanInput> {
    for w in warnings(stack) {
        cx.warn(WarningKind::CuttingPlan, w);
    }
    let (mut input, numbers) = plan_input(stack, model, settings)?;
    for w in number_warnings(&numbers) {
        cx.warn(WarningKind::CuttingPlan, w);
    }
    crate::repair::clean_input(&mut input, cx);
    Ok(input)
}

/// The stack of `layers` (their islands as cut from the planes of `plan`) of model `name`:
/// shafts placed through them, slots cut.
pub(crate) fn build(
    name: &str,
    plan: SlicePlan,
    mut layers: LayerIslands,
    loops: LoopStats,
    settings: &Settings,
    cx: &StepContext<'_>,
) -> Result<Stack> {
    let geometry = |e: platener_geom::GridError| Error::model(name, ModelProblem::OffGrid(e));
    let (placed, bosses) = place_with_bosses(&mut layers.islands, settings).map_err(geometry)?;
    cx.check_cancel()?;
    let mut stack = assemble::assemble(plan, settings.shaft_thickness(), layers, placed, loops).map_err(geometry)?;
    stack.bosses = bosses;
    Ok(stack)
}

/// Shafts placed through `islands`; where only glue would hold two layers, bosses added to
/// both and the shafts placed again (`boss`). Bosses the second placement still leaves
/// unheld are taken back.
fn place_with_bosses(
    islands: &mut [Vec<Polygon>],
    settings: &Settings,
) -> std::result::Result<(shafts::Placed, Vec<Boss>), platener_geom::GridError> {
    let t = settings.shaft_thickness();
    let placed = shafts::place(islands, &settings.stacked, t)?;
    let original = islands.to_vec();
    let mut bosses = boss::add_bosses(islands, &placed, t)?;
    if bosses.is_empty() {
        return Ok((placed, bosses));
    }
    let again = shafts::place_bossed(islands, &settings.stacked, t, &bosses)?;
    let mut groups = peg::IslandGroups::of(islands, &again.shafts);
    let count = bosses.len();
    bosses.retain(|b| groups.same(b.layer, b.lower, b.upper));
    if bosses.len() == count {
        return Ok((again, bosses));
    }
    islands.clone_from_slice(&original);
    for b in &bosses {
        boss::apply(islands, b)?;
    }
    Ok((shafts::place_bossed(islands, &settings.stacked, t, &bosses)?, bosses))
}

/// Where the numbers of layers too thin for them went.
fn number_warnings(n: &Numbers) -> Vec<String> {
    let mut out = Vec::new();
    if !n.on_tab.is_empty() {
        out.push(format!(
            "{} layer part(s) ({}) are too thin for their numbers: each carries its number on a tab on its outline",
            n.on_tab.len(),
            crate::labels::id_ranges(&n.on_tab)
        ));
    }
    for [shaft, on] in &n.beside_slot {
        out.push(format!(
            "shaft {shaft} is too narrow for its number: it is engraved beside its slot on part {on}"
        ));
    }
    for [part, on] in &n.on_neighbour {
        out.push(format!(
            "part {part} has room neither for its number nor for a tab: its outline and number are engraved on part {on}, where it rests"
        ));
    }
    out
}

/// What the bosses added: one line per boss, or one line for them all when there are more
/// than [`BOSS_LINES`] (a box's rings: one per pair of layers).
fn boss_warnings(stack: &Stack) -> Vec<String> {
    let part = |k: usize, i: usize| stack.layers[k].islands[i].part;
    let Some(first) = stack.bosses.first() else {
        return Vec::new();
    };
    let widened = format!("{:.1} mm square that holds one", first.side);
    if stack.bosses.len() <= BOSS_LINES {
        return stack
            .bosses
            .iter()
            .map(|b| {
                format!(
                    "layers {} and {}: parts {} and {} overlap by {:.1} mm² but nowhere wide enough for a peg; both are widened there by a {widened} ({:.1} mm² added outside the model)",
                    b.layer + 1,
                    b.layer + 2,
                    part(b.layer, b.lower),
                    part(b.layer + 1, b.upper),
                    b.overlap,
                    b.added
                )
            })
            .collect();
    }
    let pairs: Vec<String> = stack
        .bosses
        .iter()
        .map(|b| format!("{}–{}", part(b.layer, b.lower), part(b.layer + 1, b.upper)))
        .collect();
    let added: f64 = stack.bosses.iter().map(|b| b.added).sum();
    vec![format!(
        "{} pairs of parts overlap nowhere wide enough for a peg ({}): both parts of each are widened there by a {widened} ({added:.1} mm² added outside the model in all)",
        stack.bosses.len(),
        pairs.join(", ")
    )]
}

/// Bosses said one per line up to this many.
const BOSS_LINES: usize = 3;

/// What the user should know about a stack: dropped islands, unjoined layers, repaired loops.
pub fn warnings(stack: &Stack) -> Vec<String> {
    let mut out = Vec::new();
    for d in &stack.dropped {
        out.push(format!(
            "layer {}: an island of {:.1} mm² is too small or thin to cut and was dropped",
            d.layer + 1,
            d.area
        ));
    }
    for k in &stack.kept_small {
        out.push(format!(
            "layer {}: an island of {:.1} mm² is too small or thin to cut, but it holds the layers above and below together; kept, enlarged to {:.1} mm²",
            k.layer + 1,
            k.area,
            k.enlarged
        ));
    }
    out.extend(boss_warnings(stack));
    // A pair held through other layers needs no glue: nothing falls apart there.
    let (ids, mut groups) = shaft_groups(stack);
    let mut apart = |a: u32, b: u32| {
        let (x, y) = (ids.binary_search(&a), ids.binary_search(&b));
        x.ok().map(|x| groups.root(x)) != y.ok().map(|y| groups.root(y))
    };
    for u in &stack.unjoined {
        let part = |k: usize, i: usize| stack.layers[k].islands[i].part;
        if !apart(part(u.layer, u.lower), part(u.layer + 1, u.upper)) {
            continue;
        }
        out.push(format!(
            "layers {} and {}: parts {} and {} overlap by {:.1} mm² but no shaft fits between them; glue them",
            u.layer + 1,
            u.layer + 2,
            part(u.layer, u.lower),
            part(u.layer + 1, u.upper),
            u.overlap
        ));
    }
    out.extend(glued::glued(stack).1);
    for r in &stack.raised {
        let (face, turn) = match r.side {
            crate::plan::MarkSide::Bottom => ("upper", "; turn the part over to engrave it, the marks read mirrored"),
            crate::plan::MarkSide::Top => ("lower", ""),
        };
        out.push(format!(
            "part {}: lettering or relief of {:.1} mm² standing on its {face} face (layer {}) is engraved there{turn}",
            stack.layers[r.layer].islands[r.island].part,
            r.area,
            r.layer + 1
        ));
    }
    let l = &stack.loops;
    if l.bridged > 0 {
        out.push(format!(
            "{} slice loop(s) ran into holes in the surface and were closed across the gap",
            l.bridged
        ));
    }
    if l.dropped > 0 {
        out.push(format!(
            "{} open slice loop(s) could not be closed (holes in the surface over a quarter of the model across) and were ignored",
            l.dropped
        ));
    }
    out
}

#[cfg(test)]
mod tests;
