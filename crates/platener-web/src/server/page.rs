//! `GET /`: a minimal placeholder page listing the gallery (the real page is issue 18),
//! served under a strict Content-Security-Policy with every name escaped.

use std::fmt::Write as _;
use std::sync::Arc;

use axum::extract::State;
use axum::http::header;
use axum::response::{IntoResponse, Response};

use super::App;
use super::error::ApiResult;

/// The page's Content-Security-Policy: nothing but its own images, no scripts.
pub const PAGE_CSP: &str = "default-src 'none'; img-src 'self'; style-src 'unsafe-inline'; base-uri 'none'; form-action 'self'; frame-ancestors 'none'";

/// `text` with `& < > " '` escaped for HTML.
pub fn escape_html(text: &str) -> String {
    let mut s = String::with_capacity(text.len());
    for c in text.chars() {
        match c {
            '&' => s.push_str("&amp;"),
            '<' => s.push_str("&lt;"),
            '>' => s.push_str("&gt;"),
            '"' => s.push_str("&quot;"),
            '\'' => s.push_str("&#39;"),
            c => s.push(c),
        }
    }
    s
}

/// `GET /`.
pub async fn index(State(app): State<Arc<App>>) -> ApiResult<Response> {
    let gallery = super::misc::gallery_page(&app, 1).await?;
    let mut html = String::from(
        "<!doctype html><html lang=\"en\"><head><meta charset=\"utf-8\"><title>platener</title></head><body>\
         <h1>platener</h1><p>3D-print models to laser-cut plans. Upload with \
         <code>curl -F model=@box.stl http://HOST/api/conversions</code>; the web page comes next.</p>\
         <h2>Gallery</h2><ul>",
    );
    for item in gallery["items"].as_array().into_iter().flatten() {
        let name = escape_html(item["name"].as_str().unwrap_or_default());
        let status = escape_html(item["status"].as_str().unwrap_or_default());
        let link = escape_html(item["links"]["self"].as_str().unwrap_or_default());
        let _ = write!(html, "<li><a href=\"{link}\">{name}</a> ({status})");
        if let Some(thumb) = item["thumbnail"].as_str() {
            let _ = write!(html, " <img src=\"{}\" alt=\"\" width=\"120\">", escape_html(thumb));
        }
        html.push_str("</li>");
    }
    html.push_str("</ul></body></html>");
    Ok((
        [
            (header::CONTENT_TYPE, "text/html; charset=utf-8"),
            (header::CONTENT_SECURITY_POLICY, PAGE_CSP),
        ],
        html,
    )
        .into_response())
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
