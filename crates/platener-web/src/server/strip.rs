//! `GET /api/test-strip.svg` and `.json`: the kerf test strip for a sheet and material.

use std::sync::Arc;

use axum::extract::Query;
use axum::http::header;
use axum::response::{IntoResponse, Response};
use axum::routing::get;
use axum::{Json, Router};
use platener::plan::Material;
use platener::swatches::strip::test_strip_marking;
use serde::Deserialize;
use serde_json::{Value, json};

use super::App;
use super::error::{ApiError, ApiResult};

/// The routes of this resource.
pub fn routes() -> Router<Arc<App>> {
    Router::new()
        .route("/api/test-strip.svg", get(test_strip_svg))
        .route("/api/test-strip.json", get(test_strip_json))
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
    // The slot row (an extension of api.md): each slot's sheet thickness, drawn width and ring.
    let slots: Vec<Value> = s
        .slots
        .iter()
        .zip(&s.strip.holes[s.holes.len()..])
        .map(|(slot, ring)| json!({"sheet": slot.sheet, "width": slot.width, "ring": points(ring)}))
        .collect();
    Ok(Json(json!({
        "thickness": thickness,
        "material": material.name(),
        "width": s.width,
        "height": s.height,
        "default_hole": s.default_hole,
        "marked_hole": s.marked_hole,
        "holes": holes,
        "slots": slots,
        "strip": points(&s.strip.outer),
        "spike": points(&s.spike.outer),
        "engrave": s.strip_engrave.iter().chain(&s.spike_engrave).map(Vec::as_slice).map(points).collect::<Vec<_>>(),
    })))
}

/// A ring as `[[x, y], …]`, mm.
fn points(ring: &[platener::glam::DVec2]) -> Value {
    ring.iter().map(|p| json!([p.x, p.y])).collect()
}
