//! platener turns 3D-printing models into laser-cut construction plans.
//!
//! The modules read in pipeline order; each pipeline step is one module named like its entry in
//! the conversion report.

pub mod read;
