//! The shared corpus of real STL files (`/work/shared/corpus`, beside the workspace): every file
//! reads with the triangle count and format its SOURCES.md states, or fails as stated there.
//! Skipped, with a message, when the corpus is absent.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use platener::read::stl::{parse_bytes, read_path};
use platener::read::{Format, RawMesh, ReadErrorKind};

/// `folder/file.stl` → (triangles, "binary" | "ascii" | …, mesh-health text) from SOURCES.md.
fn stated(sources: &str) -> BTreeMap<String, (usize, String, String)> {
    let mut table = BTreeMap::new();
    let mut folder = String::new();
    for line in sources.lines() {
        if let Some(heading) = line.strip_prefix("## ") {
            folder = heading.split('/').next().unwrap_or("").to_string();
            continue;
        }
        let cells: Vec<&str> = line.split('|').map(str::trim).collect();
        if cells.len() < 9 || !cells[1].starts_with('`') {
            continue;
        }
        let Ok(triangles) = cells[4].parse() else {
            continue;
        };
        let name = cells[1].trim_matches('`');
        table.insert(
            format!("{folder}/{name}"),
            (triangles, cells[5].to_string(), cells[8].to_string()),
        );
    }
    table
}

fn stl_files(dir: &Path, out: &mut Vec<PathBuf>) {
    for entry in std::fs::read_dir(dir).expect("corpus folder").flatten() {
        let path = entry.path();
        if path.is_dir() {
            stl_files(&path, out);
        } else if path.extension().is_some_and(|e| e.eq_ignore_ascii_case("stl")) {
            out.push(path);
        }
    }
}

/// Streaming and in-memory reading must agree.
fn same(a: &Result<(Format, RawMesh), ReadErrorKind>, b: &Result<(Format, RawMesh), ReadErrorKind>, name: &str) {
    match (a, b) {
        (Ok((fa, a)), Ok((fb, b))) => {
            assert_eq!((fa, &a.triangles, &a.notes), (fb, &b.triangles, &b.notes), "{name}");
            assert_eq!((a.solids, a.zero_normals), (b.solids, b.zero_normals), "{name}");
            assert_eq!(a.normals_against_winding, b.normals_against_winding, "{name}");
        }
        (a, b) => assert_eq!(a.as_ref().err(), b.as_ref().err(), "{name}"),
    }
}

fn syntax(result: &Result<(Format, RawMesh), ReadErrorKind>, line: usize, quoted: &str) {
    match result {
        Err(ReadErrorKind::Syntax { line: l, message }) => {
            assert_eq!(*l, line, "{message}");
            assert!(message.contains(quoted), "{message} should quote {quoted}");
        }
        other => panic!("expected a syntax error at line {line}, got {other:?}"),
    }
}

fn mesh(result: &Result<(Format, RawMesh), ReadErrorKind>, format: Format, triangles: usize) -> &RawMesh {
    match result {
        Ok((f, mesh)) => {
            assert_eq!((*f, mesh.triangles.len()), (format, triangles));
            mesh
        }
        Err(e) => panic!("expected {triangles} triangles, got {e:?}"),
    }
}

/// Checks the files whose outcome the reader issue spells out; false for the others.
fn check_special(name: &str, result: &Result<(Format, RawMesh), ReadErrorKind>) -> bool {
    match name {
        "broken/openscad_invalid_vertex.stl" => syntax(result, 89, "'vertex 0 0 blah'"),
        "broken/openscad_too_many_vertices.stl" => syntax(result, 93, "facet with 4 vertices (a facet has exactly 3)"),
        "broken/numpy_stl_incomplete_ascii.stl" => syntax(result, 5, "'vertex 0.'"),
        "broken/numpy_stl_end_solid_with_space.stl" => syntax(result, 9, "unexpected text 'end solid test.stl'"),
        "broken/openscad_empty_0_bytes.stl" => {
            assert_eq!(result.as_ref().err(), Some(&ReadErrorKind::Empty))
        }
        "broken/trimesh_empty_binary_header_only.stl" => {
            assert_eq!(result.as_ref().err(), Some(&ReadErrorKind::HeaderOnly { count: 0 }));
        }
        "broken/numpy_stl_halfdonut_solid_header_trailing_byte.stl" => {
            let notes = &mesh(result, Format::StlBinary, 288).notes;
            assert!(
                notes
                    .iter()
                    .any(|n| n.starts_with("1 trailing bytes after the last facet")),
                "{notes:?}"
            );
        }
        "broken/assimp_two_solids_one_file.stl" => {
            assert_eq!(mesh(result, Format::StlAscii, 2).solids, 2)
        }
        _ => return false,
    }
    true
}

#[test]
fn corpus_files_read_as_stated() {
    let dir = match platener_fixtures::samples::shared_corpus() {
        Ok(dir) => dir,
        Err(skip) => return eprintln!("{skip}"),
    };
    let sources = std::fs::read_to_string(dir.join("SOURCES.md")).expect("the corpus has SOURCES.md");
    let table = stated(&sources);
    let mut files = Vec::new();
    stl_files(&dir, &mut files);
    assert!(files.len() >= 50, "corpus has only {} STL files", files.len());
    for path in files {
        let name = path
            .strip_prefix(&dir)
            .expect("inside")
            .to_string_lossy()
            .replace('\\', "/");
        let bytes = std::fs::read(&path).expect("readable");
        let result = parse_bytes(&bytes);
        same(&result, &read_path(&path), &name);
        if check_special(&name, &result) {
            continue;
        }
        let (triangles, format, health) = table
            .get(&name)
            .unwrap_or_else(|| panic!("{name} is not in SOURCES.md"));
        let format = match format.as_str() {
            "binary" => Format::StlBinary,
            "ascii" => Format::StlAscii,
            other => panic!("{name}: SOURCES.md states format {other}"),
        };
        let read = mesh(&result, format, *triangles);
        if let Some(against) = health
            .split("; ")
            .find_map(|h| h.strip_suffix(" stored normals against winding"))
        {
            assert_eq!(read.normals_against_winding.to_string(), against, "{name}");
        }
    }
}
