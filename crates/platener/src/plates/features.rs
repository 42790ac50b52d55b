//! A plate's shape is the model's material at its mid-plane; what one face lacks there is a
//! feature on that face, not a hole.
//!
//! The faces of a plate have holes wherever the surface leaves their plane: where the model is
//! open through the plate, but also under engraved or embossed text, pockets and the footprints
//! of standoffs. Only the model's cross-section at the plate's mid-plane tells them apart:
//!
//! - **features** = `(filled(piece) ∩ section) ∖ piece`: material at the mid-plane where a face
//!   is missing (pieces smaller or narrower than a kerf are seams along a through-hole's edge
//!   and are dropped).
//! - **shape** = `piece ∪ features`: the outline comes from the faces, the holes from the
//!   section. The union keeps everything the faces vouch for, so a section spoilt by a
//!   defective mesh never shrinks a plate, and a through-hole keeps the faces' exact ring. A feature belongs to the face it is missing from (both, if both are); it is
//!   *raised* (a boss, embossed text) when the model has material just outside that face over
//!   it, *recessed* (a pocket, engraved text) when not. A raised feature's height is found by
//!   sectioning at the heights of the mesh vertices above it until the material stops.
//!
//! Sides are named as the part lies on the laser's bed: a part is drawn in its own (x, y)
//! frame on a sheet whose y axis points down, so its local +z points into the bed: the face at
//! local z = 0 is [`Side::Up`] (engraved as drawn), the face at z = thickness is
//! [`Side::Down`].

use glam::{DVec2, DVec3};
use platener_geom::boolean::{difference, intersection, union};
use platener_geom::offset::offset;
use platener_geom::slab::Slab;
use platener_geom::{Frame, GridError, Polygon, polygon};
use serde::Serialize;

use super::{Plate, map_polygon};
use crate::mesh::Mesh;
use crate::settings::Features as Mode;

/// Features smaller than this (mm²) are the seams between a face's hole and the section's
/// (a window whose sides are not quite square to the wall), not features: on the corpus such
/// seams reach 0.32 mm², while letters and standoff footprints are several mm² each.
const MIN_AREA: f64 = 0.5;
/// …as are features narrower on average than this (mm, twice the area over the perimeter):
/// about a kerf, so a laser could not score them apart from the hole's edge.
const MIN_WIDTH: f64 = 0.2;
/// How far outside a face (mm, at most a tenth of the sheet) the section that tells raised from
/// recessed features is taken.
const PROBE: f64 = 0.1;
/// The share of a raised feature's footprint every section up to its height must cover for it
/// to stand straight up (the model's facets and the grid leave a few per cent).
pub const PRISM: f64 = 0.9;
/// Sections spent per plate measuring how tall its raised features are; past it, heights are
/// not measured (a plate covered in embossed text would otherwise cost one section per glyph
/// and height).
const HEIGHT_PROBES: usize = 32;
/// Share of a region beside a plate's edge the mid-plane material must fill (and the material
/// just inside the pocketed face must leave empty) for it to be a pocket, not a chamfer.
const EDGE_FILL: f64 = 0.95;
/// How close (mm) a region beside a piece must come to count as touching its edge (grid
/// noise between the faces' booleans).
const EDGE_TOUCH: f64 = 0.01;
/// Vertices cut ring corners closer than this (mm) to a straight run out of sections.
const SECTION_TOLERANCE: f64 = 1e-3;

/// The face of a plate a feature is on, as the part lies on the sheet.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Side {
    /// The face at local z = 0: up on the sheet, engraved as drawn.
    Up,
    /// The face at local z = thickness: down on the sheet; engraving it means turning the part
    /// over (the marks then read mirrored).
    Down,
}

/// Whether a feature stands out of its face or is sunk into it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Elevation {
    /// Engraved text, a pocket: below the face.
    Recessed,
    /// Embossed text, a boss, a standoff: above the face.
    Raised,
}

/// A feature on one face of a plate that does not go through it.
#[derive(Debug, Clone, Serialize)]
pub struct Feature {
    /// The plate (index into `Plates::plates`; the plate method's part id is this + 1).
    pub plate: u32,
    /// Which face.
    pub side: Side,
    /// Raised or recessed.
    pub relief: Elevation,
    /// Its footprint on the face, in the plate's 2D frame (plan.json has it as score marks).
    #[serde(skip)]
    pub region: Polygon,
    /// Footprint area, mm².
    pub area: f64,
    /// Footprint width and height along the plate's x and y, mm.
    pub size: [f64; 2],
    /// Centre of the footprint's box on the face, in the model.
    pub center: DVec3,
    /// How far a raised feature stands out of the face, mm; `None` when recessed or not
    /// measured.
    pub height: Option<f64>,
    /// A raised feature that stands straight up: every section up to its height covers at
    /// least [`PRISM`] of its footprint (a standoff, a boss; not a dome).
    #[serde(skip)]
    pub prism: bool,
    /// The frame it was found in (the plate's once assigned).
    #[serde(skip)]
    pub frame: Frame,
    /// The thickness of the plate it was found on.
    #[serde(skip)]
    pub thickness: f64,
}

/// One face of a plate being made: where it is and what of its plane it covers.
pub(super) struct Face {
    /// Which face.
    pub side: Side,
    /// Its height in the plate's frame.
    pub z: f64,
    /// The face's whole shape, in the plate's 2D frame.
    pub shape: Vec<Polygon>,
}

/// Sections of one mesh for the plates of one conversion.
pub(super) struct Sections<'a> {
    mesh: &'a Mesh,
    mode: Mode,
}

impl<'a> Sections<'a> {
    pub fn new(mesh: &'a Mesh, mode: Mode) -> Self {
        Self { mesh, mode }
    }

    /// The material at local height `z` of `frame`.
    fn at(&self, frame: &Frame, z: f64) -> Result<Vec<Polygon>, GridError> {
        crate::slicing::section(self.mesh, frame, z, SECTION_TOLERANCE)
    }

    /// The plate `piece` (a region both faces share, in `frame`'s plane, `t` thick) makes:
    /// its connected polygons as the model's material at the mid-plane, and the features of
    /// `faces()` in its holes. With `--features cut`, or no holes, the piece as it is (and
    /// `faces` is not called).
    pub fn solid(
        &self,
        piece: Polygon,
        frame: &Frame,
        t: f64,
        faces: impl FnOnce() -> Vec<Face>,
    ) -> Result<(Vec<Polygon>, Vec<Feature>), GridError> {
        if self.mode == Mode::Cut {
            return Ok((vec![piece], Vec::new()));
        }
        let faces = faces();
        let beside = beside(&piece, &faces)?;
        if piece.holes.is_empty() && beside.is_empty() {
            return Ok((vec![piece], Vec::new()));
        }
        let section = self.at(frame, t / 2.0)?;
        let filled = Polygon::new(piece.outer.clone());
        let inside = intersection(&[filled], &section)?;
        // Material in the piece's holes; seams along a through-hole's edge are not, so such a
        // hole keeps the faces' exact ring.
        let mut missing = significant(difference(&inside, std::slice::from_ref(&piece))?);
        missing.extend(self.recessed_at_edge(beside, &section, frame, t, &faces)?);
        if missing.is_empty() {
            return Ok((vec![piece], Vec::new()));
        }
        let mut solid = union(std::slice::from_ref(&piece), &missing)?;
        for p in &mut solid {
            p.normalize_orientation();
        }
        if self.mode == Mode::Ignore {
            return Ok((solid, Vec::new()));
        }
        let mut features = Vec::new();
        let mut budget = HEIGHT_PROBES;
        for face in &faces {
            let on_face = significant(difference(&missing, &face.shape)?);
            if on_face.is_empty() {
                continue;
            }
            let out = if face.z > t / 2.0 { 1.0 } else { -1.0 };
            let probe = self.at(frame, face.z + out * PROBE.min(t / 10.0))?;
            for region in on_face {
                let raised =
                    polygon::total_area(&intersection(std::slice::from_ref(&region), &probe)?) > 0.5 * region.area();
                let rise = match raised {
                    true => self.height(frame, face.z, out, &region, &mut budget)?,
                    false => None,
                };
                let relief = if raised { Elevation::Raised } else { Elevation::Recessed };
                let (height, prism) = (rise.map(|r| r.0), rise.is_some_and(|r| r.1));
                features.push(feature(region, frame, t, (face.side, face.z), relief, (height, prism)));
            }
        }
        Ok((solid, features))
    }

    /// The regions `beside` the piece (one face has them, the other not) that are a pocket
    /// sunk into the other face at the piece's edge: the material at the mid-plane fills the
    /// region (a chamfer or rounded edge fills about half of it), and just inside the other
    /// face there is none (at a corner the rim of a wall's outer face is the neighbouring
    /// wall's material at every depth). Such a pocket is the plate's material with a mark on
    /// that face, not a notch in its outline.
    fn recessed_at_edge(
        &self,
        beside: Vec<(usize, Polygon)>,
        section: &[Polygon],
        frame: &Frame,
        t: f64,
        faces: &[Face],
    ) -> Result<Vec<Polygon>, GridError> {
        let mut out = Vec::new();
        for (other, region) in beside {
            let area = region.area();
            let mid = polygon::total_area(&intersection(std::slice::from_ref(&region), section)?);
            if mid < EDGE_FILL * area {
                continue;
            }
            let inward = if faces[other].z > t / 2.0 { -1.0 } else { 1.0 };
            let probe = self.at(frame, faces[other].z + inward * PROBE.min(t / 10.0))?;
            let near = polygon::total_area(&intersection(std::slice::from_ref(&region), &probe)?);
            if near < (1.0 - EDGE_FILL) * area {
                out.extend(significant(intersection(&[region], section)?));
            }
        }
        Ok(out)
    }

    /// How far the material over `region` reaches out of the face at height `z` (direction
    /// `out`): the material ends at a vertex height, so the sections are taken between
    /// consecutive vertex heights above the footprint until one is empty over it, and whether
    /// every section below covers at least [`PRISM`] of the footprint (a standoff stands
    /// straight up; a dome narrows). `None` when the budget of sections runs out first.
    fn height(
        &self,
        frame: &Frame,
        z: f64,
        out: f64,
        region: &Polygon,
        budget: &mut usize,
    ) -> Result<Option<(f64, bool)>, GridError> {
        let (lo, hi) = region.bounds();
        let near = |q: DVec2| q.x >= lo.x - 1e-3 && q.y >= lo.y - 1e-3 && q.x <= hi.x + 1e-3 && q.y <= hi.y + 1e-3;
        let mut heights: Vec<f64> = self
            .mesh
            .vertices
            .iter()
            .map(|p| frame.to_local(*p))
            .filter(|l| near(l.truncate()))
            .map(|l| (l.z - z) * out)
            .filter(|h| *h > 1e-4)
            .collect();
        heights.sort_by(f64::total_cmp);
        heights.dedup_by(|a, b| *a - *b < 1e-4);
        let mut prism = true;
        for (k, &h) in heights.iter().enumerate() {
            if *budget == 0 {
                return Ok(None);
            }
            *budget -= 1;
            let next = heights.get(k + 1).copied().unwrap_or(h + 2.0 * PROBE);
            let above = self.at(frame, z + out * (h + next) / 2.0)?;
            let left = polygon::total_area(&intersection(std::slice::from_ref(region), &above)?);
            if left < 0.1 * region.area() {
                return Ok(Some((h, prism)));
            }
            prism &= left >= PRISM * region.area();
        }
        Ok(None)
    }
}

/// The regions one face has beyond the piece's outline, touching it, that the other face
/// (index into `faces`) lacks: where a pocket at the plate's edge notched the piece.
fn beside(piece: &Polygon, faces: &[Face]) -> Result<Vec<(usize, Polygon)>, GridError> {
    if faces.len() != 2 {
        return Ok(Vec::new());
    }
    let near = offset(std::slice::from_ref(piece), EDGE_TOUCH)?;
    let mut out = Vec::new();
    for (k, face) in faces.iter().enumerate() {
        let other = 1 - k;
        let extra = difference(&face.shape, std::slice::from_ref(piece))?;
        let extra = significant(difference(&extra, &faces[other].shape)?);
        for region in extra {
            if polygon::total_area(&intersection(std::slice::from_ref(&region), &near)?) > 0.0 {
                out.push((other, region));
            }
        }
    }
    Ok(out)
}

/// The polygons of `ps` large and wide enough to be features, outer rings counter-clockwise.
fn significant(ps: Vec<Polygon>) -> Vec<Polygon> {
    ps.into_iter()
        .filter(|p| {
            let area = p.area();
            let perimeter: f64 = std::iter::once(&p.outer)
                .chain(&p.holes)
                .map(|r| polygon::perimeter(r))
                .sum();
            area >= MIN_AREA && perimeter > 0.0 && 2.0 * area / perimeter >= MIN_WIDTH
        })
        .map(|mut p| {
            p.normalize_orientation();
            p
        })
        .collect()
}

/// A feature of `region` on the face `(side, z)` of a plate in `frame`, not yet assigned to a
/// plate.
fn feature(
    region: Polygon,
    frame: &Frame,
    t: f64,
    (side, z): (Side, f64),
    relief: Elevation,
    (height, prism): (Option<f64>, bool),
) -> Feature {
    let (lo, hi) = region.bounds();
    let mid = (lo + hi) / 2.0;
    Feature {
        plate: u32::MAX,
        side,
        relief,
        area: region.area(),
        size: [hi.x - lo.x, hi.y - lo.y],
        center: frame.to_model(mid.extend(z)),
        height,
        prism,
        region,
        frame: *frame,
        thickness: t,
    }
}

/// The features found while making plates, on the plates as they finally are (trimmed,
/// rejoined, sorted): each goes to every plate in whose plane and slab its mid-plane lies, cut
/// to that plate's outline, in its frame (the side swaps when the plate faces the other way).
pub(super) fn assign(found: &[Feature], plates: &[Plate]) -> Result<Vec<Feature>, GridError> {
    let parallel = 0.5f64.to_radians().cos();
    let mut out = Vec::new();
    for (i, plate) in plates.iter().enumerate() {
        for f in found {
            let along = plate.frame.n.dot(f.frame.n);
            let mid = plate
                .frame
                .to_local(f.frame.to_model(DVec3::new(0.0, 0.0, f.thickness / 2.0)));
            if along.abs() < parallel || mid.z <= 0.0 || mid.z >= plate.thickness {
                continue;
            }
            let mapped = map_polygon(&f.region, &f.frame, &plate.frame);
            for region in significant(intersection(&[mapped], std::slice::from_ref(&plate.polygon))?) {
                let side = match (along > 0.0, f.side) {
                    (true, s) => s,
                    (false, Side::Up) => Side::Down,
                    (false, Side::Down) => Side::Up,
                };
                // The face keeps its height in the model (a 4 mm wall's face is outside a 3 mm plate).
                let z = plate.frame.to_local(f.center).z;
                let rise = (f.height, f.prism);
                let mut g = feature(region, &plate.frame, plate.thickness, (side, z), f.relief, rise);
                g.plate = i as u32;
                out.push(g);
            }
        }
    }
    Ok(out)
}

/// The report's lines on features, plate by plate (plates in order): how many were engraved,
/// their area and sides, and the raised details up to a sheet high engraved as their outline
/// (not those other `plates` build: a table's legs stand on its top as bosses do, but are
/// plates of their own). Taller ones are the `parts` step's to build or list.
pub(super) fn warnings(features: &[Feature], plates: &[Plate]) -> Vec<String> {
    let slabs: Vec<Slab> = plates.iter().map(Plate::slab).collect();
    let mut out = Vec::new();
    let mut start = 0;
    while start < features.len() {
        let plate = features[start].plate;
        let end = start + features[start..].iter().take_while(|f| f.plate == plate).count();
        out.extend(plate_warnings(plate, &features[start..end], &slabs));
        start = end;
    }
    out
}

/// Probes per raised feature when asking whether other plates build it.
const PROBES: f64 = 64.0;

/// Whether other plates than its own build at least half of raised feature `f`: probed on a
/// grid over its footprint, just off the face (half its height, at most half a thickness).
pub(crate) fn built_by_plates(f: &Feature, slabs: &[Slab]) -> bool {
    builder(f, slabs).is_some()
}

/// The other plate that builds at least half of raised feature `f` (the one holding the most
/// probes), as [`built_by_plates`] probes it.
pub(crate) fn builder(f: &Feature, slabs: &[Slab]) -> Option<usize> {
    let own = slabs.get(f.plate as usize)?;
    let z_face = own.frame.to_local(f.center).z;
    let rise = f.height.unwrap_or(f.thickness).min(f.thickness) / 2.0;
    let z = match f.side {
        Side::Up => z_face - rise,
        Side::Down => z_face + rise,
    };
    let (lo, hi) = f.region.bounds();
    let step = (f.area.max(f64::MIN_POSITIVE) / PROBES).sqrt();
    let mut inside = 0usize;
    let mut hits: std::collections::BTreeMap<usize, usize> = std::collections::BTreeMap::new();
    let mut y = lo.y + step / 2.0;
    while y < hi.y {
        let mut x = lo.x + step / 2.0;
        while x < hi.x {
            let p = DVec2::new(x, y);
            if f.region.contains(p) {
                inside += 1;
                let at = own.frame.to_model(p.extend(z));
                if let Some(k) = (0..slabs.len()).find(|&k| k != f.plate as usize && slabs[k].contains(at)) {
                    *hits.entry(k).or_default() += 1;
                }
            }
            x += step;
        }
        y += step;
    }
    let built: usize = hits.values().sum();
    if inside == 0 || 2 * built < inside {
        return None;
    }
    hits.into_iter()
        .max_by(|a, b| a.1.cmp(&b.1).then(b.0.cmp(&a.0)))
        .map(|(k, _)| k)
}

/// The lines for one plate's features.
fn plate_warnings(plate: u32, fs: &[Feature], slabs: &[Slab]) -> Vec<String> {
    let count = |side| fs.iter().filter(|f| f.side == side).count();
    let (up, down) = (count(Side::Up), count(Side::Down));
    let area: f64 = fs.iter().map(|f| f.area).sum();
    let mut lines = vec![format!(
        "plate {}: {} feature(s) on one face ({area:.1} mm²) kept solid and scored: {up} on the face up on \
         the sheet, {down} on the face down{}",
        plate + 1,
        fs.len(),
        if down > 0 {
            " (turn the part over to engrave those; they read mirrored)"
        } else {
            ""
        }
    )];
    // Raised lettering and relief up to a sheet high are kept as their engraved outline;
    // what stands taller is the `parts` step's (standoffs: stacked discs, or listed).
    let sheet = slabs.get(plate as usize).map_or(f64::INFINITY, |s| s.thickness);
    let low: Vec<&Feature> = fs
        .iter()
        .filter(|f| f.relief == Elevation::Raised && f.height.is_some_and(|h| h <= sheet + 1e-6))
        .filter(|f| !built_by_plates(f, slabs))
        .collect();
    if !low.is_empty() {
        let area: f64 = low.iter().map(|f| f.area).sum();
        lines.push(format!(
            "plate {}: {} raised detail(s) (lettering, relief; {area:.1} mm², up to a sheet high) are engraved as \
             their outline on the face they stand on",
            plate + 1,
            low.len()
        ));
    }
    lines
}
