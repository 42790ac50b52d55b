//! The conversion endpoints: upload, show, recut, delete (events are in `events`, publishing
//! in `publish`).

use std::net::SocketAddr;
use std::sync::Arc;
use std::sync::atomic::Ordering;

use axum::Json;
use axum::extract::multipart::{Multipart, MultipartRejection};
use axum::extract::{ConnectInfo, Path, State};
use axum::http::{HeaderMap, StatusCode, header};
use axum::response::{IntoResponse, Response};
use serde_json::Value;

use super::error::{ApiError, ApiResult};
use super::{App, inspect, view};
use crate::db::{JobRow, NewJob, now_ms};
use crate::ids;
use crate::settings::{JobSettings, SettingsError};
use crate::sniff;

/// Bytes a multipart form may have beyond the model (boundaries, headers, settings fields).
pub const FORM_SLACK: usize = 64 * 1024;

/// `POST /api/conversions`.
pub async fn create(
    State(app): State<Arc<App>>,
    ConnectInfo(peer): ConnectInfo<SocketAddr>,
    headers: HeaderMap,
    form: Result<Multipart, MultipartRejection>,
) -> ApiResult<Response> {
    admit(&app, peer).await?;
    let limit = app.config.max_upload_bytes();
    let declared = headers
        .get(header::CONTENT_LENGTH)
        .and_then(|v| v.to_str().ok())
        .and_then(|v| v.parse::<usize>().ok());
    if declared.is_some_and(|n| n > limit + FORM_SLACK) {
        return Err(too_large(&app));
    }
    let form = form.map_err(|_| ApiError::bad_request("send the model as a multipart/form-data field named model"))?;
    let upload = read_form(form, &app).await?;
    let model = upload
        .model
        .ok_or_else(|| ApiError::bad_request("the form has no field named model"))?;
    enqueue(&app, model, upload.name, upload.settings, None).await
}

/// What an upload form held.
struct Upload {
    model: Option<Vec<u8>>,
    name: Option<String>,
    settings: JobSettings,
}

async fn read_form(mut form: Multipart, app: &App) -> ApiResult<Upload> {
    let mut upload = Upload {
        model: None,
        name: None,
        settings: JobSettings::default(),
    };
    let body_error = |e: axum::extract::multipart::MultipartError| {
        if e.status() == StatusCode::PAYLOAD_TOO_LARGE {
            too_large(app)
        } else {
            ApiError::bad_request("the multipart form could not be read")
        }
    };
    while let Some(field) = form.next_field().await.map_err(body_error)? {
        let field_name = field.name().unwrap_or_default().to_string();
        match field_name.as_str() {
            "model" => {
                if upload.name.is_none() {
                    upload.name = field.file_name().map(str::to_string);
                }
                let bytes = field.bytes().await.map_err(body_error)?;
                if bytes.len() > app.config.max_upload_bytes() {
                    return Err(too_large(app));
                }
                upload.model = Some(bytes.to_vec());
            }
            "name" => upload.name = Some(field.text().await.map_err(body_error)?),
            other => {
                let value = field.text().await.map_err(body_error)?;
                upload
                    .settings
                    .set_field(other, &value)
                    .map_err(ApiError::bad_request)?;
            }
        }
    }
    Ok(upload)
}

fn too_large(app: &App) -> ApiError {
    ApiError::too_large(format!(
        "the upload is larger than this server's limit of {} MB; simplify or split the model",
        app.config.max_upload_mb
    ))
}

/// Refuses work while draining, above the per-address rate or with a full queue.
async fn admit(app: &App, peer: SocketAddr) -> ApiResult<()> {
    if app.draining.load(Ordering::SeqCst) {
        return Err(ApiError::busy("the server is restarting; try again in a minute", 60));
    }
    if let Err(wait) = app.limiter.check(peer.ip()) {
        return Err(ApiError::rate_limited(wait));
    }
    if app.db.queue_len().await? >= app.config.max_queue {
        return Err(ApiError::busy(
            "the conversion queue is full; try again in a minute",
            30,
        ));
    }
    Ok(())
}

/// Checks a model's first bytes and its settings, reads it ([`inspect`]) and stores the job;
/// answers `202` with the conversion (the model's triangles and bounding box as read), its
/// `Location` and its delete token (the only time the token is shown).
async fn enqueue(
    app: &App,
    model: Vec<u8>,
    name: Option<String>,
    settings: JobSettings,
    parent: Option<String>,
) -> ApiResult<Response> {
    let sniffed = sniff::sniff(&model, app.config.max_triangles).map_err(ApiError::from)?;
    let (library, _) = settings.to_library().map_err(|e| match e {
        SettingsError::Unknown(m) => ApiError::bad_request(m),
        SettingsError::OutOfRange(m) => ApiError::invalid_setting(m),
    })?;
    let name = format!("{}.{}", safe_stem(name.as_deref()), sniffed.format.extension());
    let limits = inspect::ReadLimits {
        max_triangles: app.config.max_triangles,
        max_unpacked: (app.config.max_upload_bytes() as u64).saturating_mul(inspect::UNPACK_FACTOR),
    };
    let (model, inspected) = inspect::read(name.clone(), model, library, limits).await?;
    let token = ids::token();
    let job = NewJob {
        id: ids::conversion_id(),
        name,
        model,
        triangles: i64::try_from(inspected.triangles).ok(),
        settings: serde_json::to_string(&settings).map_err(|_| ApiError::internal())?,
        created: now_ms(),
        delete_token_hash: ids::hash_token(&token),
        published: None,
        parent,
    };
    app.db.insert_job(&job).await?;
    app.metrics.accepted.fetch_add(1, Ordering::Relaxed);
    let mut body = view::conversion(&accepted(&job), &[]);
    body["model"]["bbox_mm"] = serde_json::json!(inspected.bbox_mm);
    body["queue_ahead"] = serde_json::json!(app.db.queue_ahead(&job.id, job.created).await?);
    body["delete_token"] = Value::String(token);
    let location = format!("/api/conversions/{}", job.id);
    Ok((StatusCode::ACCEPTED, [(header::LOCATION, location)], Json(body)).into_response())
}

/// The job as it was stored, for the `202`: built from what was inserted rather than read
/// back, since a worker may already have claimed it (api.md answers `202` in state `queued`).
fn accepted(job: &NewJob) -> JobRow {
    JobRow {
        id: job.id.clone(),
        status: "queued".into(),
        name: job.name.clone(),
        model_bytes: i64::try_from(job.model.len()).unwrap_or(i64::MAX),
        triangles: job.triangles,
        settings: job.settings.clone(),
        created: job.created,
        started: None,
        finished: None,
        attempts: 0,
        worker: None,
        error: None,
        summary: None,
        delete_token_hash: job.delete_token_hash.clone(),
        published: job.published,
        parent: job.parent.clone(),
    }
}

/// A model name safe everywhere it appears: the ASCII letters, digits, `-` and `_` of the
/// stem, anything else `_` (never used as a path), at most 60 characters, `model` when nothing
/// is left.
pub fn safe_stem(name: Option<&str>) -> String {
    let name = name.unwrap_or_default();
    let base = name.rsplit(['/', '\\']).next().unwrap_or_default();
    let stem = base.rsplit_once('.').map_or(base, |(s, _)| s);
    let clean: String = stem
        .chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || c == '-' || c == '_' {
                c
            } else {
                '_'
            }
        })
        .take(60)
        .collect();
    let clean = clean.trim_matches('_').to_string();
    if clean.is_empty() { "model".into() } else { clean }
}

/// Loads a job by an id of the right shape, else 404.
pub(super) async fn load(app: &App, id: &str) -> ApiResult<JobRow> {
    if !ids::is_conversion_id(id) {
        return Err(ApiError::not_found("conversion"));
    }
    app.db.job(id).await?.ok_or_else(|| ApiError::not_found("conversion"))
}

/// `GET /api/conversions/{id}`.
pub async fn show(State(app): State<Arc<App>>, Path(id): Path<String>) -> ApiResult<Json<Value>> {
    let row = load(&app, &id).await?;
    Ok(Json(shown(&app, &row).await?))
}

/// The conversion JSON of a stored job, with `queue_ahead` (an extension of api.md): while
/// it is queued, how many queued jobs a worker takes before it; otherwise null.
async fn shown(app: &App, row: &JobRow) -> ApiResult<Value> {
    let files = app.db.result_index(&row.id).await?;
    let mut body = view::conversion(row, &files);
    body["queue_ahead"] = match row.status.as_str() {
        "queued" => serde_json::json!(app.db.queue_ahead(&row.id, row.created).await?),
        _ => Value::Null,
    };
    Ok(body)
}

/// Checks the `Authorization: Bearer` token against the job's stored hash.
pub(super) fn authorize(headers: &HeaderMap, row: &JobRow) -> ApiResult<()> {
    let token = headers
        .get(header::AUTHORIZATION)
        .and_then(|v| v.to_str().ok())
        .and_then(|v| v.strip_prefix("Bearer "))
        .ok_or_else(ApiError::unauthorized)?;
    if ids::same(&ids::hash_token(token.trim()), &row.delete_token_hash) {
        Ok(())
    } else {
        Err(ApiError::unauthorized())
    }
}

/// `DELETE /api/conversions/{id}`.
pub async fn delete(State(app): State<Arc<App>>, Path(id): Path<String>, headers: HeaderMap) -> ApiResult<StatusCode> {
    let row = load(&app, &id).await?;
    authorize(&headers, &row)?;
    app.db.delete(&row.id).await?;
    Ok(StatusCode::NO_CONTENT)
}

/// `POST /api/conversions/{id}/recut`: the same model with changed settings, a new conversion.
pub async fn recut(
    State(app): State<Arc<App>>,
    ConnectInfo(peer): ConnectInfo<SocketAddr>,
    Path(id): Path<String>,
    body: Result<Json<Value>, axum::extract::rejection::JsonRejection>,
) -> ApiResult<Response> {
    let row = load(&app, &id).await?;
    let Json(changes) =
        body.map_err(|_| ApiError::bad_request("the body must be JSON settings, e.g. {\"kerf\": 0.15}"))?;
    admit(&app, peer).await?;
    let settings: JobSettings = serde_json::from_str(&row.settings).map_err(|_| ApiError::internal())?;
    let settings = settings.with_changes(&changes).map_err(ApiError::bad_request)?;
    let model = app
        .db
        .model(&row.id)
        .await?
        .ok_or_else(|| ApiError::not_found("conversion"))?;
    enqueue(&app, model, Some(row.name.clone()), settings, Some(row.id)).await
}

/// The routes of the conversions resource: upload, read, delete, recut, publish and cancel
/// (its files are `files`', its events `events`', its debug view `debug`'s).
pub fn routes() -> axum::Router<std::sync::Arc<super::App>> {
    use axum::routing::{get, post};
    axum::Router::new()
        .route("/api/conversions", post(create))
        .route("/api/conversions/{id}", get(show).delete(delete))
        .route("/api/conversions/{id}/recut", post(recut))
        .route(
            "/api/conversions/{id}/publish",
            post(super::publish::publish).delete(super::publish::unpublish),
        )
        .route("/api/conversions/{id}/cancel", post(super::cancel::cancel))
}
