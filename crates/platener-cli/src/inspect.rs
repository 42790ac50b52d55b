//! `platener inspect`: prints the library's [`platener::inspect::Inspection`].

use std::fmt::Write as _;

use platener::glam::DVec3;
use platener::inspect::{Inspection, inspect};
use platener::{Cancel, Source};

use crate::args::InspectArgs;

/// Runs the command.
pub fn run(args: &InspectArgs) -> anyhow::Result<()> {
    let settings = args.model_args.settings()?;
    let report = inspect(Source::File(args.model.clone()), settings, &Cancel::default())?;
    if args.json {
        println!("{}", serde_json::to_string_pretty(&report)?);
    } else {
        print!("{}", render(&report));
    }
    Ok(())
}

fn v3(v: DVec3) -> String {
    format!("({:.2}, {:.2}, {:.2})", v.x, v.y, v.z)
}

/// The human-readable report.
pub fn render(r: &Inspection) -> String {
    let mut s = String::new();
    let h = &r.health;
    let size = r.bounds.max - r.bounds.min;
    let _ = writeln!(
        s,
        "model      {} ({}, {} solid{})",
        r.model,
        r.format.unwrap_or("generated"),
        r.solids,
        if r.solids == 1 { "" } else { "s" }
    );
    let _ = writeln!(
        s,
        "triangles  {} read; {} degenerate and {} duplicate removed; {} in the mesh",
        r.triangles_read, r.degenerate_removed, r.duplicates_removed, r.triangles
    );
    let _ = writeln!(
        s,
        "welding    {:.3} mm: {} vertices merged, {} triangles welded away",
        r.weld_distance, r.vertices_merged, r.triangles_welded_away
    );
    let _ = writeln!(
        s,
        "size       {:.2} × {:.2} × {:.2} mm, from {} to {}",
        size.x,
        size.y,
        size.z,
        v3(r.bounds.min),
        v3(r.bounds.max)
    );
    let _ = writeln!(
        s,
        "model mesh {} open edges, {} non-manifold edges (as given, before welding)",
        r.input_open_edges, r.input_non_manifold_edges
    );
    let _ = writeln!(
        s,
        "health     {}; {} bod{}, {} open edges, {} non-manifold edges, {} flipped faces fixed{} (after welding)",
        if h.closed { "closed" } else { "not closed" },
        h.components,
        if h.components == 1 { "y" } else { "ies" },
        h.open_edges,
        h.non_manifold_edges,
        h.flipped_faces,
        h.volume
            .map(|v| format!("; volume {:.1} cm³", v / 1000.0))
            .unwrap_or_default()
    );
    let _ = writeln!(
        s,
        "surface    {:.1} cm² in {} planar groups, {} planar shapes",
        r.surface_area / 100.0,
        r.planar_groups,
        r.shapes
    );
    if !r.largest_shapes.is_empty() {
        let _ = writeln!(
            s,
            "largest shapes:\n  {:>3}  {:>12}  {:<22} {:>5} {:>8}  at",
            "#", "area mm²", "normal", "holes", "vertices"
        );
        for (i, sh) in r.largest_shapes.iter().enumerate() {
            let _ = writeln!(
                s,
                "  {:>3}  {:>12.2}  {:<22} {:>5} {:>8}  {}",
                i + 1,
                sh.area,
                v3(sh.normal),
                sh.holes,
                sh.vertices,
                v3(sh.at)
            );
        }
    }
    let warnings: Vec<_> = r.warnings().collect();
    if !warnings.is_empty() {
        let _ = writeln!(s, "warnings:");
        for w in warnings {
            let _ = writeln!(s, "  [{}] {}", w.step, w.message);
        }
    }
    let times: Vec<String> = r
        .steps
        .iter()
        .map(|st| format!("{} {:.1}", st.name, st.millis))
        .collect();
    let total: f64 = r.steps.iter().map(|st| st.millis).sum();
    let _ = writeln!(s, "steps (ms) {} · total {:.1}", times.join(" · "), total);
    s
}
