//! `platener verify`: reads a cutting plan (and the model), prints what the library measured.

use std::fmt::Write as _;

use anyhow::Context;
use platener::verify::{Verification, model_weld, plan_from_zip, source_mismatch, verify_with};
use platener::{Cancel, Source};

use crate::args::VerifyArgs;

/// Runs the command; exit code 0 when every check passed, 1 otherwise.
pub fn run(args: &VerifyArgs) -> anyhow::Result<u8> {
    let bytes = std::fs::read(&args.plan).with_context(|| format!("cannot read {}", args.plan.display()))?;
    let plan = plan_from_zip(&bytes).map_err(|e| anyhow::anyhow!("{}: {e}", args.plan.display()))?;
    let state = match &args.model {
        Some(path) => {
            // Measured against the mesh convert judged the plan on: the model welded as the plan records.
            let settings = platener::Settings {
                weld: model_weld(&plan),
                ..args.settings.chosen()?.settings
            };
            let (state, _) =
                platener::inspect::run_foundation(Source::File(path.clone()), settings, &Cancel::default())?;
            Some(state)
        }
        None => None,
    };
    let mesh = state.as_ref().and_then(|s| s.mesh.as_deref());
    let mut v = verify_with(&plan, mesh, args.min_coverage / 100.0);
    if let Some(model) = state.as_ref().and_then(|s| s.read.as_deref()) {
        v.warnings.extend(source_mismatch(&plan, model));
    }
    if args.json {
        println!("{}", serde_json::to_string_pretty(&v)?);
    } else {
        print!("{}", render(&v));
    }
    Ok(if v.passed() { 0 } else { 1 })
}

fn render(v: &Verification) -> String {
    let mut s = String::new();
    let _ = writeln!(
        s,
        "parts      {} ({:.1} cm³), sampled every {:.2} mm",
        v.parts,
        v.parts_volume / 1000.0,
        v.step
    );
    let _ = writeln!(
        s,
        "interference {:.3} % of the parts' volume{}",
        100.0 * v.interference_share,
        v.interference
            .first()
            .map(|i| format!(" (most: parts {} and {}, {:.1} mm³)", i.parts[0], i.parts[1], i.volume))
            .unwrap_or_default()
    );
    let _ = writeln!(
        s,
        "assembly   {} group{} held together by the joints{}",
        v.groups,
        if v.groups == 1 { "" } else { "s" },
        v.model_solids
            .map(|m| format!("; the model has {m} solid{}", if m == 1 { "" } else { "s" }))
            .unwrap_or_default()
    );
    let _ = writeln!(s, "edges      {}", edges(&v.mismatched_edges));
    if let (Some(c), Some(i)) = (v.surface_covered, v.volume_inside) {
        let _ = writeln!(
            s,
            "model      {:.1} % of its surface within {:.1} mm of a part; {:.1} % of the parts' volume inside it",
            100.0 * c,
            v.cover_distance,
            100.0 * i
        );
    }
    for w in &v.warnings {
        let _ = writeln!(s, "WARNING: {w}");
    }
    if v.passed() {
        let _ = writeln!(s, "passed");
    } else {
        for p in &v.problems {
            let _ = writeln!(s, "FAILED: {p}");
        }
    }
    s
}

/// Pairs of joints named on the `edges` line, at most.
const NAMED_PAIRS: usize = 6;

/// The `edges` line: how many pairs of non-partner edges fit each other (a wrong assembly
/// that goes together), naming the first ones; reported, never a failure.
fn edges(m: &platener::verify::MismatchReport) -> String {
    let twins = match m.interchangeable_pairs {
        0 => String::new(),
        n => format!("; {n} between interchangeable parts (harmless)"),
    };
    if m.accepting_pairs == 0 {
        return format!(
            "every finger-joint edge fits only its partner ({} joint{} read){twins}",
            m.joints_read,
            if m.joints_read == 1 { "" } else { "s" }
        );
    }
    let named: Vec<String> = m
        .pairs
        .iter()
        .take(NAMED_PAIRS)
        .map(|p| {
            let turned = if p.reversed { ", turned round" } else { "" };
            format!(
                "joints {} and {} (parts {} and {}{turned})",
                p.joints[0], p.joints[1], p.parts[0], p.parts[1]
            )
        })
        .collect();
    let more = m.accepting_pairs.saturating_sub(NAMED_PAIRS);
    format!(
        "{} pair{} of edges of different joints fit each other: {}{}{twins}",
        m.accepting_pairs,
        if m.accepting_pairs == 1 { "" } else { "s" },
        named.join(", "),
        if more > 0 {
            format!(" and {more} more")
        } else {
            String::new()
        }
    )
}
