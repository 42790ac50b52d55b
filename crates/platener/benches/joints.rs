//! Joints on a grid of closed 3 mm boxes (every plate has four corner joints): finger joints
//! and dovetails with their keys; three plates on one line (a Y, 50 mm long); a 12 × 8
//! low-poly ball.
//!
//! Run: `cargo bench -p platener --bench joints`. Figures go in docs/performance.md.

use criterion::{Criterion, criterion_group, criterion_main};
use platener::joints::{JointSettings, JointStyle, compute};
use platener::{Cancel, Settings, Source};
use platener_fixtures::samples;

fn bench(c: &mut Criterion) {
    let mut group = c.benchmark_group("joints");
    group.sample_size(10);
    for n in [1usize, 10] {
        let source = Source::triangles("box grid", samples::box_grid(n, n, 40.0, 3.0, 10.0));
        let mut state = platener::State::new(source, Settings::default());
        platener::pipeline::run(&platener::pipeline::PLATE, &mut state, &Cancel::default()).expect("runs");
        let plates = state.plates.clone().expect("plates");
        assert_eq!(plates.plates.len(), 6 * n * n);
        for style in [JointStyle::Finger, JointStyle::Dovetail] {
            let settings = JointSettings {
                style: Some(style),
                ..JointSettings::default()
            };
            group.bench_function(format!("{style:?}/{} plates", 6 * n * n), |b| {
                b.iter(|| compute(&plates.plates, &settings).expect("grid"));
            });
        }
    }
    let source = Source::triangles("Y", samples::star(3, 40.0, 3.0, 50.0));
    let mut state = platener::State::new(source, Settings::default());
    platener::pipeline::run(&platener::pipeline::PLATE, &mut state, &Cancel::default()).expect("runs");
    let plates = state.plates.clone().expect("plates");
    assert_eq!(plates.plates.len(), 3);
    group.bench_function("Finger/Y of 3 plates", |b| {
        b.iter(|| compute(&plates.plates, &JointSettings::default()).expect("grid"));
    });
    // A low-poly ball: 72 facets at 147°–163°, shorter fingers and growth cut back at vertices.
    let source = Source::triangles("ball", samples::sphere(glam::DVec3::ZERO, 40.0, 12, 8));
    let mut state = platener::State::new(source, Settings::default());
    platener::pipeline::run(&platener::pipeline::PLATE, &mut state, &Cancel::default()).expect("runs");
    let plates = state.plates.clone().expect("plates");
    group.bench_function(format!("Finger/ball of {} plates", plates.plates.len()), |b| {
        b.iter(|| compute(&plates.plates, &JointSettings::default()).expect("grid"));
    });
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
