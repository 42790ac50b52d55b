//! Every difference between SQLite and PostgreSQL, in one place.
//!
//! The rest of the crate writes one SQL text for both: `$1`-style parameters (SQLite reads
//! `$N` as the N-th argument), `BIGINT` milliseconds written by the program instead of each
//! database's time functions, and `RETURNING`, which both have. What cannot be shared is here:
//! the column type of bytes (so two migration folders), how a job is claimed, and SQLite's
//! journal mode.

use sqlx::migrate::Migrator;

/// The database behind a URL.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Dialect {
    /// One file, one machine: the default (`sqlite://DIR/platener.sqlite`).
    Sqlite,
    /// Several servers and workers on several machines (`postgres://…`).
    Postgres,
}

/// The PostgreSQL channel a worker notifies with a job's id when it commits an event of it.
pub const EVENTS_CHANNEL: &str = "platener_events";

static SQLITE_MIGRATIONS: Migrator = sqlx::migrate!("migrations/sqlite");
static POSTGRES_MIGRATIONS: Migrator = sqlx::migrate!("migrations/postgres");

impl Dialect {
    /// The dialect of a database URL, `None` for another database.
    pub fn of_url(url: &str) -> Option<Self> {
        if url.starts_with("sqlite:") {
            Some(Dialect::Sqlite)
        } else if url.starts_with("postgres://") || url.starts_with("postgresql://") {
            Some(Dialect::Postgres)
        } else {
            None
        }
    }

    /// The migrations of this dialect (the same tables; bytes are `BLOB` or `BYTEA`).
    pub fn migrator(self) -> &'static Migrator {
        match self {
            Dialect::Sqlite => &SQLITE_MIGRATIONS,
            Dialect::Postgres => &POSTGRES_MIGRATIONS,
        }
    }

    /// Statements run once after connecting. SQLite in WAL mode lets the server read while a
    /// worker writes (WAL is a property of the file, so once is enough).
    pub fn setup(self) -> &'static [&'static str] {
        match self {
            Dialect::Sqlite => &["PRAGMA journal_mode = WAL"],
            Dialect::Postgres => &[],
        }
    }

    /// Takes the oldest queued job for worker `$1` with lease end `$2` at time `$3`, and
    /// returns it. PostgreSQL skips rows another worker is locking, so workers on several
    /// machines never take the same job; SQLite has one writer at a time, so the `UPDATE`
    /// with a sub-select is already atomic.
    pub fn claim_sql(self) -> &'static str {
        match self {
            Dialect::Sqlite => {
                "UPDATE jobs SET status = 'running', attempts = attempts + 1, worker = $1, \
                 lease_until = $2, started = COALESCE(started, $3) \
                 WHERE id = (SELECT id FROM jobs WHERE status = 'queued' ORDER BY created, id LIMIT 1) \
                 AND status = 'queued' \
                 RETURNING id, name, model, settings, attempts"
            }
            Dialect::Postgres => {
                "UPDATE jobs SET status = 'running', attempts = attempts + 1, worker = $1, \
                 lease_until = $2, started = COALESCE(started, $3) \
                 WHERE id = (SELECT id FROM jobs WHERE status = 'queued' ORDER BY created, id LIMIT 1 \
                 FOR UPDATE SKIP LOCKED) \
                 RETURNING id, name, model, settings, attempts"
            }
        }
    }

    /// Notifies [`EVENTS_CHANNEL`] with the job id `$1`, or `None` where the database has no
    /// notifications (SQLite: servers poll). `pg_notify` returns `void`, which sqlx's `Any`
    /// driver cannot decode, hence the cast.
    pub fn notify_sql(self) -> Option<&'static str> {
        match self {
            Dialect::Sqlite => None,
            Dialect::Postgres => Some("SELECT CAST(pg_notify('platener_events', $1) AS TEXT) AS sent"),
        }
    }
}
