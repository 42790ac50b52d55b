//! `platener test-strip`: writes the kerf test strip and prints its hole → kerf table.

use std::fmt::Write as _;

use anyhow::Context as _;
use platener::draw::svg::num;
use platener::swatches::strip::{KERF_STEP, SPIKE_WIDTH, TestStrip, test_strip};

use crate::args::TestStripArgs;

/// Runs the command.
pub fn run(args: &TestStripArgs) -> anyhow::Result<()> {
    let material = args.material.chosen()?.settings.cut.material;
    let strip = test_strip(args.thickness, material)?;
    std::fs::write(&args.output, strip.svg()).with_context(|| format!("cannot write {}", args.output.display()))?;
    print!(
        "{}",
        render(&strip, &args.output.display().to_string(), material.name())
    );
    Ok(())
}

/// The instructions and the table printed after writing the strip.
pub fn render(strip: &TestStrip, file: &str, material: &str) -> String {
    let mut s = String::new();
    let _ = writeln!(
        s,
        "wrote {file}: {:.1} × {:.1} mm, a strip with {} holes and a {SPIKE_WIDTH:.3} mm spike",
        strip.width,
        strip.height,
        strip.holes.len()
    );
    let _ = writeln!(
        s,
        "Cut it as drawn (no kerf compensation), push the spike into the holes and pick the narrowest hole it enters."
    );
    let _ = writeln!(
        s,
        "kerf of hole n = (n - 1) × {KERF_STEP} mm (hole width = {SPIKE_WIDTH} - 2 × kerf)"
    );
    let _ = writeln!(s, "hole  width mm  kerf mm");
    for h in &strip.holes {
        let mark = if h.number == strip.default_hole {
            format!("  * {material} default")
        } else {
            String::new()
        };
        let _ = writeln!(s, "{:>4}  {:>8.3}  {:>7.3}{mark}", h.number, h.width, h.kerf);
    }
    if let (Some(first), Some(last)) = (strip.slots.first(), strip.slots.last()) {
        let _ = writeln!(
            s,
            "Slot row: turn the spike on its side and push it into the slots (each engraved with the sheet \
             thickness it fits, {:.2}–{:.2} mm, for the starred kerf). The narrowest slot it enters snugly \
             is your sheet's real thickness: give it as thickness {}@THAT (e.g. {}@{:.2}). The next narrower slot, \
             pressed home, shows how tight a press fit is.",
            first.sheet,
            last.sheet,
            num(strip.thickness),
            num(strip.thickness),
            strip.thickness - 0.15
        );
    }
    s
}
