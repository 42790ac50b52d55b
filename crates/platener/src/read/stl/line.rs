//! Lines and tokens of ASCII STL, and quoting them in error messages.
//!
//! Why a byte table: tokenizing is the inner loop of the ASCII reader, and one table lookup per
//! byte is the cheapest way to split tokens at blanks and lines at `\n` (CR counts as a blank,
//! so CRLF files need nothing special).

/// Longest quote of a line in an error message.
const QUOTE_MAX: usize = 100;

/// Byte classes: 0 = part of a token, 1 = blank, 2 = end of line.
pub(super) const CLASS: [u8; 256] = {
    let mut table = [0u8; 256];
    table[b' ' as usize] = 1;
    table[b'\t' as usize] = 1;
    table[b'\r' as usize] = 1;
    table[0x0b] = 1;
    table[0x0c] = 1;
    table[b'\n' as usize] = 2;
    table
};

/// Bytes that never occur in a text file: they mark binary data.
pub(super) fn is_binary_byte(b: u8) -> bool {
    matches!(b, 0..=8 | 0x0e..=0x1f | 0x7f)
}

/// One line of the input: its bytes run from `start` to the next `\n` (or the end).
pub(super) struct Line<'a> {
    pub(super) buf: &'a [u8],
    pub(super) start: usize,
    pub(super) pos: usize,
}

impl<'a> Line<'a> {
    /// The next blank-separated token of this line; empty at the end of the line.
    pub(super) fn token(&mut self) -> &'a [u8] {
        let buf = self.buf;
        let mut i = self.pos;
        while i < buf.len() && CLASS[buf[i] as usize] == 1 {
            i += 1;
        }
        let begin = i;
        while i < buf.len() && CLASS[buf[i] as usize] == 0 {
            i += 1;
        }
        self.pos = i;
        &buf[begin..i]
    }

    /// Index just after this line's `\n` (or the end of the buffer).
    pub(super) fn end(&self) -> usize {
        match self
            .buf
            .get(self.pos..)
            .and_then(|rest| rest.iter().position(|&b| b == b'\n'))
        {
            Some(offset) => self.pos + offset + 1,
            None => self.buf.len(),
        }
    }

    /// The line without its line break and surrounding blanks.
    pub(super) fn text(&self) -> &'a [u8] {
        let end = self.end();
        let line = self.buf.get(self.start..end).unwrap_or_default();
        line.trim_ascii()
    }

    /// Whether the file ends with this line, which has no line break (a cut-off file).
    pub(super) fn is_cut_off(&self) -> bool {
        !self.text().is_empty() && self.buf.get(self.start..).is_some_and(|r| !r.contains(&b'\n'))
    }
}

/// Quotes text for an error message, shortened when long.
pub(super) fn quote(text: &[u8]) -> String {
    let shown = text.get(..QUOTE_MAX).unwrap_or(text);
    let mut quoted = format!("'{}", String::from_utf8_lossy(shown));
    if shown.len() < text.len() {
        quoted.push('…');
    }
    quoted.push('\'');
    quoted
}

/// `1 number`, `2 numbers`.
pub(super) fn plural(count: usize, noun: &str) -> String {
    if count == 1 {
        format!("1 {noun}")
    } else {
        format!("{count} {noun}s")
    }
}
