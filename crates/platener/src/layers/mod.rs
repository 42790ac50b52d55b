//! Step `layers` (classifier method): the spheres and freeforms the plates leave out, as
//! stacked layers on shafts among the plates.
//!
//! Plates build planes, boxes, prisms, cylinders and cones. A sphere or a freeform (surface no
//! primitive explains) has no plate, so without this step the classifier's plan simply left it
//! out. Here those triangles are *marked* (`mark`), the model is sliced as the stacked method
//! slices it, and each layer keeps the material inside loops cut mostly (by length) from marked
//! triangles: a dome's circles, not the lid's square it stands on. Where a part already in the
//! plan passes through a layer (the columns of the layer meeting its volume, bend zones
//! included), the layer gives way with a clearance, so layers never overlap plates. The layers
//! are laid parallel to the plate face the marked surface meets along the longest boundary,
//! starting on it, and threaded on shafts by the stacked method's own code, the plates lying
//! where layers lie taking part as islands of those layers (`aligned`): shafts go on through
//! slots in them, so the stack is jointed to the plates. Groups of layers no shaft holds to a
//! plate are left out: nothing would hold them in place.
//!
//! docs/classifier.md ("Spheres and freeforms") gives the rules and their limits.

mod aligned;
mod mark;

pub use mark::Surface;

use glam::DVec3;
use platener_geom::slab::Slab;
use platener_geom::{Frame, GridError, Polygon, boolean, offset};
use rayon::prelude::*;
use serde::Serialize;

use crate::classify::Classification;
use crate::cleanup::Cleaned;
use crate::context::{StepContext, WarningKind};
use crate::coplanar::PlanarGroups;
use crate::error::{Error, ModelProblem, Result};
use crate::mesh::Mesh;
use crate::plan::{Joint, JointKind, Part, PlanInput};
use crate::plates::Plates;
use crate::read::Model;
use crate::settings::Settings;
use crate::shapes::Shapes;
use crate::stacked::{self, AxisChoice, SliceLoop, SlicePlan, Stack};

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
    /// Layer and shaft parts left out because no shaft holds them to a plate.
    pub left_out: usize,
    /// Why no layers were made, when none were.
    pub skipped: Option<String>,
}

impl Layers {
    /// Nothing stacked yet: the marked surface's area and share.
    fn marked(marked_area: f64, marked_share: f64) -> Self {
        Self {
            marked_area,
            marked_share,
            rests_on: None,
            stack: None,
            tenons: Vec::new(),
            left_out: 0,
            skipped: None,
        }
    }

    /// Nothing stacked, and why.
    fn none(marked_area: f64, marked_share: f64, why: String) -> Self {
        Self {
            skipped: Some(why),
            ..Self::marked(marked_area, marked_share)
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

/// Why no layers are made when `share` of the surface is marked, if too little is.
fn too_little(share: f64) -> Option<String> {
    (share < MIN_MARKED_SHARE).then(|| {
        format!(
            "{:.1} % of the surface is neither plate nor plane, cylinder or cone (layers start at {:.0} %)",
            // A share rounding to −0 (the plates' area a hair over the surface) reads 0.
            (100.0 * share).max(0.0),
            100.0 * MIN_MARKED_SHARE
        )
    })
}

/// The share of `mesh`'s surface that `area` is.
fn marked_share(mesh: &Mesh, area: f64) -> f64 {
    if mesh.surface_area > 0.0 {
        area / mesh.surface_area
    } else {
        0.0
    }
}

/// Why the classifier's plan would be the plate method's, known once plates are made: no
/// primitive replaced an exact face and this step will make no layers. The classifier beside
/// the plate method stops there rather than after joints, parts and nesting.
pub fn repeats_plate_plan(surface: &Surface<'_>, settings: &Settings) -> Option<String> {
    if !surface.found.replaced.is_empty() {
        return None;
    }
    let why = too_little(marked_share(surface.mesh, mark::marked(surface, settings).area))?;
    Some(format!(
        "no primitive replaces the model's exact faces and {why}: the classifier's plan would be the plate method's"
    ))
}

impl Inputs<'_> {
    /// The inputs that decide which triangles are marked.
    fn surface(&self) -> Surface<'_> {
        Surface {
            mesh: self.mesh,
            found: self.found,
            groups: self.groups,
            shapes: self.shapes,
            plates: self.plates,
        }
    }
}

/// Step `layers`: the marked surface as stacked layers among the plates. Returns the snapshot
/// and, when layers were made, the parts with them added (plates with their slots).
pub fn run(inputs: &Inputs<'_>, settings: &Settings, cx: &mut StepContext<'_>) -> Result<(Layers, Option<PlanInput>)> {
    let mesh = inputs.mesh;
    let marked = mark::marked(&inputs.surface(), settings);
    let share = marked_share(mesh, marked.area);
    if let Some(why) = too_little(share) {
        return Ok((Layers::none(marked.area, share, why), None));
    }
    let built = mark::built_groups(inputs.groups, inputs.shapes, inputs.plates);
    let rests_on =
        mark::resting_face(mesh, &marked.faces, inputs.groups, &built).map(|(group, shared)| RestsOn { group, shared });
    let Some(plan) = slice_plan(mesh, &marked.faces, inputs.groups, rests_on, settings.layer_thickness()) else {
        return Ok((Layers::none(marked.area, share, "no marked triangle".into()), None));
    };
    let layers = Layers {
        rests_on,
        ..Layers::marked(marked.area, share)
    };
    let mut merged = inputs.parts.clone();
    let (mut stack, tenons, left_out) = match held_stack(inputs, &marked.faces, plan, &mut merged, settings, cx)? {
        Ok(held) => held,
        Err((why, left_out)) => {
            let skipped = Some(why);
            return Ok((
                Layers {
                    skipped,
                    left_out,
                    ..layers
                },
                None,
            ));
        }
    };
    let ids = stack.number_from(merged.parts.iter().map(|p| p.id).max().unwrap_or(0) + 1);
    let tenons: Vec<[u32; 2]> = tenons.iter().map(|[s, p]| [ids[s], *p]).collect();
    let input = stacked::parts_of(&stack, inputs.model, settings, cx)?;
    merge(&mut merged, input, &tenons);
    let layers = Layers {
        stack: Some(stack),
        tenons,
        left_out,
        ..layers
    };
    Ok((layers, Some(merged)))
}

/// What [`held_stack`] made: the stack, its tenons (shaft, plate) and how many parts it left
/// out; or why nothing is left, and how many parts were left out.
type Held = std::result::Result<(Stack, Vec<[u32; 2]>, usize), (String, usize)>;

/// The layers of the `marked` surface cut from the planes of `plan`, threaded on shafts
/// together with the plates of `merged` lying where layers lie (their slots cut into them), less
/// the groups of parts no shaft holds to a plate.
fn held_stack(
    inputs: &Inputs<'_>,
    marked: &[bool],
    plan: SlicePlan,
    merged: &mut PlanInput,
    settings: &Settings,
    cx: &mut StepContext<'_>,
) -> Result<Held> {
    let name = &inputs.model.name;
    let geometry = |e: GridError| Error::model(name, ModelProblem::OffGrid(e));
    let tolerance = settings
        .straight_tolerance
        .unwrap_or(inputs.cleaned.tolerances.straight);
    let sliced = stacked::slice_marked(inputs.mesh, &plan, tolerance, marked);
    cx.check_cancel()?;
    let filled = layer_material(&sliced.loops, &plan, inputs.parts)?;
    let rule = stacked::island_rule(plan.thickness, &settings.stacked);
    let islands = stacked::islands_from(filled, &rule).map_err(geometry)?;
    if islands.islands.iter().all(Vec::is_empty) {
        let why = "the surface no plate builds leaves no layer large enough to cut beside the plates";
        return Ok(Err((why.to_string(), 0)));
    }
    let (plan, islands, aligned) = aligned::take_in(plan, islands, &merged.parts);
    let mut stack = stacked::build(name, plan, islands, sliced.stats, settings, cx)?;
    let tenons = aligned::take_out(&mut stack, &aligned, &mut merged.parts).map_err(geometry)?;
    let left_out = unheld(&stack, &tenons, !merged.parts.is_empty());
    // `unheld` lists ids ascending.
    stack.retain_parts(|part| left_out.binary_search(&part).is_err());
    let why = format!(
        "{} layer part(s) no shaft holds to a plate were left out (nothing would hold them in place); the stacked method builds the whole model in layers",
        left_out.len()
    );
    if !left_out.is_empty() {
        cx.warn(WarningKind::CuttingPlan, why.clone());
    }
    if stack.layers.iter().all(|l| l.islands.is_empty()) {
        return Ok(Err((why, left_out.len())));
    }
    Ok(Ok((stack, tenons, left_out.len())))
}

/// The stack's part ids (ascending) that no chain of shafts holds to a plate (none of their shaft group's
/// shafts is a tenon), when the plan has plates to hold them (a plan of layers alone keeps all).
fn unheld(stack: &Stack, tenons: &[[u32; 2]], plates: bool) -> Vec<u32> {
    if !plates {
        return Vec::new();
    }
    let (ids, mut groups) = stacked::shaft_groups(stack);
    let index = |part: u32| ids.binary_search(&part).expect("a stack part");
    let held: Vec<usize> = tenons.iter().map(|t| groups.root(index(t[0]))).collect();
    (0..ids.len())
        .filter(|&i| !held.contains(&groups.root(i)))
        .map(|i| ids[i])
        .collect()
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

/// Per layer, the material inside its marked loops, less the columns that meet a part already
/// in the plan (grown by [`CLEARANCE`]).
fn layer_material(loops: &[Vec<SliceLoop>], plan: &SlicePlan, parts: &PlanInput) -> Result<Vec<Vec<Polygon>>> {
    let pieces: Vec<Slab> = parts.parts.iter().flat_map(solid_pieces).collect();
    // Each piece's heights up the stack, so a layer looks only at the pieces reaching it.
    let heights: Vec<(f64, f64)> = pieces
        .iter()
        .map(|p| heights_in(&p.polygon.outer, &p.frame, p.thickness, &plan.frame))
        .collect();
    let grid = |e: GridError| Error::model(&parts.source.name, ModelProblem::OffGrid(e));
    loops
        .par_iter()
        .enumerate()
        .map(|(k, loops)| {
            let kept: Vec<SliceLoop> = loops
                .iter()
                .filter(|l| l.marked >= MARKED_LOOP_SHARE)
                .cloned()
                .collect();
            if kept.is_empty() {
                return Ok(Vec::new());
            }
            let material = crate::slicing::fill(&kept).map_err(grid)?;
            let (z0, z1) = (plan.bottom(k), plan.bottom(k + 1));
            let near: Vec<&Slab> = (0..pieces.len())
                .filter(|&i| heights[i].0 < z1 && heights[i].1 > z0)
                .map(|i| &pieces[i])
                .collect();
            give_way(material, plan.layer_frame(k), plan.thickness, &near).map_err(grid)
        })
        .collect()
}

/// The heights (local z of `frame`) spanned by `ring`, placed by `placed` and extruded
/// `thickness` along its normal.
fn heights_in(ring: &[glam::DVec2], placed: &Frame, thickness: f64, frame: &Frame) -> (f64, f64) {
    let mut range = (f64::INFINITY, f64::NEG_INFINITY);
    for &p in ring {
        for z in [0.0, thickness] {
            let h = frame.to_local(placed.to_model(DVec3::new(p.x, p.y, z))).z;
            range = (range.0.min(h), range.1.max(h));
        }
    }
    range
}

/// The rigid pieces of `part` in the model; a bent part whose zones cannot be rebuilt (the
/// `bends` step keeps none such) falls back to its segments.
fn solid_pieces(part: &Part) -> Vec<Slab> {
    part.pieces().unwrap_or_else(|_| {
        part.segments
            .iter()
            .map(|s| Slab {
                frame: s.frame,
                polygon: s.polygon.clone(),
                thickness: part.thickness,
            })
            .collect()
    })
}

/// `material` (a layer's, in its `frame`, `thickness` thick) less the columns meeting any of
/// `pieces`, grown by [`CLEARANCE`].
fn give_way(material: Vec<Polygon>, frame: Frame, thickness: f64, pieces: &[&Slab]) -> Result<Vec<Polygon>, GridError> {
    let mut taken = Vec::new();
    for polygon in &material {
        let layer = Slab {
            frame,
            polygon: polygon.clone(),
            thickness,
        };
        for piece in pieces {
            taken.extend(layer.columns_meeting(piece, 1e-3)?);
        }
    }
    if taken.is_empty() {
        return Ok(material);
    }
    let taken = offset::offset(&boolean::union_all(&taken)?, CLEARANCE)?;
    boolean::difference(&material, &taken)
}

/// Adds the stack's parts, shaft joints and glue to the plan, and a `slot` joint per tenon;
/// joint labels continue the plan's.
fn merge(plan: &mut PlanInput, stack: PlanInput, tenons: &[[u32; 2]]) {
    let mut label = plan.joints.iter().map(|j| j.label).max().unwrap_or(0);
    plan.parts.extend(stack.parts);
    for mut j in stack.joints {
        label += 1;
        j.label = label;
        plan.joints.push(j);
    }
    for t in tenons {
        label += 1;
        plan.joints.push(Joint {
            parts: *t,
            kind: JointKind::Slot,
            angle_deg: 90.0,
            label,
        });
    }
    plan.glued.extend(stack.glued);
}
