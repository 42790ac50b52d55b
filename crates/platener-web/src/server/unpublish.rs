//! `DELETE /api/conversions/{id}/publish` (an extension of api.md): the owner takes a
//! published conversion out of the gallery again.
//!
//! Publishing shows a model to everyone, so the page asks before it publishes and offers this
//! undo; the same delete token that publishes (`Authorization: Bearer`) unpublishes. The
//! conversion stays reachable by its id, as it was before publishing. Unpublishing a
//! conversion that is not published changes nothing and answers the same way, so a retried
//! request is harmless.

use std::sync::Arc;

use axum::Json;
use axum::extract::{Path, State};
use axum::http::HeaderMap;
use serde_json::Value;

use super::App;
use super::api::{authorize, load, show};
use super::error::ApiResult;

/// `DELETE /api/conversions/{id}/publish` with the delete token: the conversion, now private.
pub async fn unpublish(
    State(app): State<Arc<App>>,
    Path(id): Path<String>,
    headers: HeaderMap,
) -> ApiResult<Json<Value>> {
    let row = load(&app, &id).await?;
    authorize(&headers, &row)?;
    app.db.unpublish(&row.id).await?;
    show(State(app), Path(id)).await
}
