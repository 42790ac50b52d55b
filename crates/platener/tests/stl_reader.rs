//! STL reader through its public API: every quirk and error the reader promises, stl_io as an
//! oracle for binary coordinates, the shared corpus, and a random-input smoke test.

#[path = "stl_reader/corpus.rs"]
mod corpus;
#[path = "stl_reader/smoke.rs"]
mod smoke;

use std::io::{Cursor, Write};

use glam::DVec3;
use platener::read::stl::{parse_bytes, read_path};
use platener::read::{Format, RawMesh, ReadErrorKind};

/// Parses in memory and from a file; both must agree. Returns the in-memory result.
fn parse(bytes: &[u8]) -> Result<(Format, RawMesh), ReadErrorKind> {
    let in_memory = parse_bytes(bytes);
    let mut file = tempfile::NamedTempFile::new().expect("temp file");
    file.write_all(bytes).expect("write");
    let streamed = read_path(file.path());
    match (&in_memory, &streamed) {
        (Ok((fa, a)), Ok((fb, b))) => {
            assert_eq!(fa, fb);
            assert_eq!(a.triangles, b.triangles);
            assert_eq!(a.notes, b.notes);
            assert_eq!(
                (a.solids, a.zero_normals, a.normals_against_winding),
                (b.solids, b.zero_normals, b.normals_against_winding)
            );
        }
        (a, b) => assert_eq!(a.as_ref().err(), b.as_ref().err()),
    }
    in_memory
}

fn ascii(text: &str) -> RawMesh {
    match parse(text.as_bytes()) {
        Ok((Format::StlAscii, mesh)) => mesh,
        other => panic!("expected ASCII, got {other:?}"),
    }
}

/// The error of `text` as (line, message).
fn syntax(text: &str) -> (usize, String) {
    match parse(text.as_bytes()) {
        Err(ReadErrorKind::Syntax { line, message }) => (line, message),
        other => panic!("expected a syntax error, got {other:?}"),
    }
}

const FACET: &str =
    "facet normal 0 0 1\n outer loop\n  vertex 0 0 0\n  vertex 1 0 0\n  vertex 0 1 0\n endloop\nendfacet\n";

/// A binary STL: `header` (padded to 80 bytes), count, facets of (normal, corners).
fn binary(header: &[u8], facets: &[([f32; 3], [[f32; 3]; 3])]) -> Vec<u8> {
    let mut bytes = header.to_vec();
    bytes.resize(80, b' ');
    bytes.extend_from_slice(&(facets.len() as u32).to_le_bytes());
    for (normal, corners) in facets {
        for v in std::iter::once(normal).chain(corners) {
            for c in v {
                bytes.extend_from_slice(&c.to_le_bytes());
            }
        }
        bytes.extend_from_slice(&[0, 0]);
    }
    bytes
}

const UNIT: ([f32; 3], [[f32; 3]; 3]) = ([0.0, 0.0, 1.0], [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]);

#[test]
fn ascii_basic_coordinates() {
    let mesh = ascii(&format!("solid cube\n{FACET}endsolid cube\n"));
    assert_eq!(mesh.triangles, vec![[DVec3::ZERO, DVec3::X, DVec3::Y]]);
    assert_eq!(
        (mesh.solids, mesh.zero_normals, mesh.normals_against_winding),
        (1, 0, 0)
    );
    assert!(mesh.notes.is_empty());
}

#[test]
fn ascii_crlf_blank_lines_tabs_spaces_and_case() {
    let text = "SOLID Part\r\n\r\n\r\n\tFACET   NORMAL\t0  0\t\t1\r\n  \r\n Outer\tLoop\r\n\
                VERTEX  1.5e+01\t-2 3 \r\nVertex 1E-3 0.5 -0.25\r\n vErTeX +7 .5 8.\r\n\
                ENDLOOP\r\n EndFacet \r\nENDSOLID Part\r\n";
    let mesh = ascii(text);
    assert_eq!(
        mesh.triangles,
        vec![[
            DVec3::new(15.0, -2.0, 3.0),
            DVec3::new(0.001, 0.5, -0.25),
            DVec3::new(7.0, 0.5, 8.0)
        ]]
    );
}

#[test]
fn ascii_endsolid_with_or_without_name_and_several_solids() {
    let text = format!("solid a\n{FACET}endsolid\nsolid b\n{FACET}{FACET}endsolid b\nsolid\n{FACET}endsolid c\n");
    let mesh = ascii(&text);
    assert_eq!((mesh.triangles.len(), mesh.solids), (4, 3));
}

#[test]
fn ascii_missing_and_zero_normals_are_counted() {
    let text = "solid x\nfacet\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendfacet\n\
                facet normal\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\n\
                facet normal 0 0 0\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\n\
                facet normal 0 0 -1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\nendsolid\n";
    let mesh = ascii(text);
    assert_eq!(mesh.triangles.len(), 4);
    assert_eq!((mesh.zero_normals, mesh.normals_against_winding), (3, 1));
}

#[test]
fn ascii_very_long_solid_name() {
    let name = "very long name ".repeat(10_000);
    let mesh = ascii(&format!("solid {name}\n{FACET}endsolid {name}\n"));
    assert_eq!(mesh.triangles.len(), 1);
}

#[test]
fn ascii_missing_final_endsolid_is_a_note() {
    let mesh = ascii(&format!("solid x\n{FACET}{FACET}"));
    assert_eq!(mesh.triangles.len(), 2);
    assert_eq!(mesh.notes.len(), 1);
    assert!(mesh.notes[0].contains("endsolid"), "{:?}", mesh.notes);
}

#[test]
fn ascii_without_facets_is_empty() {
    let mesh = ascii("solid empty\nendsolid empty\n");
    assert!(mesh.triangles.is_empty());
}

#[test]
fn ascii_four_and_two_vertices() {
    let four = "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nvertex 1 1 0\nendloop\nendfacet\nendsolid\n";
    let (line, message) = syntax(four);
    assert_eq!(line, 9);
    assert!(
        message.starts_with("facet with 4 vertices (a facet has exactly 3)"),
        "{message}"
    );
    let two = "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nendloop\nendfacet\nendsolid\n";
    let (line, message) = syntax(two);
    assert_eq!(line, 7);
    assert!(
        message.starts_with("facet with 2 vertices (a facet has exactly 3)"),
        "{message}"
    );
}

#[test]
fn ascii_unparseable_number() {
    let (line, message) = syntax(&format!("solid x\n{FACET}facet\nouter loop\nvertex 0 0 blah\n"));
    assert_eq!(line, 11);
    assert!(
        message.contains("'blah'") && message.contains("'vertex 0 0 blah'"),
        "{message}"
    );
}

#[test]
fn ascii_unexpected_text() {
    let (line, message) = syntax(&format!("solid x\n{FACET}end solid x\n"));
    assert_eq!(line, 9);
    assert!(message.contains("unexpected text 'end solid x'"), "{message}");
    let (line, message) = syntax("solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 0 0 0 0\n");
    assert_eq!(line, 5);
    assert!(message.contains("4 numbers"), "{message}");
    let (line, _) = syntax("solid x\nvertex 0 0 0\n");
    assert_eq!(line, 2);
    let (line, _) = syntax(&format!("solid x\n{FACET}endsolid x\nfacet\n"));
    assert_eq!(line, 10);
}

#[test]
fn ascii_truncated_mid_facet() {
    let (line, message) = syntax("solid x\nfacet normal 0 0 1\n  outer loop\n    vertex 0 0 0\n    vertex 0.");
    assert_eq!(line, 5);
    assert!(
        message.contains("'vertex 0.'") && message.contains("truncated"),
        "{message}"
    );
    let (line, message) = syntax("solid x\nfacet normal 0 0 1\n  outer loop\n    vertex 0 0 0\n");
    assert_eq!(line, 4);
    assert!(message.contains("truncated") && message.contains("line 2"), "{message}");
}

#[test]
fn ascii_non_finite() {
    for (value, text) in [
        ("nan", "vertex nan 0 0"),
        ("inf", "vertex 0 inf 0"),
        ("-1e999", "vertex 0 0 -1e999"),
    ] {
        let result = parse(format!("solid x\nfacet\nouter loop\n{text}\n").as_bytes());
        assert_eq!(
            result.err(),
            Some(ReadErrorKind::NonFinite {
                location: "line 4".into(),
                value: value.into()
            }),
            "{text}"
        );
    }
}

#[test]
fn binary_matches_stl_io() {
    let mut state = 0x1234_5678_9ABC_DEF0_u64;
    let mut next = move || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state % 2_000_000) as f32 / 1000.0 - 1000.0
    };
    let triangles: Vec<stl_io::Triangle> = (0..5000)
        .map(|_| stl_io::Triangle {
            normal: stl_io::Normal::new([next(), next(), next()]),
            vertices: [0; 3].map(|_| stl_io::Vertex::new([next(), next(), next()])),
        })
        .collect();
    let mut bytes = Vec::new();
    stl_io::write_stl(&mut bytes, triangles.iter()).expect("write");
    let (format, mesh) = parse(&bytes).expect("parses");
    assert_eq!(format, Format::StlBinary);
    let oracle: Vec<stl_io::Triangle> = stl_io::create_stl_reader(&mut Cursor::new(&bytes))
        .expect("stl_io reads")
        .collect::<Result<_, _>>()
        .expect("stl_io reads");
    assert_eq!(mesh.triangles.len(), oracle.len());
    for (ours, theirs) in mesh.triangles.iter().zip(&oracle) {
        for (a, b) in ours.iter().zip(&theirs.vertices) {
            assert_eq!(*a, DVec3::new(b.0[0].into(), b.0[1].into(), b.0[2].into()));
        }
    }
    assert_eq!(mesh.solids, 1);
}

#[test]
fn binary_with_solid_header_reads_as_binary() {
    let bytes = binary(b"solid exported by a CAD program", &[UNIT, UNIT]);
    let (format, mesh) = parse(&bytes).expect("parses");
    assert_eq!(format, Format::StlBinary);
    assert_eq!(mesh.triangles, vec![[DVec3::ZERO, DVec3::X, DVec3::Y]; 2]);
    assert!(mesh.notes.is_empty());
}

#[test]
fn binary_normals_are_counted() {
    let against = ([0.0, 0.0, -1.0], UNIT.1);
    let zero = ([0.0, 0.0, 0.0], UNIT.1);
    let (_, mesh) = parse(&binary(b"", &[UNIT, against, zero, against])).expect("parses");
    assert_eq!((mesh.normals_against_winding, mesh.zero_normals), (2, 1));
}

#[test]
fn binary_with_solid_header_and_trailing_byte() {
    let mut bytes = binary(b"solid trailing", &[UNIT, UNIT, UNIT]);
    bytes.push(0x0a);
    let (format, mesh) = parse(&bytes).expect("parses");
    assert_eq!((format, mesh.triangles.len()), (Format::StlBinary, 3));
    assert!(
        mesh.notes[0].starts_with("1 trailing bytes after the last facet ignored"),
        "{:?}",
        mesh.notes
    );
}

#[test]
fn binary_size_errors() {
    assert_eq!(parse(b"").err(), Some(ReadErrorKind::Empty));
    assert_eq!(
        parse(&binary(b"", &[])).err(),
        Some(ReadErrorKind::HeaderOnly { count: 0 })
    );
    assert_eq!(parse(&[0u8; 50]).err(), Some(ReadErrorKind::TooShort { actual: 50 }));
    let mut cut = binary(b"", &[UNIT, UNIT]);
    cut.truncate(150);
    let mismatch = ReadErrorKind::CountMismatch {
        count: 2,
        expected: 184,
        actual: 150,
    };
    assert_eq!(parse(&cut).err(), Some(mismatch));
    let mut solid_cut = binary(b"solid x", &[UNIT, UNIT]);
    solid_cut.truncate(183);
    let mismatch = ReadErrorKind::CountMismatch {
        count: 2,
        expected: 184,
        actual: 183,
    };
    assert_eq!(parse(&solid_cut).err(), Some(mismatch));
    let mut huge_count = binary(b"", &[UNIT]);
    huge_count[80..84].copy_from_slice(&u32::MAX.to_le_bytes());
    assert!(matches!(
        parse(&huge_count),
        Err(ReadErrorKind::CountMismatch { count: u32::MAX, .. })
    ));
}

#[test]
fn binary_non_finite_names_the_triangle() {
    let nan = (
        [0.0, 0.0, 1.0],
        [[0.0, 0.0, 0.0], [1.0, f32::NAN, 0.0], [0.0, 1.0, 0.0]],
    );
    let inf = (
        [0.0, 0.0, 1.0],
        [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, f32::INFINITY]],
    );
    let expected = |value: &str| ReadErrorKind::NonFinite {
        location: "triangle 2".into(),
        value: value.into(),
    };
    assert_eq!(parse(&binary(b"", &[UNIT, UNIT, nan])).err(), Some(expected("NaN")));
    assert_eq!(
        parse(&binary(b"", &[UNIT, UNIT, inf, UNIT])).err(),
        Some(expected("inf"))
    );
    // A non-finite normal is harmless: counted as a zero normal.
    let odd_normal = ([f32::NAN, 0.0, 0.0], UNIT.1);
    let (_, mesh) = parse(&binary(b"", &[odd_normal])).expect("parses");
    assert_eq!(mesh.zero_normals, 1);
}

#[test]
fn missing_file_is_an_io_error() {
    let result = read_path(std::path::Path::new("/nonexistent/dir/model.stl"));
    assert!(matches!(result, Err(ReadErrorKind::Io(_))), "{result:?}");
}
