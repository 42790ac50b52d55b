//! The debug view's endpoints (an extension of api.md):
//!
//! - `GET /api/conversions/{id}/debug`: per method, its steps in order with time, warnings,
//!   input step and links to the step's JSON and scene, for a conversion submitted with
//!   `debug=true` (404 `not_found` otherwise, 409 `not_ready` while it runs).
//! - `GET /api/conversions/{id}/debug/{method}/{step}.json`: one step's bounded snapshot.
//! - `GET /api/debug/models` and `GET /api/debug/models/{name}.stl`: the test set (the
//!   library's labelled samples and the shipped examples) the isolated-step mode converts.
//!
//! Everything but the test set was made by the worker ([`crate::debug`]); the server copies
//! it out of the database. The test set's STL files are written from triangles made in code,
//! which runs no step.

use std::sync::Arc;

use axum::Json;
use axum::extract::{Path, State};
use axum::http::{HeaderValue, header};
use axum::response::{IntoResponse, Response};
use serde_json::{Value, json};

use super::App;
use super::api::load;
use super::error::{ApiError, ApiResult};
use super::examples::EXAMPLES;
use super::files::{known_method, serve_file};
use crate::debug::INDEX;

/// `GET /api/conversions/{id}/debug`.
pub async fn index(State(app): State<Arc<App>>, Path(id): Path<String>) -> ApiResult<Json<Value>> {
    let row = load(&app, &id).await?;
    if matches!(row.status.as_str(), "queued" | "running") {
        return Err(ApiError::not_ready(
            "the conversion has not finished yet; follow its events",
        ));
    }
    let files = app.db.result_index(&row.id).await?;
    let base = format!("/api/conversions/{}", row.id);
    let mut methods = Vec::new();
    for (method, file) in files.iter().filter(|(_, f)| f == INDEX) {
        let Some((_, data)) = app.db.result_file(&row.id, method, file).await? else {
            continue;
        };
        let mut index: Value = serde_json::from_slice(&data).map_err(|_| ApiError::internal())?;
        let has_scene = |view: &str| {
            files
                .iter()
                .any(|(m, f)| m == method && *f == format!("scenes/{view}.glb"))
        };
        for step in index["steps"].as_array_mut().into_iter().flatten() {
            let name = step["step"].as_str().unwrap_or_default().to_string();
            step["json"] = json!(format!("{base}/debug/{method}/{name}.json"));
            step["scene"] = match step["view"].as_str() {
                Some(view) if has_scene(view) => json!(format!("{base}/scenes/{view}.glb?method={method}")),
                _ => Value::Null,
            };
        }
        methods.push(index);
    }
    if methods.is_empty() {
        return Err(ApiError::not_found(
            "debug snapshots (convert with the field debug=true to keep them)",
        ));
    }
    let settings: Value = serde_json::from_str(&row.settings).unwrap_or(Value::Null);
    Ok(Json(json!({
        "id": row.id, "status": row.status, "name": row.name, "settings": settings, "methods": methods,
    })))
}

/// `GET /api/conversions/{id}/debug/{method}/{step}.json`.
pub async fn step(
    State(app): State<Arc<App>>,
    Path((id, method, file)): Path<(String, String, String)>,
) -> ApiResult<Response> {
    known_method(&method)?;
    let step = file.strip_suffix(".json").ok_or_else(|| ApiError::not_found("step"))?;
    if !platener::pipeline::StepId::ALL.iter().any(|s| s.name() == step) {
        return Err(ApiError::not_found("step"));
    }
    let row = load(&app, &id).await?;
    serve_file(&app, &row, &method, &format!("debug/{step}.json")).await
}

/// `GET /api/debug/models`: the test set, samples first, then the examples, and the steps
/// each method runs (the step list of the isolated mode before anything ran).
pub async fn models() -> Json<Value> {
    let samples = platener_fixtures::test_set::test_set().into_iter().map(|m| {
        json!({"name": m.name, "label": m.label, "kind": "sample",
               "triangles": m.triangles.len(), "url": format!("/api/debug/models/{}.stl", m.name)})
    });
    let examples = EXAMPLES.iter().map(|(file, _)| {
        let name = file.trim_end_matches(".stl");
        json!({"name": name, "label": format!("example {file}"), "kind": "example",
               "url": format!("/api/debug/models/{name}.stl")})
    });
    let methods: serde_json::Map<String, Value> = platener::method::MethodKind::ALL
        .iter()
        .map(|m| {
            let steps: Vec<&str> = platener::pipeline::StepId::of_method(*m)
                .iter()
                .map(|s| s.name())
                .collect();
            (m.name().to_string(), json!(steps))
        })
        .collect();
    Json(json!({"models": samples.chain(examples).collect::<Vec<_>>(), "methods": methods}))
}

/// `GET /api/debug/models/{name}.stl`: a test model as binary STL.
pub async fn model(Path(file): Path<String>) -> ApiResult<Response> {
    let name = file
        .strip_suffix(".stl")
        .ok_or_else(|| ApiError::not_found("test model"))?;
    let bytes = match platener_fixtures::test_set::test_set()
        .into_iter()
        .find(|m| m.name == name)
    {
        Some(m) => platener_fixtures::samples::to_binary_stl(&m.triangles, m.name),
        None => EXAMPLES
            .iter()
            .find(|(f, _)| f.trim_end_matches(".stl") == name)
            .map(|(_, bytes)| bytes.to_vec())
            .ok_or_else(|| ApiError::not_found("test model"))?,
    };
    let mut response = bytes.into_response();
    response
        .headers_mut()
        .insert(header::CONTENT_TYPE, HeaderValue::from_static("model/stl"));
    Ok(response)
}

/// The routes of the debug view: a conversion's step snapshots and the sample models.
pub fn routes() -> axum::Router<std::sync::Arc<super::App>> {
    use axum::routing::get;
    axum::Router::new()
        .route("/api/conversions/{id}/debug", get(index))
        .route("/api/conversions/{id}/debug/{method}/{file}", get(step))
        .route("/api/debug/models", get(models))
        .route("/api/debug/models/{file}", get(model))
}
