//! Writes the bent-plate samples of issue 19 (`platener_fixtures::samples::bent_samples`) and the CAD
//! detail samples of issue 32 (`cad_detail_samples`) and the organic samples of issue 31
//! (`organic_samples`) as binary STL into a folder, for
//! converting them by hand: the before/after figures.
//!
//! `cargo run -p platener --example bent_samples -- /tmp/bentsamples`

use std::path::PathBuf;

use platener_fixtures::samples;

fn main() -> std::io::Result<()> {
    let dir = std::env::args_os()
        .nth(1)
        .map_or_else(|| PathBuf::from("bentsamples"), PathBuf::from);
    std::fs::create_dir_all(&dir)?;
    for (name, triangles) in samples::bent_samples()
        .into_iter()
        .chain(samples::cad_detail_samples())
        .chain(samples::organic_samples())
    {
        let header = format!("platener bent-plate sample {name}");
        std::fs::write(dir.join(name), samples::to_binary_stl(&triangles, &header))?;
        println!("wrote {} ({} triangles)", dir.join(name).display(), triangles.len());
    }
    Ok(())
}
