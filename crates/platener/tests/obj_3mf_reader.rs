//! OBJ and 3MF readers, called through `platener::read::read_file` so the dispatcher is covered.
//!
//! Files are written to a temporary directory: OBJ as text, 3MF as hand-zipped XML (so each case
//! says exactly what the file holds) and once through `threemf`'s own writer.

use std::io::{Cursor, Write};
use std::path::PathBuf;

use glam::DVec3;
use platener::read::{Format, RawMesh, ReadError, ReadErrorKind, Triangle, read_file};
use tempfile::TempDir;

// ---------------------------------------------------------------------------------------------
// helpers

/// A temporary directory holding one file `name` with `contents`.
fn file(name: &str, contents: &[u8]) -> (TempDir, PathBuf) {
    let dir = tempfile::tempdir().expect("temporary directory");
    let path = dir.path().join(name);
    std::fs::write(&path, contents).expect("write test file");
    (dir, path)
}

/// Reads `contents` saved as `name`.
fn read(name: &str, contents: &[u8]) -> Result<(Format, RawMesh), ReadError> {
    let (_dir, path) = file(name, contents);
    read_file(&path)
}

/// Reads a file that must be fine.
fn read_ok(name: &str, contents: &[u8]) -> (Format, RawMesh) {
    read(name, contents).unwrap_or_else(|e| panic!("{name} should read: {e}"))
}

/// The error kind of a file that must fail.
fn read_err(name: &str, contents: &[u8]) -> ReadErrorKind {
    match read(name, contents) {
        Ok((_, mesh)) => panic!("{name} should fail, read {} triangles", mesh.triangles.len()),
        Err(e) => e.kind,
    }
}

/// The message of an `Obj(..)` or `ThreeMf(..)` error.
fn message(kind: &ReadErrorKind) -> &str {
    match kind {
        ReadErrorKind::Obj(m) | ReadErrorKind::ThreeMf(m) => m,
        other => panic!("expected an OBJ or 3MF error, got {other:?}"),
    }
}

fn v(x: f64, y: f64, z: f64) -> DVec3 {
    DVec3::new(x, y, z)
}

fn area(triangles: &[Triangle]) -> f64 {
    triangles
        .iter()
        .map(|[a, b, c]| (*b - *a).cross(*c - *a).length() / 2.0)
        .sum()
}

/// Signed volume (positive when the windings' normals point outwards).
fn volume(triangles: &[Triangle]) -> f64 {
    triangles.iter().map(|[a, b, c]| a.dot(b.cross(*c)) / 6.0).sum()
}

// ---------------------------------------------------------------------------------------------
// OBJ

/// A 2 x 3 x 4 box with quad faces wound outwards.
const BOX_OBJ: &str = "\
# box 2 x 3 x 4
mtllib box.mtl
o box
v 0 0 0
v 2 0 0
v 2 3 0
v 0 3 0
v 0 0 4
v 2 0 4
v 2 3 4
v 0 3 4
vn 0 0 -1
usemtl grey
s off
f 1//1 4//1 3//1 2//1
f 5 6 7 8
f 1 2 6 5
f 2 3 7 6
f 3 4 8 7
f 4 1 5 8
";

#[test]
fn obj_quad_box_gives_twelve_exact_triangles() {
    let (format, mesh) = read_ok("box.obj", BOX_OBJ.as_bytes());
    assert_eq!(format, Format::Obj);
    assert_eq!(mesh.solids, 1);
    let corners = [
        v(0.0, 0.0, 0.0),
        v(2.0, 0.0, 0.0),
        v(2.0, 3.0, 0.0),
        v(0.0, 3.0, 0.0),
        v(0.0, 0.0, 4.0),
        v(2.0, 0.0, 4.0),
        v(2.0, 3.0, 4.0),
        v(0.0, 3.0, 4.0),
    ];
    // Each quad a b c d becomes (a b c) and (a c d).
    let quads = [
        [1, 4, 3, 2],
        [5, 6, 7, 8],
        [1, 2, 6, 5],
        [2, 3, 7, 6],
        [3, 4, 8, 7],
        [4, 1, 5, 8],
    ];
    let at = |i: usize| corners[i - 1];
    let expected: Vec<Triangle> = quads
        .iter()
        .flat_map(|&[a, b, c, d]| [[at(a), at(b), at(c)], [at(a), at(c), at(d)]])
        .collect();
    assert_eq!(mesh.triangles.len(), 12);
    assert_eq!(mesh.triangles, expected);
    assert_eq!(area(&mesh.triangles), 2.0 * (6.0 + 8.0 + 12.0));
    assert_eq!(volume(&mesh.triangles), 24.0);
}

#[test]
fn obj_missing_mtl_is_tolerated() {
    // BOX_OBJ names box.mtl and material "grey"; neither exists.
    let (_dir, path) = file("box.obj", BOX_OBJ.as_bytes());
    assert!(!path.with_extension("mtl").exists());
    let (_, mesh) = read_file(&path).expect("a missing .mtl must not fail the read");
    assert_eq!(mesh.triangles.len(), 12);
}

#[test]
fn obj_two_objects_are_two_solids() {
    let text = "\
o first
v 0 0 0
v 1 0 0
v 0 1 0
f 1 2 3
o second
v 5 0 0
v 6 0 0
v 5 1 0
usemtl red
f 4 5 6
";
    let (_, mesh) = read_ok("two.obj", text.as_bytes());
    assert_eq!(mesh.solids, 2);
    assert_eq!(
        mesh.triangles,
        vec![
            [v(0.0, 0.0, 0.0), v(1.0, 0.0, 0.0), v(0.0, 1.0, 0.0)],
            [v(5.0, 0.0, 0.0), v(6.0, 0.0, 0.0), v(5.0, 1.0, 0.0)],
        ]
    );
}

#[test]
fn obj_negative_indices_are_relative() {
    let text = "\
v 0 0 0
v 1 0 0
v 0 1 0
f -3 -2 -1
v 0 0 1
f -4/-1 -2 -1
";
    let (_, mesh) = read_ok("relative.obj", text.as_bytes());
    assert_eq!(
        mesh.triangles,
        vec![
            [v(0.0, 0.0, 0.0), v(1.0, 0.0, 0.0), v(0.0, 1.0, 0.0)],
            [v(0.0, 0.0, 0.0), v(0.0, 1.0, 0.0), v(0.0, 0.0, 1.0)],
        ]
    );
}

#[test]
fn obj_index_out_of_range_is_an_error_naming_the_line() {
    let text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n";
    let kind = read_err("bad.obj", text.as_bytes());
    let m = message(&kind);
    assert!(m.contains("line 4") && m.contains("vertex 9"), "{m}");

    let text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf -4 -2 -1\n";
    let kind = read_err("bad.obj", text.as_bytes());
    let m = message(&kind);
    assert!(m.contains("line 4") && m.contains("vertex -4"), "{m}");

    let text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n";
    let kind = read_err("bad.obj", text.as_bytes());
    assert!(message(&kind).contains("index 0"), "{kind}");

    let text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 x\n";
    let kind = read_err("bad.obj", text.as_bytes());
    assert!(message(&kind).contains("line 4"), "{kind}");

    // A huge index must be an error, not an overflow.
    let text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 -9223372036854775808\n";
    assert!(matches!(read_err("bad.obj", text.as_bytes()), ReadErrorKind::Obj(_)));
}

#[test]
fn obj_bad_texture_and_normal_indices_do_not_matter() {
    // Only positions are read; tobj would overflow on the absurd texture index.
    let text = "\
v 0 0 0
v 1 0 0
v 0 1 0
vt 0 0
f 1/-9223372036854775807/5 2/99/5 3/1/5
";
    let (_, mesh) = read_ok("uv.obj", text.as_bytes());
    assert_eq!(mesh.triangles.len(), 1);
}

#[test]
fn obj_nan_is_an_error_naming_the_line() {
    let text = "v 0 0 0\nv 1 nan 0\nv 0 1 0\nf 1 2 3\n";
    assert_eq!(
        read_err("nan.obj", text.as_bytes()),
        ReadErrorKind::NonFinite {
            location: "line 2".into(),
            value: "nan".into()
        }
    );
    let text = "v 0 0 0\nv 1 0 inf\nv 0 1 0\nf 1 2 3\n";
    assert!(matches!(
        read_err("inf.obj", text.as_bytes()),
        ReadErrorKind::NonFinite { .. }
    ));
}

#[test]
fn obj_coordinate_too_large_for_tobj_is_an_error_naming_the_triangle() {
    // Finite as f64 but infinite once tobj (f32 by default) has stored it.
    let text = "o big\nv 0 0 0\nv 1e39 0 0\nv 0 1 0\nf 1 2 3\n";
    match read("big.obj", text.as_bytes()) {
        // tobj built with `use_f64` keeps the value.
        Ok((_, mesh)) => assert_eq!(mesh.triangles[0][1].x, 1e39),
        Err(e) => match e.kind {
            ReadErrorKind::NonFinite { location, .. } => {
                assert!(
                    location.contains("big") && location.contains("triangle 0"),
                    "{location}"
                );
            }
            other => panic!("expected NonFinite, got {other:?}"),
        },
    }
}

#[test]
fn obj_empty_has_no_triangles() {
    for text in [
        "",
        "# only a comment\n",
        "v 0 0 0\nv 1 0 0\nv 0 1 0\n",
        "v 0 0 0\nf 1 1\n",
    ] {
        assert_eq!(
            read_err("empty.obj", text.as_bytes()),
            ReadErrorKind::NoTriangles,
            "{text:?}"
        );
    }
}

#[test]
fn obj_polygon_is_fan_triangulated_and_noted() {
    let text = "\
V_IGNORED
v 0 0 0
v 2 0 0
v 3 1 0
v 1 2 0
v -1 1 0
f 1 2 3 4 5
l 1 2
";
    let (_, mesh) = read_ok("pentagon.OBJ", text.as_bytes());
    assert_eq!(mesh.triangles.len(), 3);
    assert_eq!(
        mesh.triangles[2],
        [v(0.0, 0.0, 0.0), v(1.0, 2.0, 0.0), v(-1.0, 1.0, 0.0)]
    );
    assert!(
        mesh.notes.iter().any(|n| n.contains("five or more corners")),
        "{:?}",
        mesh.notes
    );
}

#[test]
fn obj_vertex_weight_and_colour() {
    let text = "v 2 4 6 2\nv 1 0 0 0.5 0.5 0.5\nv 0 1 0\nf 1 2 3\n";
    let (_, mesh) = read_ok("weights.obj", text.as_bytes());
    assert_eq!(
        mesh.triangles,
        vec![[v(1.0, 2.0, 3.0), v(1.0, 0.0, 0.0), v(0.0, 1.0, 0.0)]]
    );

    let kind = read_err("weights.obj", b"v 1 2 3 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    assert!(message(&kind).contains("line 1"), "{kind}");
}

// ---------------------------------------------------------------------------------------------
// 3MF

const CORE_NS: &str = "http://schemas.microsoft.com/3dmanufacturing/core/2015/02";
const PRODUCTION_NS: &str = "http://schemas.microsoft.com/3dmanufacturing/production/2015/06";

/// A `<model>` document.
fn model(unit: &str, resources: &str, build: &str) -> String {
    format!(
        r#"<?xml version="1.0" encoding="UTF-8"?>
<model unit="{unit}" xml:lang="en-US" xmlns="{CORE_NS}" xmlns:p="{PRODUCTION_NS}">
 <metadata name="Application">platener tests</metadata>
 <resources>
{resources}
 </resources>
 <build>
{build}
 </build>
</model>
"#
    )
}

/// An `<object>` with a mesh.
fn mesh_object(id: usize, vertices: &[[f64; 3]], triangles: &[[usize; 3]]) -> String {
    let vertices: String = vertices
        .iter()
        .map(|[x, y, z]| format!("     <vertex x=\"{x}\" y=\"{y}\" z=\"{z}\"/>\n"))
        .collect();
    let triangles: String = triangles
        .iter()
        .map(|[a, b, c]| format!("     <triangle v1=\"{a}\" v2=\"{b}\" v3=\"{c}\"/>\n"))
        .collect();
    format!(
        "  <object id=\"{id}\" name=\"part {id}\" type=\"model\">\n   <mesh>\n    <vertices>\n\
         {vertices}    </vertices>\n    <triangles>\n{triangles}    </triangles>\n   </mesh>\n  </object>"
    )
}

/// An `<object>` made of components `(object id, transform)`.
fn component_object(id: usize, components: &[(usize, Option<&str>)]) -> String {
    let components: String = components
        .iter()
        .map(|(objectid, transform)| match transform {
            Some(t) => format!("    <component objectid=\"{objectid}\" transform=\"{t}\"/>\n"),
            None => format!("    <component objectid=\"{objectid}\"/>\n"),
        })
        .collect();
    format!("  <object id=\"{id}\" type=\"model\">\n   <components>\n{components}   </components>\n  </object>")
}

/// A build `<item>`.
fn item(objectid: usize, transform: Option<&str>) -> String {
    match transform {
        Some(t) => format!("  <item objectid=\"{objectid}\" transform=\"{t}\"/>"),
        None => format!("  <item objectid=\"{objectid}\"/>"),
    }
}

/// A 3MF archive whose root model part is `3D/3dmodel.model`, plus `extra` parts.
fn archive(root_model: &str, extra: &[(&str, &str)]) -> Vec<u8> {
    let mut zip = zip::ZipWriter::new(Cursor::new(Vec::new()));
    let options = zip::write::SimpleFileOptions::default();
    let content_types = r#"<?xml version="1.0" encoding="UTF-8"?>
<Types xmlns="http://schemas.openxmlformats.org/package/2006/content-types">
 <Default Extension="rels" ContentType="application/vnd.openxmlformats-package.relationships+xml"/>
 <Default Extension="model" ContentType="application/vnd.ms-package.3dmanufacturing-3dmodel+xml"/>
</Types>
"#;
    let rels = r#"<?xml version="1.0" encoding="UTF-8"?>
<Relationships xmlns="http://schemas.openxmlformats.org/package/2006/relationships">
 <Relationship Target="/3D/3dmodel.model" Id="rel0" Type="http://schemas.microsoft.com/3dmanufacturing/2013/01/3dmodel"/>
</Relationships>
"#;
    let parts = [
        ("[Content_Types].xml", content_types),
        ("_rels/.rels", rels),
        ("3D/3dmodel.model", root_model),
    ];
    for (name, text) in parts.iter().chain(extra) {
        zip.start_file(*name, options).expect("zip entry");
        zip.write_all(text.as_bytes()).expect("zip write");
    }
    zip.finish().expect("zip finish").into_inner()
}

/// One right triangle with legs 1, 2 and 3 along x, y and z.
fn corner_object(id: usize) -> String {
    mesh_object(id, &[[1.0, 0.0, 0.0], [0.0, 2.0, 0.0], [0.0, 0.0, 3.0]], &[[0, 1, 2]])
}

/// Translation by (x, y, z) in 3MF's row-vector layout.
fn translate(x: f64, y: f64, z: f64) -> String {
    format!("1 0 0 0 1 0 0 0 1 {x} {y} {z}")
}

/// 90° about +z (x → y, y → -x), then translation by (x, y, z).
fn rotate_z_then_translate(x: f64, y: f64, z: f64) -> String {
    format!("0 1 0 -1 0 0 0 0 1 {x} {y} {z}")
}

#[test]
fn threemf_one_object_in_two_build_items_with_their_transforms() {
    let shift = translate(10.0, 20.0, 30.0);
    let turn = rotate_z_then_translate(5.0, 0.0, 0.0);
    let build = [item(1, Some(&shift)), item(1, Some(&turn))].join("\n");
    let bytes = archive(&model("millimeter", &corner_object(1), &build), &[]);
    let (format, mesh) = read_ok("two.3mf", &bytes);
    assert_eq!(format, Format::ThreeMf);
    assert_eq!(mesh.solids, 2);
    assert_eq!(
        mesh.triangles,
        vec![
            [v(11.0, 20.0, 30.0), v(10.0, 22.0, 30.0), v(10.0, 20.0, 33.0)],
            // (1,0,0) → (0,1,0), (0,2,0) → (-2,0,0), (0,0,3) stays; then + (5,0,0).
            [v(5.0, 1.0, 0.0), v(3.0, 0.0, 0.0), v(5.0, 0.0, 3.0)],
        ]
    );
    assert!(mesh.notes.is_empty(), "{:?}", mesh.notes);
}

#[test]
fn threemf_components_compose_component_then_item_transform() {
    // Object 2 = object 1 turned 90° about z, plus object 1 moved by (0, 0, 100); the build item
    // then moves object 2 by (10, 0, 0). Applying the item before the component would give
    // different coordinates for the turned copy.
    let turn = rotate_z_then_translate(0.0, 0.0, 0.0);
    let lift = translate(0.0, 0.0, 100.0);
    let resources = [
        corner_object(1),
        component_object(2, &[(1, Some(&turn)), (1, Some(&lift))]),
    ]
    .join("\n");
    let shift = translate(10.0, 0.0, 0.0);
    let bytes = archive(&model("millimeter", &resources, &item(2, Some(&shift))), &[]);
    let (_, mesh) = read_ok("assembly.3mf", &bytes);
    assert_eq!(mesh.solids, 1);
    assert_eq!(
        mesh.triangles,
        vec![
            [v(10.0, 1.0, 0.0), v(8.0, 0.0, 0.0), v(10.0, 0.0, 3.0)],
            [v(11.0, 0.0, 100.0), v(10.0, 2.0, 100.0), v(10.0, 0.0, 103.0)],
        ]
    );
}

#[test]
fn threemf_nested_components_without_transforms() {
    let resources = [
        corner_object(7),
        component_object(8, &[(7, None)]),
        component_object(9, &[(8, None), (7, Some(&translate(1.0, 1.0, 1.0)))]),
    ]
    .join("\n");
    let bytes = archive(&model("millimeter", &resources, &item(9, None)), &[]);
    let (_, mesh) = read_ok("nested.3mf", &bytes);
    assert_eq!(mesh.triangles.len(), 2);
    assert_eq!(mesh.triangles[1][0], v(2.0, 1.0, 1.0));
}

#[test]
fn threemf_inch_is_scaled_to_millimetres() {
    let bytes = archive(&model("inch", &corner_object(1), &item(1, None)), &[]);
    let (_, mesh) = read_ok("inch.3mf", &bytes);
    assert_eq!(
        mesh.triangles,
        vec![[v(25.4, 0.0, 0.0), v(0.0, 50.8, 0.0), v(0.0, 0.0, 3.0 * 25.4)]]
    );
    assert!(mesh.notes.iter().any(|n| n.contains("inch")), "{:?}", mesh.notes);

    for (unit, factor) in [
        ("micron", 0.001),
        ("centimeter", 10.0),
        ("foot", 304.8),
        ("meter", 1000.0),
    ] {
        let bytes = archive(&model(unit, &corner_object(1), &item(1, None)), &[]);
        let (_, mesh) = read_ok("unit.3mf", &bytes);
        assert_eq!(mesh.triangles[0][0], v(factor, 0.0, 0.0), "{unit}");
    }
}

#[test]
fn threemf_mirrored_item_is_rewound() {
    let mirror = "-1 0 0 0 1 0 0 0 1 0 0 0";
    let bytes = archive(&model("millimeter", &corner_object(1), &item(1, Some(mirror))), &[]);
    let (_, mesh) = read_ok("mirror.3mf", &bytes);
    assert_eq!(
        mesh.triangles,
        vec![[v(-1.0, 0.0, 0.0), v(0.0, 0.0, 3.0), v(0.0, 2.0, 0.0)]]
    );
    assert!(mesh.notes.iter().any(|n| n.contains("mirror")), "{:?}", mesh.notes);
}

#[test]
fn threemf_written_by_the_threemf_crate() {
    use threemf::model::{Build, Item, Mesh, Model, Object, Resources, Triangle as T, Triangles, Vertex, Vertices};
    let mesh = Mesh {
        vertices: Vertices {
            vertex: [[0.0, 0.0, 0.0], [4.0, 0.0, 0.0], [0.0, 4.0, 0.0]]
                .into_iter()
                .map(|[x, y, z]| Vertex { x, y, z })
                .collect(),
        },
        triangles: Triangles {
            triangle: vec![T { v1: 0, v2: 1, v3: 2 }],
        },
    };
    let model = Model {
        resources: Resources {
            object: vec![Object {
                id: 1,
                mesh: Some(mesh),
                ..Object::default()
            }],
            basematerials: None,
        },
        build: Build {
            item: vec![Item {
                objectid: 1,
                transform: Some([1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 7.0]),
                partnumber: None,
            }],
        },
        ..Model::default()
    };
    let mut bytes = Cursor::new(Vec::new());
    threemf::write(&mut bytes, model).expect("threemf writes");
    let (_, mesh) = read_ok("written.3mf", bytes.get_ref());
    assert_eq!(
        mesh.triangles,
        vec![[v(0.0, 0.0, 7.0), v(4.0, 0.0, 7.0), v(0.0, 4.0, 7.0)]]
    );
}

#[test]
fn threemf_production_extension_parts_are_followed() {
    // Bambu Studio style: the root holds an assembly pointing into 3D/Objects/object_1.model.
    let part = model("millimeter", &corner_object(1), "");
    let root = model(
        "millimeter",
        "  <object id=\"2\" type=\"model\"><components>\
         <component p:path=\"/3D/Objects/object_1.model\" objectid=\"1\" \
         transform=\"1 0 0 0 1 0 0 0 1 0 0 5\"/></components></object>",
        &item(2, Some(&translate(1.0, 0.0, 0.0))),
    );
    let bytes = archive(&root, &[("3D/Objects/object_1.model", &part)]);
    let (_, mesh) = read_ok("bambu.3mf", &bytes);
    assert_eq!(
        mesh.triangles,
        vec![[v(2.0, 0.0, 5.0), v(1.0, 2.0, 5.0), v(1.0, 0.0, 8.0)]]
    );
    assert!(mesh.notes.iter().any(|n| n.contains("Production")), "{:?}", mesh.notes);

    // The same id in two parts cannot be told apart without p:path: refuse, do not guess.
    let root = model(
        "millimeter",
        &[component_object(1, &[(1, None)]), component_object(2, &[(3, None)])].join("\n"),
        &[item(1, None), item(2, None)].join("\n"),
    );
    let bytes = archive(
        &root,
        &[
            ("3D/Objects/object_1.model", &part),
            ("3D/Objects/object_2.model", &part),
        ],
    );
    let kind = read_err("ambiguous.3mf", &bytes);
    assert!(matches!(kind, ReadErrorKind::ThreeMf(_)), "{kind:?}");
}

#[test]
fn threemf_bad_vertex_index_names_object_and_triangle() {
    let object = mesh_object(
        4,
        &[[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]],
        &[[0, 1, 2], [0, 2, 3]],
    );
    let bytes = archive(&model("millimeter", &object, &item(4, None)), &[]);
    let kind = read_err("bad-index.3mf", &bytes);
    let m = message(&kind);
    assert!(
        m.contains("object 4") && m.contains("triangle 1") && m.contains("index 3"),
        "{m}"
    );
}

#[test]
fn threemf_nan_names_object_and_triangle() {
    let object = mesh_object(
        3,
        &[[0.0, 0.0, 0.0], [f64::NAN, 0.0, 0.0], [0.0, 1.0, 0.0]],
        &[[0, 1, 2]],
    );
    let bytes = archive(&model("millimeter", &object, &item(3, None)), &[]);
    match read_err("nan.3mf", &bytes) {
        ReadErrorKind::NonFinite { location, value } => {
            assert!(
                location.contains("object 3") && location.contains("triangle 0"),
                "{location}"
            );
            assert_eq!(value, "NaN");
        }
        other => panic!("expected NonFinite, got {other:?}"),
    }

    let bytes = archive(
        &model(
            "millimeter",
            &corner_object(1),
            &item(1, Some("1 0 0 0 1 0 0 0 1 inf 0 0")),
        ),
        &[],
    );
    assert!(matches!(read_err("inf.3mf", &bytes), ReadErrorKind::NonFinite { .. }));
}

#[test]
fn threemf_component_cycle_is_an_error_not_a_hang() {
    let resources = [
        corner_object(1),
        component_object(2, &[(1, None), (3, None)]),
        component_object(3, &[(2, None)]),
    ]
    .join("\n");
    let bytes = archive(&model("millimeter", &resources, &item(2, None)), &[]);
    let kind = read_err("cycle.3mf", &bytes);
    assert!(message(&kind).contains("cycle"), "{kind}");

    let bytes = archive(
        &model("millimeter", &component_object(5, &[(5, None)]), &item(5, None)),
        &[],
    );
    assert!(message(&read_err("self.3mf", &bytes)).contains("cycle"));
}

#[test]
fn threemf_exponential_and_deep_nesting_are_limited() {
    // Each level places the next one twice: 2^30 placements if nothing stopped it.
    let mut resources = vec![mesh_object(100, &[], &[])];
    for level in 0..30 {
        resources.push(component_object(level, &[(level + 1, None), (level + 1, None)]));
    }
    resources.push(component_object(30, &[(100, None)]));
    let bytes = archive(&model("millimeter", &resources.join("\n"), &item(0, None)), &[]);
    assert!(matches!(read_err("bomb.3mf", &bytes), ReadErrorKind::ThreeMf(_)));

    let mut resources = vec![corner_object(100)];
    for level in 0..40 {
        resources.push(component_object(level, &[(level + 1, None)]));
    }
    resources.push(component_object(40, &[(100, None)]));
    let bytes = archive(&model("millimeter", &resources.join("\n"), &item(0, None)), &[]);
    let kind = read_err("deep.3mf", &bytes);
    assert!(message(&kind).contains("nested"), "{kind}");
}

#[test]
fn threemf_missing_object_is_an_error() {
    let bytes = archive(&model("millimeter", &corner_object(1), &item(9, None)), &[]);
    let kind = read_err("missing.3mf", &bytes);
    assert!(message(&kind).contains("object 9"), "{kind}");
}

#[test]
fn threemf_corrupt_files_are_errors() {
    let kind = read_err("junk.3mf", b"this is not a zip archive at all");
    assert!(message(&kind).contains("ZIP"), "{kind}");

    let good = archive(&model("millimeter", &corner_object(1), &item(1, None)), &[]);
    let kind = read_err("truncated.3mf", &good[..good.len() / 2]);
    assert!(matches!(kind, ReadErrorKind::ThreeMf(_)), "{kind:?}");

    assert_eq!(read_err("empty.3mf", b""), ReadErrorKind::Empty);

    // A ZIP without any model part.
    let mut zip = zip::ZipWriter::new(Cursor::new(Vec::new()));
    zip.start_file("readme.txt", zip::write::SimpleFileOptions::default())
        .expect("zip entry");
    zip.write_all(b"hello").expect("zip write");
    let bytes = zip.finish().expect("zip finish").into_inner();
    let kind = read_err("nomodel.3mf", &bytes);
    assert!(message(&kind).contains("no 3D model"), "{kind}");

    // Broken XML in the model part.
    let bytes = archive("<model><resources><object id=\"1\">", &[]);
    assert!(matches!(read_err("badxml.3mf", &bytes), ReadErrorKind::ThreeMf(_)));
}

#[test]
fn threemf_empty_build_has_no_triangles() {
    let bytes = archive(&model("millimeter", &corner_object(1), ""), &[]);
    assert_eq!(read_err("nobuild.3mf", &bytes), ReadErrorKind::NoTriangles);
}
