//! Runs a batch: `jobs` workers take models in turn and hand each to the library's
//! `convert_all` (every method, the time limit, errors and panics caught, scores, the best),
//! then write its ZIPs and sub-reports. One bad model never stops a batch. Results come back
//! in input order.

use std::path::PathBuf;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{Arc, Mutex, PoisonError, mpsc};
use std::time::Duration;

use platener::convert::{Conversions, Event, Fault, MethodResult, PanicHook, Request, Status, convert_all};
use platener::method::MethodKind;
use platener::{Cancel, Settings, Source};
use tracing::Span;
use tracing_indicatif::span_ext::IndicatifSpanExt as _;

use crate::inputs::ModelFile;
use crate::report::{MethodReport, ModelReport, VerifySummary};
use crate::setting_args::flags;

/// What every model of the batch is converted with.
#[derive(Debug, Clone)]
pub struct BatchConfig {
    /// Library settings.
    pub settings: Settings,
    /// Methods, in order.
    pub methods: Vec<MethodKind>,
    /// Per-model time limit.
    pub timeout: Option<Duration>,
    /// Where the ZIPs go.
    pub out_dir: PathBuf,
    /// Write a report per model and method.
    pub sub_reports: bool,
    /// The `joint` setting as asked for (`auto` or a style), recorded in sub-reports.
    pub joint: serde_json::Value,
    /// Workers.
    pub jobs: usize,
    /// Failures the tests inject (`PLATENER_FAULT`).
    pub faults: Vec<Fault>,
}

/// Runs every model; `done` gets each model's report in input order, as soon as it and all
/// models before it are finished. Returns all reports in input order.
pub fn run(
    models: &[ModelFile],
    config: &BatchConfig,
    progress: &Span,
    mut done: impl FnMut(&ModelReport),
) -> Vec<ModelReport> {
    let _hook = PanicHook::install();
    let next = AtomicUsize::new(0);
    let (tx, rx) = mpsc::channel::<(usize, ModelReport)>();
    let mut slots: Vec<Option<ModelReport>> = vec![None; models.len()];
    std::thread::scope(|scope| {
        for _ in 0..config.jobs.clamp(1, models.len().max(1)) {
            let tx = tx.clone();
            let next = &next;
            scope.spawn(move || {
                loop {
                    let i = next.fetch_add(1, Ordering::Relaxed);
                    let Some(model) = models.get(i) else { break };
                    let report = convert_model(model, config, models.len(), progress);
                    if tx.send((i, report)).is_err() {
                        break;
                    }
                }
            });
        }
        drop(tx);
        let mut printed = 0;
        for (i, report) in rx {
            progress.pb_inc(1);
            slots[i] = Some(report);
            while let Some(Some(r)) = slots.get(printed) {
                done(r);
                printed += 1;
            }
        }
    });
    slots.into_iter().flatten().collect()
}

/// Converts one model with every method through the library and writes its files.
fn convert_model(model: &ModelFile, config: &BatchConfig, models_at_once: usize, progress: &Span) -> ModelReport {
    let file = model.path.display().to_string();
    progress.pb_set_message(&file);
    tracing::info!(file = %file, "converting");
    let request = Request {
        methods: config.methods.clone(),
        timeout: config.timeout,
        parallel: methods_at_once(config.jobs, models_at_once),
        faults: config.faults.clone(),
        ..Request::new(Source::File(model.path.clone()), config.settings.clone())
    };
    // Each method's files are written the moment it ends, while the others still run.
    let written: Arc<Mutex<Vec<MethodReport>>> = Arc::default();
    let on_event = {
        let (written, model, config, file) = (written.clone(), model.clone(), config.clone(), file.clone());
        move |event: Event<'_>| {
            if let Event::Method(m) = event {
                let report = finish(m, &model, &config);
                tracing::info!(file = %file, method = report.method, status = ?report.status, seconds = m.seconds, "done");
                written.lock().unwrap_or_else(PoisonError::into_inner).push(report);
            }
        }
    };
    let span = tracing::info_span!(parent: progress, "model", file = %file);
    let all = span.in_scope(|| convert_all(request, &Cancel::default(), Arc::new(on_event)));
    let mut written = std::mem::take(&mut *written.lock().unwrap_or_else(PoisonError::into_inner));
    let methods: Vec<MethodReport> = all
        .methods
        .iter()
        .map(|m| match written.iter().position(|r| r.method == m.method.name()) {
            Some(k) => written.swap_remove(k),
            None => finish(m, model, config),
        })
        .collect();
    ModelReport::new(file, model.stem.clone(), model.bytes, methods, best(&all), all.seconds)
}

/// How many methods of one model run at once: the cores the batch's models leave each (all
/// methods when one model has the machine), so every method gets a core's time within its
/// own time limit.
fn methods_at_once(jobs: usize, models_at_once: usize) -> usize {
    let cores = std::thread::available_parallelism().map_or(1, usize::from);
    (cores / jobs.clamp(1, models_at_once.max(1))).max(1)
}

/// The library's best method, by name.
fn best(all: &Conversions) -> Option<&'static str> {
    all.best.map(MethodKind::name)
}

/// Writes a method's ZIP (and sub-report) and makes its report.
fn finish(result: &MethodResult, model: &ModelFile, config: &BatchConfig) -> MethodReport {
    let method = result.method;
    // Built by hand, not with `with_extension`: stems may hold dots ("tray_3.2mm").
    let base = format!("{}-{}", model.stem, method.name());
    let bundle = result.bundle().filter(|_| result.status == Status::Converted);
    let mut report = MethodReport {
        method: method.name(),
        status: result.status,
        zip: None,
        report: None,
        score: result.score.clone(),
        verify: result.verification.as_ref().map(|v| VerifySummary {
            passed: v.passed(),
            problems: v.problems.clone(),
        }),
        parts: bundle.map(|b| b.plan.parts.len()),
        sheets: bundle.map(|b| b.plan.sheets.len()),
        glue: bundle.map(|b| b.plan.glue_note()),
        fabrication: bundle.map(|b| b.report.fabrication.clone()),
        warnings: result
            .warnings()
            .map(|w| format!("[{}] {}", w.step, flags(&w.message)))
            .collect(),
        error: result.error.as_ref().map(|e| match e {
            platener::Error::TimedOut { .. } => format!("{e} (--timeout)"),
            // The status already says "skipped"; the line reads "skipped: why".
            platener::Error::Skipped { reason } => flags(reason),
            e => flags(&e.to_string()),
        }),
        seconds: result.seconds,
    };
    if let Some(bundle) = bundle {
        let zip = config.out_dir.join(format!("{base}.zip"));
        match std::fs::write(&zip, &bundle.zip) {
            Ok(()) => report.zip = Some(zip.display().to_string()),
            Err(e) => {
                report.status = Status::Failed;
                report.error = Some(format!("cannot write {}: {e}", zip.display()));
            }
        }
    }
    if config.sub_reports {
        write_sub_report(&mut report, result, model, config, &base);
    }
    report
}

/// `OUT_DIR/<model>-<method>.report.json`: score, warnings or error, the plan's report.json.
fn write_sub_report(
    report: &mut MethodReport,
    result: &MethodResult,
    model: &ModelFile,
    config: &BatchConfig,
    base: &str,
) {
    let path = config.out_dir.join(format!("{base}.report.json"));
    let library_report = result
        .bundle()
        .filter(|_| report.status == Status::Converted)
        .and_then(|b| serde_json::to_value(&b.report).ok())
        .unwrap_or(serde_json::Value::Null);
    let sub = serde_json::json!({
        "generator": concat!("platener ", env!("CARGO_PKG_VERSION")),
        "file": model.path.display().to_string(),
        "method": result.method.name(),
        "status": report.status,
        "joint": config.joint,
        "score": report.score,
        "warnings": report.warnings,
        "error": report.error,
        "report": library_report,
    });
    let written = serde_json::to_string_pretty(&sub)
        .map_err(|e| e.to_string())
        .and_then(|text| std::fs::write(&path, text + "\n").map_err(|e| e.to_string()));
    match written {
        Ok(()) => report.report = Some(path.display().to_string()),
        Err(e) => report
            .warnings
            .push(format!("[report] cannot write {}: {e}", path.display())),
    }
}
