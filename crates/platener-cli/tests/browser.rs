//! The web page (issue 18) in Debian's Chromium, headless, against the real `platener serve`
//! on 127.0.0.1 with a temp data dir: upload by the button and by a drop, progress, the six
//! 3D views checked by their pixels, hover in 3D and on the sheet, the exploded view and the
//! assembly player, publishing, re-cuts from the settings and the test strip, the strip's SVG
//! and the ZIP downloads verified, the gallery (a finished conversion's steps per method), the
//! phone-width layout, the debug view, the keyboard, results as they come (the model view
//! before any plan, each plan as it lands, switching among stored plans, Cancel, a superseded
//! re-cut cancelled), and no console error or failed request
//! anywhere. Screenshots go to target/browser-shots/.
//!
//! Without Chromium the tests say so and pass, unless PLATENER_REQUIRE_CHROMIUM=1 (CI).
//! Every wait is bounded (`PATIENCE`); nothing asserts on speed.

mod browser_support;
mod web_support;

use std::path::{Path, PathBuf};

use browser_support::models::{metre_scale_box, million_triangle_box};
use browser_support::pixels::{Image, assert_view_rendered, assert_viewer_empty, palette_share};
use browser_support::{Browser, PATIENCE, Page, Rect, chromium};
use serde_json::Value;
use web_support::Server;

/// The six views of the plate method (all but the classifier's `primitives`), in the page's
/// order.
const VIEWS: [&str; 6] = ["model", "wireframe", "coplanar", "plates", "bent", "final"];

/// A server and a browser for one test; the data dir lives as long as they do.
struct Rig {
    browser: Browser,
    server: Server,
    data: tempfile::TempDir,
}

impl Rig {
    /// None (after a message) when there is no Chromium and it is not required.
    fn start(server_args: &[&str]) -> Option<Rig> {
        Rig::start_env(server_args, &[])
    }

    /// [`Rig::start`] with the server's environment extended by `env`.
    fn start_env(server_args: &[&str], env: &[(&str, &str)]) -> Option<Rig> {
        let chromium = chromium()?;
        let data = tempfile::tempdir().expect("temp dir");
        let server = Server::start(data.path(), server_args, env);
        let browser = Browser::launch(&chromium);
        Some(Rig { browser, server, data })
    }

    fn url(&self, path: &str) -> String {
        format!("http://{}{path}", self.server.addr)
    }

    /// Opens the landing page and waits for the app to run.
    fn open(&self, path: &str) -> Page<'_> {
        let page = self.browser.open(&self.url(path));
        page.wait_until("window.platener && window.platener.state", "the app starts");
        page
    }
}

fn example(name: &str) -> PathBuf {
    // Canonical: Chromium refuses to read an upload through a path with `..` in it.
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../examples")
        .join(name)
        .canonicalize()
        .expect("the example exists")
}

fn tid(id: &str) -> String {
    Page::testid(id)
}

/// Waits until the page shows a finished conversion other than `previous`; its id.
fn wait_converted(page: &Page, previous: Option<&str>) -> String {
    let prev = serde_json::to_string(&previous).expect("json");
    let js = format!(
        "(() => {{ const s = window.platener.state; \
         if (s.status === 'failed') throw new Error('conversion failed: ' + document.querySelector('[data-testid=error]').textContent); \
         return s.id && s.id !== {prev} && s.status === 'done' ? s.id : null; }})()"
    );
    page.wait_until(&js, "a finished conversion")
        .as_str()
        .expect("id")
        .to_string()
}

/// Uploads through the "Upload model" button: the click opens the file chooser (intercepted
/// by the protocol), which is given the file as a person would pick it.
fn upload_by_button(page: &Page, file: &Path) {
    page.call(
        "Page.setInterceptFileChooserDialog",
        serde_json::json!({ "enabled": true }),
    );
    let cursor = page.browser.cdp.event_count();
    page.click(&tid("upload"));
    let opened = page
        .browser
        .cdp
        .wait_event(cursor, PATIENCE, |e| e["method"] == "Page.fileChooserOpened")
        .expect("the button opens a file chooser");
    page.call(
        "DOM.setFileInputFiles",
        serde_json::json!({ "backendNodeId": opened["params"]["backendNodeId"], "files": [file] }),
    );
}

/// Waits for the page's next two animation frames, so what was loaded has been drawn.
fn settle(page: &Page) {
    page.eval("new Promise(r => requestAnimationFrame(() => requestAnimationFrame(() => r(true))))");
}

/// Shows a view by its button; the canvas's pixels once it has been drawn.
fn show_view(page: &Page, view: &str, shot: &str) -> Image {
    page.click(&tid(&format!("view-{view}")));
    page.wait_until(
        &format!(
            "window.platener.state.loadedView === '{view}' && \
             document.querySelector('[data-testid=view-{view}]').getAttribute('aria-pressed') === 'true'"
        ),
        &format!("the {view} view"),
    );
    settle(page);
    canvas_pixels(page, shot)
}

fn canvas_pixels(page: &Page, shot: &str) -> Image {
    let rect = page.rect(&tid("viewer"));
    Image::from_png(&page.screenshot(shot, Some(rect)))
}

/// A part of the sheet other than `not`, in view as the page is: scrolling to one would move
/// the 3D view under the pointer when its pixels are read.
fn sheet_part_in_view(page: &Page, not: u64) -> u64 {
    page.eval(&format!(
        "[...document.querySelectorAll('[data-testid=sheet-part]')].map(g => [Number(g.dataset.part), g.getBoundingClientRect()]) \
         .filter(([p, r]) => p !== {not} && r.top >= 0 && r.bottom <= innerHeight && r.left >= 0 && r.right <= innerWidth) \
         .map(([p]) => p)[0] ?? null"
    ))
    .as_u64()
    .expect("a part of the sheet in view")
}

/// Moves the mouse over the canvas on a grid until a part is hovered; its number.
fn hover_a_part(page: &Page, canvas: Rect) -> u64 {
    for i in 1..8 {
        for j in 1..8 {
            let x = canvas.x + canvas.width * f64::from(i) / 8.0;
            let y = canvas.y + canvas.height * f64::from(j) / 8.0;
            page.mouse_move(x, y);
            settle(page);
            if let Some(n) = page.state()["hovered"].as_u64() {
                return n;
            }
        }
    }
    panic!("no part under the mouse anywhere on the canvas: {}", page.state());
}

/// The conversion's JSON from the API.
fn conversion(rig: &Rig, id: &str) -> Value {
    let r = rig.server.get(&format!("/api/conversions/{id}"));
    assert_eq!(r.status, 200, "{}", r.text());
    r.json()
}

/// A worker process of the test's own on the server's SQLite database, killed when dropped:
/// started only once the page listens, so the page sees every step's event as it happens.
struct Worker(std::process::Child);

impl Worker {
    fn start(data: &Path) -> Worker {
        let url = format!("sqlite://{}", data.join("platener.sqlite").display());
        let child = std::process::Command::new(env!("CARGO_BIN_EXE_platener"))
            .args(["worker", "--database", &url, "--memory-mb", "0"])
            .stderr(std::process::Stdio::null())
            .spawn()
            .expect("platener worker starts");
        Worker(child)
    }
}

impl Drop for Worker {
    fn drop(&mut self) {
        let _ = self.0.kill();
        let _ = self.0.wait();
    }
}

/// Records every (step, state) the progress list shows, as it changes.
const WATCH_PROGRESS: &str = "(() => { window.__progress = []; const list = document.querySelector('[data-testid=progress]'); \
    new MutationObserver(() => { for (const li of list.querySelectorAll('[data-step]')) { \
      const k = li.dataset.step + ':' + li.dataset.state; if (!window.__progress.includes(k)) window.__progress.push(k); } }) \
    .observe(list, { subtree: true, childList: true, attributes: true, characterData: true }); })()";

#[test]
fn upload_button_progress_six_views_hover_and_settings_recut() {
    let Some(rig) = Rig::start(&["--workers", "0", "--no-examples"]) else {
        return;
    };
    let page = rig.open("/");
    page.screenshot("01-landing", None);
    assert_viewer_empty(&canvas_pixels(&page, "01-viewer-empty"));
    page.eval(WATCH_PROGRESS);
    upload_by_button(&page, &example("box-3mm.stl"));
    page.wait_until(
        "window.platener.state.id && window.platener.state.status === 'queued'",
        "the upload, queued",
    );
    // No worker yet: the page says it waits, and its place in the queue (issue 30).
    page.wait_until(
        "document.getElementById('status-line').textContent.includes('Waiting for a free worker (0 ahead)')",
        "the queue place in words",
    );
    page.screenshot("02-box-queued", None);
    let _worker = Worker::start(rig.data.path());
    let id = wait_converted(&page, None);
    assert_progress(&page, &conversion(&rig, &id));
    let seen = page.eval("window.__progress");
    for k in ["read:started", "read:finished"] {
        assert!(
            seen.as_array().is_some_and(|a| a.iter().any(|x| x == k)),
            "{k} never shown live: {seen}"
        );
    }
    page.screenshot("02-box-converted", None);
    says_it_in_plain_words(&page);

    for view in VIEWS {
        let img = show_view(&page, view, &format!("03-view-{view}"));
        assert_view_rendered(view, &img);
    }
    assert_eq!(
        page.eval("document.querySelector('[data-testid=view-primitives]').disabled"),
        Value::Bool(true),
        "the plate method has no primitives to show"
    );

    // Hover in the final view: the part lights up in 3D, its number shows, and the same part
    // is marked on the sheet.
    let canvas = page.rect(&tid("viewer"));
    let before = canvas_pixels(&page, "04-final-before-hover");
    let part = hover_a_part(&page, canvas);
    let after = canvas_pixels(&page, "05-final-hover");
    assert!(
        after.changed_pixels(&before, 24) > 100,
        "the hovered part {part} is not highlighted in 3D"
    );
    let label = page.eval("document.querySelector('[data-testid=part-label]').textContent");
    assert!(
        label.as_str().is_some_and(|l| l.contains(&part.to_string())),
        "label {label}"
    );
    let hot =
        page.eval("[...document.querySelectorAll('[data-testid=sheet-part].hot')].map(g => Number(g.dataset.part))");
    assert_eq!(hot, serde_json::json!([part]), "the sheet marks the hovered part");
    page.screenshot("06-hover-page", None);

    // And the other way: hovering a part on the sheet lights it up in 3D.
    let other = sheet_part_in_view(&page, part);
    let (x, y) = page
        .rect(&format!("[data-testid=sheet-part][data-part=\"{other}\"]"))
        .center();
    page.mouse_move(x, y);
    page.wait_until(
        &format!("window.platener.state.hovered === {other}"),
        "the sheet's part hovered",
    );
    settle(&page);
    let from_sheet = canvas_pixels(&page, "06-hover-from-sheet");
    assert_eq!(page.state()["hovered"], other, "still the sheet's part");
    let label = page.eval("document.querySelector('[data-testid=part-label]').textContent");
    assert_eq!(label, format!("Part {other}"));
    assert!(
        from_sheet.changed_pixels(&before, 24) > 100,
        "part {other} hovered on the sheet is not lit in 3D"
    );
    every_part_lights_up_hidden_ones_too(&page, &before);
    check_explode_and_player(&rig, &page, &id);
    multi_sheet_hover_scrolls_to_the_sheet(&rig, &page, &id);
    publish_and_see_in_gallery(&rig, &page, &id);
    recut_keeps_view(&rig, &page, &id);
    classifier_shows_its_primitives(&rig, &page);
    page.assert_no_problems("landing page, upload, views, hover, re-cut");
}

/// Each part of the box hovered on the sheet lights up in 3D over most of its outline, also
/// the three walls the camera sees only through the others (the highlight is drawn on top).
fn every_part_lights_up_hidden_ones_too(page: &Page, before: &Image) {
    let parts =
        page.eval("[...document.querySelectorAll('[data-testid=sheet-part]')].map(g => Number(g.dataset.part))");
    let parts: Vec<u64> = serde_json::from_value(parts).expect("numbers");
    assert_eq!(parts.len(), 6, "the box's six walls");
    // Focus marks a sheet's part as hovering does, with no mouse to wander when the page
    // scrolls for a screenshot.
    page.mouse_move(5.0, 5.0);
    let mut lit = Vec::new();
    for part in parts {
        page.eval(&format!(
            "document.querySelector('[data-testid=sheet-part][data-part=\"{part}\"]').focus({{ preventScroll: true }})"
        ));
        page.wait_until(
            &format!("window.platener.state.hovered === {part}"),
            "a wall marked on the sheet",
        );
        settle(page);
        let img = canvas_pixels(page, &format!("06-hover-wall-{part}"));
        assert_eq!(page.state()["hovered"], part, "still wall {part}");
        lit.push((part, img.changed_pixels(before, 24)));
    }
    page.eval("document.activeElement.blur()");
    assert!(
        lit.iter().all(|&(_, n)| n > LIT_WALL),
        "pixels lit per wall (more than {LIT_WALL} each): {lit:?}"
    );
}

/// Changed pixels a hovered wall of the box lights up at least, seen or hidden: 21 000 and
/// more with the highlight drawn on top, under 3 000 for a hidden wall without (its finger
/// tips), in the 488 × 430 canvas.
const LIT_WALL: usize = 10_000;

/// A re-cut of the box on 200 × 150 mm sheets has several: a part hovered in 3D (stepped to
/// with the keyboard until one on the last sheet) scrolls the sheet list to that sheet, is
/// marked there, and the label names its sheet.
fn multi_sheet_hover_scrolls_to_the_sheet(rig: &Rig, page: &Page, id: &str) {
    let body = serde_json::json!({ "sheet": "200x150", "method": "plate" }).to_string();
    let r = rig.server.request(
        "POST",
        &format!("/api/conversions/{id}/recut"),
        &[("Content-Type", "application/json")],
        body.as_bytes(),
    );
    assert_eq!(r.status, 202, "{}", r.text());
    let small = r.json()["id"].as_str().expect("id").to_string();
    page.eval(&format!("location.hash = '#/c/{small}'"));
    page.wait_until(
        &format!("window.platener.state.id === '{small}' && window.platener.state.loadedView === 'final'"),
        "the re-cut on small sheets",
    );
    let plan = plan_json(&rig.server.get(&format!("/api/conversions/{small}/plan.zip")).body);
    let sheet_of = |n: u64| {
        plan["parts"]
            .as_array()
            .expect("parts")
            .iter()
            .find(|p| p["id"] == n)
            .expect("part")["sheet"]["index"]
            .as_u64()
            .expect("index")
            + 1
    };
    let last = plan["sheets"].as_array().expect("sheets").len() as u64;
    assert!(last >= 2, "200 × 150 mm sheets hold the box in one: {}", plan["sheets"]);
    page.wait_until(
        &format!("document.querySelectorAll('[data-testid=sheets] figure').length === {last}"),
        "every sheet shown",
    );
    // The mouse rests away from the sheets, which scroll under it otherwise.
    page.mouse_move(5.0, 5.0);
    page.eval("document.querySelector('[data-testid=viewer]').focus()");
    let mut part = 0;
    for _ in 0..plan["parts"].as_array().expect("parts").len() {
        page.key("n", "KeyN", 78, false);
        part = page.state()["hovered"].as_u64().expect("a part stepped to");
        if sheet_of(part) == last {
            break;
        }
    }
    assert_eq!(sheet_of(part), last, "no part of the last sheet reached");
    let label = page.eval("document.querySelector('[data-testid=part-label]').textContent");
    assert_eq!(label, format!("Part {part}, sheet {last}"));
    let shown = page.wait_until(
        &format!(
            "(() => {{ const box = document.querySelector('[data-testid=sheets]').getBoundingClientRect(); \
             const figure = document.querySelectorAll('[data-testid=sheets] figure')[{last} - 1]; \
             const g = figure.querySelector('[data-testid=sheet-part][data-part=\"{part}\"]'); \
             const r = g.getBoundingClientRect(); \
             return g.classList.contains('hot') && r.top >= box.top - 1 && r.bottom <= box.bottom + 1; }})()"
        ),
        "the hovered part's sheet scrolled into view",
    );
    assert_eq!(shown, Value::Bool(true));
    page.screenshot("16-multi-sheet-hover", None);
    page.eval(&format!("location.hash = '#/c/{id}'"));
    page.wait_until(
        &format!("window.platener.state.id === '{id}' && window.platener.state.loadedView === 'final'"),
        "the box on one sheet again",
    );
}

/// The clean box's warnings say so in words, the other methods' notes grouped by method; the
/// laser-time note names the plan's material and thickness; the score and the engraved
/// numbers are explained.
fn says_it_in_plain_words(page: &Page) {
    let text = |id: &str| {
        page.eval(&format!("document.getElementById('{id}').textContent"))
            .as_str()
            .unwrap_or_default()
            .to_string()
    };
    let title = text("warnings-title");
    assert!(
        title.starts_with("No warnings about this plan (") && title.contains("notes from the methods not shown"),
        "{title}"
    );
    let groups = page.eval(
        "[...document.querySelectorAll('[data-testid=warnings] > li')].map(li => [li.dataset.method, li.className])",
    );
    let groups = groups.as_array().expect("groups");
    assert!(
        !groups.is_empty()
            && groups
                .iter()
                .all(|g| g[0] != "plate" && g[0].is_string() && g[1] == "group other-method"),
        "the notes grouped by the methods not shown: {groups:?}"
    );
    // The stacked box's notes say its rings overlap "nowhere wide enough for a peg" (issue 31:
    // bosses hold them): a "why?" explains the word.
    let why = page.eval(
        "[...document.querySelectorAll('[data-testid=warnings] li[data-method=stacked] [data-testid=why] dt')].map(d => d.textContent)",
    );
    let why = why.as_array().expect("terms");
    assert!(why.iter().any(|t| t == "peg"), "no “why?” for peg: {why:?}");
    page.wait_until(
        "document.getElementById('speed-note').textContent.startsWith('Laser time for 3 mm plywood or MDF:')",
        "the laser-time note of a 3 mm wood plan",
    );
    // Issue 35: print time and speed-up beside the laser time; the assembly steps beside the
    // player, each showing the parts so far; their printable page served with its pictures.
    page.wait_until(
        "document.querySelector('#stats [data-stat=speedup]').textContent.endsWith('× faster')",
        "the speed-up against printing",
    );
    page.wait_until(
        "document.querySelectorAll('#assembly-steps > li').length === 6",
        "the box's six assembly steps beside the player",
    );
    page.eval("document.querySelector('#assembly-steps > li:nth-child(2) button').click()");
    page.wait_until(
        "document.getElementById('player').value === '2'",
        "step 2 shows two parts",
    );
    let instructions = page.eval(
        "(async () => { const a = document.getElementById('steps-link'); const r = await fetch(a.href);          const t = await r.text(); const img = await fetch(new URL('assembly/step-02.png', a.href));          return [r.status, t.includes('Step 6 of 6'), img.status, img.headers.get('content-type')]; })()",
    );
    assert_eq!(
        instructions,
        serde_json::json!([200, true, 200, "image/png"]),
        "the instructions' page"
    );
    let help =
        page.eval("['score-help', 'labels-help'].map(t => document.querySelector(`[data-testid=${t}]`).textContent)");
    assert!(
        help[0].as_str().is_some_and(|t| t.contains("from 0 to 1"))
            && help[1].as_str().is_some_and(|t| t.contains("#7")),
        "{help}"
    );
}

/// Part `id` came in along its assembly step's direction (plan.json, model axes): it started
/// back along that direction, at least a few millimetres away, and now rests at `home`.
fn check_motion(page: &Page, plan: &Value, id: u64, home: &std::collections::BTreeMap<u64, [f64; 3]>) {
    let step = plan["assembly"]
        .as_array()
        .expect("plan.json's assembly")
        .iter()
        .find(|s| s["parts"].as_array().is_some_and(|p| p.contains(&Value::from(id))))
        .expect("a step adds the part");
    let way: [f64; 3] = serde_json::from_value(step["direction"].clone()).expect("a direction");
    let motion = &page.state()["motion"][id.to_string()];
    if way.iter().all(|c| c.abs() < 0.5) {
        assert!(motion.is_null(), "part {id} has no way in, yet moved: {motion}");
        return;
    }
    let (from, to): ([f64; 3], [f64; 3]) = (
        serde_json::from_value(motion["from"].clone()).unwrap_or_else(|_| panic!("part {id} moved: {motion}")),
        serde_json::from_value(motion["to"].clone()).expect("where it rests"),
    );
    let moved = [to[0] - from[0], to[1] - from[1], to[2] - from[2]];
    let length = distance(from, to);
    assert!(length > 5.0, "part {id} slides {length} mm");
    let along = (0..3).map(|i| moved[i] * way[i]).sum::<f64>() / length;
    assert!(along > 0.999, "part {id} moves {moved:?}, its step says {way:?}");
    let rest = part_centres(page)[&id];
    assert!(
        distance(rest, home[&id]) < 0.01,
        "part {id} rests at {rest:?}, not {:?}",
        home[&id]
    );
}

/// Choosing the classifier method re-cuts, and its primitives view is enabled and drawn in
/// the palette's colours.
fn classifier_shows_its_primitives(rig: &Rig, page: &Page) {
    let id = page.state()["id"].as_str().expect("a conversion").to_string();
    page.eval(
        "(() => { const s = document.querySelector('[data-testid=method]'); s.value = 'classifier'; \
         s.dispatchEvent(new Event('change', { bubbles: true })); })()",
    );
    let recut = wait_converted(page, Some(&id));
    assert_eq!(conversion(rig, &recut)["best"], "classifier");
    let img = show_view(page, "primitives", "09-classifier-primitives");
    assert_view_rendered("primitives", &img);
}

/// A settings change re-cuts: a new conversion with the new material, the view kept (plates,
/// not the default final view), drawn from the re-cut's own scene. The old conversion's plates
/// scene is held back (paused by the protocol) until the re-cut's has been asked for: let
/// through late, it is dropped, and no view is named loaded before the re-cut's is drawn.
fn recut_keeps_view(rig: &Rig, page: &Page, id: &str) {
    show_view(page, "model", "07-before-recut");
    page.call(
        "Fetch.enable",
        serde_json::json!({ "patterns": [{ "urlPattern": "*/scenes/plates.glb*" }] }),
    );
    let cursor = page.browser.cdp.event_count();
    page.click(&tid("view-plates"));
    let old = paused_scene(page, cursor, id);
    let dropped = page.state()["scenesDropped"].as_u64().expect("scenesDropped");
    page.eval(
        "(() => { const s = document.querySelector('[data-testid=material]'); s.value = 'acrylic'; \
         s.dispatchEvent(new Event('change', { bubbles: true })); })()",
    );
    let recut = wait_converted(page, Some(id));
    assert_eq!(conversion(rig, &recut)["settings"]["material"], "acrylic");
    let new = paused_scene(page, cursor, &recut);
    page.call("Fetch.continueRequest", serde_json::json!({ "requestId": old }));
    page.wait_until(
        &format!("window.platener.state.scenesDropped > {dropped}"),
        "the old conversion's late scene dropped",
    );
    assert_eq!(
        page.state()["loadedView"],
        Value::Null,
        "a view is named loaded while the re-cut's scene is still on its way"
    );
    page.call("Fetch.continueRequest", serde_json::json!({ "requestId": new }));
    page.call("Fetch.disable", serde_json::json!({}));
    page.wait_until(
        "window.platener.state.loadedView === 'plates'",
        "the plates view of the re-cut",
    );
    assert_eq!(page.state()["view"], "plates", "the view is kept across a re-cut");
    page.wait_until(
        "document.getElementById('speed-note').textContent.startsWith('Laser time for 3 mm acrylic:')",
        "the laser-time note of the acrylic re-cut",
    );
    settle(page);
    assert_view_rendered("plates", &canvas_pixels(page, "08-recut-acrylic"));
}

/// Waits for the protocol to pause the request of conversion `id`'s plates scene; its id.
fn paused_scene(page: &Page, cursor: usize, id: &str) -> Value {
    let url = format!("/api/conversions/{id}/scenes/plates.glb");
    let e = page
        .browser
        .cdp
        .wait_event(cursor, PATIENCE, |e| {
            e["method"] == "Fetch.requestPaused"
                && e["params"]["request"]["url"].as_str().is_some_and(|u| u.contains(&url))
        })
        .unwrap_or_else(|| panic!("{url} never requested"));
    e["params"]["requestId"].clone()
}

/// Sets a range input as dragging it does (its value, then an `input` event).
fn set_range(page: &Page, id: &str, value: u32) {
    page.eval(&format!(
        "(() => {{ const r = document.querySelector('[data-testid={id}]'); r.value = '{value}'; \
         r.dispatchEvent(new Event('input', {{ bubbles: true }})); }})()"
    ));
    settle(page);
}

/// Part number → centre (mm) from the viewer's state.
fn part_centres(page: &Page) -> std::collections::BTreeMap<u64, [f64; 3]> {
    let state = page.state();
    let map = state["partCentres"].as_object().expect("partCentres");
    map.iter()
        .map(|(n, c)| {
            let c: Vec<f64> = c.as_array().expect("xyz").iter().filter_map(Value::as_f64).collect();
            (n.parse().expect("a number"), [c[0], c[1], c[2]])
        })
        .collect()
}

fn distance(a: [f64; 3], b: [f64; 3]) -> f64 {
    a.iter().zip(b).map(|(x, y)| (x - y) * (x - y)).sum::<f64>().sqrt()
}

/// The exploded slider moves every part of the final view away from the others (the
/// viewer's part centres, and the picture changes); the assembly player then shows k parts,
/// in plan.json's `assembly` order, where each part after the first is joined (plan.json's
/// joints) to one before.
fn check_explode_and_player(rig: &Rig, page: &Page, id: &str) {
    let assembled = show_view(page, "final", "13-final-assembled");
    let home = part_centres(page);
    let plan = plan_json(&rig.server.get(&format!("/api/conversions/{id}/plan.zip")).body);
    let parts = plan["parts"].as_array().expect("parts").len();
    assert_eq!(home.len(), parts, "one node per part of plan.json: {home:?}");
    set_range(page, "explode", 100);
    let exploded = canvas_pixels(page, "14-final-exploded");
    assert_eq!(page.state()["exploded"], 1.0);
    assert!(
        exploded.changed_pixels(&assembled, 24) > 1000,
        "exploding changes nothing on screen"
    );
    let apart = part_centres(page);
    let state = page.state();
    assert_eq!(
        state["offscreenParts"],
        serde_json::json!([]),
        "exploded parts leave the picture"
    );
    assert!(
        state["gridBelowModelMm"].as_f64().is_some_and(|d| d > 0.0),
        "the grid is not under the exploded parts: {}",
        state["gridBelowModelMm"]
    );
    let centroid = |m: &std::collections::BTreeMap<u64, [f64; 3]>| {
        let mut c = [0.0; 3];
        for p in m.values() {
            for i in 0..3 {
                c[i] += p[i] / m.len() as f64;
            }
        }
        c
    };
    let (c0, c1) = (centroid(&home), centroid(&apart));
    for (n, p) in &home {
        let q = apart[n];
        assert!(distance(*p, q) > 5.0, "part {n} did not move: {p:?} → {q:?}");
        assert!(
            distance(q, c1) > distance(*p, c0) + 5.0,
            "part {n} did not move away from the others: {p:?} → {q:?}"
        );
    }
    set_range(page, "explode", 0);
    let back = part_centres(page);
    assert!(
        home.iter().all(|(n, p)| distance(*p, back[n]) < 0.01),
        "the slider at 0 puts the parts back: {home:?} → {back:?}"
    );
    check_player(page, &plan, &assembled, &home);
}

/// Steps the assembly player from one part to all of them (see `check_explode_and_player`):
/// each part it adds slides in along its step's direction and comes to rest where it was in
/// the assembled view (`home`, mm).
fn check_player(page: &Page, plan: &Value, assembled: &Image, home: &std::collections::BTreeMap<u64, [f64; 3]>) {
    let joined: std::collections::HashSet<(u64, u64)> = plan["joints"]
        .as_array()
        .expect("joints")
        .iter()
        .filter_map(|j| Some((j["parts"][0].as_u64()?, j["parts"][1].as_u64()?)))
        .flat_map(|(a, b)| [(a, b), (b, a)])
        .collect();
    assert!(!joined.is_empty(), "plan.json has joints");
    let total = plan["parts"].as_array().expect("parts").len();
    // plan.json's assembly order, which the library plans from the parts' geometry.
    let order: Vec<u64> = plan["assembly"]
        .as_array()
        .expect("plan.json's assembly")
        .iter()
        .flat_map(|s| {
            s["parts"]
                .as_array()
                .expect("a step's parts")
                .iter()
                .filter_map(Value::as_u64)
        })
        .collect();
    assert_eq!(order.len(), total, "every part in one step: {order:?}");
    let mut shown: Vec<u64> = Vec::new();
    for k in 1..=total {
        page.click(&tid("player-step"));
        settle(page);
        page.wait_until(
            "!(window.platener.state.moving || []).length",
            "the player's part comes to rest",
        );
        let now: Vec<u64> = serde_json::from_value(page.state()["shownParts"].clone()).expect("numbers");
        assert_eq!(now.len(), k, "step {k} shows {now:?}");
        if k > 1 {
            // The first step goes back to the base alone: nothing comes in.
            check_motion(page, plan, now[k - 1], home);
        }
        assert_eq!(now[..k - 1], shown[..], "step {k} keeps the parts shown before");
        assert_eq!(now[..], order[..k], "step {k} follows plan.json's assembly");
        let new = now[k - 1];
        assert!(
            k == 1 || shown.iter().any(|&s| joined.contains(&(s, new))),
            "part {new} (step {k}) is joined to none of {shown:?}"
        );
        if k == 1 {
            let one = canvas_pixels(page, "15-player-one-part");
            assert!(
                one.changed_pixels(assembled, 24) > 1000,
                "one part looks like all of them"
            );
        }
        shown = now;
    }
    let all = canvas_pixels(page, "16-player-all-parts");
    assert!(
        all.changed_pixels(assembled, 24) < 200,
        "after the last step the whole model shows"
    );
}

/// Publishing asks first (Cancel publishes nothing); once confirmed the conversion appears in
/// the gallery (the API's and the page's) with its thumbnail, a picture of the assembled box
/// (non-background pixels cover at least a fifth of it); Unpublish takes it out again.
fn publish_and_see_in_gallery(rig: &Rig, page: &Page, id: &str) {
    let in_gallery = || {
        let items = rig.server.get("/api/gallery?page=1").json();
        items["items"]
            .as_array()
            .is_some_and(|a| a.iter().any(|i| i["id"] == id))
    };
    let dialog_open = "document.querySelector('[data-testid=publish-dialog]').open";
    page.click(&tid("publish"));
    page.wait_until(dialog_open, "the question before publishing");
    page.screenshot("17-publish-asks", None);
    page.click(&tid("publish-cancel"));
    page.wait_until(&format!("!{dialog_open}"), "the question closed");
    assert!(!in_gallery(), "Cancel published the conversion");
    page.click(&tid("publish"));
    page.wait_until(dialog_open, "the question again");
    page.click(&tid("publish-confirm"));
    page.wait_until(
        "!document.querySelector('[data-testid=unpublish]').hidden && document.querySelector('[data-testid=publish]').hidden",
        "Unpublish offered once published",
    );
    assert!(in_gallery(), "not in the gallery once published");
    let img = format!("[data-testid=gallery-item][data-id=\"{id}\"] img");
    page.rect(&img);
    let cover = thumbnail_cover(page, &img);
    assert!(
        cover >= 0.2,
        "the thumbnail shows the box on {:.0} % of it",
        cover * 100.0
    );
    page.screenshot("17-published", None);
    page.click(&tid("unpublish"));
    page.wait_until(
        &format!("!document.querySelector('[data-testid=publish]').hidden && !document.querySelector('{img}')"),
        "the conversion out of the page's gallery",
    );
    assert!(!in_gallery(), "still in the gallery after Unpublish");
}

/// The share of a gallery thumbnail's pixels (its `img`, once loaded) that are not the white
/// background, read back through a canvas. Thumbnails load lazily, so the card is scrolled
/// into view first, as a visitor scrolls down to the gallery below the form.
fn thumbnail_cover(page: &Page, img: &str) -> f64 {
    let js = format!(
        "(() => {{ const i = document.querySelector('{img}'); if (i && !i.complete) i.scrollIntoView(); \
         if (!i || !i.complete || !i.naturalWidth) return null; \
         const c = document.createElement('canvas'); c.width = i.naturalWidth; c.height = i.naturalHeight; \
         const x = c.getContext('2d'); x.drawImage(i, 0, 0); const d = x.getImageData(0, 0, c.width, c.height).data; \
         let n = 0; for (let k = 0; k < d.length; k += 4) if (d[k] < 250 || d[k + 1] < 250 || d[k + 2] < 250) n += 1; \
         return n / (c.width * c.height); }})()"
    );
    page.wait_until(&js, "a thumbnail loaded").as_f64().expect("a share")
}

/// Each step of the conversion appears in the progress list, finished, with its time.
fn assert_progress(page: &Page, conversion: &Value) {
    let shown = page.eval(
        "[...document.querySelectorAll('[data-testid=progress] [data-step]')]\
         .map(li => [li.dataset.step, li.dataset.state, li.textContent])",
    );
    let shown = shown.as_array().expect("a list");
    let steps = conversion["steps"].as_array().expect("steps");
    assert!(!steps.is_empty(), "{conversion}");
    for step in steps {
        let name = step["name"].as_str().expect("name");
        let row = shown
            .iter()
            .find(|r| r[0] == name)
            .unwrap_or_else(|| panic!("step {name} not in the progress list {shown:?}"));
        assert_eq!(row[1], "finished", "{row}");
        assert!(
            row[2].as_str().is_some_and(|t| t.contains("ms") || t.contains(" s")),
            "no time: {row}"
        );
    }
}

/// The test ids of the elements that Tab reaches from the top of the page, in order (an
/// element without one counts as its nearest ancestor's).
fn tab_order(page: &Page, presses: usize) -> Vec<String> {
    page.eval("document.activeElement && document.activeElement.blur(); window.scrollTo(0, 0)");
    let mut seen = Vec::new();
    for _ in 0..presses {
        page.key("Tab", "Tab", 9, false);
        let id = page.eval(
            "(() => { const a = document.activeElement; const t = a && a.closest('[data-testid]'); \
             return t ? t.dataset.testid : (a ? a.tagName.toLowerCase() : null); })()",
        );
        if let Some(id) = id.as_str() {
            seen.push(id.to_string());
        }
    }
    seen
}

/// Clicks the download link `selector`; the downloaded file (in a temp dir, returned too so
/// the file lives as long as the caller keeps it).
fn download(page: &Page, selector: &str) -> (tempfile::TempDir, PathBuf) {
    let downloads = tempfile::tempdir().expect("downloads");
    page.browser.download_to(downloads.path());
    let cursor = page.browser.cdp.event_count();
    page.click(selector);
    let file = page.browser.wait_download(cursor, downloads.path());
    (downloads, file)
}

/// The parsed plan.json of a plan ZIP.
fn plan_json(zip: &[u8]) -> Value {
    use std::io::Read as _;
    let mut archive = zip::ZipArchive::new(std::io::Cursor::new(zip)).expect("a ZIP");
    let mut text = String::new();
    archive
        .by_name("plan.json")
        .expect("plan.json in the ZIP")
        .read_to_string(&mut text)
        .expect("text");
    serde_json::from_str(&text).expect("JSON")
}

/// `platener verify ZIP --model MODEL` passes.
fn assert_verifies(zip: &Path, model: &Path) {
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_platener"))
        .arg("verify")
        .arg(zip)
        .arg("--model")
        .arg(model)
        .output()
        .expect("platener verify runs");
    assert!(
        out.status.success(),
        "verify {}: {}{}",
        zip.display(),
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    );
}

#[test]
fn drop_keyboard_download_dialog_test_strip_and_zip() {
    let Some(rig) = Rig::start(&["--workers", "1", "--no-examples"]) else {
        return;
    };
    let page = rig.open("/");
    let tray = example("tray-3mm.stl");
    page.drag_over("body", &tray);
    page.wait_until(
        "!document.querySelector('[data-testid=drop-zone]').hidden && \
         document.querySelector('[data-testid=drop-zone]').getBoundingClientRect().width > 600",
        "the drop overlay while a file is dragged over the page",
    );
    page.screenshot("09-dragging-tray", None);
    page.drop("body");
    let id = wait_converted(&page, None);
    assert_eq!(
        page.eval("document.querySelector('[data-testid=drop-zone]').hidden"),
        Value::Bool(true)
    );
    assert_eq!(conversion(&rig, &id)["model"]["name"], "tray-3mm.stl");
    settle(&page);
    page.screenshot("10-dropped-tray", None);

    // The main controls are reachable by Tab, in a sensible order.
    let order = tab_order(&page, 60);
    let wanted = ["upload", "thickness", "material", "method"]
        .into_iter()
        .map(String::from)
        .chain(VIEWS.iter().map(|v| format!("view-{v}")))
        .chain(["viewer", "download", "sheets"].map(String::from));
    for w in wanted {
        assert!(order.contains(&w), "Tab never reaches {w}: {order:?}");
    }
    let first = |w: &str| order.iter().position(|o| o == w).unwrap_or(usize::MAX);
    assert!(
        first("upload") < first("material") && first("material") < first("view-model"),
        "{order:?}"
    );

    // The download dialog opens from the keyboard too.
    page.eval("document.querySelector('[data-testid=download]').focus()");
    page.key("Enter", "Enter", 13, false);
    page.wait_until(
        "document.querySelector('[data-testid=download-dialog]').open",
        "the download dialog",
    );
    page.wait_until(
        "document.querySelectorAll('[data-testid=strip-hole]').length > 3",
        "the test strip",
    );
    page.screenshot("11-download-dialog", None);
    download_strip_svg(&page);
    pick_kerf_and_download(&rig, &page, &id, &tray);
    page.assert_no_problems("drop, keyboard, download dialog, test strip, ZIP");
}

/// Width (mm, to 0.001) of a path written as `M x y L x y … Z`.
fn path_width(d: &str) -> String {
    let xs: Vec<f64> = d
        .split(|c: char| c.is_ascii_alphabetic())
        .filter_map(|pair| pair.split_whitespace().next()?.parse().ok())
        .collect();
    let (lo, hi) = xs.iter().fold((f64::MAX, f64::MIN), |(l, h), &x| (l.min(x), h.max(x)));
    format!("{:.3}", hi - lo)
}

/// The dialog's "Download the test strip (SVG)" link: the file parses as SVG and its cut
/// paths are the strip's outline and one hole per hole drawn in the page, of the same widths.
fn download_strip_svg(page: &Page) {
    let (_downloads, file) = download(page, &tid("test-strip-svg"));
    let text = std::fs::read_to_string(&file).expect("the downloaded SVG");
    let doc = roxmltree::Document::parse(&text).unwrap_or_else(|e| panic!("the strip SVG: {e}"));
    assert_eq!(doc.root_element().tag_name().name(), "svg");
    let strip = doc
        .descendants()
        .find(|n| n.attribute("id") == Some("part-1"))
        .expect("the strip is part 1");
    let mut cuts: Vec<String> = strip
        .children()
        .filter(|n| n.has_tag_name("path") && n.attribute("stroke") == Some("#ff0000"))
        .map(|n| path_width(n.attribute("d").expect("d")))
        .collect();
    // The widest cut is the strip's outline; the rest are its holes and its slot row.
    cuts.sort_by(|a, b| a.parse::<f64>().unwrap_or(0.0).total_cmp(&b.parse().unwrap_or(0.0)));
    cuts.pop();
    let shown = page.eval(
        "[...document.querySelectorAll('[data-testid=strip-hole] .strip-hole-cut, .strip-slot')].map(p => p.getAttribute('d'))",
    );
    let mut holes: Vec<String> = shown
        .as_array()
        .expect("paths")
        .iter()
        .map(|d| path_width(d.as_str().expect("d")))
        .collect();
    holes.sort_by(|a, b| a.parse::<f64>().unwrap_or(0.0).total_cmp(&b.parse().unwrap_or(0.0)));
    assert!(holes.len() > 3, "{holes:?}");
    assert_eq!(cuts, holes, "the SVG's holes and slots are the page's strip's");
}

/// Clicks a test-strip hole other than the chosen one: a re-cut whose plan.json has that
/// kerf; then the ZIP link downloads that plan, which `platener verify` passes.
fn pick_kerf_and_download(rig: &Rig, page: &Page, id: &str, model: &Path) {
    let kerf = page
        .eval("[...document.querySelectorAll('[data-testid=strip-hole]:not(.chosen)')].at(-1).dataset.kerf")
        .as_str()
        .expect("a hole's kerf")
        .to_string();
    let old = plan_json(&rig.server.get(&format!("/api/conversions/{id}/plan.zip")).body);
    assert_ne!(
        old["settings"]["kerf"].to_string(),
        kerf,
        "the hole picked is not the current kerf"
    );
    page.click(&format!("[data-testid=strip-hole][data-kerf=\"{kerf}\"]"));
    let recut = wait_converted(page, Some(id));
    let kerf: f64 = kerf.parse().expect("a number");
    let plan = plan_json(&rig.server.get(&format!("/api/conversions/{recut}/plan.zip")).body);
    let got = plan["settings"]["kerf"].as_f64().expect("kerf in plan.json");
    assert!((got - kerf).abs() < 5e-4, "plan.json kerf {got}, picked {kerf}");
    page.wait_until(
        &format!("document.querySelector('[data-testid=kerf]').textContent.includes('{kerf}')"),
        "the dialog shows the new kerf",
    );
    assert_strip_stars(rig, page, kerf);
    page.screenshot("12-kerf-picked", None);

    let (_downloads, zip) = download(page, &tid("download-zip"));
    let plan = plan_json(&std::fs::read(&zip).expect("the downloaded ZIP"));
    assert_eq!(
        plan["settings"]["kerf"].as_f64(),
        Some(got),
        "the ZIP is the re-cut plan"
    );
    assert_verifies(&zip, model);
}

/// After a kerf change the dialog's strip (its SVG link and the strip drawn) is asked for
/// with the new kerf, whose hole the engraved table stars.
fn assert_strip_stars(rig: &Rig, page: &Page, kerf: f64) {
    let href = page.wait_until(
        &format!(
            "(() => {{ const h = document.querySelector('[data-testid=test-strip-svg]').getAttribute('href'); \
             return h && new URL(h, location.href).searchParams.get('kerf') === String({kerf}) ? h : null; }})()"
        ),
        "the test strip link with the plan's kerf",
    );
    let json = href
        .as_str()
        .expect("href")
        .replace("test-strip.svg", "test-strip.json");
    let strip = rig.server.get(&json).json();
    let hole = page.eval(&format!(
        "Number(document.querySelector('[data-testid=strip-hole][data-kerf=\"{kerf:.3}\"]').dataset.number)"
    ));
    assert_eq!(strip["marked_hole"], hole, "the table stars the kerf in use: {strip}");
    assert_ne!(strip["marked_hole"], strip["default_hole"], "{strip}");
}

#[test]
fn gallery_hover_view_and_download() {
    let Some(rig) = Rig::start(&["--workers", "2"]) else {
        return;
    };
    // The three shipped examples are converted and published on the first start.
    let items = wait_gallery(&rig, 3);
    let page = rig.open("/");
    page.wait_until(
        "document.querySelectorAll('[data-testid=gallery-item] img').length >= 3",
        "three cards",
    );
    // Every card shows its assembled model: at least a fifth of each thumbnail is drawn.
    for item in &items {
        let img = format!(
            "[data-testid=gallery-item][data-id=\"{}\"] img",
            item["id"].as_str().expect("id")
        );
        let cover = thumbnail_cover(&page, &img);
        assert!(
            cover >= 0.2,
            "{}: the thumbnail covers {:.0} %",
            item["name"],
            cover * 100.0
        );
    }
    let id = items[0]["id"].as_str().expect("id").to_string();
    let card = format!("[data-testid=gallery-item][data-id=\"{id}\"]");
    let view = format!("{card} [data-testid=gallery-view]");
    let shown = format!(
        "(() => {{ const v = document.querySelector('{view}'); const s = getComputedStyle(v.parentElement); \
         return s.visibility !== 'hidden' && Number(s.opacity) > 0.9 && v.getBoundingClientRect().width > 0; }})()"
    );
    let (x, y) = page.rect(&card).center();
    assert_eq!(
        page.eval(&shown),
        Value::Bool(false),
        "the View button is hidden until hovered"
    );
    page.mouse_move(x, y);
    page.wait_until(&shown, "the View button shows on hover");
    page.screenshot("20-gallery-hover", None);

    page.click(&view);
    page.wait_until(
        &format!("window.platener.state.id === '{id}' && window.platener.state.status === 'done'"),
        "the example loads",
    );
    page.wait_until("window.platener.state.loadedView", "a 3D view");
    settle(&page);
    let shown = page.state()["loadedView"].as_str().expect("view").to_string();
    assert_view_rendered(&shown, &canvas_pixels(&page, "21-gallery-view"));
    assert_method_steps(&rig, &page, &id);
    page.screenshot("22-gallery-view-page", None);
    side_column_fits_from_1920_to_1024(&page);

    page.goto(&rig.url("/#/"));
    page.wait_until(
        "document.querySelectorAll('[data-testid=gallery-item]').length >= 3",
        "the gallery again",
    );
    let (x, y) = page.rect(&card).center();
    page.mouse_move(x, y);
    let (_downloads, zip) = download(&page, &format!("{card} [data-testid=gallery-download]"));
    let name = items[0]["name"].as_str().expect("name");
    assert_verifies(&zip, &example(name));
    check_phone_layout(&page, &card);
    page.assert_no_problems("gallery, phone width");
}

/// The (method, step) pairs finished in the conversion's event stream, which replays every
/// event of a finished conversion and ends.
fn method_steps_of_events(rig: &Rig, id: &str) -> Vec<(String, String)> {
    let r = rig.server.get(&format!("/api/conversions/{id}/events"));
    assert_eq!(r.status, 200);
    let text = r.text();
    let mut out: Vec<(String, String)> = text
        .lines()
        .filter_map(|l| l.strip_prefix("data:"))
        .filter_map(|d| serde_json::from_str::<Value>(d.trim()).ok())
        .filter(|d| d["state"] == "finished" && d["method"].is_string())
        .map(|d| {
            (
                d["method"].as_str().unwrap_or_default().to_string(),
                d["step"].as_str().unwrap_or_default().to_string(),
            )
        })
        .collect();
    out.sort();
    out.dedup();
    out
}

/// A conversion opened after it finished lists each method's steps, with their times,
/// exactly as its events name them.
fn assert_method_steps(rig: &Rig, page: &Page, id: &str) {
    let wanted = method_steps_of_events(rig, id);
    assert!(wanted.len() > 3, "the events name the methods' steps: {wanted:?}");
    let js = format!(
        "(() => {{ const rows = [...document.querySelectorAll('[data-testid=progress] li[data-method]')]; \
         return rows.length >= {} ? rows.map(li => [li.dataset.method, li.dataset.step, li.dataset.state, li.textContent]) : null; }})()",
        wanted.len()
    );
    let rows = page.wait_until(&js, "each method's steps in the progress list");
    let mut shown: Vec<(String, String)> = Vec::new();
    for row in rows.as_array().expect("rows") {
        assert_eq!(row[2], "finished", "{row}");
        let text = row[3].as_str().unwrap_or_default();
        assert!(text.contains(" ms") || text.contains(" s"), "no time: {row}");
        shown.push((
            row[0].as_str().unwrap_or_default().into(),
            row[1].as_str().unwrap_or_default().into(),
        ));
    }
    shown.sort();
    assert_eq!(shown, wanted, "the methods' steps shown are the events'");
}

/// Neither the page nor the document scrolls sideways, and `selector` lies within the width.
fn assert_fits_width(page: &Page, selector: &str, what: &str) {
    let r = page.rect(selector);
    let widths = page.eval("[innerWidth, document.documentElement.scrollWidth, document.body.scrollWidth]");
    let w = |i: usize| widths[i].as_f64().expect("width");
    assert!(w(1) <= w(0) && w(2) <= w(0), "{what}: horizontal overflow {widths}");
    assert!(
        r.x >= 0.0 && r.x + r.width <= w(0) + 0.5,
        "{what}: {selector} outside the width ({r:?})"
    );
}

/// Whether every element of the settings column (`aside.side`) lies within it: the list of
/// those that stick out, with their boxes (empty when all fit).
const SIDE_OVERFLOW: &str = "(() => { const side = document.querySelector('aside.side'); const r = side.getBoundingClientRect(); \
    const out = []; if (side.scrollWidth > side.clientWidth + 1) out.push('aside scrolls sideways: ' + side.scrollWidth + ' > ' + side.clientWidth); \
    for (const e of side.querySelectorAll('*')) { const b = e.getBoundingClientRect(); if (!b.width && !b.height) continue; \
      if (b.left < r.left - 0.5 || b.right > r.right + 0.5) out.push(`${e.tagName.toLowerCase()}${e.id ? '#' + e.id : ''}: ${Math.round(b.left)}..${Math.round(b.right)} outside ${Math.round(r.left)}..${Math.round(r.right)}`); } \
    return out; })()";

/// No element of the settings column extends past it, and the column stays left of the 3D
/// pane and inside the page, at the `width` set.
fn assert_side_column_fits(page: &Page, width: u32) {
    let out = page.eval(SIDE_OVERFLOW);
    assert_eq!(
        out,
        serde_json::json!([]),
        "at {width} px, the settings column overflows"
    );
    assert_fits_width(page, "aside.side", &format!("the settings column at {width} px"));
    if width > 720 {
        let (side, pane) = (page.rect("aside.side"), page.rect(".viewer-pane"));
        assert!(
            side.x + side.width <= pane.x,
            "at {width} px the 3D pane covers the settings column"
        );
    }
}

/// Sets the viewport's size and waits for the page to take it.
fn set_width(page: &Page, width: u32, height: u32) {
    page.call(
        "Emulation.setDeviceMetricsOverride",
        serde_json::json!({ "width": width, "height": height, "deviceScaleFactor": 1, "mobile": false }),
    );
    page.wait_until(&format!("innerWidth === {width}"), &format!("the width {width}"));
}

/// A model exported in metres with a long file name fails (every method says why, naming
/// the file): at 1920, 1280 and 1024 px nothing of the settings column, neither its controls
/// nor the long name and error, sticks out of it.
fn side_column_fits_from_1920_to_1024(page: &Page) {
    let dir = tempfile::tempdir().expect("temp dir");
    let tiny = dir
        .path()
        .join(format!("bunny-exported-in-metres-{}.stl", "z".repeat(80)));
    metre_scale_box(&tiny);
    page.drop_file("body", &tiny);
    page.wait_until(
        "window.platener.state.status === 'failed' && !document.querySelector('[data-testid=error]').hidden",
        "the metre-scale model's failure, in words",
    );
    for width in [1920, 1280, 1024] {
        set_width(page, width, 900);
        settle(page);
        page.screenshot(&format!("22-side-column-{width}"), None);
        assert_side_column_fits(page, width);
    }
    set_width(page, 1280, 720);
}

/// At a phone's 375×740 the gallery cards and the download dialog show and work: no
/// horizontal overflow, the ZIP link inside the screen, the dialog's controls clickable.
fn check_phone_layout(page: &Page, card: &str) {
    set_width(page, 375, 740);
    assert_fits_width(page, card, "the gallery");
    assert_fits_width(page, &format!("{card} img"), "a card's thumbnail");
    page.screenshot("23-phone-gallery", None);
    let (x, y) = page.rect(card).center();
    page.mouse_move(x, y);
    page.click(&format!("{card} [data-testid=gallery-view]"));
    page.wait_until("window.platener.state.loadedView", "the conversion at phone width");
    assert_fits_width(page, &tid("viewer"), "the conversion");
    assert_side_column_fits(page, 375);
    page.click(&tid("download"));
    page.wait_until(
        "document.querySelector('[data-testid=download-dialog]').open",
        "the download dialog at phone width",
    );
    // The strip keeps its size (its holes stay big enough to tap) and scrolls in its box.
    for part in [tid("download-dialog"), tid("download-zip"), ".strip-box".to_string()] {
        assert_fits_width(page, &part, "the download dialog");
    }
    // The dialog's controls are hit where they show: the ZIP link is the element there.
    let (x, y) = page.rect(&tid("download-zip")).center();
    let hit = page.eval(&format!(
        "(() => {{ const e = document.elementFromPoint({x}, {y}); return !!e && !!e.closest('[data-testid=download-zip]'); }})()"
    ));
    assert_eq!(hit, Value::Bool(true), "the ZIP link is covered at phone width");
    page.screenshot("24-phone-download", None);
    let (_downloads, zip) = download(page, &tid("download-zip"));
    let plan = plan_json(&std::fs::read(&zip).expect("the ZIP downloaded at phone width"));
    assert!(plan["parts"].as_array().is_some_and(|p| !p.is_empty()), "{plan}");
}

/// Waits until the gallery API lists `n` finished items; they, newest first.
fn wait_gallery(rig: &Rig, n: usize) -> Vec<Value> {
    let start = std::time::Instant::now();
    loop {
        let g = rig.server.get("/api/gallery?page=1").json();
        let items: Vec<Value> = g["items"].as_array().cloned().unwrap_or_default();
        if items.iter().filter(|i| i["status"] == "done").count() >= n {
            return items;
        }
        assert!(start.elapsed() < PATIENCE, "the examples did not finish: {g}");
        std::thread::sleep(std::time::Duration::from_millis(200));
    }
}

/// Drops a model on a fresh landing page; milliseconds (page clock) from the drop until the
/// first 3D view has been drawn, and the page.
fn drop_to_first_view_ms<'r>(rig: &'r Rig, model: &Path) -> (Page<'r>, f64) {
    let page = rig.open("/");
    page.eval("window.__dropped = performance.now()");
    page.drop_file("body", model);
    wait_converted(&page, None);
    page.wait_until("window.platener.state.loadedView", "a 3D view");
    settle(&page);
    let ms = page.eval("performance.now() - window.__dropped").as_f64().expect("ms");
    page.assert_no_problems(&format!("dropping {}", model.display()));
    (page, ms)
}

/// Frames per second while the mouse orbits the model (page clock, frames counted by the
/// page itself).
fn orbit_fps(page: &Page) -> f64 {
    let canvas = page.rect(&tid("viewer"));
    let (cx, cy) = canvas.center();
    let before = page.eval("[window.platener.state.frames, performance.now()]");
    page.drag((cx - 200.0, cy), (cx + 200.0, cy + 50.0), 120);
    settle(page);
    let after = page.eval("[window.platener.state.frames, performance.now()]");
    let frames = after[0].as_f64().unwrap_or(0.0) - before[0].as_f64().unwrap_or(0.0);
    let seconds = (after[1].as_f64().unwrap_or(0.0) - before[1].as_f64().unwrap_or(0.0)) / 1000.0;
    assert!(frames > 0.0, "no frame drawn while orbiting");
    frames / seconds
}

/// Measurements for docs/performance.md (issue 18), printed, not asserted: drop to first 3D
/// view for the three examples and a 1M-triangle box, and fps orbiting that box. Ignored by
/// default (a minute or more on 2 cores): `cargo test -p platener-cli --test browser --
/// --ignored --nocapture measure`.
#[test]
#[ignore = "a measurement, run on demand"]
fn measure_drop_to_first_view_and_orbit_fps() {
    let Some(rig) = Rig::start(&[
        "--workers",
        "1",
        "--no-examples",
        "--max-upload-mb",
        "80",
        "--timeout",
        "600",
        "--worker-memory-mb",
        "0",
    ]) else {
        return;
    };
    for name in ["box-3mm.stl", "tray-3mm.stl", "phone-stand.stl"] {
        let (_, ms) = drop_to_first_view_ms(&rig, &example(name));
        println!("measure: {name}: drop to first 3D view {ms:.0} ms");
    }
    let dir = tempfile::tempdir().expect("temp dir");
    let big = dir.path().join("million-box.stl");
    million_triangle_box(&big);
    let (page, ms) = drop_to_first_view_ms(&rig, &big);
    println!("measure: million-box.stl (1,002,252 triangles): drop to first 3D view {ms:.0} ms");
    for view in ["model", "final"] {
        show_view(&page, view, &format!("30-million-{view}"));
        let note = page.eval("document.querySelector('[data-testid=simplified]').textContent");
        println!("measure: million-box.stl {view} view note: {note}");
        println!(
            "measure: million-box.stl {view} view: {:.1} fps while orbiting",
            orbit_fps(&page)
        );
    }
}
/// Waits for the debug view's conversion to be shown (its root's `data-status`).
fn wait_debug_ready(page: &Page) {
    page.wait_until(
        "(() => { const r = document.getElementById('debug-root'); \
         if (r.dataset.status === 'failed') throw new Error('debug: ' + document.querySelector('[data-testid=debug-error]').textContent); \
         return r.dataset.status === 'ready'; })()",
        "the debug view's conversion",
    );
    settle(page);
}

/// The debug view's snapshot panel: its JSON parses and names the step shown.
fn debug_json(page: &Page, prefix: &str) -> Value {
    let text = page.eval(&format!(
        "document.querySelector('[data-testid={prefix}-json]').textContent"
    ));
    serde_json::from_str(text.as_str().expect("text"))
        .unwrap_or_else(|e| panic!("{prefix}-json is not JSON ({e}): {text}"))
}

/// Clicks the output viewer on a grid until the side panel names a plate; its text.
fn click_a_plate(page: &Page) -> String {
    let canvas = page.rect(&tid("debug-viewer-output"));
    for (i, j) in [(4, 4), (3, 4), (5, 4), (4, 3), (4, 5), (3, 3), (5, 5), (3, 5), (5, 3)] {
        page.click_at(
            canvas.x + canvas.width * f64::from(i) / 8.0,
            canvas.y + canvas.height * f64::from(j) / 8.0,
        );
        settle(page);
        let selected = page.eval("document.querySelector('[data-testid=debug-plate-info]').dataset.selected || ''");
        if selected.as_str().is_some_and(|s| !s.is_empty()) {
            let text = page.eval("document.querySelector('[data-testid=debug-plate-info]').textContent");
            return text.as_str().unwrap_or_default().to_string();
        }
    }
    panic!("no plate under the mouse in the debug output view");
}

#[test]
fn debug_view_isolated_step_and_converting() {
    let Some(rig) = Rig::start(&["--workers", "1", "--no-examples"]) else {
        return;
    };
    let page = rig.browser.open(&rig.url("/#/debug"));
    page.wait_until(
        "document.querySelectorAll('[data-testid=debug-model] option').length > 0",
        "the test set",
    );
    page.screenshot("40-debug-start", None);

    // Isolated step: the plates step of a test model, its input and output side by side.
    page.click(&tid("debug-run"));
    wait_debug_ready(&page);
    let out = debug_json(&page, "debug");
    assert_eq!(out["step"], "plates", "{out}");
    // The default test model is a closed box: six plates, six pairs, in the snapshot shown.
    assert_eq!(out["summary"]["count"], 6, "{out}");
    debug_json(&page, "debug-input");
    let timing = page.eval("document.querySelector('[data-testid=debug-timing]').textContent");
    assert!(timing.as_str().is_some_and(|t| t.contains("ms")), "{timing}");
    let output =
        Image::from_png(&page.screenshot("41-debug-plates-output", Some(page.rect(&tid("debug-viewer-output")))));
    assert_view_rendered("plates", &output);
    let input = Image::from_png(&page.screenshot("42-debug-plates-input", Some(page.rect(&tid("debug-viewer-input")))));
    assert!(
        input.share_unlike(input.background(), 8) > 0.02,
        "the step's input is drawn"
    );
    // The render mode changes the drawing only: hidden leaves no palette colour.
    page.eval(
        "(() => { const s = document.querySelector('[data-testid=debug-render]'); s.value = 'hidden'; \
         s.dispatchEvent(new Event('change', { bubbles: true })); })()",
    );
    settle(&page);
    let hidden =
        Image::from_png(&page.screenshot("43-debug-render-hidden", Some(page.rect(&tid("debug-viewer-output")))));
    assert!(palette_share(&hidden).0 < 0.01, "hidden still draws the plates");
    page.eval(
        "(() => { const s = document.querySelector('[data-testid=debug-render]'); s.value = 'solid'; \
         s.dispatchEvent(new Event('change', { bubbles: true })); })()",
    );
    settle(&page);
    let info = click_a_plate(&page);
    assert!(
        info.contains("finger") && info.contains("connections"),
        "plate info: {info}"
    );
    page.screenshot("44-debug-plate-info", None);

    // Converting: the whole plate pipeline, any step chosen from the list.
    page.eval(
        "(() => { const s = document.querySelector('[data-testid=debug-mode]'); s.value = 'converting'; \
         s.dispatchEvent(new Event('change', { bubbles: true })); })()",
    );
    page.click(&tid("debug-run"));
    wait_debug_ready(&page);
    let steps = page.wait_until(
        "[...document.querySelectorAll('[data-testid=debug-steps] [data-step]')].map(b => b.dataset.step)",
        "the step list",
    );
    for step in ["read", "plates", "bends", "joints", "parts", "sheets"] {
        assert!(
            steps.as_array().is_some_and(|a| a.iter().any(|s| s == step)),
            "{step} in {steps}"
        );
    }
    page.click("[data-testid=debug-steps] [data-step=joints]");
    page.wait_until("window.platenerDebug.state.step === 'joints'", "the joints step");
    page.wait_until(
        "(() => { try { return JSON.parse(document.querySelector('[data-testid=debug-json]').textContent).step === 'joints'; } catch (_) { return false; } })()",
        "the joints snapshot",
    );
    assert_eq!(
        debug_json(&page, "debug")["summary"]["count"],
        12,
        "the box's 12 corner joints"
    );
    page.screenshot("45-debug-converting-joints", None);
    page.assert_no_problems("debug view");
}

/// The form is built from `GET /api/settings`, and the CLI's `--help` comes from the same
/// definitions: every setting is a control with the same choices and default in all three.
/// A model exported in metres fails with its size and a button that applies the scale that
/// fixes it; three quick setting changes make one re-cut.
#[test]
fn settings_form_cli_and_api_agree_and_a_metre_model_is_fixed_by_its_advice() {
    let Some(rig) = Rig::start(&["--workers", "1", "--no-examples"]) else {
        return;
    };
    let page = rig.open("/");
    let schema = page.eval("fetch('/api/settings').then(r => r.json())");
    let help = std::process::Command::new(env!("CARGO_BIN_EXE_platener"))
        .args(["convert", "--help"])
        .output()
        .expect("platener convert --help");
    let help = String::from_utf8_lossy(&help.stdout).to_string();
    for def in schema["settings"].as_array().expect("settings") {
        assert_form_control_matches(&page, def);
        assert_help_matches(&help, def);
    }
    assert_fits_width(&page, "aside.side", "the settings column, as built from the schema");

    let dir = tempfile::tempdir().expect("temp dir");
    let metres = dir.path().join("box-in-metres.stl");
    std::fs::write(
        &metres,
        platener_fixtures::samples::to_binary_stl(
            &platener_fixtures::samples::closed_box(0.12, 0.09, 0.07, 0.003),
            "box in metres",
        ),
    )
    .expect("write");
    upload_by_button(&page, &metres);
    page.wait_until("window.platener.state.status === 'failed'", "the metre-scale box fails");
    let error = page.eval("document.querySelector('[data-testid=error]').textContent");
    let error = error.as_str().unwrap_or_default();
    assert!(
        error.contains("0.12 × 0.09 × 0.07 mm") && error.contains("metres"),
        "{error}"
    );
    assert!(!error.contains('`'), "settings are named by their labels: {error}");
    let failed = page.state()["id"].as_str().expect("id").to_string();
    page.click(&tid("apply-scale"));
    page.wait_until(
        &format!("window.platener.state.id !== {failed:?}"),
        "the re-cut at the suggested scale",
    );
    let fixed = wait_converted(&page, Some(&failed));
    let c = conversion(&rig, &fixed);
    assert_eq!(c["settings"]["scale"], 1000.0, "{c}");
    assert!(
        c["methods"]
            .as_array()
            .expect("methods")
            .iter()
            .any(|m| m["parts"] == 6),
        "{c}"
    );
    page.screenshot("30-metre-box-fixed", None);

    // Three changes within the form's pause: one re-cut with all three.
    page.eval("performance.clearResourceTimings(); true");
    page.eval(
        "(() => { for (const [id, v] of [['material', 'acrylic'], ['labels', 'parts'], ['sheet', 'fit']]) { \
         const s = document.getElementById(id); s.value = v; s.dispatchEvent(new Event('change', { bubbles: true })); } \
         return true; })()",
    );
    let recut = wait_converted(&page, Some(&fixed));
    let settings = conversion(&rig, &recut)["settings"].clone();
    assert_eq!(
        (&settings["material"], &settings["labels"], &settings["sheet"]),
        (&Value::from("acrylic"), &Value::from("parts"), &Value::from("fit")),
        "{settings}"
    );
    let recuts = page.eval("performance.getEntriesByType('resource').filter(e => e.name.endsWith('/recut')).length");
    assert_eq!(recuts, 1, "three quick changes make one conversion");
    page.assert_no_problems("settings form, metre-scale advice, quick changes");
}

/// The page's control of one setting has the schema's values and default.
fn assert_form_control_matches(page: &Page, def: &Value) {
    let name = def["name"].as_str().expect("name");
    let js = format!(
        "(() => {{ const el = document.getElementById({name:?}); if (!el) return null; \
         if (el.tagName === 'SELECT') return {{ values: [...el.options].map(o => o.value).filter(v => v !== 'custom'), value: el.value }}; \
         if (el.tagName === 'FIELDSET') return {{ value: [...el.querySelectorAll('input:checked')].map(i => Number(i.value)) }}; \
         if (el.type === 'text') return {{ value: el.value === '' ? 'none' : el.value }}; \
         return {{ value: el.value === '' ? null : Number(el.value) }}; }})()"
    );
    let control = page.eval(&js);
    assert!(!control.is_null(), "the form has no control for {name}");
    let kind = &def["kind"];
    match kind["type"].as_str() {
        Some("choice") => {
            let values: Vec<&Value> = kind["choices"]
                .as_array()
                .expect("choices")
                .iter()
                .map(|c| &c["value"])
                .collect();
            let shown: Vec<&Value> = control["values"].as_array().expect("options").iter().collect();
            assert_eq!(shown, values, "{name}: the form's choices");
        }
        Some("sheet") => {
            let values: Vec<&Value> = kind["presets"]
                .as_array()
                .expect("presets")
                .iter()
                .map(|c| &c["value"])
                .collect();
            let shown: Vec<&Value> = control["values"].as_array().expect("options").iter().collect();
            assert_eq!(shown, values, "{name}: the form's presets");
        }
        _ => {}
    }
    let default = &def["default"];
    let same = match (default.as_f64(), control["value"].as_f64()) {
        (Some(a), Some(b)) => (a - b).abs() < 1e-9,
        _ => &control["value"] == default || control["value"] == serde_json::json!(default),
    };
    assert!(
        same,
        "{name}: the form shows {} for the default {default}",
        control["value"]
    );
}

/// `platener convert --help` has the setting's flag, its choices and its default.
fn assert_help_matches(help: &str, def: &Value) {
    let name = def["name"].as_str().expect("name");
    assert!(help.contains(&format!("--{name} ")), "--help has no --{name}");
    if let Some(choices) = def["kind"]["choices"].as_array() {
        for c in choices {
            let value = c["value"].as_str().expect("value");
            assert!(help.contains(&format!("- {value}:")), "--{name}: --help lacks {value}");
        }
    }
    let number = |v: &Value| v.as_f64().map_or_else(|| v.to_string(), |f| f.to_string());
    let default = match &def["default"] {
        Value::Null => "auto".to_string(),
        Value::Array(items) => items.iter().map(number).collect::<Vec<_>>().join(" "),
        Value::String(s) => s.clone(),
        other => number(other),
    };
    assert!(
        help.contains(&format!("[default: {default}]")),
        "--{name}: --help lacks its default {default}"
    );
}

/// A copy of the example box named `name` in `dir` (the name chooses a test hook).
fn box_named(dir: &Path, name: &str) -> PathBuf {
    let path = dir.join(name);
    std::fs::copy(example("box-3mm.stl"), &path).expect("copy the box");
    path
}

/// Lets `method` of the held model `name` go on past its `sheets` step.
fn open_gate(gates: &Path, name: &str, method: &str) {
    std::fs::write(gates.join(format!("{name}.{method}")), b"").expect("write a gate");
}

/// The page's own state value `key`, as JSON.
fn state_of(page: &Page, key: &str) -> Value {
    page.state()[key].clone()
}

/// Results as they come (issue 30), with every method of a `platener-test-hold…` box held at
/// its `sheets` step until the test opens its gate: the model view is drawn while no method has
/// a plan, the bars say the step in words, the plate plan shows while stacked still runs,
/// choosing the stacked plan from the method select makes no request to convert, Cancel ends a
/// running conversion and keeps its plan, and a re-cut cancels the conversion it supersedes.
#[test]
fn results_as_they_come_method_switch_and_cancel() {
    let gates = tempfile::tempdir().expect("gates");
    let gate_dir = gates.path().to_str().expect("a UTF-8 path").to_string();
    let env = [("PLATENER_TEST_HOOKS", "1"), ("PLATENER_TEST_GATE", gate_dir.as_str())];
    let args = ["--workers", "1", "--no-examples", "--worker-lease", "10"];
    let Some(rig) = Rig::start_env(&args, &env) else {
        return;
    };
    let models = tempfile::tempdir().expect("models");
    let page = rig.open("/");
    let name = "platener-test-hold-a.stl";
    page.drop_file("body", &box_named(models.path(), name));
    model_before_any_plan(&rig, &page);
    let id = state_of(&page, "id").as_str().expect("id").to_string();
    open_gate(gates.path(), name, "plate");
    page.wait_until(
        "window.platener.state.method === 'plate' && window.platener.state.loadedView === 'final' && \
         document.querySelector('#stats [data-stat=parts]').textContent === '6'",
        "the plate plan while the others run",
    );
    assert_eq!(conversion(&rig, &id)["status"], "running", "stacked is still held");
    page.screenshot("50-live-first-plan", None);
    for method in ["stacked", "classifier", "interlocked"] {
        open_gate(gates.path(), name, method);
    }
    assert_eq!(wait_converted(&page, None), id);
    switch_method_without_converting(&rig, &page, &id);
    cancel_keeps_the_plan(&page, models.path(), gates.path());
    superseded_recut_is_cancelled(&rig, &page, models.path());
    page.assert_no_problems("results as they come, method switch, cancel");
}

/// The model view is drawn from the early model scene while no method has a plan; the plate
/// bar says its held step in words, short of full; the step log is folded; Cancel shows.
fn model_before_any_plan(rig: &Rig, page: &Page) {
    page.wait_until(
        "window.platener.state.loadedView === 'model' && window.platener.state.method === null",
        "the model view before any plan",
    );
    settle(page);
    assert_view_rendered("model", &canvas_pixels(page, "51-live-model-first"));
    let id = state_of(page, "id").as_str().expect("id").to_string();
    let c = conversion(rig, &id);
    assert_eq!(c["status"], "running", "{c}");
    let planned = c["methods"]
        .as_array()
        .expect("methods")
        .iter()
        .any(|m| m["status"] == "done");
    assert!(!planned, "no plan yet: {c}");
    let words = platener::pipeline::StepId::Sheets.label();
    let bar = "[data-testid=method-bar][data-method=plate]";
    let shown = page.wait_until(
        &format!(
            "(() => {{ const b = document.querySelector('{bar}'); const t = b && b.querySelector('[data-testid=method-step]').textContent; \
             return t && t.toLowerCase().startsWith('{words}') ? [t, b.querySelector('progress').value, b.querySelector('progress').max] : null; }})()"
        ),
        "the plate bar at its held step",
    );
    assert!(shown[1].as_f64() < shown[2].as_f64(), "the bar is not full: {shown}");
    assert_eq!(
        page.eval(
            "[document.querySelector('[data-testid=step-log]').open, \
             document.querySelectorAll('[data-testid=progress] li').length > 3]"
        ),
        serde_json::json!([false, true]),
        "the step log is there, folded"
    );
    page.rect(&tid("cancel"));
    page.screenshot("52-live-bars", None);
}

/// Choosing the stacked method in the select shows its stored plan: same conversion, no POST.
fn switch_method_without_converting(rig: &Rig, page: &Page, id: &str) {
    let stacked = conversion(rig, id)["methods"]
        .as_array()
        .expect("methods")
        .iter()
        .find(|m| m["method"] == "stacked")
        .cloned()
        .expect("stacked ran");
    assert_eq!(stacked["status"], "done", "{stacked}");
    let cursor = page.browser.cdp.event_count();
    page.eval(
        "(() => { const s = document.querySelector('[data-testid=method]'); s.value = 'stacked'; \
         s.dispatchEvent(new Event('change', { bubbles: true })); })()",
    );
    page.wait_until(
        &format!(
            "window.platener.state.method === 'stacked' && window.platener.state.loadedView === 'final' && \
             document.querySelector('#stats [data-stat=parts]').textContent === '{}'",
            stacked["parts"]
        ),
        "the stacked plan",
    );
    assert_eq!(state_of(page, "id"), id, "the same conversion");
    page.screenshot("53-live-stacked-shown", None);
    // And back to the best of all methods (the next uploads convert with every method again).
    page.eval(
        "(() => { const s = document.querySelector('[data-testid=method]'); s.value = 'all'; \
         s.dispatchEvent(new Event('change', { bubbles: true })); })()",
    );
    let best = conversion(rig, id)["best"].clone();
    page.wait_until(
        &format!("window.platener.state.method === {best} && window.platener.state.loadedView === 'final'"),
        "the best plan again",
    );
    let posts: Vec<String> = page.browser.cdp.events()[cursor..]
        .iter()
        .filter(|e| e["method"] == "Network.requestWillBeSent" && e["params"]["request"]["method"] == "POST")
        .map(|e| e["params"]["request"]["url"].to_string())
        .collect();
    assert!(posts.is_empty(), "switching method sent {posts:?}");
}

/// Cancel on a running conversion whose plate plan landed: it ends cancelled and the plate plan
/// stays shown, its ZIP downloadable.
fn cancel_keeps_the_plan(page: &Page, models: &Path, gates: &Path) {
    let name = "platener-test-hold-b.stl";
    open_gate(gates, name, "plate");
    let before = state_of(page, "id");
    page.drop_file("body", &box_named(models, name));
    page.wait_until(
        &format!(
            "window.platener.state.id !== {before} && window.platener.state.method === 'plate' && \
             window.platener.state.status === 'running'"
        ),
        "the second held conversion's plate plan",
    );
    page.click(&tid("cancel"));
    page.wait_until(
        "window.platener.state.status === 'cancelled'",
        "the conversion cancelled",
    );
    assert_eq!(state_of(page, "method"), "plate", "the landed plan stays");
    assert_eq!(
        page.eval(
            "[document.querySelector('[data-testid=cancel]').hidden, \
             document.querySelector('[data-testid=download]').disabled]"
        ),
        serde_json::json!([true, false]),
        "no Cancel after the end; the kept plan downloads"
    );
    page.screenshot("54-live-cancelled", None);
}

/// A settings change while a conversion runs: the re-cut replaces it and the page cancels it.
fn superseded_recut_is_cancelled(rig: &Rig, page: &Page, models: &Path) {
    let before = state_of(page, "id");
    page.drop_file("body", &box_named(models, "platener-test-hold-c.stl"));
    let old = page.wait_until(
        &format!(
            "window.platener.state.id !== {before} && window.platener.state.status === 'running' && \
             window.platener.state.id"
        ),
        "the third held conversion running",
    );
    let old = old.as_str().expect("id").to_string();
    page.eval(
        "(() => { const s = document.querySelector('[data-testid=material]'); s.value = 'cardboard'; \
         s.dispatchEvent(new Event('change', { bubbles: true })); })()",
    );
    page.wait_until(
        &format!("window.platener.state.id && window.platener.state.id !== '{old}'"),
        "the re-cut shown",
    );
    let start = std::time::Instant::now();
    while conversion(rig, &old)["status"] != "cancelled" {
        assert!(
            start.elapsed() < PATIENCE,
            "the superseded conversion was not cancelled"
        );
        std::thread::sleep(std::time::Duration::from_millis(50));
    }
}

/// Marks, on the page's clock from now, when the model view is first drawn, when the first
/// plan's view is drawn and when the conversion is done with its plan drawn (every frame).
const MARKS: &str = "(() => { window.__marks = {}; const t0 = performance.now(); const m = window.__marks; \
    (function tick() { const s = window.platener.state; const t = performance.now() - t0; \
      if (s.loadedView === 'model' && m.model == null) m.model = t; \
      if (s.method && s.loadedView && s.loadedView !== 'model' && m.plan == null) m.plan = t; \
      if (s.status === 'done' && m.plan != null && m.done == null) m.done = t; \
      if (m.done == null) requestAnimationFrame(tick); })(); })()";

/// Measurements for issue 30's closing note, printed, not asserted: drop → model view drawn,
/// → first plan shown, → all plans (done), for the box and, from the shared corpus, the
/// Arduino enclosure, the 1.3 MB tray and the Utah teapot (the example tray without the
/// corpus). `cargo test -p platener-cli --test browser -- --ignored --nocapture
/// measure_results`.
#[test]
#[ignore = "a measurement, run on demand"]
fn measure_results_as_they_come() {
    let Some(rig) = Rig::start(&["--workers", "1", "--no-examples"]) else {
        return;
    };
    let mut models = vec![example("box-3mm.stl")];
    match platener_fixtures::samples::shared_corpus() {
        Ok(dir) => {
            for name in [
                "plates/arduino_uno_enclosure.stl",
                "plates/tray_bottom_14in_3.2mm_sheet.stl",
                "organic/utah_teapot.stl",
            ] {
                models.push(dir.join(name).canonicalize().expect("a corpus model"));
            }
        }
        Err(_) => models.push(example("tray-3mm.stl")),
    }
    for model in models {
        let page = rig.open("/");
        page.eval(MARKS);
        page.drop_file("body", &model);
        let marks = page.wait_until("window.__marks.done != null && window.__marks", "all plans");
        let ms = |k: &str| marks[k].as_f64().map_or("never".to_string(), |t| format!("{t:.0} ms"));
        println!(
            "measure: {}: drop → model view {}, → first plan {}, → all plans {}",
            model.file_name().map(|n| n.to_string_lossy()).unwrap_or_default(),
            ms("model"),
            ms("plan"),
            ms("done")
        );
        page.assert_no_problems("measuring");
    }
}
