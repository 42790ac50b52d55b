//! Step `relief` (classifier method): a texture the classifier flattened is engraved on the
//! plate it became (`--features engrave`, the default).
//!
//! A textured wall becomes one plate at the wall's fitted plane (`classify/groups.rs`); its
//! texture is gone from the cut part. Here it comes back as score marks on that plate's face:
//! for every plane primitive whose triangles replaced a fragmented set of exact faces (a
//! texture, a knurl, noise), the surface standing out of the fitted plane is projected onto the
//! face the plate has on that plane, and the outlines of those raised regions are engraved
//! there. That is the texture's pattern, as a laser can draw it, on the face it was on.
//! Regions smaller than a sheet's thickness squared are noise, not a pattern, and are dropped.
//! With `--features cut` or `ignore` the step changes nothing.

use glam::DVec3;
use platener_geom::{GridError, Polygon, boolean};
use serde::Serialize;

use crate::classify::{Classification, Surface};
use crate::context::StepContext;
use crate::error::{Error, ModelProblem, Result};
use crate::mesh::Mesh;
use crate::plan::score_rings;
use crate::plan::{MarkSide, Part, PartKind, PlanInput};
use crate::settings::{Features, Settings};

/// One texture engraved.
#[derive(Debug, Clone, Serialize)]
pub struct Texture {
    /// The plane primitive (index into the classification's).
    pub primitive: u32,
    /// The part it is engraved on.
    pub part: u32,
    /// The face.
    pub side: MarkSide,
    /// Raised regions engraved.
    pub regions: usize,
    /// Their area, mm².
    pub area: f64,
    /// How far the surface stands out of the plane at most, mm.
    pub amplitude: f64,
}

/// The snapshot of step `relief`.
#[derive(Debug, Clone, Serialize)]
pub struct Relief {
    /// The textures engraved.
    pub textures: Vec<Texture>,
    /// Why nothing was engraved, when nothing was.
    pub skipped: Option<String>,
}

/// Step `relief`: the parts of `parts` with the textures of `found`'s replaced planes engraved
/// on their faces (`None` when nothing was engraved).
pub fn run(
    mesh: &Mesh,
    found: &Classification,
    parts: &PlanInput,
    settings: &Settings,
    cx: &mut StepContext<'_>,
) -> Result<(Relief, Option<PlanInput>)> {
    if settings.features != Features::Engrave {
        let why = "textures are engraved with `features` engrave".to_string();
        return Ok((
            Relief {
                textures: Vec::new(),
                skipped: Some(why),
            },
            None,
        ));
    }
    let geometry = |e: GridError| Error::model(&parts.source.name, ModelProblem::OffGrid(e));
    let min_area = settings.thinnest() * settings.thinnest();
    let mut out = parts.clone();
    let mut textures = Vec::new();
    for &k in &found.replaced {
        cx.check_cancel()?;
        let p = &found.primitives[k as usize];
        let Surface::Plane { normal, offset } = p.shape else {
            continue;
        };
        let Some((at, side)) = face_on(&out.parts, normal, offset) else {
            continue;
        };
        let part = &mut out.parts[at];
        let (regions, amplitude) = raised(mesh, &p.triangles, normal, offset, part).map_err(geometry)?;
        let regions: Vec<Polygon> = regions.into_iter().filter(|r| r.area() >= min_area).collect();
        if regions.is_empty() {
            continue;
        }
        let area = regions.iter().map(Polygon::area).sum();
        part.marks.extend(score_rings(&regions, side));
        textures.push(Texture {
            primitive: k,
            part: part.id,
            side,
            regions: regions.len(),
            area,
            amplitude,
        });
    }
    if textures.is_empty() {
        let why = "no flattened texture stands out of its plate's face by a region of a sheet's thickness squared"
            .to_string();
        return Ok((
            Relief {
                textures,
                skipped: Some(why),
            },
            None,
        ));
    }
    Ok((
        Relief {
            textures,
            skipped: None,
        },
        Some(out),
    ))
}

/// The plate among `parts` with a face on the plane `normal · x = offset`, and which face (the
/// part lies with its local z = 0 face up).
fn face_on(parts: &[Part], normal: DVec3, offset: f64) -> Option<(usize, MarkSide)> {
    parts.iter().enumerate().find_map(|(i, p)| {
        let parallel = p.frame.n.dot(normal).abs() > 1.0 - 1e-6;
        if p.kind != PartKind::Plate || !parallel {
            return None;
        }
        let on = |z: f64| (normal.dot(p.frame.origin + p.frame.n * z) - offset).abs() < p.thickness / 10.0;
        if on(0.0) {
            Some((i, MarkSide::Top))
        } else if on(p.thickness) {
            Some((i, MarkSide::Bottom))
        } else {
            None
        }
    })
}

/// The regions of `triangles` standing out of the plane `normal · x = offset`, in `part`'s 2D
/// frame and clipped to its outline, and the most they stand out, mm.
fn raised(
    mesh: &Mesh,
    triangles: &[u32],
    normal: DVec3,
    offset: f64,
    part: &Part,
) -> std::result::Result<(Vec<Polygon>, f64), GridError> {
    let mut pieces = Vec::new();
    let mut amplitude: f64 = 0.0;
    for &f in triangles {
        let corners = mesh.triangles[f as usize].map(|v| mesh.vertices[v as usize]);
        let heights = corners.map(|c| normal.dot(c) - offset);
        amplitude = heights.iter().fold(amplitude, |a, h| a.max(*h));
        let above = above_plane(&corners, &heights);
        if above.len() < 3 {
            continue;
        }
        let mut piece = Polygon::new(above.iter().map(|&c| part.frame.to_local(c).truncate()).collect());
        piece.normalize_orientation();
        if piece.area() > 1e-9 {
            pieces.push(piece);
        }
    }
    if pieces.is_empty() {
        return Ok((Vec::new(), amplitude));
    }
    let united = boolean::union_all(&pieces)?;
    let clipped = boolean::intersection(&united, std::slice::from_ref(&part.polygon))?;
    Ok((clipped, amplitude))
}

/// The part of the triangle `corners` (heights above the plane `heights`) on or above it.
fn above_plane(corners: &[DVec3; 3], heights: &[f64; 3]) -> Vec<DVec3> {
    let mut out = Vec::with_capacity(4);
    for i in 0..3 {
        let j = (i + 1) % 3;
        let (a, b, ha, hb) = (corners[i], corners[j], heights[i], heights[j]);
        if ha >= 0.0 {
            out.push(a);
        }
        if (ha >= 0.0) != (hb >= 0.0) {
            out.push(a + (b - a) * (ha / (ha - hb)));
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_triangle_crossing_the_plane_keeps_the_part_above_it() {
        let corners = [
            DVec3::new(0.0, 0.0, -1.0),
            DVec3::new(2.0, 0.0, 1.0),
            DVec3::new(0.0, 2.0, 1.0),
        ];
        let heights = corners.map(|c| c.z);
        let above = above_plane(&corners, &heights);
        // The quad from the crossings (1, 0) and (0, 1) up to the two corners above.
        assert_eq!(above.len(), 4);
        assert!(above.iter().all(|p| p.z >= 0.0));
        assert!(above.contains(&DVec3::new(1.0, 0.0, 0.0)) && above.contains(&DVec3::new(0.0, 1.0, 0.0)));
        assert!(above_plane(&corners, &heights.map(|h| h - 5.0)).is_empty());
    }
}
