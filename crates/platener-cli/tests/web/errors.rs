//! Every error of api.md with its status and code, on one database: 400, 401, 404, 409, 413
//! (upload, triangles, an unpacking 3MF), 415, 422 (the reader's message), 429 and 503.

use std::io::Write as _;

use serde_json::json;

use crate::web_support::{Backend, Server, example_box};

/// An OBJ fan of `n` triangles around the origin (a readable model of any size).
fn obj_fan(n: usize) -> Vec<u8> {
    let mut obj = String::from("v 0 0 0\n");
    for i in 0..=n {
        let a = i as f64 / n as f64 * std::f64::consts::TAU;
        obj.push_str(&format!("v {:.4} {:.4} 0\n", 50.0 * a.cos(), 50.0 * a.sin()));
    }
    for i in 0..n {
        obj.push_str(&format!("f 1 {} {}\n", i + 2, i + 3));
    }
    obj.into_bytes()
}

/// A 3MF (a ZIP) whose model part is `size` bytes of blanks: a few kB that unpack to `size`.
fn unpacking_3mf(size: usize) -> Vec<u8> {
    let mut out = std::io::Cursor::new(Vec::new());
    let mut zip = zip::ZipWriter::new(&mut out);
    let options = zip::write::SimpleFileOptions::default().compression_method(zip::CompressionMethod::Deflated);
    zip.start_file("3D/3dmodel.model", options).expect("entry");
    zip.write_all(b"<?xml version=\"1.0\"?>").expect("write");
    zip.write_all(&vec![b' '; size]).expect("write");
    zip.finish().expect("finish");
    out.into_inner()
}

/// The error table on `backend`.
pub fn every_error_has_its_status_and_code(backend: Backend) {
    let dir = tempfile::tempdir().expect("temp dir");
    let args = [
        "--workers",
        "0",
        "--no-examples",
        "--max-upload-mb",
        "1",
        "--max-triangles",
        "150",
        "--rate-limit",
        "0",
    ];
    let Some(server) = Server::start_on(backend, dir.path(), &args, &[]) else {
        return;
    };
    not_found_and_bad_requests(&server);
    refused_uploads(&server);

    // Accepted, but no worker runs it: its plan is not ready; its files do not exist; publish,
    // unpublish and delete need its token.
    let r = server.upload("box.stl", &example_box(), &[]);
    assert_eq!(r.status, 202, "{}", r.text());
    let id = r.json()["id"].as_str().expect("id").to_string();
    let base = format!("/api/conversions/{id}");
    server.get(&format!("{base}/plan.zip")).assert_error(409, "not_ready");
    for missing in [
        "methods/cubist/plan.zip",
        "methods/plate/sheets/0.svg",
        "scenes/nothing.glb",
    ] {
        server.get(&format!("{base}/{missing}")).assert_error(404, "not_found");
    }
    let recut = |body: &[u8]| {
        server.request(
            "POST",
            &format!("{base}/recut"),
            &[("Content-Type", "application/json")],
            body,
        )
    };
    for body in [&b"[1]"[..], b"{\"colour\":1}"] {
        recut(body).assert_error(400, "bad_request");
    }
    // Understood but out of the library's range: 422 with its sentence.
    let r = recut(b"{\"kerf\":-1}");
    r.assert_error(422, "invalid_setting");
    assert!(
        r.json()["error"]["message"]
            .as_str()
            .is_some_and(|m| m.starts_with("Kerf: "))
    );
    for (method, path) in [
        ("POST", format!("{base}/publish")),
        ("DELETE", format!("{base}/publish")),
        ("DELETE", base.clone()),
    ] {
        server
            .request(method, &path, &[], b"")
            .assert_error(401, "unauthorized");
        server
            .request(method, &path, &[("Authorization", "Bearer wrong")], b"")
            .assert_error(401, "unauthorized");
    }
    assert_eq!(
        server.get(&base).json()["status"],
        "queued",
        "refused requests changed nothing"
    );
}

/// 404s for what does not exist, 400s for what cannot be understood.
fn not_found_and_bad_requests(server: &Server) {
    let unknown = format!("/api/conversions/c_{}", "0".repeat(32));
    server.get(&unknown).assert_error(404, "not_found");
    server
        .get("/api/conversions/../../etc/passwd")
        .assert_error(404, "not_found");
    server.get("/api/conversions/c_nothex").assert_error(404, "not_found");
    server.get("/nothing/here").assert_error(404, "not_found");
    server.get("/api/gallery?page=0").assert_error(400, "bad_request");
    server
        .get("/api/test-strip.svg?thickness=-1")
        .assert_error(400, "bad_request");
    server
        .get("/api/test-strip.json?material=gold")
        .assert_error(400, "bad_request");
    let box_stl = example_box();
    server
        .upload("box.stl", &box_stl, &[("material", "<b>gold</b>")])
        .assert_error(400, "bad_request");
    server
        .upload("box.stl", &box_stl, &[("colour", "red")])
        .assert_error(400, "bad_request");
    // The page's custom thickness says min="0.1"; a form may send less, and 0.05 mm hung a
    // conversion (issue 29): refused before the job is stored, naming the page's field.
    for (field, value, named) in [
        ("thickness", "0.05", "Sheet thickness"),
        ("thickness", "51", "Sheet thickness"),
        ("scale", "5000", "Scale"),
        ("kerf", "3", "Kerf"),
        ("sheet", "60000x400", "Sheet size"),
    ] {
        let r = server.upload("box.stl", &box_stl, &[(field, value)]);
        r.assert_error(422, "invalid_setting");
        let message = r.json()["error"]["message"].as_str().unwrap_or_default().to_string();
        assert!(message.starts_with(named), "{field}={value}: {message}");
    }
    server
        .request(
            "POST",
            "/api/conversions",
            &[("Content-Type", "application/json")],
            b"{}",
        )
        .assert_error(400, "bad_request");
}

/// Uploads refused for their content: 413, 415 and 422, each message saying why.
fn refused_uploads(server: &Server) {
    let message =
        |r: &crate::web_support::Response| r.json()["error"]["message"].as_str().unwrap_or_default().to_string();
    server
        .upload("page.stl", b"<html><script>alert(1)</script></html>", &[])
        .assert_error(415, "unsupported_format");
    server
        .upload("empty.stl", b"", &[])
        .assert_error(422, "unreadable_model");
    let big = vec![b'x'; 1_200_000];
    server.upload("big.stl", &big, &[]).assert_error(413, "too_large");
    // More triangles than --max-triangles: a binary STL by its header, an OBJ once read.
    let mut header_only = vec![0u8; 80];
    header_only.extend_from_slice(&1000u32.to_le_bytes());
    header_only.resize(84 + 50 * 1000, 0);
    let r = server.upload("many.stl", &header_only, &[]);
    r.assert_error(413, "too_large");
    assert!(message(&r).contains("1000 triangles"), "{}", message(&r));
    let r = server.upload("fan.obj", &obj_fan(150), &[]);
    assert_eq!(r.status, 202, "{}", r.text());
    let model = r.json()["model"].clone();
    assert_eq!(
        (&model["name"], &model["triangles"]),
        (&json!("fan.obj"), &json!(150)),
        "{model}"
    );
    assert_eq!(model["bbox_mm"][0], 100.0, "{model}");
    assert_eq!(model["bbox_mm"][2], 0.0, "{model}");
    let r = server.upload("fan.obj", &obj_fan(151), &[]);
    r.assert_error(413, "too_large");
    assert!(message(&r).contains("151 triangles"), "{}", message(&r));
    // A 3MF of a few kB that would unpack to 11 MB (the limit is 10 × 1 MB).
    let bomb = unpacking_3mf(11_000_000);
    assert!(bomb.len() < 100_000, "{} bytes", bomb.len());
    let r = server.upload("bomb.3mf", &bomb, &[]);
    r.assert_error(413, "too_large");
    assert!(message(&r).contains("unpacks to more than 10 MB"), "{}", message(&r));
    // The reader's message, with the line, and no markup of the upload's.
    let bad = "solid x\nfacet normal 0 0 1\nouter loop\nvertex <img src=x onerror=alert(1)> 0 0\n";
    let r = server.upload("bad.stl", bad.as_bytes(), &[]);
    r.assert_error(422, "unreadable_model");
    let m = message(&r);
    assert!(m.starts_with("bad.stl: line 4: "), "{m}");
    assert!(m.contains("?img src=x onerror=alert(1)?"), "{m}");
}

/// 429 beyond the per-address rate and 503 with a full queue, both with `Retry-After`.
pub fn rate_limit_and_full_queue_are_429_and_503(backend: Backend) {
    let dir = tempfile::tempdir().expect("temp dir");
    let args = [
        "--workers",
        "0",
        "--no-examples",
        "--rate-limit",
        "3",
        "--max-queue",
        "2",
    ];
    let Some(server) = Server::start_on(backend, dir.path(), &args, &[]) else {
        return;
    };
    let box_stl = example_box();
    assert_eq!(server.upload("a.stl", &box_stl, &[]).status, 202);
    assert_eq!(server.upload("b.stl", &box_stl, &[]).status, 202);
    let busy = server.upload("c.stl", &box_stl, &[]);
    busy.assert_error(503, "busy");
    assert!(busy.header("retry-after").is_some());
    server.get("/api/health").assert_error(503, "busy");
    let limited = server.upload("d.stl", &box_stl, &[]);
    limited.assert_error(429, "rate_limited");
    assert!(
        limited
            .header("retry-after")
            .and_then(|s| s.parse::<u64>().ok())
            .is_some_and(|s| (1..=60).contains(&s))
    );
}

/// The corpus' broken files: the six the reader refuses are `422` at upload with the reader's
/// line or problem; one it reads despite a quirk is accepted with its triangles.
pub fn broken_corpus_files_give_the_readers_message(backend: Backend) {
    let corpus = match platener_fixtures::samples::shared_corpus() {
        Ok(dir) => dir,
        Err(message) => {
            eprintln!("skipping: {message}");
            return;
        }
    };
    let dir = tempfile::tempdir().expect("temp dir");
    let args = ["--workers", "0", "--no-examples", "--rate-limit", "0"];
    let Some(server) = Server::start_on(backend, dir.path(), &args, &[]) else {
        return;
    };
    let read = |file: &str| std::fs::read(corpus.join("broken").join(file)).expect("corpus file");
    // The files SOURCES.md lists as not parsing, and where the reader stops.
    let cases = [
        ("openscad_invalid_vertex.stl", "openscad_invalid_vertex.stl: line 89: "),
        (
            "openscad_too_many_vertices.stl",
            "openscad_too_many_vertices.stl: line 93: ",
        ),
        ("openscad_empty_0_bytes.stl", "the file is empty"),
        ("trimesh_empty_binary_header_only.stl", "no triangles"),
        (
            "numpy_stl_incomplete_ascii.stl",
            "numpy_stl_incomplete_ascii.stl: line ",
        ),
        (
            "numpy_stl_end_solid_with_space.stl",
            "numpy_stl_end_solid_with_space.stl: line ",
        ),
    ];
    for (file, says) in cases {
        let r = server.upload(file, &read(file), &[]);
        r.assert_error(422, "unreadable_model");
        let message = r.json()["error"]["message"].as_str().unwrap_or_default().to_string();
        assert!(message.contains(says), "{file}: {message}");
    }
    let quirk = "numpy_stl_halfdonut_solid_header_trailing_byte.stl";
    let r = server.upload(quirk, &read(quirk), &[]);
    assert_eq!(r.status, 202, "{}", r.text());
    assert_eq!(r.json()["model"]["triangles"], 288);
}
