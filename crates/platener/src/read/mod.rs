//! Step `read`: turns a model file (STL, OBJ, 3MF) into a triangle soup in millimetres.
//!
//! Readers are tolerant of the quirks real files have and strict about what cannot be
//! trusted: every failure is a [`ReadError`] naming the file and the line (ASCII) or triangle
//! index (binary) and saying what to do. Coordinates are validated here, before they reach any
//! geometry code (i_overlay panics on non-finite input).

mod obj;
pub mod stl;
mod threemf;

use std::path::{Path, PathBuf};
use std::sync::Arc;

use serde::Serialize;

pub use platener_geom::Triangle;

/// The file formats platener reads.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Format {
    /// Binary STL (80-byte header, count, 50 bytes per facet).
    StlBinary,
    /// ASCII STL (`solid … endsolid`).
    StlAscii,
    /// Wavefront OBJ.
    Obj,
    /// 3D Manufacturing Format (a ZIP with XML).
    ThreeMf,
}

impl Format {
    /// Human-readable name, as printed by `platener inspect`.
    pub fn label(self) -> &'static str {
        match self {
            Format::StlBinary => "STL (binary)",
            Format::StlAscii => "STL (ASCII)",
            Format::Obj => "OBJ",
            Format::ThreeMf => "3MF",
        }
    }

    /// The file extension whose reader reads it (`read_bytes` goes by the name).
    pub fn extension(self) -> &'static str {
        match self {
            Format::StlBinary | Format::StlAscii => "stl",
            Format::Obj => "obj",
            Format::ThreeMf => "3mf",
        }
    }
}

/// What a reader returns: the triangles exactly as stored (file units), plus what it noticed.
#[derive(Debug, Clone, Default)]
pub struct RawMesh {
    /// The triangles, corners as stored, converted to f64 without any scaling.
    pub triangles: Vec<Triangle>,
    /// Number of `solid` blocks (ASCII STL), objects (OBJ, 3MF build items); 1 for binary STL.
    pub solids: usize,
    /// Facets whose stored normal is non-zero and points against the winding's normal (STL only).
    pub normals_against_winding: usize,
    /// Facets whose stored normal is zero or missing (STL only); harmless, we use the winding.
    pub zero_normals: usize,
    /// Reader remarks that are not errors (e.g. bytes after the last binary facet).
    pub notes: Vec<String>,
}

// The reader's errors are kernel data (`error`), which imports no step.
pub use crate::error::{ReadError, ReadErrorKind};

/// Where a model comes from.
#[derive(Debug, Clone)]
pub enum Source {
    /// A file on disk; the format follows the extension.
    File(PathBuf),
    /// A file's bytes held in memory (an upload never touches the disk); the format follows
    /// the extension of `name`.
    Bytes {
        /// The file's name as the user gave it (`box.stl`): its extension picks the reader,
        /// its stem names the model, and errors name it.
        name: String,
        /// The file's content.
        bytes: Arc<[u8]>,
    },
    /// Triangles made in code (tests, benchmarks, generated models), already in mm.
    Triangles {
        /// A name for reports.
        name: String,
        /// The triangles.
        triangles: Arc<Vec<Triangle>>,
    },
}

impl Source {
    /// Triangles made in code, named `name` for reports.
    pub fn triangles(name: impl Into<String>, triangles: Vec<Triangle>) -> Self {
        Source::Triangles {
            name: name.into(),
            triangles: Arc::new(triangles),
        }
    }

    /// The model's name for messages: the file stem, or the given name.
    pub fn name(&self) -> String {
        let stem = |p: &Path| {
            p.file_stem()
                .map_or_else(|| p.display().to_string(), |s| s.to_string_lossy().into())
        };
        match self {
            Source::File(p) => stem(p),
            Source::Bytes { name, .. } => stem(Path::new(name)),
            Source::Triangles { name, .. } => name.clone(),
        }
    }
}

/// Reads any supported model file, choosing the reader by extension (case-insensitive).
pub fn read_file(path: &Path) -> Result<(Format, RawMesh), ReadError> {
    read_any(path, None)
}

/// Reads a model file held in memory; `name` is its file name (the extension picks the
/// reader, errors name it).
pub fn read_bytes(name: &str, bytes: &[u8]) -> Result<(Format, RawMesh), ReadError> {
    read_any(Path::new(name), Some(bytes))
}

/// The reader for `path`'s extension, on `bytes` when given (an upload), else on the file.
fn read_any(path: &Path, bytes: Option<&[u8]>) -> Result<(Format, RawMesh), ReadError> {
    let wrap = |kind| ReadError {
        path: path.to_path_buf(),
        kind,
    };
    if bytes.is_some_and(<[u8]>::is_empty) {
        return Err(wrap(ReadErrorKind::Empty));
    }
    let read = match (extension_of(path).as_str(), bytes) {
        ("stl", None) => stl::read_path(path),
        ("stl", Some(b)) => stl::parse_bytes(b),
        ("obj", None) => obj::read_path(path).map(|m| (Format::Obj, m)),
        ("obj", Some(b)) => obj::parse_bytes(b).map(|m| (Format::Obj, m)),
        ("3mf", None) => threemf::read_path(path).map(|m| (Format::ThreeMf, m)),
        ("3mf", Some(b)) => threemf::parse_bytes(b).map(|m| (Format::ThreeMf, m)),
        (extension, _) => Err(ReadErrorKind::Unsupported {
            extension: extension.into(),
        }),
    };
    let (format, mesh) = read.map_err(wrap)?;
    non_empty(format, mesh).map_err(wrap)
}

fn extension_of(path: &Path) -> String {
    path.extension()
        .and_then(|e| e.to_str())
        .unwrap_or("")
        .to_ascii_lowercase()
}

fn non_empty(format: Format, mesh: RawMesh) -> Result<(Format, RawMesh), ReadErrorKind> {
    if mesh.triangles.is_empty() {
        return Err(ReadErrorKind::NoTriangles);
    }
    Ok((format, mesh))
}

mod sniff;
mod step;
pub use sniff::{Sniffed, sniff};
pub use step::{Bounds, Model, SUSPICIOUSLY_LARGE, SUSPICIOUSLY_SMALL, run};

/// The plan's description of a model is made here, on the step's side: `plan` is kernel data
/// and imports no step (docs/architecture.md).
impl From<&Model> for crate::plan::SourceInfo {
    /// The plan's description of the model as read.
    fn from(model: &Model) -> Self {
        Self {
            name: model.name.clone(),
            triangles: model.triangles.len() as u64,
            bbox_min: model.bounds.min,
            bbox_max: model.bounds.max,
            units: model.units,
            scale: model.scale,
            print: Some(model.print),
        }
    }
}
