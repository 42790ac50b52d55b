//! Which model files a `convert` run reads: the files given, and the model files found in the
//! folders given (recursively, in name order), each with the stem its ZIPs are named after.

use std::collections::BTreeSet;
use std::path::{Path, PathBuf};

use serde::Serialize;

/// The extensions `convert` looks for in folders (compared case-insensitively).
pub const MODEL_EXTENSIONS: [&str; 3] = ["stl", "obj", "3mf"];

/// A model file to convert.
#[derive(Debug, Clone)]
pub struct ModelFile {
    /// The file.
    pub path: PathBuf,
    /// Its size in bytes.
    pub bytes: u64,
    /// What its outputs are named after: the file stem, with `-2`, `-3`… when two models of
    /// the batch share a stem.
    pub stem: String,
}

/// An input that gave no model, or a model left out.
#[derive(Debug, Clone, Serialize)]
pub struct Problem {
    /// The path as given or found.
    pub file: String,
    /// Why.
    pub reason: String,
}

/// What the inputs hold.
#[derive(Debug, Default)]
pub struct Inputs {
    /// Model files to convert, in order.
    pub models: Vec<ModelFile>,
    /// Inputs that are missing, unreadable, not models, or folders without models.
    pub errors: Vec<Problem>,
    /// Models larger than `--max-filesize`.
    pub skipped: Vec<Problem>,
}

fn is_model(path: &Path) -> bool {
    path.extension()
        .and_then(|e| e.to_str())
        .is_some_and(|e| MODEL_EXTENSIONS.iter().any(|m| e.eq_ignore_ascii_case(m)))
}

/// Model files under `dir`, sorted by path; unreadable folders are reported, not fatal.
fn walk(dir: &Path, found: &mut Vec<PathBuf>, errors: &mut Vec<Problem>) {
    let entries = match std::fs::read_dir(dir) {
        Ok(entries) => entries,
        Err(e) => {
            errors.push(Problem {
                file: dir.display().to_string(),
                reason: format!("cannot read the folder: {e}"),
            });
            return;
        }
    };
    let mut paths: Vec<PathBuf> = entries.filter_map(|e| e.ok().map(|e| e.path())).collect();
    paths.sort();
    for path in paths {
        if path.is_dir() {
            walk(&path, found, errors);
        } else if is_model(&path) {
            found.push(path);
        }
    }
}

/// A file size for messages: MB (10^6 bytes) from 0.01 MB on, bytes below.
fn size(bytes: u64) -> String {
    if bytes >= 10_000 {
        format!("{:.2} MB", bytes as f64 / 1e6)
    } else {
        format!("{bytes} bytes")
    }
}

/// Expands the inputs into model files; `max_mb` (MB of 10^6 bytes) leaves out larger ones.
pub fn collect(inputs: &[PathBuf], max_mb: Option<f64>) -> Inputs {
    let mut out = Inputs::default();
    let mut files = Vec::new();
    for input in inputs {
        let shown = input.display().to_string();
        match std::fs::metadata(input) {
            Err(e) => out.errors.push(Problem {
                file: shown,
                reason: format!("cannot read it: {e}"),
            }),
            Ok(m) if m.is_dir() => {
                let before = files.len();
                walk(input, &mut files, &mut out.errors);
                if files.len() == before {
                    out.errors.push(Problem {
                        file: shown,
                        reason: "no model files (.stl, .obj, .3mf) in this folder".into(),
                    });
                }
            }
            Ok(_) if !is_model(input) => out.errors.push(Problem {
                file: shown,
                reason: "not a model file: platener reads .stl, .obj and .3mf".into(),
            }),
            Ok(_) => files.push(input.clone()),
        }
    }
    let mut stems: BTreeSet<String> = BTreeSet::new();
    let mut seen: BTreeSet<PathBuf> = BTreeSet::new();
    for path in files {
        // A file named twice (directly and through its folder) is converted once.
        if !seen.insert(std::fs::canonicalize(&path).unwrap_or_else(|_| path.clone())) {
            continue;
        }
        let bytes = std::fs::metadata(&path).map(|m| m.len()).unwrap_or(0);
        if let Some(max) = max_mb
            && bytes as f64 > max * 1e6
        {
            out.skipped.push(Problem {
                file: path.display().to_string(),
                reason: format!("{} is over --max-filesize {max} MB", size(bytes)),
            });
            continue;
        }
        let base = path
            .file_stem()
            .map_or_else(|| "model".to_string(), |s| s.to_string_lossy().into_owned());
        let mut stem = base.clone();
        let mut k = 1;
        while stems.contains(&stem) {
            k += 1;
            stem = format!("{base}-{k}");
        }
        stems.insert(stem.clone());
        out.models.push(ModelFile { path, bytes, stem });
    }
    out
}
