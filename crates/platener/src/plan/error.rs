//! Errors of the cutting-plan steps, each saying whose fault it is.

/// Everything that stops a cutting plan.
#[derive(Debug, thiserror::Error)]
pub enum PlanError {
    /// A setting is out of range (caller's fault).
    #[error("invalid setting {name}: {message}")]
    Setting {
        /// The setting.
        name: &'static str,
        /// Why it is invalid and what is allowed.
        message: String,
    },
    /// A part's geometry cannot be used (input's fault: non-finite or huge coordinates, an
    /// outline with no area, a duplicate id).
    #[error("part {part}: {message}")]
    Part {
        /// The part's id.
        part: u32,
        /// What is wrong with it.
        message: String,
    },
    /// Writing a file into memory failed (our fault: please report it).
    #[error("internal error writing {file}: {message}; please report this")]
    Write {
        /// The file being written.
        file: String,
        /// The writer's message.
        message: String,
    },
    /// The caller cancelled the run.
    #[error("cancelled during step {step}")]
    Cancelled {
        /// The step that noticed.
        step: &'static str,
    },
}

impl PlanError {
    /// A [`PlanError::Write`] for `file`.
    pub(crate) fn write(file: impl Into<String>, e: impl std::fmt::Display) -> Self {
        PlanError::Write {
            file: file.into(),
            message: e.to_string(),
        }
    }
}
