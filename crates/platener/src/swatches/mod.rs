//! The swatches a maker cuts before a plan, beside `convert` and not steps of it: the kerf
//! test strip (`strip`, `platener test-strip`) and the hinge test (`hinge`, `platener
//! hinge-test`). They draw with `draw` and design with `hinge`; nothing in the pipeline
//! imports them (issue 33: they were modules of the `kerf` and `hinge` steps and drew through
//! `export` and `labels`).

pub mod hinge;
pub mod strip;
