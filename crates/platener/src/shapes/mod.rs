//! Step `shapes` (the thesis' ShapesFinder and HoleDetection): each planar group's outline.
//!
//! A group's boundary is the set of its half-edges not cancelled by a neighbour in the group
//! running the same edge the other way (net count, so non-manifold edges come out right).
//! Boundary half-edges are chained into closed loops in linear time, taken into the group's own
//! 2D frame, cleared of vertices on straight runs, and turned into polygons with holes by the
//! even-odd rule: a loop inside one loop is a hole, a loop inside a hole is a shape of its own.

mod loops;

use platener_geom::polygon::remove_straight_vertices;
use platener_geom::{Frame, GridError, Polygon, Ring, boolean};
use rayon::prelude::*;
use serde::Serialize;

use crate::cleanup::Cleaned;
use crate::context::StepContext;
use crate::coplanar::{PlanarGroup, PlanarGroups};
use crate::error::{Error, ModelProblem, Result};
use crate::mesh::Mesh;
use crate::settings::Settings;

/// One planar shape: a polygon with holes in its plane, and where that plane is.
#[derive(Debug, Clone, Serialize)]
pub struct Shape {
    /// Index of the planar group it came from.
    pub group: u32,
    /// The plane's frame: `frame.to_model_2d(p)` puts a polygon point back on the model.
    pub frame: Frame,
    /// The outline (counter-clockwise seen from the normal side) and holes (clockwise).
    pub polygon: Polygon,
    /// Area in mm².
    pub area: f64,
}

/// The snapshot of step `shapes`.
#[derive(Debug, Clone, Serialize)]
pub struct Shapes {
    /// Shapes, largest first.
    pub shapes: Vec<Shape>,
    /// Boundary loops dropped: fewer than 3 vertices after simplification, or not closed.
    pub loops_dropped: usize,
    /// Vertices removed from straight runs.
    pub vertices_removed: usize,
    /// The straight-run tolerance used (mm).
    pub straight_tolerance: f64,
}

struct GroupShapes {
    shapes: Vec<Shape>,
    dropped: usize,
    removed: usize,
}

fn shapes_of_group(mesh: &Mesh, groups: &PlanarGroups, gid: usize, tolerance: f64) -> Result<GroupShapes, GridError> {
    let group: &PlanarGroup = &groups.groups[gid];
    let (loops, open) = loops::boundary_loops(mesh, &groups.face_group, gid as u32, &group.faces);
    let origin_on_plane = {
        let c = group.faces.iter().map(|&f| {
            let [a, b, c] = mesh.corners(f as usize);
            (a + b + c) / 3.0 * mesh.areas[f as usize]
        });
        let centroid = c.fold(glam::DVec3::ZERO, |s, p| s + p) / group.area;
        centroid - group.normal * (group.normal.dot(centroid) - group.offset)
    };
    let frame = Frame::on_plane(origin_on_plane, group.normal);
    let mut dropped = open;
    let mut removed = 0;
    let mut rings: Vec<Ring> = Vec::with_capacity(loops.len());
    for lp in loops {
        // Through the vertices refitted to the model's planes, not the welded ones.
        let ring: Ring = lp.iter().map(|&v| frame.to_2d(groups.vertices[v as usize])).collect();
        let simple = remove_straight_vertices(&ring, tolerance);
        removed += ring.len() - simple.len();
        if simple.len() < 3 {
            dropped += 1;
        } else {
            rings.push(simple);
        }
    }
    let polygons = boolean::from_rings_even_odd(&rings)?;
    let shapes = polygons
        .into_iter()
        .map(|polygon| Shape {
            group: gid as u32,
            frame,
            area: polygon.area(),
            polygon,
        })
        .collect();
    Ok(GroupShapes {
        shapes,
        dropped,
        removed,
    })
}

/// Finds the shapes of every planar group.
pub fn find_shapes(mesh: &Mesh, groups: &PlanarGroups, tolerance: f64) -> Result<Shapes, GridError> {
    let per_group: Vec<GroupShapes> = (0..groups.groups.len())
        .into_par_iter()
        .map(|g| shapes_of_group(mesh, groups, g, tolerance))
        .collect::<Result<_, _>>()?;
    let mut shapes = Vec::new();
    let (mut dropped, mut removed) = (0, 0);
    for g in per_group {
        shapes.extend(g.shapes);
        dropped += g.dropped;
        removed += g.removed;
    }
    // Largest first; the sort is stable, so equal areas keep group order.
    shapes.sort_by(|a, b| b.area.total_cmp(&a.area));
    Ok(Shapes {
        shapes,
        loops_dropped: dropped,
        vertices_removed: removed,
        straight_tolerance: tolerance,
    })
}

/// Step `shapes`: each planar group's outline with holes, in its own 2D frame.
pub fn run(
    mesh: &Mesh,
    groups: &PlanarGroups,
    cleaned: &Cleaned,
    settings: &Settings,
    cx: &mut StepContext<'_>,
) -> Result<Shapes> {
    let tolerance = settings.straight_tolerance.unwrap_or(cleaned.tolerances.straight);
    cx.check_cancel()?;
    find_shapes(mesh, groups, tolerance).map_err(|e| Error::model(cx.model(), ModelProblem::OffGrid(e)))
}

#[cfg(test)]
mod tests;
