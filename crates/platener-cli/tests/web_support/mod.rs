//! A real `platener serve` for tests: the built binary on 127.0.0.1 at a free port, SQLite in a
//! temp dir, its worker processes the same binary; and a minimal HTTP/1.1 client (one request
//! per connection) so the tests see exactly the bytes the server sends.

#![allow(dead_code, reason = "each test file uses a part")]

pub mod plans;

use std::io::{BufRead, BufReader, Read, Write};
use std::net::TcpStream;
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::sync::mpsc;
use std::time::{Duration, Instant};

use serde_json::Value;

/// Every wait in these tests ends with a failure after this long (never a timed assertion:
/// it only stops a test that would hang).
pub const PATIENCE: Duration = Duration::from_secs(90);

/// A running server; killed (SIGKILL) when dropped.
pub struct Server {
    pub child: Child,
    pub addr: String,
    pub data: PathBuf,
}

impl Server {
    /// Starts `platener serve` on `data` with `args` and `env`, and waits for its address.
    pub fn start(data: &Path, args: &[&str], env: &[(&str, &str)]) -> Server {
        let mut cmd = Command::new(env!("CARGO_BIN_EXE_platener"));
        cmd.args(["serve", "--addr", "127.0.0.1:0", "--data"])
            .arg(data)
            .args(args)
            .stdout(Stdio::piped())
            .stderr(Stdio::null());
        for (k, v) in env {
            cmd.env(k, v);
        }
        let mut child = cmd.spawn().expect("platener serve starts");
        let stdout = child.stdout.take().expect("stdout piped");
        let (tx, rx) = mpsc::channel();
        std::thread::spawn(move || {
            let mut line = String::new();
            let _ = BufReader::new(stdout).read_line(&mut line);
            let _ = tx.send(line);
        });
        let line = rx.recv_timeout(PATIENCE).expect("the server prints its address");
        let addr = line
            .trim()
            .strip_prefix("platener: serving on http://")
            .unwrap_or_else(|| panic!("unexpected first line {line:?}"))
            .to_string();
        Server {
            child,
            addr,
            data: data.to_path_buf(),
        }
    }

    /// Sends one request; the answer.
    pub fn request(&self, method: &str, path: &str, headers: &[(&str, &str)], body: &[u8]) -> Response {
        request(&self.addr, method, path, headers, body)
    }

    /// GET.
    pub fn get(&self, path: &str) -> Response {
        self.request("GET", path, &[], b"")
    }

    /// Uploads `model` as the form field `model` named `name`, with settings fields.
    pub fn upload(&self, name: &str, model: &[u8], fields: &[(&str, &str)]) -> Response {
        let (content_type, body) = multipart(name, model, fields);
        self.request("POST", "/api/conversions", &[("Content-Type", &content_type)], &body)
    }

    /// Polls a conversion until `done(status)` holds; its JSON.
    pub fn wait_for(&self, id: &str, done: impl Fn(&str) -> bool) -> Value {
        let start = Instant::now();
        loop {
            let c = self.get(&format!("/api/conversions/{id}")).json();
            if done(c["status"].as_str().unwrap_or_default()) {
                return c;
            }
            assert!(start.elapsed() < PATIENCE, "conversion {id} stuck: {c}");
            std::thread::sleep(Duration::from_millis(100));
        }
    }

    /// Waits until a conversion has ended (done, failed or cancelled).
    pub fn wait_ended(&self, id: &str) -> Value {
        self.wait_for(id, |s| matches!(s, "done" | "failed" | "cancelled"))
    }

    /// The process ids of the server's children (its workers).
    pub fn worker_pids(&self) -> Vec<u32> {
        children_of(self.child.id())
    }

    /// Resident memory of the server process, kB.
    pub fn rss_kb(&self) -> u64 {
        let status = std::fs::read_to_string(format!("/proc/{}/status", self.child.id())).unwrap_or_default();
        status
            .lines()
            .find_map(|l| l.strip_prefix("VmRSS:"))
            .and_then(|v| v.trim().trim_end_matches("kB").trim().parse().ok())
            .unwrap_or(0)
    }

    /// Sends SIGTERM and waits for the server to exit; its exit status success.
    pub fn terminate(mut self) -> bool {
        signal(self.child.id(), "TERM");
        let start = Instant::now();
        loop {
            if let Some(status) = self.child.try_wait().expect("wait") {
                return status.success();
            }
            assert!(start.elapsed() < PATIENCE, "the server did not stop on SIGTERM");
            std::thread::sleep(Duration::from_millis(50));
        }
    }
}

impl Drop for Server {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

/// Sends a signal to one process by id.
pub fn signal(pid: u32, name: &str) {
    let status = Command::new("kill")
        .arg(format!("-{name}"))
        .arg(pid.to_string())
        .status()
        .expect("kill runs");
    assert!(status.success(), "kill -{name} {pid}");
}

/// Processes whose parent is `pid` (from /proc).
pub fn children_of(pid: u32) -> Vec<u32> {
    let mut pids = Vec::new();
    for entry in std::fs::read_dir("/proc").into_iter().flatten().flatten() {
        let Ok(child) = entry.file_name().to_string_lossy().parse::<u32>() else {
            continue;
        };
        let stat = std::fs::read_to_string(entry.path().join("stat")).unwrap_or_default();
        // Fields after the command name (which may hold spaces) in parentheses.
        let after = stat.rsplit_once(')').map(|(_, r)| r).unwrap_or_default();
        let ppid = after.split_whitespace().nth(1).and_then(|p| p.parse::<u32>().ok());
        if ppid == Some(pid) && !after.trim_start().starts_with('Z') {
            pids.push(child);
        }
    }
    pids.sort_unstable();
    pids
}

/// A multipart form with the model and settings fields.
pub fn multipart(name: &str, model: &[u8], fields: &[(&str, &str)]) -> (String, Vec<u8>) {
    let boundary = "platenertestboundary7d3a";
    let mut body = Vec::new();
    for (k, v) in fields {
        body.extend_from_slice(
            format!("--{boundary}\r\nContent-Disposition: form-data; name=\"{k}\"\r\n\r\n{v}\r\n").as_bytes(),
        );
    }
    body.extend_from_slice(
        format!(
            "--{boundary}\r\nContent-Disposition: form-data; name=\"model\"; filename=\"{name}\"\r\n\
             Content-Type: application/octet-stream\r\n\r\n"
        )
        .as_bytes(),
    );
    body.extend_from_slice(model);
    body.extend_from_slice(format!("\r\n--{boundary}--\r\n").as_bytes());
    (format!("multipart/form-data; boundary={boundary}"), body)
}

/// An answer.
#[derive(Debug)]
pub struct Response {
    pub status: u16,
    /// Header names in lower case.
    pub headers: Vec<(String, String)>,
    pub body: Vec<u8>,
}

impl Response {
    /// A header's value.
    pub fn header(&self, name: &str) -> Option<&str> {
        self.headers.iter().find(|(k, _)| k == name).map(|(_, v)| v.as_str())
    }

    /// The body as JSON (panics with the body when it is not).
    pub fn json(&self) -> Value {
        serde_json::from_slice(&self.body)
            .unwrap_or_else(|e| panic!("not JSON ({e}): {}", String::from_utf8_lossy(&self.body)))
    }

    /// The body as text.
    pub fn text(&self) -> String {
        String::from_utf8_lossy(&self.body).into_owned()
    }

    /// Asserts an API error: status, code, and a message without markup.
    pub fn assert_error(&self, status: u16, code: &str) {
        let j = self.json();
        assert_eq!(self.status, status, "{j}");
        assert_eq!(j["error"]["code"], code, "{j}");
        let message = j["error"]["message"].as_str().expect("a message");
        assert!(!message.is_empty() && !message.contains('<'), "{message}");
        assert_eq!(j.as_object().map(|o| o.len()), Some(1), "only `error`: {j}");
    }
}

/// One HTTP/1.1 request on its own connection (`Connection: close`), read to the end.
pub fn request(addr: &str, method: &str, path: &str, headers: &[(&str, &str)], body: &[u8]) -> Response {
    let mut stream = TcpStream::connect(addr).expect("connect");
    stream.set_read_timeout(Some(PATIENCE)).expect("timeout");
    let mut head = format!(
        "{method} {path} HTTP/1.1\r\nHost: {addr}\r\nConnection: close\r\nContent-Length: {}\r\n",
        body.len()
    );
    for (k, v) in headers {
        head.push_str(&format!("{k}: {v}\r\n"));
    }
    head.push_str("\r\n");
    stream.write_all(head.as_bytes()).expect("send head");
    // The server may answer (413) and close before the body is sent.
    let _ = stream.write_all(body);
    let mut raw = Vec::new();
    stream.read_to_end(&mut raw).expect("read answer");
    parse(&raw)
}

/// Splits an HTTP/1.1 answer into status, headers and (de-chunked) body.
pub fn parse(raw: &[u8]) -> Response {
    let split = raw.windows(4).position(|w| w == b"\r\n\r\n").expect("a header block");
    let head = String::from_utf8_lossy(&raw[..split]).into_owned();
    let mut lines = head.split("\r\n");
    let status = lines
        .next()
        .and_then(|l| l.split_whitespace().nth(1))
        .and_then(|s| s.parse().ok())
        .expect("a status line");
    let headers: Vec<(String, String)> = lines
        .filter_map(|l| l.split_once(':'))
        .map(|(k, v)| (k.trim().to_ascii_lowercase(), v.trim().to_string()))
        .collect();
    let mut body = raw[split + 4..].to_vec();
    if headers
        .iter()
        .any(|(k, v)| k == "transfer-encoding" && v.contains("chunked"))
    {
        body = dechunk(&body);
    }
    Response { status, headers, body }
}

fn dechunk(mut data: &[u8]) -> Vec<u8> {
    let mut out = Vec::new();
    while let Some(eol) = data.windows(2).position(|w| w == b"\r\n") {
        let size = usize::from_str_radix(String::from_utf8_lossy(&data[..eol]).trim(), 16).unwrap_or(0);
        if size == 0 {
            break;
        }
        let start = eol + 2;
        out.extend_from_slice(&data[start..(start + size).min(data.len())]);
        data = &data[(start + size + 2).min(data.len())..];
    }
    out
}

/// The server-sent events of a conversion until its last one: (event, data JSON) pairs.
pub fn events(addr: &str, id: &str) -> Vec<(String, Value)> {
    let r = request(addr, "GET", &format!("/api/conversions/{id}/events"), &[], b"");
    assert_eq!(r.status, 200, "{}", r.text());
    assert!(
        r.header("content-type")
            .is_some_and(|c| c.starts_with("text/event-stream"))
    );
    let mut out = Vec::new();
    for block in r.text().split("\n\n") {
        let mut event = None;
        let mut data = None;
        for line in block.lines() {
            if let Some(e) = line.strip_prefix("event: ") {
                event = Some(e.to_string());
            } else if let Some(d) = line.strip_prefix("data: ") {
                data = serde_json::from_str(d).ok();
            }
        }
        if let (Some(e), Some(d)) = (event, data) {
            out.push((e, d));
        }
    }
    out
}

/// The example box of the repository.
pub fn example_box() -> Vec<u8> {
    std::fs::read(Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/box-3mm.stl"))
        .expect("examples/box-3mm.stl")
}

/// The database a test's server keeps its jobs in; tests of the API run on both.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Backend {
    /// SQLite in the server's data folder (`serve`'s default).
    Sqlite,
    /// A fresh database of the test's own in the test binary's throwaway PostgreSQL cluster.
    Postgres,
}

impl Backend {
    /// `serve`'s flags for this database; `None` (after the harness printed why) when
    /// PostgreSQL is not installed and `PLATENER_REQUIRE_POSTGRES=1` is not set, so the test
    /// skips; any other failure to get a database panics.
    pub fn args(self) -> Option<Vec<String>> {
        match self {
            Backend::Sqlite => Some(Vec::new()),
            Backend::Postgres => {
                let cluster = platener_testpg::Cluster::for_tests()?;
                let db = cluster
                    .fresh_database()
                    .expect("a PostgreSQL database of this test's own");
                Some(vec!["--database".into(), db.url])
            }
        }
    }
}

impl Server {
    /// [`Server::start`] on `backend`; `None` when the backend is skipped ([`Backend::args`]).
    pub fn start_on(backend: Backend, data: &Path, args: &[&str], env: &[(&str, &str)]) -> Option<Server> {
        let mut all = backend.args()?;
        all.extend(args.iter().map(|a| (*a).to_string()));
        let all: Vec<&str> = all.iter().map(String::as_str).collect();
        Some(Server::start(data, &all, env))
    }
}
