//! The conversion as the API shows it (api.md, "A conversion"), from a job row, its summary
//! and the names of its result files.

use std::collections::BTreeMap;

use serde_json::{Value, json};

use crate::db::JobRow;
use crate::results::{MODEL_SCENE, SHARED};
use crate::summary::Summary;

/// An ISO 8601 UTC time of milliseconds since 1970 (`2026-11-23T18:00:00Z`).
pub fn iso_time(ms: i64) -> String {
    let secs = ms.div_euclid(1000);
    let (days, rest) = (secs.div_euclid(86_400), secs.rem_euclid(86_400));
    let (y, m, d) = civil_from_days(days);
    format!(
        "{y:04}-{m:02}-{d:02}T{:02}:{:02}:{:02}Z",
        rest / 3600,
        rest % 3600 / 60,
        rest % 60
    )
}

/// Year, month, day of a day count since 1970-01-01 (Howard Hinnant's `civil_from_days`).
fn civil_from_days(z: i64) -> (i64, i64, i64) {
    let z = z + 719_468;
    let era = z.div_euclid(146_097);
    let doe = z - era * 146_097;
    let yoe = (doe - doe / 1460 + doe / 36_524 - doe / 146_096) / 365;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let d = doy - (153 * mp + 2) / 5 + 1;
    let m = if mp < 10 { mp + 3 } else { mp - 9 };
    (yoe + era * 400 + i64::from(m <= 2), m, d)
}

/// The conversion JSON; `files` are the (method, file) names of its results.
pub fn conversion(row: &JobRow, files: &[(String, String)]) -> Value {
    let summary = Summary::parse(row.summary.as_deref());
    let settings: Value = serde_json::from_str(&row.settings).unwrap_or(Value::Null);
    let error: Value = row
        .error
        .as_deref()
        .and_then(|s| serde_json::from_str(s).ok())
        .unwrap_or(Value::Null);
    let triangles = summary.model.map(|m| m.triangles as i64).or(row.triangles);
    let best = summary.best.clone();
    json!({
        "id": row.id,
        "status": row.status,
        "created": iso_time(row.created),
        "started": row.started.map(iso_time),
        "finished": row.finished.map(iso_time),
        "attempts": row.attempts,
        "published": row.published.is_some(),
        "recut_of": row.parent,
        "model": {
            "name": row.name,
            "bytes": row.model_bytes,
            "triangles": triangles,
            "bbox_mm": summary.model.map(|m| m.bbox_mm),
        },
        "settings": settings,
        "steps": summary.steps,
        "methods": summary.methods,
        "best": best,
        "error": error,
        "links": links(&row.id, best.as_deref(), files),
    })
}

/// Every link of a conversion: its own, its events, the best plan and scenes, and per method
/// its plan, files, sheets and scenes, for every method stored so far (a running conversion
/// lists each as it lands). The model scene, stored once for all methods as soon as the model
/// is read, is in every method's scenes and in `scenes` before a best is chosen.
fn links(id: &str, best: Option<&str>, files: &[(String, String)]) -> Value {
    let base = format!("/api/conversions/{id}");
    let shared_model = files.iter().any(|(m, f)| m == SHARED && f == MODEL_SCENE);
    let mut methods: BTreeMap<&str, Value> = BTreeMap::new();
    for (method, file) in files {
        if method == SHARED || file.starts_with("debug/") {
            continue;
        }
        let entry = methods
            .entry(method)
            .or_insert_with(|| json!({"sheets": [], "previews": [], "scenes": {}}));
        let url = format!("{base}/methods/{method}/{file}");
        if let Some(n) = file.strip_prefix("sheets/") {
            let list = if n.ends_with(".svg") { "sheets" } else { "previews" };
            if let Some(a) = entry[list].as_array_mut() {
                a.push(Value::String(url));
            }
        } else if file.starts_with("assembly/") {
            // The instructions' pictures: assembly.html links them itself.
            continue;
        } else if let Some(view) = file.strip_prefix("scenes/").and_then(|v| v.strip_suffix(".glb")) {
            entry["scenes"][view] = Value::String(format!("{base}/scenes/{view}.glb?method={method}"));
        } else {
            let key = file.replace('.', "_");
            entry[key] = Value::String(url);
        }
    }
    for entry in methods.values_mut() {
        for list in ["sheets", "previews"] {
            if let Some(a) = entry[list].as_array_mut() {
                a.sort_by_key(|v| sheet_number(v.as_str().unwrap_or_default()));
            }
        }
    }
    if shared_model {
        for (method, entry) in &mut methods {
            entry["scenes"]["model"] = Value::String(format!("{base}/{MODEL_SCENE}?method={method}"));
        }
    }
    let mut scenes = best
        .and_then(|b| methods.get(b))
        .map_or_else(|| json!({}), |m| strip_method_query(&m["scenes"]));
    if shared_model {
        scenes["model"] = Value::String(format!("{base}/{MODEL_SCENE}"));
    }
    let debug = files.iter().any(|(_, f)| f == crate::debug::INDEX);
    json!({
        "self": base,
        "events": format!("{base}/events"),
        "debug": debug.then(|| format!("{base}/debug")),
        "plan": best.map(|_| format!("{base}/plan.zip")),
        "scenes": scenes,
        "methods": methods,
    })
}

/// The number of a `…/sheets/N.svg` link, for ordering 1, 2, …, 10.
fn sheet_number(url: &str) -> u64 {
    url.rsplit('/')
        .next()
        .and_then(|f| f.split('.').next())
        .and_then(|n| n.parse().ok())
        .unwrap_or(0)
}

/// The best method's scene links without `?method=` (the default is the best).
fn strip_method_query(scenes: &Value) -> Value {
    match scenes {
        Value::Object(map) => Value::Object(
            map.iter()
                .map(|(k, v)| {
                    let url = v.as_str().unwrap_or_default();
                    (
                        k.clone(),
                        Value::String(url.split('?').next().unwrap_or_default().to_string()),
                    )
                })
                .collect(),
        ),
        _ => json!({}),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn times_are_iso_utc() {
        assert_eq!(iso_time(0), "1970-01-01T00:00:00Z");
        // 2026-11-23T18:00:00Z
        assert_eq!(iso_time(1_795_456_800_000), "2026-11-23T18:00:00Z");
        assert_eq!(iso_time(951_782_400_000), "2000-02-29T00:00:00Z");
    }

    /// The model scene, stored once for all methods, is every method's and is linked before a
    /// best is chosen (a running conversion).
    #[test]
    fn the_model_scene_is_every_methods_and_is_linked_before_a_best() {
        let files: Vec<(String, String)> = [
            (SHARED, MODEL_SCENE),
            ("plate", "plan.zip"),
            ("plate", "scenes/final.glb"),
        ]
        .iter()
        .map(|(m, f)| ((*m).to_string(), (*f).to_string()))
        .collect();
        let links = links("c_1", None, &files);
        assert_eq!(
            links["scenes"],
            json!({"model": "/api/conversions/c_1/scenes/model.glb"})
        );
        let plate = &links["methods"]["plate"];
        assert_eq!(
            plate["scenes"]["model"],
            "/api/conversions/c_1/scenes/model.glb?method=plate"
        );
        assert_eq!(plate["plan_zip"], "/api/conversions/c_1/methods/plate/plan.zip");
        assert!(links["methods"].get(SHARED).is_none(), "{links}");
        assert_eq!(links["plan"], Value::Null, "no best yet");
    }
}
