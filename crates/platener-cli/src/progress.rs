//! Logs (tracing-subscriber, on stderr) and progress bars (tracing-indicatif): a bar over the
//! batch, and with `-v` a spinner per model, method and pipeline step (the library's `step`
//! spans). No bars when stdout is not a terminal; no colours when NO_COLOR is set.

use std::io::{IsTerminal as _, Write as _};

use indicatif::ProgressStyle;
use tracing::Span;
use tracing_indicatif::IndicatifLayer;
use tracing_indicatif::filter::{IndicatifFilter, hide_indicatif_span_fields};
use tracing_indicatif::span_ext::IndicatifSpanExt as _;
use tracing_subscriber::filter::LevelFilter;
use tracing_subscriber::fmt::format::DefaultFields;
use tracing_subscriber::layer::{Layer as _, SubscriberExt as _};
use tracing_subscriber::util::SubscriberInitExt as _;

/// Whether NO_COLOR asks for plain output (any non-empty value, as no-color.org says).
pub fn no_color() -> bool {
    std::env::var_os("NO_COLOR").is_some_and(|v| !v.is_empty())
}

/// The terminal side of a run.
pub struct Ui {
    /// Whether bars are drawn.
    bars: bool,
}

impl Ui {
    /// Sets up logging (warnings; `-v` info; `-vv` debug) and, on a terminal, progress bars.
    pub fn init(verbose: u8) -> Self {
        let level = match verbose {
            0 => LevelFilter::WARN,
            1 => LevelFilter::INFO,
            _ => LevelFilter::DEBUG,
        };
        let color = !no_color() && std::io::stderr().is_terminal();
        let bars = std::io::stdout().is_terminal() && std::io::stderr().is_terminal();
        let result = if bars {
            let indicatif = IndicatifLayer::new()
                .with_span_field_formatter(hide_indicatif_span_fields(DefaultFields::new()))
                .with_max_progress_bars(8, None);
            let fmt = tracing_subscriber::fmt::layer()
                .with_writer(indicatif.get_stderr_writer())
                .with_ansi(color)
                .with_target(false)
                .without_time()
                .with_filter(level);
            tracing_subscriber::registry()
                .with(fmt)
                .with(indicatif.with_filter(IndicatifFilter::new(verbose > 0)))
                .try_init()
        } else {
            let fmt = tracing_subscriber::fmt::layer()
                .with_writer(std::io::stderr)
                .with_ansi(color)
                .with_target(false)
                .without_time()
                .with_filter(level);
            tracing_subscriber::registry().with(fmt).try_init()
        };
        // Only fails when a subscriber is already set (never in the binary); logs still go
        // to that one.
        let _ = result;
        Self { bars }
    }

    /// The span whose bar counts the models of the batch.
    pub fn batch(&self, total: usize) -> Span {
        let span = tracing::info_span!("convert", indicatif.pb_show = tracing::field::Empty);
        if self.bars {
            let template = if no_color() {
                "{spinner} {elapsed_precise} [{bar:30}] {pos}/{len} models  {wide_msg}"
            } else {
                "{spinner:.green} {elapsed_precise} [{bar:30.cyan/blue}] {pos}/{len} models  {wide_msg}"
            };
            if let Ok(style) = ProgressStyle::with_template(template) {
                span.pb_set_style(&style.progress_chars("=> "));
            }
            span.pb_set_length(total as u64);
            span.pb_start();
        }
        span
    }

    /// Prints `text` on stdout without tearing the bars.
    pub fn print(&self, text: &str) {
        let written = match tracing_indicatif::writer::get_indicatif_stdout_writer() {
            Some(mut w) if self.bars => w.write_all(text.as_bytes()),
            _ => std::io::stdout().lock().write_all(text.as_bytes()),
        };
        // stdout closed (e.g. piped into `head`): nothing left to tell.
        let _ = written;
    }
}
