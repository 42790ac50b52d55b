//! Debian's Chromium driven headless over the DevTools protocol (`cdp`), for the web page's
//! tests (issue 18): launching it, one tab (`Page`) with clicks, hovers, files, downloads,
//! screenshots, and every console error or failed request it saw; pixel checks in `pixels`.

#![allow(dead_code, reason = "each test uses a part")]

pub mod cdp;
pub mod models;
pub mod pixels;

use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use base64::Engine as _;
use serde_json::{Value, json};

use cdp::Cdp;

/// Every wait ends with a failure after this long: it only stops a test that would hang.
pub const PATIENCE: Duration = Duration::from_secs(90);

/// Where the screenshots of each state go (described in the closing note of issue 18).
pub fn shots_dir() -> PathBuf {
    let target = std::env::var_os("CARGO_TARGET_DIR")
        .map(PathBuf::from)
        .unwrap_or_else(|| Path::new(env!("CARGO_MANIFEST_DIR")).join("../../target"));
    target.join("browser-shots")
}

/// Debian's Chromium (or `PLATENER_CHROMIUM`). None when there is none, after saying so,
/// unless `PLATENER_REQUIRE_CHROMIUM=1` (CI), where a missing browser fails the test.
pub fn chromium() -> Option<PathBuf> {
    let candidates = std::env::var_os("PLATENER_CHROMIUM")
        .map(PathBuf::from)
        .into_iter()
        .chain(["/usr/bin/chromium", "/usr/bin/chromium-browser"].map(PathBuf::from));
    for c in candidates {
        if c.is_file() {
            return Some(c);
        }
    }
    assert!(
        std::env::var("PLATENER_REQUIRE_CHROMIUM").as_deref() != Ok("1"),
        "PLATENER_REQUIRE_CHROMIUM=1 but no Chromium: install Debian's `chromium` package"
    );
    eprintln!("skipped: no Chromium (apt-get install chromium, or set PLATENER_CHROMIUM)");
    None
}

/// A headless Chromium with its own empty profile and download folder.
pub struct Browser {
    pub cdp: Cdp,
    pub profile: tempfile::TempDir,
}

impl Browser {
    /// Starts the browser at 1280×720; WebGL through SwiftShader (no GPU here).
    pub fn launch(chromium: &Path) -> Browser {
        let profile = tempfile::tempdir().expect("profile dir");
        let flags: Vec<String> = [
            "--headless",
            "--no-sandbox",
            "--disable-gpu",
            "--use-angle=swiftshader",
            "--enable-unsafe-swiftshader",
            "--disable-quic",
            "--no-first-run",
            "--no-default-browser-check",
            "--disable-background-networking",
            "--disable-component-update",
            "--disable-sync",
            "--disable-extensions",
            "--mute-audio",
            "--hide-scrollbars",
            "--window-size=1280,720",
            // Headless Chromium reports `(hover: none)` and no pointer; a desktop has a mouse
            // (hover 2 = hover, pointer 4 = fine), so hover-only styles apply as for people.
            "--blink-settings=primaryHoverType=2,availableHoverTypes=2,primaryPointerType=4,availablePointerTypes=4",
            "--remote-debugging-pipe",
        ]
        .iter()
        .map(|s| s.to_string())
        .chain([format!("--user-data-dir={}", profile.path().join("profile").display())])
        .collect();
        let log = profile.path().join("chromium.log");
        let cdp = Cdp::launch(chromium, &flags, &log).expect("chromium starts");
        cdp.call(None, "Browser.getVersion", json!({}), PATIENCE)
            .unwrap_or_else(|e| panic!("chromium answers: {e}; its log: {}", read_log(&log)));
        Browser { cdp, profile }
    }

    /// Opens a tab on `url` and waits until the document has loaded.
    pub fn open(&self, url: &str) -> Page<'_> {
        let target = self.call(None, "Target.createTarget", json!({ "url": "about:blank" }));
        let attached = self.call(
            None,
            "Target.attachToTarget",
            json!({ "targetId": target["targetId"], "flatten": true }),
        );
        let session = attached["sessionId"].as_str().expect("a session").to_string();
        let page = Page {
            browser: self,
            session,
            cursor: self.cdp.event_count(),
        };
        for domain in ["Page", "Runtime", "Log", "Network", "DOM"] {
            page.call(&format!("{domain}.enable"), json!({}));
        }
        page.call(
            "Emulation.setDeviceMetricsOverride",
            json!({ "width": 1280, "height": 720, "deviceScaleFactor": 1, "mobile": false }),
        );
        page.goto(url);
        page
    }

    /// Lets downloads of every tab go to `dir`, under the names the server suggests.
    pub fn download_to(&self, dir: &Path) {
        self.call(
            None,
            "Browser.setDownloadBehavior",
            json!({ "behavior": "allow", "downloadPath": dir, "eventsEnabled": true }),
        );
    }

    fn call(&self, session: Option<&str>, method: &str, params: Value) -> Value {
        self.cdp
            .call(session, method, params, PATIENCE)
            .unwrap_or_else(|e| panic!("{e}"))
    }

    /// Waits for a download to complete after event `cursor`; its path in `dir`.
    pub fn wait_download(&self, cursor: usize, dir: &Path) -> PathBuf {
        let begin = self
            .cdp
            .wait_event(cursor, PATIENCE, |e| e["method"] == "Browser.downloadWillBegin")
            .expect("a download begins");
        let guid = begin["params"]["guid"].clone();
        let done = self
            .cdp
            .wait_event(cursor, PATIENCE, |e| {
                e["method"] == "Browser.downloadProgress"
                    && e["params"]["guid"] == guid
                    && e["params"]["state"] != "inProgress"
            })
            .expect("the download ends");
        assert_eq!(done["params"]["state"], "completed", "{done}");
        let name = begin["params"]["suggestedFilename"].as_str().expect("a file name");
        dir.join(name)
    }
}

fn read_log(path: &Path) -> String {
    std::fs::read_to_string(path).unwrap_or_default()
}

/// One tab, attached by its own protocol session.
pub struct Page<'b> {
    pub browser: &'b Browser,
    pub session: String,
    /// Events before this one belong to other tabs' setup.
    cursor: usize,
}

/// An element's box in CSS pixels of the viewport.
#[derive(Debug, Clone, Copy)]
pub struct Rect {
    pub x: f64,
    pub y: f64,
    pub width: f64,
    pub height: f64,
}

impl Rect {
    /// The middle.
    pub fn center(&self) -> (f64, f64) {
        (self.x + self.width / 2.0, self.y + self.height / 2.0)
    }
}

impl Page<'_> {
    /// One protocol command on this tab; panics with the protocol's message on error.
    pub fn call(&self, method: &str, params: Value) -> Value {
        self.browser.call(Some(&self.session), method, params)
    }

    /// Navigates and waits for the load event's document state.
    pub fn goto(&self, url: &str) {
        let r = self.call("Page.navigate", json!({ "url": url }));
        assert!(r.get("errorText").is_none(), "{url}: {r}");
        self.wait_until("document.readyState === 'complete'", "the page loads");
    }

    /// Evaluates `js` (promises awaited); its value as JSON. Panics with the exception.
    pub fn eval(&self, js: &str) -> Value {
        let r = self.call(
            "Runtime.evaluate",
            json!({ "expression": js, "awaitPromise": true, "returnByValue": true, "userGesture": true }),
        );
        if let Some(ex) = r.get("exceptionDetails") {
            panic!(
                "{js}\nthrew: {}",
                ex["exception"]["description"].as_str().unwrap_or(&ex.to_string())
            );
        }
        r["result"]["value"].clone()
    }

    /// Polls `js` every 50 ms until it is truthy; its value. Fails with `what`, the page's
    /// state and its problems after `PATIENCE`, or at once when the page has a problem.
    pub fn wait_until(&self, js: &str, what: &str) -> Value {
        let start = Instant::now();
        loop {
            let problems = self.problems();
            assert!(
                problems.is_empty(),
                "while waiting for {what}: {problems:#?}; state {}",
                self.state()
            );
            let v = self.eval(js);
            if !matches!(v, Value::Null | Value::Bool(false)) && v != json!(0) && v != json!("") {
                return v;
            }
            assert!(
                start.elapsed() < PATIENCE,
                "waited {PATIENCE:?} for {what} ({js}); state {}; problems {:?}",
                self.state(),
                self.problems()
            );
            std::thread::sleep(Duration::from_millis(50));
        }
    }

    /// `window.platener.state` (the page's read-only view for tests), or null.
    pub fn state(&self) -> Value {
        self.eval("JSON.parse(JSON.stringify((window.platener && window.platener.state) || null))")
    }

    /// The box of the first element matching the CSS selector, scrolled into view if it is
    /// not wholly in it (scrolling under a resting mouse would hover something else).
    pub fn rect(&self, selector: &str) -> Rect {
        let sel = serde_json::to_string(selector).expect("json");
        let r = self.wait_until(
            &format!(
                "(() => {{ const e = document.querySelector({sel}); if (!e) return null; \
                 let r = e.getBoundingClientRect(); \
                 if (r.top < 0 || r.left < 0 || r.bottom > innerHeight || r.right > innerWidth) {{ \
                   e.scrollIntoView({{block: 'center', inline: 'center'}}); r = e.getBoundingClientRect(); }} \
                 return r.width > 0 && r.height > 0 ? [r.x, r.y, r.width, r.height] : null; }})()"
            ),
            &format!("{selector} visible"),
        );
        let n = |i: usize| r[i].as_f64().expect("number");
        Rect {
            x: n(0),
            y: n(1),
            width: n(2),
            height: n(3),
        }
    }

    /// `[data-testid="id"]`.
    pub fn testid(id: &str) -> String {
        format!("[data-testid=\"{id}\"]")
    }

    /// Moves the mouse to a point (hover).
    pub fn mouse_move(&self, x: f64, y: f64) {
        self.mouse("mouseMoved", x, y, "none", 0);
    }

    /// A real left click at the middle of the element (mouse moved there, pressed, released).
    pub fn click(&self, selector: &str) {
        let (x, y) = self.rect(selector).center();
        self.click_at(x, y);
    }

    /// A real left click at a point.
    pub fn click_at(&self, x: f64, y: f64) {
        self.mouse_move(x, y);
        self.mouse("mousePressed", x, y, "left", 1);
        self.mouse("mouseReleased", x, y, "left", 1);
    }

    /// A drag with the left button from one point to another in `steps` moves (orbiting).
    pub fn drag(&self, from: (f64, f64), to: (f64, f64), steps: u32) {
        self.mouse_move(from.0, from.1);
        self.mouse("mousePressed", from.0, from.1, "left", 1);
        for i in 1..=steps {
            let t = f64::from(i) / f64::from(steps);
            let (x, y) = (from.0 + (to.0 - from.0) * t, from.1 + (to.1 - from.1) * t);
            self.call(
                "Input.dispatchMouseEvent",
                json!({ "type": "mouseMoved", "x": x, "y": y, "button": "left", "buttons": 1 }),
            );
        }
        self.mouse("mouseReleased", to.0, to.1, "left", 1);
    }

    fn mouse(&self, kind: &str, x: f64, y: f64, button: &str, clicks: u32) {
        self.call(
            "Input.dispatchMouseEvent",
            json!({ "type": kind, "x": x, "y": y, "button": button, "clickCount": clicks,
                    "buttons": if kind == "mousePressed" { 1 } else { 0 } }),
        );
    }

    /// Presses a key (e.g. "Tab", "Enter") with its DOM code and key code.
    pub fn key(&self, key: &str, code: &str, key_code: u32, shift: bool) {
        let modifiers = if shift { 8 } else { 0 };
        for kind in ["rawKeyDown", "keyUp"] {
            self.call(
                "Input.dispatchKeyEvent",
                json!({ "type": kind, "key": key, "code": code, "windowsVirtualKeyCode": key_code,
                        "nativeVirtualKeyCode": key_code, "modifiers": modifiers }),
            );
        }
        if key == "Enter" {
            self.call(
                "Input.dispatchKeyEvent",
                json!({ "type": "char", "text": "\r", "key": key }),
            );
        }
    }

    /// Gives a file `<input>` these files, as the file chooser would (fires `change`).
    pub fn set_files(&self, selector: &str, files: &[&Path]) {
        let sel = serde_json::to_string(selector).expect("json");
        let r = self.call(
            "Runtime.evaluate",
            json!({ "expression": format!("document.querySelector({sel})") }),
        );
        let object = r["result"]["objectId"]
            .as_str()
            .unwrap_or_else(|| panic!("no element {selector}"));
        self.call(
            "DOM.setFileInputFiles",
            json!({ "objectId": object, "files": files.iter().map(|p| p.display().to_string()).collect::<Vec<_>>() }),
        );
    }

    /// Drags a file over the element as a person dragging it from the desktop would: the
    /// file is read from disk by a scratch `<input>` (never into JS source) into a
    /// `DataTransfer`, which dragenter and dragover carry; `drop` lets go of it.
    pub fn drag_over(&self, selector: &str, file: &Path) {
        self.eval(
            "(() => { const i = document.createElement('input'); i.type = 'file'; i.id = '__drop_source'; \
             i.hidden = true; document.body.append(i); })()",
        );
        self.set_files("#__drop_source", &[file]);
        self.eval(&format!(
            "(() => {{ const src = document.getElementById('__drop_source'); window.__dragged = new DataTransfer(); \
             window.__dragged.items.add(src.files[0]); src.remove(); {} }})()",
            drag_events(selector, &["dragenter", "dragover"])
        ));
    }

    /// Drops what `drag_over` dragged onto the element.
    pub fn drop(&self, selector: &str) {
        self.eval(&format!("(() => {{ {} }})()", drag_events(selector, &["drop"])));
    }

    /// `drag_over` then `drop`.
    pub fn drop_file(&self, selector: &str, file: &Path) {
        self.drag_over(selector, file);
        self.drop(selector);
    }

    /// A PNG screenshot of the viewport (or a clip of it) saved as `shots_dir()/name.png`.
    pub fn screenshot(&self, name: &str, clip: Option<Rect>) -> Vec<u8> {
        let mut params = json!({ "format": "png", "captureBeyondViewport": false });
        if let Some(c) = clip {
            // The clip is in document coordinates, the rectangle in the viewport's.
            let scroll = self.eval("[window.scrollX, window.scrollY]");
            let (sx, sy) = (scroll[0].as_f64().unwrap_or(0.0), scroll[1].as_f64().unwrap_or(0.0));
            params["clip"] = json!({ "x": c.x + sx, "y": c.y + sy, "width": c.width, "height": c.height, "scale": 1 });
        }
        let r = self.call("Page.captureScreenshot", params);
        let png = base64::engine::general_purpose::STANDARD
            .decode(r["data"].as_str().expect("data"))
            .expect("base64");
        let dir = shots_dir();
        std::fs::create_dir_all(&dir).expect("shots dir");
        std::fs::write(dir.join(format!("{name}.png")), &png).expect("write screenshot");
        png
    }

    /// Everything that went wrong on this tab: console errors, uncaught exceptions, log
    /// errors (CSP violations among them), failed requests and answers of 400 or more.
    pub fn problems(&self) -> Vec<String> {
        self.browser
            .cdp
            .events()
            .iter()
            .skip(self.cursor)
            .filter(|e| e["sessionId"] == self.session.as_str())
            .filter_map(problem)
            .collect()
    }

    /// Asserts that nothing went wrong on this tab (`problems`).
    pub fn assert_no_problems(&self, when: &str) {
        let p = self.problems();
        assert!(p.is_empty(), "{when}: {p:#?}");
    }
}

/// JS dispatching drag events of `window.__dragged` on the element (or the body).
fn drag_events(selector: &str, kinds: &[&str]) -> String {
    let sel = serde_json::to_string(selector).expect("json");
    let kinds = serde_json::to_string(kinds).expect("json");
    format!(
        "const target = document.querySelector({sel}) || document.body; \
         for (const type of {kinds}) target.dispatchEvent(new DragEvent(type, \
           {{ bubbles: true, cancelable: true, dataTransfer: window.__dragged }}));"
    )
}

/// One event as a problem, if it is one.
fn problem(e: &Value) -> Option<String> {
    let p = &e["params"];
    match e["method"].as_str()? {
        "Runtime.consoleAPICalled" if p["type"] == "error" || p["type"] == "assert" => {
            let args: Vec<String> = p["args"]
                .as_array()?
                .iter()
                .map(|a| {
                    a["value"]
                        .as_str()
                        .map_or_else(|| a["description"].to_string(), str::to_string)
                })
                .collect();
            Some(format!("console.error: {}", args.join(" ")))
        }
        "Runtime.exceptionThrown" => Some(format!(
            "exception: {}",
            p["exceptionDetails"]["exception"]["description"]
                .as_str()
                .unwrap_or(&p["exceptionDetails"]["text"].to_string())
        )),
        "Log.entryAdded" if p["entry"]["level"] == "error" => Some(format!(
            "log: {} {}",
            p["entry"]["text"],
            p["entry"]["url"].as_str().unwrap_or_default()
        )),
        "Network.loadingFailed" if p["canceled"] != true => {
            Some(format!("request failed: {} ({})", p["errorText"], p["requestId"]))
        }
        "Network.responseReceived" if p["response"]["status"].as_u64()? >= 400 => {
            Some(format!("HTTP {}: {}", p["response"]["status"], p["response"]["url"]))
        }
        _ => None,
    }
}
