//! A layer's loops become its islands: polygons with holes, one part each.
//!
//! Within one body (mesh component) loops are filled by the even-odd rule, which needs no
//! trust in their orientation: a loop inside one loop is a hole, a loop inside a hole an island
//! of its own. Bodies are then combined by their orientation (the `mesh` step winds every closed
//! body outwards and every cavity inwards): bodies whose loops run counter-clockwise in total
//! are united, so two shells that overlap (common in printable models made of several parts)
//! give their union instead of a hole where they cross; a clockwise body lying inside the others
//! is a cavity and is cut out. Islands smaller than the smallest part ([`Rule`]: somewhere t
//! wide, 2t × 2t of material, or the stacked settings' floors when larger) are too small to
//! cut: they are dropped and reported, unless they hold other layers together (`support.rs`:
//! then they are kept, enlarged until cuttable).

use platener_geom::tolerance::CRUMB_AREA;
use platener_geom::{GridError, Polygon};
use rayon::prelude::*;
use serde::Serialize;

use super::support::{KeptIsland, Small, keep_supporting};
use crate::cuttable::Rule;
use crate::settings::StackedSettings;
use crate::slicing::{Sliced, fill};

/// An island too small to cut.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct DroppedIsland {
    /// Its layer (0-based).
    pub layer: usize,
    /// Its area, mm².
    pub area: f64,
}

/// Every layer's islands (outlines in the stack's 2D frame) and the ones dropped.
#[derive(Debug, Clone, Serialize)]
pub struct LayerIslands {
    /// Per layer, its islands: outer ring counter-clockwise, holes clockwise, ordered by the
    /// lowest corner of their bounds (x, then y).
    pub islands: Vec<Vec<Polygon>>,
    /// Islands dropped as too small.
    pub dropped: Vec<DroppedIsland>,
    /// Islands too small to cut that were kept (enlarged) because they hold other layers
    /// together (`support.rs`); they are among `islands`.
    pub kept_small: Vec<KeptIsland>,
}

/// The smallest island the stacked method keeps in layers `thickness` mm thick: the
/// smallest-part rule, or the settings' floors when they ask for more.
pub fn island_rule(thickness: f64, settings: &StackedSettings) -> Rule {
    Rule::for_sheet(thickness, settings.min_width, settings.min_area)
}

/// The islands of every layer of `sliced`, those `rule` keeps.
pub fn islands_of(sliced: &Sliced, rule: &Rule) -> Result<LayerIslands, GridError> {
    let filled: Vec<Vec<Polygon>> = sliced
        .loops
        .par_iter()
        .map(|loops| fill(loops))
        .collect::<Result<_, _>>()?;
    islands_from(filled, rule)
}

/// The islands of layers whose material is `filled` (per layer, bottom first): the pieces
/// large enough to cut, and the small ones that hold other layers together.
pub(crate) fn islands_from(filled: Vec<Vec<Polygon>>, rule: &Rule) -> Result<LayerIslands, GridError> {
    let per_layer: Vec<(Vec<Polygon>, Vec<Polygon>)> = filled
        .into_par_iter()
        .map(|filled| keep_cuttable(filled, rule))
        .collect::<Result<_, GridError>>()?;
    let mut islands = Vec::with_capacity(per_layer.len());
    let mut small = Vec::new();
    for (layer, (kept, dropped)) in per_layer.into_iter().enumerate() {
        islands.push(kept);
        small.extend(dropped.into_iter().map(|polygon| Small { layer, polygon }));
    }
    let (kept_small, chosen) = keep_supporting(&mut islands, &small, rule)?;
    let dropped = small
        .iter()
        .zip(chosen)
        .filter(|(_, kept)| !kept)
        .map(|(s, _)| DroppedIsland {
            layer: s.layer,
            area: s.polygon.area(),
        })
        .collect();
    Ok(LayerIslands {
        islands,
        dropped,
        kept_small,
    })
}

/// Splits polygons into those large enough to cut and those that are not (both normalised,
/// the first ordered); grid crumbs are neither.
pub(crate) fn keep_cuttable(polygons: Vec<Polygon>, rule: &Rule) -> Result<(Vec<Polygon>, Vec<Polygon>), GridError> {
    let mut kept = Vec::new();
    let mut dropped = Vec::new();
    for mut p in polygons {
        p.normalize_orientation();
        let area = p.area();
        if rule.check(&p)?.is_ok() {
            kept.push(p);
        } else if area >= CRUMB_AREA {
            dropped.push(p);
        }
    }
    kept.sort_by(|a, b| {
        let (pa, pb) = (a.bounds().0, b.bounds().0);
        pa.x.total_cmp(&pb.x).then(pa.y.total_cmp(&pb.y))
    });
    Ok((kept, dropped))
}
