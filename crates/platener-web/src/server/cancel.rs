//! `POST /api/conversions/{id}/cancel` (an extension of api.md): the owner stops a conversion.
//!
//! A queued or running conversion becomes `cancelled` at once, with a `cancelled` last event
//! ([`crate::db::Db::cancel`]); a running one's worker notices at its next progress write or
//! heartbeat, stops converting and stores nothing. A conversion that has ended is `409`.

use std::sync::Arc;

use axum::Json;
use axum::extract::{Path, State};
use axum::http::{HeaderMap, StatusCode};
use serde_json::Value;

use super::App;
use super::api::{authorize, load, show};
use super::error::{ApiError, ApiResult};
use crate::db::Cancelled;

/// `POST /api/conversions/{id}/cancel` with the delete token: the conversion, now cancelled.
pub async fn cancel(State(app): State<Arc<App>>, Path(id): Path<String>, headers: HeaderMap) -> ApiResult<Json<Value>> {
    let row = load(&app, &id).await?;
    authorize(&headers, &row)?;
    match app.db.cancel(&row.id).await? {
        Cancelled::Now => show(State(app), Path(id)).await,
        Cancelled::AlreadyEnded(status) => Err(already_ended(&status)),
        Cancelled::Missing => Err(ApiError::not_found("conversion")),
    }
}

/// 409: only a queued or running conversion can be cancelled.
fn already_ended(status: &str) -> ApiError {
    ApiError {
        status: StatusCode::CONFLICT,
        code: "already_ended",
        message: format!("this conversion has already ended ({status}); only a queued or running one can be cancelled"),
        retry_after: None,
    }
}
