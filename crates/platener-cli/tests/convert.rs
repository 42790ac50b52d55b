//! `platener convert` driven through the real binary: single models, folders, bad inputs, the
//! JSON report, exit codes, failing, panicking and hanging methods, and the whole corpus.
//!
//! `PLATENER_FAULT` (see src/fault.rs) makes a method fail, panic or hang, so these tests hold
//! whatever the methods can do by the time they run.

use std::io::Read as _;
use std::path::{Path, PathBuf};

use assert_cmd::Command;
use serde_json::Value;

fn example(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples").join(name)
}

fn platener() -> Command {
    let mut c = Command::cargo_bin("platener").expect("binary built");
    c.env_remove("PLATENER_FAULT");
    c
}

struct Run {
    code: i32,
    stdout: String,
    stderr: String,
}

fn run(cmd: &mut Command) -> Run {
    let out = cmd.output().expect("runs");
    Run {
        code: out.status.code().expect("exited, not killed"),
        stdout: String::from_utf8(out.stdout).expect("utf-8"),
        stderr: String::from_utf8(out.stderr).expect("utf-8"),
    }
}

fn convert(args: &[&Path], out: &Path, extra: &[&str]) -> Run {
    run(platener().arg("convert").args(args).arg("-o").arg(out).args(extra))
}

fn json(r: &Run) -> Value {
    serde_json::from_str(&r.stdout).unwrap_or_else(|e| panic!("{e}: {}\n{}", r.stdout, r.stderr))
}

fn zip_entry(zip: &Path, name: &str) -> String {
    let file = std::fs::File::open(zip).unwrap_or_else(|e| panic!("{}: {e}", zip.display()));
    let mut archive = zip::ZipArchive::new(file).expect("a ZIP");
    let mut text = String::new();
    archive
        .by_name(name)
        .expect("entry")
        .read_to_string(&mut text)
        .expect("utf-8");
    text
}

/// A folder holding the three shipped examples, one of them in a subfolder, and a text file.
fn example_folder() -> tempfile::TempDir {
    let dir = tempfile::tempdir().expect("temp dir");
    std::fs::create_dir(dir.path().join("sub")).expect("sub");
    for (name, to) in [
        ("box-3mm.stl", "box-3mm.stl"),
        ("tray-3mm.stl", "sub/tray-3mm.stl"),
        ("phone-stand.stl", "phone-stand.stl"),
    ] {
        std::fs::copy(example(name), dir.path().join(to)).expect("copy");
    }
    std::fs::write(dir.path().join("notes.txt"), "not a model").expect("write");
    dir
}

#[test]
fn a_single_model_becomes_a_zip_with_six_parts() {
    let out = tempfile::tempdir().expect("temp dir");
    let r = convert(&[&example("box-3mm.stl")], out.path(), &["--method", "plate"]);
    assert_eq!(r.code, 0, "{}{}", r.stdout, r.stderr);
    let plan: Value =
        serde_json::from_str(&zip_entry(&out.path().join("box-3mm-plate.zip"), "plan.json")).expect("JSON");
    assert_eq!(plan["parts"].as_array().expect("parts").len(), 6);
    assert_eq!(plan["method"], "plate");
    assert!(r.stdout.contains("box-3mm.stl"), "{}", r.stdout);
    assert!(r.stdout.contains("summary"), "{}", r.stdout);
    assert!(r.stdout.contains("1 converted"), "{}", r.stdout);
}

#[test]
fn a_folder_is_searched_recursively_in_name_order() {
    let dir = example_folder();
    let out = tempfile::tempdir().expect("temp dir");
    let r = convert(&[dir.path()], out.path(), &["--method", "plate", "--json", "-j", "2"]);
    assert_eq!(r.code, 0, "{}{}", r.stdout, r.stderr);
    let v = json(&r);
    let files: Vec<String> = v["models"]
        .as_array()
        .expect("models")
        .iter()
        .map(|m| m["file"].as_str().expect("file").replace('\\', "/"))
        .collect();
    // Sorted by path (box, phone, sub/tray); the text file is not a model and is ignored.
    assert_eq!(files.len(), 3, "{files:?}");
    assert!(files[0].ends_with("box-3mm.stl") && files[1].ends_with("phone-stand.stl"));
    assert!(files[2].ends_with("sub/tray-3mm.stl"));
    for stem in ["box-3mm", "phone-stand", "tray-3mm"] {
        assert!(out.path().join(format!("{stem}-plate.zip")).is_file(), "{stem}");
    }
}

#[test]
fn a_missing_file_fails_with_its_reason_and_the_batch_goes_on() {
    let out = tempfile::tempdir().expect("temp dir");
    let missing = Path::new("no/such/model.stl");
    let r = convert(&[missing, &example("box-3mm.stl")], out.path(), &["--method", "plate"]);
    assert_eq!(r.code, 1, "{}{}", r.stdout, r.stderr);
    assert!(r.stdout.contains("model.stl: cannot read it"), "{}", r.stdout);
    assert!(out.path().join("box-3mm-plate.zip").is_file());
}

#[test]
fn a_non_model_file_fails_with_its_reason() {
    let dir = tempfile::tempdir().expect("temp dir");
    let text = dir.path().join("notes.txt");
    std::fs::write(&text, "hello").expect("write");
    let garbage = dir.path().join("garbage.stl");
    std::fs::write(&garbage, "this is not an STL file at all").expect("write");
    let out = tempfile::tempdir().expect("temp dir");
    let r = convert(&[&text, &garbage], out.path(), &["--method", "plate", "--json"]);
    assert_eq!(r.code, 1, "{}{}", r.stdout, r.stderr);
    let v = json(&r);
    assert_eq!(
        v["input_errors"][0]["reason"],
        "not a model file: platener reads .stl, .obj and .3mf"
    );
    let model = &v["models"][0];
    assert_eq!(model["status"], "failed");
    let error = model["methods"][0]["error"].as_str().expect("error");
    assert!(error.contains("garbage.stl"), "{error}");
    assert_eq!(v["summary"]["failures"].as_array().expect("failures").len(), 2);
}

#[test]
fn an_empty_folder_is_reported() {
    let empty = tempfile::tempdir().expect("temp dir");
    let out = tempfile::tempdir().expect("temp dir");
    let r = convert(&[empty.path()], out.path(), &[]);
    assert_eq!(r.code, 1, "{}{}", r.stdout, r.stderr);
    assert!(
        r.stdout.contains("no model files (.stl, .obj, .3mf) in this folder"),
        "{}",
        r.stdout
    );
    assert!(r.stdout.contains("0 attempted"), "{}", r.stdout);
}

#[test]
fn files_over_max_filesize_are_skipped_and_listed() {
    let dir = example_folder();
    let out = tempfile::tempdir().expect("temp dir");
    // box-3mm.stl has 6084 bytes, the other examples under 5000.
    let r = convert(
        &[dir.path()],
        out.path(),
        &["--method", "plate", "--json", "--max-filesize", "0.005"],
    );
    let v = json(&r);
    let skipped = v["skipped"].as_array().expect("skipped");
    assert_eq!(skipped.len(), 1, "{skipped:?}");
    assert!(skipped[0]["file"].as_str().expect("file").ends_with("box-3mm.stl"));
    assert_eq!(skipped[0]["reason"], "6084 bytes is over --max-filesize 0.005 MB");
    assert!(!out.path().join("box-3mm-plate.zip").exists());
    assert!(out.path().join("tray-3mm-plate.zip").is_file());
    assert_eq!(v["summary"]["skipped"], 1);
    assert_eq!(v["summary"]["models"], 2);
    // Skipping is asked for: not a failure.
    assert_eq!(r.code, 0, "{}", r.stderr);
}

#[test]
fn the_json_report_has_scores_and_a_summary() {
    let out = tempfile::tempdir().expect("temp dir");
    let r = convert(&[&example("box-3mm.stl")], out.path(), &["--method", "plate", "--json"]);
    assert_eq!(r.code, 0, "{}", r.stderr);
    let v = json(&r);
    assert!(v["generator"].as_str().expect("generator").starts_with("platener "));
    assert_eq!(v["settings"]["methods"], serde_json::json!(["plate"]));
    assert_eq!(v["settings"]["joint"], "auto");
    assert_eq!(v["settings"]["material"], "wood");
    let m = &v["models"][0];
    assert_eq!(m["status"], "converted");
    assert_eq!(m["best"], "plate");
    let method = &m["methods"][0];
    assert_eq!(method["status"], "converted");
    assert_eq!(method["parts"], 6);
    assert_eq!(method["glue"], "glue-free", "a jointed box needs no glue");
    assert!(method["zip"].as_str().expect("zip").ends_with("box-3mm-plate.zip"));
    let score = &method["score"];
    let total = score["total"].as_f64().expect("total");
    assert!((0.0..=1.0).contains(&total), "{score}");
    for component in [
        &score["surface"]["value"],
        &score["quality"]["value"],
        &score["assembly"]["connectivity"],
        &score["assembly"]["interference"],
        &score["effort"]["value"],
    ] {
        let x = component.as_f64().expect("a number");
        assert!((0.0..=1.0).contains(&x), "{score}");
    }
    assert!(score["surface"]["value"].as_f64().expect("share") > 0.95, "{score}");
    assert_eq!(method["verify"]["passed"], true, "{method}");
    let s = &v["summary"];
    assert_eq!((s["models"].as_u64(), s["converted"].as_u64()), (Some(1), Some(1)));
    assert_eq!(s["methods"]["plate"]["converted"], 1);
    assert_eq!(s["exit_code"], 0);
    assert!(s["models_per_second"].as_f64().expect("rate") > 0.0);
}

#[test]
fn usage_errors_exit_with_2() {
    let out = tempfile::tempdir().expect("temp dir");
    let model = example("box-3mm.stl");
    for bad in [
        &["--kerf", "5"][..],
        &["--sheet", "600"],
        &["--method", "laser"],
        &["-m", "steel"],
        &["-t", "-3"],
        &["--weld", "lots"],
        &["-j", "0"],
        &["--timeout", "soon"],
    ] {
        let r = convert(&[&model], out.path(), bad);
        assert_eq!(r.code, 2, "{bad:?}: {}", r.stderr);
        assert!(r.stderr.contains("error"), "{bad:?}: {}", r.stderr);
    }
    // No output folder.
    let r = run(platener().arg("convert").arg(&model));
    assert_eq!(r.code, 2, "{}", r.stderr);
    assert_eq!(std::fs::read_dir(out.path()).expect("listed").count(), 0);
}

#[test]
fn a_failing_method_leaves_the_other_written_and_the_model_counts_as_converted() {
    let out = tempfile::tempdir().expect("temp dir");
    let r = run(platener()
        .env("PLATENER_FAULT", "stacked=error")
        .arg("convert")
        .arg(example("box-3mm.stl"))
        .arg("-o")
        .arg(out.path())
        .args(["--method", "all", "--json"]));
    assert_eq!(r.code, 0, "{}", r.stderr);
    assert!(out.path().join("box-3mm-plate.zip").is_file());
    assert!(!out.path().join("box-3mm-stacked.zip").exists());
    let v = json(&r);
    let m = &v["models"][0];
    assert_eq!(m["status"], "partial");
    assert_eq!(m["best"], "plate");
    assert_eq!(m["methods"][1]["method"], "stacked");
    assert_eq!(m["methods"][1]["status"], "failed");
    assert!(m["methods"][1]["error"].as_str().expect("reason").contains("fail"));
    assert_eq!(v["summary"]["methods"]["stacked"]["failed"], 1);
    // The classifier has nothing to add to a box: its reason, without a second "skipped".
    assert_eq!(m["methods"][2]["status"], "skipped");
    let why = m["methods"][2]["error"].as_str().expect("reason");
    assert!(why.starts_with("the model's faces are exact"), "{why}");
}

#[test]
fn panics_are_caught_reported_and_counted() {
    let dir = example_folder();
    let out = tempfile::tempdir().expect("temp dir");
    let r = run(platener()
        .env("PLATENER_FAULT", "plate=panic")
        .arg("convert")
        .arg(dir.path())
        .arg("-o")
        .arg(out.path())
        .args(["--method", "plate", "-j", "2"]));
    assert_eq!(r.code, 1, "{}{}", r.stdout, r.stderr);
    // Every model was tried and reported, with where the panic happened.
    assert_eq!(
        r.stdout.matches("panicked: panicked at ").count(),
        3 * 2,
        "{}",
        r.stdout
    );
    assert!(r.stdout.contains("0 converted, 3 failed (3 panicked)"), "{}", r.stdout);
    assert!(!r.stderr.contains("RUST_BACKTRACE"), "{}", r.stderr);
}

#[test]
fn models_past_the_timeout_are_cancelled_and_the_batch_goes_on() {
    let out = tempfile::tempdir().expect("temp dir");
    // One job: the second model starts only after the first was given up.
    let r = run(platener()
        .env("PLATENER_FAULT", "plate=hang")
        .arg("convert")
        .arg(example("box-3mm.stl"))
        .arg(example("tray-3mm.stl"))
        .arg("-o")
        .arg(out.path())
        .args(["--method", "plate", "--timeout", "0.5", "-j", "1", "--json"]));
    assert_eq!(r.code, 1, "{}", r.stderr);
    let v = json(&r);
    for model in v["models"].as_array().expect("models") {
        assert_eq!(model["methods"][0]["status"], "timed-out", "{model}");
        assert!(
            model["methods"][0]["error"]
                .as_str()
                .expect("reason")
                .contains("--timeout")
        );
    }
    assert_eq!(v["summary"]["methods"]["plate"]["timed_out"], 2);
    assert_eq!(std::fs::read_dir(out.path()).expect("listed").count(), 0);
}

#[test]
fn sub_reports_and_zips_are_the_same_every_run() {
    let a = tempfile::tempdir().expect("temp dir");
    let b = tempfile::tempdir().expect("temp dir");
    for out in [&a, &b] {
        let r = convert(
            &[&example("tray-3mm.stl")],
            out.path(),
            &["--method", "plate", "--sub-reports", "--joint", "finger"],
        );
        assert_eq!(r.code, 0, "{}", r.stderr);
    }
    for name in ["tray-3mm-plate.zip", "tray-3mm-plate.report.json"] {
        let (x, y) = (a.path().join(name), b.path().join(name));
        assert_eq!(
            std::fs::read(&x).expect("first"),
            std::fs::read(&y).expect("second"),
            "{name}"
        );
    }
    let sub: Value = serde_json::from_slice(&std::fs::read(a.path().join("tray-3mm-plate.report.json")).expect("read"))
        .expect("JSON");
    assert_eq!(sub["method"], "plate");
    assert_eq!(sub["joint"], "finger");
    assert!(sub["score"]["total"].as_f64().is_some());
    assert_eq!(sub["report"]["part_count"], 5);
}

/// Issue 33: the README's synopsis names every flag each command's `--help` lists (long or
/// short form), so the two cannot drift apart.
#[test]
fn the_readme_synopsis_has_every_flag_of_every_command() {
    let readme = std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("../../README.md"))
        .expect("README readable");
    let start = readme.find("## Using the command line").expect("the synopsis section");
    let block = &readme[start..];
    let block = &block[block.find("```").expect("its code block") + 3..];
    let block = &block[..block.find("```").expect("its end")];
    // Each command's synopsis: its line and the indented lines after it.
    let mut synopsis: Vec<(String, String)> = Vec::new();
    for line in block.lines() {
        if let Some(rest) = line.strip_prefix("platener ") {
            let command = rest.split_whitespace().next().unwrap_or_default().to_string();
            synopsis.push((command, line.to_string()));
        } else if line.starts_with(' ')
            && let Some(last) = synopsis.last_mut()
        {
            last.1.push(' ');
            last.1.push_str(line);
        }
    }
    let names = |text: &str| -> Vec<String> {
        text.split(|c: char| !(c.is_ascii_alphanumeric() || c == '-'))
            .filter(|w| {
                w.starts_with('-')
                    && w.trim_start_matches('-')
                        .chars()
                        .next()
                        .is_some_and(|c| c.is_ascii_alphabetic())
            })
            .map(str::to_string)
            .collect()
    };
    let commands = [
        "convert",
        "inspect",
        "verify",
        "scene",
        "test-strip",
        "hinge-test",
        "serve",
        "worker",
        "completions",
    ];
    for command in commands {
        let (_, text) = synopsis
            .iter()
            .find(|(c, _)| c == command)
            .unwrap_or_else(|| panic!("the README has no synopsis of {command}"));
        let written = names(text);
        let help = run(platener().args([command, "--help"])).stdout;
        for line in help.lines().map(str::trim_start).filter(|l| l.starts_with('-')) {
            let flags = names(line.split("  ").next().unwrap_or_default());
            let flags: Vec<&String> = flags
                .iter()
                .filter(|f| f.as_str() != "--help" && f.as_str() != "-h")
                .collect();
            if flags.is_empty() {
                continue;
            }
            assert!(
                flags.iter().any(|f| written.contains(f)),
                "the README's synopsis of {command} lacks {flags:?}"
            );
        }
    }
}

#[test]
fn help_completions_and_version() {
    for sub in ["convert", "inspect", "test-strip", "verify", "scene", "completions"] {
        let r = run(platener().args([sub, "--help"]));
        assert_eq!(r.code, 0);
        assert!(r.stdout.contains("Examples:"), "{sub}: {}", r.stdout);
    }
    let r = run(platener().arg("--help"));
    assert!(
        r.stdout.contains("convert") && r.stdout.contains("Examples:"),
        "{}",
        r.stdout
    );
    // The exit codes `--help` states are the README's, word for word.
    let readme = std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("../../README.md"))
        .expect("README readable");
    let words = |t: &str| t.split_whitespace().collect::<Vec<_>>().join(" ");
    let help = words(&r.stdout);
    let stated = help
        .find("Exit codes:")
        .map(|i| &help[i..])
        .expect("--help states exit codes");
    assert!(words(&readme).contains(stated), "README lacks: {stated}");
    let r = run(platener().arg("--version"));
    assert_eq!(r.code, 0);
    assert!(r.stdout.starts_with("platener "), "{}", r.stdout);
    let r = run(platener().args(["completions", "bash"]));
    assert_eq!(r.code, 0);
    assert!(r.stdout.contains("platener") && r.stdout.contains("convert"));
    assert_eq!(run(platener().args(["completions", "tcsh"])).code, 2);
}

/// The shared corpus, or `None` (with a message) when it is absent.
fn corpus() -> Option<PathBuf> {
    platener_fixtures::samples::shared_corpus()
        .map_err(|m| eprintln!("{m}"))
        .ok()
}

#[test]
fn the_whole_corpus_converts_or_fails_with_reasons() {
    let Some(dir) = corpus() else { return };
    let out = tempfile::tempdir().expect("temp dir");
    // Debug builds are ten times slower than release ones: a 10 s limit keeps the run under a
    // minute (the slowest models are given up, which is reported like any failure).
    let r = convert(
        &[&dir],
        out.path(),
        &["--method", "plate", "-j", "2", "--timeout", "10", "--json"],
    );
    // Finishes, never crashes: 0 or 1, never a panic's 101 or a signal.
    assert!(r.code == 0 || r.code == 1, "exit {}: {}", r.code, r.stderr);
    let v = json(&r);
    let summary = &v["summary"];
    // A caught panic is still a bug: there must be none.
    assert_eq!(summary["methods"]["plate"]["panicked"], 0, "{summary}");
    assert!(summary["models_per_second"].as_f64().expect("rate") > 0.0, "{summary}");
    assert!(summary["models"].as_u64().expect("model count") >= 50, "{summary}");
    // Every failed model is listed among the failures, with a reason.
    let failures = summary["failures"].as_array().expect("failures");
    let failed: Vec<&serde_json::Value> = v["models"]
        .as_array()
        .expect("models")
        .iter()
        .filter(|m| m["status"] != "converted")
        .collect();
    for m in failed {
        let listed = failures
            .iter()
            .find(|f| f["file"] == m["file"])
            .unwrap_or_else(|| panic!("{} is not among the failures:\n{summary}", m["file"]));
        let reason = listed["reason"].as_str().unwrap_or("");
        assert!(!reason.trim().is_empty(), "{listed}");
    }
    // The clean plate models convert.
    for stem in ["chess_case_bottom", "model_house_walls", "plycutter_PlyTest0.1"] {
        assert!(
            out.path().join(format!("{stem}-plate.zip")).is_file(),
            "{stem}\n{summary}"
        );
    }
    eprintln!("{summary}");
}
