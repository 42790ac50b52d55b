//! The API's errors: `{"error": {"code", "message"}}` with the status of api.md.
//!
//! Messages are fixed sentences or the library's own (the reader's line and problem); they
//! never quote what the client sent, and serde escapes them as JSON.

use axum::Json;
use axum::http::{HeaderValue, StatusCode, header};
use axum::response::{IntoResponse, Response};
use serde_json::json;

use crate::db::DbError;

/// An error answer.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ApiError {
    /// The HTTP status.
    pub status: StatusCode,
    /// The machine-readable code.
    pub code: &'static str,
    /// A sentence a person can act on.
    pub message: String,
    /// Seconds for a `Retry-After` header (429, 503).
    pub retry_after: Option<u64>,
}

impl ApiError {
    fn new(status: StatusCode, code: &'static str, message: impl Into<String>) -> Self {
        Self {
            status,
            code,
            message: message.into(),
            retry_after: None,
        }
    }

    /// 404: no such conversion, file or page (also for one that is private to someone else:
    /// ids are unguessable, so "not found" is all a stranger learns).
    pub fn not_found(what: &str) -> Self {
        Self::new(StatusCode::NOT_FOUND, "not_found", format!("no such {what}"))
    }

    /// 400 with a reason.
    pub fn bad_request(message: impl Into<String>) -> Self {
        Self::new(StatusCode::BAD_REQUEST, "bad_request", message)
    }

    /// 401: a missing or wrong delete token.
    pub fn unauthorized() -> Self {
        Self::new(
            StatusCode::UNAUTHORIZED,
            "unauthorized",
            "this needs the conversion's delete token as `Authorization: Bearer TOKEN`",
        )
    }

    /// 413 with a reason.
    pub fn too_large(message: impl Into<String>) -> Self {
        Self::new(StatusCode::PAYLOAD_TOO_LARGE, "too_large", message)
    }

    /// 415 with a reason.
    pub fn unsupported_format(message: impl Into<String>) -> Self {
        Self::new(StatusCode::UNSUPPORTED_MEDIA_TYPE, "unsupported_format", message)
    }

    /// 422 with the reader's message.
    pub fn unreadable_model(message: impl Into<String>) -> Self {
        Self::new(StatusCode::UNPROCESSABLE_ENTITY, "unreadable_model", message)
    }

    /// 422: a setting out of range, with the library's sentence naming it as the page does.
    pub fn invalid_setting(message: impl Into<String>) -> Self {
        Self::new(StatusCode::UNPROCESSABLE_ENTITY, "invalid_setting", message)
    }

    /// 429: too many uploads from one address.
    pub fn rate_limited(retry_after: u64) -> Self {
        Self {
            retry_after: Some(retry_after),
            ..Self::new(
                StatusCode::TOO_MANY_REQUESTS,
                "rate_limited",
                "too many uploads from your address; wait a minute and try again",
            )
        }
    }

    /// 503: the queue is full or the server is shutting down.
    pub fn busy(message: impl Into<String>, retry_after: u64) -> Self {
        Self {
            retry_after: Some(retry_after),
            ..Self::new(StatusCode::SERVICE_UNAVAILABLE, "busy", message)
        }
    }

    /// 409: the conversion is not in a state that has this (no plan yet, or it failed).
    pub fn not_ready(message: impl Into<String>) -> Self {
        Self::new(StatusCode::CONFLICT, "not_ready", message)
    }

    /// 500 for a failure of ours; the details go to the log, not to the client.
    pub fn internal() -> Self {
        Self::new(
            StatusCode::INTERNAL_SERVER_ERROR,
            "internal",
            "the server failed to answer; try again later",
        )
    }
}

impl From<DbError> for ApiError {
    fn from(e: DbError) -> Self {
        tracing::error!("database: {e}");
        ApiError::internal()
    }
}

impl IntoResponse for ApiError {
    fn into_response(self) -> Response {
        let body = json!({"error": {"code": self.code, "message": self.message}});
        let mut response = (self.status, Json(body)).into_response();
        if let Some(s) = self.retry_after {
            response.headers_mut().insert(header::RETRY_AFTER, HeaderValue::from(s));
        }
        response
    }
}

/// A handler's result.
pub type ApiResult<T> = Result<T, ApiError>;

/// Anything not routed.
pub async fn not_found() -> ApiError {
    ApiError::not_found("page")
}

impl From<crate::sniff::Refusal> for ApiError {
    /// An upload refused by its first bytes: `415`, `422` or `413`.
    fn from(refusal: crate::sniff::Refusal) -> Self {
        use crate::sniff::Refusal;
        match refusal {
            Refusal::Unsupported(m) => ApiError::unsupported_format(m),
            Refusal::Unreadable(m) => ApiError::unreadable_model(m),
            Refusal::TooLarge(m) => ApiError::too_large(m),
        }
    }
}
