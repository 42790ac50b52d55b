//! The steps the pipeline knows: their names, the lists methods run, and how each step's
//! inputs are taken from the state and its snapshot stored back.

use std::sync::Arc;

use super::{State, need};
use crate::context::StepContext;
use crate::error::Result;
use crate::interlocked;
use crate::method::MethodKind;
use crate::{
    bends, classify, cleanup, coplanar, export, joints, kerf, labels, layers, mesh, parts, plates, read, relief,
    shapes, sheets, stacked, weld,
};

/// Every pipeline step, named as in report.json and as the module it lives in.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum StepId {
    /// [`read`]: triangles in mm.
    Read,
    /// [`cleanup`]: degenerate and duplicate triangles removed.
    Cleanup,
    /// [`weld`]: nearby vertices merged.
    Weld,
    /// [`mesh`]: topology, winding, health.
    Mesh,
    /// [`coplanar`]: planar groups.
    Coplanar,
    /// [`classify`]: primitives, and the planar groups they stand for (classifier method).
    Classify,
    /// [`shapes`]: each group's outline.
    Shapes,
    /// [`plates`]: the plates.
    Plates,
    /// [`bends`]: plates merged into bent parts.
    Bends,
    /// [`joints`]: the joints between plates.
    Joints,
    /// [`parts`]: plates as parts to cut (plate method).
    Parts,
    /// [`stacked`]: layers and shafts as parts to cut (stacked method).
    Stacked,
    /// [`interlocked`]: upright slices crossing in halved slots as parts to cut
    /// (interlocked method).
    Interlocked,
    /// [`relief`]: flattened textures engraved on their plates (classifier method).
    Relief,
    /// [`layers`]: spheres and freeforms as stacked layers among the plates (classifier
    /// method).
    Layers,
    /// [`kerf`]: cut paths.
    Kerf,
    /// [`labels`]: engraved numbers.
    Labels,
    /// [`sheets`]: nesting.
    Sheets,
    /// [`export`]: files and the ZIP.
    Export,
}

/// The steps that turn a model into planar shapes (the foundation every method builds on).
pub const FOUNDATION: [StepId; 6] = [
    StepId::Read,
    StepId::Cleanup,
    StepId::Weld,
    StepId::Mesh,
    StepId::Coplanar,
    StepId::Shapes,
];

/// The foundation steps, then plate finding, bent parts and joints.
pub const PLATE: [StepId; 9] = {
    let f = FOUNDATION;
    [
        f[0],
        f[1],
        f[2],
        f[3],
        f[4],
        f[5],
        StepId::Plates,
        StepId::Bends,
        StepId::Joints,
    ]
};

/// The cutting-plan steps: they start from the `parts` snapshot, whichever method made it.
pub const CUTTING_PLAN: [StepId; 4] = [StepId::Kerf, StepId::Labels, StepId::Sheets, StepId::Export];

impl StepId {
    /// Every step, in pipeline order.
    pub const ALL: [StepId; 19] = {
        let (p, c) = (PLATE, CUTTING_PLAN);
        [
            p[0],
            p[1],
            p[2],
            p[3],
            p[4],
            StepId::Classify,
            p[5],
            p[6],
            p[7],
            p[8],
            StepId::Parts,
            StepId::Relief,
            StepId::Layers,
            StepId::Stacked,
            StepId::Interlocked,
            c[0],
            c[1],
            c[2],
            c[3],
        ]
    };

    /// The step's name, as in report.json and the module it lives in.
    pub fn name(self) -> &'static str {
        match self {
            StepId::Read => "read",
            StepId::Cleanup => "cleanup",
            StepId::Weld => "weld",
            StepId::Mesh => "mesh",
            StepId::Coplanar => "coplanar",
            StepId::Classify => "classify",
            StepId::Shapes => "shapes",
            StepId::Plates => "plates",
            StepId::Bends => "bends",
            StepId::Joints => "joints",
            StepId::Parts => "parts",
            StepId::Stacked => "stacked",
            StepId::Interlocked => "interlocked",
            StepId::Relief => "relief",
            StepId::Layers => "layers",
            StepId::Kerf => "kerf",
            StepId::Labels => "labels",
            StepId::Sheets => "sheets",
            StepId::Export => "export",
        }
    }

    /// The step of a name given by [`StepId::name`] (an event's or report.json's), if any.
    pub fn named(name: &str) -> Option<StepId> {
        StepId::ALL.into_iter().find(|s| s.name() == name)
    }

    /// What the step does, in a maker's words, for progress shown to people ("finding
    /// plates"): the one table of them, so the page and the CLI say the same thing and
    /// neither copies the pipeline's step list.
    pub fn label(self) -> &'static str {
        match self {
            StepId::Read => "reading the model",
            StepId::Cleanup => "cleaning up the mesh",
            StepId::Weld => "closing gaps between faces",
            StepId::Mesh => "checking the surface",
            StepId::Coplanar => "finding flat faces",
            StepId::Classify => "recognising curved shapes",
            StepId::Shapes => "tracing the faces' outlines",
            StepId::Plates => "finding plates",
            StepId::Bends => "finding bends",
            StepId::Joints => "making joints",
            StepId::Parts => "shaping the parts",
            StepId::Stacked => "slicing into layers",
            StepId::Interlocked => "slicing into crossing slices",
            StepId::Relief => "engraving the textures",
            StepId::Layers => "slicing the curved parts",
            StepId::Kerf => "allowing for the laser's cut",
            StepId::Labels => "numbering the parts",
            StepId::Sheets => "nesting the parts",
            StepId::Export => "writing the files",
        }
    }

    /// The steps of `method` up to and including its `parts` snapshot, then the cutting plan.
    pub fn of_method(method: MethodKind) -> Vec<StepId> {
        let mut steps = match method {
            MethodKind::Plate => [&PLATE[..], &[StepId::Parts]].concat(),
            MethodKind::Stacked => [&FOUNDATION[..], &[StepId::Stacked]].concat(),
            MethodKind::Interlocked => [&FOUNDATION[..4], &[StepId::Interlocked]].concat(),
            MethodKind::Classifier => {
                let (f, p) = (&FOUNDATION, &PLATE);
                [
                    &f[..4],
                    &[StepId::Classify],
                    &f[5..],
                    &p[6..],
                    &[StepId::Parts, StepId::Relief, StepId::Layers],
                ]
                .concat()
            }
        };
        steps.extend(CUTTING_PLAN);
        steps
    }
}

/// Runs `step` on the snapshots it reads and stores the one it makes.
pub(super) fn apply(step: StepId, state: &mut State, cx: &mut StepContext<'_>) -> Result<()> {
    let s = Arc::clone(&state.settings);
    let name = step.name();
    match step {
        StepId::Read => state.read = Some(Arc::new(read::run(&state.source, &s, cx)?)),
        StepId::Cleanup => state.cleanup = Some(Arc::new(cleanup::run(need(&state.read, name, "read")?, cx)?)),
        StepId::Weld => {
            let (model, cleaned) = (need(&state.read, name, "read")?, need(&state.cleanup, name, "cleanup")?);
            state.weld = Some(Arc::new(weld::run(model, cleaned, &s, cx)?));
        }
        StepId::Mesh => {
            let (welded, cleaned) = (need(&state.weld, name, "weld")?, need(&state.cleanup, name, "cleanup")?);
            state.mesh = Some(Arc::new(mesh::run(welded, cleaned, cx)?));
        }
        StepId::Coplanar => state.coplanar = Some(Arc::new(coplanar::run(need(&state.mesh, name, "mesh")?, &s))),
        StepId::Classify => {
            let mesh = need(&state.mesh, name, "mesh")?;
            let (found, groups) = classify::step(mesh, &s, cx)?;
            state.classify = Some(Arc::new(found));
            state.coplanar = Some(Arc::new(groups));
        }
        StepId::Shapes => {
            let (mesh, groups) = (
                need(&state.mesh, name, "mesh")?,
                need(&state.coplanar, name, "coplanar")?,
            );
            let cleaned = need(&state.cleanup, name, "cleanup")?;
            state.shapes = Some(Arc::new(shapes::run(mesh, groups, cleaned, &s, cx)?));
        }
        StepId::Plates => plates_step(state, &s, cx)?,
        StepId::Bends => {
            let (plates, mesh) = (need(&state.plates, name, "plates")?, need(&state.mesh, name, "mesh")?);
            state.bends = Some(Arc::new(bends::run(plates, mesh, &s, cx)?));
        }
        StepId::Joints => {
            let plates = need(&state.plates, name, "plates")?;
            state.joints = Some(Arc::new(joints::run(plates, state.bends.as_deref(), &s, cx)?));
        }
        StepId::Parts => {
            let (model, plates) = (need(&state.read, name, "read")?, need(&state.plates, name, "plates")?);
            let welded = need(&state.weld, name, "weld")?;
            let made = (state.joints.as_deref(), state.bends.as_deref());
            // The classifier's `layers` step builds the solids standing on its plates.
            let standoffs = state.classify.is_none();
            let input = parts::run(model, plates, made, (welded, standoffs), &s, cx)?;
            state.parts = Some(Arc::new(input));
        }
        StepId::Stacked | StepId::Interlocked => sliced_step(step, state, &s, cx)?,
        StepId::Relief => {
            let (mesh, found) = (
                need(&state.mesh, name, "mesh")?,
                need(&state.classify, name, "classify")?,
            );
            let (made, input) = relief::run(mesh, found, need(&state.parts, name, "parts")?, &s, cx)?;
            state.relief = Some(Arc::new(made));
            state.relief_parts = input.map(Arc::new);
        }
        StepId::Layers => layers_step(state, &s, cx)?,
        StepId::Kerf => state.kerf = Some(Arc::new(kerf::run(need(state.final_parts(), name, "parts")?, cx)?)),
        StepId::Labels => state.labels = Some(Arc::new(labels::run(need(state.final_parts(), name, "parts")?, cx))),
        StepId::Sheets => {
            let (input, cut) = (
                need(state.final_parts(), name, "parts")?,
                need(&state.kerf, name, "kerf")?,
            );
            state.sheets = Some(Arc::new(sheets::run(input, cut, cx)?));
        }
        StepId::Export => {
            let (input, cut) = (
                need(state.final_parts(), name, "parts")?,
                need(&state.kerf, name, "kerf")?,
            );
            let (labels, nesting) = (
                need(&state.labels, name, "labels")?,
                need(&state.sheets, name, "sheets")?,
            );
            state.export = Some(Arc::new(export::run(input, cut, labels, nesting, &state.records)?));
        }
    }
    Ok(())
}

/// Step `plates`: stores its snapshot, then refuses plates no sheet holds (cheap refusals
/// first: the snapshot stays for the viewer).
fn plates_step(state: &mut State, s: &crate::settings::Settings, cx: &mut StepContext<'_>) -> Result<()> {
    let name = StepId::Plates.name();
    let (shapes, mesh) = (need(&state.shapes, name, "shapes")?, need(&state.mesh, name, "mesh")?);
    let model = need(&state.read, name, "read")?;
    let plates = Arc::new(plates::run(shapes, mesh, model, s, cx)?);
    state.plates = Some(plates.clone());
    plates.fit_sheets(&s.cut)?;
    // The classifier beside the plate method: said now rather than after joints, parts and
    // nesting.
    if let (Some(found), Some(groups)) = (state.classify.as_deref(), state.coplanar.as_deref())
        && !s.classify_exact_faces
    {
        let surface = layers::Surface {
            mesh,
            found,
            groups,
            shapes,
            plates: &plates,
        };
        if let Some(reason) = layers::repeats_plate_plan(&surface, s) {
            return Err(crate::error::Error::Skipped { reason });
        }
    }
    Ok(())
}

/// Step `layers`: stores its snapshot, and the parts with the layers added when it made any.
fn layers_step(state: &mut State, s: &crate::settings::Settings, cx: &mut StepContext<'_>) -> Result<()> {
    let name = StepId::Layers.name();
    let inputs = layers::Inputs {
        model: need(&state.read, name, "read")?,
        cleaned: need(&state.cleanup, name, "cleanup")?,
        mesh: need(&state.mesh, name, "mesh")?,
        found: need(&state.classify, name, "classify")?,
        groups: need(&state.coplanar, name, "classify")?,
        shapes: need(&state.shapes, name, "shapes")?,
        plates: need(&state.plates, name, "plates")?,
        parts: need(state.final_parts(), name, "parts")?,
    };
    let (made, input) = layers::run(&inputs, s, cx)?;
    state.layers = Some(Arc::new(made));
    state.layers_parts = input.map(Arc::new);
    Ok(())
}

/// Steps `stacked` and `interlocked`: the model sliced, the slices as the parts to cut.
fn sliced_step(step: StepId, state: &mut State, s: &crate::Settings, cx: &mut StepContext<'_>) -> Result<()> {
    let name = step.name();
    let (model, cleaned) = (need(&state.read, name, "read")?, need(&state.cleanup, name, "cleanup")?);
    let mesh = need(&state.mesh, name, "mesh")?;
    if step == StepId::Stacked {
        let (stack, input) = stacked::run(model, cleaned, mesh, state.coplanar.as_deref(), s, cx)?;
        state.stacked = Some(Arc::new(stack));
        state.stacked_parts = Some(Arc::new(input));
    } else {
        let (slices, input) = interlocked::run(model, cleaned, mesh, s, cx)?;
        state.interlocked = Some(Arc::new(slices));
        state.interlocked_parts = Some(Arc::new(input));
    }
    Ok(())
}
