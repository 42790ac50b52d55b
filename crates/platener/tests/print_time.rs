//! The print-time estimate (`fabrication::print`) against PrusaSlicer 2.5's own estimates,
//! recorded in `tests/fixtures/prusaslicer-times.json` by tools/print-time-vs-prusaslicer.py
//! with the stated profile tools/prusaslicer/profile.ini (no slicer runs here). The stated
//! error: within ±25 % of PrusaSlicer on at least 80 % of the models, and on each shipped
//! example. The corpus's models are required in CI (`PLATENER_REQUIRE_CORPUS=1`).

use std::path::{Path, PathBuf};

use platener::fabrication::print::estimate;
use platener::read::read_file;

const FIXTURE: &str = include_str!("fixtures/prusaslicer-times.json");

/// Models PrusaSlicer printed in under two minutes are files in inches or unit scale
/// sliced as mm (a 4 mm Benchy): no printer prints them, and they calibrate nothing.
const MIN_SECONDS: f64 = 120.0;
/// The stated error.
const WITHIN: f64 = 0.25;

struct Compared {
    file: String,
    ratio: f64,
}

fn workspace() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// Our estimate over PrusaSlicer's for every model of the fixture found on this machine,
/// after checking that the file is the one the slicer measured (its size).
fn compare(corpus: Option<&Path>) -> Vec<Compared> {
    let fixture: serde_json::Value = serde_json::from_str(FIXTURE).expect("the fixture is JSON");
    let mut out = Vec::new();
    for m in fixture["models"].as_array().expect("models") {
        let file = m["file"].as_str().expect("a file name");
        let Some(seconds) = m["seconds"].as_f64().filter(|s| *s >= MIN_SECONDS) else {
            continue;
        };
        let path = match (file.strip_prefix("corpus/"), corpus) {
            (Some(rest), Some(dir)) => dir.join(rest),
            (Some(_), None) => continue,
            (None, _) => workspace().join(file),
        };
        let (_, raw) = read_file(&path).unwrap_or_else(|e| panic!("{file}: {e}"));
        let (lo, hi) = raw.triangles.iter().flatten().fold(
            (glam::DVec3::splat(f64::INFINITY), glam::DVec3::splat(f64::NEG_INFINITY)),
            |(lo, hi), p| (lo.min(*p), hi.max(*p)),
        );
        let size = hi - lo;
        let theirs: Vec<f64> = m["size_mm"]
            .as_array()
            .expect("a size")
            .iter()
            .map(|v| v.as_f64().expect("a number"))
            .collect();
        for (axis, (ours, theirs)) in size.to_array().iter().zip(&theirs).enumerate() {
            assert!(
                (ours - theirs).abs() < 0.01 + 1e-3 * theirs,
                "{file}: axis {axis} is {ours} mm here and {theirs} mm in the fixture: the fixture is stale, run tools/print-time-vs-prusaslicer.py"
            );
        }
        out.push(Compared {
            file: file.to_string(),
            ratio: estimate(&raw.triangles).seconds / seconds,
        });
    }
    out
}

fn within(c: &Compared) -> bool {
    (1.0 - WITHIN..=1.0 + WITHIN).contains(&c.ratio)
}

#[test]
fn the_shipped_examples_print_within_a_quarter_of_prusaslicer() {
    let examples: Vec<Compared> = compare(None);
    assert_eq!(examples.len(), 3, "the fixture names the three shipped examples");
    for c in &examples {
        assert!(within(c), "{}: ours / PrusaSlicer = {:.2}", c.file, c.ratio);
    }
}

#[test]
fn most_corpus_models_print_within_a_quarter_of_prusaslicer() {
    let corpus = match platener_fixtures::samples::shared_corpus() {
        Ok(dir) => dir,
        Err(message) => {
            eprintln!("{message}");
            return;
        }
    };
    let all = compare(Some(&corpus));
    // 34 corpus models printed for at least two minutes, and the three examples.
    assert!(all.len() >= 30, "only {} models compared", all.len());
    let good = all.iter().filter(|c| within(c)).count();
    let outside: Vec<String> = all
        .iter()
        .filter(|c| !within(c))
        .map(|c| format!("{} {:.2}", c.file, c.ratio))
        .collect();
    assert!(
        good as f64 >= 0.8 * all.len() as f64,
        "{good} of {} within ±25 %; outside: {outside:?}",
        all.len()
    );
}
