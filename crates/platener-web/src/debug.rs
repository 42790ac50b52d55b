//! The debug view's files, made by the worker for a conversion submitted with `debug=true`:
//! per method, `debug/index.json` (its steps in order with time, warning count, input step
//! and scene) and `debug/{step}.json` (the step's bounded snapshot, [`platener::debug`]).
//!
//! They are made in the worker like every other result, so the server only copies bytes out
//! of the database. Scenes are not stored again: a snapshot never changes after its step, so
//! the method's `scenes/{view}.glb` already draws it; the index names the view.

use platener::convert::{Conversions, MethodResult};
use serde_json::json;

use crate::db::ResultFile;
use crate::results::JSON;

/// The index file of a method's debug snapshots.
pub const INDEX: &str = "debug/index.json";

/// The debug files of every method that reached a step.
pub fn files(all: &Conversions) -> Vec<ResultFile> {
    all.methods.iter().flat_map(method_files).collect()
}

fn method_files(m: &MethodResult) -> Vec<ResultFile> {
    let Some(state) = &m.state else {
        return Vec::new();
    };
    let method = m.method.name();
    let file = |name: String, value: &serde_json::Value| ResultFile {
        method: method.into(),
        file: name,
        content_type: JSON.into(),
        data: value.to_string().into_bytes(),
    };
    let steps = platener::debug::steps(state);
    let index: Vec<serde_json::Value> = steps
        .iter()
        .map(|s| {
            json!({"step": s.step, "input": s.input, "ms": s.millis, "warnings": s.warnings.len(),
                   "view": s.view, "view_exact": s.view_exact})
        })
        .collect();
    let mut out = vec![file(INDEX.into(), &json!({"method": method, "steps": index}))];
    for s in &steps {
        let value = serde_json::to_value(s).unwrap_or_default();
        out.push(file(format!("debug/{}.json", s.step), &value));
    }
    out
}
