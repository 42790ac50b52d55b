//! `platener inspect`: prints the library's [`platener::inspect::Inspection`].

use std::fmt::Write as _;

use platener::glam::DVec3;
use platener::inspect::{Inspection, PlatesReport, inspect};
use platener::plates::Coverage;
use platener::{Cancel, Source};

use crate::args::InspectArgs;

/// Runs the command.
pub fn run(args: &InspectArgs) -> anyhow::Result<()> {
    let mut settings = args.settings.chosen()?.settings;
    if args.inherent_only {
        settings.plates.mode = platener::PlateMode::InherentOnly;
    }
    let with_plates = args.plates || args.inherent_only;
    let report = inspect(
        Source::File(args.model.clone()),
        settings.clone(),
        &Cancel::default(),
        with_plates,
    )?;
    if args.json {
        println!("{}", serde_json::to_string_pretty(&report)?);
    } else {
        print!("{}", render(&report));
        if let Some(plates) = &report.plates {
            print!("{}", render_plates(plates, &settings.thicknesses));
        }
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
    let _ = writeln!(
        s,
        "print      {} on an FDM printer ({}): {} layers, {:.1} cm³ of plastic",
        crate::report::duration(r.print.seconds),
        platener::fabrication::PRINT_PROFILE,
        r.print.layers,
        r.print.filament_mm3 / 1000.0
    );
    render_largest_shapes(&mut s, r);
    render_warnings_and_steps(&mut s, r);
    s
}

/// How many shapes the coverage table lists (largest first); `--json` has them all.
const COVERAGE_ROWS: usize = 20;

/// The plates and the coverage report.
pub fn render_plates(r: &PlatesReport, offered: &[f64]) -> String {
    let mut s = String::new();
    let c = &r.coverage;
    let inherent = r
        .plates
        .iter()
        .filter(|p| p.kind == platener::plates::PlateKind::Inherent)
        .count();
    let _ = writeln!(
        s,
        "plates     {} ({} inherent, {} extruded); {:.1} % of the surface ({:.1} % inherent); {} contained removed, {} trimmed, {} rejoined",
        r.plates.len(),
        inherent,
        r.plates.len() - inherent,
        100.0 * c.surface_share,
        100.0 * c.inherent_share,
        r.contained_removed,
        r.trimmed,
        r.rejoined
    );
    for t in &c.per_thickness {
        let _ = writeln!(
            s,
            "           {} mm: {} plates, {:.1} % of the surface",
            t.thickness,
            t.plates,
            100.0 * t.surface_share
        );
    }
    render_plate_table(&mut s, r);
    render_coverage(&mut s, c, offered);
    s
}

/// The table of the largest planar shapes, if there are any.
fn render_largest_shapes(s: &mut String, r: &Inspection) {
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
}

/// The warnings and the time each step took.
fn render_warnings_and_steps(s: &mut String, r: &Inspection) {
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
}

/// One row per plate, if there are any.
fn render_plate_table(s: &mut String, r: &PlatesReport) {
    if !r.plates.is_empty() {
        let _ = writeln!(
            s,
            "  {:>3}  {:<9} {:>5}  {:>10} {:>8} {:>5}  {:<26} normal",
            "#", "kind", "t mm", "area mm²", "vertices", "holes", "centre"
        );
        for (i, p) in r.plates.iter().enumerate() {
            let kind = format!("{:?}", p.kind).to_lowercase();
            let _ = writeln!(
                s,
                "  {:>3}  {:<9} {:>5}  {:>10.1} {:>8} {:>5}  {:<26} {}",
                i,
                kind,
                p.thickness,
                p.area,
                p.vertices,
                p.holes,
                v3(p.center),
                v3(p.normal)
            );
        }
    }
}

/// The coverage of the largest planar shapes: which plate each became, or why none.
fn render_coverage(s: &mut String, c: &Coverage, offered: &[f64]) {
    let mut order: Vec<_> = c.shapes.iter().collect();
    order.sort_by(|a, b| b.area.total_cmp(&a.area));
    let _ = writeln!(
        s,
        "coverage of the {} planar shapes (largest {}):",
        c.shapes.len(),
        COVERAGE_ROWS.min(order.len())
    );
    for u in order.iter().take(COVERAGE_ROWS) {
        let what = match (&u.rejected, u.plates.is_empty()) {
            (Some(why), _) => format!("rejected: {}", why.explain(offered)),
            (None, false) => {
                let list = u.plates.iter().map(|k| format!("#{k}")).collect::<Vec<_>>().join(", ");
                let used = 100.0 * u.used_area / u.area.max(f64::MIN_POSITIVE);
                match &u.why_not_inherent {
                    Some(why) => format!(
                        "plate {list}, {used:.0} % used (extruded; not inherent: {})",
                        why.explain(offered)
                    ),
                    None => format!("plate {list}, {used:.0} % used"),
                }
            }
            (None, true) => "unused".into(),
        };
        let _ = writeln!(
            s,
            "  shape {:>5}  {:>10.1} mm²  {}  {}",
            u.shape,
            u.area,
            v3(u.normal),
            what
        );
    }
}
