//! Where the layers lie: a frame whose local z runs up the stack, the layer thickness and
//! count, and how the slicing direction was chosen.

use glam::DVec3;
use platener_geom::Frame;
use rayon::prelude::*;
use serde::Serialize;

use crate::mesh::Mesh;

/// How the slicing direction was chosen.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[serde(rename_all = "kebab-case", tag = "rule")]
pub enum AxisChoice {
    /// Set by the user (`--axis x|y|z`).
    Given,
    /// The largest planar face laid flat.
    FlatFace {
        /// Its area, mm².
        area: f64,
    },
    /// No planar face of note: the model's z axis.
    ModelZ,
}

/// Where the layers are: a frame whose local z is the height up the stack (z = 0 the bottom
/// face of layer 1, the 2D origin over the model's centre), the thickness and the count.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct SlicePlan {
    /// The stack frame: `n` is the slicing direction.
    pub frame: Frame,
    /// Layer thickness, mm.
    pub thickness: f64,
    /// Number of layers (planes).
    pub count: usize,
    /// How the direction was chosen.
    pub choice: AxisChoice,
}

impl SlicePlan {
    /// Layers of `thickness` along `up` through the vertices `mesh`'s triangles use; `None`
    /// when there are no triangles.
    pub fn new(mesh: &Mesh, up: DVec3, choice: AxisChoice, thickness: f64) -> Option<Self> {
        let axes = Frame::on_plane(DVec3::ZERO, up);
        let mut used = vec![false; mesh.vertices.len()];
        for t in &mesh.triangles {
            for &v in t {
                used[v as usize] = true;
            }
        }
        let (lo, hi) = mesh
            .vertices
            .par_iter()
            .zip(used.par_iter())
            .filter(|(_, u)| **u)
            .map(|(p, _)| {
                let l = axes.to_local(*p);
                (l, l)
            })
            .reduce_with(|(a, b), (c, d)| (a.min(c), b.max(d)))?;
        let height = hi.z - lo.z;
        let count = ((height / thickness).round() as usize).max(1);
        let base = lo.z + (height - count as f64 * thickness) / 2.0;
        let center = (lo + hi) / 2.0;
        let origin = axes.to_model(DVec3::new(center.x, center.y, base));
        Some(Self {
            frame: Frame { origin, ..axes },
            thickness,
            count,
            choice,
        })
    }

    /// Height of plane `k` (layer `k`'s mid-plane) in the stack frame.
    pub fn plane(&self, k: usize) -> f64 {
        (k as f64 + 0.5) * self.thickness
    }

    /// Height of layer `k`'s bottom face in the stack frame.
    pub fn bottom(&self, k: usize) -> f64 {
        k as f64 * self.thickness
    }

    /// The frame of layer `k`: the stack frame moved up to its bottom face.
    pub fn layer_frame(&self, k: usize) -> Frame {
        self.frame.shifted(self.bottom(k))
    }
}
