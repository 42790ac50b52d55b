//! Runs a batch: `jobs` workers take models in turn; each model's methods run in a thread of
//! their own, so a model that runs past the time limit is cancelled and left behind while the
//! batch goes on. Errors and panics are caught per method; one bad model never stops a batch.
//! Results come back in input order.

use std::cell::{Cell, RefCell};
use std::panic::{self, AssertUnwindSafe};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::mpsc::{self, RecvTimeoutError};
use std::time::{Duration, Instant};

use platener::method::{MethodKind, convert};
use platener::score::Score;
use platener::{Cancel, Settings, Source};
use tracing::Span;
use tracing_indicatif::span_ext::IndicatifSpanExt as _;

use crate::args::JointArg;
use crate::inputs::ModelFile;
use crate::report::{MethodReport, ModelReport, Status};

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
    /// The joint type asked for (recorded in sub-reports).
    pub joint: JointArg,
    /// Workers.
    pub jobs: usize,
}

/// How long a timed-out model's thread is waited for after it was cancelled.
const CANCEL_GRACE: Duration = Duration::from_secs(2);

/// What a method's thread hands back.
enum Outcome {
    Converted(Box<Converted>),
    Failed {
        reason: String,
        panicked: bool,
        warnings: Vec<String>,
    },
}

struct Converted {
    zip: Vec<u8>,
    report: serde_json::Value,
    score: Option<Score>,
    parts: usize,
    sheets: usize,
    warnings: Vec<String>,
}

/// Runs every model; `done` gets each model's report in input order, as soon as it and all
/// models before it are finished. Returns all reports in input order.
pub fn run(
    models: &[ModelFile],
    config: &BatchConfig,
    progress: &Span,
    mut done: impl FnMut(&ModelReport),
) -> Vec<ModelReport> {
    let _hook = PanicCapture::install();
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
                    let report = convert_model(model, config, progress);
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

/// Converts one model with every method, within the time limit, and writes its files.
fn convert_model(model: &ModelFile, config: &BatchConfig, progress: &Span) -> ModelReport {
    let file = model.path.display().to_string();
    progress.pb_set_message(&file);
    tracing::info!(file = %file, "converting");
    let start = Instant::now();
    let cancel = Cancel::default();
    let (tx, rx) = mpsc::channel::<(usize, Outcome, f64)>();
    let thread = {
        let (path, settings, methods, cancel) = (
            model.path.clone(),
            config.settings.clone(),
            config.methods.clone(),
            cancel.clone(),
        );
        let parent = progress.clone();
        std::thread::Builder::new()
            .name(format!("model {}", model.index))
            .spawn(move || {
                let span = tracing::info_span!(parent: &parent, "model", file = %path.display());
                let _entered = span.enter();
                for (k, method) in methods.iter().enumerate() {
                    if cancel.is_cancelled() {
                        break;
                    }
                    let start = Instant::now();
                    let outcome = run_method(*method, &path, &settings, &cancel);
                    if tx.send((k, outcome, start.elapsed().as_secs_f64())).is_err() {
                        break;
                    }
                }
            })
    };
    let mut outcomes: Vec<Option<(Outcome, f64)>> = config.methods.iter().map(|_| None).collect();
    let mut missing = "the conversion thread stopped without a result".to_string();
    let mut timed_out = false;
    match thread {
        Err(e) => missing = format!("cannot start a thread: {e}"),
        Ok(handle) => {
            let deadline = config.timeout.map(|t| start + t);
            let mut received = 0;
            while received < outcomes.len() {
                let message = match deadline {
                    Some(d) => rx.recv_timeout(d.saturating_duration_since(Instant::now())),
                    None => rx.recv().map_err(|_| RecvTimeoutError::Disconnected),
                };
                match message {
                    Ok((k, outcome, seconds)) => {
                        outcomes[k] = Some((outcome, seconds));
                        received += 1;
                    }
                    Err(RecvTimeoutError::Timeout) => {
                        // The thread stops at its next cancellation check. Wait a little for
                        // it, so it does not compete with the next model for the cores, but
                        // never for long: a step that checks rarely is left behind.
                        cancel.cancel();
                        timed_out = true;
                        let grace = Instant::now() + CANCEL_GRACE;
                        while let Ok(_) | Err(RecvTimeoutError::Timeout) =
                            rx.recv_timeout(grace.saturating_duration_since(Instant::now()))
                        {
                            if Instant::now() >= grace {
                                break;
                            }
                        }
                        break;
                    }
                    Err(RecvTimeoutError::Disconnected) => break,
                }
            }
            if !timed_out {
                let _ = handle.join();
            }
        }
    }
    let limit = config.timeout.map_or(0.0, |t| t.as_secs_f64());
    let methods: Vec<MethodReport> = config
        .methods
        .iter()
        .zip(outcomes)
        .map(|(method, outcome)| match outcome {
            Some((outcome, seconds)) => finish(*method, outcome, seconds, model, config),
            None if timed_out => failed(
                *method,
                Status::TimedOut,
                format!("timed out after {limit} s (--timeout); cancelled"),
                0.0,
            ),
            None => failed(*method, Status::Failed, missing.clone(), 0.0),
        })
        .collect();
    for m in &methods {
        tracing::info!(file = %file, method = m.method, status = ?m.status, "done");
    }
    ModelReport::new(
        file,
        model.stem.clone(),
        model.bytes,
        methods,
        start.elapsed().as_secs_f64(),
    )
}

fn failed(method: MethodKind, status: Status, reason: String, seconds: f64) -> MethodReport {
    MethodReport {
        method: method.name(),
        status,
        zip: None,
        report: None,
        score: None,
        parts: None,
        sheets: None,
        warnings: Vec::new(),
        error: Some(reason),
        seconds,
    }
}

/// Writes a method's ZIP (and sub-report) and makes its report.
fn finish(method: MethodKind, outcome: Outcome, seconds: f64, model: &ModelFile, config: &BatchConfig) -> MethodReport {
    // Built by hand, not with `with_extension`: stems may hold dots ("tray_3.2mm").
    let base = format!("{}-{}", model.stem, method.name());
    let (mut report, library_report) = match outcome {
        Outcome::Failed {
            reason,
            panicked,
            warnings,
        } => {
            let status = if panicked { Status::Panicked } else { Status::Failed };
            let mut r = failed(method, status, reason, seconds);
            r.warnings = warnings;
            (r, serde_json::Value::Null)
        }
        Outcome::Converted(c) => {
            let zip = config.out_dir.join(format!("{base}.zip"));
            let mut r = MethodReport {
                method: method.name(),
                status: Status::Converted,
                zip: Some(zip.display().to_string()),
                report: None,
                score: c.score,
                parts: Some(c.parts),
                sheets: Some(c.sheets),
                warnings: c.warnings,
                error: None,
                seconds,
            };
            if let Err(e) = std::fs::write(&zip, &c.zip) {
                r.status = Status::Failed;
                r.zip = None;
                r.error = Some(format!("cannot write {}: {e}", zip.display()));
            }
            (r, c.report)
        }
    };
    if config.sub_reports {
        let path = config.out_dir.join(format!("{base}.report.json"));
        let sub = serde_json::json!({
            "generator": concat!("platener ", env!("CARGO_PKG_VERSION")),
            "file": model.path.display().to_string(),
            "method": method.name(),
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
    report
}

/// Converts with one method and scores the result; errors and panics become `Failed`.
fn run_method(method: MethodKind, path: &Path, settings: &Settings, cancel: &Cancel) -> Outcome {
    let span = tracing::info_span!("method", name = method.name());
    let _entered = span.enter();
    let result = PanicCapture::catch(|| -> Result<Converted, String> {
        crate::fault::inject(method, cancel)?;
        let conversion =
            convert(method, Source::File(path.to_path_buf()), settings.clone(), cancel).map_err(|e| e.to_string())?;
        let bundle = conversion.bundle().map_err(|e| e.to_string())?;
        let mut warnings: Vec<String> = conversion
            .steps
            .iter()
            .flat_map(|s| s.warnings.iter().map(move |w| format!("[{}] {}", s.name, w.message)))
            .collect();
        let score = match platener::score::score(&conversion) {
            Ok(score) => Some(score),
            Err(e) => {
                warnings.push(format!("[score] {e}"));
                None
            }
        };
        Ok(Converted {
            zip: bundle.zip.clone(),
            report: serde_json::to_value(&bundle.report).unwrap_or(serde_json::Value::Null),
            score,
            parts: bundle.plan.parts.len(),
            sheets: bundle.plan.sheets.len(),
            warnings,
        })
    });
    match result {
        // An empty plan is nothing to cut: a failure, with the warnings that say why.
        Ok(Ok(c)) if c.parts == 0 => Outcome::Failed {
            reason: format!(
                "the {} method made no parts to cut (the warnings say why; `platener inspect --plates` shows more)",
                method.name()
            ),
            panicked: false,
            warnings: c.warnings,
        },
        Ok(Ok(c)) => Outcome::Converted(Box::new(c)),
        Ok(Err(reason)) => Outcome::Failed {
            reason,
            panicked: false,
            warnings: Vec::new(),
        },
        Err(reason) => Outcome::Failed {
            reason,
            panicked: true,
            warnings: Vec::new(),
        },
    }
}

thread_local! {
    /// Whether this thread is running a conversion under [`PanicCapture::catch`].
    static CAPTURING: Cell<bool> = const { Cell::new(false) };
    /// Where the last captured panic of this thread happened.
    static LOCATION: RefCell<Option<String>> = const { RefCell::new(None) };
}

/// A panic hook that, inside conversions, records where the panic happened instead of
/// printing it (it goes into the report); elsewhere the previous hook runs as usual.
struct PanicCapture;

impl PanicCapture {
    fn install() -> Self {
        let previous = panic::take_hook();
        panic::set_hook(Box::new(move |info| {
            if CAPTURING.with(Cell::get) {
                let at = info
                    .location()
                    .map(|l| format!("{}:{}:{}", l.file(), l.line(), l.column()));
                tracing::debug!(at = ?at, "a conversion panicked");
                LOCATION.with(|l| *l.borrow_mut() = at);
            } else {
                previous(info);
            }
        }));
        Self
    }

    /// Runs `f`; a panic becomes `Err("panicked at FILE:LINE:COL: message")`.
    fn catch<T>(f: impl FnOnce() -> T) -> Result<T, String> {
        CAPTURING.with(|c| c.set(true));
        let result = panic::catch_unwind(AssertUnwindSafe(f));
        CAPTURING.with(|c| c.set(false));
        result.map_err(|payload| {
            let message = payload
                .downcast_ref::<&str>()
                .map(|s| s.to_string())
                .or_else(|| payload.downcast_ref::<String>().cloned())
                .unwrap_or_else(|| "a panic without a message".into());
            let at = LOCATION.with(|l| l.borrow_mut().take());
            match at {
                Some(at) => format!("panicked at {at}: {message} (a bug in platener: please report it)"),
                None => format!("panicked: {message} (a bug in platener: please report it)"),
            }
        })
    }
}

impl Drop for PanicCapture {
    fn drop(&mut self) {
        // Back to the default hook; conversions left running after a timeout report nothing.
        let _ = panic::take_hook();
    }
}
