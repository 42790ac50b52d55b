//! `platener hinge-test` driven through the real binary: the SVG it writes is measured.

use assert_cmd::Command;

mod svg_support;

fn platener() -> Command {
    Command::cargo_bin("platener").expect("binary built")
}

/// The `width`, `height` and viewBox numbers of the SVG's root.
fn size(svg: &str) -> (f64, f64, String) {
    let mm = |name: &str| -> f64 {
        let value = svg_support::root_attribute(svg, name);
        value
            .trim_end_matches("mm")
            .parse()
            .unwrap_or_else(|e| panic!("{name} {value}: {e}"))
    };
    (mm("width"), mm("height"), svg_support::root_attribute(svg, "viewBox"))
}

/// The red open paths (two points each) of the SVG, or of its group `group`: the slits.
fn red_slits(svg: &str, group: Option<&str>) -> Vec<[(f64, f64); 2]> {
    svg_support::paths(svg, group)
        .into_iter()
        .filter(|p| p.stroke == "#ff0000" && !p.closed)
        .map(|p| {
            assert_eq!(p.points.len(), 2, "a slit is one straight cut");
            [p.points[0], p.points[1]]
        })
        .collect()
}

/// Runs `hinge-test ARGS -o out` successfully and returns what it printed.
fn swatch(args: &[&str], out: &std::path::Path) -> String {
    let assert = platener()
        .arg("hinge-test")
        .args(args)
        .arg("-o")
        .arg(out)
        .assert()
        .success();
    String::from_utf8_lossy(&assert.get_output().stdout).to_string()
}

/// The distinct x of `slits` (rows across the strip), ascending.
fn rows(slits: &[[(f64, f64); 2]]) -> Vec<f64> {
    let mut xs: Vec<f64> = slits.iter().map(|s| s[0].0).collect();
    xs.sort_by(f64::total_cmp);
    xs.dedup_by(|a, b| (*a - *b).abs() < 1e-3);
    xs
}

#[test]
fn a_wood_swatch_is_written_at_true_size_with_a_strip_per_pattern() {
    let dir = tempfile::tempdir().expect("temp dir");
    let out = dir.path().join("hinge.svg");
    let stdout = swatch(&["-t", "3", "-m", "wood"], &out);
    assert!(stdout.contains("2 strip(s)"), "{stdout}");
    assert!(stdout.contains("23 links 3.00 × 12.00 mm in 24 rows"), "{stdout}");
    // The straight flex: rows 1.5 mm apart (0.5 t), slits 12 mm with 3 mm bridges, bent at
    // 5 t: 16 pitches of 1.5 mm over a quarter turn, a 15.28 mm radius.
    assert!(stdout.contains("straight pattern"), "{stdout}");
    assert!(
        stdout.contains("zone 24.00 mm wide (flat), neutral radius 15.28 mm"),
        "{stdout}"
    );
    assert!(
        stdout.contains("16 links 1.30 × 4.50 mm in 17 rows of slits 12.00 mm long (bridges 3.00 mm"),
        "{stdout}"
    );
    let svg = std::fs::read_to_string(&out).expect("svg written");
    let (w, h, view) = size(&svg);
    assert_eq!(view, format!("0 0 {w} {h}"));
    // Two 30 mm ends (at least) around a 23 × 3.2 mm zone, 5 mm margins.
    assert!(w >= 10.0 + 60.0 + 73.6 - 1e-9 && h >= 50.0, "{w} × {h}");
    let (lattice, straight) = (red_slits(&svg, Some("part-1")), red_slits(&svg, Some("part-2")));
    assert!(lattice.len() > 48, "{} slits", lattice.len());
    // Slits run across the strip (vertical), inside it, on 24 distinct rows 3.2 mm apart.
    let xs = rows(&lattice);
    assert_eq!(xs.len(), 24);
    assert!(xs.windows(2).all(|p| (p[1] - p[0] - 3.2).abs() < 1e-3));
    for s in lattice.iter().chain(&straight) {
        assert!((s[0].0 - s[1].0).abs() < 1e-9);
        assert!(s.iter().all(|p| p.1 > 5.0 && p.1 < h - 5.0));
    }
    // The flex strip lies below the lattice's, its 17 rows 1.5 mm apart.
    let xs = rows(&straight);
    assert_eq!(xs.len(), 17);
    assert!(xs.windows(2).all(|p| (p[1] - p[0] - 1.5).abs() < 1e-3));
    let lowest_lattice = lattice.iter().flat_map(|s| [s[0].1, s[1].1]).fold(f64::MIN, f64::max);
    assert!(straight.iter().all(|s| s[0].1.min(s[1].1) > lowest_lattice));
    let blue = svg_support::paths(&svg, None)
        .iter()
        .filter(|p| p.stroke == "#0000ff")
        .count();
    assert!(blue > 0, "engraved legend");
}

#[test]
fn a_card_swatch_takes_the_material_style() {
    let dir = tempfile::tempdir().expect("temp dir");
    let out = dir.path().join("card.svg");
    let stdout = swatch(&["-t", "1.5", "-m", "cardboard", "--angle", "60"], &out);
    assert!(stdout.contains("a perforation bend of 60.0°"), "{stdout}");
    let svg = std::fs::read_to_string(&out).expect("svg written");
    let dashes = red_slits(&svg, None);
    assert!(dashes.len() >= 5 && dashes.iter().all(|s| (s[0].0 - dashes[0][0].0).abs() < 1e-9));
}

#[test]
fn bad_thickness_style_or_material_is_refused() {
    let dir = tempfile::tempdir().expect("temp dir");
    let out = dir.path().join("never.svg");
    let refused = |args: &[&str], message: &str| {
        let assert = platener()
            .arg("hinge-test")
            .args(args)
            .arg("-o")
            .arg(&out)
            .assert()
            .code(1);
        let stderr = String::from_utf8_lossy(&assert.get_output().stderr).to_string();
        assert!(stderr.contains(message), "{stderr}");
    };
    refused(&["--thickness=-3"], "thickness must be a positive finite number");
    refused(
        &["-t", "3", "-m", "wood", "--bend", "heat"],
        "a heat bend does not work in 3 mm wood",
    );
    refused(&["-t", "3", "--angle", "200"], "turns at most 180.0°");
    platener()
        .args(["hinge-test", "-t", "3", "-m", "stone", "-o"])
        .arg(&out)
        .assert()
        .code(2);
    assert!(!out.exists());
}
