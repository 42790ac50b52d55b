//! The classifier's detection (issue 20): sampling, RANSAC, labels, volumes and graph on a
//! finely tessellated, textured box (noise 0.25 mm, moved off the axes) of about 10k, 100k
//! and 1M triangles. The target: 1M triangles under 2 s on 2 cores; the sample
//! budget is fixed, so only sampling, labelling and the graph grow with the triangles.
//! Run: `cargo bench -p platener --bench classify`. Figures go in docs/classifier.md.

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use platener::classify::{self, ClassifySettings, testsets};
use platener::glam::DVec3;
use platener::mesh::Mesh;

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

criterion_group!(benches, classification);
criterion_main!(benches);
