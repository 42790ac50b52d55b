//! The platener web service (issue 17): an HTTP API over a job queue in a database, with
//! conversions run by `platener worker` processes, never by the server.
//!
//! - [`db`]: jobs, events and results in SQLite (default) or PostgreSQL.
//! - [`worker`]: the worker process's loop: claim a job, run [`platener::convert_all`], store.
//! - [`server`]: the axum server, its worker processes, the gallery's examples.
//! - [`results`]: what a worker stores of a conversion (summary, ZIP, sheets, scenes);
//!   [`debug`]: every step's snapshot for the debug view, when asked for.
//! - [`settings`], [`sniff`], [`ids`]: upload settings, formats by content, random ids and
//!   hashed delete tokens.
//!
//! docs/architecture.md: this crate may use `platener`; the CLI calls [`server::serve`] and
//! [`worker::run`] and does nothing else.

pub mod db;
pub mod debug;
pub mod ids;
pub mod results;
pub mod server;
pub mod settings;
pub mod sniff;
pub mod summary;
pub mod worker;

pub use server::{ServeConfig, ServeError, serve};
pub use worker::{WorkerConfig, WorkerError};
