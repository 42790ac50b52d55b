//! A part as a solid: its outline extruded by its thickness, placed by its transform.
//!
//! Built from plan.json's part (outline, holes, `[R | t]`), so what is measured is exactly
//! what a reader of the plan would assemble, whichever method made it. The geometry is a
//! [`Slab`] (the kernel's one extruded-polygon type); a solid adds the part's id and its
//! model box, kept for the cheap first test of every sample point.

use glam::DVec3;
use platener_geom::slab::Slab;
use platener_geom::{Frame, Polygon};

use crate::plan::PlanPart;

/// One part's volume: points `slab.frame.to_model((x, y, z))` with (x, y) in the outline and
/// 0 ≤ z ≤ thickness.
#[derive(Debug, Clone)]
pub(crate) struct Solid {
    /// The part's id in the plan.
    pub(crate) id: u32,
    /// The outline (rings as in the plan) extruded by the thickness, local → model.
    pub(crate) slab: Slab,
    /// Model-space box of the volume.
    pub(crate) lo: DVec3,
    /// Model-space box of the volume.
    pub(crate) hi: DVec3,
    /// Volume, mm³.
    pub(crate) volume: f64,
}

impl Solid {
    /// The part of the plan as a solid.
    pub(crate) fn from_part(part: &PlanPart) -> Self {
        let m = part.transform;
        let column = |j: usize| DVec3::new(m[0][j], m[1][j], m[2][j]);
        let slab = Slab {
            frame: Frame {
                u: column(0),
                v: column(1),
                n: column(2),
                origin: column(3),
            },
            polygon: Polygon {
                outer: part.outline.clone(),
                holes: part.holes.clone(),
            },
            thickness: part.thickness,
        };
        Self::from_slab(part.id, slab)
    }

    /// A slab as the solid of part `id` (for checks made before the plan exists).
    pub(crate) fn from_slab(id: u32, slab: Slab) -> Self {
        let (lo, hi) = slab.model_bounds();
        Self {
            id,
            volume: slab.volume(),
            slab,
            lo,
            hi,
        }
    }

    /// Whether the box of the volume, grown by `reach`, holds `p` (a cheap first test).
    pub(crate) fn near_box(&self, p: DVec3, reach: f64) -> bool {
        p.cmpge(self.lo - reach).all() && p.cmple(self.hi + reach).all()
    }

    /// Whether the model point `p` is inside the volume (see [`Slab::contains`]).
    pub(crate) fn contains(&self, p: DVec3) -> bool {
        self.slab.contains(p)
    }

    /// Whether the model point `p` is within `reach` of the volume (see [`Slab::within`]).
    pub(crate) fn within(&self, p: DVec3, reach: f64) -> bool {
        self.near_box(p, reach) && self.slab.within(p, reach)
    }
}
