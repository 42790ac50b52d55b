//! Wavefront OBJ reader on `tobj`.
//!
//! tobj groups faces into objects and triangulates polygons, but its errors carry no line number
//! and it can panic on absurd texture/normal indices, so a first pass here validates every vertex
//! and face line (naming the line) and hands tobj only the position data it needs.

use std::borrow::Cow;
use std::path::Path;

use glam::DVec3;

use super::{RawMesh, ReadErrorKind, Triangle};

/// Reads every object of an OBJ file, triangulating polygons.
///
/// Only positions are read: texture coordinates, normals, materials (`mtllib`, `usemtl`), lines
/// and points are ignored, so a missing `.mtl` file is not an error. Each `o`/`g` block that
/// holds faces counts as one solid. An empty file gives an empty mesh.
pub fn read_path(path: &Path) -> Result<RawMesh, ReadErrorKind> {
    let bytes = std::fs::read(path).map_err(|e| ReadErrorKind::Io(e.to_string()))?;
    parse_bytes(&bytes)
}

/// Reads an OBJ held in memory (uploads), as [`read_path`] reads a file.
pub fn parse_bytes(bytes: &[u8]) -> Result<RawMesh, ReadErrorKind> {
    let text = String::from_utf8_lossy(bytes);
    let prepared = prepare(&text, matches!(text, Cow::Owned(_)))?;
    read_prepared(prepared)
}

/// What the validating pass hands to tobj, plus what it noticed.
struct Prepared {
    /// The file reduced to `v` (x y z [w]), `f` (position indices only), `o` and `g` lines.
    text: String,
    /// Faces with fewer than three corners, dropped.
    short_faces: usize,
    /// Faces with five or more corners, fan-triangulated by tobj.
    large_polygons: usize,
    /// Whether the file was not valid UTF-8 (read with replacement characters).
    lossy: bool,
}

/// Validates vertex and face lines (naming the line on error) and builds the text for tobj.
/// `lossy` says whether `text` was decoded with replacement characters.
fn prepare(text: &str, lossy: bool) -> Result<Prepared, ReadErrorKind> {
    let total_vertices = text
        .lines()
        .filter(|line| line.split_whitespace().next() == Some("v"))
        .count();
    let mut out = String::with_capacity(text.len());
    let mut vertices_so_far = 0usize;
    let mut short_faces = 0;
    let mut large_polygons = 0;
    for (index, line) in text.lines().enumerate() {
        let number = index + 1;
        let mut words = line.split_whitespace();
        match words.next() {
            Some("v") => {
                vertex_line(number, words, &mut out)?;
                vertices_so_far += 1;
            }
            Some("f") => {
                let corners = face_line(number, words, vertices_so_far, total_vertices, &mut out)?;
                if corners < 3 {
                    short_faces += 1;
                } else if corners >= 5 {
                    large_polygons += 1;
                }
            }
            Some(keyword @ ("o" | "g")) => {
                let name = line.trim_start()[keyword.len()..].trim();
                out.push_str(keyword);
                out.push(' ');
                out.push_str(name);
                out.push('\n');
            }
            // Comments, texture coordinates, normals, materials, smoothing groups, lines, points
            // and unknown keywords carry nothing we need.
            _ => {}
        }
    }
    Ok(Prepared {
        text: out,
        short_faces,
        large_polygons,
        lossy,
    })
}

/// Checks a `v x y z [w | r g b]` line and appends `v x y z [w]` to `out`.
fn vertex_line<'a>(line: usize, words: impl Iterator<Item = &'a str>, out: &mut String) -> Result<(), ReadErrorKind> {
    let words: Vec<&str> = words.collect();
    if words.len() < 3 {
        return Err(ReadErrorKind::Obj(format!(
            "line {line}: a vertex needs three coordinates, found {:?}; repair or re-export the file",
            words.join(" ")
        )));
    }
    let coordinates = words.get(..3).unwrap_or_default();
    for word in coordinates {
        let value: f64 = word.parse().map_err(|_| {
            ReadErrorKind::Obj(format!(
                "line {line}: vertex coordinate {word:?} is not a number; repair or re-export the file"
            ))
        })?;
        if !value.is_finite() {
            return Err(ReadErrorKind::NonFinite {
                location: format!("line {line}"),
                value: (*word).to_owned(),
            });
        }
    }
    out.push('v');
    for word in coordinates {
        out.push(' ');
        out.push_str(word);
    }
    // Exactly four numbers: the fourth is the homogeneous weight, which tobj divides by.
    // Six numbers are x y z r g b; the colour is not needed and is dropped.
    if let [_, _, _, w] = words.as_slice() {
        let weight: f64 = w.parse().map_err(|_| {
            ReadErrorKind::Obj(format!(
                "line {line}: vertex weight {w:?} is not a number; repair or re-export the file"
            ))
        })?;
        if weight == 0.0 || !weight.is_finite() {
            return Err(ReadErrorKind::Obj(format!(
                "line {line}: vertex weight (4th number) is {w}, which does not give a point; \
                 repair or re-export the file"
            )));
        }
        out.push(' ');
        out.push_str(w);
    }
    out.push('\n');
    Ok(())
}

/// Checks an `f` line's position indices and appends `f i j k …` (positions only) to `out`.
/// Returns the number of corners. Faces with fewer than three corners are not written.
fn face_line<'a>(
    line: usize,
    words: impl Iterator<Item = &'a str>,
    vertices_so_far: usize,
    total_vertices: usize,
    out: &mut String,
) -> Result<usize, ReadErrorKind> {
    let mut face = String::from("f");
    let mut corners = 0;
    for word in words {
        let position = word.split('/').next().unwrap_or_default();
        let index: i64 = position.parse().map_err(|_| {
            ReadErrorKind::Obj(format!(
                "line {line}: face corner {word:?} does not start with a vertex index; \
                 repair or re-export the file"
            ))
        })?;
        let valid = match index {
            0 => {
                return Err(ReadErrorKind::Obj(format!(
                    "line {line}: face uses vertex index 0, but OBJ indices start at 1; \
                     the exporter is broken: re-export the file"
                )));
            }
            // 1-based; tobj, like most readers, also accepts vertices defined after the face.
            i if i > 0 => usize::try_from(i).is_ok_and(|i| i <= total_vertices),
            // Relative: -1 is the last vertex defined before this line.
            i => usize::try_from(i.unsigned_abs()).is_ok_and(|back| back <= vertices_so_far),
        };
        if !valid {
            let defined = if index > 0 {
                format!("the file defines only {total_vertices} vertices")
            } else {
                format!("only {vertices_so_far} vertices are defined before this line")
            };
            return Err(ReadErrorKind::Obj(format!(
                "line {line}: face refers to vertex {index}, but {defined}; \
                 the file is damaged or truncated: re-export it"
            )));
        }
        face.push(' ');
        face.push_str(position);
        corners += 1;
    }
    if corners >= 3 {
        out.push_str(&face);
        out.push('\n');
    }
    Ok(corners)
}

/// Runs tobj on the validated text and collects the triangles, checking they are finite.
fn read_prepared(prepared: Prepared) -> Result<RawMesh, ReadErrorKind> {
    #[allow(
        clippy::needless_update,
        reason = "tobj has more fields when its `merging`/`reordering` features are on"
    )]
    let options = tobj::LoadOptions {
        triangulate: true,
        single_index: false,
        ignore_points: true,
        ignore_lines: true,
        ..Default::default()
    };
    // `mtllib` lines were dropped, so the material loader is never asked for anything.
    let (models, _materials) = tobj::load_obj_buf(&mut prepared.text.as_bytes(), &options, |_| {
        Err(tobj::LoadError::OpenFileFailed)
    })
    .map_err(|e| {
        ReadErrorKind::Obj(format!(
            "{e} (tobj); the file is not a valid OBJ: repair or re-export it"
        ))
    })?;

    let mut mesh = RawMesh::default();
    for (number, model) in models.iter().enumerate() {
        let label = if model.name.is_empty() {
            format!("object #{}", number + 1)
        } else {
            format!("object {:?}", model.name)
        };
        let before = mesh.triangles.len();
        let positions = &model.mesh.positions;
        for (t, corners) in model.mesh.indices.chunks(3).enumerate() {
            let mut triangle: Triangle = [DVec3::ZERO; 3];
            for (slot, &index) in triangle.iter_mut().zip(corners) {
                let start = usize::try_from(index).unwrap_or(usize::MAX);
                let xyz = start
                    .checked_mul(3)
                    .and_then(|s| positions.get(s..s.checked_add(3)?))
                    .ok_or_else(|| {
                        ReadErrorKind::Obj(format!(
                            "{label}, triangle {t}: tobj returned a vertex index outside the \
                             object; re-export the file (and please report this file)"
                        ))
                    })?;
                let point = DVec3::new(widen(xyz[0]), widen(xyz[1]), widen(xyz[2]));
                if let Some(bad) = point.to_array().into_iter().find(|c| !c.is_finite()) {
                    return Err(ReadErrorKind::NonFinite {
                        location: format!("{label}, triangle {t}"),
                        value: bad.to_string(),
                    });
                }
                *slot = point;
            }
            if corners.len() == 3 {
                mesh.triangles.push(triangle);
            }
        }
        if mesh.triangles.len() > before {
            mesh.solids += 1;
        }
    }

    if prepared.lossy {
        mesh.notes
            .push("the file is not valid UTF-8; unreadable characters were replaced".into());
    }
    if prepared.short_faces > 0 {
        mesh.notes.push(format!(
            "{} faces with fewer than three corners were ignored",
            prepared.short_faces
        ));
    }
    if prepared.large_polygons > 0 {
        mesh.notes.push(format!(
            "{} faces with five or more corners were split into triangles fanning from their \
             first corner (right for convex faces only)",
            prepared.large_polygons
        ));
    }
    Ok(mesh)
}

/// tobj stores `f32` unless built with `use_f64`; accept either without a lossy cast.
fn widen<T: Into<f64>>(value: T) -> f64 {
    value.into()
}
