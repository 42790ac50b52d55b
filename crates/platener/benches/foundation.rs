//! The foundation pipeline (read → cleanup → weld → mesh → coplanar → shapes) on a finely
//! tessellated rounded box of 10k, 100k and 1M triangles, read from a binary STL file.
//!
//! Run: `cargo bench -p platener --bench foundation`. Figures go in docs/performance.md.

use std::sync::Arc;

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use platener::glam::DVec3;
use platener::inspect::run_foundation;
use platener::{Cancel, Settings, Source, Weld};
use platener_fixtures::samples;

/// Grid sizes per face: 12·n² triangles ≈ 10k, 100k, 1M.
const SIZES: [usize; 3] = [29, 91, 289];

fn model(n: usize) -> Vec<[DVec3; 3]> {
    samples::rounded_box(DVec3::new(200.0, 150.0, 100.0), 10.0, n)
}

fn bench(c: &mut Criterion) {
    let dir = tempfile::tempdir().expect("temp dir");
    let mut group = c.benchmark_group("foundation");
    group.sample_size(10);
    for n in SIZES {
        let triangles = model(n);
        let path = dir.path().join(format!("rounded-box-{n}.stl"));
        std::fs::write(&path, samples::to_binary_stl(&triangles, "rounded box")).expect("write model");
        group.throughput(Throughput::Elements(triangles.len() as u64));
        for (label, weld) in [("auto-weld", Weld::Auto), ("no-weld", Weld::Off)] {
            let settings = Settings {
                weld,
                ..Settings::default()
            };
            group.bench_with_input(BenchmarkId::new(label, triangles.len()), &path, |b, path| {
                b.iter(|| {
                    run_foundation(Source::File(path.clone()), settings.clone(), &Cancel::default()).expect("converts")
                });
            });
        }
        // The same in memory, without the file read, to separate parsing from the rest.
        let shared = Arc::new(triangles);
        group.bench_with_input(
            BenchmarkId::new("in-memory-auto-weld", shared.len()),
            &shared,
            |b, tris| {
                b.iter(|| {
                    let source = Source::Triangles {
                        name: "rounded box".into(),
                        triangles: tris.clone(),
                    };
                    run_foundation(source, Settings::default(), &Cancel::default()).expect("converts")
                });
            },
        );
    }
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
