//! Binary STL facets: 12 little-endian f32 (normal, three corners) and a 2-byte attribute.
//!
//! Why chunks: a file is decoded a few thousand facets at a time from a reused buffer, so a
//! 1 GB file never sits in memory; only the triangles do. The count was checked against the
//! real size before we get here, so reserving for it is safe.

use std::io::Read;

use glam::DVec3;

use super::{FACET_BYTES, classify_normal, io_error};
use crate::read::{RawMesh, ReadErrorKind, Triangle};

/// Facets decoded per read when streaming (about 200 KB).
const FACETS_PER_CHUNK: usize = 4096;

/// Decodes `count` facets from `reader`, which is positioned just after the 84-byte header.
pub(super) fn read_facets<R: Read>(reader: &mut R, count: u32) -> Result<RawMesh, ReadErrorKind> {
    let count = count as usize;
    let mut mesh = new_mesh(count);
    let mut buffer = vec![0u8; FACETS_PER_CHUNK.min(count) * FACET_BYTES];
    let mut done = 0;
    while done < count {
        let n = FACETS_PER_CHUNK.min(count - done);
        let chunk = buffer.get_mut(..n * FACET_BYTES).unwrap_or_default();
        reader.read_exact(chunk).map_err(io_error)?;
        decode(chunk, done, &mut mesh)?;
        done += n;
    }
    Ok(mesh)
}

/// Decodes all facets in `bytes` (a whole number of 50-byte records).
pub(super) fn parse_facets(bytes: &[u8]) -> Result<RawMesh, ReadErrorKind> {
    let mut mesh = new_mesh(bytes.len() / FACET_BYTES);
    decode(bytes, 0, &mut mesh)?;
    Ok(mesh)
}

fn new_mesh(count: usize) -> RawMesh {
    RawMesh {
        triangles: Vec::with_capacity(count),
        solids: 1,
        ..RawMesh::default()
    }
}

/// Decodes the facets of `chunk`; `first` is the index of its first facet in the file.
///
/// Decodes every facet first and checks afterwards, so that the loop has no early exit and
/// `extend` can write straight into the reserved triangles; a non-finite corner is rare.
fn decode(chunk: &[u8], first: usize, mesh: &mut RawMesh) -> Result<(), ReadErrorKind> {
    const BLANK: [u8; FACET_BYTES] = [0; FACET_BYTES];
    let mut finite = true;
    let start = mesh.triangles.len();
    let (mut zero, mut against) = (0, 0);
    mesh.triangles.extend(chunk.chunks_exact(FACET_BYTES).map(|record| {
        let record = <&[u8; FACET_BYTES]>::try_from(record).unwrap_or(&BLANK);
        let f = |k: usize| {
            let o = 4 * k;
            f32::from_le_bytes([record[o], record[o + 1], record[o + 2], record[o + 3]])
        };
        let corners = [f(3), f(4), f(5), f(6), f(7), f(8), f(9), f(10), f(11)];
        finite &= corners.iter().fold(true, |all, c| all & c.is_finite());
        let v = |k: usize| DVec3::new(corners[k].into(), corners[k + 1].into(), corners[k + 2].into());
        let triangle: Triangle = [v(0), v(3), v(6)];
        let normal = DVec3::new(f(0).into(), f(1).into(), f(2).into());
        let (is_zero, is_against) = classify_normal(normal, &triangle);
        zero += usize::from(is_zero);
        against += usize::from(is_against);
        triangle
    }));
    mesh.zero_normals += zero;
    mesh.normals_against_winding += against;
    if finite {
        return Ok(());
    }
    let decoded = mesh.triangles.get(start..).unwrap_or_default();
    let bad = decoded
        .iter()
        .position(|t| !t.iter().all(|v| v.is_finite()))
        .unwrap_or_default();
    Err(non_finite(
        first + bad,
        chunk.get(bad * FACET_BYTES..).unwrap_or_default(),
    ))
}

/// The error for the facet `index`, whose record starts `record`.
fn non_finite(index: usize, record: &[u8]) -> ReadErrorKind {
    let corners = record.get(12..48).unwrap_or_default().chunks_exact(4);
    let value = corners
        .map(|c| f32::from_le_bytes([c[0], c[1], c[2], c[3]]))
        .find(|c| !c.is_finite())
        .map_or_else(String::new, |c| c.to_string());
    ReadErrorKind::NonFinite {
        location: format!("triangle {index}"),
        value,
    }
}
