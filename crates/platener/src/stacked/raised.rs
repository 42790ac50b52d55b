//! Raised details on a layer's exposed faces (issue 32): lettering and relief that stand less
//! than a layer high on a face fall between two mid-plane sections and vanish. A keychain tag
//! with 1.25 mm letters on a 2.5 mm base became a blank 3 mm tag that scored 0.995.
//!
//! A face is *exposed* when no island of the neighbouring layer overlaps its island: nothing
//! of the stack lies on it, so whatever the model has there is lost. Past such a face the
//! model is sectioned every eighth of a layer, outwards from the mid-plane, up to a layer and
//! a half. While the section still covers most of the island the face has not been reached.
//! A *detail* is where the section then drops at once to at most half the island (a
//! horizontal face with something standing on it) and stays within the next probe (walls
//! that stand, not a dome's slope, whose sections shrink a little at every probe). Its
//! outline is engraved on that face as `score` marks.

use platener_geom::{GridError, Polygon, boolean};
use serde::Serialize;

use super::Stack;
use crate::mesh::Mesh;
use crate::plan::MarkSide;
use crate::slicing::section;

/// Probes per layer thickness.
const STEPS_PER_LAYER: f64 = 8.0;
/// Probes past the mid-plane: a layer and a half.
const PROBES: usize = 12;
/// A section covering more than this share of the island has not reached the face yet.
const FACE: f64 = 0.9;
/// A detail covers at most this share of the island: the section dropped at once.
const DROP: f64 = 0.5;
/// The next probe keeps at least this share of a detail: its walls stand.
const STANDS: f64 = 0.7;
/// Details smaller than this (mm² in all) are noise.
const MIN_AREA: f64 = 1.0;
/// Neighbouring islands overlapping by less than this (mm²) leave a face exposed.
const TOUCH: f64 = 1.0;

/// A detail engraved on one face of one island.
#[derive(Debug, Clone, Serialize)]
pub struct Raised {
    /// The layer (0-based).
    pub layer: usize,
    /// The island in that layer.
    pub island: usize,
    /// The face, as the part lies on the sheet (its local z = 0 face up): `bottom` is the
    /// layer's upper face in the stack.
    pub side: MarkSide,
    /// Height of the face above (or below) the layer's mid-plane at which the detail was
    /// found, mm.
    pub offset: f64,
    /// The detail's footprint in the stack's 2D frame, clipped to the island.
    #[serde(skip)]
    pub regions: Vec<Polygon>,
    /// Its area, mm².
    pub area: f64,
}

/// The details on every exposed face of `stack`'s islands, sectioning `mesh` with the
/// stack's straight-run `tolerance`.
pub(crate) fn details(mesh: &Mesh, stack: &Stack, tolerance: f64) -> Result<Vec<Raised>, GridError> {
    let mut out = Vec::new();
    let t = stack.layer_thickness();
    for (k, layer) in stack.layers.iter().enumerate() {
        for (up, side) in [(true, MarkSide::Bottom), (false, MarkSide::Top)] {
            let neighbour = if up { k.checked_add(1) } else { k.checked_sub(1) };
            let mut sections = Probes::new(mesh, stack, k, up, tolerance);
            for (i, island) in layer.islands.iter().enumerate() {
                if !exposed(&island.outline, neighbour.and_then(|n| stack.layers.get(n)))? {
                    continue;
                }
                if let Some((j, regions, area)) = detail(&island.outline, &mut sections)? {
                    out.push(Raised {
                        layer: k,
                        island: i,
                        side,
                        offset: (j as f64) * t / STEPS_PER_LAYER,
                        regions,
                        area,
                    });
                }
            }
        }
    }
    Ok(out)
}

/// Whether no island of `neighbour` overlaps `outline` by [`TOUCH`] or more.
fn exposed(outline: &Polygon, neighbour: Option<&super::Layer>) -> Result<bool, GridError> {
    let Some(layer) = neighbour else {
        return Ok(true);
    };
    let others: Vec<Polygon> = layer.islands.iter().map(|i| i.outline.clone()).collect();
    if others.is_empty() {
        return Ok(true);
    }
    let shared = boolean::intersection(std::slice::from_ref(outline), &others)?;
    Ok(shared.iter().map(Polygon::area).sum::<f64>() < TOUCH)
}

/// The first detail past the face of `outline`: the probe it was found at, its regions and
/// area.
fn detail(outline: &Polygon, sections: &mut Probes<'_>) -> Result<Option<(usize, Vec<Polygon>, f64)>, GridError> {
    let whole = outline.area();
    if whole <= 0.0 {
        return Ok(None);
    }
    for j in 1..PROBES {
        let here = clip(sections.at(j)?, outline)?;
        let area: f64 = here.iter().map(Polygon::area).sum();
        if area > FACE * whole {
            continue;
        }
        if area < MIN_AREA || area > DROP * whole {
            return Ok(None);
        }
        let next = clip(sections.at(j + 1)?, outline)?;
        let kept: f64 = boolean::intersection(&here, &next)?.iter().map(Polygon::area).sum();
        return Ok((kept >= STANDS * area).then_some((j, here, area)));
    }
    Ok(None)
}

/// `regions` within `outline`.
fn clip(regions: &[Polygon], outline: &Polygon) -> Result<Vec<Polygon>, GridError> {
    if regions.is_empty() {
        return Ok(Vec::new());
    }
    boolean::intersection(regions, std::slice::from_ref(outline))
}

/// The sections past one face of one layer, each made once for all its islands.
struct Probes<'a> {
    mesh: &'a Mesh,
    frame: platener_geom::Frame,
    /// Local height of the mid-plane and the step (signed: outwards).
    mid: f64,
    step: f64,
    tolerance: f64,
    made: Vec<Option<Vec<Polygon>>>,
}

impl<'a> Probes<'a> {
    fn new(mesh: &'a Mesh, stack: &Stack, k: usize, up: bool, tolerance: f64) -> Self {
        let t = stack.layer_thickness();
        let step = t / STEPS_PER_LAYER;
        Self {
            mesh,
            frame: stack.layer_frame(k),
            mid: t / 2.0,
            step: if up { step } else { -step },
            tolerance,
            made: vec![None; PROBES + 1],
        }
    }

    /// The model's section at probe `j` (in the layer's 2D frame, the stack's).
    fn at(&mut self, j: usize) -> Result<&[Polygon], GridError> {
        if self.made[j].is_none() {
            let z = self.mid + self.step * j as f64;
            self.made[j] = Some(section(self.mesh, &self.frame, z, self.tolerance)?);
        }
        Ok(self.made[j].as_deref().unwrap_or_default())
    }
}
