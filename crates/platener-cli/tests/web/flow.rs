//! The API's main flow on one database: upload (under a hostile name) → events → done → every
//! link answers what it names → the ZIP verifies with `platener verify` → publish, gallery,
//! recut, delete.

use std::io::Read as _;
use std::path::Path;

use serde_json::{Value, json};

use crate::web_support::plans::{all_links, zip_parts};
use crate::web_support::{Backend, Server, events, example_box};

/// The name the flow uploads the box under: markup, an entity, both quotes.
pub const HOSTILE: &str = "<img src=x onerror=alert(1)>&\"'.stl";
/// What the server keeps of it (`api::safe_stem`).
pub const REDUCED: &str = "img_src_x_onerror_alert_1.stl";

/// A ZIP's entries: (name, content).
fn zip_entries(zip: &[u8]) -> Vec<(String, Vec<u8>)> {
    let mut archive = zip::ZipArchive::new(std::io::Cursor::new(zip)).expect("a ZIP");
    (0..archive.len())
        .map(|i| {
            let mut entry = archive.by_index(i).expect("entry");
            let mut data = Vec::new();
            entry.read_to_end(&mut data).expect("unpacks");
            (entry.name().expect("a UTF-8 entry name").to_string(), data)
        })
        .collect()
}

/// Text a hostile name would leave behind if it were not reduced. The assembly instructions'
/// page shows its own pictures: there an `<img` is ours, and the rest must still be absent.
fn assert_no_markup(what: &str, text: &str) {
    let page = what.ends_with(".html");
    for bad in ["<img", "onerror=", "&\"'", "alert(1)"] {
        if page && bad == "<img" {
            continue;
        }
        assert!(!text.contains(bad), "{what} holds {bad:?}");
    }
}

/// A ZIP from the API: an attachment named after the reduced name, every entry named safely
/// and free of the hostile name, and its parts.
fn check_zip(link: &str, r: &crate::web_support::Response) -> usize {
    let method = link
        .split("/methods/")
        .nth(1)
        .and_then(|m| m.split('/').next())
        .unwrap_or("plate");
    let stem = REDUCED.trim_end_matches(".stl");
    assert_eq!(
        r.header("content-disposition"),
        Some(format!("attachment; filename=\"{stem}-{method}.zip\"").as_str()),
        "{link}"
    );
    for (name, data) in zip_entries(&r.body) {
        assert!(
            name.bytes().all(|b| b.is_ascii_alphanumeric() || b"._-/".contains(&b)),
            "{link}: entry {name:?}"
        );
        assert_no_markup(&format!("{link}: {name}"), &String::from_utf8_lossy(&data));
    }
    zip_parts(&r.body)
}

/// Checks one link's answer by what it names: content type, magic bytes, headers, and that
/// nothing in it carries the hostile name unreduced.
fn check_link(server: &Server, link: &str) {
    let r = server.get(link);
    assert_eq!(r.status, 200, "{link}: {}", r.text());
    assert_eq!(r.header("x-content-type-options"), Some("nosniff"), "{link}");
    let path = link.split('?').next().unwrap_or_default();
    let ct = r.header("content-type").unwrap_or_default().to_string();
    if path.ends_with(".zip") {
        assert_eq!(ct, "application/zip", "{link}");
        assert!(check_zip(link, &r) > 0, "{link}");
    } else if path.ends_with(".glb") {
        assert_eq!(ct, "model/gltf-binary", "{link}");
        assert_eq!(&r.body[..4], b"glTF", "{link}");
    } else if path.ends_with(".png") {
        assert_eq!(ct, "image/png", "{link}");
        assert_eq!(&r.body[..4], b"\x89PNG", "{link}");
    } else if path.ends_with(".svg") {
        assert_eq!(ct, "image/svg+xml", "{link}");
        assert!(r.text().contains("<svg"), "{link}");
        assert_no_markup(link, &r.text());
        assert!(r.header("content-security-policy").is_some(), "{link}");
    } else if path.ends_with(".html") {
        // The assembly instructions (issue 35): a page with no script, sandboxed.
        assert!(ct.starts_with("text/html"), "{link}: {ct}");
        let text = r.text();
        assert!(
            text.starts_with("<!DOCTYPE html>") && !text.contains("<script"),
            "{link}"
        );
        let csp = r.header("content-security-policy").unwrap_or_default();
        assert!(
            csp.contains("sandbox") && csp.contains("default-src 'none'"),
            "{link}: {csp}"
        );
    } else {
        assert!(ct.starts_with("application/json"), "{link}: {ct}");
        assert_no_markup(link, &r.text());
        r.json();
    }
}

/// `platener verify ZIP --model box-3mm.stl --json` on a ZIP the API served: it must pass.
fn verify_against_the_box(zip: &[u8]) -> Value {
    let dir = tempfile::tempdir().expect("temp dir");
    let path = dir.path().join("plan.zip");
    std::fs::write(&path, zip).expect("write the ZIP");
    let model = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/box-3mm.stl");
    let o = std::process::Command::new(env!("CARGO_BIN_EXE_platener"))
        .arg("verify")
        .arg(&path)
        .arg("--model")
        .arg(model)
        .arg("--json")
        .output()
        .expect("platener verify runs");
    assert_eq!(o.status.code(), Some(0), "{}", String::from_utf8_lossy(&o.stdout));
    serde_json::from_slice(&o.stdout).expect("verify's JSON")
}

/// Uploads the box under [`HOSTILE`]: the `202` as the reader found the model. Returns the id,
/// the delete token and the bounding box.
fn upload_box(server: &Server) -> (String, String, Value) {
    let r = server.upload(HOSTILE, &example_box(), &[("thickness", "3"), ("material", "wood")]);
    assert_eq!(r.status, 202, "{}", r.text());
    assert_no_markup("the 202", &r.text());
    let c = r.json();
    let id = c["id"].as_str().expect("id").to_string();
    assert_eq!(r.header("location"), Some(format!("/api/conversions/{id}").as_str()));
    assert_eq!(c["status"], "queued");
    assert_eq!(c["model"]["name"], REDUCED);
    assert_eq!(c["model"]["triangles"], 120, "read at upload: {c}");
    let bbox = c["model"]["bbox_mm"].clone();
    let sizes: Vec<f64> = bbox
        .as_array()
        .expect("bbox")
        .iter()
        .filter_map(Value::as_f64)
        .collect();
    assert!(sizes.len() == 3 && sizes.iter().all(|s| *s > 10.0), "{bbox}");
    let token = c["delete_token"].as_str().expect("a delete token once").to_string();
    (id, token, bbox)
}

/// The whole flow on `backend`.
pub fn upload_convert_and_every_link_works(backend: Backend) {
    let dir = tempfile::tempdir().expect("temp dir");
    let Some(server) = Server::start_on(backend, dir.path(), &["--workers", "2", "--no-examples"], &[]) else {
        return;
    };
    let (id, token, bbox) = upload_box(&server);

    let evs = events(&server.addr, &id);
    let kinds: Vec<&str> = evs.iter().map(|(k, _)| k.as_str()).collect();
    assert_eq!(kinds.last(), Some(&"done"), "{kinds:?}");
    assert!(
        evs.iter()
            .any(|(k, d)| k == "step" && d["step"] == "read" && d["state"] == "finished")
    );
    for m in ["plate", "stacked"] {
        assert!(
            evs.iter().any(|(k, d)| k == "method" && d["method"] == m),
            "{m}: {kinds:?}"
        );
    }
    // A late client gets the same events so far.
    assert_eq!(events(&server.addr, &id).len(), evs.len());

    let r = server.get(&format!("/api/conversions/{id}"));
    assert_no_markup("the conversion", &r.text());
    let c = r.json();
    assert_eq!(c["status"], "done", "{c}");
    assert_eq!(c["best"], "plate");
    assert!(c.get("delete_token").is_none(), "the token is shown once only");
    assert_eq!(c["model"]["name"], REDUCED);
    assert_eq!(c["model"]["triangles"], 120);
    assert_eq!(
        c["model"]["bbox_mm"], bbox,
        "the worker's read agrees with the upload's"
    );
    let plate = c["methods"]
        .as_array()
        .expect("methods")
        .iter()
        .find(|m| m["method"] == "plate")
        .expect("plate")
        .clone();
    assert_eq!(plate["parts"], 6, "{plate}");
    assert_eq!(plate["glue"], "glue-free", "{plate}");
    assert_eq!(plate["status"], "done");
    assert!(plate["score"].as_f64().is_some_and(|s| s > 0.5 && s <= 1.0), "{plate}");
    let zip = server.get(&format!("/api/conversions/{id}/plan.zip")).body;
    assert_eq!(zip_parts(&zip), 6);
    let verdict = verify_against_the_box(&zip);
    assert_eq!(
        (verdict["parts"].as_u64(), verdict["groups"].as_u64()),
        (Some(6), Some(1)),
        "{verdict}"
    );

    let mut links = Vec::new();
    all_links(&c["links"], &mut links);
    assert!(links.len() > 20, "{links:?}");
    for view in ["model", "wireframe", "coplanar", "plates", "bent", "final"] {
        assert!(c["links"]["scenes"][view].is_string(), "scene {view}");
    }
    // Beside the plate method the classifier skips the box's exact faces, saying why: no
    // primitives of its own, and none among the best method's scenes (the plate method
    // classifies nothing). `recut` below asks for the classifier alone, which runs.
    let classifier = c["methods"]
        .as_array()
        .and_then(|m| m.iter().find(|m| m["method"] == "classifier"))
        .expect("classifier");
    assert_eq!(classifier["status"], "skipped", "{classifier}");
    assert!(
        classifier["error"].to_string().contains("faces are exact"),
        "{classifier}"
    );
    assert!(c["links"]["methods"]["classifier"]["scenes"]["primitives"].is_null());
    assert!(c["links"]["scenes"]["primitives"].is_null());
    assert!(links.iter().any(|l| l.ends_with(".svg")), "{links:?}");
    for link in links.iter().filter(|l| !l.ends_with("/events")) {
        check_link(&server, link);
    }

    publish_recut_delete(&server, &id, &token);
}

/// The gallery's thumbnail is the assembly's picture (320 × 240 PNG), not a sheet preview.
fn assert_thumbnail(server: &Server, link: &str) {
    assert!(link.ends_with("/thumbnail.png"), "{link}");
    let r = server.get(link);
    assert_eq!(r.status, 200);
    assert_eq!(&r.body[1..4], b"PNG", "{link}");
    // IHDR: width and height, big-endian, at bytes 16..24.
    let size = |i: usize| u32::from_be_bytes([r.body[i], r.body[i + 1], r.body[i + 2], r.body[i + 3]]);
    assert_eq!((size(16), size(20)), (320, 240), "{link}");
}

/// Unpublishing (an extension of api.md: `DELETE …/publish` with the delete token) takes the
/// conversion out of the gallery, keeps it reachable by its id, and publishing again works.
fn unpublish(server: &Server, id: &str, bearer: &str) {
    let publish = format!("/api/conversions/{id}/publish");
    server
        .request("DELETE", &publish, &[], b"")
        .assert_error(401, "unauthorized");
    server
        .request("DELETE", &publish, &[("Authorization", "Bearer 00")], b"")
        .assert_error(401, "unauthorized");
    let in_gallery = || {
        let g = server.get("/api/gallery?page=1").json();
        g["items"].as_array().expect("items").iter().any(|i| i["id"] == id)
    };
    assert!(in_gallery(), "refused requests changed nothing");
    for _ in 0..2 {
        let r = server.request("DELETE", &publish, &[("Authorization", bearer)], b"");
        assert_eq!(r.status, 200, "{}", r.text());
        assert_eq!(r.json()["published"], false, "unpublishing twice is harmless");
        assert!(!in_gallery(), "still in the gallery");
    }
    assert_eq!(server.get(&format!("/api/conversions/{id}")).status, 200);
    let r = server.request("POST", &publish, &[("Authorization", bearer)], b"");
    assert_eq!(r.json()["published"], true, "{}", r.text());
    assert!(in_gallery(), "published again");
}

/// Publish (401 without the token), gallery, unpublish, recut, delete.
fn publish_recut_delete(server: &Server, id: &str, token: &str) {
    let publish = format!("/api/conversions/{id}/publish");
    server
        .request("POST", &publish, &[], b"")
        .assert_error(401, "unauthorized");
    server
        .request("POST", &publish, &[("Authorization", "Bearer 00")], b"")
        .assert_error(401, "unauthorized");
    let bearer = format!("Bearer {token}");
    let r = server.request("POST", &publish, &[("Authorization", &bearer)], b"");
    assert_eq!(r.status, 200, "{}", r.text());
    assert_eq!(r.json()["published"], true);
    let g = server.get("/api/gallery?page=1");
    assert_no_markup("the gallery", &g.text());
    let g = g.json();
    let item = &g["items"][0];
    assert_eq!(item["id"], id);
    assert_eq!(item["name"], REDUCED);
    assert_eq!(item["parts"], 6);
    assert_thumbnail(server, item["thumbnail"].as_str().expect("thumbnail"));
    unpublish(server, id, &bearer);

    // The classifier alone: it runs on the box's exact faces (beside the plate method it skips).
    let body = json!({"kerf": 0.15, "method": "classifier"}).to_string();
    let r = server.request(
        "POST",
        &format!("/api/conversions/{id}/recut"),
        &[("Content-Type", "application/json")],
        body.as_bytes(),
    );
    assert_eq!(r.status, 202, "{}", r.text());
    let recut = r.json();
    let rid = recut["id"].as_str().expect("id");
    assert_ne!(rid, id);
    assert_eq!(recut["recut_of"], id);
    assert_eq!(recut["settings"]["kerf"], 0.15);
    assert_eq!(recut["model"]["triangles"], 120, "a recut is read too");
    let done = server.wait_ended(rid);
    assert_eq!(done["status"], "done", "{done}");
    // Its primitives are among its own method's scenes, not the best method's.
    let primitives = done["links"]["methods"]["classifier"]["scenes"]["primitives"]
        .as_str()
        .expect("the classifier's primitives");
    assert_eq!(server.get(primitives).status, 200);

    let path = format!("/api/conversions/{id}");
    server
        .request("DELETE", &path, &[], b"")
        .assert_error(401, "unauthorized");
    assert_eq!(
        server
            .request("DELETE", &path, &[("Authorization", &bearer)], b"")
            .status,
        204
    );
    server.get(&path).assert_error(404, "not_found");
    server.get(&format!("{path}/plan.zip")).assert_error(404, "not_found");
    server.get(&format!("{path}/events")).assert_error(404, "not_found");
    let g = server.get("/api/gallery").json();
    assert!(g["items"].as_array().expect("items").iter().all(|i| i["id"] != id));
    assert_eq!(
        server.get(&format!("/api/conversions/{rid}")).status,
        200,
        "the recut stays"
    );
}
