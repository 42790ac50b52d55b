//! Issue 20's acceptance for detection: on boxes, tubes, spheres and cone frustums, finely
//! meshed, roughened by 0, 0.1, 0.25 and 0.5 mm of noise and moved by random rigid motions,
//! at least 95 % of the primitives are found with their parameters within tolerance (plane
//! normals 0.5°, radii 2 %) and no primitive matching nothing holds more than 2 % of the
//! surface. Deterministic: every set and run is seeded.

use platener::classify::{self, ClassifySettings, testsets};

/// Classifies the standard sets at `noise` for three motions; (found, total, phantoms).
fn tally(noise: f64) -> (usize, usize, usize) {
    let mut t = (0, 0, 0);
    for seed in 0..3 {
        let sets = testsets::standard(noise, seed);
        assert_eq!(sets.len(), 4);
        for set in sets {
            assert!(set.mesh.triangles.len() > 10_000, "{} is not a fine mesh", set.name);
            let c = classify::run(&set.mesh, &ClassifySettings::default()).expect("classifies");
            let s = testsets::accuracy(&set, &c);
            assert!(
                s.worst_angle_deg <= 0.5 && s.worst_radius_rel <= 0.02,
                "{}: {s:?}",
                set.name
            );
            t = (t.0 + s.found, t.1 + s.total, t.2 + s.phantoms);
        }
    }
    // 6 + 4 + 1 + 3 primitives per motion.
    assert_eq!(t.1, 3 * 14);
    t
}

fn check(noise: f64) {
    let (found, total, phantoms) = tally(noise);
    assert!(
        found as f64 >= 0.95 * total as f64,
        "noise {noise}: found {found} of {total}"
    );
    assert_eq!(phantoms, 0, "noise {noise}");
}

#[test]
fn clean_meshes() {
    check(0.0);
}

#[test]
fn noise_0_1_mm() {
    check(0.1);
}

#[test]
fn noise_0_25_mm() {
    check(0.25);
}

#[test]
fn noise_0_5_mm() {
    check(0.5);
}

/// The score itself can fail: a shifted truth is not matched, a wrong detection is a phantom.
#[test]
fn score_notices_wrong_answers() {
    let mut set = testsets::standard(0.0, 0).swap_remove(0);
    let c = classify::run(&set.mesh, &ClassifySettings::default()).expect("classifies");
    assert_eq!(testsets::accuracy(&set, &c).found, 6);
    for t in &mut set.truth {
        if let classify::Surface::Plane { offset, .. } = t {
            *offset += 5.0;
        }
    }
    let s = testsets::accuracy(&set, &c);
    assert_eq!((s.found, s.phantoms), (0, 6));
}

/// A texture as deep as the mesh is fine (0.5 mm on 0.5 mm quads, 300k triangles): triangle
/// normals point anywhere, the neighbourhood normals still find the six walls and the box.
#[test]
fn fine_deep_texture_still_gives_the_box() {
    let (soup, truth) = testsets::fine_box(platener::glam::DVec3::new(100.0, 80.0, 60.0), 0.5);
    let (mesh, rot, shift) = testsets::roughen_and_move(&soup, 0.5, 11);
    assert!(mesh.triangles.len() > 290_000);
    let c = classify::run(&mesh, &ClassifySettings::default()).expect("classifies");
    let truth: Vec<_> = truth.iter().map(|s| testsets::moved(s, rot, shift)).collect();
    let set = testsets::TestSet {
        name: "deep texture".into(),
        mesh,
        truth,
    };
    let s = testsets::accuracy(&set, &c);
    assert_eq!((s.found, s.phantoms), (6, 0), "{s:?}");
    assert_eq!(c.primitives.len(), 6);
    assert_eq!(c.volumes.len(), 1);
    assert_eq!(c.volumes[0].kind, classify::VolumeKind::Box);
}
