//! Test support for platener's web service (issue 17).
//!
//! - [`Cluster`]: a throwaway PostgreSQL cluster in a temp dir on a free loopback port, run as
//!   `nobody` when the tests run as root (initdb and postgres refuse root), stopped and removed
//!   when dropped or when the test process ends. [`Cluster::for_tests`] gives each test binary one shared
//!   cluster, and [`Cluster::fresh_database`] each test its own database.
//! - [`load`]: the load benchmark client behind the `platener-load` binary, which drives
//!   `platener serve` through the API of `shared/spec/api.md`.

mod binaries;
mod cluster;
mod error;
pub mod load;
mod shared;
mod user;
mod watchdog;

pub use binaries::{BIN_DIR_VAR, Binaries};
pub use cluster::{Cluster, DEFAULT_DATABASE, Database, SUPERUSER};
pub use error::Error;
pub use shared::REQUIRE_POSTGRES;
