//! OBJ reader on tobj. TODO.
use std::path::Path;

use super::{RawMesh, ReadErrorKind};

/// Reads every object of an OBJ file, triangulating polygons.
pub fn read_path(_path: &Path) -> Result<RawMesh, ReadErrorKind> {
    Err(ReadErrorKind::Obj("not yet implemented".into()))
}
