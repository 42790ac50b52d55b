//! Test support for platener's web service (issue 17).
//!
//! - [`Cluster`]: a throwaway PostgreSQL cluster in a temp dir on a free loopback port, run as
//!   `nobody` when the tests run as root (initdb and postgres refuse root), stopped and removed
//!   when dropped or when the test process ends. [`Cluster::for_tests`] gives each test binary one shared
//!   cluster, and [`Cluster::fresh_database`] each test its own database.
//! - [`load`]: the load benchmark client behind the `platener-load` binary, which drives
//!   `platener serve` through the API of `shared/spec/api.md`.
//!
//! A test that needs PostgreSQL:
//!
//! ```no_run
//! use platener_testpg::Cluster;
//!
//! // Skips with a message when PostgreSQL is not installed (fails under PLATENER_REQUIRE_POSTGRES=1).
//! let Some(cluster) = Cluster::for_tests() else { return };
//! let db = cluster.fresh_database().expect("a database of this test's own");
//! assert!(db.url.starts_with("postgres://platener@127.0.0.1:"));
//! // Connect to db.url with sqlx; the cluster stops when the test binary exits.
//! ```

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
