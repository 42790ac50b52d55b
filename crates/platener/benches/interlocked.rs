//! The interlocked method on a 20 k-triangle figurine (issue 31: under 2 s on 2 cores): the
//! `interlocked` step alone (sections, slots, pieces, parts), and the whole method from the
//! triangles to the ZIP (foundation without welding, the step, kerf, labels, nesting, export).
//! Run: `cargo bench -p platener --bench interlocked`. Figures go in docs/performance.md.

use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};
use platener::method::MethodKind;
use platener::pipeline::{self, Cancel, Source, State, StepId};
use platener::{Settings, convert};
use platener_fixtures::samples;

fn interlocked(c: &mut Criterion) {
    let mut group = c.benchmark_group("interlocked");
    group.sample_size(10);
    let tris = samples::animal_facets(48, 24);
    let count = tris.len();
    let settings = MethodKind::Interlocked.adjust(Settings::default());
    let steps = StepId::of_method(MethodKind::Interlocked);
    let upto = steps.iter().position(|s| *s == StepId::Interlocked).expect("the step");
    let mut state = State::new(Source::triangles("animal", tris.clone()), settings.clone());
    pipeline::run(&steps[..upto], &mut state, &Cancel::default()).expect("foundation");
    group.bench_function(BenchmarkId::new("step", count), |b| {
        b.iter(|| {
            let mut s = state.clone();
            pipeline::run(&[StepId::Interlocked], &mut s, &Cancel::default()).expect("interlocked")
        });
    });
    group.bench_function(BenchmarkId::new("method", count), |b| {
        b.iter(|| {
            let source = Source::triangles("animal", tris.clone());
            convert(MethodKind::Interlocked, source, Settings::default(), &Cancel::default()).expect("converts")
        });
    });
    group.finish();
}

criterion_group!(benches, interlocked);
criterion_main!(benches);
