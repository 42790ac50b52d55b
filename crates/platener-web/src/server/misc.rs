//! Gallery, test strip, metrics, the 404 fallback and the request counter.

use std::collections::BTreeMap;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::{Arc, Mutex};

use axum::Json;
use axum::extract::{Query, Request, State};
use axum::http::{StatusCode, header};
use axum::middleware::Next;
use axum::response::{IntoResponse, Response};
use platener::plan::Material;
use platener::swatches::strip::test_strip_marking;
use serde::Deserialize;
use serde_json::{Value, json};

use super::App;
use super::error::{ApiError, ApiResult};
use crate::summary::Summary;

/// Counters the server keeps in memory (the rest of /metrics comes from the database).
#[derive(Debug, Default)]
pub struct Metrics {
    /// Responses by status code.
    pub responses: Mutex<BTreeMap<u16, u64>>,
    /// Uploads and recuts accepted.
    pub accepted: AtomicU64,
}

/// Counts every response by status.
pub async fn count_requests(State(app): State<Arc<App>>, request: Request, next: Next) -> Response {
    let response = next.run(request).await;
    let mut counts = app
        .metrics
        .responses
        .lock()
        .unwrap_or_else(std::sync::PoisonError::into_inner);
    *counts.entry(response.status().as_u16()).or_insert(0) += 1;
    response
}

/// Anything not routed.
pub async fn not_found() -> ApiError {
    ApiError::not_found("page")
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

/// `?thickness=&material=&kerf=` of the test strip; `kerf` (an extension of api.md) is the
/// kerf in use, starred in the strip's table (default: the material's).
#[derive(Debug, Deserialize)]
pub struct StripQuery {
    thickness: Option<f64>,
    material: Option<String>,
    kerf: Option<f64>,
}

fn strip(
    query: Result<Query<StripQuery>, axum::extract::rejection::QueryRejection>,
) -> ApiResult<(platener::swatches::strip::TestStrip, Material, f64)> {
    let Query(q) = query.map_err(|_| ApiError::bad_request("thickness and kerf must be numbers of mm"))?;
    let thickness = q.thickness.unwrap_or(3.0);
    let material = match q.material.as_deref().unwrap_or("wood") {
        "wood" => Material::Wood,
        "acrylic" => Material::Acrylic,
        "cardboard" => Material::Cardboard,
        "paper" => Material::Paper,
        _ => {
            return Err(ApiError::bad_request(
                "material must be wood, acrylic, cardboard or paper",
            ));
        }
    };
    if !(thickness.is_finite() && thickness > 0.0 && thickness <= 50.0) {
        return Err(ApiError::bad_request(
            "thickness must be a number of mm above 0 and at most 50",
        ));
    }
    let kerf = q.kerf.unwrap_or_else(|| material.default_kerf());
    let s = test_strip_marking(thickness, material, kerf).map_err(|e| ApiError::bad_request(e.to_string()))?;
    Ok((s, material, thickness))
}

/// `GET /api/test-strip.svg`.
pub async fn test_strip_svg(
    query: Result<Query<StripQuery>, axum::extract::rejection::QueryRejection>,
) -> ApiResult<Response> {
    let (s, _, _) = strip(query)?;
    Ok((
        [
            (header::CONTENT_TYPE, "image/svg+xml"),
            (
                header::CONTENT_SECURITY_POLICY,
                "default-src 'none'; style-src 'unsafe-inline'; sandbox",
            ),
        ],
        s.svg(),
    )
        .into_response())
}

/// `GET /api/test-strip.json`: its holes and the kerf each stands for.
pub async fn test_strip_json(
    query: Result<Query<StripQuery>, axum::extract::rejection::QueryRejection>,
) -> ApiResult<Json<Value>> {
    let (s, material, thickness) = strip(query)?;
    // Each hole's drawn ring (the strip's holes, left to right) and both outlines let a page
    // draw the strip at true proportions.
    let holes: Vec<Value> = s
        .holes
        .iter()
        .zip(&s.strip.holes)
        .map(|(h, ring)| json!({"number": h.number, "kerf": h.kerf, "width": h.width, "ring": points(ring)}))
        .collect();
    Ok(Json(json!({
        "thickness": thickness,
        "material": material.name(),
        "width": s.width,
        "height": s.height,
        "default_hole": s.default_hole,
        "marked_hole": s.marked_hole,
        "holes": holes,
        "strip": points(&s.strip.outer),
        "spike": points(&s.spike.outer),
        "engrave": s.strip_engrave.iter().chain(&s.spike_engrave).map(Vec::as_slice).map(points).collect::<Vec<_>>(),
    })))
}

/// A ring as `[[x, y], …]`, mm.
fn points(ring: &[platener::glam::DVec2]) -> Value {
    ring.iter().map(|p| json!([p.x, p.y])).collect()
}

/// Upper bounds of the conversion time histogram, ms.
const BUCKETS_MS: [i64; 8] = [500, 1000, 2000, 5000, 10_000, 30_000, 60_000, 120_000];

/// `GET /metrics`: Prometheus text.
pub async fn metrics(State(app): State<Arc<App>>) -> ApiResult<Response> {
    use std::fmt::Write as _;
    let mut s = String::new();
    let _ = writeln!(s, "# HELP platener_http_responses_total Responses by status code.");
    let _ = writeln!(s, "# TYPE platener_http_responses_total counter");
    let responses = app
        .metrics
        .responses
        .lock()
        .unwrap_or_else(std::sync::PoisonError::into_inner)
        .clone();
    for (code, n) in responses {
        let _ = writeln!(s, "platener_http_responses_total{{status=\"{code}\"}} {n}");
    }
    let _ = writeln!(s, "# TYPE platener_uploads_accepted_total counter");
    let _ = writeln!(
        s,
        "platener_uploads_accepted_total {}",
        app.metrics.accepted.load(Ordering::Relaxed)
    );
    let _ = writeln!(s, "# HELP platener_conversions Conversions in the database by status.");
    let _ = writeln!(s, "# TYPE platener_conversions gauge");
    for (status, n) in app.db.counts().await? {
        let _ = writeln!(s, "platener_conversions{{status=\"{status}\"}} {n}");
    }
    let _ = writeln!(s, "# TYPE platener_queue_length gauge");
    let _ = writeln!(s, "platener_queue_length {}", app.db.queue_len().await?);
    let _ = writeln!(s, "# TYPE platener_workers gauge");
    let _ = writeln!(s, "platener_workers {}", app.roster.census().live);
    let (counts, n, total) = app.db.durations(&BUCKETS_MS).await?;
    let _ = writeln!(
        s,
        "# HELP platener_conversion_seconds Time from a worker's first claim to the result."
    );
    let _ = writeln!(s, "# TYPE platener_conversion_seconds histogram");
    for (b, c) in BUCKETS_MS.iter().zip(&counts) {
        let _ = writeln!(
            s,
            "platener_conversion_seconds_bucket{{le=\"{}\"}} {c}",
            *b as f64 / 1000.0
        );
    }
    let _ = writeln!(s, "platener_conversion_seconds_bucket{{le=\"+Inf\"}} {n}");
    let _ = writeln!(s, "platener_conversion_seconds_sum {}", total as f64 / 1000.0);
    let _ = writeln!(s, "platener_conversion_seconds_count {n}");
    Ok((
        StatusCode::OK,
        [(header::CONTENT_TYPE, "text/plain; version=0.0.4; charset=utf-8")],
        s,
    )
        .into_response())
}
