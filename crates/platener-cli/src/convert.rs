//! `platener convert`: flags → settings → the batch → ZIPs, the report and the exit code.

use std::time::{Duration, Instant};

use crate::args::ConvertArgs;
use crate::batch::{self, BatchConfig};
use crate::inputs;
use crate::progress::Ui;
use crate::report::{self, BatchReport, RunSettings};
use anyhow::Context as _;

/// Examples shown under `platener convert --help`.
pub const EXAMPLES: &str = "Examples:
  platener convert examples/box-3mm.stl -o out
      writes out/box-3mm-plate.zip and out/box-3mm-stacked.zip and names the better one
  platener convert models/ -o out --method plate -t 3 -t 6 -m acrylic --sheet 600x400
      every .stl/.obj/.3mf under models/, plates of 3 and 6 mm acrylic
  platener convert a.stl b.obj -o out --json > batch.json
      the batch report (scores and their components) as JSON
  platener convert models/ -o out -j 2 --timeout 30 --max-filesize 20 --sub-reports
      two models at a time, at most 30 s each, files over 20 MB skipped, a report per method

Output: OUT_DIR/<model>-<method>.zip per model and method that converted; with --sub-reports
also OUT_DIR/<model>-<method>.report.json. The score (0-1) weighs how much of the model the
parts reproduce, whether they hold together and the work; docs/score.md defines it.
Exit codes: 0 every model converted by at least one method (a method that fails on a model is
reported, the model as partial), 1 a model no method converted or an input that gave no model
(all else still runs and is reported), 2 a usage error. Files left out by --max-filesize do
not count as failures.";

/// A mistake in the flags: exit code 2.
#[derive(Debug)]
pub struct UsageError(pub anyhow::Error);

impl std::fmt::Display for UsageError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{:#}", self.0)
    }
}

impl std::error::Error for UsageError {}

/// Runs the command; the exit code says whether everything converted.
pub fn run(args: &ConvertArgs) -> anyhow::Result<u8> {
    let chosen = args.settings.chosen().map_err(|e| anyhow::Error::new(UsageError(e)))?;
    let ui = Ui::init(args.verbose);
    std::fs::create_dir_all(&args.output).with_context(|| format!("cannot create {}", args.output.display()))?;
    let jobs = args
        .jobs
        .unwrap_or_else(|| std::thread::available_parallelism().map_or(1, |n| n.get()));
    let config = BatchConfig {
        settings: chosen.settings.clone(),
        methods: chosen.methods.clone(),
        timeout: (args.timeout > 0.0).then(|| Duration::from_secs_f64(args.timeout)),
        out_dir: args.output.clone(),
        sub_reports: args.sub_reports,
        joint: chosen.to_json().remove("joint").unwrap_or_default(),
        jobs,
        faults: crate::fault::from_env(),
    };
    let start = Instant::now();
    let found = inputs::collect(&args.inputs, args.max_filesize);
    if !args.json {
        ui.print(&report::render_problems(&found.errors, &found.skipped));
    }
    let progress = ui.batch(found.models.len());
    let models = batch::run(&found.models, &config, &progress, |m| {
        if !args.json {
            ui.print(&report::render_model(m, args.verbose > 0));
        }
    });
    drop(progress);
    let methods: Vec<&'static str> = config.methods.iter().map(|m| m.name()).collect();
    let summary = report::summarize(
        &methods,
        &models,
        &found.errors,
        found.skipped.len(),
        start.elapsed().as_secs_f64(),
    );
    let batch = BatchReport {
        generator: concat!("platener ", env!("CARGO_PKG_VERSION")).into(),
        settings: RunSettings {
            methods,
            chosen: chosen.to_json(),
            kerf_mm: config.settings.cut.kerf(),
            timeout_seconds: config.timeout.map(|t| t.as_secs_f64()),
            jobs,
            max_filesize_mb: args.max_filesize,
            output: args.output.display().to_string(),
        },
        input_errors: found.errors,
        skipped: found.skipped,
        models,
        summary,
    };
    if args.json {
        ui.print(&(serde_json::to_string_pretty(&batch)? + "\n"));
    } else {
        ui.print(&report::render_summary(&batch));
    }
    Ok(batch.summary.exit_code)
}
