//! 3D scenes of the pipeline's snapshots as glTF 2.0 binary (GLB), for viewers.
//!
//! Seven views show what platener sees and makes, in this order ([`View::ALL`]):
//!
//! | view | function | what |
//! |---|---|---|
//! | `model` | [`model`] | the mesh as read |
//! | `wireframe` | [`wireframe`] | its edges, as lines |
//! | `coplanar` | [`coplanar`] | each planar group in its own colour |
//! | `primitives` | [`primitives`] | each classifier primitive in its own colour, with its inlier samples as points |
//! | `plates` | [`plates`] | each plate a closed slab in its own colour |
//! | `bent` | [`bent`] | plates coloured by their bent part |
//! | `final` | [`assembly`] | every part as cut, placed by its transform (`assembly.glb`) |
//!
//! The conventions are plan-format.md's ("The 3D scene"): positions in mm under one root node
//! that scales to metres and turns Z-up into Y-up, closed outward-facing solids, one material
//! per colour from a fixed palette, the same bytes for the same input. The functions take
//! snapshots, not the pipeline's state, so they work on any method's results.

mod decimate;
mod extrude;
mod glb;
mod palette;
mod primitives;
mod solid;
mod surface;
#[cfg(test)]
mod tests;

use std::str::FromStr;

pub use decimate::TRIANGLE_LIMIT;
pub use primitives::{POINT_LIMIT, primitives};
pub use solid::{Assembly, assembly, bent, plates};
pub use surface::{GROUP_NODE_LIMIT, coplanar, model, wireframe};

/// A 3D view a viewer can show.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum View {
    /// The mesh as read.
    Model,
    /// The mesh's edges as lines.
    Wireframe,
    /// Each planar group its own colour.
    Coplanar,
    /// Each primitive the classifier found its own colour, its inlier samples as points.
    Primitives,
    /// Each plate a solid slab, its own colour.
    Plates,
    /// Plates coloured by the bent part they belong to.
    Bent,
    /// Every part as cut, placed by its transform.
    Final,
}

impl View {
    /// Every view, in the pipeline's order.
    pub const ALL: [View; 7] = [
        View::Model,
        View::Wireframe,
        View::Coplanar,
        View::Primitives,
        View::Plates,
        View::Bent,
        View::Final,
    ];

    /// The view's name, as in URLs and file names.
    pub fn name(self) -> &'static str {
        match self {
            View::Model => "model",
            View::Wireframe => "wireframe",
            View::Coplanar => "coplanar",
            View::Primitives => "primitives",
            View::Plates => "plates",
            View::Bent => "bent",
            View::Final => "final",
        }
    }
}

impl std::fmt::Display for View {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for View {
    type Err = SceneError;

    /// The view of a name given by [`View::name`].
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        View::ALL
            .into_iter()
            .find(|v| v.name() == s)
            .ok_or_else(|| SceneError::UnknownView(s.to_string()))
    }
}

/// A scene: the GLB file and what it holds.
#[derive(Debug, Clone, PartialEq)]
pub struct Scene {
    /// The glTF 2.0 binary.
    pub glb: Vec<u8>,
    /// Triangles over all meshes.
    pub triangles: usize,
    /// Line segments over all meshes (the wireframe).
    pub lines: usize,
    /// Points over all meshes (the primitives view's samples).
    pub points: usize,
    /// Nodes, the root included.
    pub nodes: usize,
    /// What the viewer should know (decimation, views that are stand-ins).
    pub notes: Vec<String>,
}

impl Scene {
    fn finish(glb: glb::GlbBuilder, root: &str, notes: Vec<String>) -> Result<Self, SceneError> {
        let (triangles, lines, points, nodes) = (glb.triangles, glb.lines, glb.points, glb.node_count());
        Ok(Scene {
            glb: glb.finish(root)?,
            triangles,
            lines,
            points,
            nodes,
            notes,
        })
    }
}

/// Why a scene could not be made, and whose fault that is.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum SceneError {
    /// A view name that does not exist (caller's fault).
    #[error("unknown view '{0}': expected one of model, wireframe, coplanar, primitives, plates, bent, final")]
    UnknownView(String),
    /// Geometry that cannot be drawn: non-finite or huge coordinates (input's fault).
    #[error("cannot draw {what}: {error}")]
    Geometry {
        /// What was drawn (a plate, a part).
        what: String,
        /// Why its outline is off the grid.
        error: platener_geom::GridError,
    },
    /// A bent part whose segments and bends disagree, so it cannot be bent (input's fault).
    #[error("cannot bend a part: {0}")]
    Bends(String),
    /// More than a GLB holds (4 GiB, 2^32 vertices): the input is too large.
    #[error("{what} is too large for a GLB file")]
    TooLarge {
        /// What overflowed.
        what: String,
    },
    /// The view needs a step this conversion did not reach (it failed earlier, or its method
    /// has no such step: the stacked method makes no plates).
    #[error("the {view} view needs step {step}, which this conversion did not reach")]
    NotReached {
        /// The view asked for.
        view: &'static str,
        /// The step whose snapshot it needs.
        step: &'static str,
    },
    /// Our bug: please report it.
    #[error("internal error writing a scene: {0}; please report this")]
    Bug(String),
}

impl SceneError {
    /// The error with what it is about (a plate, a part) in front.
    fn about(self, name: &str) -> Self {
        match self {
            SceneError::Geometry { error, .. } => SceneError::Geometry {
                what: name.to_string(),
                error,
            },
            e => e,
        }
    }
}
