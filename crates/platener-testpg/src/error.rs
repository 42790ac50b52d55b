//! What can go wrong while starting or using a throwaway cluster.

use std::path::PathBuf;

/// Why a throwaway PostgreSQL cluster could not be started or used.
#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// No PostgreSQL server programs were found: the only error that tests may skip on.
    #[error(
        "PostgreSQL is not installed: no initdb, pg_ctl, postgres and createdb together in {searched} \
         (install the Debian package `postgresql`, or set PLATENER_PG_BIN to its bin directory)"
    )]
    NotInstalled {
        /// The places looked in, for the message.
        searched: String,
    },
    /// Running as root, and the account to run the server as does not exist.
    #[error("running as root, but the unprivileged user `{user}` to run PostgreSQL as does not exist")]
    NoUnprivilegedUser {
        /// The account looked up.
        user: String,
    },
    /// A file system or process operation failed.
    #[error("{what}: {source}")]
    Io {
        /// What was being done.
        what: String,
        /// The underlying error.
        #[source]
        source: std::io::Error,
    },
    /// A PostgreSQL program ran and failed.
    #[error("{program} failed ({status}): {output}")]
    Command {
        /// The program's path.
        program: PathBuf,
        /// Its exit status, as text.
        status: String,
        /// Its output and, when the server failed to start, the end of the server's log.
        output: String,
    },
    /// The server did not accept connections before the deadline.
    #[error("PostgreSQL did not become ready on 127.0.0.1:{port} within {seconds} s; end of its log:\n{log}")]
    NotReady {
        /// The port it was started on.
        port: u16,
        /// The deadline.
        seconds: u64,
        /// The end of the server's log.
        log: String,
    },
    /// Every port tried was taken by someone else before the server could bind it.
    #[error("no free loopback port for PostgreSQL after {attempts} attempts")]
    NoFreePort {
        /// How many ports were tried.
        attempts: usize,
    },
    /// A database name that is not a plain lower-case identifier.
    #[error("database name {0:?} is not a lower-case identifier (a-z, 0-9, _)")]
    BadDatabaseName(String),
}

impl Error {
    /// Wraps an I/O error with what was being done.
    pub(crate) fn io(what: impl Into<String>) -> impl FnOnce(std::io::Error) -> Error {
        let what = what.into();
        move |source| Error::Io { what, source }
    }
}
