//! The assembly a plan describes, rebuilt for measuring: each part as a solid (outline extruded
//! by its thickness, placed by its transform, read from plan.json alone), a point-in-model
//! test, the one [`analyse`] of the assembly (groups, joints that meet, interference,
//! surface covered) that `convert`, the score and `verify` all read, and the [`order`] to
//! assemble the parts in (plan.json's `assembly`).

mod analysis;
mod groups;
mod inside;
mod order;
pub(crate) mod sample;
mod solid;
mod sweep;

pub use analysis::{Analysis, COVER_SLACK, Interference, analyse, cover_distance};
pub(crate) use groups::UnionFind;
pub(crate) use inside::Inside;
pub use order::order;
pub(crate) use solid::Solid;

use glam::DVec3;

/// Whether two parts (as slabs) meet as the assembly analysis counts it for a joint: the same
/// sampling as [`analyse`] at the step of these two, so a step that drops joints whose
/// parts do not meet agrees with `verify`.
pub(crate) fn slabs_meet(a: &platener_geom::slab::Slab, b: &platener_geom::slab::Slab) -> bool {
    let solids = [Solid::from_slab(0, a.clone()), Solid::from_slab(1, b.clone())];
    let step = sample::step_for(&solids);
    let [sa, sb] = &solids;
    // Only the cells that can meet the other slab: within reach of its box.
    let near = |s: &Solid| (s.lo - DVec3::splat(step), s.hi + DVec3::splat(step));
    sample::meet(sa, &sample::cells_near(sa, step, near(sb)), sb, step)
        || sample::meet(sb, &sample::cells_near(sb, step, near(sa)), sa, step)
}
