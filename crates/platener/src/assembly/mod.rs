//! The assembly a plan describes, rebuilt for measuring: each part as a solid (outline extruded
//! by its thickness, placed by its transform, read from plan.json alone), a point-in-model
//! test, and the one [`analyse`] of the assembly (groups, joints that meet, interference,
//! surface covered) that `convert`, the score and `verify` all read.

mod analysis;
mod groups;
mod inside;
pub(crate) mod sample;
mod solid;

pub use analysis::{Analysis, COVER_SLACK, Interference, analyse, cover_distance};
pub(crate) use groups::UnionFind;
pub(crate) use inside::Inside;
pub(crate) use solid::Solid;
