//! `GET /api/gallery`: the published conversions, newest first (the page's first gallery page
//! is made here too).

use std::sync::Arc;

use axum::extract::{Query, State};
use axum::routing::get;
use axum::{Json, Router};
use serde::Deserialize;
use serde_json::{Value, json};

use super::App;
use super::error::{ApiError, ApiResult};
use crate::summary::Summary;

/// The routes of this resource.
pub fn routes() -> Router<Arc<App>> {
    Router::new().route("/api/gallery", get(gallery))
}

/// Gallery entries per page.
pub const GALLERY_PAGE: i64 = 20;

/// `?page=`.
#[derive(Debug, Deserialize)]
pub struct PageQuery {
    page: Option<i64>,
}

/// `GET /api/gallery?page=N`: published conversions, newest first.
pub async fn gallery(
    State(app): State<Arc<App>>,
    query: Result<Query<PageQuery>, axum::extract::rejection::QueryRejection>,
) -> ApiResult<Json<Value>> {
    let Query(query) = query.map_err(|_| ApiError::bad_request("page must be a number from 1"))?;
    let page = query.page.unwrap_or(1);
    if page < 1 {
        return Err(ApiError::bad_request("page must be a number from 1"));
    }
    Ok(Json(gallery_page(&app, page).await?))
}

/// One gallery page as JSON (the API and the placeholder page share it).
pub async fn gallery_page(app: &App, page: i64) -> ApiResult<Value> {
    let rows = app.db.gallery(page, GALLERY_PAGE + 1).await?;
    let more = rows.len() as i64 > GALLERY_PAGE;
    let items: Vec<Value> = rows
        .iter()
        .take(usize::try_from(GALLERY_PAGE).unwrap_or(20))
        .map(|r| {
            let summary = Summary::parse(r.summary.as_deref());
            let best = summary.best.as_deref();
            let method = summary.best_line();
            let base = format!("/api/conversions/{}", r.id);
            json!({
                "id": r.id,
                "name": r.name,
                "status": r.status,
                "best": best,
                "parts": method.and_then(|m| m.parts),
                "score": method.and_then(|m| m.score),
                "thumbnail": best.map(|b| format!("{base}/methods/{b}/thumbnail.png")),
                "published": super::view::iso_time(r.published),
                "links": {"self": base},
            })
        })
        .collect();
    Ok(json!({
        "page": page,
        "items": items,
        "next": more.then(|| format!("/api/gallery?page={}", page + 1)),
    }))
}
