//! Step `weld` (the thesis' Simplification): merges vertices closer than the weld distance.
//!
//! Editors add small bevels and fillets to printable models; welding at about 2 mm collapses
//! them so the flat faces meet in sharp edges again and plates are found. Triangles that lose
//! a distinct corner disappear; triangles that become equal are merged. The clustering itself
//! is [`platener_geom::weld`] (near-linear, deterministic).
//!
//! Welding must not change what the model *is*: a 2 mm screw hole welded at 1.8 mm closes, and
//! two parts 1 mm apart would fuse. Collapsing a bevel keeps the surface's Euler
//! characteristic V − E + F; closing a hole or fusing bodies changes it. So when it changes,
//! the distance is halved and welding retried (with a warning), down to exact duplicates. If
//! welding would leave nothing, the unwelded mesh is used and a warning says so.
//!
//! Welding must not eat a wall either: the automatic distance is halved until at most
//! [`AUTO_WELD_WALL_SHARE`] × the model's thinnest wall ([`walls::thinnest_wall`]), with a
//! warning when that cuts it back; a distance the user set is kept but warned about when it
//! reaches the thinnest wall. Each welded triangle remembers the cleaned triangle it came
//! from, so later steps take planes from the model's own faces, not the welded ones.

mod topology;
pub mod walls;

use glam::DVec3;
use platener_geom::dedup::first_equal;
use platener_geom::weld::{Welded as Welded2, weld, weld_connected};
use serde::Serialize;

use crate::cleanup::Cleaned;
use crate::context::{StepContext, WarningKind};
use crate::error::{Error, ModelProblem, Result};
use crate::read::Model;
use crate::settings::{AUTO_WELD_WALL_SHARE, Settings, Weld};

pub use topology::{EdgeCounts, edge_counts};

/// Copies of one vertex stored separately differ by float noise; closer than this (mm) they are
/// merged whether or not an edge joins them.
pub const SNAP: f64 = 0.01;

/// How many times the distance is halved before welding gives up and keeps exact duplicates.
const HALVINGS: usize = 3;

/// The snapshot of step `weld`: an indexed triangle list.
#[derive(Debug, Clone, Serialize)]
pub struct Welded {
    /// Vertex positions in mm.
    #[serde(skip)]
    pub vertices: Vec<DVec3>,
    /// Triangles as vertex indices, winding as in the file.
    #[serde(skip)]
    pub triangles: Vec<[u32; 3]>,
    /// For each triangle, the index of the cleaned triangle it came from (same winding).
    #[serde(skip)]
    pub source: Vec<u32>,
    /// The model's thinnest wall before welding (mm): `None` when it has no two opposite
    /// faces, or when no weld was asked for (then it is not measured).
    pub thinnest_wall: Option<f64>,
    /// The distance used (0 = exact duplicates only).
    pub distance: f64,
    /// The distance asked for (automatic or set), before any halving.
    pub distance_asked: f64,
    /// Distinct input positions before welding.
    pub vertices_before: usize,
    /// Vertices merged away by welding (`vertices_before - vertices.len()`).
    pub vertices_merged: usize,
    /// Triangles removed because two corners merged.
    pub triangles_collapsed: usize,
    /// Triangles removed because they became equal to another.
    pub triangles_merged: usize,
    /// Whether welding emptied the model and the unwelded mesh was used instead.
    pub fell_back: bool,
    /// Open edges of the model as given (exact duplicates merged, before welding).
    pub input_open_edges: usize,
    /// Non-manifold edges of the model as given (before welding).
    pub input_non_manifold_edges: usize,
}

/// A triangle soup with exact duplicate positions merged: the starting point of welding.
pub struct ExactSoup {
    points: Vec<[f64; 3]>,
    weights: Vec<f64>,
    /// Each soup corner's exact vertex.
    corner: Vec<u32>,
    /// Edge counts and Euler characteristic of the unwelded surface.
    pub counts: EdgeCounts,
}

impl ExactSoup {
    /// Merges exactly equal corners of `soup`.
    pub fn new(soup: &[[DVec3; 3]]) -> Self {
        let corners: Vec<[f64; 3]> = soup.iter().flatten().map(|p| p.to_array()).collect();
        let exact = weld(&corners, &vec![1.0; corners.len()], 0.0);
        let triangles: Vec<[u32; 3]> = exact.map.chunks_exact(3).map(|c| [c[0], c[1], c[2]]).collect();
        let counts = edge_counts(&triangles, exact.points.len());
        Self {
            points: exact.points,
            weights: exact.weights,
            corner: exact.map,
            counts,
        }
    }

    /// Welds at `distance` (0: exact duplicates only): first positions within [`SNAP`] of
    /// each other (float noise of separately stored copies), then, along mesh edges only,
    /// vertices within `distance` (see [`weld_connected`]).
    pub fn weld(&self, distance: f64) -> Welded {
        let clustered = (distance > 0.0).then(|| {
            // A surface without open edges has no separately stored copies to snap.
            let snapped = if self.counts.open > 0 {
                weld(&self.points, &self.weights, distance.min(SNAP))
            } else {
                Welded2 {
                    points: self.points.clone(),
                    weights: self.weights.clone(),
                    map: (0..self.points.len() as u32).collect(),
                }
            };
            let edges: Vec<[u32; 2]> = self
                .corner
                .chunks_exact(3)
                .flat_map(|c| {
                    let v = [c[0], c[1], c[2]].map(|i| snapped.map[i as usize]);
                    [[v[0], v[1]], [v[1], v[2]], [v[2], v[0]]]
                })
                .collect();
            let along = weld_connected(&snapped.points, &snapped.weights, distance, &edges);
            let map = snapped.map.iter().map(|&s| along.map[s as usize]).collect::<Vec<u32>>();
            (along.points, map)
        });
        let (vertices, id): (Vec<DVec3>, Vec<u32>) = match &clustered {
            Some((points, map)) => (
                points.iter().map(|p| DVec3::from_array(*p)).collect(),
                self.corner.iter().map(|&v| map[v as usize]).collect(),
            ),
            None => (
                self.points.iter().map(|p| DVec3::from_array(*p)).collect(),
                self.corner.clone(),
            ),
        };
        let mut collapsed = 0;
        let mut triangles: Vec<[u32; 3]> = Vec::with_capacity(id.len() / 3);
        let mut source: Vec<u32> = Vec::with_capacity(id.len() / 3);
        for (i, c) in id.chunks_exact(3).enumerate() {
            if c[0] == c[1] || c[1] == c[2] || c[0] == c[2] {
                collapsed += 1;
            } else {
                triangles.push([c[0], c[1], c[2]]);
                source.push(i as u32);
            }
        }
        // Cleanup removed exact duplicates already; welding can make new ones.
        let merged = if clustered.is_some() {
            merge_equal(&mut triangles, &mut source)
        } else {
            0
        };
        Welded {
            vertices_merged: self.points.len() - vertices.len(),
            vertices,
            triangles,
            source,
            thinnest_wall: None,
            distance,
            distance_asked: distance,
            vertices_before: self.points.len(),
            triangles_collapsed: collapsed,
            triangles_merged: merged,
            fell_back: false,
            input_open_edges: self.counts.open,
            input_non_manifold_edges: self.counts.non_manifold,
        }
    }

    /// Welds at `distance`, halving it while welding would change the surface's topology.
    /// Returns the result and the distances that were refused.
    pub fn weld_keeping_topology(&self, distance: f64) -> (Welded, Vec<f64>) {
        let mut refused = Vec::new();
        let mut d = distance;
        for _ in 0..=HALVINGS {
            if d <= 0.0 {
                break;
            }
            let w = self.weld(d);
            if edge_counts(&w.triangles, w.vertices.len()).euler == self.counts.euler {
                return (
                    Welded {
                        distance_asked: distance,
                        ..w
                    },
                    refused,
                );
            }
            refused.push(d);
            d /= 2.0;
        }
        (
            Welded {
                distance_asked: distance,
                ..self.weld(0.0)
            },
            refused,
        )
    }
}

/// Removes triangles equal (as vertex sets) to an earlier one, with their sources; returns how
/// many were removed.
fn merge_equal(triangles: &mut Vec<[u32; 3]>, source: &mut Vec<u32>) -> usize {
    let keys: Vec<[u32; 3]> = triangles
        .iter()
        .map(|t| {
            let mut k = *t;
            k.sort_unstable();
            k
        })
        .collect();
    let first = first_equal(&keys);
    let before = triangles.len();
    let mut i = 0;
    triangles.retain(|_| {
        i += 1;
        first[i - 1] as usize == i - 1
    });
    let mut j = 0;
    source.retain(|_| {
        j += 1;
        first[j - 1] as usize == j - 1
    });
    before - triangles.len()
}

/// Welds a triangle soup at `distance` (0 merges exact duplicates only), without the
/// topology guard.
pub fn weld_soup(soup: &[[DVec3; 3]], distance: f64) -> Welded {
    ExactSoup::new(soup).weld(distance)
}

/// Step `weld`: the cleaned triangles with nearby vertices merged, at the distance the
/// settings ask for, reduced where welding would change the model's topology.
pub fn run(model: &Model, cleaned: &Cleaned, settings: &Settings, cx: &mut StepContext<'_>) -> Result<Welded> {
    let asked = settings.weld_distance(model.bounds.largest_extent());
    // Without welding no wall is at risk; the measure is skipped (the stacked method).
    let wall = (asked > 0.0)
        .then(|| walls::thinnest_wall(&cleaned.triangles))
        .flatten();
    cx.check_cancel()?;
    let distance = distance_for_walls(settings, asked, wall, cx);
    let exact = ExactSoup::new(&cleaned.triangles);
    cx.check_cancel()?;
    let (mut welded, refused) = exact.weld_keeping_topology(distance);
    if let Some(first) = refused.first() {
        cx.warn(
            WarningKind::WeldReduced,
            format!(
                "welding at {first:.3} mm would close holes or fuse parts; welded at {:.3} mm instead (set `weld` to choose)",
                welded.distance
            ),
        );
    }
    if welded.triangles.is_empty() && welded.distance > 0.0 {
        cx.warn(
            WarningKind::WeldFallback,
            format!(
                "welding at {:.3} mm would remove every triangle; the unwelded mesh is used (try `weld` 0)",
                welded.distance
            ),
        );
        welded = Welded {
            fell_back: true,
            distance_asked: distance,
            ..exact.weld(0.0)
        };
    }
    cx.check_cancel()?;
    welded.thinnest_wall = wall;
    warn_edges(&welded, cx);
    if welded.triangles.is_empty() {
        return Err(Error::model(&model.name, ModelProblem::EmptyAfterCleanup));
    }
    Ok(welded)
}

/// The weld distance `asked` by the settings, kept below the model's thinnest wall `wall`: the
/// automatic distance is cut to [`AUTO_WELD_WALL_SHARE`] × `wall`; a distance the user set is
/// kept. A warning gives both figures when the user's distance reaches the wall, or when the
/// automatic one was cut for a wall thinner than the thinnest sheet offered: a wall as thick as
/// the sheet is what every plate has, and cutting for it is routine (the weld step's record
/// in report.json keeps the figures), where a thinner wall is a detail the maker should hear of.
fn distance_for_walls(settings: &Settings, asked: f64, wall: Option<f64>, cx: &mut StepContext<'_>) -> f64 {
    let Some(wall) = wall else {
        return asked;
    };
    let cap = AUTO_WELD_WALL_SHARE * wall;
    match settings.weld {
        Weld::Auto if asked > cap => {
            // Halved like a refused distance, until at most the cap: the distances tried stay
            // the ones the topology guard tries (the cap itself can pinch a hole the next
            // rung down does not; `tray_bottom_14in` did at 0.714 mm, not at 0.9).
            let mut d = asked;
            while d > cap {
                d /= 2.0;
            }
            if wall >= 0.99 * settings.thinnest() {
                return d;
            }
            cx.warn(
                WarningKind::WeldThinWall,
                format!(
                    "the thinnest wall of the model is {wall:.3} mm: welding at {asked:.3} mm would eat it; welded at {d:.3} mm instead (at most {cap:.3} mm, {AUTO_WELD_WALL_SHARE} × the wall)"
                ),
            );
            d
        }
        Weld::Distance(d) if d >= wall => {
            cx.warn(
                WarningKind::WeldThinWall,
                format!(
                    "`weld` {d:.3} mm reaches the thinnest wall of the model ({wall:.3} mm): that wall may be welded away (the automatic weld would use at most {cap:.3} mm)"
                ),
            );
            asked
        }
        _ => asked,
    }
}

/// Open and non-manifold edges of the model as given.
fn warn_edges(welded: &Welded, cx: &mut StepContext<'_>) {
    if welded.input_open_edges > 0 {
        cx.warn(
            WarningKind::OpenEdges,
            format!(
                "{} open edges: the model's surface has holes (not watertight)",
                welded.input_open_edges
            ),
        );
    }
    if welded.input_non_manifold_edges > 0 {
        cx.warn(
            WarningKind::NonManifoldEdges,
            format!(
                "{} non-manifold edges: some edges of the model are shared by more than two triangles",
                welded.input_non_manifold_edges
            ),
        );
    }
}

#[cfg(test)]
mod tests;
