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

use glam::DVec3;
use serde::Serialize;

/// One triangle as three corners, in the order the file gave them (the winding carries the normal).
pub type Triangle = [DVec3; 3];

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

/// Why a model file could not be read. Always the input's fault, never ours; the message says
/// where the problem is and what to do about it.
#[derive(Debug, thiserror::Error, Clone, PartialEq)]
pub enum ReadErrorKind {
    /// The file has no bytes.
    #[error("the file is empty (0 bytes); export the model again")]
    Empty,
    /// A binary STL with a header but no facets.
    #[error("binary STL with a header and no triangles (count field {count}); export the model again")]
    HeaderOnly {
        /// The count field of the header.
        count: u32,
    },
    /// A binary STL whose size does not match its count field.
    #[error(
        "binary STL count field says {count} triangles ({expected} bytes) but the file has {actual} bytes; \
         the file is truncated or not an STL: download or export it again"
    )]
    CountMismatch {
        /// The count field.
        count: u32,
        /// `84 + 50·count`.
        expected: u64,
        /// The real size.
        actual: u64,
    },
    /// A binary file too short to hold even the header.
    #[error("file of {actual} bytes is too short for a binary STL (84-byte header) and is not ASCII STL")]
    TooShort {
        /// The real size.
        actual: u64,
    },
    /// A syntax error in an ASCII STL.
    #[error("line {line}: {message}")]
    Syntax {
        /// 1-based line number.
        line: usize,
        /// What was wrong, quoting the offending text.
        message: String,
    },
    /// A coordinate that is NaN or infinite.
    #[error("{location}: coordinate is not a finite number ({value}); repair the model in a mesh editor")]
    NonFinite {
        /// `line N` (ASCII) or `triangle N` (binary, 0-based).
        location: String,
        /// The value as read.
        value: String,
    },
    /// The file parsed but holds no triangles.
    #[error("the file holds no triangles")]
    NoTriangles,
    /// The extension names no format we read.
    #[error("unsupported file type {extension:?}: platener reads .stl, .obj and .3mf")]
    Unsupported {
        /// The extension found (may be empty).
        extension: String,
    },
    /// An OBJ file tobj could not read.
    #[error("OBJ: {0}")]
    Obj(String),
    /// A 3MF file that could not be read.
    #[error("3MF: {0}")]
    ThreeMf(String),
    /// The file could not be opened or read.
    #[error("cannot read the file: {0}")]
    Io(String),
}

/// A [`ReadErrorKind`] with the file it happened in.
#[derive(Debug, thiserror::Error, Clone, PartialEq)]
#[error("{}: {kind}", path.display())]
pub struct ReadError {
    /// The file.
    pub path: PathBuf,
    /// What went wrong.
    pub kind: ReadErrorKind,
}

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

mod step;
pub use step::{Bounds, Model, SUSPICIOUSLY_LARGE, SUSPICIOUSLY_SMALL, run};
