//! `platener hinge-test`: writes a bend swatch and prints the design it shows.

use std::fmt::Write as _;

use anyhow::Context as _;
use platener::hinge::BendDesign;
use platener::plan::BendStyle;
use platener::swatches::hinge::{Swatch, hinge_swatch};

use crate::args::HingeTestArgs;

/// Runs the command.
pub fn run(args: &HingeTestArgs) -> anyhow::Result<()> {
    let material = args.material.chosen()?.settings.cut.material;
    let swatch = hinge_swatch(args.bend.style(material), material, args.thickness, args.angle)?;
    std::fs::write(&args.output, swatch.svg()).with_context(|| format!("cannot write {}", args.output.display()))?;
    print!("{}", render(&swatch, &args.output.display().to_string()));
    Ok(())
}

/// What was written, each strip's figures and how to use the swatch.
pub fn render(s: &Swatch, file: &str) -> String {
    let mut out = String::new();
    let _ = writeln!(
        out,
        "wrote {file}: {:.1} × {:.1} mm, {} strip(s) in {} mm {}",
        s.width,
        s.height,
        s.strips.len(),
        s.strips.first().map_or(0.0, |x| x.design.thickness),
        s.material.name()
    );
    for (k, strip) in s.strips.iter().enumerate() {
        out.push_str(&render_design(k + 1, &strip.design));
    }
    let turn = s.strips.first().map_or(0.0, |x| x.design.turn.to_degrees());
    let _ = writeln!(
        out,
        "Cut it (red) and engrave it (blue), then bend the two ends of each strip to {turn:.0}°: the zone should curve evenly without cracking. A strip that cracks shows the pattern this stock cannot take."
    );
    out
}

/// The figures of strip `k`'s design.
fn render_design(k: usize, d: &BendDesign) -> String {
    let mut out = String::new();
    let pattern = if d.style == BendStyle::LivingHinge {
        format!(" ({} pattern)", d.pattern.name())
    } else {
        String::new()
    };
    let _ = writeln!(
        out,
        "strip {k}: a {}{pattern} bend of {:.1}°",
        d.style.name(),
        d.turn.to_degrees()
    );
    let corner = if d.corner_gap().is_finite() {
        format!(", inside the model's corner by {:.2} mm", d.corner_gap())
    } else {
        String::new()
    };
    let _ = writeln!(
        out,
        "  zone {:.2} mm wide (flat), neutral radius {:.2} mm{corner}",
        d.zone_width, d.neutral_radius
    );
    match d.style {
        BendStyle::LivingHinge => {
            let _ = writeln!(
                out,
                "  {} links {:.2} × {:.2} mm in {} rows of slits {:.2} mm long (bridges {:.2} mm, pitch {:.2} mm)",
                d.links, d.link_width, d.link_length, d.rows, d.slit_length, d.bridge, d.pitch
            );
        }
        BendStyle::Perforation => {
            let _ = writeln!(out, "  dashes {:.2} mm cut, {:.2} mm ties", d.slit_length, d.bridge);
        }
        BendStyle::Score | BendStyle::Heat => {}
    }
    out
}
