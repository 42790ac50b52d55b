//! `platener test-strip` driven through the real binary: the SVG it writes is measured.

use assert_cmd::Command;

mod svg_support;

fn platener() -> Command {
    Command::cargo_bin("platener").expect("binary built")
}

/// Widths are written with 4 decimals: exact to 1e-4 mm.
const WIDTH_TOL: f64 = 1e-4;

/// The points of the red paths of `<g id="{group}">`, in file order.
fn red_rings(svg: &str, group: &str) -> Vec<Vec<(f64, f64)>> {
    svg_support::paths(svg, Some(group))
        .into_iter()
        .filter(|p| p.stroke == "#ff0000")
        .map(|p| p.points)
        .collect()
}

fn x_extent(ring: &[(f64, f64)]) -> (f64, f64) {
    let lo = ring.iter().map(|p| p.0).fold(f64::INFINITY, f64::min);
    let hi = ring.iter().map(|p| p.0).fold(f64::NEG_INFINITY, f64::max);
    (lo, hi)
}

#[test]
fn the_strip_is_written_at_true_size_with_exact_hole_widths() {
    let dir = tempfile::tempdir().expect("temp dir");
    let path = dir.path().join("strip.svg");
    let out = platener()
        .args(["test-strip", "-t", "3", "--material", "wood", "-o"])
        .arg(&path)
        .output()
        .expect("runs");
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let stdout = String::from_utf8(out.stdout).expect("utf-8");
    assert!(stdout.contains("   9     5.600    0.200  * wood default"), "{stdout}");
    let svg = std::fs::read_to_string(&path).expect("written");
    assert!(svg.contains("mm\" height=\"") && svg.contains("viewBox=\"0 0 "));
    let strip = red_rings(&svg, "part-1");
    // The 17 kerf holes first, then the 17 slots of the slot row, the outline last (cut order).
    assert_eq!(strip.len(), 17 + 17 + 1);
    let mut holes: Vec<(f64, f64)> = strip[..17].iter().map(|r| x_extent(r)).collect();
    holes.sort_by(|a, b| a.0.total_cmp(&b.0));
    // Slot k fits sheets 2.6 + 0.05·k mm thick with the wood's 0.2 mm kerf: drawn 0.2 narrower.
    for (k, slot) in strip[17..34].iter().enumerate() {
        let (lo, hi) = x_extent(slot);
        let sheet = 2.6 + 0.05 * k as f64;
        assert!(((hi - lo) - (sheet - 0.2)).abs() < WIDTH_TOL, "slot {k}: {}", hi - lo);
    }
    assert!(
        stdout.contains("2.60–3.40 mm") && stdout.contains("thickness 3@"),
        "{stdout}"
    );
    for (i, (lo, hi)) in holes.iter().enumerate() {
        // The documented mapping: hole n stands for kerf (n − 1) × 0.025 mm, width 6 − 2·kerf.
        let kerf = 0.025 * i as f64;
        assert!(
            ((hi - lo) - (6.0 - 2.0 * kerf)).abs() < WIDTH_TOL,
            "hole {}: {}",
            i + 1,
            hi - lo
        );
    }
    let spike = &red_rings(&svg, "part-2")[0];
    let max_y = spike.iter().map(|p| p.1).fold(f64::NEG_INFINITY, f64::max);
    let tip: Vec<f64> = spike
        .iter()
        .filter(|p| (p.1 - max_y).abs() < WIDTH_TOL)
        .map(|p| p.0)
        .collect();
    assert_eq!(tip.len(), 2);
    assert!(((tip[0] - tip[1]).abs() - 6.0).abs() < WIDTH_TOL);
}

#[test]
fn a_bad_thickness_is_refused() {
    let dir = tempfile::tempdir().expect("temp dir");
    let out = platener()
        .args(["test-strip", "-t", "0", "-o"])
        .arg(dir.path().join("s.svg"))
        .output()
        .expect("runs");
    assert_eq!(out.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&out.stderr).contains("thickness"));
    let usage = platener().args(["test-strip", "-o", "x.svg"]).output().expect("runs");
    assert_eq!(usage.status.code(), Some(2), "-t is required");
}
