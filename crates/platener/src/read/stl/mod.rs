//! Our own tolerant STL reader (binary and ASCII). TODO: implemented by the reader work.
use std::path::Path;

use super::{Format, RawMesh, ReadErrorKind};

/// Reads an STL file, streaming it; binary when `84 + 50·n == size`, ASCII otherwise.
pub fn read_path(_path: &Path) -> Result<(Format, RawMesh), ReadErrorKind> {
    Err(ReadErrorKind::Io("not yet implemented".into()))
}

/// Parses an STL held in memory (tests, fuzzing, uploads).
pub fn parse_bytes(_bytes: &[u8]) -> Result<(Format, RawMesh), ReadErrorKind> {
    Err(ReadErrorKind::Io("not yet implemented".into()))
}
