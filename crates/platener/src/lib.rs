//! platener turns 3D-printing models into laser-cut construction plans.
//!
//! The modules below read in pipeline order; each pipeline step is one module named like its
//! entry in the conversion report, and adds one immutable snapshot to the [`pipeline::State`]:
//!
//! | step | module | what it adds |
//! |---|---|---|
//! | `read` | [`read`] | triangles in mm from STL / OBJ / 3MF |
//! | `cleanup` | [`cleanup`] | zero-area and duplicate triangles removed |
//! | `weld` | [`weld`] | nearby vertices merged, an indexed triangle list |
//! | `mesh` | [`mesh`] | topology, consistent winding, health report |
//! | `coplanar` | [`coplanar`] | groups of connected faces in one plane |
//! | `shapes` | [`shapes`] | each group's outline with holes in its own 2D frame |
//!
//! [`inspect`] runs these and summarises them (`platener inspect`); [`scene`] draws any
//! snapshot as a 3D scene (glTF binary) for viewers.

pub mod assembly;
pub mod cleanup;
pub mod coplanar;
pub mod error;
pub mod export;
pub mod inspect;
pub mod joints;
pub mod kerf;
pub mod labels;
pub mod mesh;
pub mod method;
pub mod pipeline;
pub mod plan;
pub mod plates;
pub mod read;
pub mod samples;
pub mod scene;
pub mod score;
pub mod settings;
pub mod shapes;
pub mod sheets;
pub mod stacked;
pub mod verify;
pub mod weld;

pub use error::{Error, Result};
pub use pipeline::{Cancel, Source, State};
pub use platener_geom::glam;
pub use settings::{PlateMode, PlateSettings, Settings, Units, Weld};
