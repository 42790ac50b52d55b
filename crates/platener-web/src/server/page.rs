//! `GET /`: the web page (issue 18), `assets/index.html`, served under a strict
//! Content-Security-Policy: scripts only from this server plus the one inline import map,
//! allowed by its hash. For browsers without JavaScript the gallery is listed in a
//! `<noscript>`, every name escaped.

use std::fmt::Write as _;
use std::sync::{Arc, OnceLock};

use axum::extract::State;
use axum::http::header;
use axum::response::{IntoResponse, Response};

use super::App;
use super::assets;
use super::error::{ApiError, ApiResult};

/// Where index.html wants the `<noscript>` gallery.
const NOSCRIPT_MARK: &str = "<!--noscript-gallery-->";

/// The page's Content-Security-Policy: its own scripts and styles, the import map by hash,
/// fetches and images from this server only, no plugins, frames, forms elsewhere or `<base>`.
pub fn page_csp() -> &'static str {
    static CSP: OnceLock<String> = OnceLock::new();
    CSP.get_or_init(|| {
        let html = index_html();
        let hashes = assets::inline_script_hashes(&html).join(" ");
        format!(
            "default-src 'none'; script-src 'self' {hashes}; style-src 'self'; img-src 'self' data: blob:; \
             connect-src 'self'; base-uri 'none'; form-action 'self'; frame-ancestors 'none'"
        )
    })
}

/// The embedded `index.html` as text.
fn index_html() -> String {
    assets::file("index.html")
        .map(|d| String::from_utf8_lossy(&d).into_owned())
        .unwrap_or_default()
}

/// `text` with `& < > " '` escaped for HTML: the library's one escaping.
pub fn escape_html(text: &str) -> String {
    platener::draw::svg::xml_escape(text)
}

/// `GET /`.
pub async fn index(State(app): State<Arc<App>>) -> ApiResult<Response> {
    let html = index_html();
    if html.is_empty() {
        return Err(ApiError::internal());
    }
    let gallery = super::gallery::gallery_page(&app, 1).await?;
    let mut list = String::from("<ul>");
    for item in gallery["items"].as_array().into_iter().flatten() {
        let name = escape_html(item["name"].as_str().unwrap_or_default());
        let status = escape_html(item["status"].as_str().unwrap_or_default());
        let _ = write!(list, "<li>{name} ({status})</li>");
    }
    list.push_str("</ul>");
    Ok((
        [
            (header::CONTENT_TYPE, "text/html; charset=utf-8"),
            (header::CONTENT_SECURITY_POLICY, page_csp()),
            (header::CACHE_CONTROL, "no-cache"),
        ],
        html.replacen(NOSCRIPT_MARK, &list, 1),
    )
        .into_response())
}

/// The routes of the page: itself and its assets.
pub fn routes() -> axum::Router<std::sync::Arc<super::App>> {
    use axum::routing::get;
    axum::Router::new()
        .route("/", get(index))
        .route("/assets/{*path}", get(super::assets::asset))
}

#[cfg(test)]
mod tests {
    #[test]
    fn escapes_markup() {
        assert_eq!(
            super::escape_html("<a href='x'>&\"</a>"),
            "&lt;a href=&#39;x&#39;&gt;&amp;&quot;&lt;/a&gt;"
        );
    }
}
