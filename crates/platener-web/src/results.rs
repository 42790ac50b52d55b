//! What a worker stores of a conversion: the summary the API shows and every file it serves.
//!
//! Everything the server answers is made here, in the worker, so the server only copies bytes
//! out of the database (it runs no step but `read` on an upload, not even to draw a scene).
//! The model scene and each method's files are made as soon as they can be (the worker stores
//! them while the others still run, `worker::live`); [`finished`] makes the rest.

use platener::convert::{Conversions, MethodResult, Status};
use platener::method::MethodKind;
use platener::scene::View;
use platener::{Error, State};
use serde_json::{Value, json};

use crate::db::{Finished, ResultFile};
use crate::summary::{MethodLine, ModelLine, StepLine, Summary};

/// The `method` of result files that belong to no method: the model as read, one scene for
/// every method, stored once as soon as the shared steps have read it.
pub const SHARED: &str = "shared";
/// The file name of the model scene (under [`SHARED`]).
pub const MODEL_SCENE: &str = "scenes/model.glb";

/// The content type of a ZIP.
pub const ZIP: &str = "application/zip";
/// The content type of JSON.
pub const JSON: &str = "application/json";
/// The content type of an SVG sheet.
pub const SVG: &str = "image/svg+xml";
/// The content type of a PNG preview.
pub const PNG: &str = "image/png";
/// The content type of a glTF binary scene.
pub const GLB: &str = "model/gltf-binary";
/// The content type of the assembly instructions' page.
pub const HTML: &str = "text/html; charset=utf-8";

/// What a worker stored of a conversion while it ran, so the end stores only the rest.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct Landed {
    /// The model scene is stored.
    pub model: bool,
    /// The methods whose files are stored.
    pub methods: Vec<MethodKind>,
}

/// How a finished conversion is recorded: `done` when a method converted, else `failed` with
/// the first method's error (the reader's message for an unreadable model); the files of what
/// was not `landed` while it ran. With `debug`, the debug view's snapshots are stored too
/// ([`crate::debug`]), also for a failed conversion: the steps that ran are what one debugs.
pub fn finished(all: &Conversions, debug: bool, landed: &Landed) -> Finished {
    let summary = summary(all);
    let mut files = Vec::new();
    if let Some(shared) = all.shared.as_ref().filter(|_| !landed.model) {
        files.extend(model_files(shared));
    }
    for m in all.methods.iter().filter(|m| !landed.methods.contains(&m.method)) {
        files.extend(method_files(m));
    }
    if debug {
        files.extend(crate::debug::files(all));
    }
    let (status, error) = match all.best {
        Some(_) => ("done", None),
        None => ("failed", Some(error_of(all))),
    };
    let event = match &error {
        None => json!({"status": status, "best": all.best.map(|b| b.name())}),
        Some(e) => json!({"status": status, "error": e}),
    };
    // Library messages name settings in backticks; the page shows them by their labels.
    let labelled = |text: String| crate::settings::labelled(&text);
    Finished {
        status: status.into(),
        error: error.map(|e| labelled(e.to_string())),
        summary: labelled(summary.to_json()),
        files,
        event: labelled(event.to_string()),
    }
}

/// `{"code", "message"}` of a conversion no method converted.
fn error_of(all: &Conversions) -> Value {
    let first = all.methods.iter().find_map(|m| m.error.as_ref().map(|e| (m, e)));
    match first {
        // The server reads every upload before queuing it, so this is only a fallback (jobs
        // queued before that check); the message is made safe the same way.
        Some((_, e @ Error::Read(_))) => {
            json!({"code": "unreadable_model", "message": crate::sniff::safe_message(&e.to_string())})
        }
        Some((m, e)) => {
            let code = match m.status {
                Status::TimedOut => "timed_out",
                _ => "conversion_failed",
            };
            let others: Vec<String> = all
                .methods
                .iter()
                .filter(|o| o.method != m.method)
                .filter_map(|o| o.error.as_ref().map(|e| format!("{}: {e}", o.method.name())))
                .collect();
            let mut message = format!("no method converted the model; {}: {e}", m.method.name());
            for o in others {
                message.push_str("; ");
                message.push_str(&o);
            }
            json!({"code": code, "message": message})
        }
        None => json!({"code": "conversion_failed", "message": "no method converted the model"}),
    }
}

/// The summary: the model, the shared steps, every method and the best.
pub fn summary(all: &Conversions) -> Summary {
    Summary {
        model: all.shared.as_ref().and_then(model_line),
        steps: all.shared.as_ref().map_or_else(Vec::new, step_lines),
        methods: all.methods.iter().map(method_line).collect(),
        best: all.best.map(|b| b.name().to_string()),
        seconds: Some(all.seconds),
    }
}

/// The model as read; `None` before (or without) `read`.
pub fn model_line(state: &State) -> Option<ModelLine> {
    state.read.as_ref().map(|m| {
        let size = m.bounds.max - m.bounds.min;
        ModelLine {
            triangles: m.triangles.len(),
            bbox_mm: [size.x, size.y, size.z],
        }
    })
}

/// The records of the steps a state ran, as the summary lists them.
pub fn step_lines(state: &State) -> Vec<StepLine> {
    state
        .records
        .iter()
        .map(|r| StepLine {
            name: r.name.to_string(),
            ms: r.millis,
            warnings: r.warnings.iter().map(|w| json!(w)).collect(),
        })
        .collect()
}

/// A method's line of the summary.
pub fn method_line(m: &MethodResult) -> MethodLine {
    let plan = m.bundle().map(|b| &b.plan);
    MethodLine {
        method: m.method.name().to_string(),
        status: status_name(m.status).to_string(),
        score: m.score.as_ref().map(|s| s.total),
        parts: plan.map(|p| p.parts.len()),
        sheets: plan.map(|p| p.sheets.len()),
        glue: plan.map(platener::plan::Plan::glue_note),
        verified: m.verification.as_ref().map(|v| v.passed()),
        seconds: m.seconds,
        warnings: Some(m.warnings().map(|w| json!(w)).collect()),
        error: m.error.as_ref().map(ToString::to_string),
    }
}

/// The API's name of a method status: `done` for a plan, else the library's word.
pub fn status_name(status: Status) -> &'static str {
    match status {
        Status::Converted => "done",
        Status::Failed => "failed",
        Status::Panicked => "panicked",
        Status::TimedOut => "timed-out",
        Status::Cancelled => "cancelled",
        Status::Skipped => "skipped",
    }
}

/// The data of a `method` event (written when the method's files are stored): its line of
/// the summary without the warnings, which the conversion JSON lists.
pub fn method_event(m: &MethodResult) -> MethodLine {
    MethodLine {
        warnings: None,
        ..method_line(m)
    }
}

/// The model scene, decimated for viewing like every scene (`scene::TRIANGLE_LIMIT`), under
/// [`SHARED`]; nothing before (or without) `read`.
pub fn model_files(state: &State) -> Vec<ResultFile> {
    state.scene(View::Model).map_or_else(
        |_| Vec::new(),
        |scene| {
            vec![ResultFile {
                method: SHARED.into(),
                file: MODEL_SCENE.into(),
                content_type: GLB.into(),
                data: scene.glb,
            }]
        },
    )
}

/// A method's files: the ZIP, plan.json, report.json, the gallery's thumbnail, the assembly
/// instructions' page and pictures, sheets (SVG, PNG) and the scenes it reached but the
/// model's (one for all methods, [`model_files`]).
pub fn method_files(m: &MethodResult) -> Vec<ResultFile> {
    let method = m.method.name();
    let file = |file: String, content_type: &str, data: Vec<u8>| ResultFile {
        method: method.into(),
        file,
        content_type: content_type.into(),
        data,
    };
    let mut files = Vec::new();
    if let Some(bundle) = m.bundle() {
        files.push(file("plan.zip".into(), ZIP, bundle.zip.clone()));
        for name in ["plan.json", "report.json"] {
            if let Some(data) = bundle.files.get(name) {
                files.push(file(name.into(), JSON, data.clone()));
            }
        }
        if let Some(png) = bundle.files.get(platener::export::thumbnail::FILE) {
            files.push(file(platener::export::thumbnail::FILE.into(), PNG, png.clone()));
        }
        // The assembly instructions' page and its step pictures (issue 35), beside each other
        // as in the ZIP, so the page's relative picture links work.
        for (name, data) in &bundle.files {
            if name == "assembly.html" {
                files.push(file(name.clone(), HTML, data.clone()));
            } else if name.starts_with("assembly/step-") && name.ends_with(".png") {
                files.push(file(name.clone(), PNG, data.clone()));
            }
        }
        for (i, sheet) in bundle.plan.sheets.iter().enumerate() {
            let n = i + 1;
            if let Some(svg) = bundle.files.get(&sheet.file) {
                files.push(file(format!("sheets/{n}.svg"), SVG, svg.clone()));
            }
            let png_name = sheet.file.strip_suffix(".svg").map(|s| format!("{s}.png"));
            if let Some(png) = png_name.and_then(|p| bundle.files.get(&p)) {
                files.push(file(format!("sheets/{n}.png"), PNG, png.clone()));
            }
        }
    }
    if let Some(state) = &m.state {
        for view in View::ALL.into_iter().filter(|v| *v != View::Model) {
            if let Ok(scene) = state.scene(view) {
                files.push(file(format!("scenes/{view}.glb"), GLB, scene.glb));
            }
        }
    }
    files
}
