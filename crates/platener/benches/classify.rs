//! The classifier's detection (issue 20): sampling, RANSAC, labels, volumes and graph on a
//! finely tessellated, textured box (noise 0.25 mm, moved off the axes) of about 10k, 100k
//! and 1M triangles. The target: 1M triangles under 2 s on 2 cores; the sample
//! budget is fixed, so only sampling, labelling and the graph grow with the triangles.
//! The `layers` step (spheres and freeforms stacked among the plates) on a closed box with a
//! solid dome on its lid, the dome tessellated ever finer.
//! Run: `cargo bench -p platener --bench classify`. Figures go in docs/classifier.md.

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use platener::classify::{self, ClassifySettings};
use platener::glam::DVec3;
use platener::mesh::Mesh;
use platener::method::MethodKind;
use platener::pipeline::{self, StepId};
use platener::{Cancel, Settings, Source, State};
use platener_fixtures::samples;
use platener_fixtures::testsets;

/// Quad sizes (mm) giving about 10k, 100k and 1M triangles on a 100 × 80 × 60 box.
const CELLS: [f64; 3] = [2.75, 0.87, 0.275];

/// The textured box of quads of `cell` mm.
fn textured_box(cell: f64) -> Mesh {
    let (soup, _) = testsets::fine_box(DVec3::new(100.0, 80.0, 60.0), cell);
    testsets::roughen_and_move(&soup, 0.25, 1).0
}

fn classification(c: &mut Criterion) {
    let mut group = c.benchmark_group("classify");
    group.sample_size(10);
    let settings = ClassifySettings::default();
    for cell in CELLS {
        let mesh = textured_box(cell);
        let n = mesh.triangles.len();
        group.throughput(Throughput::Elements(n as u64));
        group.bench_with_input(BenchmarkId::new("textured_box", n), &mesh, |b, m| {
            b.iter(|| classify::run(m, &settings).expect("the box classifies"));
        });
    }
    group.finish();
}

/// Step `layers` alone, after the classifier's steps up to `parts`, on a 120 × 90 × 50 box
/// with a dome of radius 30 made of `segments` × `segments / 4` quads.
fn layers(c: &mut Criterion) {
    let mut group = c.benchmark_group("layers");
    group.sample_size(10);
    for segments in [48, 96, 192] {
        let tris = samples::domed_box(120.0, 90.0, 50.0, 3.0, 30.0, segments, segments / 4);
        let n = tris.len();
        let settings = MethodKind::Classifier.adjust(Settings {
            thicknesses: vec![3.0],
            ..Settings::default()
        });
        let mut state = State::new(Source::triangles("domed box", tris), settings);
        let before: Vec<StepId> = StepId::of_method(MethodKind::Classifier)
            .into_iter()
            .take_while(|s| *s != StepId::Layers)
            .collect();
        pipeline::run(&before, &mut state, &Cancel::default()).expect("the classifier's steps");
        group.bench_with_input(BenchmarkId::new("domed_box", n), &state, |b, state| {
            b.iter(|| {
                let mut s = state.clone();
                pipeline::run(&[StepId::Layers], &mut s, &Cancel::default()).expect("layers")
            });
        });
    }
    group.finish();
}

criterion_group!(benches, classification, layers);
criterion_main!(benches);
