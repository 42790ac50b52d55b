//! Small parts into the holes of large ones.
//!
//! Before the sheets are filled, every hole of every part (largest parts first) is treated as a
//! region of its own: the hole's cut path shrunk by half the spacing, filled left-first with the
//! largest parts that fit. A part placed in a hole becomes a child of its host and moves with
//! it; since it lies inside the host's outline, the sheet nesting only needs the host's outline.
//! Children can host children of their own (a part is hosted at most once, and only by a larger
//! part, so there are no cycles).

use glam::DVec2;
use platener_geom::{Polygon, offset};

use super::blf::Bin;
use super::shape::{NestShape, nestable, rotate};

/// Where a child sits in its host's frame: host-frame point = R(angle) · p + translation.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Child {
    /// Index of the host among the shapes.
    pub host: usize,
    /// Rotation relative to the host, radians.
    pub angle: f64,
    /// Translation in the host's frame, mm.
    pub translation: DVec2,
}

/// The free regions of a host's holes: each hole (made counter-clockwise) shrunk by half the
/// spacing, largest first. A curved hole barely wider than the spacing shrinks to slivers
/// microns wide; only regions jagua-rs can take ([`nestable`]) are kept (no part fits the
/// others anyway).
fn hole_regions(host: &NestShape, spacing: f64) -> Vec<Polygon> {
    let mut regions: Vec<Polygon> = host
        .cut
        .holes
        .iter()
        .filter_map(|h| {
            let mut ring = h.clone();
            ring.reverse();
            offset::offset(&[Polygon::new(ring)], -spacing / 2.0).ok()
        })
        .flatten()
        .filter(|p| nestable(&p.outer))
        .collect();
    regions.sort_by(|a, b| b.area().total_cmp(&a.area()));
    regions
}

/// Assigns parts to holes. `order` lists shape indices largest first; the result has one entry
/// per shape: `Some` for parts placed in a hole.
pub(crate) fn fill_holes(
    shapes: &[NestShape],
    order: &[usize],
    spacing: f64,
    cancelled: &dyn Fn() -> bool,
) -> Vec<Option<Child>> {
    let mut hosted: Vec<Option<Child>> = vec![None; shapes.len()];
    for &h in order {
        if cancelled() {
            break;
        }
        for region in hole_regions(&shapes[h], spacing) {
            let region_area = region.area();
            let Some(mut bin) = Bin::new(&region.outer) else {
                continue;
            };
            let (lo, hi) = bin.bounds();
            let room = hi - lo;
            for &c in order {
                let shape = &shapes[c];
                if c == h || hosted[c].is_some() || shape.area >= region_area || shape.area >= shapes[h].area {
                    continue;
                }
                let fits_box = shape.templates.iter().any(|t| t.size.x <= room.x && t.size.y <= room.y);
                if !fits_box {
                    continue;
                }
                if let Some(p) = bin.place(c, shape) {
                    let t = &shape.templates[p.template];
                    let (angle, translation) = t.placement(p.pos);
                    hosted[c] = Some(Child {
                        host: h,
                        angle,
                        translation,
                    });
                }
            }
        }
    }
    hosted
}

/// Resolves a child's placement on the sheet from its host's: returns (angle, translation).
pub(crate) fn compose(host: (f64, DVec2), child: &Child) -> (f64, DVec2) {
    (host.0 + child.angle, rotate(child.translation, host.0) + host.1)
}
