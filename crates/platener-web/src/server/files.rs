//! Result files: plans, sheets and scenes, copied out of the database with fixed content
//! types (the worker chose them), ZIPs as attachments and SVGs under a CSP that runs nothing.

use std::sync::Arc;

use axum::extract::{Path, Query, State};
use axum::http::{HeaderValue, header};
use axum::response::{IntoResponse, Response};
use serde::Deserialize;

use super::App;
use super::api::load;
use super::error::{ApiError, ApiResult};
use crate::db::JobRow;
use crate::results::{HTML, MODEL_SCENE, SHARED, SVG, ZIP};

/// The best method of a finished job, from its summary.
fn best_of(row: &JobRow) -> ApiResult<String> {
    let summary = crate::summary::Summary::parse(row.summary.as_deref());
    match summary.best.as_deref() {
        Some(b) => Ok(b.to_string()),
        None if matches!(row.status.as_str(), "queued" | "running") => Err(ApiError::not_ready(
            "the conversion has not finished yet, so no best plan is chosen; follow its events \
             (each method's plan is under links.methods as soon as that method ends)",
        )),
        None if row.status == "cancelled" => Err(ApiError::not_ready(
            "this conversion was cancelled before a best plan was chosen; the plans of the methods \
             that ended before are under links.methods, or upload the model again",
        )),
        None => Err(ApiError::not_ready(
            "no method converted this model, so there is no plan",
        )),
    }
}

/// Serves one stored file of a job.
pub(super) async fn serve_file(app: &App, row: &JobRow, method: &str, file: &str) -> ApiResult<Response> {
    stored_file(app, row, method, file)
        .await?
        .ok_or_else(|| ApiError::not_found("file"))
}

/// One stored file of a job as an answer, if it is stored.
async fn stored_file(app: &App, row: &JobRow, method: &str, file: &str) -> ApiResult<Option<Response>> {
    let Some((content_type, data)) = app.db.result_file(&row.id, method, file).await? else {
        return Ok(None);
    };
    let mut response = data.into_response();
    let headers = response.headers_mut();
    headers.insert(
        header::CONTENT_TYPE,
        HeaderValue::from_str(&content_type).map_err(|_| ApiError::internal())?,
    );
    if content_type == ZIP {
        // The stored name is letters, digits, `-`, `_` and `.` only (api::safe_stem).
        let stem = row.name.rsplit_once('.').map_or(row.name.as_str(), |(s, _)| s);
        let disposition = format!("attachment; filename=\"{stem}-{method}.zip\"");
        headers.insert(
            header::CONTENT_DISPOSITION,
            HeaderValue::from_str(&disposition).map_err(|_| ApiError::internal())?,
        );
    }
    if content_type == SVG {
        headers.insert(
            header::CONTENT_SECURITY_POLICY,
            HeaderValue::from_static("default-src 'none'; style-src 'unsafe-inline'; sandbox"),
        );
    }
    if content_type == HTML {
        // The instructions: their own pictures and style, nothing else, no script.
        headers.insert(
            header::CONTENT_SECURITY_POLICY,
            HeaderValue::from_static("default-src 'none'; img-src 'self'; style-src 'unsafe-inline'; sandbox"),
        );
    }
    Ok(Some(response))
}

/// `GET /api/conversions/{id}/plan.zip`: the best method's ZIP.
pub async fn best_plan(State(app): State<Arc<App>>, Path(id): Path<String>) -> ApiResult<Response> {
    let row = load(&app, &id).await?;
    let best = best_of(&row)?;
    serve_file(&app, &row, &best, "plan.zip").await
}

/// Methods and files a URL may name (anything else is 404 without a query).
pub(super) fn known_method(method: &str) -> ApiResult<()> {
    if platener::method::MethodKind::ALL.iter().any(|m| m.name() == method) {
        Ok(())
    } else {
        Err(ApiError::not_found("method"))
    }
}

/// `GET /api/conversions/{id}/methods/{method}/{plan.zip|plan.json|report.json|thumbnail.png|assembly.html}`.
pub async fn method_file(
    State(app): State<Arc<App>>,
    Path((id, method, file)): Path<(String, String, String)>,
) -> ApiResult<Response> {
    known_method(&method)?;
    let row = load(&app, &id).await?;
    match file.as_str() {
        "plan.zip" | "plan.json" | "report.json" | "assembly.html" => serve_file(&app, &row, &method, &file).await,
        THUMBNAIL => thumbnail(&app, &row, &method).await,
        _ => Err(ApiError::not_found("file")),
    }
}

/// The gallery's picture of a method's assembly (an extension of api.md).
const THUMBNAIL: &str = platener::export::thumbnail::FILE;

/// The method's thumbnail, or for a conversion stored before thumbnails were made, its first
/// sheet's preview (what the gallery showed then), so old gallery cards keep a picture.
async fn thumbnail(app: &App, row: &JobRow, method: &str) -> ApiResult<Response> {
    match serve_file(app, row, method, THUMBNAIL).await {
        Err(e) if e.status == axum::http::StatusCode::NOT_FOUND => serve_file(app, row, method, "sheets/1.png").await,
        answer => answer,
    }
}

/// `GET /api/conversions/{id}/methods/{method}/sheets/{n}.svg|png`.
pub async fn sheet(
    State(app): State<Arc<App>>,
    Path((id, method, file)): Path<(String, String, String)>,
) -> ApiResult<Response> {
    known_method(&method)?;
    let (n, ext) = file.split_once('.').ok_or_else(|| ApiError::not_found("sheet"))?;
    let n: u32 = n.parse().map_err(|_| ApiError::not_found("sheet"))?;
    if n == 0 || !matches!(ext, "svg" | "png") {
        return Err(ApiError::not_found("sheet"));
    }
    let row = load(&app, &id).await?;
    serve_file(&app, &row, &method, &format!("sheets/{n}.{ext}")).await
}

/// `GET /api/conversions/{id}/methods/{method}/assembly/step-NN.png`: an assembly step's
/// picture (an extension of api.md, for the instructions' page).
pub async fn step_picture(
    State(app): State<Arc<App>>,
    Path((id, method, file)): Path<(String, String, String)>,
) -> ApiResult<Response> {
    known_method(&method)?;
    let digits = file
        .strip_prefix("step-")
        .and_then(|f| f.strip_suffix(".png"))
        .filter(|n| !n.is_empty() && n.bytes().all(|b| b.is_ascii_digit()));
    if digits.is_none() {
        return Err(ApiError::not_found("step picture"));
    }
    let row = load(&app, &id).await?;
    serve_file(&app, &row, &method, &format!("assembly/{file}")).await
}

/// `?method=` of a scene.
#[derive(Debug, Deserialize)]
pub struct SceneQuery {
    method: Option<String>,
}

/// `GET /api/conversions/{id}/scenes/{view}.glb[?method=]`. The model view is one scene for
/// every method, stored as soon as the model is read, so it answers while the methods still
/// run (conversions stored before that keep a copy per method, the fallback).
pub async fn scene(
    State(app): State<Arc<App>>,
    Path((id, file)): Path<(String, String)>,
    Query(query): Query<SceneQuery>,
) -> ApiResult<Response> {
    let view = file.strip_suffix(".glb").ok_or_else(|| ApiError::not_found("scene"))?;
    let view: platener::scene::View = view.parse().map_err(|_| ApiError::not_found("scene"))?;
    let row = load(&app, &id).await?;
    let chosen = query.method.filter(|m| m != "best");
    if let Some(m) = &chosen {
        known_method(m)?;
    }
    if view == platener::scene::View::Model
        && let Some(shared) = stored_file(&app, &row, SHARED, MODEL_SCENE).await?
    {
        return Ok(shared);
    }
    let method = match chosen {
        Some(m) => m,
        None => best_of(&row)?,
    };
    serve_file(&app, &row, &method, &format!("scenes/{view}.glb")).await
}

/// The routes of a conversion's files: the best plan, each method's files and sheets, scenes.
pub fn routes() -> axum::Router<std::sync::Arc<super::App>> {
    use axum::routing::get;
    axum::Router::new()
        .route("/api/conversions/{id}/plan.zip", get(best_plan))
        .route("/api/conversions/{id}/methods/{method}/{file}", get(method_file))
        .route("/api/conversions/{id}/methods/{method}/sheets/{file}", get(sheet))
        .route(
            "/api/conversions/{id}/methods/{method}/assembly/{file}",
            get(step_picture),
        )
        .route("/api/conversions/{id}/scenes/{file}", get(scene))
}
