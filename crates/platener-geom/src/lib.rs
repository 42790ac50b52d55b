//! platener's geometry kernel.
//!
//! Everything that must be exact or shared lives here, so the pipeline crates never reason about
//! epsilons or call i_overlay or i_triangle themselves:
//!
//! | module | what |
//! |---|---|
//! | [`tolerance`] | the one [`Tolerances`] value, scaled to the model |
//! | [`grid`] | the project-wide fixed grid all 2D booleans snap to |
//! | [`polygon`] | polygons with holes, areas, orientation |
//! | [`boolean`] | union / intersection / difference, even-odd hole detection (i_overlay) |
//! | [`offset`] | outward/inward offsets with miter joins (i_overlay) |
//! | [`slab`] | plates and parts as extruded polygons: where one meets another's volume, points in or near one |
//! | [`boxes`] | which pairs of 3D boxes come near each other (a sweep along x) |
//! | [`frame`] | rigid 3D ↔ 2D frames of planes |
//! | [`rigid`] | rigid motions of the plane (bent parts laid flat) |
//! | [`rng`] | the one seeded random generator (SplitMix64) |
//! | [`triangulate`] | triangles covering a polygon with holes (i_triangle), for 3D scenes |
//! | [`dedup`] | finding equal items among millions (sorted fingerprints) |
//! | [`weld`] | merging nearby points in 2D or 3D (spatial hash) |
//! | [`plane_fit`] | planes fitted to triangles, points fitted to planes (QEF) |
//! | [`validity`] | is a part outline valid: simple rings, holes inside, nothing narrower than the kerf |
//! | [`clean`] | repairing outlines into valid pieces (regularise, open, separate touches) |

pub mod boolean;
pub mod boxes;
pub mod clean;
pub mod dedup;
pub mod frame;
pub mod grid;
pub mod necks;
pub mod offset;
pub mod plane_fit;
pub mod polygon;
pub mod rigid;
pub mod rng;
pub mod slab;
pub mod tolerance;
pub mod triangulate;
pub mod validity;
pub mod weld;

pub use frame::Frame;
pub use glam;
pub use grid::GridError;
pub use polygon::{Polygon, Ring};
pub use tolerance::Tolerances;
pub use validity::{Finding, Problem, RingId, validate};

/// One triangle as three corners, in the order a model file gave them (the winding carries the
/// normal): what readers return and sample models are made of.
pub type Triangle = [glam::DVec3; 3];
