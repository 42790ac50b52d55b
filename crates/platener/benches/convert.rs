//! One-call conversion (`convert_all`, both methods, the shared steps once) against one call
//! per method (each reading and cleaning the model again), on a model file read from bytes;
//! and the answers of issue 29 (`answers`: the box alone, the slow stand-ins).
//!
//! Run: `cargo bench -p platener --bench convert [-- answers]`. Figures go in docs/performance.md.

use std::sync::Arc;

use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};
use platener::convert::{Request, Status, convert_all, no_progress};
use platener::glam::DVec3;
use platener::method::MethodKind;
use platener::{Cancel, Settings, Source};
use platener_fixtures::samples;

fn request(bytes: &Arc<[u8]>, methods: Vec<MethodKind>) -> Request {
    let source = Source::Bytes {
        name: "model.stl".into(),
        bytes: bytes.clone(),
    };
    Request {
        methods,
        ..Request::new(source, Settings::default())
    }
}

fn bench(c: &mut Criterion) {
    let models = [
        ("box", samples::closed_box(100.0, 80.0, 60.0, 3.0)),
        ("sphere-8k", samples::sphere(DVec3::ZERO, 50.0, 64, 64)),
    ];
    let mut group = c.benchmark_group("convert");
    group.sample_size(10);
    for (name, triangles) in models {
        let bytes: Arc<[u8]> = samples::to_binary_stl(&triangles, name).into();
        let all = convert_all(
            request(&bytes, MethodKind::ALL.to_vec()),
            &Cancel::default(),
            no_progress(),
        );
        assert!(all.methods.iter().any(|m| m.status == Status::Converted), "{name}");
        group.bench_function(BenchmarkId::new("convert_all", name), |b| {
            b.iter(|| {
                convert_all(
                    request(&bytes, MethodKind::ALL.to_vec()),
                    &Cancel::default(),
                    no_progress(),
                )
            })
        });
        group.bench_function(BenchmarkId::new("one-call-per-method", name), |b| {
            b.iter(|| MethodKind::ALL.map(|m| convert_all(request(&bytes, vec![m]), &Cancel::default(), no_progress())))
        });
    }
    group.finish();
}

/// Issue 29's figures: the 6-plate box with the plate method alone (all steps, scoring and
/// verifying included; goal ≤ 60 ms), and the stand-ins for the slow real models with every
/// method (`samples::workbench`, refused by every method; `samples::polygon_boxes`).
fn answers(c: &mut Criterion) {
    let mut group = c.benchmark_group("answers");
    group.sample_size(10);
    let cases = [
        (
            "box-plate",
            samples::closed_box(120.0, 90.0, 70.0, 3.0),
            vec![MethodKind::Plate],
        ),
        ("workbench-all", samples::workbench(), MethodKind::ALL.to_vec()),
        (
            "polygon-boxes-all",
            samples::polygon_boxes(40, 5.0),
            MethodKind::ALL.to_vec(),
        ),
    ];
    for (name, triangles, methods) in cases {
        let bytes: Arc<[u8]> = samples::to_binary_stl(&triangles, name).into();
        group.bench_function(name, |b| {
            b.iter(|| convert_all(request(&bytes, methods.clone()), &Cancel::default(), no_progress()))
        });
    }
    group.finish();
}

criterion_group!(benches, bench, answers);
criterion_main!(benches);
