//! Writes a finely tessellated rounded box (the benchmark model) as a binary STL.
//!
//! `cargo run --release -p platener --example rounded_box -- N OUT.stl` writes 12·N² triangles.

use platener::glam::DVec3;
use platener_fixtures::samples;

fn main() -> std::io::Result<()> {
    let mut args = std::env::args().skip(1);
    let n: usize = args.next().and_then(|a| a.parse().ok()).unwrap_or(289);
    let out = args.next().unwrap_or_else(|| "rounded-box.stl".into());
    let tris = samples::rounded_box(DVec3::new(200.0, 150.0, 100.0), 10.0, n);
    std::fs::write(&out, samples::to_binary_stl(&tris, "rounded box"))?;
    println!("wrote {out} ({} triangles)", tris.len());
    Ok(())
}
