//! Step `layers` (classifier method): the spheres and freeforms the plates leave out, as
//! stacked layers on shafts among the plates.
//!
//! Plates build planes, boxes, prisms, cylinders and cones. A sphere or a freeform (surface no
//! primitive explains) has no plate, so without this step the classifier's plan simply left it
//! out. Here those triangles are *marked* (`mark`), the model is sliced as the stacked method
//! slices it, and each layer keeps the material inside loops cut mostly (by length) from marked
//! triangles: a dome's circles, not the lid's square it stands on. Ground a plate already
//! covers is cut away with a clearance (`footprint`), so layers never overlap plates. The layers
//! are threaded on shafts by the stacked method's own code; where the stack lies on a plate
//! parallel to its layers the shafts go on through slots in it (`tenon`), so the stack is
//! jointed to the plates. The layers are laid parallel to the plate face the marked surface
//! meets along the longest boundary and start on it.
//!
//! docs/classifier.md ("Spheres and freeforms") gives the rules and their limits.

mod footprint;
mod mark;
mod tenon;

use glam::DVec3;
use platener_geom::{Frame, GridError, Polygon, boolean, offset};
use rayon::prelude::*;
use serde::Serialize;

use crate::classify::Classification;
use crate::cleanup::Cleaned;
use crate::context::{StepContext, WarningKind};
use crate::coplanar::PlanarGroups;
use crate::error::{Error, ModelProblem, Result};
use crate::mesh::Mesh;
use crate::plan::{Joint, JointKind, PlanInput};
use crate::plates::Plates;
use crate::read::Model;
use crate::settings::Settings;
use crate::shapes::Shapes;
use crate::stacked::{self, AxisChoice, SliceLoop, SlicePlan, Stack};

use footprint::{Slab, footprint};

/// Below this share of the surface, marked triangles are details (a rounded corner, a bit of
/// text), not a volume worth layers.
pub const MIN_MARKED_SHARE: f64 = 0.02;

/// A loop belongs to the layers when at least this share of its length is cut from marked
/// triangles.
pub const MARKED_LOOP_SHARE: f64 = 0.5;

/// Gap left between layers and the plates they would otherwise touch, mm: a laser's kerf is
/// about 0.1–0.2 mm, so parts cut to touch would rub.
pub const CLEARANCE: f64 = 0.2;

/// The plate face the stack lies on.
#[derive(Debug, Clone, Copy, Serialize)]
pub struct RestsOn {
    /// Its planar group.
    pub group: u32,
    /// Length of the boundary it shares with the marked surface, mm.
    pub shared: f64,
}

/// The snapshot of step `layers`.
#[derive(Debug, Clone, Serialize)]
pub struct Layers {
    /// Area of the triangles the layers build (no plate builds them; a sphere or nothing
    /// explains them), mm².
    pub marked_area: f64,
    /// Their share of the model's surface.
    pub marked_share: f64,
    /// The plate face the layers are laid on, if the marked surface meets one.
    pub rests_on: Option<RestsOn>,
    /// The layers and shafts, when any layer was cut.
    pub stack: Option<Stack>,
    /// Shafts that go on through a slot in a plate: (shaft part, plate part).
    pub tenons: Vec<[u32; 2]>,
    /// Why no layers were made, when none were.
    pub skipped: Option<String>,
}

impl Layers {
    fn none(marked_area: f64, marked_share: f64, why: String) -> Self {
        Self {
            marked_area,
            marked_share,
            rests_on: None,
            stack: None,
            tenons: Vec::new(),
            skipped: Some(why),
        }
    }
}

/// What step `layers` reads: the model and its mesh, the classification and the plate
/// method's snapshots after it, and the parts they made.
pub struct Inputs<'a> {
    /// Step `read`.
    pub model: &'a Model,
    /// Step `cleanup` (its straight-run tolerance).
    pub cleaned: &'a Cleaned,
    /// Step `mesh`.
    pub mesh: &'a Mesh,
    /// Step `classify`.
    pub found: &'a Classification,
    /// The planar groups `classify` made.
    pub groups: &'a PlanarGroups,
    /// Step `shapes`.
    pub shapes: &'a Shapes,
    /// Step `plates`.
    pub plates: &'a Plates,
    /// Step `parts`.
    pub parts: &'a PlanInput,
}

/// Step `layers`: the marked surface as stacked layers among the plates. Returns the snapshot
/// and, when layers were made, the parts with them added (plates with their slots).
pub fn run(inputs: &Inputs<'_>, settings: &Settings, cx: &mut StepContext<'_>) -> Result<(Layers, Option<PlanInput>)> {
    let Inputs { model, mesh, .. } = *inputs;
    let marked = mark::marked(mesh, inputs.found, inputs.groups, inputs.shapes, inputs.plates);
    let share = if mesh.surface_area > 0.0 { marked.area / mesh.surface_area } else { 0.0 };
    if share < MIN_MARKED_SHARE {
        let why = format!(
            "{:.1} % of the surface is neither plate nor plane, cylinder or cone (layers start at {:.0} %)",
            100.0 * share,
            100.0 * MIN_MARKED_SHARE
        );
        return Ok((Layers::none(marked.area, share, why), None));
    }
    let built = mark::built_groups(inputs.groups, inputs.shapes, inputs.plates);
    let rests_on = mark::resting_face(mesh, &marked.faces, inputs.groups, &built)
        .map(|(group, shared)| RestsOn { group, shared });
    let Some(plan) = slice_plan(mesh, &marked.faces, inputs.groups, rests_on, settings.layer_thickness()) else {
        return Ok((Layers::none(marked.area, share, "no marked triangle".into()), None));
    };
    let geometry = |e: GridError| Error::model(&model.name, ModelProblem::OffGrid(e));
    let tolerance = settings.straight_tolerance.unwrap_or(inputs.cleaned.tolerances.straight);
    let sliced = stacked::slice_marked(mesh, &plan, tolerance, &marked.faces);
    cx.check_cancel()?;
    let filled = layer_material(&sliced.loops, &plan, inputs.parts).map_err(geometry)?;
    let islands = stacked::islands_from(filled, &settings.stacked).map_err(geometry)?;
    if islands.islands.iter().all(Vec::is_empty) {
        let why = "the marked surface leaves no layer large enough to cut beside the plates".to_string();
        return Ok((Layers::none(marked.area, share, why), None));
    }
    let mut stack = stacked::build(&model.name, plan, islands, sliced.stats, settings, cx)?;
    let mut merged = inputs.parts.clone();
    renumber(&mut stack, merged.parts.iter().map(|p| p.id).max().unwrap_or(0));
    let joined = tenon::join(&mut stack, &mut merged.parts).map_err(geometry)?;
    let (mut input, numbers) = stacked::plan_input(&stack, model, settings)?;
    crate::parts::clean::clean_input(&mut input, cx);
    for w in stacked::warnings(&stack).into_iter().chain(stacked::number_warnings(&numbers)) {
        cx.warn(WarningKind::CuttingPlan, w);
    }
    merge(&mut merged, input, &joined);
    for g in &joined.glued {
        cx.warn(
            WarningKind::CuttingPlan,
            format!(
                "parts {} and {}: a layer lies on a plate over {:.0} mm² and no shaft reaches through it; glue them",
                g.parts[0], g.parts[1], g.area
            ),
        );
    }
    let layers = Layers {
        marked_area: marked.area,
        marked_share: share,
        rests_on,
        stack: Some(stack),
        tenons: joined.tenons,
        skipped: None,
    };
    Ok((layers, Some(merged)))
}

/// Layers parallel to the resting face, starting on it (or on a whole number of layers below it
/// when the marked surface reaches through it); without one, along the model's z from the
/// marked surface's lowest point.
fn slice_plan(
    mesh: &Mesh,
    marked: &[bool],
    groups: &PlanarGroups,
    rests_on: Option<RestsOn>,
    thickness: f64,
) -> Option<SlicePlan> {
    let centre = mark::centre(mesh, marked)?;
    let (up, origin, choice) = match rests_on.and_then(|r| groups.groups.get(r.group as usize)) {
        Some(g) => {
            let up = g.normal.normalize();
            let origin = centre - up * (centre.dot(up) - g.offset);
            (up, origin, AxisChoice::FlatFace { area: g.area })
        }
        None => (DVec3::Z, centre, AxisChoice::ModelZ),
    };
    let (lo, hi) = mark::extent(mesh, marked, origin, up)?;
    let start = match choice {
        AxisChoice::FlatFace { .. } if lo >= -thickness / 2.0 => 0.0,
        AxisChoice::FlatFace { .. } => -(-lo / thickness).round() * thickness,
        _ => lo,
    };
    let count = (((hi - start) / thickness).round() as usize).max(1);
    let frame = Frame::on_plane(origin, up).shifted(start);
    Some(SlicePlan {
        frame,
        thickness,
        count,
        choice,
    })
}

/// Per layer, the material inside its marked loops, less the ground the parts already in the
/// plan cover there (grown by [`CLEARANCE`]).
fn layer_material(loops: &[Vec<SliceLoop>], plan: &SlicePlan, parts: &PlanInput) -> Result<Vec<Vec<Polygon>>, GridError> {
    let slabs: Vec<Slab<'_>> = parts
        .parts
        .iter()
        .flat_map(|p| {
            let whole = Slab {
                polygon: &p.polygon,
                frame: &p.frame,
                thickness: p.thickness,
            };
            let segments = p.segments.iter().map(|s| Slab {
                polygon: &s.polygon,
                frame: &s.frame,
                thickness: p.thickness,
            });
            // A bent part's own outline is flat; its segments are where it is.
            let own = p.segments.is_empty().then_some(whole);
            own.into_iter().chain(segments).collect::<Vec<_>>()
        })
        .collect();
    loops
        .par_iter()
        .enumerate()
        .map(|(k, loops)| {
            let kept: Vec<SliceLoop> = loops.iter().filter(|l| l.marked >= MARKED_LOOP_SHARE).cloned().collect();
            if kept.is_empty() {
                return Ok(Vec::new());
            }
            let material = stacked::fill(&kept)?;
            let (z0, z1) = (plan.bottom(k), plan.bottom(k + 1));
            let mut covered = Vec::new();
            for s in &slabs {
                covered.extend(footprint(s, &plan.frame, z0, z1)?);
            }
            if covered.is_empty() {
                return Ok(material);
            }
            let covered = offset::offset(&boolean::union_all(&covered)?, CLEARANCE)?;
            boolean::difference(&material, &covered)
        })
        .collect()
}

/// Moves the stack's part ids after `last`, the highest id already in the plan.
fn renumber(stack: &mut Stack, last: u32) {
    for island in stack.layers.iter_mut().flat_map(|l| l.islands.iter_mut()) {
        island.part += last;
    }
    for shaft in &mut stack.shafts {
        shaft.part += last;
    }
}

/// Adds the stack's parts, shaft joints and glue to the plan, and a `slot` joint per tenon;
/// joint labels continue the plan's.
fn merge(plan: &mut PlanInput, stack: PlanInput, joined: &tenon::Joined) {
    let mut label = plan.joints.iter().map(|j| j.label).max().unwrap_or(0);
    plan.parts.extend(stack.parts);
    for mut j in stack.joints {
        label += 1;
        j.label = label;
        plan.joints.push(j);
    }
    for t in &joined.tenons {
        label += 1;
        plan.joints.push(Joint {
            parts: *t,
            kind: JointKind::Slot,
            angle_deg: 90.0,
            label,
        });
    }
    plan.glued.extend(stack.glued);
    plan.glued.extend(joined.glued.iter().cloned());
}
