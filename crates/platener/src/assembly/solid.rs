//! A part as a solid: the union of its rigid pieces, each an outline extruded by the thickness
//! and placed by its frame.
//!
//! Built from plan.json's part (outline, holes, `[R | t]`, and for bent parts the segments
//! and bends), so what is measured is exactly what a reader of the plan would assemble,
//! whichever method made it. A flat part is one piece; a bent part is its segments and its
//! bend zones' slices ([`crate::plan::bent`]). Each piece is a [`Slab`] (the kernel's one
//! extruded-polygon type); a solid adds the part's id and its model box, kept for the cheap
//! first test of every sample point.

use glam::DVec3;
use platener_geom::Frame;
use platener_geom::slab::Slab;

use crate::plan::PlanPart;
use crate::plan::bent::frame_from_matrix;

/// One part's volume: the union of its pieces' volumes.
#[derive(Debug, Clone)]
pub(crate) struct Solid {
    /// The part's id in the plan.
    pub(crate) id: u32,
    /// The rigid pieces, local → model (one for a flat part).
    pub(crate) pieces: Vec<Slab>,
    /// Each piece's model box: a bent part has many pieces, and most sample points are far
    /// from most of them.
    boxes: Vec<(DVec3, DVec3)>,
    /// The part's thickness, mm.
    pub(crate) thickness: f64,
    /// Model-space box of the volume.
    pub(crate) lo: DVec3,
    /// Model-space box of the volume.
    pub(crate) hi: DVec3,
    /// Volume, mm³ (the pieces' sum: their flat shapes partition the part's).
    pub(crate) volume: f64,
}

impl Solid {
    /// The part of the plan as a solid. A bent part whose bends cannot be rebuilt counts as
    /// its flat shape placed by its transform (verify reports the bends separately).
    pub(crate) fn from_part(part: &PlanPart) -> Self {
        let pieces = part.pieces().unwrap_or_else(|_| {
            vec![Slab {
                frame: frame_from_matrix(&part.transform),
                polygon: platener_geom::Polygon {
                    outer: part.outline.clone(),
                    holes: part.holes.clone(),
                },
                thickness: part.thickness,
            }]
        });
        Self::from_pieces(part.id, part.thickness, pieces)
    }

    /// A slab as the solid of part `id` (for checks made before the plan exists).
    pub(crate) fn from_slab(id: u32, slab: Slab) -> Self {
        Self::from_pieces(id, slab.thickness, vec![slab])
    }

    fn from_pieces(id: u32, thickness: f64, pieces: Vec<Slab>) -> Self {
        let boxes: Vec<(DVec3, DVec3)> = pieces.iter().map(Slab::model_bounds).collect();
        let (lo, hi) = boxes.iter().copied().fold(
            (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)),
            |(lo, hi), (a, b)| (lo.min(a), hi.max(b)),
        );
        Self {
            id,
            volume: pieces.iter().map(Slab::volume).sum(),
            pieces,
            boxes,
            thickness,
            lo,
            hi,
        }
    }

    /// The frame of the part's first piece (a bent part's first segment).
    pub(crate) fn frame(&self) -> &Frame {
        &self.pieces[0].frame
    }

    /// Whether the box of the volume, grown by `reach`, holds `p` (a cheap first test).
    pub(crate) fn near_box(&self, p: DVec3, reach: f64) -> bool {
        in_box(p, (self.lo, self.hi), reach)
    }

    /// Whether the model point `p` is inside some piece (see [`Slab::contains`]).
    pub(crate) fn contains(&self, p: DVec3) -> bool {
        self.near_pieces(p, 0.0).any(|s| s.contains(p))
    }

    /// Whether the model point `p` is within `reach` of some piece (see [`Slab::within`]).
    pub(crate) fn within(&self, p: DVec3, reach: f64) -> bool {
        self.near_box(p, reach) && self.near_pieces(p, reach).any(|s| s.within(p, reach))
    }

    /// The pieces whose box, grown by `reach`, holds `p`.
    fn near_pieces(&self, p: DVec3, reach: f64) -> impl Iterator<Item = &Slab> {
        self.pieces
            .iter()
            .zip(&self.boxes)
            .filter(move |(_, b)| in_box(p, **b, reach))
            .map(|(s, _)| s)
    }
}

/// Whether the box `(lo, hi)` grown by `reach` holds `p`.
fn in_box(p: DVec3, (lo, hi): (DVec3, DVec3), reach: f64) -> bool {
    p.cmpge(lo - reach).all() && p.cmple(hi + reach).all()
}
