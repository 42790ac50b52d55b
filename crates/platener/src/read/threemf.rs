//! 3MF reader. TODO.
use std::path::Path;

use super::{RawMesh, ReadErrorKind};

/// Reads every object of the 3MF build with its transform.
pub fn read_path(_path: &Path) -> Result<RawMesh, ReadErrorKind> {
    Err(ReadErrorKind::ThreeMf("not yet implemented".into()))
}
