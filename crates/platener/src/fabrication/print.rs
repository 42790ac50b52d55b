//! How long an FDM printer takes to print the model itself, from its triangles alone: the
//! figure a laser plan is measured against (the CHI'15 paper's "10× faster than printing").
//!
//! A slicer's work, in the few sums that decide its time, per 0.2 mm layer as the model lies:
//! - **the section** at each layer's mid-plane: its area and the length of its outline, exact
//!   for a closed mesh wound outwards (the area by the divergence theorem: minus the signed
//!   projected area of the surface below the plane, each triangle clipped at it; the outline
//!   as the sum of each crossing triangle's segment);
//! - **perimeters**: the outline loop at the external speed, the inner loops at the perimeter
//!   speed (a wall thinner than the loops is one solid fill of its area);
//! - **top and bottom solid layers**: each up-facing triangle's projected area is solid in the
//!   few layers under it, each down-facing one in the few above, but a slope steep enough that
//!   a layer exposes a band narrower than the perimeters is covered by them (the share of a
//!   band `w` wide that lies past the perimeters is `1 − perimeters·width / w`); the topmost
//!   layer of a top surface goes at the top-surface speed;
//! - **sparse infill** of what is left, as lines of the extrusion width at the infill density;
//! - a fixed cost per layer (layer change, travel and retraction), a factor for acceleration
//!   and corners, and the slicer's cooling floor: no layer takes less than the minimum layer
//!   time, which is what small, tall models spend most of their time on.
//!
//! Supports are not counted (the reference slicer profile prints without them) and the model
//! is printed as it lies; the constants follow a stated PrusaSlicer profile
//! (tools/prusaslicer/profile.ini) and are calibrated against it (docs/performance.md).

use glam::{DVec2, DVec3};
use platener_geom::Triangle;

use crate::plan::PrintEstimate;

/// The printer and print settings the estimate assumes: a Prusa MK3S printing PLA with its
/// 0.20 mm QUALITY profile at 15 % infill (the reference slicer profile).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PrintProfile {
    /// Layer height, mm.
    pub layer: f64,
    /// Extrusion width, mm.
    pub width: f64,
    /// Perimeter loops.
    pub perimeters: f64,
    /// Solid layers under a top surface.
    pub top_layers: usize,
    /// Solid layers over a bottom surface.
    pub bottom_layers: usize,
    /// Sparse infill density, 0–1.
    pub infill: f64,
    /// Speeds, mm/s: external perimeter, other perimeters, sparse infill, solid infill, top
    /// surface, first layer.
    pub speeds: PrintSpeeds,
    /// Seconds no layer goes under (the slicer slows down to let it cool)...
    pub min_layer_seconds: f64,
    /// ...but never below this speed, mm/s.
    pub min_speed: f64,
    /// Seconds every layer costs beyond its extrusion (layer change, travel, retraction).
    pub layer_seconds: f64,
    /// Extrusion time over the time at full speed (acceleration and corners).
    pub motion_factor: f64,
}

/// Print speeds, mm/s.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PrintSpeeds {
    /// The outer loop.
    pub external: f64,
    /// Inner loops.
    pub perimeter: f64,
    /// Sparse infill.
    pub infill: f64,
    /// Solid infill.
    pub solid: f64,
    /// The top surface.
    pub top: f64,
    /// Everything on the first layer.
    pub first_layer: f64,
}

/// The reference profile (see [`PrintProfile`]).
pub const MK3S: PrintProfile = PrintProfile {
    layer: 0.2,
    width: 0.45,
    perimeters: 2.0,
    top_layers: 6,
    bottom_layers: 4,
    infill: 0.15,
    speeds: PrintSpeeds {
        external: 25.0,
        perimeter: 45.0,
        infill: 80.0,
        solid: 80.0,
        top: 40.0,
        first_layer: 20.0,
    },
    min_layer_seconds: 15.0,
    min_speed: 15.0,
    layer_seconds: 2.0,
    motion_factor: 1.5,
};

/// The most layers estimated one by one; a taller model (a 10 m tower in mm) is estimated
/// on thicker layers and scaled, so the work stays bounded.
const MAX_LAYERS: usize = 20_000;

/// What each layer holds, mm² and mm.
struct Layers {
    /// Section area.
    area: Vec<f64>,
    /// Section outline length.
    outline: Vec<f64>,
    /// Top surface exposed in the layer (solid below it).
    top: Vec<f64>,
    /// Bottom surface exposed in the layer (solid above it).
    bottom: Vec<f64>,
}

/// The print time of `triangles` (mm, wound outwards) with the reference profile.
pub fn estimate(triangles: &[Triangle]) -> PrintEstimate {
    estimate_with(triangles, &MK3S)
}

/// The print time of `triangles` with `profile`.
pub fn estimate_with(triangles: &[Triangle], profile: &PrintProfile) -> PrintEstimate {
    let (lo, hi) = z_range(triangles);
    let height = (hi - lo).max(0.0);
    let wanted = (height / profile.layer).ceil().max(1.0) as usize;
    let count = wanted.min(MAX_LAYERS);
    let h = height.max(profile.layer) / count as f64;
    let mut layers = sections(triangles, lo, h, count);
    let sign = if layers.area.iter().sum::<f64>() < 0.0 {
        -1.0
    } else {
        1.0
    };
    if sign < 0.0 {
        // Wound inwards throughout: the same model, surfaces swapped.
        layers.area.iter_mut().for_each(|a| *a = -*a);
        std::mem::swap(&mut layers.top, &mut layers.bottom);
    }
    let scale = wanted as f64 / count as f64;
    let (seconds, filament) = time(&layers, profile, h);
    PrintEstimate {
        seconds: seconds * scale,
        layers: wanted as u32,
        filament_mm3: filament,
        volume_mm3: layers.area.iter().map(|a| a.max(0.0)).sum::<f64>() * h,
    }
}

fn z_range(triangles: &[Triangle]) -> (f64, f64) {
    triangles
        .iter()
        .flatten()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), p| {
            (lo.min(p.z), hi.max(p.z))
        })
}

/// Each layer's section (area, outline) and surfaces exposed, from every triangle.
fn sections(triangles: &[Triangle], z0: f64, h: f64, count: usize) -> Layers {
    let mut layers = Layers {
        area: vec![0.0; count],
        outline: vec![0.0; count],
        top: vec![0.0; count],
        bottom: vec![0.0; count],
    };
    // Projected areas of triangles wholly below a plane, added from their first plane on.
    let mut below = vec![0.0; count + 1];
    let plane = |k: usize| z0 + (k as f64 + 0.5) * h;
    // A face exactly on a layer boundary: an up-facing one tops the layer below it, a
    // down-facing one floors the layer above.
    let index = |z: f64, up: bool| {
        let nudge = if up { -1e-6 } else { 1e-6 };
        ((z - z0) / h + nudge).floor().clamp(0.0, (count - 1) as f64) as usize
    };
    for t in triangles {
        let n = (t[1] - t[0]).cross(t[2] - t[0]);
        let length = n.length();
        if length <= 0.0 || !length.is_finite() {
            continue;
        }
        let projected = 0.5 * n.z;
        let (tlo, thi) = (t[0].z.min(t[1].z).min(t[2].z), t[0].z.max(t[1].z).max(t[2].z));
        // Planes strictly above the lowest corner and below the highest cross the triangle.
        let first = (((tlo - z0) / h - 0.5).floor() + 1.0).max(0.0) as usize;
        let above = (((thi - z0) / h - 0.5).ceil()).max(0.0) as usize;
        for k in first..above.min(count) {
            let (area, segment) = clip_below(t, plane(k));
            layers.area[k] -= area;
            layers.outline[k] += segment;
        }
        below[above.min(count)] -= projected;
        let up = n.z > 0.0;
        let span = (index(tlo, up), index(thi, up));
        expose(&mut layers, projected.abs() * band_share(n.z / length, h), up, span);
    }
    let mut sum = 0.0;
    for (a, b) in layers.area.iter_mut().zip(&below) {
        sum += b;
        *a += sum;
    }
    layers
}

/// The share of a surface sloping with normal z-component `nz` that is solid fill, not
/// perimeter: each layer exposes a band `h·|nz|/√(1−nz²)` wide, of which the reference
/// profile's two 0.45 mm loops cover 0.9 mm.
fn band_share(nz: f64, h: f64) -> f64 {
    let covered = MK3S.perimeters * MK3S.width;
    let side = (1.0 - nz * nz).max(0.0).sqrt();
    if side == 0.0 {
        return 1.0;
    }
    let band = h * nz.abs() / side;
    (1.0 - covered / band).max(0.0)
}

/// Spreads `area` of exposed surface over the layers `span` (a horizontal triangle: one).
fn expose(layers: &mut Layers, area: f64, up: bool, (from, to): (usize, usize)) {
    if area <= 0.0 {
        return;
    }
    let target = if up { &mut layers.top } else { &mut layers.bottom };
    let share = area / (to - from + 1) as f64;
    target[from..=to].iter_mut().for_each(|v| *v += share);
}

/// The signed xy-area of the part of `t` below `z` and the length of `t`'s cut at `z`.
fn clip_below(t: &Triangle, z: f64) -> (f64, f64) {
    let mut poly: Vec<DVec2> = Vec::with_capacity(4);
    let mut cut: Vec<DVec2> = Vec::with_capacity(2);
    for i in 0..3 {
        let (a, b) = (t[i], t[(i + 1) % 3]);
        if a.z < z {
            poly.push(a.truncate());
        }
        if (a.z < z) != (b.z < z) {
            let p = crossing(a, b, z);
            poly.push(p);
            cut.push(p);
        }
    }
    let area2: f64 = (0..poly.len())
        .map(|i| poly[i].perp_dot(poly[(i + 1) % poly.len()]))
        .sum();
    let segment = if cut.len() == 2 { cut[0].distance(cut[1]) } else { 0.0 };
    (0.5 * area2, segment)
}

fn crossing(a: DVec3, b: DVec3, z: f64) -> DVec2 {
    let f = (z - a.z) / (b.z - a.z);
    (a + (b - a) * f).truncate()
}

/// Seconds and filament (mm³) for the layers.
fn time(layers: &Layers, p: &PrintProfile, h: f64) -> (f64, f64) {
    let n = layers.area.len();
    let s = &p.speeds;
    let (mut seconds, mut filament) = (0.0, 0.0);
    for k in 0..n {
        let area = layers.area[k].max(0.0);
        let outline = layers.outline[k];
        // Loops: never more line than the area holds.
        let loops = (p.perimeters * outline).min(area / p.width);
        let ring = loops * p.width;
        let free = (area - ring).max(0.0);
        let tops: f64 = layers.top[k..(k + p.top_layers).min(n)].iter().sum();
        let bottoms: f64 = layers.bottom[k.saturating_sub(p.bottom_layers - 1)..=k].iter().sum();
        let solid = (tops + bottoms).min(free);
        let top = layers.top[k].min(solid);
        let sparse = free - solid;
        let external = outline.min(loops);
        let lines = [
            (external, s.external),
            (loops - external, s.perimeter),
            ((solid - top) / p.width, s.solid),
            (top / p.width, s.top),
            (sparse * p.infill / p.width, s.infill),
        ];
        let length: f64 = lines.iter().map(|(len, _)| len).sum();
        let motion: f64 = if k == 0 {
            length / s.first_layer
        } else {
            lines.iter().map(|(len, speed)| len / speed).sum()
        };
        let layer = motion * p.motion_factor + p.layer_seconds;
        // Slowed to cool: up to the floor, as far as the slowest speed allows.
        let cooled = p.min_layer_seconds.min(length / p.min_speed + p.layer_seconds);
        seconds += layer.max(cooled);
        filament += (ring + solid + sparse * p.infill) * h;
    }
    (seconds, filament)
}

#[cfg(test)]
mod tests {
    use super::*;
    use platener_fixtures::samples;

    fn cube(side: f64) -> Vec<Triangle> {
        samples::cuboid(DVec3::ZERO, DVec3::splat(side))
    }

    #[test]
    fn a_cubes_sections_are_its_square() {
        let layers = sections(&cube(20.0), 0.0, 0.2, 100);
        for k in 0..100 {
            assert!((layers.area[k] - 400.0).abs() < 1e-6, "layer {k}: {}", layers.area[k]);
            assert!(
                (layers.outline[k] - 80.0).abs() < 1e-6,
                "layer {k}: {}",
                layers.outline[k]
            );
        }
        // Its top in the last layer, its bottom in the first, nothing between.
        assert!((layers.top[99] - 400.0).abs() < 1e-6 && (layers.bottom[0] - 400.0).abs() < 1e-6);
        assert!(layers.top[..99].iter().chain(&layers.bottom[1..]).all(|&v| v == 0.0));
    }

    #[test]
    fn a_spheres_sections_follow_its_radius() {
        let sphere = samples::sphere(DVec3::ZERO, 30.0, 96, 48);
        let layers = sections(&sphere, -30.0, 0.2, 300);
        for k in [20, 100, 150, 250] {
            let z = -30.0 + (k as f64 + 0.5) * 0.2;
            let r2 = 900.0 - z * z;
            let (area, outline) = (std::f64::consts::PI * r2, std::f64::consts::TAU * r2.sqrt());
            assert!(
                (layers.area[k] / area - 1.0).abs() < 0.01,
                "layer {k}: {} vs {area}",
                layers.area[k]
            );
            assert!((layers.outline[k] / outline - 1.0).abs() < 0.01, "layer {k}");
        }
        let volume = layers.area.iter().sum::<f64>() * 0.2;
        let exact = 4.0 / 3.0 * std::f64::consts::PI * 27_000.0;
        assert!((volume / exact - 1.0).abs() < 0.01, "{volume} vs {exact}");
    }

    #[test]
    fn a_cube_takes_the_sum_of_its_lines_by_hand() {
        // 20 mm cube, 100 layers: every layer 2 loops of 80 mm; 4 bottom + 6 top layers solid.
        let p = PrintProfile {
            min_layer_seconds: 0.0,
            layer_seconds: 0.0,
            motion_factor: 1.0,
            ..MK3S
        };
        let estimate = estimate_with(&cube(20.0), &p);
        let ring = 160.0 * 0.45;
        let free = 400.0 - ring;
        let first = (160.0 + free / 0.45) / 20.0;
        let loops = 80.0 / 25.0 + 80.0 / 45.0;
        let solid = loops + free / 0.45 / 80.0;
        let top = loops + free / 0.45 / 40.0;
        let sparse = loops + free * 0.15 / 0.45 / 80.0;
        let by_hand = first + 3.0 * solid + 5.0 * solid + top + 90.0 * sparse;
        assert!(
            (estimate.seconds - by_hand).abs() < 1e-6 * by_hand,
            "{} vs {by_hand}",
            estimate.seconds
        );
        assert_eq!(estimate.layers, 100);
        assert!((estimate.volume_mm3 - 8000.0).abs() < 1e-6);
    }

    #[test]
    fn a_model_wound_inwards_takes_as_long() {
        let mut inside_out = cube(20.0);
        inside_out.iter_mut().for_each(|t| t.swap(1, 2));
        let (a, b) = (estimate(&cube(20.0)), estimate(&inside_out));
        assert!((a.seconds - b.seconds).abs() < 1e-9 * a.seconds);
    }

    #[test]
    fn small_layers_wait_for_the_cooling_floor() {
        // Two layers of a 20 mm square, no top or bottom: 160 mm of loops and 109 mm of
        // sparse fill take 11.5 s, slowed to the 15 s floor (269 mm at 15 mm/s would be 18 s).
        let layers = Layers {
            area: vec![400.0; 2],
            outline: vec![80.0; 2],
            top: vec![0.0; 2],
            bottom: vec![0.0; 2],
        };
        let (free, loops) = (400.0 - 160.0 * 0.45, 80.0 / 25.0 + 80.0 / 45.0);
        let fill = free * 0.15 / 0.45;
        let first = ((160.0 + fill) / 20.0 * 1.5 + 2.0_f64).max(15.0);
        assert!(loops * 1.5 + fill / 80.0 * 1.5 + 2.0 < 15.0);
        let (seconds, _) = time(&layers, &MK3S, 0.2);
        assert!((seconds - (first + 15.0)).abs() < 1e-9, "{seconds}");
        // A 1 mm pin: 2.2 mm of line a layer cannot be slowed to 15 s at 15 mm/s.
        let thin = estimate_with(&samples::cuboid(DVec3::ZERO, DVec3::new(1.0, 1.0, 40.0)), &MK3S);
        // The first layer at 20 mm/s with the motion factor is slower still.
        let line = 1.0 / 0.45;
        let by_hand = (line / 20.0 * 1.5 + 2.0) + 199.0 * (line / 15.0 + 2.0);
        assert!((thin.seconds - by_hand).abs() < 1e-6, "{} vs {by_hand}", thin.seconds);
    }

    #[test]
    fn steep_slopes_are_perimeters_and_flat_ones_solid() {
        assert_eq!(band_share(1.0, 0.2), 1.0);
        assert_eq!(band_share(0.0, 0.2), 0.0);
        // 45°: each layer exposes 0.2 mm, under the loops' 0.9.
        assert_eq!(band_share(std::f64::consts::FRAC_1_SQRT_2, 0.2), 0.0);
        // 5° from flat: bands of 2.3 mm, 61 % past the loops.
        let share = band_share(85f64.to_radians().sin(), 0.2);
        assert!((share - (1.0 - 0.9 / (0.2 / 5f64.to_radians().tan()))).abs() < 1e-12);
    }
}
