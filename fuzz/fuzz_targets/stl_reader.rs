//! Fuzz target for the STL reader: any bytes must give `Ok` or `Err`, never a panic or a hang,
//! and an `Ok` must hold only what the reader promises (finite corners, a binary count that
//! fits the input). Findings become regression tests in crates/platener/tests/stl_reader/smoke.rs.
#![no_main]

use libfuzzer_sys::fuzz_target;
use platener::read::stl::parse_bytes;
use platener::read::{Format, ReadErrorKind};

fuzz_target!(|data: &[u8]| {
    match parse_bytes(data) {
        Ok((format, mesh)) => {
            assert!(
                mesh.triangles.iter().flatten().all(|v| v.is_finite()),
                "non-finite corner"
            );
            assert!(mesh.zero_normals + mesh.normals_against_winding <= mesh.triangles.len());
            match format {
                Format::StlBinary => {
                    assert!(84 + 50 * mesh.triangles.len() <= data.len(), "more facets than bytes");
                    assert_eq!(mesh.solids, 1);
                }
                Format::StlAscii => assert!(mesh.triangles.is_empty() || mesh.solids >= 1),
                other => panic!("STL reader returned {other:?}"),
            }
        }
        Err(ReadErrorKind::Syntax { line, message }) => {
            let lines = data.iter().filter(|&&b| b == b'\n').count() + 1;
            assert!(line >= 1 && line <= lines, "line {line} of {lines}: {message}");
        }
        Err(ReadErrorKind::Empty) => assert!(data.is_empty()),
        Err(ReadErrorKind::TooShort { actual }) => {
            assert!(actual < 84 && actual as usize == data.len())
        }
        Err(_) => {}
    }
});
