//! `GET /api/settings`: every setting a conversion takes, from the library's one definition
//! of each (`platener::options`); the page builds its form from it.

use axum::Json;
use axum::http::header;
use axum::response::IntoResponse;

/// The groups and settings, with kinds, ranges, choices, defaults and help; the same for
/// every request, so caches may keep it as long as the server runs one version.
pub async fn schema() -> impl IntoResponse {
    (
        [(header::CACHE_CONTROL, "public, max-age=300")],
        Json(platener::options::schema()),
    )
}
