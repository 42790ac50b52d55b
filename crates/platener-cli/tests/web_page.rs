//! The web page's serving (issue 18): `/` and `/assets/…` from the real binary on 127.0.0.1 —
//! fixed content types, the CSP that allows exactly the inline import map by its hash, every
//! module the page imports served, 404 for anything else and no way out of the assets folder.
//! The page's behaviour in a browser is tested elsewhere (the browser tests).

mod web_support;

use std::collections::{BTreeSet, VecDeque};

use base64::Engine as _;
use sha2::{Digest, Sha256};
use web_support::Server;

/// The text between `open` and the next `close` after it.
fn between<'a>(text: &'a str, open: &str, close: &str) -> Option<&'a str> {
    let start = text.find(open)? + open.len();
    let len = text[start..].find(close)?;
    Some(&text[start..start + len])
}

/// The import specifiers of an ES module (`from '…'`, `import '…'` and `import('…')`).
fn imports(js: &str) -> Vec<String> {
    let mut out = Vec::new();
    for marker in ["from '", "from \"", "import('", "import(\"", "import '", "import \""] {
        let quote = &marker[marker.len() - 1..];
        let mut rest = js;
        while let Some(i) = rest.find(marker) {
            let tail = &rest[i + marker.len()..];
            if let Some(end) = tail.find(quote) {
                let spec = &tail[..end];
                if !spec.contains('\n') && (spec.starts_with('.') || spec.starts_with('/') || spec.starts_with("three"))
                {
                    out.push(spec.to_string());
                }
            }
            rest = tail;
        }
    }
    out
}

/// Resolves an import specifier of the module at `base` (a URL path) through the import map.
fn resolve(spec: &str, base: &str, map: &serde_json::Value) -> String {
    if spec == "three" {
        return map["imports"]["three"].as_str().expect("three mapped").to_string();
    }
    if let Some(rest) = spec.strip_prefix("three/addons/") {
        return format!(
            "{}{rest}",
            map["imports"]["three/addons/"].as_str().expect("addons mapped")
        );
    }
    if spec.starts_with('/') {
        return spec.to_string();
    }
    let mut parts: Vec<&str> = base.split('/').collect();
    parts.pop();
    for seg in spec.split('/') {
        match seg {
            "." => {}
            ".." => {
                parts.pop();
            }
            s => parts.push(s),
        }
    }
    parts.join("/")
}

#[test]
fn the_page_and_every_module_it_imports_are_served_under_a_hashed_csp() {
    let dir = tempfile::tempdir().expect("temp dir");
    let server = Server::start(dir.path(), &["--workers", "0", "--no-examples"], &[]);
    let page = server.get("/");
    assert_eq!(page.status, 200);
    assert_eq!(page.header("content-type"), Some("text/html; charset=utf-8"));
    let html = page.text();
    let import_map = between(&html, "<script type=\"importmap\">", "</script>").expect("an import map");
    let map: serde_json::Value = serde_json::from_str(import_map).expect("the import map is JSON");

    // The CSP names the import map's own hash and allows nothing else inline.
    let csp = page.header("content-security-policy").expect("a CSP").to_string();
    let hash = base64::engine::general_purpose::STANDARD.encode(Sha256::digest(import_map.as_bytes()));
    let script_src = csp
        .split(';')
        .map(str::trim)
        .find(|d| d.starts_with("script-src"))
        .expect("script-src");
    assert_eq!(script_src, format!("script-src 'self' 'sha256-{hash}'"), "{csp}");
    assert!(csp.contains("default-src 'none'") && !csp.contains("unsafe"), "{csp}");
    assert_eq!(html.matches("<script").count(), 2, "the import map and app.js only");

    // Every module reachable from app.js is served as JavaScript (the whole graph, three.js
    // and the debug view's stub included), so no import can 404 in a browser.
    let entry = between(&html, "<script type=\"module\" src=\"", "\"").expect("the entry module");
    let mut seen = BTreeSet::new();
    let mut queue = VecDeque::from([entry.to_string()]);
    while let Some(path) = queue.pop_front() {
        if !seen.insert(path.clone()) {
            continue;
        }
        let r = server.get(&path);
        assert_eq!(r.status, 200, "{path}");
        assert_eq!(
            r.header("content-type"),
            Some("text/javascript; charset=utf-8"),
            "{path}"
        );
        assert_eq!(r.header("x-content-type-options"), Some("nosniff"), "{path}");
        for spec in imports(&r.text()) {
            queue.push_back(resolve(&spec, &path, &map));
        }
    }
    for needed in [
        "/assets/js/api.js",
        "/assets/js/viewer.js",
        "/assets/js/debug/main.js",
        "/assets/vendor/three/build/three.module.js",
        "/assets/vendor/three/build/three.core.js",
        "/assets/vendor/three/examples/jsm/loaders/GLTFLoader.js",
    ] {
        assert!(seen.contains(needed), "{needed} not imported: {seen:?}");
    }
    let css = server.get("/assets/app.css");
    assert_eq!(
        (css.status, css.header("content-type")),
        (200, Some("text/css; charset=utf-8"))
    );
    let licence = server.get("/assets/vendor/three/LICENSE");
    assert_eq!(licence.header("content-type"), Some("text/plain; charset=utf-8"));
    assert!(licence.text().contains("MIT"), "{}", licence.text());
}

#[test]
fn unknown_assets_are_404_and_paths_cannot_leave_the_folder() {
    let dir = tempfile::tempdir().expect("temp dir");
    let server = Server::start(dir.path(), &["--workers", "0", "--no-examples"], &[]);
    for path in [
        "/assets/nope.js",
        "/assets/js/",
        "/assets/",
        "/assets/js/app.js.map",
        "/assets/../Cargo.toml",
        "/assets/%2e%2e/Cargo.toml",
        "/assets/..%2fCargo.toml",
        "/assets/js/..%2f..%2fsrc%2flib.rs",
        "/assets/%2e%2e%2f%2e%2e%2fsrc%2flib.rs",
        "/assets//etc/passwd",
        "/assets/%2fetc%2fpasswd",
        "/assets/js%5c..%5c..%5cCargo.toml",
    ] {
        let r = server.get(path);
        assert_eq!(r.status, 404, "{path}: {}", r.text());
        let body = r.text();
        assert!(!body.contains("[package]") && !body.contains("root:"), "{path}: {body}");
        if r.header("content-type")
            .is_some_and(|c| c.starts_with("application/json"))
        {
            r.assert_error(404, "not_found");
        }
    }
}

#[test]
fn assets_revalidate_by_etag() {
    let dir = tempfile::tempdir().expect("temp dir");
    let server = Server::start(dir.path(), &["--workers", "0", "--no-examples"], &[]);
    let first = server.get("/assets/js/app.js");
    assert_eq!(first.status, 200);
    assert_eq!(first.header("cache-control"), Some("no-cache"));
    let etag = first.header("etag").expect("an ETag").to_string();
    let again = server.request("GET", "/assets/js/app.js", &[("If-None-Match", &etag)], b"");
    assert_eq!(again.status, 304);
    assert!(again.body.is_empty());
    let other = server.request("GET", "/assets/js/app.js", &[("If-None-Match", "\"stale\"")], b"");
    assert_eq!((other.status, other.body.len()), (200, first.body.len()));
}

#[test]
fn the_test_strip_json_holds_the_rings_the_page_draws() {
    let dir = tempfile::tempdir().expect("temp dir");
    let server = Server::start(dir.path(), &["--workers", "0", "--no-examples"], &[]);
    let strip = server.get("/api/test-strip.json?thickness=4&material=acrylic").json();
    let (w, h) = (
        strip["width"].as_f64().expect("width"),
        strip["height"].as_f64().expect("height"),
    );
    let inside = |p: &serde_json::Value| {
        let (x, y) = (p[0].as_f64().expect("x"), p[1].as_f64().expect("y"));
        (0.0..=w).contains(&x) && (0.0..=h).contains(&y)
    };
    for key in ["strip", "spike"] {
        let ring = strip[key].as_array().expect(key);
        assert!(ring.len() >= 4 && ring.iter().all(inside), "{key}: {ring:?}");
    }
    assert!(
        strip["engrave"].as_array().is_some_and(|e| e.len() > 10),
        "the numbers and table"
    );
    let holes = strip["holes"].as_array().expect("holes");
    assert_eq!(holes.len(), 17);
    let mut last_x = f64::MIN;
    for hole in holes {
        let ring = hole["ring"].as_array().expect("ring");
        let xs: Vec<f64> = ring.iter().filter_map(|p| p[0].as_f64()).collect();
        let ys: Vec<f64> = ring.iter().filter_map(|p| p[1].as_f64()).collect();
        let span = |v: &[f64]| v.iter().copied().fold(f64::MIN, f64::max) - v.iter().copied().fold(f64::MAX, f64::min);
        // The drawn ring is the hole: its width along the strip, thickness + 1 mm across.
        assert!(
            (span(&xs) - hole["width"].as_f64().expect("width")).abs() < 1e-9,
            "{hole}"
        );
        assert!((span(&ys) - 5.0).abs() < 1e-9, "{hole}");
        let x = xs.iter().copied().fold(f64::MAX, f64::min);
        assert!(x > last_x, "left to right");
        last_x = x;
    }
}
