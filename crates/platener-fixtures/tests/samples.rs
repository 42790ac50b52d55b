//! The generated samples are what their names promise: closed, wound outwards, and the
//! shipped example files are what the generators write.

use glam::DVec3;
use platener::mesh::Mesh;
use platener::weld::weld_soup;
use platener_fixtures::samples::{phone_stand, rounded_box, shipped_examples, to_binary_stl};

#[test]
fn generated_samples_are_closed_and_wound_outwards() {
    for (name, _, tris) in shipped_examples() {
        let w = weld_soup(&tris, 0.0);
        let m = Mesh::build(w.vertices, &w.triangles, 1e-9);
        assert!(m.health.closed, "{name}");
        assert_eq!(m.health.flipped_faces, 0, "{name}");
    }
    let rb = rounded_box(DVec3::new(40.0, 30.0, 20.0), 4.0, 12);
    assert_eq!(rb.len(), 12 * 12 * 12);
}

#[test]
fn shipped_example_files_match_their_generators() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples");
    for (name, header, tris) in shipped_examples() {
        let on_disk = std::fs::read(dir.join(name)).expect("examples/ is part of the repository");
        assert!(
            on_disk == to_binary_stl(&tris, header),
            "examples/{name} is stale: run `cargo run -p platener --example make_examples`"
        );
    }
}

#[test]
fn phone_stand_back_plate_leans_at_65_degrees() {
    let tris = phone_stand();
    let w = weld_soup(&tris, 0.0);
    let m = Mesh::build(w.vertices, &w.triangles, 1e-9);
    let expect = DVec3::new(-(65f64.to_radians().sin()), 0.0, 65f64.to_radians().cos());
    assert!(
        m.normals.iter().any(|n| (n.dot(expect) - 1.0).abs() < 1e-12),
        "front face of the back plate"
    );
    // 85×3 base + lip 3×9 + back plate 90×3: cross-section area × width.
    let volume = (85.0 * 3.0 + 3.0 * 9.0 + 90.0 * 3.0) * 70.0;
    assert!((m.health.volume.expect("closed") - volume).abs() < 1e-6);
}
