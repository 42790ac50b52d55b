//! Writes the models shipped in `examples/` from the generators in `platener_fixtures::samples`.
//!
//! Run `cargo run -p platener --example make_examples` after changing a generator; a test
//! checks the shipped files still match.

use std::path::Path;

use platener_fixtures::samples;

fn main() -> std::io::Result<()> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples");
    for (name, header, triangles) in samples::shipped_examples() {
        let bytes = samples::to_binary_stl(&triangles, header);
        std::fs::write(dir.join(name), bytes)?;
        println!("wrote examples/{name} ({} triangles)", triangles.len());
    }
    Ok(())
}
