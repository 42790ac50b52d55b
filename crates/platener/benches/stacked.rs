//! The stacked method: slicing (bucketing, segments, loop chaining, even-odd islands) of a
//! finely tessellated rounded box, and the whole `stacked` step (slicing, shafts, parts) on a
//! sphere.
//!
//! The target: a 1 000 000-triangle model sliced into 100 layers under 1 s, near linear
//! in triangles + layers; hence the runs at 100k and 1M triangles and 10, 100 and 1000 layers.
//! Run: `cargo bench -p platener --bench stacked`. Figures go in docs/stacked.md.

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use platener::Settings;
use platener::glam::DVec3;
use platener::mesh::Mesh;
use platener::pipeline::{self, Cancel, Source, State};
use platener::pipeline::{FOUNDATION, StepId};
use platener::settings::{StackAxis, StackedSettings};
use platener::stacked::{AxisChoice, SlicePlan, island_rule, islands_of, slice};
use platener::weld::weld_soup;
use platener_fixtures::samples;

/// Grid sizes per face: 12·n² triangles ≈ 100k and 1M.
const SIZES: [usize; 2] = [91, 289];

/// A 200 × 150 × 300 mm rounded box: 100 layers of 3 mm.
fn mesh(n: usize) -> Mesh {
    let tris = samples::rounded_box(DVec3::new(200.0, 150.0, 300.0), 10.0, n);
    let w = weld_soup(&tris, 0.0);
    Mesh::build(w.vertices, &w.triangles, 1e-9)
}

fn slicing(c: &mut Criterion) {
    let mut group = c.benchmark_group("slice");
    group.sample_size(10);
    let keep = StackedSettings::default();
    for n in SIZES {
        let m = mesh(n);
        group.throughput(Throughput::Elements(m.triangles.len() as u64));
        for layers in [10usize, 100, 1000] {
            if n != SIZES[1] && layers != 100 {
                continue;
            }
            let t = 300.0 / layers as f64;
            let plan = SlicePlan::new(&m, DVec3::Z, AxisChoice::Given, t).expect("triangles");
            assert_eq!(plan.count, layers);
            let id = BenchmarkId::new(format!("{layers}-layers"), m.triangles.len());
            group.bench_with_input(id, &plan, |b, plan| {
                b.iter(|| {
                    let sliced = slice(&m, plan, 1e-3);
                    islands_of(&sliced, &island_rule(t, &keep)).expect("on the grid")
                });
            });
        }
    }
    group.finish();
}

fn whole_step(c: &mut Criterion) {
    let mut group = c.benchmark_group("stacked-step");
    group.sample_size(10);
    let tris = samples::sphere(DVec3::ZERO, 50.0, 256, 128);
    let count = tris.len();
    let mut settings = Settings::default();
    settings.stacked.axis = StackAxis::Auto;
    let source = Source::triangles("sphere", tris);
    let mut state = State::new(source, platener::method::MethodKind::Stacked.adjust(settings));
    pipeline::run(&FOUNDATION, &mut state, &Cancel::default()).expect("foundation");
    group.bench_function(BenchmarkId::new("sphere-100mm", count), |b| {
        b.iter(|| {
            let mut s = state.clone();
            pipeline::run(&[StepId::Stacked], &mut s, &Cancel::default()).expect("stacked")
        });
    });
    group.finish();
}

criterion_group!(benches, slicing, whole_step);
criterion_main!(benches);
