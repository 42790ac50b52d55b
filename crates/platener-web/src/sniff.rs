//! What an upload is, from its content (never its name alone), checked in a few bytes before
//! the model is read: an empty file, a format platener does not read, or a binary STL whose
//! header promises more triangles than the server takes is refused without allocating for it.
//! The reading itself (`server::inspect`) follows, with the library's reader.

/// A model format, as far as the first bytes tell.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Kind {
    /// STL, binary or ASCII.
    Stl,
    /// Wavefront OBJ.
    Obj,
    /// 3MF (a ZIP).
    ThreeMf,
}

impl Kind {
    /// The file extension the library's reader goes by.
    pub fn extension(self) -> &'static str {
        match self {
            Kind::Stl => "stl",
            Kind::Obj => "obj",
            Kind::ThreeMf => "3mf",
        }
    }
}

/// Why an upload is refused before it is queued.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Refusal {
    /// Not a model format platener reads (`415`).
    Unsupported(String),
    /// A model format with a defect the header shows (`422`).
    Unreadable(String),
    /// More triangles (or, for 3MF, more unpacked bytes) than the server takes (`413`).
    TooLarge(String),
}

/// What the sniff found: the format and, for binary STL, the triangle count.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Sniffed {
    /// The format.
    pub kind: Kind,
    /// Triangles, when the header says (binary STL).
    pub triangles: Option<u64>,
}

/// How many bytes of text are looked at for ASCII STL and OBJ keywords.
const TEXT_WINDOW: usize = 64 * 1024;

/// The format of `bytes`, refusing an empty file, a binary STL without triangles and one whose
/// count exceeds `max_triangles` (before anything is allocated for them).
pub fn sniff(bytes: &[u8], max_triangles: u64) -> Result<Sniffed, Refusal> {
    if bytes.is_empty() {
        return Err(Refusal::Unreadable(
            "the file is empty (0 bytes); export the model again".into(),
        ));
    }
    if bytes.starts_with(b"PK\x03\x04") {
        return Ok(Sniffed {
            kind: Kind::ThreeMf,
            triangles: None,
        });
    }
    if let Some(count) = binary_stl_count(bytes) {
        if count == 0 {
            return Err(Refusal::Unreadable(
                "binary STL with a header and no triangles; export the model again".into(),
            ));
        }
        within_triangles(count, max_triangles)?;
        return Ok(Sniffed {
            kind: Kind::Stl,
            triangles: Some(count),
        });
    }
    let window = &bytes[..bytes.len().min(TEXT_WINDOW)];
    let text = String::from_utf8_lossy(window);
    if text.trim_start().to_ascii_lowercase().starts_with("solid") {
        return Ok(Sniffed {
            kind: Kind::Stl,
            triangles: None,
        });
    }
    let obj_lines = text
        .lines()
        .map(str::trim_start)
        .filter(|l| l.starts_with("v ") || l.starts_with("f ") || l.starts_with("vn ") || l.starts_with("o "))
        .count();
    if obj_lines > 0 && !window.contains(&0) {
        return Ok(Sniffed {
            kind: Kind::Obj,
            triangles: None,
        });
    }
    Err(Refusal::Unsupported(
        "the file is not an STL, OBJ or 3MF model (judged by its content); export it as one of these".into(),
    ))
}

/// Refuses a model of more than `max_triangles` triangles (`413`), whichever way it was counted
/// (a binary STL's header, or the triangles read from any format).
pub fn within_triangles(count: u64, max_triangles: u64) -> Result<(), Refusal> {
    if count > max_triangles {
        return Err(Refusal::TooLarge(format!(
            "the model has {count} triangles; this server converts models of at most {max_triangles}"
        )));
    }
    Ok(())
}

/// Longest message shown for a model the reader refused, in characters.
const MESSAGE_MAX: usize = 400;

/// A reader's message made safe to show: the reader quotes the offending line of the upload
/// (`line 89: unparseable number 'blah' …`), which helps a person find it but is the client's
/// text. Markup and quoting characters (`<`, `>`, `&`, `"`, `` ` ``, `\`), control characters
/// and invisible or direction-changing ones become `?`, and the message is cut at
/// [`MESSAGE_MAX`] characters, so no input reaches a page or a log unescaped whatever renders it.
pub fn safe_message(message: &str) -> String {
    let mut out: String = message
        .chars()
        .take(MESSAGE_MAX)
        .map(|c| if shown_as_is(c) { c } else { '?' })
        .collect();
    if message.chars().nth(MESSAGE_MAX).is_some() {
        out.push('…');
    }
    out
}

/// Whether a character of a message is shown as it is (see [`safe_message`]).
fn shown_as_is(c: char) -> bool {
    let invisible =
        matches!(c, '\u{200B}'..='\u{200F}' | '\u{2028}'..='\u{202E}' | '\u{2060}'..='\u{206F}' | '\u{FEFF}');
    !(c.is_control() || invisible || matches!(c, '<' | '>' | '&' | '"' | '`' | '\\'))
}

/// The triangle count of a binary STL: 80-byte header, a count, 50 bytes per triangle. The
/// size must match the count (up to one triangle of trailing bytes, which the reader notes
/// and ignores), whatever the header's first word says.
fn binary_stl_count(bytes: &[u8]) -> Option<u64> {
    let count_bytes: [u8; 4] = bytes.get(80..84)?.try_into().ok()?;
    let count = u64::from(u32::from_le_bytes(count_bytes));
    let expected = 84 + 50 * count;
    let len = bytes.len() as u64;
    (len >= expected && len - expected < 50).then_some(count)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn binary(count: u32, extra: usize) -> Vec<u8> {
        let mut b = vec![0u8; 80];
        b.extend_from_slice(&count.to_le_bytes());
        b.resize(84 + 50 * count as usize + extra, 0);
        b
    }

    #[test]
    fn formats_by_content() {
        let s = sniff(&binary(12, 0), 100).expect("binary STL");
        assert_eq!((s.kind, s.triangles), (Kind::Stl, Some(12)));
        assert_eq!(sniff(&binary(12, 1), 100).expect("trailing byte").triangles, Some(12));
        assert_eq!(
            sniff(b"solid x\nfacet normal 0 0 1\n", 100).expect("ascii").kind,
            Kind::Stl
        );
        assert_eq!(
            sniff(b"# cube\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", 100)
                .expect("obj")
                .kind,
            Kind::Obj
        );
        assert_eq!(sniff(b"PK\x03\x04rest", 100).expect("3mf").kind, Kind::ThreeMf);
        assert!(matches!(sniff(b"<html><script>", 100), Err(Refusal::Unsupported(_))));
        assert!(matches!(sniff(b"\x89PNG\r\n\x1a\n", 100), Err(Refusal::Unsupported(_))));
    }

    #[test]
    fn messages_show_no_markup_controls_or_invisible_characters() {
        let m = safe_message(
            "x.stl: line 3: unexpected text '<img src=x onerror=\"a()\">&\u{202E}\u{7}`\\' (expected facet)",
        );
        assert_eq!(
            m,
            "x.stl: line 3: unexpected text '?img src=x onerror=?a()???????' (expected facet)"
        );
        assert_eq!(safe_message("line 5: 12.5 µm … °"), "line 5: 12.5 µm … °");
        let long = "y".repeat(MESSAGE_MAX + 10);
        let cut = safe_message(&long);
        assert_eq!(cut.chars().count(), MESSAGE_MAX + 1);
        assert!(cut.ends_with('…'));
        assert!(within_triangles(100, 100).is_ok());
        assert!(matches!(within_triangles(101, 100), Err(Refusal::TooLarge(m)) if m.contains("101 triangles")));
    }

    #[test]
    fn defects_in_the_header_are_refused() {
        assert!(matches!(sniff(b"", 100), Err(Refusal::Unreadable(_))));
        assert!(matches!(sniff(&binary(0, 0), 100), Err(Refusal::Unreadable(_))));
        assert!(matches!(sniff(&binary(101, 0), 100), Err(Refusal::TooLarge(_))));
    }
}
