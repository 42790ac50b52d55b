use std::sync::Arc;

use glam::DVec3;

use super::*;
use platener_fixtures::samples::cuboid;

fn source(size: f64) -> Source {
    Source::triangles("cube", cuboid(DVec3::ZERO, DVec3::splat(size)))
}

#[test]
fn a_cancelled_run_stops_with_the_step_it_reached() {
    let cancel = Cancel::default();
    cancel.cancel();
    let mut state = State::new(source(10.0), Settings::default());
    let err = run(&FOUNDATION, &mut state, &cancel).expect_err("cancelled");
    assert!(matches!(err, Error::Cancelled { step: "read" }));
    assert!(state.read.is_none());
}

#[test]
fn a_step_without_its_input_says_which_step_is_missing() {
    let mut state = State::new(source(10.0), Settings::default());
    let err = run(&[StepId::Mesh], &mut state, &Cancel::default()).expect_err("no weld yet");
    assert!(matches!(
        err,
        Error::Internal {
            step: "mesh",
            problem: crate::error::Internal::MissingStep { needs: "weld", .. }
        }
    ));
    assert_eq!(err.culprit(), crate::error::Culprit::Internal);
}

#[test]
fn every_step_leaves_a_snapshot_and_a_record() {
    let mut state = State::new(source(10.0), Settings::default());
    run(&FOUNDATION, &mut state, &Cancel::default()).expect("runs");
    let names: Vec<_> = state.records.iter().map(|r| r.name).collect();
    assert_eq!(names, ["read", "cleanup", "weld", "mesh", "coplanar", "shapes"]);
    let before = state.read.clone().expect("read");
    // Snapshots are shared, not copied: a later state holds the very same read result.
    let later = state.clone();
    assert!(Arc::ptr_eq(&before, later.read.as_ref().expect("read")));
    assert_eq!(state.shapes.expect("shapes").shapes.len(), 6);
}

/// Every step has its own phrase for people, found again by its name (what an event carries).
#[test]
fn every_step_has_a_label_of_its_own_found_by_its_name() {
    let mut labels = std::collections::HashSet::new();
    for step in StepId::ALL {
        assert_eq!(StepId::named(step.name()), Some(step));
        let label = step.label();
        assert!(
            !label.is_empty() && label.chars().all(|c| c.is_ascii_lowercase() || " '".contains(c)),
            "{}: {label:?}",
            step.name()
        );
        assert!(labels.insert(label), "{label:?} twice");
    }
    assert_eq!(StepId::named("no such step"), None);
}

#[test]
fn tiny_and_huge_models_get_a_units_warning() {
    for (size, warned) in [(0.5, true), (50.0, false), (6000.0, true)] {
        let mut state = State::new(source(size), Settings::default());
        run(&FOUNDATION, &mut state, &Cancel::default()).expect("runs");
        let units = state.records[0].warnings.iter().any(|w| w.kind == WarningKind::Units);
        assert_eq!(units, warned, "size {size}");
    }
}

#[test]
fn scale_is_applied_in_the_read_step() {
    let settings = Settings {
        units: crate::Units::In,
        scale: 2.0,
        ..Settings::default()
    };
    let mut state = State::new(source(1.0), settings);
    run(&FOUNDATION, &mut state, &Cancel::default()).expect("runs");
    let b = state.read.expect("read").bounds;
    assert!((b.max - DVec3::splat(50.8)).length() < 1e-12);
}

#[test]
fn a_file_read_from_bytes_is_the_file_read_from_disk() {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/box-3mm.stl");
    let bytes: Arc<[u8]> = std::fs::read(&path).expect("example exists").into();
    let mut from_disk = State::new(Source::File(path), Settings::default());
    let mut from_bytes = State::new(
        Source::Bytes {
            name: "box-3mm.stl".into(),
            bytes,
        },
        Settings::default(),
    );
    run(&FOUNDATION, &mut from_disk, &Cancel::default()).expect("reads");
    run(&FOUNDATION, &mut from_bytes, &Cancel::default()).expect("reads");
    let (a, b) = (from_disk.read.expect("read"), from_bytes.read.expect("read"));
    assert_eq!(a.name, b.name);
    assert_eq!(a.triangles, b.triangles);
    assert_eq!(a.format, b.format);
}

/// The layering rule of docs/architecture.md: a step module is a function of its inputs and
/// knows nothing of the pipeline (nor of the orchestration above it). Test files may use it
/// to set up their inputs.
#[test]
fn no_step_module_imports_the_pipeline() {
    let src = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut checked = 0;
    for step in StepId::ALL {
        let dir = src.join(step.name());
        assert!(
            dir.is_dir(),
            "step {} has no module folder {}",
            step.name(),
            dir.display()
        );
        for file in rust_files(&dir) {
            let name = file.file_name().and_then(|n| n.to_str()).unwrap_or("");
            if name.ends_with("tests.rs") {
                continue;
            }
            let text = std::fs::read_to_string(&file).expect("readable");
            for forbidden in [
                "crate::pipeline",
                "crate::convert",
                "crate::inspect",
                "crate::options",
                "crate::swatches",
                "super::pipeline",
            ] {
                assert!(
                    !text.contains(forbidden),
                    "{} (step {}) uses {forbidden}: steps take their inputs as arguments",
                    file.display(),
                    step.name()
                );
            }
            checked += 1;
        }
    }
    assert!(checked >= StepId::ALL.len(), "checked only {checked} files");
    // The step context imports nothing else of the crate.
    let context = std::fs::read_to_string(src.join("context.rs")).expect("readable");
    assert!(!context.contains("crate::"), "context.rs must not import the crate");
}

/// Layer 1 of docs/architecture.md: the kernel data (context, settings, errors, the plan and
/// its parts, the smallest-part rule, the SVG writer) imports only itself and the geometry
/// kernel, never a step or anything above; test modules may use anything.
#[test]
fn kernel_data_imports_no_step() {
    const DATA: [&str; 6] = ["context", "settings", "error", "plan", "cuttable", "draw"];
    let src = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut checked = 0;
    for module in DATA {
        let dir = src.join(module);
        let files = if dir.is_dir() {
            rust_files(&dir)
        } else {
            vec![src.join(format!("{module}.rs"))]
        };
        for file in files.iter().filter(|f| !is_test_file(f)) {
            for used in crate_imports(file) {
                assert!(
                    DATA.contains(&used.as_str()),
                    "{} (kernel data) uses crate::{used}: kernel data imports no step",
                    file.display()
                );
            }
            checked += 1;
        }
    }
    assert!(checked >= DATA.len(), "checked only {checked} files");
}

/// Layer 2 of docs/architecture.md: a step imports only earlier steps, never a later one,
/// except the pairs architecture.md lists with their reason; test modules may use anything.
/// The order is [`StepId::ALL`]'s with the sliced methods' steps before the classifier's
/// `relief` and `layers`: the methods run apart, and `layers` builds with `stacked`'s code.
#[test]
fn no_step_imports_a_later_step() {
    /// (step, later step it uses): `stacked` numbers its layers with the `labels` step's own
    /// placement, so a tab grows exactly where the label will land.
    const LISTED: [(&str, &str); 1] = [("stacked", "labels")];
    let src = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let sliced = [StepId::Stacked, StepId::Interlocked];
    let mut order: Vec<&str> = StepId::ALL
        .iter()
        .filter(|s| !sliced.contains(s))
        .map(|s| s.name())
        .collect();
    let at = order.iter().position(|s| *s == "relief").expect("relief is a step");
    order.splice(at..at, sliced.iter().map(|s| s.name()));
    let mut found = Vec::new();
    for (k, step) in order.iter().enumerate() {
        for file in rust_files(&src.join(step)).iter().filter(|f| !is_test_file(f)) {
            for used in crate_imports(file) {
                let later = order[k + 1..].contains(&used.as_str());
                if later && !LISTED.contains(&(*step, used.as_str())) {
                    found.push(format!("{} (step {step}) uses crate::{used}", file.display()));
                }
            }
        }
    }
    found.dedup();
    assert!(found.is_empty(), "steps importing later steps:\n{}", found.join("\n"));
}

/// Whether `file` holds only tests (`tests.rs`, `*_tests.rs`).
fn is_test_file(file: &std::path::Path) -> bool {
    file.file_name()
        .and_then(|n| n.to_str())
        .is_some_and(|n| n.ends_with("tests.rs"))
}

/// The crate's modules `file` names after `crate::`, outside its test module (what
/// `#[cfg(test)]` guards comes last in our files).
fn crate_imports(file: &std::path::Path) -> Vec<String> {
    let text = std::fs::read_to_string(file).expect("readable");
    let text = text.split("#[cfg(test)]").next().unwrap_or("");
    text.match_indices("crate::")
        .flat_map(|(at, _)| modules_named(&text[at + 7..]))
        .collect()
}

/// The crate's modules a path after `crate::` names: `read` in `read::Model`, `a` and `b` in
/// `{a::X, b}` (the braces' top level; `self` and type names are not modules).
fn modules_named(rest: &str) -> Vec<String> {
    let word = |s: &str| -> String { s.chars().take_while(|c| c.is_ascii_lowercase() || *c == '_').collect() };
    let Some(inner) = rest.strip_prefix('{') else {
        return vec![word(rest)].into_iter().filter(|w| !w.is_empty()).collect();
    };
    let (mut depth, mut items, mut start) = (1, Vec::new(), 0);
    for (i, c) in inner.char_indices() {
        match c {
            '{' => depth += 1,
            '}' if depth == 1 => {
                items.push(&inner[start..i]);
                break;
            }
            '}' => depth -= 1,
            ',' if depth == 1 => {
                items.push(&inner[start..i]);
                start = i + 1;
            }
            _ => {}
        }
    }
    items
        .into_iter()
        .map(|item| word(item.trim_start()))
        .filter(|w| !w.is_empty() && w != "self")
        .collect()
}

#[test]
fn modules_named_reads_paths_and_braces() {
    assert_eq!(modules_named("read::Model;"), ["read"]);
    assert_eq!(
        modules_named("{plan::Part, joints::{Key, Joints}, Result};"),
        ["plan", "joints"]
    );
    assert!(modules_named("Error").is_empty());
}

fn rust_files(dir: &std::path::Path) -> Vec<std::path::PathBuf> {
    let mut out = Vec::new();
    for entry in std::fs::read_dir(dir).expect("listable").flatten() {
        let path = entry.path();
        if path.is_dir() {
            out.extend(rust_files(&path));
        } else if path.extension().is_some_and(|e| e == "rs") {
            out.push(path);
        }
    }
    out.sort();
    out
}

#[test]
fn models_too_small_for_mm_or_for_the_sheets_get_the_units_hint() {
    let units_hint = |size: f64, thickness: f64| {
        let settings = Settings {
            thicknesses: vec![thickness],
            ..Settings::default()
        };
        let mut state = State::new(source(size), settings);
        run(&[StepId::Read], &mut state, &Cancel::default()).expect("reads");
        state.records[0].warnings.iter().any(|w| w.kind == WarningKind::Units)
    };
    // A 4-unit Benchy, a 20-unit part: probably cm or inches.
    assert!(units_hint(4.0, 3.0));
    assert!(units_hint(20.0, 3.0));
    assert!(!units_hint(50.0, 3.0));
    // 50 mm is 5 sheets of 10 mm: no room for a joint between two walls.
    assert!(units_hint(50.0, 10.0));
}

#[test]
fn report_json_lists_the_warnings_of_exactly_the_cutting_plan_steps_before_export() {
    let names: Vec<&str> = CUTTING_PLAN
        .iter()
        .map(|s| s.name())
        .filter(|n| *n != "export")
        .collect();
    assert_eq!(names, crate::export::CUTTING_PLAN_STEPS);
}

/// The rule of docs/architecture.md ("Floats in comparators"): every comparator over floats is
/// a total order (`total_cmp`, or integer keys on a grid). `partial_cmp` panics or misorders on
/// NaN, and a tolerance that answers `Equal` is not transitive, so `sort_by` may panic ("does
/// not correctly implement a total order"), as it did on a cup beside its saucer.
#[test]
fn comparators_are_total_orders() {
    let crates = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let mut closures = 0;
    for krate in ["platener", "platener-geom", "platener-web", "platener-cli"] {
        for file in rust_files(&crates.join(krate).join("src")) {
            let text = std::fs::read_to_string(&file).expect("readable");
            assert!(
                !text.contains(concat!(".partial", "_cmp(")),
                "{} uses partial_cmp: use total_cmp",
                file.display()
            );
            for comparator in comparator_closures(&text) {
                closures += 1;
                assert!(
                    !comparator.contains(concat!("Ordering", "::Equal")),
                    "{}: a comparator answers Equal by hand (a tolerance is not a total order; \
                     compare integer keys instead):\n{comparator}",
                    file.display()
                );
            }
        }
    }
    assert!(closures > 50, "found only {closures} comparators: the scan is broken");
}

/// The argument text of every `sort_by(…)`, `max_by(…)`, `min_by(…)` and the like in `text`.
fn comparator_closures(text: &str) -> Vec<&str> {
    let mut out = Vec::new();
    for call in [
        ".sort_by(",
        ".sort_unstable_by(",
        ".max_by(",
        ".min_by(",
        ".binary_search_by(",
    ] {
        let mut from = 0;
        while let Some(at) = text[from..].find(call) {
            let open = from + at + call.len();
            let mut depth = 1;
            let end = text[open..]
                .char_indices()
                .find_map(|(k, c)| {
                    depth += i32::from(c == '(') - i32::from(c == ')');
                    (depth == 0).then_some(open + k)
                })
                .unwrap_or(text.len());
            out.push(&text[open..end]);
            from = open;
        }
    }
    out
}
