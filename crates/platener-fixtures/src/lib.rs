//! Test fixtures of platener, kept out of the library's public API (issue 33).
//!
//! - [`samples`]: named shapes made in code (boxes, spheres, the shipped examples, the
//!   stand-ins for corpus models) and the location of the shared corpus.
//! - [`test_set`]: the labelled small models the web service's debug view converts step by step.
//! - [`testsets`]: the classifier's labelled, roughened test meshes and the score of a
//!   classification against them.
//!
//! `samples` and `test_set` name only `platener-geom` and `glam` types, so the library's own
//! unit tests can use them through a dev-dependency (a cycle cargo allows for tests: the test
//! build links a second copy of the library, which these two modules never touch). `testsets`
//! names the library's mesh and surface types and is for integration tests and benchmarks.

pub mod samples;
pub mod test_set;
pub mod testsets;
