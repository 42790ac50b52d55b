//! The assembly a plan describes, rebuilt for measuring: each part as a solid (outline extruded
//! by its thickness, placed by its transform, read from plan.json alone), and a point-in-model
//! test. `verify` (thorough, on grids) and `score` (fast, on seeded samples) both measure with
//! these.

mod groups;
mod inside;
mod solid;

pub(crate) use groups::UnionFind;
pub(crate) use inside::Inside;
pub(crate) use solid::Solid;
