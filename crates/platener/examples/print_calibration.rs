//! Calibrates the print-time estimate (`fabrication::print`) against PrusaSlicer's figures in
//! `crates/platener/tests/fixtures/prusaslicer-times.json` (written by
//! tools/print-time-vs-prusaslicer.py): for each model the slicer printed, our estimate, the
//! ratio, and the share within ±25 %; with `--grid`, the same share over a grid of the two
//! free constants (seconds per layer, motion factor), best first.
//!
//! `cargo run --release -p platener --example print_calibration -- [CORPUS_DIR] [--grid]`

use std::path::{Path, PathBuf};

use platener::fabrication::print::{MK3S, PrintProfile, estimate_with};
use platener::read::{Triangle, read_file};

const FIXTURE: &str = "crates/platener/tests/fixtures/prusaslicer-times.json";

/// The models too small to print as meant (files in inches or unit scale, sliced as mm):
/// their 2–60 s say nothing of a printer.
const MIN_SECONDS: f64 = 120.0;

struct Sample {
    file: String,
    seconds: f64,
    filament: f64,
    triangles: Vec<Triangle>,
}

fn main() -> Result<(), String> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let grid = args.iter().any(|a| a == "--grid");
    let corpus = args
        .iter()
        .find(|a| !a.starts_with("--"))
        .map_or_else(|| PathBuf::from("../shared/corpus"), PathBuf::from);
    let samples = load(&corpus)?;
    if grid {
        let mut results = Vec::new();
        for layer in [0.0, 0.5, 1.0, 1.5, 2.0, 3.0] {
            for motion in [1.0, 1.1, 1.2, 1.3, 1.4, 1.5, 1.6] {
                let p = PrintProfile {
                    layer_seconds: layer,
                    motion_factor: motion,
                    ..MK3S
                };
                let (within, spread) = judge(&samples, &p);
                results.push((within, -spread, layer, motion));
            }
        }
        results.sort_by(|a, b| b.0.cmp(&a.0).then(b.1.total_cmp(&a.1)));
        for (within, spread, layer, motion) in results.iter().take(10) {
            println!(
                "layer {layer:.1} s, motion ×{motion:.1}: {within} of {} within ±25 %, mean |log ratio| {:.3}",
                samples.len(),
                -spread
            );
        }
        return Ok(());
    }
    println!(
        "| model | triangles | PrusaSlicer | ours | ours / PrusaSlicer | filament ours / PrusaSlicer | estimate took |"
    );
    println!("|---|---|---|---|---|---|---|");
    for s in &samples {
        let start = std::time::Instant::now();
        let e = estimate_with(&s.triangles, &MK3S);
        let took = start.elapsed().as_secs_f64() * 1000.0;
        println!(
            "| {} | {} | {:.2} h | {:.2} h | {:.2} | {:.2} | {took:.1} ms |",
            s.file,
            s.triangles.len(),
            s.seconds / 3600.0,
            e.seconds / 3600.0,
            e.seconds / s.seconds,
            e.filament_mm3 / s.filament
        );
    }
    let sphere = platener_fixtures::samples::sphere(platener::glam::DVec3::ZERO, 50.0, 1000, 500);
    let start = std::time::Instant::now();
    let e = estimate_with(&sphere, &MK3S);
    println!(
        "\na sphere of r 50 mm in {} triangles: {:.2} h, estimated in {:.0} ms",
        sphere.len(),
        e.seconds / 3600.0,
        start.elapsed().as_secs_f64() * 1000.0
    );
    let (within, spread) = judge(&samples, &MK3S);
    println!(
        "\n{within} of {} models within ±25 % of PrusaSlicer; mean |log ratio| {spread:.3}",
        samples.len()
    );
    Ok(())
}

/// How many estimates fall within ±25 %, and the mean |ln(ours / theirs)|.
fn judge(samples: &[Sample], p: &PrintProfile) -> (usize, f64) {
    let ratios: Vec<f64> = samples
        .iter()
        .map(|s| estimate_with(&s.triangles, p).seconds / s.seconds)
        .collect();
    let within = ratios.iter().filter(|r| (0.75..=1.25).contains(*r)).count();
    let spread = ratios.iter().map(|r| r.ln().abs()).sum::<f64>() / ratios.len().max(1) as f64;
    (within, spread)
}

fn load(corpus: &Path) -> Result<Vec<Sample>, String> {
    let text =
        std::fs::read_to_string(FIXTURE).map_err(|e| format!("{FIXTURE}: {e} (run from the repository root)"))?;
    let fixture: serde_json::Value = serde_json::from_str(&text).map_err(|e| format!("{FIXTURE}: {e}"))?;
    let models = fixture["models"].as_array().ok_or("the fixture has no models")?;
    let mut samples = Vec::new();
    for m in models {
        let (Some(file), Some(seconds)) = (m["file"].as_str(), m["seconds"].as_f64()) else {
            continue;
        };
        if seconds < MIN_SECONDS {
            continue;
        }
        let path = match file.strip_prefix("corpus/") {
            Some(rest) => corpus.join(rest),
            None => PathBuf::from(file),
        };
        let (_, raw) = read_file(&path).map_err(|e| format!("{}: {e}", path.display()))?;
        samples.push(Sample {
            file: file.to_string(),
            seconds,
            filament: m["filament_mm3"].as_f64().unwrap_or(f64::NAN),
            triangles: raw.triangles,
        });
    }
    Ok(samples)
}
