//! platener turns 3D-printing models into laser-cut construction plans.
//!
//! Each pipeline step is one module named like its entry in the conversion report, with a
//! `run` function of its inputs that returns one immutable snapshot; the [`pipeline`] runs
//! them and keeps the snapshots in its [`State`]:
//!
//! | step | module | what it adds |
//! |---|---|---|
//! | `read` | [`read`] | triangles in mm from STL / OBJ / 3MF |
//! | `cleanup` | [`cleanup`] | zero-area and duplicate triangles removed |
//! | `weld` | [`weld`] | nearby vertices merged, an indexed triangle list |
//! | `mesh` | [`mesh`] | topology, consistent winding, health report |
//! | `coplanar` | [`coplanar`] | groups of connected faces in one plane |
//! | `classify` | [`classify`] | primitives of a noisy or textured surface and the planar groups they stand for (classifier method) |
//! | `shapes` | [`shapes`] | each group's outline with holes in its own 2D frame |
//! | `plates` | [`plates`] | the plates and the coverage report |
//! | `bends` | [`bends`] | plates meeting at shallow turns made one bent part |
//! | `joints` | [`joints`] | the plate graph and its joints |
//! | `parts` / `stacked` | [`parts`] / [`stacked`] | the parts to cut (plate / stacked method) |
//! | `interlocked` | [`interlocked`] | upright slices crossing in halved slots as parts to cut (interlocked method) |
//! | `relief` | [`relief`] | textures the classifier flattened, engraved on their plates |
//! | `layers` | [`layers`] | what no plate builds among the classifier's plates, as stacked layers |
//! | `kerf`, `labels`, `sheets`, `export` | [`kerf`] … [`export`] | the cutting plan and its ZIP |
//!
//! Each method runs the steps it needs in this order ([`method`]); the cutting plan reads the
//! parts of its last step that made some ([`State::final_parts`]).
//!
//! Below the steps: [`context`], [`settings`], [`error`], [`plan`], [`cuttable`] (the
//! smallest part) and [`draw`] (SVG and the stroke font); beside them the helpers
//! [`assembly`], [`hinge`], [`repair`], [`score`], [`verify`]; above them [`mod@convert`],
//! [`options`] (every setting's one definition) and [`swatches`] (`test-strip`, `hinge-test`).
//!
//! [`inspect`] runs these and summarises them (`platener inspect`); [`scene`] draws any
//! snapshot as a 3D scene (glTF binary) for viewers; [`debug`] gives every snapshot of a run as
//! bounded JSON (the web service's debug view).
//!
//! Programs convert a model in one call, [`convert_all`]: every method, each with its plan,
//! ZIP, score and warnings or error, and the best named. An upload never touches the disk
//! (the models made in code for tests are in the `platener-fixtures` crate):
//!
//! ```
//! use std::sync::Arc;
//! use platener::convert::{Request, Status, convert_all, no_progress};
//! use platener::{Cancel, Settings, Source};
//!
//! # let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples/box-3mm.stl");
//! let bytes = std::fs::read(path).expect("the shipped example box");
//! let source = Source::Bytes { name: "box.stl".into(), bytes: Arc::from(bytes) };
//! let all = convert_all(Request::new(source, Settings::default()), &Cancel::default(), no_progress());
//! let best = all.best().expect("a method converted the box");
//! assert_eq!(best.status, Status::Converted);
//! let plan = &best.bundle().expect("a plan").plan;
//! assert_eq!(plan.parts.len(), 6);
//! ```
//!
//! docs/architecture.md says which module may use which.

pub mod assembly;
pub mod bends;
pub mod classify;
pub mod cleanup;
pub mod context;
pub mod convert;
pub mod coplanar;
pub mod cuttable;
pub mod debug;
pub mod draw;
pub mod error;
pub mod export;
pub mod fabrication;
pub mod hinge;
pub mod inspect;
pub mod interlocked;
pub mod joints;
pub mod kerf;
pub mod labels;
pub mod layers;
pub mod mesh;
pub mod method;
pub mod options;
pub mod parts;
pub mod pipeline;
pub mod plan;
pub mod plates;
pub mod read;
pub mod relief;
pub mod repair;
pub mod scene;
pub mod score;
pub mod settings;
pub mod shapes;
pub mod sheets;
pub mod slicing;
pub mod stacked;
pub mod swatches;
pub mod verify;
pub mod weld;

pub use context::{Cancel, Warning, WarningKind};
pub use convert::{Conversions, Request, convert, convert_all};
pub use error::{Error, Result};
pub use pipeline::State;
pub use platener_geom::glam;
pub use read::Source;
pub use settings::{Bending, Features, PlateMode, PlateSettings, Settings, Units, Weld};
