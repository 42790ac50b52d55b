//! The library's error type. Each variant says whose fault it is: the input's (a file we
//! cannot read, a model with nothing left to convert), the caller's (settings out of range,
//! a cancelled run), or ours (an invariant that broke: please report it).

use crate::read::ReadError;

/// Everything that can stop a conversion.
#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// The model file could not be read (input's fault; the message names file and place).
    #[error(transparent)]
    Read(#[from] ReadError),
    /// The model has nothing left after a step (input's fault).
    #[error("{model}: {message}")]
    Model {
        /// The model's name.
        model: String,
        /// What is missing and what to do.
        message: String,
    },
    /// A setting is out of range (caller's fault).
    #[error("invalid setting {name}: {message}")]
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
    /// A step ran before the steps it depends on (our fault).
    #[error("internal error: step {step} needs the result of step {needs}; please report this")]
    MissingStep {
        /// The step that ran.
        step: &'static str,
        /// The step whose snapshot was missing.
        needs: &'static str,
    },
    /// A coordinate could not be put on the 2D grid (input's fault, validated before geometry).
    #[error("{model}: {message}")]
    Geometry {
        /// The model's name.
        model: String,
        /// What was wrong.
        message: String,
    },
}

/// Shorthand for results of this crate.
pub type Result<T, E = Error> = std::result::Result<T, E>;
