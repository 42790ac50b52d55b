//! Named part shapes made in code, shared by tests and the nesting benchmark: rectangles,
//! L-shapes, plates with finger notches, plates with holes, and mixed sets of them.

use glam::{DVec2, DVec3};
use platener_geom::{Frame, Polygon};

use super::part::{EdgeLabel, Part};

pub use platener_geom::polygon::rect;

/// A 3 mm plate lying in the model's x–y plane, for tests that only care about its outline.
pub fn flat_part(id: u32, polygon: Polygon) -> Part {
    Part::plate(id, 3.0, polygon, Frame::on_plane(glam::DVec3::ZERO, glam::DVec3::Z))
}

/// A frame somewhere in the model for part `id`: tilted differently per part, so transforms in
/// tests are not all the identity.
pub fn frame(id: u32) -> Frame {
    let a = f64::from(id) * 0.7;
    Frame::on_plane(
        DVec3::new(10.0 * f64::from(id), -5.0, 3.0),
        DVec3::new(a.cos(), a.sin(), 0.5),
    )
}

/// A plain `w` × `h` plate.
pub fn rectangle(id: u32, w: f64, h: f64) -> Part {
    Part::plate(id, 3.0, Polygon::new(rect(0.0, 0.0, w, h)), frame(id))
}

/// An L: a `w` × `h` box with the top-right `w − arm` × `h − arm` corner removed.
pub fn l_shape(id: u32, w: f64, h: f64, arm: f64) -> Part {
    let outer = vec![
        DVec2::new(0.0, 0.0),
        DVec2::new(w, 0.0),
        DVec2::new(w, arm),
        DVec2::new(arm, arm),
        DVec2::new(arm, h),
        DVec2::new(0.0, h),
    ];
    Part::plate(id, 3.0, Polygon::new(outer), frame(id))
}

/// A `w` × `h` plate whose bottom and top edges carry `fingers` notches `depth` deep (a
/// finger-jointed side), with those two edges labelled as connections `id·10` and `id·10 + 1`.
pub fn fingered(id: u32, w: f64, h: f64, fingers: u32, depth: f64) -> Part {
    let pitch = w / f64::from(2 * fingers + 1);
    let mut outer = vec![DVec2::new(0.0, 0.0)];
    for k in 0..fingers {
        let x = pitch * f64::from(2 * k + 1);
        outer.extend([
            DVec2::new(x, 0.0),
            DVec2::new(x, depth),
            DVec2::new(x + pitch, depth),
            DVec2::new(x + pitch, 0.0),
        ]);
    }
    outer.push(DVec2::new(w, 0.0));
    outer.push(DVec2::new(w, h));
    for k in (0..fingers).rev() {
        let x = pitch * f64::from(2 * k + 1);
        outer.extend([
            DVec2::new(x + pitch, h),
            DVec2::new(x + pitch, h - depth),
            DVec2::new(x, h - depth),
            DVec2::new(x, h),
        ]);
    }
    outer.push(DVec2::new(0.0, h));
    let mut part = Part::plate(id, 3.0, Polygon::new(outer), frame(id));
    part.edge_labels = vec![
        EdgeLabel {
            connection: id * 10,
            segment: [DVec2::new(0.0, 0.0), DVec2::new(w, 0.0)],
        },
        EdgeLabel {
            connection: id * 10 + 1,
            segment: [DVec2::new(w, h), DVec2::new(0.0, h)],
        },
    ];
    part
}

/// A `w` × `h` plate with a centred rectangular hole leaving a `band` wide rim.
pub fn window(id: u32, w: f64, h: f64, band: f64) -> Part {
    let mut hole = rect(band, band, w - band, h - band);
    hole.reverse();
    let polygon = Polygon {
        outer: rect(0.0, 0.0, w, h),
        holes: vec![hole],
    };
    Part::plate(id, 3.0, polygon, frame(id))
}

/// A deterministic mix of `n` parts (ids 1…n) from all shapes above, sizes 15–250 mm, drawn
/// with a simple linear congruential sequence from `seed`.
pub fn mixed(n: u32, seed: u64) -> Vec<Part> {
    let mut state = seed.wrapping_mul(6_364_136_223_846_793_005).wrapping_add(1);
    let mut unit = move || {
        state = state
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        (state >> 11) as f64 / (1u64 << 53) as f64
    };
    (1..=n)
        .map(|id| {
            let (w, h) = (15.0 + 235.0 * unit() * unit(), 15.0 + 150.0 * unit() * unit());
            match id % 5 {
                0 => l_shape(id, w.max(30.0), h.max(30.0), 12.0),
                1 => fingered(id, w.max(40.0), h.max(25.0), 3, 3.0),
                2 => window(id, w.max(60.0), h.max(60.0), 12.0),
                _ => rectangle(id, w, h),
            }
        })
        .collect()
}
