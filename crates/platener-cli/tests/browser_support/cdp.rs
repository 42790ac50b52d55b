//! The Chrome DevTools Protocol over `--remote-debugging-pipe`: Chromium reads commands from
//! its file descriptor 3 and writes answers and events to 4, each message JSON ended by a NUL.
//! A pipe needs no WebSocket, no port and no client crate, so the browser tests add nothing
//! to the build (docs/decisions.md).

use std::collections::HashMap;
use std::io::{BufRead, BufReader, Write};
use std::path::Path;
use std::process::{Child, ChildStdin, Command, Stdio};
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::{Arc, Condvar, Mutex};
use std::time::{Duration, Instant};

use serde_json::{Value, json};

/// What the reader thread has received so far.
#[derive(Default)]
struct Inbox {
    replies: HashMap<u64, Value>,
    events: Vec<Value>,
    closed: bool,
}

type Shared = Arc<(Mutex<Inbox>, Condvar)>;

/// A running Chromium and its protocol pipe; the browser is killed when dropped.
pub struct Cdp {
    child: Child,
    writer: Mutex<ChildStdin>,
    next_id: AtomicU64,
    inbox: Shared,
}

impl Cdp {
    /// Starts `chromium` with `flags`. The shell moves the child's stdin and stdout pipes to
    /// descriptors 3 and 4 (Rust's `Command` cannot name other descriptors without unsafe
    /// code, which the workspace forbids); Chromium's own output goes to `log`.
    pub fn launch(chromium: &Path, flags: &[String], log: &Path) -> std::io::Result<Cdp> {
        let log = std::fs::File::create(log)?;
        let mut child = Command::new("sh")
            .arg("-c")
            .arg(r#"exec "$@" 3<&0 4>&1 0</dev/null 1>&2"#)
            .arg("sh")
            .arg(chromium)
            .args(flags)
            .stdin(Stdio::piped())
            .stdout(Stdio::piped())
            .stderr(log)
            .spawn()?;
        let writer = child.stdin.take().expect("stdin piped");
        let reader = child.stdout.take().expect("stdout piped");
        let inbox: Shared = Arc::default();
        let shared = Arc::clone(&inbox);
        std::thread::spawn(move || read_messages(BufReader::new(reader), &shared));
        Ok(Cdp {
            child,
            writer: Mutex::new(writer),
            next_id: AtomicU64::new(1),
            inbox,
        })
    }

    /// Sends one command (to a page's `session`, or to the browser) and waits at most
    /// `patience` for its answer: the result, or the protocol's error message.
    pub fn call(
        &self,
        session: Option<&str>,
        method: &str,
        params: Value,
        patience: Duration,
    ) -> Result<Value, String> {
        let id = self.next_id.fetch_add(1, Ordering::Relaxed);
        let mut msg = json!({ "id": id, "method": method, "params": params });
        if let Some(s) = session {
            msg["sessionId"] = json!(s);
        }
        let mut bytes = serde_json::to_vec(&msg).map_err(|e| e.to_string())?;
        bytes.push(0);
        {
            let mut w = self.writer.lock().map_err(|_| "writer poisoned".to_string())?;
            w.write_all(&bytes)
                .and_then(|()| w.flush())
                .map_err(|e| format!("{method}: {e}"))?;
        }
        let (lock, cvar) = &*self.inbox;
        let start = Instant::now();
        let mut inbox = lock.lock().map_err(|_| "inbox poisoned".to_string())?;
        loop {
            if let Some(reply) = inbox.replies.remove(&id) {
                return match reply.get("error") {
                    Some(e) => Err(format!("{method}: {e}")),
                    None => Ok(reply.get("result").cloned().unwrap_or(Value::Null)),
                };
            }
            if inbox.closed {
                return Err(format!("{method}: the browser closed its pipe"));
            }
            let left = patience
                .checked_sub(start.elapsed())
                .ok_or(format!("{method}: no answer in {patience:?}"))?;
            inbox = cvar
                .wait_timeout(inbox, left)
                .map_err(|_| "inbox poisoned".to_string())?
                .0;
        }
    }

    /// Every event received so far (method, params, sessionId), oldest first.
    pub fn events(&self) -> Vec<Value> {
        self.inbox.0.lock().map(|i| i.events.clone()).unwrap_or_default()
    }

    /// How many events have arrived: a cursor for `events_after`.
    pub fn event_count(&self) -> usize {
        self.inbox.0.lock().map(|i| i.events.len()).unwrap_or_default()
    }

    /// Waits at most `patience` for an event after `cursor` that `wanted` accepts.
    pub fn wait_event(&self, cursor: usize, patience: Duration, wanted: impl Fn(&Value) -> bool) -> Option<Value> {
        let (lock, cvar) = &*self.inbox;
        let start = Instant::now();
        let mut inbox = lock.lock().ok()?;
        loop {
            if let Some(e) = inbox.events.iter().skip(cursor).find(|e| wanted(e)) {
                return Some(e.clone());
            }
            let left = patience.checked_sub(start.elapsed())?;
            if inbox.closed {
                return None;
            }
            inbox = cvar.wait_timeout(inbox, left).ok()?.0;
        }
    }
}

impl Drop for Cdp {
    fn drop(&mut self) {
        // The shell exec'd Chromium, so this is the browser's own process; its helpers
        // (renderer, GPU, zygote) exit when their parent's pipes close.
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

/// The reader thread: splits the pipe at NULs, files answers by id and keeps events.
fn read_messages(mut reader: impl BufRead, inbox: &Shared) {
    let (lock, cvar) = &**inbox;
    let mut buf = Vec::new();
    loop {
        buf.clear();
        let n = reader.read_until(0, &mut buf).unwrap_or(0);
        if n == 0 {
            break;
        }
        if buf.last() == Some(&0) {
            buf.pop();
        }
        let Ok(msg) = serde_json::from_slice::<Value>(&buf) else {
            continue;
        };
        let Ok(mut i) = lock.lock() else { break };
        match msg.get("id").and_then(Value::as_u64) {
            Some(id) => {
                i.replies.insert(id, msg);
            }
            None => i.events.push(msg),
        }
        cvar.notify_all();
    }
    if let Ok(mut i) = lock.lock() {
        i.closed = true;
    }
    cvar.notify_all();
}
