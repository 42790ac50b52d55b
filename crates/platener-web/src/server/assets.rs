//! `GET /assets/{path}`: the web page's static files, embedded in the binary (rust-embed) so
//! that `platener serve` needs nothing beside it. Only files in `assets/` with a known
//! extension are served, each with a fixed content type (never guessed from the bytes), an
//! ETag of its content and `no-cache` (the browser revalidates, so a new binary's page is
//! never mixed with an old cached module).

use axum::extract::Path;
use axum::http::{HeaderMap, HeaderValue, StatusCode, header};
use axum::response::{IntoResponse, Response};
use base64::Engine as _;
use rust_embed::Embed;
use sha2::{Digest, Sha256};

use super::error::ApiError;

/// The files under `crates/platener-web/assets/`.
#[derive(Embed)]
#[folder = "assets/"]
struct Assets;

/// One embedded file's bytes, if `path` names one (relative, `/`-separated, no `..`).
pub fn file(path: &str) -> Option<std::borrow::Cow<'static, [u8]>> {
    if !safe_path(path) {
        return None;
    }
    Assets::get(path).map(|f| f.data)
}

/// A path that stays inside `assets/`: non-empty segments of ordinary names only. The
/// embedded table could not be escaped anyway, but in debug builds rust-embed reads the
/// folder from disk, so `..`, absolute paths and backslashes are refused before any lookup.
fn safe_path(path: &str) -> bool {
    !path.is_empty()
        && !path.contains('\\')
        && !path.contains('\0')
        && path.split('/').all(|seg| !seg.is_empty() && seg != "." && seg != "..")
}

/// The content type of a served file, by its extension; `None`: not served.
pub fn content_type(path: &str) -> Option<&'static str> {
    let name = path.rsplit('/').next().unwrap_or(path);
    let ext = name.rsplit_once('.').map(|(_, e)| e);
    Some(match ext {
        Some("html") => "text/html; charset=utf-8",
        Some("css") => "text/css; charset=utf-8",
        Some("js" | "mjs") => "text/javascript; charset=utf-8",
        Some("json") => "application/json",
        Some("svg") => "image/svg+xml",
        Some("png") => "image/png",
        Some("txt" | "md") => "text/plain; charset=utf-8",
        // The vendored licence and version files.
        None if matches!(name, "LICENSE" | "VERSION") => "text/plain; charset=utf-8",
        _ => return None,
    })
}

/// `GET /assets/{*path}`.
pub async fn asset(Path(path): Path<String>, headers: HeaderMap) -> Response {
    let (Some(content_type), Some(data)) = (content_type(&path), file(&path)) else {
        return ApiError::not_found("file").into_response();
    };
    let etag = format!("\"{}\"", hex(&Sha256::digest(&data)[..12]));
    let fresh = headers
        .get(header::IF_NONE_MATCH)
        .and_then(|v| v.to_str().ok())
        .is_some_and(|v| v.split(',').any(|t| t.trim() == etag));
    let status = if fresh {
        StatusCode::NOT_MODIFIED
    } else {
        StatusCode::OK
    };
    let mut response = if fresh {
        status.into_response()
    } else {
        data.into_owned().into_response()
    };
    let h = response.headers_mut();
    h.insert(header::CONTENT_TYPE, HeaderValue::from_static(content_type));
    h.insert(header::CACHE_CONTROL, HeaderValue::from_static("no-cache"));
    if let Ok(v) = HeaderValue::from_str(&etag) {
        h.insert(header::ETAG, v);
    }
    response
}

fn hex(bytes: &[u8]) -> String {
    bytes.iter().map(|b| format!("{b:02x}")).collect()
}

/// `'sha256-…'` of every inline `<script>` in `html` (the page has one: the import map), for
/// the page's Content-Security-Policy. Computed from the embedded file, so editing the import
/// map can never leave a stale hash behind.
pub fn inline_script_hashes(html: &str) -> Vec<String> {
    let mut hashes = Vec::new();
    let mut rest = html;
    while let Some(start) = rest.find("<script") {
        let after = &rest[start..];
        let Some(open_end) = after.find('>') else { break };
        let tag = &after[..open_end];
        let body = &after[open_end + 1..];
        let Some(close) = body.find("</script>") else { break };
        if !tag.contains("src=") {
            let digest = Sha256::digest(&body.as_bytes()[..close]);
            let b64 = base64::engine::general_purpose::STANDARD.encode(digest);
            hashes.push(format!("'sha256-{b64}'"));
        }
        rest = &body[close..];
    }
    hashes
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn paths_that_leave_the_folder_are_refused() {
        for bad in [
            "",
            "/etc/passwd",
            "../Cargo.toml",
            "js/../../Cargo.toml",
            "js//app.js",
            ".",
            "a\\b",
            "./index.html",
        ] {
            assert!(!safe_path(bad), "{bad}");
            assert!(file(bad).is_none(), "{bad}");
        }
        assert!(file("index.html").is_some());
        assert!(file("vendor/three/build/three.module.js").is_some());
    }

    #[test]
    fn content_types_are_fixed_by_extension() {
        assert_eq!(content_type("js/app.js"), Some("text/javascript; charset=utf-8"));
        assert_eq!(content_type("app.css"), Some("text/css; charset=utf-8"));
        assert_eq!(content_type("vendor/three/LICENSE"), Some("text/plain; charset=utf-8"));
        assert_eq!(content_type("x.exe"), None);
        assert_eq!(content_type("Makefile"), None);
    }

    #[test]
    fn inline_script_hash_is_the_sha256_of_its_text() {
        let html = "<script src=\"/a.js\"></script><script type=\"importmap\">{}</script>";
        // printf '{}' | openssl dgst -sha256 -binary | base64
        assert_eq!(
            inline_script_hashes(html),
            ["'sha256-RBNvo1WzZ4oRRq0W9+hknpT7T8If536DEMBg9hyq/4o='"]
        );
    }
}
