//! Writes the stand-ins for the slow real models of issue 29 as binary STL into a folder,
//! for timing `platener convert` on them (docs/performance.md, "Every model answers in
//! seconds"): a workbench frame no sheet holds, and three 40-gon boxes with lids, 5 mm walls.
//!
//! `cargo run --release -p platener --example slow_samples -- /tmp/slow`

use std::path::PathBuf;

use platener_fixtures::samples;

fn main() -> std::io::Result<()> {
    let dir = std::env::args_os()
        .nth(1)
        .map_or_else(|| PathBuf::from("slowsamples"), PathBuf::from);
    std::fs::create_dir_all(&dir)?;
    for (name, triangles) in [
        ("workbench.stl", samples::workbench()),
        ("polygon-boxes.stl", samples::polygon_boxes(40, 5.0)),
    ] {
        let header = format!("platener slow-model stand-in {name}");
        std::fs::write(dir.join(name), samples::to_binary_stl(&triangles, &header))?;
        println!("wrote {} ({} triangles)", dir.join(name).display(), triangles.len());
    }
    Ok(())
}
