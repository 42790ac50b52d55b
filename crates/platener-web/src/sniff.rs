//! What an upload is, from its content (never its name alone), checked in a few bytes before
//! the model is read: an empty file, a format platener does not read, or a binary STL whose
//! header promises more triangles than the server takes is refused without allocating for it.
//! The reading itself (`server::inspect`) follows, with the library's reader.

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

pub use platener::read::Sniffed;

/// The format of `bytes` by the library's rule (`platener::read::sniff`), refusing an empty
/// file, a format platener does not read, a binary STL without triangles and one whose count
/// exceeds `max_triangles` (before anything is allocated for them).
pub fn sniff(bytes: &[u8], max_triangles: u64) -> Result<Sniffed, Refusal> {
    if bytes.is_empty() {
        return Err(Refusal::Unreadable(
            "the file is empty (0 bytes); export the model again".into(),
        ));
    }
    let sniffed = platener::read::sniff(bytes).ok_or_else(|| {
        Refusal::Unsupported(
            "the file is not an STL, OBJ or 3MF model (judged by its content); export it as one of these".into(),
        )
    })?;
    match sniffed.triangles {
        Some(0) => Err(Refusal::Unreadable(
            "binary STL with a header and no triangles; export the model again".into(),
        )),
        Some(count) => within_triangles(count, max_triangles).map(|()| sniffed),
        None => Ok(sniffed),
    }
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

#[cfg(test)]
mod tests {
    use super::*;
    use platener::read::Format;

    fn binary(count: u32, extra: usize) -> Vec<u8> {
        let mut b = vec![0u8; 80];
        b.extend_from_slice(&count.to_le_bytes());
        b.resize(84 + 50 * count as usize + extra, 0);
        b
    }

    #[test]
    fn formats_by_content() {
        let s = sniff(&binary(12, 0), 100).expect("binary STL");
        assert_eq!((s.format, s.triangles), (Format::StlBinary, Some(12)));
        assert_eq!(sniff(&binary(12, 1), 100).expect("trailing byte").triangles, Some(12));
        assert_eq!(
            sniff(b"solid x\nfacet normal 0 0 1\n", 100).expect("ascii").format,
            Format::StlAscii
        );
        assert_eq!(
            sniff(b"# cube\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", 100)
                .expect("obj")
                .format,
            Format::Obj
        );
        assert_eq!(sniff(b"PK\x03\x04rest", 100).expect("3mf").format, Format::ThreeMf);
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
