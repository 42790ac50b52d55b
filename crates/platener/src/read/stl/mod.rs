//! Our own tolerant STL reader (binary and ASCII).
//!
//! Why not stl_io: it calls a file ASCII when its header starts with `solid`, which many binary
//! exporters write, it stops at quirks real ASCII files have, and its errors name no line. Here
//! the size decides: a file is binary exactly when it is `84 + 50·n` bytes long, `n` being the
//! count at byte 80; otherwise it is parsed as ASCII. A file that is neither (binary bytes, no
//! facet) but has its `n` facets and less than one facet more is read as binary, the trailing
//! bytes noted.
//! Files are streamed (memory grows with the triangles, not the file), and every failure names
//! the line (ASCII, 1-based) or triangle (binary, 0-based).

mod ascii;
mod binary;
mod line;
mod number;
#[cfg(test)]
mod tests;

use std::fs::File;
use std::io::{Read, Seek, SeekFrom};
use std::path::Path;

use glam::DVec3;

use super::{Format, RawMesh, ReadErrorKind, Triangle};

/// Bytes before the first binary facet: an 80-byte header and the u32 facet count.
pub(super) const HEADER_BYTES: usize = 84;
/// Bytes per binary facet.
pub(super) const FACET_BYTES: usize = 50;

/// Reads an STL file, streaming it; binary when `84 + 50·n == size`, ASCII otherwise.
pub fn read_path(path: &Path) -> Result<(Format, RawMesh), ReadErrorKind> {
    let mut file = File::open(path).map_err(io_error)?;
    let size = file.metadata().map_err(io_error)?.len();
    let mut head = Vec::with_capacity(HEADER_BYTES);
    (&mut file)
        .take(HEADER_BYTES as u64)
        .read_to_end(&mut head)
        .map_err(io_error)?;
    read_input(&mut FileInput { file, size, head })
}

/// Parses an STL held in memory (tests, fuzzing, uploads).
pub fn parse_bytes(bytes: &[u8]) -> Result<(Format, RawMesh), ReadErrorKind> {
    read_input(&mut SliceInput(bytes))
}

/// What the format decision needs from a file or a slice.
trait Input {
    /// Total size in bytes.
    fn size(&self) -> u64;
    /// The first (up to) 84 bytes.
    fn head(&self) -> &[u8];
    /// Decodes `count` binary facets after the header.
    fn binary(&mut self, count: u32) -> Result<RawMesh, ReadErrorKind>;
    /// Parses the whole input as ASCII STL.
    fn ascii(&mut self) -> Result<RawMesh, ascii::Failure>;
}

struct SliceInput<'a>(&'a [u8]);

impl Input for SliceInput<'_> {
    fn size(&self) -> u64 {
        self.0.len() as u64
    }
    fn head(&self) -> &[u8] {
        self.0.get(..HEADER_BYTES).unwrap_or(self.0)
    }
    fn binary(&mut self, count: u32) -> Result<RawMesh, ReadErrorKind> {
        let end = HEADER_BYTES + count as usize * FACET_BYTES;
        let facets = self
            .0
            .get(HEADER_BYTES..end)
            .ok_or(ReadErrorKind::TooShort { actual: self.size() })?;
        binary::parse_facets(facets)
    }
    fn ascii(&mut self) -> Result<RawMesh, ascii::Failure> {
        ascii::parse_slice(self.0)
    }
}

struct FileInput {
    file: File,
    size: u64,
    head: Vec<u8>,
}

impl Input for FileInput {
    fn size(&self) -> u64 {
        self.size
    }
    fn head(&self) -> &[u8] {
        &self.head
    }
    fn binary(&mut self, count: u32) -> Result<RawMesh, ReadErrorKind> {
        self.file.seek(SeekFrom::Start(HEADER_BYTES as u64)).map_err(io_error)?;
        binary::read_facets(&mut self.file, count)
    }
    fn ascii(&mut self) -> Result<RawMesh, ascii::Failure> {
        let rewind = self.file.seek(SeekFrom::Start(0));
        if let Err(e) = rewind {
            return Err(ascii::Failure {
                kind: io_error(e),
                not_text: false,
                facets: 0,
            });
        }
        ascii::parse_reader(&mut self.file)
    }
}

/// Chooses binary or ASCII and reads. See the module documentation for the rule.
fn read_input(input: &mut impl Input) -> Result<(Format, RawMesh), ReadErrorKind> {
    let size = input.size();
    if size == 0 {
        return Err(ReadErrorKind::Empty);
    }
    let count = count_field(input.head());
    if let Some(count) = count
        && binary_size(count) == size
    {
        if count == 0 {
            return Err(ReadErrorKind::HeaderOnly { count });
        }
        return Ok((Format::StlBinary, input.binary(count)?));
    }
    // A binary reading of a file longer than its facets by less than one facet (exporters
    // that pad); more than that means the count field is wrong, and we refuse to guess.
    let with_trailing = count.filter(|&n| n > 0 && binary_size(n) < size && size - binary_size(n) < FACET_BYTES as u64);
    if looks_ascii(input.head()) {
        let failure = match input.ascii() {
            Ok(mesh) if !mesh.triangles.is_empty() || with_trailing.is_none() => {
                return Ok((Format::StlAscii, mesh));
            }
            Ok(_) => None,
            Err(failure) => Some(failure),
        };
        if let Some(failure) = failure {
            let io = matches!(failure.kind, ReadErrorKind::Io(_));
            let binary_like = !io && (failure.not_text || failure.facets == 0);
            if !binary_like || (with_trailing.is_none() && !failure.not_text) {
                return Err(failure.kind);
            }
        }
    }
    match (with_trailing, count) {
        (Some(n), _) => {
            let mut mesh = input.binary(n)?;
            let trailing = size - binary_size(n);
            mesh.notes.push(format!(
                "{trailing} trailing bytes after the last facet ignored (the count field says {n} \
                 facets, {} bytes; the file has {size})",
                binary_size(n)
            ));
            Ok((Format::StlBinary, mesh))
        }
        (None, Some(count)) => Err(ReadErrorKind::CountMismatch {
            count,
            expected: binary_size(count),
            actual: size,
        }),
        (None, None) => Err(ReadErrorKind::TooShort { actual: size }),
    }
}

/// The facet count at byte 80, if the header is complete.
fn count_field(head: &[u8]) -> Option<u32> {
    let bytes = head.get(80..HEADER_BYTES)?;
    Some(u32::from_le_bytes([bytes[0], bytes[1], bytes[2], bytes[3]]))
}

/// Size of a binary STL with `count` facets.
fn binary_size(count: u32) -> u64 {
    HEADER_BYTES as u64 + FACET_BYTES as u64 * u64::from(count)
}

/// Whether the file starts like ASCII STL: `solid`, after an optional UTF-8 BOM and blanks.
pub(super) fn looks_ascii(head: &[u8]) -> bool {
    let head = head.strip_prefix(b"\xEF\xBB\xBF").unwrap_or(head);
    let head = head.trim_ascii_start();
    head.get(..5).is_some_and(|word| word.eq_ignore_ascii_case(b"solid"))
}

/// Counts a facet's stored normal: zero (or not finite), or against the winding.
fn record_normal(mesh: &mut RawMesh, normal: DVec3, triangle: &Triangle) {
    let (zero, against) = classify_normal(normal, triangle);
    mesh.zero_normals += usize::from(zero);
    mesh.normals_against_winding += usize::from(against);
}

/// Whether a stored normal is zero (or not finite), and whether it points against the winding.
fn classify_normal(normal: DVec3, triangle: &Triangle) -> (bool, bool) {
    let [a, b, c] = *triangle;
    let zero = (normal == DVec3::ZERO) | !normal.is_finite();
    let against = !zero & (normal.dot((b - a).cross(c - a)) < 0.0);
    (zero, against)
}

fn io_error(error: std::io::Error) -> ReadErrorKind {
    ReadErrorKind::Io(error.to_string())
}
