//! ASCII STL: a line-oriented state machine over bytes.
//!
//! Why by hand: real files bend the grammar (any keyword case, CRLF, tabs, blank lines, missing
//! normals, several solids, no final `endsolid`) and a file of millions of lines must parse at
//! hundreds of MB/s, so there is no per-line allocation and no regex. Errors name the 1-based
//! line and quote it. The parser is fed whole lines, either a complete slice or chunks from a
//! stream, and keeps its state between chunks.

use std::io::Read;

use glam::DVec3;

use super::line::{CLASS, Line, is_binary_byte, plural, quote};
use super::number::parse_f64;
use super::record_normal;
use crate::read::{RawMesh, ReadErrorKind};

/// Streaming read size.
const CHUNK: usize = 256 * 1024;
/// Longest line accepted when streaming; no STL writer comes near it.
const MAX_LINE: usize = 1 << 20;

/// Why the ASCII parse stopped, with what the caller needs to consider a binary reading instead.
#[derive(Debug)]
pub(super) struct Failure {
    /// The error to report if the file is not binary after all.
    pub kind: ReadErrorKind,
    /// The offending line holds bytes no text file has (NUL, control characters).
    pub not_text: bool,
    /// Complete facets read before the failure.
    pub facets: usize,
}

#[derive(Debug, Clone, Copy, PartialEq)]
enum State {
    /// Before the first `solid` or after an `endsolid`.
    Outside,
    /// Inside `solid … endsolid`, between facets.
    Solid,
    /// Inside `facet … endfacet`.
    Facet,
}

/// The numbers on the rest of a line.
struct Numbers<const N: usize> {
    /// The first `N` numbers.
    values: [f64; N],
    /// How many numbers the line held.
    count: usize,
    /// The first NaN or infinite number, as written.
    non_finite: Option<String>,
}

/// The ASCII STL state machine.
pub(super) struct Parser {
    mesh: RawMesh,
    /// Number of the line being parsed (1-based); after the end, the number of lines.
    line: usize,
    state: State,
    /// Line of the current `solid` / `facet`.
    solid_line: usize,
    facet_line: usize,
    normal: DVec3,
    corners: [DVec3; 3],
    /// Vertices seen in the current facet (may exceed 3: reported at `endfacet`).
    vertices: usize,
    /// NUL padding after `endsolid` has been noted.
    padding_noted: bool,
    /// First `solid` line whose name holds binary bytes (a binary header starting with `solid`).
    binary_name: Option<usize>,
}

impl Parser {
    pub(super) fn new() -> Self {
        Parser {
            mesh: RawMesh::default(),
            line: 0,
            state: State::Outside,
            solid_line: 0,
            facet_line: 0,
            normal: DVec3::ZERO,
            corners: [DVec3::ZERO; 3],
            vertices: 0,
            padding_noted: false,
            binary_name: None,
        }
    }

    /// Parses every line of `buf`, which holds whole lines (only the last chunk of a file may
    /// end without a line break).
    pub(super) fn feed(&mut self, buf: &[u8]) -> Result<(), Failure> {
        let mut pos = 0;
        if self.line == 0 && buf.starts_with(b"\xEF\xBB\xBF") {
            pos = 3; // UTF-8 byte order mark
        }
        while pos < buf.len() {
            self.line += 1;
            let mut line = Line { buf, start: pos, pos };
            self.parse_line(&mut line)?;
            pos = line.end();
        }
        Ok(())
    }

    /// Ends the parse: checks that no facet is left open.
    pub(super) fn finish(mut self) -> Result<RawMesh, Failure> {
        if let Some(line) = self.binary_name
            && self.mesh.triangles.is_empty()
        {
            let message = "the 'solid' line holds bytes that are not text (damaged or binary file?)".into();
            return Err(self.syntax(line, message, true));
        }
        match self.state {
            State::Facet => {
                let message = format!(
                    "the file ends inside the facet that starts at line {}: it looks truncated; \
                     download or export it again",
                    self.facet_line
                );
                Err(self.syntax(self.line, message, false))
            }
            State::Solid => {
                self.mesh.notes.push(format!(
                    "no 'endsolid' for the solid at line {}: the file may be truncated, but all {} \
                     facets are complete",
                    self.solid_line,
                    self.mesh.triangles.len()
                ));
                Ok(self.mesh)
            }
            State::Outside => Ok(self.mesh),
        }
    }

    fn syntax(&self, line: usize, message: String, not_text: bool) -> Failure {
        self.failure(ReadErrorKind::Syntax { line, message }, not_text)
    }

    fn failure(&self, kind: ReadErrorKind, not_text: bool) -> Failure {
        Failure {
            kind,
            not_text,
            facets: self.mesh.triangles.len(),
        }
    }

    /// A syntax error on the current line; a line holding binary bytes is reported as such.
    fn error(&self, line: &Line<'_>, message: String) -> Failure {
        let text = line.text();
        if text.iter().any(|&b| is_binary_byte(b)) {
            let message = format!(
                "{} holds bytes that are not text (damaged or binary file?)",
                quote(text)
            );
            return self.syntax(self.line, message, true);
        }
        self.syntax(self.line, message, false)
    }

    fn unexpected(&self, line: &Line<'_>, expected: &str) -> Failure {
        let message = format!("unexpected text {} (expected {expected})", quote(line.text()));
        self.error(line, message)
    }

    /// Reads the numbers of the rest of the line, keeping the first `N`.
    fn numbers<const N: usize>(&self, line: &mut Line<'_>) -> Result<Numbers<N>, Failure> {
        let mut numbers = Numbers {
            values: [0.0; N],
            count: 0,
            non_finite: None,
        };
        loop {
            let token = line.token();
            if token.is_empty() {
                return Ok(numbers);
            }
            let Some(value) = parse_f64(token) else {
                let message = format!("unparseable number {} in {}", quote(token), quote(line.text()));
                return Err(self.error(line, message));
            };
            if !value.is_finite() && numbers.non_finite.is_none() {
                numbers.non_finite = Some(String::from_utf8_lossy(token).into_owned());
            }
            if let Some(slot) = numbers.values.get_mut(numbers.count) {
                *slot = value;
            }
            numbers.count += 1;
        }
    }

    fn parse_line(&mut self, line: &mut Line<'_>) -> Result<(), Failure> {
        let keyword = line.token();
        if keyword.is_empty() {
            return Ok(());
        }
        let is = |word: &str| keyword.eq_ignore_ascii_case(word.as_bytes());
        match self.state {
            State::Facet if is("vertex") => self.vertex(line),
            State::Facet if is("outer") => {
                let (next, rest) = (line.token(), line.token());
                if next.eq_ignore_ascii_case(b"loop") && rest.is_empty() {
                    Ok(())
                } else {
                    Err(self.unexpected(line, "'outer loop'"))
                }
            }
            State::Facet if is("endloop") => self.bare(line),
            State::Facet if is("endfacet") => {
                self.bare(line)?;
                self.end_facet(line)
            }
            State::Facet => {
                let expected = format!(
                    "'vertex', 'endloop' or 'endfacet' in the facet that starts at line {}",
                    self.facet_line
                );
                Err(self.unexpected(line, &expected))
            }
            State::Solid if is("facet") => self.facet(line),
            State::Solid if is("endsolid") => {
                self.state = State::Outside;
                Ok(())
            }
            State::Solid if is("solid") => {
                self.mesh.notes.push(format!(
                    "line {}: new 'solid' without 'endsolid' for the solid at line {}",
                    self.line, self.solid_line
                ));
                self.start_solid(line);
                Ok(())
            }
            State::Solid => Err(self.unexpected(line, "'facet' or 'endsolid'")),
            State::Outside if is("solid") => {
                self.start_solid(line);
                Ok(())
            }
            State::Outside if self.mesh.solids > 0 && line.text().iter().all(|&b| b == 0 || CLASS[b as usize] == 1) => {
                if !self.padding_noted {
                    self.padding_noted = true;
                    self.mesh
                        .notes
                        .push(format!("NUL padding after 'endsolid' (line {}) ignored", self.line));
                }
                Ok(())
            }
            State::Outside if self.mesh.solids > 0 => {
                Err(self.unexpected(line, "'solid' or the end of the file after 'endsolid'"))
            }
            State::Outside => Err(self.unexpected(line, "'solid'")),
        }
    }

    fn start_solid(&mut self, line: &Line<'_>) {
        if self.binary_name.is_none() && line.text().iter().any(|&b| is_binary_byte(b)) {
            self.binary_name = Some(self.line);
        }
        self.mesh.solids += 1;
        self.solid_line = self.line;
        self.state = State::Solid;
    }

    /// A keyword line that takes nothing after the keyword.
    fn bare(&self, line: &mut Line<'_>) -> Result<(), Failure> {
        if line.token().is_empty() {
            Ok(())
        } else {
            Err(self.unexpected(line, "nothing after the keyword"))
        }
    }

    fn facet(&mut self, line: &mut Line<'_>) -> Result<(), Failure> {
        self.facet_line = self.line;
        self.vertices = 0;
        self.state = State::Facet;
        let word = line.token();
        self.normal = if word.is_empty() {
            DVec3::ZERO
        } else if word.eq_ignore_ascii_case(b"normal") {
            // A non-finite normal is harmless (we use the winding): counted as a zero normal.
            match self.numbers::<3>(line)? {
                Numbers {
                    values: [x, y, z],
                    count: 3,
                    ..
                } => DVec3::new(x, y, z),
                Numbers { count: 0, .. } => DVec3::ZERO,
                Numbers { count, .. } => {
                    let message = format!(
                        "{} has {} (a normal has 3, or none)",
                        quote(line.text()),
                        plural(count, "number")
                    );
                    return Err(self.error(line, message));
                }
            }
        } else {
            return Err(self.unexpected(line, "'facet normal x y z'"));
        };
        Ok(())
    }

    fn vertex(&mut self, line: &mut Line<'_>) -> Result<(), Failure> {
        let numbers = self.numbers::<3>(line)?;
        if numbers.count != 3 {
            let mut message = format!(
                "vertex line {} has {} (a vertex has 3)",
                quote(line.text()),
                plural(numbers.count, "number")
            );
            if line.is_cut_off() {
                message.push_str("; the file ends here: it looks truncated, download or export it again");
            }
            return Err(self.error(line, message));
        }
        if let Some(value) = numbers.non_finite {
            let location = format!("line {}", self.line);
            return Err(self.failure(ReadErrorKind::NonFinite { location, value }, false));
        }
        let [x, y, z] = numbers.values;
        if let Some(corner) = self.corners.get_mut(self.vertices) {
            *corner = DVec3::new(x, y, z);
        }
        self.vertices = self.vertices.saturating_add(1);
        Ok(())
    }

    fn end_facet(&mut self, line: &Line<'_>) -> Result<(), Failure> {
        if self.vertices != 3 {
            let message = format!(
                "facet with {} vertices (a facet has exactly 3), in the facet that starts at line {}",
                self.vertices, self.facet_line
            );
            return Err(self.error(line, message));
        }
        record_normal(&mut self.mesh, self.normal, &self.corners);
        self.mesh.triangles.push(self.corners);
        self.state = State::Solid;
        Ok(())
    }
}

/// Parses an ASCII STL held in memory.
pub(super) fn parse_slice(bytes: &[u8]) -> Result<RawMesh, Failure> {
    let mut parser = Parser::new();
    parser.feed(bytes)?;
    parser.finish()
}

/// Parses an ASCII STL from a stream, a chunk of whole lines at a time.
pub(super) fn parse_reader<R: Read>(reader: &mut R) -> Result<RawMesh, Failure> {
    let mut parser = Parser::new();
    let mut buf = vec![0u8; CHUNK];
    let mut filled = 0;
    loop {
        if filled == buf.len() {
            if buf.len() >= MAX_LINE {
                let not_text = buf.iter().any(|&b| is_binary_byte(b));
                let message = format!("line longer than {MAX_LINE} bytes: this is not an ASCII STL file");
                return Err(parser.syntax(parser.line + 1, message, not_text));
            }
            buf.resize(buf.len() * 2, 0);
        }
        let read = loop {
            match reader.read(buf.get_mut(filled..).unwrap_or_default()) {
                Ok(n) => break n,
                Err(e) if e.kind() == std::io::ErrorKind::Interrupted => continue,
                Err(e) => return Err(parser.failure(super::io_error(e), false)),
            }
        };
        if read == 0 {
            parser.feed(buf.get(..filled).unwrap_or_default())?;
            return parser.finish();
        }
        let new = filled..filled + read;
        filled += read;
        if let Some(last) = buf.get(new.clone()).and_then(|b| b.iter().rposition(|&b| b == b'\n')) {
            let cut = new.start + last + 1;
            parser.feed(buf.get(..cut).unwrap_or_default())?;
            buf.copy_within(cut..filled, 0);
            filled -= cut;
        }
    }
}
