//! Nesting: density and time on part sets made in code (rectangles of mixed sizes, L-shapes,
//! plates with finger notches, plates with holes, and a mix), on 600 × 400 mm sheets and on a
//! fitted sheet. Densities (parts' area / used sheet area) are printed before timing.
//!
//! Run: `cargo bench -p platener --bench nesting`. Figures go in docs/cutting-plans.md.

use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};
use platener::kerf::cut_paths;
use platener::plan::samples::{fingered, l_shape, mixed, rectangle, window};
use platener::plan::{CutSettings, NestEffort, Part, SheetSize};
use platener::sheets::{Nesting, nest};

/// A simple deterministic sequence in [0, 1) for sizes.
fn units(seed: u64) -> impl FnMut() -> f64 {
    let mut s = seed;
    move || {
        s = s
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        (s >> 11) as f64 / (1u64 << 53) as f64
    }
}

fn part_sets() -> Vec<(&'static str, Vec<Part>)> {
    let mut u = units(1);
    let rectangles = (1..=40)
        .map(|id| rectangle(id, 20.0 + 160.0 * u(), 15.0 + 110.0 * u()))
        .collect();
    let ls = (1..=30)
        .map(|id| l_shape(id, 40.0 + 120.0 * u(), 40.0 + 100.0 * u(), 12.0 + 10.0 * u()))
        .collect();
    let fingers = (1..=30)
        .map(|id| fingered(id, 60.0 + 140.0 * u(), 40.0 + 80.0 * u(), 2 + id % 4, 3.0))
        .collect();
    let holes = (1..=24)
        .map(|id| {
            if id % 2 == 0 {
                window(id, 80.0 + 120.0 * u(), 80.0 + 100.0 * u(), 15.0)
            } else {
                rectangle(id, 20.0 + 40.0 * u(), 20.0 + 40.0 * u())
            }
        })
        .collect();
    vec![
        ("rectangles-40", rectangles),
        ("l-shapes-30", ls),
        ("fingered-30", fingers),
        ("holes-24", holes),
        ("mixed-60", mixed(60, 3)),
        ("mixed-150", mixed(150, 5)),
    ]
}

fn run(parts: &[Part], settings: &CutSettings) -> (Nesting, f64) {
    let start = std::time::Instant::now();
    let (cut, _) = cut_paths(parts, settings.kerf()).expect("cut paths");
    let nesting = nest(parts, &cut, settings, &|| false).expect("nests");
    (nesting, start.elapsed().as_secs_f64() * 1e3)
}

/// Overall density and the density of every sheet but the last (full sheets).
fn summary((n, millis): &(Nesting, f64)) -> String {
    let parts: f64 = n.sheets.iter().map(|s| s.parts_area).sum();
    let used: f64 = n.sheets.iter().map(|s| s.used_area).sum();
    let per: Vec<String> = n.sheets.iter().map(|s| format!("{:.1}", 100.0 * s.density)).collect();
    format!(
        "{} sheets, density {:.1} % (per sheet {}), {:.0} ms",
        n.sheets.len(),
        100.0 * parts / used,
        per.join(" / "),
        millis
    )
}

/// The parts of `model` as the stacked method makes them (its layers, shafts and keys).
fn stacked_parts(name: &str, model: Vec<platener_geom::Triangle>) -> Vec<Part> {
    use platener::method::MethodKind;
    let state = platener::convert(
        MethodKind::Stacked,
        platener::Source::triangles(name, model),
        platener::Settings::default(),
        &platener::Cancel::default(),
    )
    .expect("the stacked method converts");
    state.stacked_parts.expect("the stacked parts").parts.clone()
}

/// The strip-packing sets compared with sparrow (issue 34): finger-jointed plates, a sphere's
/// layers and an organic figure's layers.
fn strip_sets() -> Vec<(&'static str, Vec<Part>)> {
    use platener::glam::DVec3;
    use platener_fixtures::samples;
    let mut u = units(7);
    let fingers = (1..=13)
        .map(|id| fingered(id, 60.0 + 140.0 * u(), 40.0 + 80.0 * u(), 2 + id % 4, 3.0))
        .collect();
    vec![
        ("fingered-13", fingers),
        (
            "sphere-layers",
            stacked_parts("sphere", samples::sphere(DVec3::ZERO, 50.0, 32, 16)),
        ),
        ("animal-layers", stacked_parts("animal", samples::animal())),
    ]
}

/// With `PLATENER_NESTING_EXPORT=FILE`, writes [`strip_sets`] for `tools/nesting-vs-spyrrow.py`:
/// each set's cut outlines and our strip length on a 400 mm high strip (no margin, 2 mm
/// spacing) at each `nesting` level, with the time it took.
fn export_strip_sets(file: &str) {
    let mut sets = Vec::new();
    for (name, parts) in strip_sets() {
        let (cut, _) = cut_paths(&parts, CutSettings::default().kerf()).expect("cut paths");
        let outlines: Vec<Vec<[f64; 2]>> = cut
            .parts
            .iter()
            .map(|p| p.cut.outer.iter().map(|q| [q.x, q.y]).collect())
            .collect();
        let area: f64 = cut.parts.iter().map(|p| p.nominal.area()).sum();
        let mut ours = serde_json::Map::new();
        for effort in NestEffort::ALL {
            let settings = CutSettings {
                sheet: SheetSize::Fixed {
                    width: 10_000.0,
                    height: 400.0,
                },
                margin: 0.0,
                nest_tries: effort.tries(),
                labels: platener::plan::LabelMode::None,
                ..CutSettings::default()
            };
            let (n, millis) = run(&parts, &settings);
            let length = n.sheets[0].used_area / 400.0;
            println!(
                "strip {name} {}: {} parts, length {length:.1} mm, {millis:.0} ms",
                effort.name(),
                parts.len()
            );
            ours.insert(
                effort.name().into(),
                serde_json::json!({"length": length, "millis": millis}),
            );
        }
        sets.push(serde_json::json!({"name": name, "height": 400.0, "spacing": 2.0, "area": area, "outlines": outlines, "ours": ours}));
    }
    std::fs::write(file, serde_json::to_string(&sets).expect("json")).expect("write the sets");
}

fn bench(c: &mut Criterion) {
    if let Ok(file) = std::env::var("PLATENER_NESTING_EXPORT") {
        export_strip_sets(&file);
        return;
    }
    let mut group = c.benchmark_group("nesting");
    group.sample_size(10);
    for (name, parts) in part_sets() {
        // The `nesting` setting's levels on 600 × 400 mm sheets, and the default on a fitted one.
        for (label, sheet, effort) in [
            ("600x400-fast", SheetSize::default(), NestEffort::Fast),
            ("600x400-good", SheetSize::default(), NestEffort::Good),
            ("600x400-best", SheetSize::default(), NestEffort::Best),
            ("fit-good", SheetSize::Fit, NestEffort::Good),
        ] {
            let settings = CutSettings {
                sheet,
                nest_tries: effort.tries(),
                labels: platener::plan::LabelMode::None,
                ..CutSettings::default()
            };
            println!("nesting {name} {label}: {}", summary(&run(&parts, &settings)));
            group.bench_with_input(BenchmarkId::new(name, label), &parts, |b, parts| {
                b.iter(|| run(parts, &settings));
            });
        }
    }
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
