//! Plate finding on a grid of closed 3 mm boxes: 100k triangles, 5 000 plates.
//!
//! Run: `cargo bench -p platener --bench plates`. Figures go in docs/performance.md.

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use platener::inspect::run_foundation;
use platener::plates::find_plates;
use platener::{Cancel, Settings, Source};
use platener_fixtures::samples;

fn bench(c: &mut Criterion) {
    // 29 × 29 boxes × 120 triangles = 100 920 triangles.
    let triangles = samples::box_grid(29, 29, 40.0, 3.0, 10.0);
    let n = triangles.len();
    let source = Source::triangles("box grid", triangles);
    let settings = Settings::default();
    let (state, _) = run_foundation(source.clone(), settings.clone(), &Cancel::default()).expect("converts");
    let shapes = state.shapes.clone().expect("shapes");
    let mesh = state.mesh.clone().expect("mesh");
    let model = state.read.clone().expect("read");
    let center = (model.bounds.min + model.bounds.max) / 2.0;
    let found = find_plates(&shapes, &mesh, center, &settings).expect("plates");
    assert_eq!(found.plates.len(), 6 * 29 * 29);

    let mut group = c.benchmark_group("plates");
    group.sample_size(10);
    group.throughput(Throughput::Elements(n as u64));
    group.bench_function("find_plates/box-grid-100k", |b| {
        b.iter(|| find_plates(&shapes, &mesh, center, &settings).expect("plates"));
    });
    group.bench_function("file-to-plates/box-grid-100k", |b| {
        b.iter(|| {
            let mut state = platener::State::new(source.clone(), settings.clone());
            platener::pipeline::run(&platener::pipeline::PLATE, &mut state, &Cancel::default()).expect("runs")
        });
    });
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
