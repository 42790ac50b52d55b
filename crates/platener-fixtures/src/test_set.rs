//! The debug view's test set: small labelled models, each exercising one part of the pipeline.

use crate::samples as s;

/// One model of the debug view's test set.
#[derive(Debug, Clone)]
pub struct TestModel {
    /// A name for URLs and files (letters, digits, `-`).
    pub name: &'static str,
    /// What it is and what it exercises.
    pub label: &'static str,
    /// Its triangles, in mm.
    pub triangles: Vec<platener_geom::Triangle>,
}

/// Small labelled models from [`crate::samples`], each exercising one part of the pipeline,
/// for the debug view's isolated steps (the shipped examples come on top of these).
pub fn test_set() -> Vec<TestModel> {
    let model = |name, label, triangles| TestModel { name, label, triangles };
    vec![
        model(
            "closed-box",
            "closed box 100x80x60, 3 mm walls: 6 plates, 12 corner joints",
            s::closed_box(100.0, 80.0, 60.0, 3.0),
        ),
        model(
            "tray",
            "open tray 120x80x40, 3 mm walls: 5 plates",
            s::open_box(120.0, 80.0, 40.0, 3.0),
        ),
        model(
            "shelf",
            "shelf (H profile): tee joints, tabs and slots",
            s::shelf(80.0, 120.0, 50.0, 60.0, 3.0),
        ),
        model(
            "crossing-plates",
            "two plates crossing: a halved joint",
            s::crossing_plates(100.0, 3.0),
        ),
        model(
            "roof",
            "gable roof at 40 degrees: a mitred ridge",
            s::roof(50.0, 40.0, 80.0, 3.0),
        ),
        model("star", "three arms meeting on one line", s::star(3, 40.0, 3.0, 50.0)),
        model(
            "table",
            "table: a top on two leg panels",
            s::table(120.0, 60.0, 70.0, 10.0, 3.0),
        ),
        model("phone-stand", "phone stand, back at 65 degrees", s::phone_stand()),
        model(
            "solid-block",
            "solid block 60x40x30: extruded plates only (empty with inherent only)",
            s::cuboid(glam::DVec3::ZERO, glam::DVec3::new(60.0, 40.0, 30.0)),
        ),
        model(
            "rounded-box",
            "rounded box: curved faces for weld and coplanar",
            s::rounded_box(glam::DVec3::new(60.0, 40.0, 30.0), 5.0, 8),
        ),
        model(
            "two-bodies",
            "sphere and torus: the stacked method's layers",
            s::two_bodies(10.0),
        ),
        model(
            "textured-box",
            "hollow box 60x40x30, 3 mm walls, 0.5 mm bumps outside: the classifier's 12 planes",
            s::textured_box(glam::DVec3::new(60.0, 40.0, 30.0), 3.0, 0.5, 10.0),
        ),
    ]
}
