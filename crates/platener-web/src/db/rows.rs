//! The rows the database module reads and writes.

use sqlx::Row;
use sqlx::any::AnyRow;

use super::Result;

/// A job to store.
#[derive(Debug, Clone)]
pub struct NewJob {
    /// Its random id.
    pub id: String,
    /// The model's name as shown (sanitised, with the extension of its sniffed format).
    pub name: String,
    /// The model file.
    pub model: Vec<u8>,
    /// Triangles, as the server read them at upload.
    pub triangles: Option<i64>,
    /// The settings as JSON (`crate::settings::JobSettings`).
    pub settings: String,
    /// When it was accepted (ms).
    pub created: i64,
    /// The SHA-256 of its delete token.
    pub delete_token_hash: String,
    /// When it was published (ms), or `None`: private.
    pub published: Option<i64>,
    /// The conversion it is a recut of.
    pub parent: Option<String>,
}

/// A stored job, without the model's bytes.
#[derive(Debug, Clone)]
pub struct JobRow {
    /// Its id.
    pub id: String,
    /// queued, running, done, failed, cancelled.
    pub status: String,
    /// The model's name.
    pub name: String,
    /// The model's size in bytes.
    pub model_bytes: i64,
    /// Triangles, when known at upload.
    pub triangles: Option<i64>,
    /// The settings JSON.
    pub settings: String,
    /// Times (ms).
    pub created: i64,
    /// When a worker first took it.
    pub started: Option<i64>,
    /// When it ended.
    pub finished: Option<i64>,
    /// How many times a worker took it.
    pub attempts: i64,
    /// The worker holding it.
    pub worker: Option<String>,
    /// `{"code", "message"}` when it failed.
    pub error: Option<String>,
    /// The worker's summary JSON (steps, methods, best, model) when it ended.
    pub summary: Option<String>,
    /// The SHA-256 of its delete token.
    pub delete_token_hash: String,
    /// When it was published.
    pub published: Option<i64>,
    /// The conversion it is a recut of.
    pub parent: Option<String>,
}

impl JobRow {
    pub(super) fn from_row(r: &AnyRow) -> Result<Self> {
        Ok(Self {
            id: r.try_get("id")?,
            status: r.try_get("status")?,
            name: r.try_get("name")?,
            model_bytes: r.try_get("model_bytes")?,
            triangles: r.try_get("triangles")?,
            settings: r.try_get("settings")?,
            created: r.try_get("created")?,
            started: r.try_get("started")?,
            finished: r.try_get("finished")?,
            attempts: r.try_get("attempts")?,
            worker: r.try_get("worker")?,
            error: r.try_get("error")?,
            summary: r.try_get("summary")?,
            delete_token_hash: r.try_get("delete_token")?,
            published: r.try_get("published")?,
            parent: r.try_get("parent")?,
        })
    }
}

/// A job a worker took.
#[derive(Debug, Clone)]
pub struct Claimed {
    /// Its id.
    pub id: String,
    /// The model's name (its extension picks the reader).
    pub name: String,
    /// The model file.
    pub model: Vec<u8>,
    /// The settings JSON.
    pub settings: String,
    /// This attempt's number, from 1.
    pub attempts: i64,
}

impl Claimed {
    pub(super) fn from_row(r: &AnyRow) -> Result<Self> {
        Ok(Self {
            id: r.try_get("id")?,
            name: r.try_get("name")?,
            model: r.try_get("model")?,
            settings: r.try_get("settings")?,
            attempts: r.try_get("attempts")?,
        })
    }
}

/// One progress event.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct EventRow {
    /// Its place in the job's list, from 1.
    pub seq: i64,
    /// The SSE event name: step, method, retry, done, failed.
    pub kind: String,
    /// Its JSON.
    pub data: String,
}

impl EventRow {
    pub(super) fn from_row(r: &AnyRow) -> Result<Self> {
        Ok(Self {
            seq: r.try_get("seq")?,
            kind: r.try_get("kind")?,
            data: r.try_get("data")?,
        })
    }
}

/// One result file of a job.
#[derive(Debug, Clone)]
pub struct ResultFile {
    /// The method it belongs to.
    pub method: String,
    /// Its name in the API: `plan.zip`, `sheets/1.svg`, `scenes/final.glb`, …
    pub file: String,
    /// The content type it is served with.
    pub content_type: String,
    /// Its bytes.
    pub data: Vec<u8>,
}

/// How a job ended, written in one transaction.
#[derive(Debug, Clone)]
pub struct Finished {
    /// done or failed.
    pub status: String,
    /// `{"code", "message"}` when failed.
    pub error: Option<String>,
    /// The summary JSON.
    pub summary: String,
    /// Every result file.
    pub files: Vec<ResultFile>,
    /// The data of the last event (named like the status).
    pub event: String,
}

/// A published job.
#[derive(Debug, Clone)]
pub struct GalleryRow {
    /// Its id.
    pub id: String,
    /// The model's name.
    pub name: String,
    /// Its status.
    pub status: String,
    /// Its summary JSON, when it ended.
    pub summary: Option<String>,
    /// When it was published (ms).
    pub published: i64,
}

impl GalleryRow {
    pub(super) fn from_row(r: &AnyRow) -> Result<Self> {
        Ok(Self {
            id: r.try_get("id")?,
            name: r.try_get("name")?,
            status: r.try_get("status")?,
            summary: r.try_get("summary")?,
            published: r.try_get("published")?,
        })
    }
}
