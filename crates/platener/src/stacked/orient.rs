//! The slicing direction and where the layers lie along it.
//!
//! **Direction** (`--axis`): by default the model's largest planar face is laid flat, face
//! down, as the seed did: a model standing on a flat base gets its layers parallel to that base,
//! which gives fewer layers and a bottom layer that rests on the whole base. A face only counts
//! when it is at least [`FLAT_FACE_SHARE`] of the surface; a model without one (a sphere, a
//! bust) keeps its own z axis up, which is how it was modelled to be printed.
//!
//! **Layers**: `n = round(height / thickness)` layers (at least one), centred on the model's
//! extent along the direction, so the stack is as tall as the model to within half a layer and
//! the error is shared between top and bottom ([`crate::slicing::SlicePlan`]). Each layer's
//! outline is the cross-section at its mid-plane.

use glam::DVec3;

use crate::coplanar::PlanarGroups;
use crate::mesh::Mesh;
use crate::settings::StackAxis;
use crate::slicing::AxisChoice;

/// A planar face lies flat only when it is at least this share of the model's surface: the
/// largest "face" of a finely tessellated sphere is one facet, which says nothing.
pub const FLAT_FACE_SHARE: f64 = 0.02;

/// The slicing direction (the stack's up, unit) for `axis`.
pub fn choose_up(mesh: &Mesh, groups: Option<&PlanarGroups>, axis: StackAxis) -> (DVec3, AxisChoice) {
    match axis {
        StackAxis::X => (DVec3::X, AxisChoice::Given),
        StackAxis::Y => (DVec3::Y, AxisChoice::Given),
        StackAxis::Z => (DVec3::Z, AxisChoice::Given),
        StackAxis::Auto => {
            // Groups come largest first.
            let largest = groups.and_then(|g| g.groups.first());
            match largest {
                Some(g) if g.area >= FLAT_FACE_SHARE * mesh.surface_area && g.normal.is_finite() => {
                    // Face down: the stack's up is against the face's outward normal.
                    (-g.normal.normalize(), AxisChoice::FlatFace { area: g.area })
                }
                _ => (DVec3::Z, AxisChoice::ModelZ),
            }
        }
    }
}
