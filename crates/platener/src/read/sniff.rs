//! A model's format judged by its content, in a few bytes and without reading it: what a
//! service checks before it queues an upload whose name may lie (issue 33: the web service
//! had its own copy of these rules). The readers themselves go by the file's extension
//! (`read_file`, `read_bytes`); this is the rule they agree with.

use super::Format;
use super::stl::{FACET_BYTES, HEADER_BYTES, looks_ascii};

/// How many bytes of text are looked at for ASCII STL and OBJ keywords.
const TEXT_WINDOW: usize = 64 * 1024;

/// What the first bytes tell.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Sniffed {
    /// The format.
    pub format: Format,
    /// For binary STL, the count field (which the size matches, up to one facet of padding).
    pub triangles: Option<u64>,
}

/// The format of `bytes`: a ZIP is 3MF; a file as long as its binary STL count field says
/// (up to one facet of trailing bytes, which the reader ignores) is binary STL; text starting
/// with `solid` is ASCII STL; text with `v`, `vn`, `f` or `o` lines is OBJ; else `None`.
pub fn sniff(bytes: &[u8]) -> Option<Sniffed> {
    let found = |format, triangles| Some(Sniffed { format, triangles });
    if bytes.starts_with(b"PK\x03\x04") {
        return found(Format::ThreeMf, None);
    }
    if let Some(count) = binary_stl_count(bytes) {
        return found(Format::StlBinary, Some(count));
    }
    let window = &bytes[..bytes.len().min(TEXT_WINDOW)];
    if looks_ascii(window) {
        return found(Format::StlAscii, None);
    }
    let text = String::from_utf8_lossy(window);
    let obj_lines = text
        .lines()
        .map(str::trim_start)
        .filter(|l| l.starts_with("v ") || l.starts_with("f ") || l.starts_with("vn ") || l.starts_with("o "))
        .count();
    if obj_lines > 0 && !window.contains(&0) {
        return found(Format::Obj, None);
    }
    None
}

/// The count field of a binary STL whose size matches it (up to one facet of trailing bytes),
/// whatever the header's first word says.
fn binary_stl_count(bytes: &[u8]) -> Option<u64> {
    let count_bytes: [u8; 4] = bytes.get(HEADER_BYTES - 4..HEADER_BYTES)?.try_into().ok()?;
    let count = u64::from(u32::from_le_bytes(count_bytes));
    let expected = HEADER_BYTES as u64 + FACET_BYTES as u64 * count;
    let len = bytes.len() as u64;
    (len >= expected && len - expected < FACET_BYTES as u64).then_some(count)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn binary(count: u32, extra: usize) -> Vec<u8> {
        let mut b = vec![0u8; 80];
        b.extend(count.to_le_bytes());
        b.extend(vec![0u8; 50 * count as usize + extra]);
        b
    }

    #[test]
    fn formats_by_content() {
        let is = |bytes: &[u8]| sniff(bytes).map(|s| (s.format, s.triangles));
        assert_eq!(is(&binary(3, 0)), Some((Format::StlBinary, Some(3))));
        assert_eq!(is(&binary(3, 49)), Some((Format::StlBinary, Some(3))), "padding");
        assert_eq!(is(&binary(0, 0)), Some((Format::StlBinary, Some(0))));
        assert_eq!(is(b"\xEF\xBB\xBF  solid cube\n"), Some((Format::StlAscii, None)));
        assert_eq!(is(b"# made by hand\nv 0 0 0\nf 1 2 3\n"), Some((Format::Obj, None)));
        assert_eq!(is(b"PK\x03\x04rest"), Some((Format::ThreeMf, None)));
        assert_eq!(is(b"hello"), None);
        assert_eq!(is(b""), None);
    }
}
