//! Reading server-sent events (the `text/event-stream` format) from a byte stream.
//!
//! Only what `GET …/events` needs: `event:` and `data:` fields, comments, and a blank line
//! ending an event. Lines end with `\n` or `\r\n` (a lone `\r` is not recognised).

/// One event: its type (`message` when the server named none) and its data lines joined.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Event {
    /// The `event:` field.
    pub name: String,
    /// The `data:` fields, joined with newlines.
    pub data: String,
}

/// Turns chunks of bytes, split anywhere, into events.
#[derive(Debug, Default)]
pub struct Parser {
    buffer: Vec<u8>,
    name: Option<String>,
    data: Option<String>,
}

impl Parser {
    /// Adds a chunk and returns the events it completed, in order.
    pub fn push(&mut self, chunk: &[u8]) -> Vec<Event> {
        self.buffer.extend_from_slice(chunk);
        let mut events = Vec::new();
        while let Some(end) = self.buffer.iter().position(|&b| b == b'\n') {
            let line: Vec<u8> = self.buffer.drain(..=end).collect();
            let line = String::from_utf8_lossy(&line[..end]);
            let line = line.strip_suffix('\r').unwrap_or(&line);
            if let Some(event) = self.line(line) {
                events.push(event);
            }
        }
        events
    }

    /// One line: a blank line ends the event (if it had any data or a name).
    fn line(&mut self, line: &str) -> Option<Event> {
        if line.is_empty() {
            let (name, data) = (self.name.take(), self.data.take());
            return (name.is_some() || data.is_some()).then(|| Event {
                name: name.unwrap_or_else(|| "message".into()),
                data: data.unwrap_or_default(),
            });
        }
        if line.starts_with(':') {
            return None;
        }
        let (field, value) = line.split_once(':').unwrap_or((line, ""));
        let value = value.strip_prefix(' ').unwrap_or(value);
        match field {
            "event" => self.name = Some(value.to_string()),
            "data" => match &mut self.data {
                Some(data) => {
                    data.push('\n');
                    data.push_str(value);
                }
                None => self.data = Some(value.to_string()),
            },
            _ => {}
        }
        None
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn events_split_across_chunks_and_line_endings() {
        let stream = b": hello\r\nevent: step\r\ndata: {\"name\":\"read\"}\r\n\r\nevent: done\ndata: a\ndata: b\n\ndata: plain\n\n";
        // Fed one byte at a time, the same events come out as when fed at once.
        let mut whole = Parser::default();
        let at_once = whole.push(stream);
        let mut bytewise = Parser::default();
        let split: Vec<Event> = stream
            .iter()
            .flat_map(|b| bytewise.push(std::slice::from_ref(b)))
            .collect();
        assert_eq!(at_once, split);
        assert_eq!(
            at_once,
            vec![
                Event {
                    name: "step".into(),
                    data: "{\"name\":\"read\"}".into()
                },
                Event {
                    name: "done".into(),
                    data: "a\nb".into()
                },
                Event {
                    name: "message".into(),
                    data: "plain".into()
                },
            ]
        );
    }

    #[test]
    fn an_unfinished_event_is_not_reported() {
        let mut parser = Parser::default();
        assert!(parser.push(b"event: done\ndata: x\n").is_empty());
        assert_eq!(
            parser.push(b"\n"),
            vec![Event {
                name: "done".into(),
                data: "x".into()
            }]
        );
    }
}
