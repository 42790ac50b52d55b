//! STL reader throughput, in bytes of file per second. Targets on the 2-core reference machine:
//! binary ≥ 1 GB/s, ASCII ≥ 150 MB/s. The files are generated in memory (a 1,000,000-triangle
//! binary STL of 50 MB and 200,000-facet ASCII STLs), so the bench needs no data on disk;
//! `read_path` is measured too, on the same bytes written to a temporary file.

use std::fmt::Write as _;
use std::hint::black_box;
use std::io::Write as _;
use std::path::Path;
use std::time::Duration;

use criterion::{BenchmarkGroup, Criterion, Throughput, criterion_group, criterion_main, measurement::WallTime};
use platener::read::stl::{parse_bytes, read_path};

/// Deterministic coordinates in ±500 mm with micrometre steps, like exported models.
struct Coordinates(u64);

impl Coordinates {
    fn next(&mut self) -> f64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        (self.0 % 1_000_000_000) as f64 / 1e6 - 500.0
    }
}

fn binary_stl(facets: u32) -> Vec<u8> {
    let mut rng = Coordinates(0x0123_4567_89AB_CDEF);
    let mut bytes = Vec::with_capacity(84 + 50 * facets as usize);
    bytes.extend_from_slice(&[b' '; 80]);
    bytes.extend_from_slice(&facets.to_le_bytes());
    for _ in 0..facets {
        for _ in 0..12 {
            bytes.extend_from_slice(&(rng.next() as f32).to_le_bytes());
        }
        bytes.extend_from_slice(&[0, 0]);
    }
    bytes
}

/// An ASCII STL; `e_notation` prints like C's `%e` (SolidWorks, numpy-stl), else like `%.6f`.
fn ascii_stl(facets: usize, e_notation: bool) -> Vec<u8> {
    let mut rng = Coordinates(0xFEDC_BA98_7654_3210);
    let mut number = |out: &mut String| {
        let v = rng.next();
        if e_notation {
            let exponent = if v == 0.0 { 0 } else { v.abs().log10().floor() as i32 };
            let mantissa = v / 10f64.powi(exponent);
            let _ = write!(
                out,
                " {mantissa:.6}e{}{:02}",
                if exponent < 0 { '-' } else { '+' },
                exponent.abs()
            );
        } else {
            let _ = write!(out, " {v:.6}");
        }
    };
    let mut text = String::from("solid benchmark\n");
    for _ in 0..facets {
        text.push_str("  facet normal");
        (0..3).for_each(|_| number(&mut text));
        text.push_str("\n    outer loop\n");
        for _ in 0..3 {
            text.push_str("      vertex");
            (0..3).for_each(|_| number(&mut text));
            text.push('\n');
        }
        text.push_str("    endloop\n  endfacet\n");
    }
    text.push_str("endsolid benchmark\n");
    text.into_bytes()
}

fn bench_file(group: &mut BenchmarkGroup<'_, WallTime>, name: &str, bytes: &[u8], dir: &Path) {
    group.throughput(Throughput::Bytes(bytes.len() as u64));
    group.bench_function(format!("parse_bytes/{name}"), |b| {
        b.iter(|| parse_bytes(black_box(bytes)).map(|(_, mesh)| mesh.triangles.len()))
    });
    let path = dir.join(format!("{name}.stl"));
    let written = std::fs::File::create(&path).and_then(|mut file| file.write_all(bytes));
    if written.is_ok() {
        group.bench_function(format!("read_path/{name}"), |b| {
            b.iter(|| read_path(black_box(&path)).map(|(_, mesh)| mesh.triangles.len()))
        });
    }
}

fn read(c: &mut Criterion) {
    let Ok(dir) = tempfile::tempdir() else { return };
    let mut group = c.benchmark_group("stl");
    group
        .sample_size(10)
        .warm_up_time(Duration::from_secs(1))
        .measurement_time(Duration::from_secs(4));
    bench_file(&mut group, "binary_1M", &binary_stl(1_000_000), dir.path());
    bench_file(&mut group, "ascii_e_200k", &ascii_stl(200_000, true), dir.path());
    bench_file(&mut group, "ascii_plain_200k", &ascii_stl(200_000, false), dir.path());
    group.finish();
}

criterion_group!(benches, read);
criterion_main!(benches);
