//! Unit tests of the STL reader internals: streaming equals in-memory parsing at every chunk
//! boundary, and the format decision. Quirk-by-quirk behaviour is tested through the public API
//! in `tests/stl_reader.rs`.

use std::io::Read;

use glam::DVec3;

use super::{ascii, binary, looks_ascii, parse_bytes};
use crate::read::{Format, RawMesh, ReadErrorKind};

/// A reader that hands out at most `step` bytes per call, to cut lines at every position.
struct Trickle<'a> {
    data: &'a [u8],
    step: usize,
}

impl Read for Trickle<'_> {
    fn read(&mut self, buf: &mut [u8]) -> std::io::Result<usize> {
        let n = self.step.min(buf.len()).min(self.data.len());
        buf[..n].copy_from_slice(&self.data[..n]);
        self.data = &self.data[n..];
        Ok(n)
    }
}

const QUIRKY: &str = "\u{feff}SOLID quirky\r\n\r\n  Facet Normal 0 0 -1.0\r\n\tOuter Loop\r\n  \
    VERTEX 0 0 0\r\n vertex 1.5e+01 0 0\r\n vertex 0 1E-3 0\r\n EndLoop\r\n endfacet\r\n\
    facet\nouter loop\nvertex 0 0 0\nvertex 0 1 0\nvertex 1 0 0\nendloop\nendfacet\nendsolid";

fn same(a: &RawMesh, b: &RawMesh) {
    assert_eq!(a.triangles, b.triangles);
    assert_eq!(a.solids, b.solids);
    assert_eq!(a.zero_normals, b.zero_normals);
    assert_eq!(a.normals_against_winding, b.normals_against_winding);
    assert_eq!(a.notes, b.notes);
}

#[test]
fn streaming_ascii_matches_slice_at_every_chunk_size() {
    let whole = ascii::parse_slice(QUIRKY.as_bytes()).expect("parses");
    assert_eq!(whole.triangles.len(), 2);
    assert_eq!(whole.triangles[0][1], DVec3::new(15.0, 0.0, 0.0));
    assert_eq!(whole.triangles[0][2], DVec3::new(0.0, 0.001, 0.0));
    assert_eq!(whole.zero_normals, 1);
    assert_eq!(whole.normals_against_winding, 1);
    for step in 1..40 {
        let streamed = ascii::parse_reader(&mut Trickle {
            data: QUIRKY.as_bytes(),
            step,
        })
        .expect("parses");
        same(&whole, &streamed);
    }
}

#[test]
fn streaming_ascii_errors_match_slice() {
    let text = "solid a\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 0 0 blah\n";
    let whole = ascii::parse_slice(text.as_bytes()).expect_err("fails");
    for step in 1..20 {
        let streamed = ascii::parse_reader(&mut Trickle {
            data: text.as_bytes(),
            step,
        })
        .expect_err("fails");
        assert_eq!(whole.kind, streamed.kind);
    }
    assert!(
        matches!(whole.kind, ReadErrorKind::Syntax { line: 5, .. }),
        "{:?}",
        whole.kind
    );
}

#[test]
fn streaming_binary_matches_slice() {
    let mut bytes = Vec::new();
    for i in 0..10_000u32 {
        for k in 0..12 {
            bytes.extend_from_slice(&((i * 12 + k) as f32 * 0.25).to_le_bytes());
        }
        bytes.extend_from_slice(&[0, 0]);
    }
    let whole = binary::parse_facets(&bytes).expect("parses");
    let streamed = binary::read_facets(
        &mut Trickle {
            data: &bytes,
            step: 777,
        },
        10_000,
    )
    .expect("parses");
    same(&whole, &streamed);
    assert_eq!(whole.triangles[9_999][2], DVec3::new(29_999.25, 29_999.5, 29_999.75));
}

#[test]
fn very_long_line_is_read_when_streaming() {
    let name = "n".repeat(300_000);
    let text = format!("solid {name}\nfacet\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendfacet\nendsolid {name}\n");
    let streamed = ascii::parse_reader(&mut Trickle {
        data: text.as_bytes(),
        step: 4096,
    })
    .expect("parses");
    assert_eq!(streamed.triangles.len(), 1);
}

#[test]
fn endless_line_is_refused_when_streaming() {
    let text = format!("solid x\n{}", "y".repeat(3 << 20));
    let failure = ascii::parse_reader(&mut Trickle {
        data: text.as_bytes(),
        step: 65536,
    })
    .expect_err("fails");
    assert!(
        matches!(failure.kind, ReadErrorKind::Syntax { line: 2, .. }),
        "{:?}",
        failure.kind
    );
}

#[test]
fn ascii_detection() {
    assert!(looks_ascii(b"solid x"));
    assert!(looks_ascii(b"  \r\nSoLiD"));
    assert!(looks_ascii(b"\xEF\xBB\xBFsolid"));
    assert!(!looks_ascii(b"soli"));
    assert!(!looks_ascii(b"binary solid"));
}

#[test]
fn binary_failure_carries_not_text() {
    let failure = ascii::parse_slice(b"solid x\n\x01\x00\x00\x00garbage\n").expect_err("fails");
    assert!(failure.not_text);
    assert_eq!(failure.facets, 0);
}

#[test]
fn nul_padding_after_endsolid_is_noted() {
    let text = b"solid x\nfacet\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendfacet\nendsolid x\n\0\0\0\0";
    let (format, mesh) = parse_bytes(text).expect("parses");
    assert_eq!(format, Format::StlAscii);
    assert_eq!(mesh.triangles.len(), 1);
    assert_eq!(mesh.notes.len(), 1, "{:?}", mesh.notes);
}

#[test]
fn a_whole_facet_too_many_is_a_count_mismatch_not_a_guess() {
    let tri = [glam::DVec3::ZERO, glam::DVec3::X, glam::DVec3::Y];
    let mut bytes = platener_fixtures::samples::to_binary_stl(&[tri, tri], "padded");
    bytes[80..84].copy_from_slice(&1u32.to_le_bytes());
    assert!(matches!(
        parse_bytes(&bytes),
        Err(ReadErrorKind::CountMismatch { count: 1, .. })
    ));
    // Less than one facet of padding is tolerated, with a note.
    bytes.truncate(84 + 50 + 7);
    let (format, mesh) = parse_bytes(&bytes).expect("padded file reads");
    assert_eq!((format, mesh.triangles.len()), (Format::StlBinary, 1));
    assert!(mesh.notes[0].starts_with("7 trailing bytes"));
}
