//! Model names from uploads are reduced to letters, digits, `-` and `_` (plus the format's
//! extension) before they are stored, so every place that shows one (the conversion and gallery
//! JSON, the SVG sheets, plan files, `Content-Disposition`) gets a safe name. The main flow
//! (`flow.rs`) follows a hostile name through all of them; this table checks the reduction.

use crate::web_support::{Server, example_box, multipart};

#[test]
fn names_are_reduced_to_safe_ones() {
    let dir = tempfile::tempdir().expect("temp dir");
    let args = ["--workers", "0", "--no-examples", "--rate-limit", "0"];
    let server = Server::start(dir.path(), &args, &[]);
    let box_stl = example_box();
    // (file name of the form's model field, the `name` field if any, the name kept)
    let cases = [
        (
            "<img src=x onerror=alert(1)>&\"'.stl",
            None,
            "img_src_x_onerror_alert_1.stl",
        ),
        ("../../etc/passwd.stl", None, "passwd.stl"),
        ("..\\..\\boot.ini.stl", None, "boot_ini.stl"),
        ("Würfel 立方体.stl", None, "W_rfel.stl"),
        ("\u{202E}lts.exe.stl", None, "lts_exe.stl"),
        ("....stl", None, "model.stl"),
        // The `name` field wins over the file name, and may hold what a header cannot.
        (
            "box.stl",
            Some("tab\there\u{1}\u{7f}bell\u{7}.stl"),
            "tab_here__bell.stl",
        ),
        ("box.stl", Some(&*"x".repeat(200)), &*"x".repeat(60)),
        // The extension follows the content, not the name: a binary STL called .obj.
        ("model.obj", None, "model.stl"),
    ];
    for (file, name, kept) in cases {
        let fields: Vec<(&str, &str)> = name.map(|n| ("name", n)).into_iter().collect();
        let r = server.upload(file, &box_stl, &fields);
        assert_eq!(r.status, 202, "{file:?}: {}", r.text());
        let c = r.json();
        let expected = if kept.contains('.') {
            kept.to_string()
        } else {
            format!("{kept}.stl")
        };
        assert_eq!(c["model"]["name"], expected.as_str(), "{file:?} {name:?}");
        let id = c["id"].as_str().expect("id");
        let shown = server.get(&format!("/api/conversions/{id}")).json();
        assert_eq!(shown["model"]["name"], expected.as_str());
    }
    // A file name made of bytes that are not UTF-8 is still a model, named `model`.
    let (content_type, body) = multipart("placeholder", &box_stl, &[]);
    let body = replace(&body, b"placeholder", b"\xff\xfe.stl");
    let r = server.request("POST", "/api/conversions", &[("Content-Type", &content_type)], &body);
    assert_eq!(r.status, 202, "{}", r.text());
    assert_eq!(r.json()["model"]["name"], "model.stl");
}

/// `data` with the first `from` replaced by `to`.
fn replace(data: &[u8], from: &[u8], to: &[u8]) -> Vec<u8> {
    let at = data
        .windows(from.len())
        .position(|w| w == from)
        .expect("the placeholder");
    [&data[..at], to, &data[at + from.len()..]].concat()
}
