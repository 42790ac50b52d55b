//! The library's error type. Each variant says whose fault it is: the model's (a file we
//! cannot read, with file and line or triangle; a model with nothing left to convert), the
//! caller's (settings out of range, a cancelled or timed-out run), or ours ([`Error::Internal`]:
//! an invariant that broke, with the step; please report it). Callers render these; the
//! library never prints.

use std::path::PathBuf;

use platener_geom::GridError;

use crate::context::Cancelled;
use crate::plan::PlanError;

/// Everything that can stop a conversion.
#[derive(Debug, Clone, thiserror::Error)]
pub enum Error {
    /// The model file could not be read (the model's fault; the message names file and place).
    #[error(transparent)]
    Read(#[from] ReadError),
    /// The model was read but cannot be converted (the model's fault).
    #[error("{model}: {problem}")]
    Model {
        /// The model's name.
        model: String,
        /// What is wrong with it and what to do.
        problem: ModelProblem,
    },
    /// A setting is out of range (the caller's fault).
    #[error("`{name}`: {message}")]
    Setting {
        /// The setting.
        name: &'static str,
        /// Why it is invalid and what is allowed.
        message: String,
    },
    /// The run was cancelled by the caller.
    #[error("cancelled during step {step}")]
    Cancelled {
        /// The step that noticed the cancellation.
        step: &'static str,
    },
    /// The run took longer than the caller's time limit and was cancelled.
    #[error("timed out after {seconds} s (the time limit); cancelled")]
    TimedOut {
        /// The limit, seconds.
        seconds: f64,
    },
    /// The method has nothing to add for this model and did not run its costly steps (the
    /// classifier on a model whose faces are exact); not a failure.
    #[error("skipped: {reason}")]
    Skipped {
        /// Why, in words the page can show.
        reason: String,
    },
    /// A bug of ours: an invariant broke in `step` (please report it).
    #[error("{problem}")]
    Internal {
        /// The step (or `convert` for the orchestration) where it happened.
        step: &'static str,
        /// What broke.
        problem: Internal,
    },
}

/// Why a model that was read cannot be converted.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ModelProblem {
    /// No triangles at all.
    #[error("the model has no triangles")]
    NoTriangles,
    /// A coordinate is NaN or infinite after units and scale.
    #[error(
        "triangle {triangle} has a coordinate that is not a finite number after scaling; check `scale` and `units`"
    )]
    NonFinite {
        /// The triangle, 0-based.
        triangle: usize,
    },
    /// Cleanup removed every triangle.
    #[error("no triangle with an area is left after cleanup")]
    EmptyAfterCleanup,
    /// Welding collapsed every triangle.
    #[error("no triangle with an area is left after welding; set `weld` to 0")]
    EmptyAfterWeld,
    /// A coordinate is beyond what the 2D grid holds.
    #[error("{0}: scale the model down (`scale`) or check its `units`")]
    OffGrid(GridError),
    /// The stacked method found nothing to slice.
    #[error("the model has no triangles to slice")]
    NothingToSlice,
    /// Every layer of the stacked method was too small to cut.
    #[error(
        "no layer is large enough to cut ({islands} island(s) under {min_area} mm² or thinner than {min_width} mm; \
         the stack is {height:.1} mm tall): scale the model up (`scale`) or use thinner sheets (`thickness`)"
    )]
    NoLayer {
        /// Islands dropped.
        islands: usize,
        /// The smallest island area kept, mm².
        min_area: f64,
        /// The narrowest island kept, mm.
        min_width: f64,
        /// The stack's height, mm.
        height: f64,
    },
    /// No slice of the interlocked method was large enough to cut and held.
    #[error(
        "no slice is large enough to cut and held by another ({pieces} piece(s) under {min_area} mm², thinner than \
         {min_width} mm or crossing no slice; slices {spacing:.1} mm apart): the interlocked method suits solid \
         shapes; for thin walls use the plate method, or try a smaller `slice-spacing`, thinner sheets (`thickness`) \
         or a larger `scale`"
    )]
    NoSlice {
        /// Pieces left out.
        pieces: usize,
        /// The smallest piece area kept, mm².
        min_area: f64,
        /// The narrowest piece kept, mm.
        min_width: f64,
        /// The slice spacing, mm.
        spacing: f64,
    },
    /// The classifier could not classify the model.
    #[error("{0}; use the plate or stacked method")]
    Classify(ClassifyError),
    /// A method made no parts (its step warnings say why).
    #[error("the {method} method made no parts to cut (the warnings say why)")]
    NoParts {
        /// The method.
        method: &'static str,
    },
}

/// A bug of ours, by kind.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum Internal {
    /// A step ran before the steps it depends on.
    #[error("internal error: step {step} needs the result of step {needs}; please report this")]
    MissingStep {
        /// The step that ran.
        step: &'static str,
        /// The step whose snapshot was missing.
        needs: &'static str,
    },
    /// The code panicked; the panic was caught.
    #[error("{} (a bug in platener: please report it)", panic_text(message, location.as_deref()))]
    Panic {
        /// The panic's message.
        message: String,
        /// `file:line:column`, when known.
        location: Option<String>,
    },
    /// A cutting-plan step made or met a part it cannot use.
    #[error("internal error: part {part}: {message}; please report this")]
    Part {
        /// The part's id.
        part: u32,
        /// What is wrong with it.
        message: String,
    },
    /// Writing a file into memory failed.
    #[error("internal error writing {file}: {message}; please report this")]
    Write {
        /// The file being written.
        file: String,
        /// The writer's message.
        message: String,
    },
    /// The thread running the conversion stopped without a result.
    #[error("internal error: the conversion thread stopped without a result ({message}); please report this")]
    Thread {
        /// What happened.
        message: String,
    },
    /// A caller asked, for a test, that the method fail.
    #[error("the {method} method was asked to fail (fault injection)")]
    Injected {
        /// The method.
        method: &'static str,
    },
}

fn panic_text(message: &str, location: Option<&str>) -> String {
    match location {
        Some(at) => format!("panicked at {at}: {message}"),
        None => format!("panicked: {message}"),
    }
}

/// Whose fault an error is.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Culprit {
    /// The model (file, line or triangle named in the message).
    Model,
    /// The settings or the caller (cancelled, timed out).
    Caller,
    /// platener itself.
    Internal,
}

impl Error {
    /// Whose fault this error is.
    pub fn culprit(&self) -> Culprit {
        match self {
            Error::Read(_) | Error::Model { .. } => Culprit::Model,
            Error::Setting { .. } | Error::Cancelled { .. } | Error::TimedOut { .. } | Error::Skipped { .. } => {
                Culprit::Caller
            }
            Error::Internal { .. } => Culprit::Internal,
        }
    }

    /// A model error.
    pub(crate) fn model(model: impl Into<String>, problem: ModelProblem) -> Self {
        Error::Model {
            model: model.into(),
            problem,
        }
    }

    /// A step ran without the snapshot of a step it needs.
    pub(crate) fn missing(step: &'static str, needs: &'static str) -> Self {
        Error::Internal {
            step,
            problem: Internal::MissingStep { step, needs },
        }
    }
}

impl From<Cancelled> for Error {
    fn from(c: Cancelled) -> Self {
        Error::Cancelled { step: c.step }
    }
}

impl From<PlanError> for Error {
    /// Cutting-plan errors: settings are the caller's, cancellation too, the rest ours.
    fn from(e: PlanError) -> Self {
        let step = "cutting plan";
        match e {
            PlanError::Setting { name, message } => Error::Setting { name, message },
            PlanError::Cancelled { step } => Error::Cancelled { step },
            PlanError::Part { part, message } => Error::Internal {
                step,
                problem: Internal::Part { part, message },
            },
            PlanError::Write { file, message } => Error::Internal {
                step,
                problem: Internal::Write { file, message },
            },
        }
    }
}

/// Shorthand for results of this crate.
pub type Result<T, E = Error> = std::result::Result<T, E>;

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

/// Why a model could not be classified.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ClassifyError {
    /// A setting is out of range.
    #[error("invalid classifier setting {name}: {message}")]
    Setting {
        /// The setting.
        name: &'static str,
        /// What is allowed.
        message: String,
    },
    /// The mesh has no surface to sample.
    #[error("the model has no surface area to classify")]
    NoSurface,
}
