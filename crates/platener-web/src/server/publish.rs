//! Publishing: `POST /api/conversions/{id}/publish` shows a conversion in the gallery, and
//! `DELETE /api/conversions/{id}/publish` (an extension of api.md) takes it out again.
//!
//! Publishing shows a model to everyone, so the page asks before it publishes and offers the
//! undo; both need the delete token (`Authorization: Bearer`). An unpublished conversion stays
//! reachable by its id, as before it was published. Either request repeated changes nothing
//! more and answers the same way, so a retry is harmless.

use std::sync::Arc;

use axum::Json;
use axum::extract::{Path, State};
use axum::http::HeaderMap;
use serde_json::Value;

use super::App;
use super::api::{authorize, load, show};
use super::error::ApiResult;

/// `POST /api/conversions/{id}/publish` with the delete token: the conversion, now published.
pub async fn publish(
    State(app): State<Arc<App>>,
    Path(id): Path<String>,
    headers: HeaderMap,
) -> ApiResult<Json<Value>> {
    set_published(app, id, &headers, true).await
}

/// `DELETE /api/conversions/{id}/publish` with the delete token: the conversion, now private.
pub async fn unpublish(
    State(app): State<Arc<App>>,
    Path(id): Path<String>,
    headers: HeaderMap,
) -> ApiResult<Json<Value>> {
    set_published(app, id, &headers, false).await
}

/// Publishes (`on`) or unpublishes the owner's conversion; the conversion as it is now.
async fn set_published(app: Arc<App>, id: String, headers: &HeaderMap, on: bool) -> ApiResult<Json<Value>> {
    let row = load(&app, &id).await?;
    authorize(headers, &row)?;
    if on {
        app.db.publish(&row.id).await?;
    } else {
        app.db.unpublish(&row.id).await?;
    }
    show(State(app), Path(id)).await
}
