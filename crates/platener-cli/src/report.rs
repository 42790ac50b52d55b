//! The batch report of `platener convert`: per model, per method, and the statistics summary,
//! as data (`--json`) and as text.

use std::collections::BTreeMap;
use std::fmt::Write as _;

use platener::convert::Status;
use platener::fabrication::{Fabrication, SPEED_UP_CLASS};
use platener::score::Score;
use serde::Serialize;

use crate::inputs::Problem;

/// One method on one model.
#[derive(Debug, Clone, Serialize)]
pub struct MethodReport {
    /// The method's name.
    pub method: &'static str,
    /// How it went.
    pub status: Status,
    /// The ZIP written, when converted.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub zip: Option<String>,
    /// The sub-report written (`--sub-reports`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub report: Option<String>,
    /// The score and its components, when converted.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub score: Option<Score>,
    /// `verify`'s verdict on the plan (against the method's mesh), when converted: from the
    /// same analysis of the assembly as the score.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub verify: Option<VerifySummary>,
    /// Number of parts, when converted.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub parts: Option<usize>,
    /// Number of sheets, when converted.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub sheets: Option<usize>,
    /// "glue-free" or "needs glue: N parts in G groups", when converted (`Plan::glue_note`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub glue: Option<String>,
    /// Laser, handwork and print times, when converted (report.json's `fabrication`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub fabrication: Option<platener::fabrication::Fabrication>,
    /// Warnings of the steps, as `[step] message`.
    pub warnings: Vec<String>,
    /// Why it failed.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub error: Option<String>,
    /// Wall time, seconds (not for timed-out methods).
    pub seconds: f64,
}

/// `verify`'s verdict on a converted plan, in the batch report.
#[derive(Debug, Clone, Serialize)]
pub struct VerifySummary {
    /// Whether every check passed.
    pub passed: bool,
    /// Why it failed, naming the parts.
    pub problems: Vec<String>,
}

/// How a model did over all methods run.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum ModelStatus {
    /// Every method converted it.
    Converted,
    /// Some methods converted it.
    Partial,
    /// No method converted it.
    Failed,
}

/// One model of the batch.
#[derive(Debug, Clone, Serialize)]
pub struct ModelReport {
    /// The file.
    pub file: String,
    /// What its outputs are named after.
    pub stem: String,
    /// File size in bytes.
    pub bytes: u64,
    /// Over all methods.
    pub status: ModelStatus,
    /// The converted method with the highest score (the first on a tie).
    pub best: Option<&'static str>,
    /// Every method run, in order.
    pub methods: Vec<MethodReport>,
    /// Wall time for the model, seconds.
    pub seconds: f64,
}

impl ModelReport {
    /// Fills in the status from the method reports; `best` is the library's choice, kept
    /// only when that method's ZIP was written.
    pub fn new(
        file: String,
        stem: String,
        bytes: u64,
        methods: Vec<MethodReport>,
        best: Option<&'static str>,
        seconds: f64,
    ) -> Self {
        // A method that skipped the model (nothing to add) does not make it partial.
        let converted = methods.iter().filter(|m| m.status == Status::Converted).count();
        let applied = methods.iter().filter(|m| m.status != Status::Skipped).count();
        let status = match converted {
            0 => ModelStatus::Failed,
            n if n == applied => ModelStatus::Converted,
            _ => ModelStatus::Partial,
        };
        let best = best.filter(|b| methods.iter().any(|m| m.method == *b && m.status == Status::Converted));
        Self {
            file,
            stem,
            bytes,
            status,
            best,
            methods,
            seconds,
        }
    }
}

/// The settings of the run, as resolved.
#[derive(Debug, Clone, Serialize)]
pub struct RunSettings {
    /// Methods run, in order.
    pub methods: Vec<&'static str>,
    /// Every setting, by the web API's key (`material`, `thicknesses`, `kerf`: `null` for the
    /// material's, …), as `platener::options` writes them.
    #[serde(flatten)]
    pub chosen: serde_json::Map<String, serde_json::Value>,
    /// The kerf in effect, mm (the material's unless `kerf` is set).
    pub kerf_mm: f64,
    /// Per-model time limit, seconds (`null`: none).
    pub timeout_seconds: Option<f64>,
    /// Models converted at the same time.
    pub jobs: usize,
    /// Size limit, MB.
    pub max_filesize_mb: Option<f64>,
    /// Output folder.
    pub output: String,
}

/// Per-method statistics.
#[derive(Debug, Clone, Default, Serialize)]
pub struct MethodStats {
    /// Models it converted.
    pub converted: usize,
    /// Models it failed on (errors and panics).
    pub failed: usize,
    /// Of those, panics.
    pub panicked: usize,
    /// Models that timed out before it finished.
    pub timed_out: usize,
    /// Models it skipped: it had nothing to add (the classifier on exact faces).
    pub skipped: usize,
    /// Models it was the best method for.
    pub best: usize,
    /// Mean score over the models it converted.
    pub mean_score: Option<f64>,
}

/// A failure, for the summary's list.
#[derive(Debug, Clone, Serialize)]
pub struct Failure {
    /// The file or input.
    pub file: String,
    /// The method, if a method failed (none for inputs that gave no model).
    pub method: Option<&'static str>,
    /// Failed, panicked or timed out.
    pub status: &'static str,
    /// Why.
    pub reason: String,
}

/// The statistics summary at the end of a batch.
#[derive(Debug, Clone, Serialize)]
pub struct Summary {
    /// Models attempted (not counting skipped ones).
    pub models: usize,
    /// Models every method converted.
    pub converted: usize,
    /// Models some methods converted.
    pub partial: usize,
    /// Models no method converted.
    pub failed: usize,
    /// Models left out by `--max-filesize`.
    pub skipped: usize,
    /// Inputs that gave no model (missing, not a model, empty folder).
    pub input_errors: usize,
    /// Per method.
    pub methods: BTreeMap<&'static str, MethodStats>,
    /// Every failure with its reason, in input order.
    pub failures: Vec<Failure>,
    /// Converted models whose best plan has a print time to compare with.
    pub compared: usize,
    /// Of those, the models whose best plan cuts at least 10× faster than printing
    /// (`fabrication::SPEED_UP_CLASS`).
    pub ten_times_faster: usize,
    /// Wall time of the batch, seconds.
    pub seconds: f64,
    /// Models attempted per second of wall time.
    pub models_per_second: f64,
    /// The exit code: 0 when some method converted every model and every input gave models.
    pub exit_code: u8,
}

/// The whole batch report (`--json`).
#[derive(Debug, Clone, Serialize)]
pub struct BatchReport {
    /// "platener" and its version.
    pub generator: String,
    /// The settings.
    pub settings: RunSettings,
    /// Inputs that gave no model.
    pub input_errors: Vec<Problem>,
    /// Models left out.
    pub skipped: Vec<Problem>,
    /// Every model, in input order.
    pub models: Vec<ModelReport>,
    /// The statistics.
    pub summary: Summary,
}

fn status_name(s: Status) -> &'static str {
    match s {
        Status::Converted => "converted",
        Status::Failed => "failed",
        Status::Panicked => "panicked",
        Status::TimedOut => "timed out",
        Status::Cancelled => "cancelled",
        Status::Skipped => "skipped",
    }
}

/// The summary of these results.
pub fn summarize(
    methods: &[&'static str],
    models: &[ModelReport],
    input_errors: &[Problem],
    skipped: usize,
    seconds: f64,
) -> Summary {
    let mut stats: BTreeMap<&'static str, MethodStats> = methods.iter().map(|m| (*m, MethodStats::default())).collect();
    let mut scores: BTreeMap<&'static str, Vec<f64>> = BTreeMap::new();
    let mut failures: Vec<Failure> = input_errors
        .iter()
        .map(|p| Failure {
            file: p.file.clone(),
            method: None,
            status: "failed",
            reason: p.reason.clone(),
        })
        .collect();
    for model in models {
        for m in &model.methods {
            let s = stats.entry(m.method).or_default();
            match m.status {
                Status::Converted => {
                    s.converted += 1;
                    if let Some(score) = &m.score {
                        scores.entry(m.method).or_default().push(score.total);
                    }
                }
                Status::Failed | Status::Cancelled => s.failed += 1,
                Status::Panicked => {
                    s.failed += 1;
                    s.panicked += 1;
                }
                Status::TimedOut => s.timed_out += 1,
                Status::Skipped => s.skipped += 1,
            }
            if !matches!(m.status, Status::Converted | Status::Skipped) {
                failures.push(Failure {
                    file: model.file.clone(),
                    method: Some(m.method),
                    status: status_name(m.status),
                    reason: m.error.clone().unwrap_or_default(),
                });
            }
        }
        if let Some(best) = model.best {
            stats.entry(best).or_default().best += 1;
        }
    }
    for (method, s) in &mut stats {
        if let Some(v) = scores.get(method).filter(|v| !v.is_empty()) {
            s.mean_score = Some(v.iter().sum::<f64>() / v.len() as f64);
        }
    }
    let count = |st: ModelStatus| models.iter().filter(|m| m.status == st).count();
    let speed_ups: Vec<f64> = models.iter().filter_map(best_speed_up).collect();
    // A model counts as converted when some method converted it: with `--method all`, a
    // method that fails on a model did not apply to it (the summary still says "partial").
    let all_ok = input_errors.is_empty() && models.iter().all(|m| m.status != ModelStatus::Failed);
    Summary {
        models: models.len(),
        converted: count(ModelStatus::Converted),
        partial: count(ModelStatus::Partial),
        failed: count(ModelStatus::Failed),
        skipped,
        input_errors: input_errors.len(),
        methods: stats,
        failures,
        compared: speed_ups.len(),
        ten_times_faster: speed_ups.iter().filter(|&&v| v >= SPEED_UP_CLASS).count(),
        seconds,
        models_per_second: if seconds > 0.0 {
            models.len() as f64 / seconds
        } else {
            0.0
        },
        exit_code: if all_ok { 0 } else { 1 },
    }
}

/// The speed-up of a model's best plan: print time over laser time.
fn best_speed_up(model: &ModelReport) -> Option<f64> {
    let best = model.best?;
    let m = model.methods.iter().find(|m| m.method == best)?;
    m.fabrication.as_ref()?.speed_up
}

/// A duration as a maker reads it: seconds under a minute, minutes under two hours, hours.
pub fn duration(seconds: f64) -> String {
    match seconds {
        s if s < 60.0 => format!("{s:.0} s"),
        s if s < 7200.0 => format!("{:.0} min", s / 60.0),
        s => format!("{:.1} h", s / 3600.0),
    }
}

/// "laser 3 min, print 6.1 h (127× faster)": a plan's making time against printing it.
pub fn times(f: &Fabrication) -> String {
    let laser = format!("laser {}", duration(f.laser_seconds));
    match (f.print_seconds, f.speed_up) {
        (Some(print), Some(up)) => format!("{laser}, print {} ({up:.0}× faster)", duration(print)),
        _ => laser,
    }
}

/// The text lines of one model: a status line, then one line per method.
pub fn render_model(m: &ModelReport, verbose: bool) -> String {
    let mut s = String::new();
    let status = match m.status {
        ModelStatus::Converted => "ok",
        ModelStatus::Partial => "partial",
        ModelStatus::Failed => "FAILED",
    };
    let _ = writeln!(s, "{status:<8}{}  ({:.1} s)", m.file, m.seconds);
    for r in &m.methods {
        let mut line = format!("        {:<8} ", r.method);
        match (&r.status, &r.score) {
            (Status::Converted, score) => {
                let total = score.as_ref().map_or("—".to_string(), |s| format!("{:.3}", s.total));
                let plural = |n: Option<usize>| if n == Some(1) { "" } else { "s" };
                let _ = write!(
                    line,
                    "score {total}  {} part{}, {} sheet{}",
                    r.parts.unwrap_or(0),
                    plural(r.parts),
                    r.sheets.unwrap_or(0),
                    plural(r.sheets)
                );
                if let Some(glue) = &r.glue {
                    let _ = write!(line, ", {glue}");
                }
                if let Some(f) = &r.fabrication {
                    let _ = write!(line, ", {}", times(f));
                }
                if let Some(v) = r.verify.as_ref().filter(|v| !v.passed) {
                    let n = v.problems.len();
                    let _ = write!(line, "  verify FAILED ({n} problem{})", if n == 1 { "" } else { "s" });
                }
                if let Some(zip) = &r.zip {
                    let _ = write!(line, "  → {zip}");
                }
                if m.best == Some(r.method) && m.methods.len() > 1 {
                    line.push_str("  (best)");
                }
            }
            (status, _) => {
                let _ = write!(
                    line,
                    "{}: {}",
                    status_name(*status),
                    r.error.as_deref().unwrap_or("no reason given")
                );
            }
        }
        // A method that failed lists its warnings: they say why (no plates found, …).
        let listed = verbose || r.status != Status::Converted;
        if !r.warnings.is_empty() && !listed {
            let n = r.warnings.len();
            let _ = write!(line, "  [{n} warning{}; -v lists them]", if n == 1 { "" } else { "s" });
        }
        let _ = writeln!(s, "{line}");
        if listed {
            for w in &r.warnings {
                let _ = writeln!(s, "                 warning {w}");
            }
        }
        // Why verify fails the plan: always, a plan that does not assemble is what matters.
        for p in r.verify.iter().flat_map(|v| &v.problems) {
            let _ = writeln!(s, "                 verify  {p}");
        }
    }
    s
}

/// The lines for inputs that gave no model and for skipped files.
pub fn render_problems(input_errors: &[Problem], skipped: &[Problem]) -> String {
    let mut s = String::new();
    for p in input_errors {
        let _ = writeln!(s, "FAILED  {}: {}", p.file, p.reason);
    }
    for p in skipped {
        let _ = writeln!(s, "skipped {}: {}", p.file, p.reason);
    }
    s
}

/// The statistics summary.
pub fn render_summary(r: &BatchReport) -> String {
    let mut s = String::new();
    let u = &r.summary;
    let _ = writeln!(s, "\nsummary");
    let _ = writeln!(
        s,
        "  models     {} attempted: {} converted by every method, {} by some, {} by none; {} skipped, {} input{} without models",
        u.models,
        u.converted,
        u.partial,
        u.failed,
        u.skipped,
        u.input_errors,
        if u.input_errors == 1 { "" } else { "s" }
    );
    for (method, m) in &u.methods {
        let mean = m.mean_score.map_or(String::new(), |v| format!(", mean score {v:.3}"));
        let _ = writeln!(
            s,
            "  {method:<10} {} converted, {} failed ({} panicked), {} timed out, {} skipped; best for {}{mean}",
            m.converted, m.failed, m.panicked, m.timed_out, m.skipped, m.best
        );
    }
    if !u.failures.is_empty() {
        let _ = writeln!(s, "  failures   {}", u.failures.len());
        for f in &u.failures {
            let method = f.method.map_or(String::new(), |m| format!(" [{m}]"));
            let _ = writeln!(s, "    {}{method} {}: {}", f.file, f.status, f.reason);
        }
    }
    if u.compared > 0 {
        let _ = writeln!(
            s,
            "  speed-up   ≥ {SPEED_UP_CLASS}× for {} of {} converted model{} (the best plan's laser time against printing the model)",
            u.ten_times_faster,
            u.compared,
            if u.compared == 1 { "" } else { "s" }
        );
    }
    let _ = writeln!(
        s,
        "  time       {:.1} s for {} model{}, {:.2} models/s with {} job{}",
        u.seconds,
        u.models,
        if u.models == 1 { "" } else { "s" },
        u.models_per_second,
        r.settings.jobs,
        if r.settings.jobs == 1 { "" } else { "s" }
    );
    s
}
