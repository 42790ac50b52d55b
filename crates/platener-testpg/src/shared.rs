//! One cluster per test binary, and the skip-or-fail policy of tests that need PostgreSQL.

use std::sync::OnceLock;

use crate::{Binaries, Cluster, Error};

/// Set to `1` (as `.ci/run` does) to make a missing PostgreSQL fail the tests instead of
/// skipping them.
pub const REQUIRE_POSTGRES: &str = "PLATENER_REQUIRE_POSTGRES";

impl Cluster {
    /// The test binary's cluster, started on first use. Starting one takes a second or two, so the
    /// tests of a binary share it and each takes a [`Cluster::fresh_database`]. It is never
    /// dropped (statics are not), so its watchdog stops it when the process exits.
    pub fn shared() -> Result<&'static Cluster, &'static Error> {
        static SHARED: OnceLock<Result<Cluster, Error>> = OnceLock::new();
        SHARED.get_or_init(Cluster::start).as_ref()
    }

    /// The shared cluster for a test, or `None` after printing why the test skips: PostgreSQL is
    /// not installed and [`REQUIRE_POSTGRES`] is not `1`. Any other failure panics: PostgreSQL is
    /// there and broken, which a skip would hide.
    pub fn for_tests() -> Option<&'static Cluster> {
        match Cluster::shared() {
            Ok(cluster) => Some(cluster),
            Err(err) => skip_or_panic(err),
        }
    }

    /// A cluster of the test's own (for tests of starting and stopping), with the same policy as
    /// [`Cluster::for_tests`].
    pub fn own_for_tests() -> Option<Cluster> {
        match Cluster::start() {
            Ok(cluster) => Some(cluster),
            Err(err) => skip_or_panic(&err),
        }
    }

    /// Whether PostgreSQL is installed, for tests that start their clusters in another process:
    /// `false` after printing why the test skips, with the same policy as [`Cluster::for_tests`].
    pub fn installed_for_tests() -> bool {
        match Binaries::find() {
            Ok(_) => true,
            Err(err) => skip_or_panic::<()>(&err).is_some(),
        }
    }
}

/// `None` with a message when `err` is a missing installation that may be skipped, else panics.
fn skip_or_panic<T>(err: &Error) -> Option<T> {
    let required = std::env::var_os(REQUIRE_POSTGRES).is_some_and(|v| v == "1");
    match err {
        Error::NotInstalled { .. } if !required => {
            eprintln!("skipping: {err}");
            None
        }
        Error::NotInstalled { .. } => panic!("{err}, and {REQUIRE_POSTGRES}=1 requires it"),
        _ => panic!("could not start a throwaway PostgreSQL cluster: {err}"),
    }
}
