//! The `bends` step on many facets: a vase (a surface of revolution of 3 mm plates, one per
//! facet, `sides` around × `rings` up) developed into bent parts. 10 000 facets is the
//! issue's figure; 400 and 2 500 show the growth.
//!
//! Run: `cargo bench -p platener --bench bends`. Figures go in docs/performance.md.

use criterion::{Criterion, criterion_group, criterion_main};
use glam::{DVec2, DVec3};
use platener::Bending;
use platener::bends::compute;
use platener::plan::{BendStyle, Material};
use platener::plates::{Plate, PlateKind};
use platener_geom::{Frame, Polygon};

/// One plate per facet of a vase: ring k at height 12k mm with radius 250 + 40·sin(k/8) mm,
/// so that even at 100 × 100 facets each is about 15 × 12 mm, room for a 3 mm hinge.
fn vase(sides: usize, rings: usize) -> Vec<Plate> {
    let t = 3.0;
    let at = |s: usize, k: usize| {
        let z = 12.0 * k as f64;
        let r = 250.0 + 40.0 * (k as f64 / 8.0).sin();
        let a = std::f64::consts::TAU * s as f64 / sides as f64;
        DVec3::new(r * a.cos(), r * a.sin(), z)
    };
    let mut plates = Vec::new();
    for k in 0..rings {
        for s in 0..sides {
            let quad = [at(s, k), at(s + 1, k), at(s + 1, k + 1), at(s, k + 1)];
            let normal = (quad[1] - quad[0]).cross(quad[3] - quad[0]).normalize();
            // The facet is the plate's outer face; the plate reaches a thickness inwards.
            let frame = Frame::on_plane(quad[0] - normal * t, normal);
            let polygon = Polygon::new(quad.iter().map(|p| frame.to_2d(*p)).collect::<Vec<DVec2>>());
            plates.push(Plate {
                kind: PlateKind::Extruded,
                thickness: t,
                frame,
                area: polygon.area().abs(),
                polygon,
                shapes: vec![plates.len() as u32],
            });
        }
    }
    for p in &mut plates {
        p.polygon.normalize_orientation();
    }
    plates
}

fn bench(c: &mut Criterion) {
    let mut group = c.benchmark_group("bends");
    group.sample_size(10);
    for (sides, rings) in [(20, 20), (50, 50), (100, 100)] {
        let plates = vase(sides, rings);
        let style = Bending::Style(BendStyle::LivingHinge);
        let once = compute(&plates, None, style, Material::Wood, (1e5, 1e5)).expect("grid");
        assert!(!once.parts.is_empty());
        group.bench_function(format!("vase/{} facets", plates.len()), |b| {
            b.iter(|| compute(&plates, None, style, Material::Wood, (1e5, 1e5)).expect("grid"));
        });
    }
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
