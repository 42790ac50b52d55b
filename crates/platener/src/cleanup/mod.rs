//! Step `cleanup` (the thesis' MeshCleanup): drops zero-area and duplicate triangles.
//!
//! Both are common in real files (OpenSCAD T-junction slivers, facets stored several times) and
//! both break topology: a zero-area triangle makes an edge look non-manifold, a duplicate makes
//! every one of its edges non-manifold. A triangle and its mirror (same corners, opposite
//! winding) count as duplicates: together they enclose nothing.

use std::sync::Arc;

use platener_geom::Tolerances;
use platener_geom::dedup::first_equal;
use serde::Serialize;

use crate::context::{StepContext, WarningKind};
use crate::error::Result;
use crate::read::{Model, Triangle};

/// The snapshot of step `cleanup`.
#[derive(Debug, Clone, Serialize)]
pub struct Cleaned {
    /// The triangles kept, in input order.
    #[serde(skip)]
    pub triangles: Arc<Vec<Triangle>>,
    /// Zero-area triangles removed (a repeated corner or no height).
    pub degenerate_removed: usize,
    /// Duplicate triangles removed.
    pub duplicates_removed: usize,
    /// The tolerances derived from the model's size, used by every later step.
    pub tolerances: Tolerances,
}

/// Whether a triangle has (numerically) no area: its height over the longest edge is below
/// `min_height`.
pub fn is_degenerate(t: &Triangle, min_height: f64) -> bool {
    let e = [t[1] - t[0], t[2] - t[1], t[0] - t[2]];
    let longest2 = e.iter().map(|v| v.length_squared()).fold(0.0, f64::max);
    if longest2 == 0.0 {
        return true;
    }
    let area2 = e[0].cross(-e[2]).length();
    area2 / longest2.sqrt() < min_height
}

/// Removes degenerate and duplicate triangles; returns the kept ones (in input order) and the
/// two counts.
pub fn clean(triangles: &[Triangle], tolerances: &Tolerances) -> (Vec<Triangle>, usize, usize) {
    let candidates: Vec<&Triangle> = triangles
        .iter()
        .filter(|t| !is_degenerate(t, tolerances.degenerate_height))
        .collect();
    let degenerate = triangles.len() - candidates.len();
    // A triangle's identity: its corners' bits (−0 taken as +0), sorted, so rotated and
    // mirrored copies compare equal.
    let keys: Vec<[[u64; 3]; 3]> = candidates
        .iter()
        .map(|t| {
            let mut k = t.map(|p| [(p.x + 0.0).to_bits(), (p.y + 0.0).to_bits(), (p.z + 0.0).to_bits()]);
            k.sort_unstable();
            k
        })
        .collect();
    let first = first_equal(&keys);
    let kept: Vec<Triangle> = candidates
        .iter()
        .enumerate()
        .filter(|&(i, _)| first[i] as usize == i)
        .map(|(_, t)| **t)
        .collect();
    let duplicates = candidates.len() - kept.len();
    (kept, degenerate, duplicates)
}

/// Step `cleanup`: the model's triangles without zero-area and duplicate ones, and the
/// tolerances every later step uses.
pub fn run(model: &Model, cx: &mut StepContext<'_>) -> Result<Cleaned> {
    let tolerances = Tolerances::for_model(model.bounds.diagonal());
    let (kept, degenerate, duplicates) = clean(&model.triangles, &tolerances);
    if degenerate > 0 {
        cx.warn(
            WarningKind::DegenerateFaces,
            format!("{degenerate} degenerate (zero-area) triangles removed"),
        );
    }
    if duplicates > 0 {
        cx.warn(
            WarningKind::DuplicateFaces,
            format!("{duplicates} duplicate triangles removed"),
        );
    }
    Ok(Cleaned {
        triangles: Arc::new(kept),
        degenerate_removed: degenerate,
        duplicates_removed: duplicates,
        tolerances,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec3;

    #[test]
    fn removes_slivers_and_duplicates() {
        let a = DVec3::ZERO;
        let b = DVec3::new(10.0, 0.0, 0.0);
        let c = DVec3::new(0.0, 10.0, 0.0);
        let tris = vec![
            [a, b, c],
            [b, c, a],                                                  // same triangle, rotated: duplicate
            [a, c, b],                                                  // mirrored: duplicate
            [a, DVec3::new(0.0, 0.0, 5.0), DVec3::new(0.0, 0.0, 10.0)], // collinear sliver
            [a, a, b],                                                  // repeated corner
            [a, b, DVec3::new(0.0, 0.0, 1.0)],
        ];
        let (kept, degenerate, duplicates) = clean(&tris, &Tolerances::default());
        assert_eq!((kept.len(), degenerate, duplicates), (2, 2, 2));
        assert_eq!(kept[0], tris[0]);
        assert_eq!(kept[1], tris[5]);
    }
}
