//! Named shapes made in code, shared by tests, benchmarks and the shipped examples.
//!
//! Each generator returns a closed, outward-wound triangle list in mm, so tests can assert
//! exact areas and positions against a model whose true geometry is known.

use glam::{DVec2, DVec3};

use platener_geom::Triangle;

/// An axis-aligned box from `min` to `max`, 12 triangles, normals out.
pub fn cuboid(min: DVec3, max: DVec3) -> Vec<Triangle> {
    let xs = [min.x, max.x];
    let ys = [min.y, max.y];
    let zs = [min.z, max.z];
    voxels(&xs, &ys, &zs, |_, _, _| true)
}

/// A rectilinear solid: the union of the grid cells `[xs[i], xs[i+1]] × …` for which
/// `filled(i, j, k)` holds. Only faces between a filled and an empty cell are emitted, so the
/// surface is closed and conforming (cells must not touch along an edge only).
pub fn voxels(xs: &[f64], ys: &[f64], zs: &[f64], filled: impl Fn(usize, usize, usize) -> bool) -> Vec<Triangle> {
    let (nx, ny, nz) = (xs.len() - 1, ys.len() - 1, zs.len() - 1);
    let at = |i: isize, j: isize, k: isize| {
        i >= 0
            && j >= 0
            && k >= 0
            && (i as usize) < nx
            && (j as usize) < ny
            && (k as usize) < nz
            && filled(i as usize, j as usize, k as usize)
    };
    let mut out = Vec::new();
    let p = |i: usize, j: usize, k: usize| DVec3::new(xs[i], ys[j], zs[k]);
    for i in 0..nx {
        for j in 0..ny {
            for k in 0..nz {
                if !at(i as isize, j as isize, k as isize) {
                    continue;
                }
                let (ii, jj, kk) = (i as isize, j as isize, k as isize);
                // Each face as a quad wound counter-clockwise seen from outside.
                let mut quad = |q: [DVec3; 4]| {
                    out.push([q[0], q[1], q[2]]);
                    out.push([q[0], q[2], q[3]]);
                };
                if !at(ii - 1, jj, kk) {
                    quad([p(i, j, k), p(i, j, k + 1), p(i, j + 1, k + 1), p(i, j + 1, k)]);
                }
                if !at(ii + 1, jj, kk) {
                    quad([
                        p(i + 1, j, k),
                        p(i + 1, j + 1, k),
                        p(i + 1, j + 1, k + 1),
                        p(i + 1, j, k + 1),
                    ]);
                }
                if !at(ii, jj - 1, kk) {
                    quad([p(i, j, k), p(i + 1, j, k), p(i + 1, j, k + 1), p(i, j, k + 1)]);
                }
                if !at(ii, jj + 1, kk) {
                    quad([
                        p(i, j + 1, k),
                        p(i, j + 1, k + 1),
                        p(i + 1, j + 1, k + 1),
                        p(i + 1, j + 1, k),
                    ]);
                }
                if !at(ii, jj, kk - 1) {
                    quad([p(i, j, k), p(i, j + 1, k), p(i + 1, j + 1, k), p(i + 1, j, k)]);
                }
                if !at(ii, jj, kk + 1) {
                    quad([
                        p(i, j, k + 1),
                        p(i + 1, j, k + 1),
                        p(i + 1, j + 1, k + 1),
                        p(i, j + 1, k + 1),
                    ]);
                }
            }
        }
    }
    out
}

/// An open-top box (a tray) `w × d × h` with walls and floor `t` thick, outer corner at the
/// origin: five plates.
pub fn open_box(w: f64, d: f64, h: f64, t: f64) -> Vec<Triangle> {
    voxels(&[0.0, t, w - t, w], &[0.0, t, d - t, d], &[0.0, t, h], |i, j, k| {
        k == 0 || i != 1 || j != 1
    })
}

/// Ear-clipping triangulation of a simple counter-clockwise polygon (no holes).
fn triangulate(poly: &[DVec2]) -> Vec<[usize; 3]> {
    let mut idx: Vec<usize> = (0..poly.len()).collect();
    let mut out = Vec::new();
    let mut guard = 0;
    while idx.len() > 3 && guard < 10 * poly.len() * poly.len() {
        guard += 1;
        let n = idx.len();
        let ear = (0..n).find(|&i| {
            let (ia, ib, ic) = ((i + n - 1) % n, i, (i + 1) % n);
            let (a, b, c) = (poly[idx[ia]], poly[idx[ib]], poly[idx[ic]]);
            if (b - a).perp_dot(c - b) <= 0.0 {
                return false;
            }
            // No other corner may lie inside the ear or on its edges.
            (0..n).filter(|&k| k != ia && k != ib && k != ic).all(|k| {
                let q = poly[idx[k]];
                !((b - a).perp_dot(q - a) >= 0.0 && (c - b).perp_dot(q - b) >= 0.0 && (a - c).perp_dot(q - c) >= 0.0)
            })
        });
        let Some(i) = ear else { break };
        out.push([idx[(i + n - 1) % n], idx[i], idx[(i + 1) % n]]);
        idx.remove(i);
    }
    if idx.len() == 3 {
        out.push([idx[0], idx[1], idx[2]]);
    }
    out
}

/// A prism: the simple counter-clockwise `profile` drawn in the XZ plane (x right, z up, seen
/// from −y), extruded from y = 0 to y = `width`.
pub fn prism(profile: &[DVec2], width: f64) -> Vec<Triangle> {
    let at = |p: DVec2, y: f64| DVec3::new(p.x, y, p.y);
    let mut out = Vec::new();
    for [a, b, c] in triangulate(profile) {
        // Counter-clockwise in (x, z) turns around −y (x × z = −y): that is the y = 0 cap.
        out.push([at(profile[a], 0.0), at(profile[b], 0.0), at(profile[c], 0.0)]);
        out.push([at(profile[a], width), at(profile[c], width), at(profile[b], width)]);
    }
    let n = profile.len();
    for i in 0..n {
        let (p, q) = (profile[i], profile[(i + 1) % n]);
        // The solid lies left of p → q, so the side faces right: (q − p) × ŷ.
        out.push([at(p, 0.0), at(q, width), at(q, 0.0)]);
        out.push([at(p, 0.0), at(p, width), at(q, width)]);
    }
    out
}

/// A phone stand of 3 mm plates, one bent profile extruded 70 mm wide: an 85 mm base, a
/// 12 mm front lip, and a 90 mm back plate leaning back at 65° from the base.
pub fn phone_stand() -> Vec<Triangle> {
    let t = 3.0;
    let (len, lip, back, x0) = (85.0, 12.0, 90.0, 35.0);
    let a = 65f64.to_radians();
    let dir = DVec2::new(a.cos(), a.sin());
    let front_foot = DVec2::new(x0, t);
    // A slanted plate t thick is t / sin(a) wide where it meets the base.
    let back_foot = front_foot + DVec2::new(t / a.sin(), 0.0);
    let profile = [
        DVec2::new(0.0, 0.0),
        DVec2::new(len, 0.0),
        DVec2::new(len, t),
        back_foot,
        back_foot + dir * back,
        front_foot + dir * back,
        front_foot,
        DVec2::new(t, t),
        DVec2::new(t, lip),
        DVec2::new(0.0, lip),
    ];
    prism(&profile, 70.0)
}

/// A box `size` with rounded edges of `radius`, each face cut into an `n × n` grid before
/// rounding: `12·n²` triangles, flat where the faces are flat. The benchmark model.
pub fn rounded_box(size: DVec3, radius: f64, n: usize) -> Vec<Triangle> {
    let half = size / 2.0;
    let inner = (half - DVec3::splat(radius)).max(DVec3::ZERO);
    let map = |p: DVec3| {
        let q = p * half;
        let c = q.clamp(-inner, inner);
        let d = q - c;
        if d.length_squared() > 0.0 {
            c + d.normalize() * radius
        } else {
            q
        }
    };
    let faces = [
        (DVec3::X, DVec3::Y, DVec3::Z),
        (-DVec3::X, DVec3::Z, DVec3::Y),
        (DVec3::Y, DVec3::Z, DVec3::X),
        (-DVec3::Y, DVec3::X, DVec3::Z),
        (DVec3::Z, DVec3::X, DVec3::Y),
        (-DVec3::Z, DVec3::Y, DVec3::X),
    ];
    let mut out = Vec::with_capacity(12 * n * n);
    for (normal, u, v) in faces {
        let p = |i: usize, j: usize| {
            let s = 2.0 * i as f64 / n as f64 - 1.0;
            let t = 2.0 * j as f64 / n as f64 - 1.0;
            map(normal + u * s + v * t)
        };
        for i in 0..n {
            for j in 0..n {
                out.push([p(i, j), p(i + 1, j), p(i + 1, j + 1)]);
                out.push([p(i, j), p(i + 1, j + 1), p(i, j + 1)]);
            }
        }
    }
    out
}

/// Serialises triangles as a binary STL (normals from the winding), for tests and examples.
pub fn to_binary_stl(triangles: &[Triangle], header: &str) -> Vec<u8> {
    let mut out = Vec::with_capacity(84 + 50 * triangles.len());
    let mut h = [b' '; 80];
    let bytes = header.as_bytes();
    h[..bytes.len().min(80)].copy_from_slice(&bytes[..bytes.len().min(80)]);
    out.extend_from_slice(&h);
    out.extend_from_slice(&(triangles.len() as u32).to_le_bytes());
    for t in triangles {
        let n = (t[1] - t[0]).cross(t[2] - t[0]).normalize_or_zero();
        for v in std::iter::once(n).chain(t.iter().copied()) {
            for c in v.to_array() {
                out.extend_from_slice(&(c as f32).to_le_bytes());
            }
        }
        out.extend_from_slice(&[0, 0]);
    }
    out
}

/// A closed box `w × d × h` whose six walls are `t` thick (a hollow cube as CAD draws it).
pub fn closed_box(w: f64, d: f64, h: f64, t: f64) -> Vec<Triangle> {
    voxels(
        &[0.0, t, w - t, w],
        &[0.0, t, d - t, d],
        &[0.0, t, h - t, h],
        |i, j, k| (i, j, k) != (1, 1, 1),
    )
}

/// A closed box `w × d × h` (walls `t` thick) with a solid dome on the middle of its lid: a
/// hemisphere of `radius` with `segments` meridians and `rings` bands from its rim up to its
/// top. Plates and a sphere in one closed model, the classifier's mixed plan's reference.
pub fn domed_box(w: f64, d: f64, h: f64, t: f64, radius: f64, segments: usize, rings: usize) -> Vec<Triangle> {
    let rings = rings.max(1);
    let profile: Vec<DVec2> = (0..=rings)
        .map(|i| {
            let (s, c) = (std::f64::consts::FRAC_PI_2 * i as f64 / rings as f64).sin_cos();
            if i == rings {
                DVec2::new(0.0, radius)
            } else {
                DVec2::new(radius * c, radius * s)
            }
        })
        .collect();
    knobbed_box(w, d, h, t, &profile, segments)
}

/// A closed box `w × d × h` (walls `t` thick) with a solid knob on the middle of its lid: the
/// solid of revolution of `profile` (radius, height above the lid) from its rim `(r, 0)` up
/// to its apex `(0, top)`, with `segments` meridians. The box is an outer shell and an
/// inward-wound cavity, so the lid's face is a plain rectangle with the knob's rim as a hole.
pub fn knobbed_box(w: f64, d: f64, h: f64, t: f64, profile: &[DVec2], segments: usize) -> Vec<Triangle> {
    let segments = segments.max(3);
    let mut out: Vec<Triangle> = cuboid(DVec3::ZERO, DVec3::new(w, d, h))
        .into_iter()
        .filter(|tri| !tri.iter().all(|p| p.z == h))
        .collect();
    let cavity = cuboid(DVec3::splat(t), DVec3::new(w - t, d - t, h - t));
    out.extend(cavity.into_iter().map(|[a, b, c]| [a, c, b]));
    let c = DVec2::new(w / 2.0, d / 2.0);
    let at = |i: usize, j: usize| {
        let (sp, cp) = (std::f64::consts::TAU * (j % segments) as f64 / segments as f64).sin_cos();
        let DVec2 { x: r, y: z } = profile[i];
        DVec3::new(c.x + r * cp, c.y + r * sp, h + z)
    };
    let lid = platener_geom::Polygon {
        outer: vec![DVec2::ZERO, DVec2::new(w, 0.0), DVec2::new(w, d), DVec2::new(0.0, d)],
        holes: vec![(0..segments).rev().map(|j| at(0, j).truncate()).collect()],
    };
    let lid = platener_geom::triangulate::triangulate(&lid).expect("a lid on the grid");
    for tri in &lid.triangles {
        out.push(tri.map(|i| lid.points[i as usize].extend(h)));
    }
    let last = profile.len() - 1;
    for j in 0..segments {
        for i in 0..last - 1 {
            let (a, b, c2, e) = (at(i, j), at(i, j + 1), at(i + 1, j + 1), at(i + 1, j));
            out.push([a, b, c2]);
            out.push([a, c2, e]);
        }
        out.push([at(last - 1, j), at(last - 1, j + 1), at(last, 0)]);
    }
    out
}

/// Two `t`-thick plates crossing at right angles in a plus-shaped profile `size` across,
/// extruded `size` deep: a horizontal one at mid height and a vertical one at mid width.
pub fn crossing_plates(size: f64, t: f64) -> Vec<Triangle> {
    let (a, b) = ((size - t) / 2.0, (size + t) / 2.0);
    let p = DVec2::new;
    let profile = [
        p(a, 0.0),
        p(b, 0.0),
        p(b, a),
        p(size, a),
        p(size, b),
        p(b, b),
        p(b, size),
        p(a, size),
        p(a, b),
        p(0.0, b),
        p(0.0, a),
        p(a, a),
    ];
    prism(&profile, size)
}

/// Two `t`-thick plates crossing at right angles (each `len` long, centred on each other),
/// standing over different heights: plate a (normal y) spans `a` in z, plate b (normal x)
/// spans `b`. Where the spans differ the crossing is only as tall as their overlap (a taller
/// divider through a shorter one, or two offset ones).
pub fn crossing_plates_spans(len: f64, t: f64, a: (f64, f64), b: (f64, f64)) -> Vec<Triangle> {
    let across = [0.0, (len - t) / 2.0, (len + t) / 2.0, len];
    let mut zs = vec![a.0, a.1, b.0, b.1];
    zs.sort_by(f64::total_cmp);
    zs.dedup();
    let within = |z: f64, s: (f64, f64)| s.0 < z && z < s.1;
    let zs2 = zs.clone();
    voxels(&across, &across, &zs, move |i, j, k| {
        let z = (zs2[k] + zs2[k + 1]) / 2.0;
        (j == 1 && within(z, a)) || (i == 1 && within(z, b))
    })
}

/// A shelf: two `t`-thick sides `h` tall, `w` apart outside, and a board between them at
/// `shelf` height (an H-shaped profile), `depth` deep.
pub fn shelf(w: f64, h: f64, shelf: f64, depth: f64, t: f64) -> Vec<Triangle> {
    let p = DVec2::new;
    let profile = [
        p(0.0, 0.0),
        p(t, 0.0),
        p(t, shelf),
        p(w - t, shelf),
        p(w - t, 0.0),
        p(w, 0.0),
        p(w, h),
        p(w - t, h),
        p(w - t, shelf + t),
        p(t, shelf + t),
        p(t, h),
        p(0.0, h),
    ];
    prism(&profile, depth)
}

/// A gable roof: two `t`-thick plates rising at `pitch_deg` to a ridge, each `run` wide
/// horizontally, `depth` deep; the plates meet in a mitre along the ridge and their eaves are
/// cut square to the slope.
pub fn roof(run: f64, pitch_deg: f64, depth: f64, t: f64) -> Vec<Triangle> {
    let a = pitch_deg.to_radians();
    let rise = run * a.tan();
    let p = DVec2::new;
    // Outer (upper) surface from (0, 0) up to the ridge (run, rise) and down to (2·run, 0);
    // the lower surface is t below, measured perpendicular to each slope.
    let drop = t / a.cos();
    let (left_in, right_in) = (p(a.sin(), -a.cos()) * t, p(2.0 * run - t * a.sin(), -t * a.cos()));
    let profile = [
        left_in,
        p(run, rise - drop),
        right_in,
        p(2.0 * run, 0.0),
        p(run, rise),
        p(0.0, 0.0),
    ];
    prism(&profile, depth)
}

/// A grid of `nx × ny` closed boxes (`size` mm cubes with `t` mm walls) `gap` mm apart:
/// `120·nx·ny` triangles and `6·nx·ny` plates, the plate-finding benchmark model.
pub fn box_grid(nx: usize, ny: usize, size: f64, t: f64, gap: f64) -> Vec<Triangle> {
    let one = closed_box(size, size, size, t);
    let mut out = Vec::with_capacity(one.len() * nx * ny);
    for i in 0..nx {
        for j in 0..ny {
            let shift = DVec3::new(i as f64 * (size + gap), j as f64 * (size + gap), 0.0);
            out.extend(one.iter().map(|tri| tri.map(|p| p + shift)));
        }
    }
    out
}

/// A workbench frame of 89 × 89 mm lumber, 1526 × 612 × 900 mm: four legs, a ring of
/// rails at the top and one 150 mm above the floor, as one closed solid. The stand-in for a
/// real frame (236 triangles) whose top ring, 1526 × 612 mm, fits no 600 × 400 sheet: every
/// method must refuse it at once, naming that part and the sheet.
pub fn workbench() -> Vec<Triangle> {
    let (w, d, h, s) = (1526.0, 612.0, 900.0, 89.0);
    let (xs, ys, zs) = (
        [0.0, s, w - s, w],
        [0.0, s, d - s, d],
        [0.0, 150.0, 150.0 + s, h - s, h],
    );
    voxels(&xs, &ys, &zs, |i, j, k| {
        let leg = i != 1 && j != 1;
        let ring = (k == 1 || k == 3) && (i != 1 || j != 1);
        leg || ring
    })
}

/// Three `n`-gon boxes with their lids beside them, as an OpenSCAD print plate lays them out:
/// boxes of radius 125 mm and 75 mm high, lids 20 mm high, every wall and floor `wall` thick
/// (`polygon_boxes(40, 5.0)`: 751 × 520 mm, about 3,900 triangles). The stand-in for a real
/// model of polygonal boxes whose plate method took minutes (issue 29).
pub fn polygon_boxes(n: usize, wall: f64) -> Vec<Triangle> {
    let radius = 125.0;
    let mut out = Vec::new();
    for k in 0..3 {
        for (row, height) in [(0.0, 75.0), (1.0, 20.0)] {
            let shift = DVec3::new(radius + k as f64 * 250.5, radius + row * 270.0, 0.0);
            out.extend(cup(n, radius, height, wall).into_iter().map(|t| t.map(|p| p + shift)));
        }
    }
    out
}

/// The models shipped in `examples/`: file name, STL header, triangles.
pub fn shipped_examples() -> Vec<(&'static str, &'static str, Vec<Triangle>)> {
    vec![
        (
            "box-3mm.stl",
            "platener example: closed box 100x80x60 mm of 3 mm plates",
            closed_box(100.0, 80.0, 60.0, 3.0),
        ),
        (
            "tray-3mm.stl",
            "platener example: open tray 120x80x40 mm of 3 mm plates",
            open_box(120.0, 80.0, 40.0, 3.0),
        ),
        (
            "phone-stand.stl",
            "platener example: phone stand of 3 mm plates, back at 65 deg",
            phone_stand(),
        ),
    ]
}

/// A UV sphere of `radius` around `center`: `segments` meridians, `rings` bands from pole to
/// pole (`2·segments·(rings − 1)` triangles), closed and wound outwards. The stacked method's
/// reference model: its cross-sections and surface are known exactly.
pub fn sphere(center: DVec3, radius: f64, segments: usize, rings: usize) -> Vec<Triangle> {
    let (segments, rings) = (segments.max(3), rings.max(2));
    let at = |i: usize, j: usize| {
        let (st, ct) = (std::f64::consts::PI * i as f64 / rings as f64).sin_cos();
        let (sp, cp) = (std::f64::consts::TAU * (j % segments) as f64 / segments as f64).sin_cos();
        center + radius * DVec3::new(st * cp, st * sp, ct)
    };
    let (north, south) = (center + DVec3::Z * radius, center - DVec3::Z * radius);
    let mut out = Vec::with_capacity(2 * segments * (rings - 1));
    for j in 0..segments {
        out.push([north, at(1, j), at(1, j + 1)]);
        for i in 1..rings - 1 {
            // Ring i is above ring i + 1; j + 1 is further round anticlockwise seen from +z.
            let (a, b, c, d) = (at(i, j), at(i, j + 1), at(i + 1, j + 1), at(i + 1, j));
            out.push([a, d, c]);
            out.push([a, c, b]);
        }
        out.push([south, at(rings - 1, j + 1), at(rings - 1, j)]);
    }
    out
}

/// An ellipsoid around `center` with semi-axes `radii` along x, y and z: [`sphere`] stretched
/// (`segments` meridians, `rings` bands), closed and wound outwards.
pub fn ellipsoid(center: DVec3, radii: DVec3, segments: usize, rings: usize) -> Vec<Triangle> {
    sphere(DVec3::ZERO, 1.0, segments, rings)
        .into_iter()
        .map(|t| t.map(|p| center + p * radii))
        .collect()
}

/// An ellipsoid "animal" as issue 31 describes the figurines makers bring: a 90 × 44 × 40 mm
/// body on four legs 10 mm thick reaching 64 mm up into it, a head, a tail and two ears, each its own
/// closed shell overlapping the body (as figurines are often modelled), 128 mm from tail to
/// snout and 94 mm tall, standing on z = 0. 8 640 triangles.
pub fn animal() -> Vec<Triangle> {
    animal_facets(32, 16)
}

/// [`animal`] with every shell `segments` meridians round and `rings` bands high
/// (`9 · 2 · segments · (rings − 1)` triangles: 48 × 24 gives 19 872, a 20 k figurine).
pub fn animal_facets(segments: usize, rings: usize) -> Vec<Triangle> {
    let e = |c: [f64; 3], r: [f64; 3]| ellipsoid(DVec3::from_array(c), DVec3::from_array(r), segments, rings);
    let mut out = e([0.0, 0.0, 60.0], [45.0, 22.0, 20.0]);
    for (x, y) in [(-28.0, -12.0), (-28.0, 12.0), (28.0, -12.0), (28.0, 12.0)] {
        out.extend(e([x, y, 32.0], [5.0, 5.0, 32.0]));
    }
    out.extend(e([48.0, 0.0, 74.0], [14.0, 12.0, 12.0]));
    out.extend(e([-52.0, 0.0, 66.0], [14.0, 3.0, 3.0]));
    for y in [-7.0, 7.0] {
        out.extend(e([52.0, y, 88.0], [3.0, 2.0, 6.0]));
    }
    out
}

/// A boat-like hull with a cabin: a 120 × 36 × 20 mm lens of a hull and a 30 × 20 mm cabin
/// standing 10 mm above its deck, one shell each, overlapping.
pub fn hull_with_cabin() -> Vec<Triangle> {
    let mut out = ellipsoid(DVec3::new(0.0, 0.0, 10.0), DVec3::new(60.0, 18.0, 10.0), 48, 24);
    out.extend(cuboid(DVec3::new(-20.0, -10.0, 12.0), DVec3::new(10.0, 10.0, 30.0)));
    out
}

/// A vase with a handle: a 50 mm wide, 80 mm tall rounded body and a ring handle (12 mm
/// across the middle of its 3 mm thick tube) standing on its side, overlapping the body.
pub fn vase_with_handle() -> Vec<Triangle> {
    let mut out = ellipsoid(DVec3::new(0.0, 0.0, 40.0), DVec3::new(25.0, 25.0, 40.0), 48, 24);
    out.extend(torus(DVec3::new(28.0, 0.0, 45.0), DVec3::Y, 12.0, 3.0, 48, 12));
    out
}

/// The organic samples of issue 31 (file name, triangles): the animal, the hull with its
/// cabin, a torus standing on its rim and the vase with its handle.
pub fn organic_samples() -> Vec<(&'static str, Vec<Triangle>)> {
    vec![
        ("animal.stl", animal()),
        ("hull_with_cabin.stl", hull_with_cabin()),
        (
            "torus.stl",
            torus(DVec3::new(0.0, 0.0, 55.0), DVec3::Y, 40.0, 15.0, 64, 24),
        ),
        ("vase_with_handle.stl", vase_with_handle()),
    ]
}

/// A torus around `center` whose ring turns about the unit `axis`: tube centre `major` from
/// the axis, tube radius `minor`, `segments` steps round the ring and `sides` round the tube
/// (`2·segments·sides` triangles), closed and wound outwards. With `axis` = +y it stands on
/// its rim like a wheel, so layers along z cut two islands in the middle band.
pub fn torus(center: DVec3, axis: DVec3, major: f64, minor: f64, segments: usize, sides: usize) -> Vec<Triangle> {
    let (segments, sides) = (segments.max(3), sides.max(3));
    let axis = axis.normalize();
    // A right-handed (e1, e2, axis): the ring runs from e1 towards e2.
    let e1 = axis.any_orthonormal_vector();
    let e2 = axis.cross(e1);
    let at = |i: usize, j: usize| {
        let (sp, cp) = (std::f64::consts::TAU * (i % segments) as f64 / segments as f64).sin_cos();
        let (ss, cs) = (std::f64::consts::TAU * (j % sides) as f64 / sides as f64).sin_cos();
        let radial = e1 * cp + e2 * sp;
        center + radial * (major + minor * cs) + axis * (minor * ss)
    };
    let mut out = Vec::with_capacity(2 * segments * sides);
    for i in 0..segments {
        for j in 0..sides {
            // d/dring × d/dtube points away from the tube's centre line.
            let (p00, p10, p11, p01) = (at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
            out.push([p00, p10, p11]);
            out.push([p00, p11, p01]);
        }
    }
    out
}

/// Two separate bodies `gap` mm apart along x: a sphere of radius 30 mm at the origin and a
/// torus lying flat (axis z, ring radius 40 mm, tube radius 15 mm), whose layers are rings
/// with a hole. A model of several bodies in one file, as many printable models are.
pub fn two_bodies(gap: f64) -> Vec<Triangle> {
    let mut out = sphere(DVec3::ZERO, 30.0, 48, 24);
    let center = DVec3::new(30.0 + gap + 55.0, 0.0, 0.0);
    out.extend(torus(center, DVec3::Z, 40.0, 15.0, 64, 24));
    out
}

/// A table: a `top_w × top_d` top `t` thick lying flat with its upper face at z = `height`,
/// resting on two vertical leg panels `t` thick, `top_d` deep and `height − t` tall standing on
/// z = 0, their outer faces `leg_inset` (> 0) in from the top's ends at x = 0 and x = `top_w`.
/// One closed solid (the top and legs united): the legs end against the top's underside.
pub fn table(top_w: f64, top_d: f64, height: f64, leg_inset: f64, t: f64) -> Vec<Triangle> {
    assert!(leg_inset > 0.0 && 2.0 * (leg_inset + t) < top_w, "legs inside the top");
    let xs = [
        0.0,
        leg_inset,
        leg_inset + t,
        top_w - leg_inset - t,
        top_w - leg_inset,
        top_w,
    ];
    voxels(&xs, &[0.0, top_d], &[0.0, height - t, height], |i, _, k| {
        k == 1 || i == 1 || i == 3
    })
}

/// A 200 × 100 × 3 mm table top at 75 mm on four solid 15 × 15 mm legs 10 mm in from its
/// edges: the legs stand on the top's underside as bosses would, but become plates (issue 32).
pub fn table_square_legs() -> Vec<Triangle> {
    voxels(
        &[0.0, 10.0, 25.0, 175.0, 190.0, 200.0],
        &[0.0, 10.0, 25.0, 75.0, 90.0, 100.0],
        &[0.0, 72.0, 75.0],
        |i, j, k| k == 1 || ([1, 3].contains(&i) && [1, 3].contains(&j)),
    )
}

/// The letter strokes of [`keychain_tag`]: (x0, y0, x1, y1) rectangles, mm, 1.2 mm wide and
/// 8 mm tall, spelling "ITLEH" in block capitals.
pub const KEYCHAIN_STROKES: [(f64, f64, f64, f64); 12] = [
    (8.0, 2.5, 9.2, 10.5),
    (14.0, 9.3, 21.0, 10.5),
    (16.9, 2.5, 18.1, 9.3),
    (25.0, 2.5, 26.2, 10.5),
    (26.2, 2.5, 31.0, 3.7),
    (35.0, 2.5, 36.2, 10.5),
    (36.2, 2.5, 41.0, 3.7),
    (36.2, 5.9, 40.0, 7.1),
    (36.2, 9.3, 41.0, 10.5),
    (45.0, 2.5, 46.2, 10.5),
    (50.0, 2.5, 51.2, 10.5),
    (46.2, 5.9, 50.0, 7.1),
];

/// A keychain tag as issue 32 saw it: a 60 × 13 × 2.5 mm base with block letters
/// ([`KEYCHAIN_STROKES`]) standing 1.25 mm on its top.
pub fn keychain_tag() -> Vec<Triangle> {
    tag_with_raised(&KEYCHAIN_STROKES)
}

/// A 60 × 13 × 2.5 mm tag with `strokes` ((x0, y0, x1, y1) rectangles, mm, inside it)
/// standing 1.25 mm on its top; touching strokes make one raised detail.
pub fn tag_with_raised(strokes: &[(f64, f64, f64, f64)]) -> Vec<Triangle> {
    let mut xs = vec![0.0, 60.0];
    let mut ys = vec![0.0, 13.0];
    for &(x0, y0, x1, y1) in strokes {
        xs.extend([x0, x1]);
        ys.extend([y0, y1]);
    }
    for v in [&mut xs, &mut ys] {
        v.sort_by(f64::total_cmp);
        v.dedup();
    }
    let (cx, cy) = (xs.clone(), ys.clone());
    voxels(&xs, &ys, &[0.0, 2.5, 3.75], move |i, j, k| {
        let (x, y) = ((cx[i] + cx[i + 1]) / 2.0, (cy[j] + cy[j + 1]) / 2.0);
        k == 0
            || strokes
                .iter()
                .any(|&(x0, y0, x1, y1)| x > x0 && x < x1 && y > y0 && y < y1)
    })
}

/// An 80 × 50 mm floor 3 mm thick with three standoffs on its top (issue 32): a solid
/// 10 × 10 mm boss 6 mm tall (x 10–20, y 10–20), a 10 × 10 mm standoff 6 mm tall with a
/// 3.2 mm square screw hole down to the floor (x 35–45, y 10–20), and an Arduino-like
/// 5.2 mm standoff 5 mm tall with a 3.2 mm hole, 1 mm walls (x 60–65.2, y 10–15.2).
pub fn standoff_floor() -> Vec<Triangle> {
    let xs = [0.0, 10.0, 20.0, 35.0, 38.4, 41.6, 45.0, 60.0, 61.0, 64.2, 65.2, 80.0];
    let ys = [0.0, 10.0, 11.0, 13.4, 14.2, 15.2, 16.6, 20.0, 50.0];
    let (cx, cy) = (xs, ys);
    voxels(&xs, &ys, &[0.0, 3.0, 8.0, 9.0], move |i, j, k| {
        let (x, y) = ((cx[i] + cx[i + 1]) / 2.0, (cy[j] + cy[j + 1]) / 2.0);
        let within = |x0: f64, x1: f64, y0: f64, y1: f64| x > x0 && x < x1 && y > y0 && y < y1;
        let boss = within(10.0, 20.0, 10.0, 20.0);
        let standoff = within(35.0, 45.0, 10.0, 20.0) && !within(38.4, 41.6, 13.4, 16.6);
        let small = within(60.0, 65.2, 10.0, 15.2) && !within(61.0, 64.2, 11.0, 14.2);
        match k {
            0 => true,
            1 => boss || standoff || small,
            _ => boss || standoff,
        }
    })
}

/// A teacup as issue 32 saw it: `segments` facets round and `steps` bands high, 60 mm tall,
/// its curved wall `wall` thick flaring from a 50 mm foot to an 80 mm rim, on a floor `wall`
/// thick, open at the top. With 48 × 12 its facets are about 5 × 5 mm: the plate method cuts
/// each into a plate and its joints leave chips.
pub fn teacup(segments: usize, steps: usize, wall: f64) -> Vec<Triangle> {
    let (rim, height) = (40.0, 60.0);
    let radius = |z: f64| 25.0 + 15.0 * (z / height * std::f64::consts::FRAC_PI_2).sin();
    let outer = (0..=steps).map(|k| {
        let z = height * k as f64 / steps as f64;
        DVec2::new(radius(z) - rim, z)
    });
    let inner = (0..=steps).rev().map(|k| {
        let z = wall + (height - wall) * k as f64 / steps as f64;
        DVec2::new(radius(z) - rim - wall, z)
    });
    let profile: Vec<DVec2> = outer.chain(inner).collect();
    let outline = regular_outline(segments, rim);
    let mut out = sweep_outline(&outline, &profile, false);
    out.extend(outline_cap(&outline, profile[0], false));
    out.extend(outline_cap(&outline, profile[profile.len() - 1], true));
    out
}

/// A small chair as issue 32 saw it, for 2 mm sheet: a 40 × 40 × 2 mm seat 40 mm up on four
/// 4 × 4 mm legs at its corners, and a 40 × 2 × 40 mm back standing on the seat's rear edge.
pub fn small_chair() -> Vec<Triangle> {
    voxels(
        &[0.0, 4.0, 36.0, 40.0],
        &[0.0, 4.0, 36.0, 38.0, 40.0],
        &[0.0, 40.0, 42.0, 82.0],
        |i, j, k| match k {
            0 => i != 1 && j != 1,
            1 => true,
            _ => j == 3,
        },
    )
}

/// The rounded tray of issue 32: 120 × 80 × 40 mm, 3 mm walls and bottom, its vertical corners
/// filleted at 12 mm as 6 facets each (3.1 mm wide outside, 2.4 mm inside): too narrow for a
/// bend zone each, a run of them turns 90°.
pub fn filleted_tray() -> Vec<Triangle> {
    rounded_tray(120.0, 80.0, 40.0, 12.0, 6, 3.0)
}

/// The samples of issue 32's CAD details (file name, triangles): a hexagonal and an octagonal
/// tube with 2 mm walls (to cut from 2 mm sheet), a table on square legs and a keychain tag
/// with raised letters, a teacup with 1.5 mm curved walls and a small chair on 4 × 4 mm legs.
pub fn cad_detail_samples() -> Vec<(&'static str, Vec<Triangle>)> {
    vec![
        ("hex_tube_2mm.stl", tube(6, 50.0, 60.0, 2.0)),
        ("octagon_tube_2mm.stl", tube(8, 50.0, 60.0, 2.0)),
        ("table_square_legs.stl", table_square_legs()),
        ("keychain_tag.stl", keychain_tag()),
        ("standoff_floor.stl", standoff_floor()),
        ("teacup_1.5mm.stl", teacup(48, 12, 1.5)),
        ("small_chair_2mm.stl", small_chair()),
        ("filleted_tray.stl", filleted_tray()),
        ("filleted_tray_2mm.stl", rounded_tray(120.0, 80.0, 40.0, 12.0, 6, 2.0)),
        (
            "filleted_tray_card_1.5mm.stl",
            rounded_tray(120.0, 80.0, 40.0, 12.0, 6, 1.5),
        ),
        ("filleted_case.stl", rounded_case(120.0, 80.0, 40.0, 12.0, 6, 3.0)),
    ]
}

/// The profile of [`star`]: `arms` (at least 3) strips `t` wide radiating from the origin at
/// equal angles, the first along +x, each `arm_len` long from the origin; counter-clockwise,
/// `3·arms` corners (between two arms, the corner where their sides meet).
pub fn star_profile(arms: usize, arm_len: f64, t: f64) -> Vec<DVec2> {
    assert!(arms >= 3, "a star has at least 3 arms");
    let step = 360.0 / arms as f64;
    let angles: Vec<f64> = (0..arms).map(|k| step * k as f64).collect();
    fan_profile(&angles, arm_len, t)
}

/// The profile of [`fan`]: strips `t` wide radiating from the origin at `angles_deg`
/// (ascending, in [0, 360), neighbours at most 180° apart: two arms 180° apart are one plate), each `arm_len` long from the
/// origin; counter-clockwise, three corners per arm (between two arms, the corner where their
/// sides meet).
pub fn fan_profile(angles_deg: &[f64], arm_len: f64, t: f64) -> Vec<DVec2> {
    let k = angles_deg.len();
    assert!(k >= 3, "a fan has at least 3 arms");
    let dir = |a: f64| DVec2::new(a.to_radians().cos(), a.to_radians().sin());
    // Snapped to 1e-9 mm so that sides meant to be collinear (opposite arms of a "+") are
    // exactly so: rounding noise would make the cap triangulation emit zero-area slivers.
    let snap = |p: DVec2| (p * 1e9).round() / 1e9;
    let mut out = Vec::with_capacity(3 * k);
    for i in 0..k {
        let (a, next) = (
            angles_deg[i],
            angles_deg[(i + 1) % k] + if i + 1 == k { 360.0 } else { 0.0 },
        );
        assert!(
            next > a && next - a <= 180.0,
            "arms ascending, neighbours at most 180° apart"
        );
        let (d, n) = (dir(a), dir(a).perp());
        out.push(snap(d * arm_len - n * (t / 2.0)));
        out.push(snap(d * arm_len + n * (t / 2.0)));
        // Where this arm's left side meets the next arm's right side: on the bisector, t/2
        // from both sides.
        let half = (next - a) / 2.0;
        out.push(snap(dir(a + half) * (t / 2.0 / half.to_radians().sin())));
    }
    out
}

/// Plates `t` thick radiating from the z axis at `angles_deg` (see [`fan_profile`]), from
/// z = 0 to z = `depth`: one closed solid whose arms all meet on one line.
pub fn fan(angles_deg: &[f64], arm_len: f64, t: f64, depth: f64) -> Vec<Triangle> {
    along_z(&fan_profile(angles_deg, arm_len, t), depth)
}

/// `profile` (x, y) extruded from z = 0 to z = `depth`.
fn along_z(profile: &[DVec2], depth: f64) -> Vec<Triangle> {
    // `prism` extrudes along +y; turning +90° about x takes y to z and the profile's z to −y,
    // so the profile goes in mirrored (and reversed, to stay counter-clockwise).
    let mirrored: Vec<DVec2> = profile.iter().rev().map(|p| DVec2::new(p.x, -p.y)).collect();
    prism(&mirrored, depth)
        .into_iter()
        .map(|tri| tri.map(|p| DVec3::new(p.x, -p.z, p.y)))
        .collect()
}

/// `arms` (3: a "Y", 4: a "+") plates `t` thick radiating from the z axis at equal angles, the
/// first along +x, each `arm_len` long from the axis, from z = 0 to z = `depth`: the
/// [`star_profile`] extruded along z. One closed solid whose arms all meet on one line.
pub fn star(arms: usize, arm_len: f64, t: f64, depth: f64) -> Vec<Triangle> {
    along_z(&star_profile(arms, arm_len, t), depth)
}

/// The corners of a regular `n`-gon of circumradius `radius` around the origin, the first on
/// +x, counter-clockwise.
fn regular_outline(n: usize, radius: f64) -> Vec<DVec2> {
    assert!(n >= 3, "a polygon has at least 3 sides");
    (0..n)
        .map(|i| {
            let (s, c) = (std::f64::consts::TAU * i as f64 / n as f64).sin_cos();
            DVec2::new(c, s) * radius
        })
        .collect()
}

/// For each corner of the convex counter-clockwise `outline`, the vector that moves it by one
/// unit perpendicular to BOTH its edges (outwards): `outline[i] + d·miter[i]` is the corner of
/// the outline offset by `d`. Offsetting along it keeps every wall exactly `d` thick measured
/// perpendicular to its facet, which is what a sheet of that thickness bent there would give.
fn outline_miters(outline: &[DVec2]) -> Vec<DVec2> {
    let n = outline.len();
    let normal = |i: usize| {
        let e = outline[(i + 1) % n] - outline[i];
        DVec2::new(e.y, -e.x).normalize()
    };
    (0..n)
        .map(|i| {
            let (a, b) = (normal((i + n - 1) % n), normal(i));
            (a + b) / (1.0 + a.dot(b))
        })
        .collect()
}

/// The outline swept around itself: `profile` points are (outward offset of the outline in
/// mm, height z) and each profile edge `k → k + 1` becomes a band of quads round the outline.
/// A counter-clockwise profile (the solid on its left, offset pointing right) gives outward
/// faces. With `closed`, the last profile point joins the first (a ring, open at both ends of
/// the outline's axis); otherwise the profile's ends must be closed by caps
/// ([`outline_cap`]). Triangles whose corners coincide (a profile point whose offset collapses
/// the outline to one point) are left out, so the surface stays closed and conforming.
fn sweep_outline(outline: &[DVec2], profile: &[DVec2], closed: bool) -> Vec<Triangle> {
    let miters = outline_miters(outline);
    let (n, m) = (outline.len(), profile.len());
    let at = |i: usize, k: usize| offset_point(outline[i % n], miters[i % n], profile[k % m]);
    let mut out = Vec::with_capacity(2 * n * m);
    let bands = if closed { m } else { m - 1 };
    for k in 0..bands {
        for i in 0..n {
            let (a, b, c, d) = (at(i, k), at(i + 1, k), at(i + 1, k + 1), at(i, k + 1));
            out.extend(
                [[a, b, c], [a, c, d]]
                    .into_iter()
                    .filter(|t| t[0] != t[1] && t[1] != t[2] && t[0] != t[2]),
            );
        }
    }
    out
}

/// One corner of an offset outline in 3D: `corner + offset·miter` at height `z`, given as the
/// profile point (offset, z). A collapsed corner lands on exactly the same point for every
/// corner (0·miter adds +0.0), which [`sweep_outline`] relies on.
fn offset_point(corner: DVec2, miter: DVec2, profile: DVec2) -> DVec3 {
    let p = corner + miter * profile.x;
    DVec3::new(p.x, p.y, profile.y)
}

/// The flat cap filling the outline offset by `profile.x` at height `profile.y`, facing up
/// (`up`) or down; its corners are exactly [`sweep_outline`]'s, so the two close each other.
fn outline_cap(outline: &[DVec2], profile: DVec2, up: bool) -> Vec<Triangle> {
    let miters = outline_miters(outline);
    let points: Vec<DVec3> = outline
        .iter()
        .zip(&miters)
        .map(|(&c, &m)| offset_point(c, m, profile))
        .collect();
    let flat: Vec<DVec2> = points.iter().map(|p| p.truncate()).collect();
    triangulate(&flat)
        .into_iter()
        .map(|[a, b, c]| {
            if up {
                [points[a], points[b], points[c]]
            } else {
                [points[a], points[c], points[b]]
            }
        })
        .collect()
}

/// An open tray on `outline` (convex, counter-clockwise): walls `wall` thick measured
/// perpendicular to each facet, from z = 0 to `height`, on a floor `wall` thick.
fn tray_on(outline: &[DVec2], height: f64, wall: f64) -> Vec<Triangle> {
    assert!(wall > 0.0 && height > wall, "a tray is taller than its floor is thick");
    let profile = [
        DVec2::new(0.0, 0.0),
        DVec2::new(0.0, height),
        DVec2::new(-wall, height),
        DVec2::new(-wall, wall),
    ];
    let mut out = sweep_outline(outline, &profile, false);
    out.extend(outline_cap(outline, profile[0], false));
    out.extend(outline_cap(outline, profile[3], true));
    out
}

/// A tube: an `n`-sided prism ring around the z axis from z = 0 to `height`, open at both
/// ends. `outer_radius` is the outer corners' circumradius (the first corner on +x); the wall
/// is `wall` thick perpendicular to each facet, so the inner apothem is the outer apothem
/// `outer_radius·cos(π/n)` minus `wall`. Volume `height·n·tan(π/n)·(a_o² − a_i²)`. A bent-plate
/// model: one strip bent `n` times and closed by a seam.
pub fn tube(n: usize, outer_radius: f64, height: f64, wall: f64) -> Vec<Triangle> {
    let apothem = outer_radius * (std::f64::consts::PI / n as f64).cos();
    assert!(
        wall > 0.0 && wall < apothem && height > 0.0,
        "a tube wall thinner than its apothem"
    );
    let profile = [
        DVec2::new(-wall, 0.0),
        DVec2::new(0.0, 0.0),
        DVec2::new(0.0, height),
        DVec2::new(-wall, height),
    ];
    sweep_outline(&regular_outline(n, outer_radius), &profile, true)
}

/// A cup: an `n`-sided wall (outer corners on a circle of `radius` around the z axis, the
/// first on +x) `height` tall on a bottom `wall` thick, open at the top; the wall is `wall`
/// thick perpendicular to each facet. A bent-plate model whose strip is jointed to a bottom.
pub fn cup(n: usize, radius: f64, height: f64, wall: f64) -> Vec<Triangle> {
    assert!(
        wall < radius * (std::f64::consts::PI / n as f64).cos(),
        "a cup wall thinner than its apothem"
    );
    tray_on(&regular_outline(n, radius), height, wall)
}

/// An open tray `w × d × h` (outer corner at the origin) with walls and bottom `wall` thick,
/// whose four vertical corners are rounded: each outer corner is `corner_facets` facets whose
/// corners lie on a circle of `corner_radius`, and the walls are `wall` thick perpendicular to
/// every facet. A bent-plate model: one strip bent at every corner facet.
pub fn rounded_tray(w: f64, d: f64, h: f64, corner_radius: f64, corner_facets: usize, wall: f64) -> Vec<Triangle> {
    tray_on(&rounded_outline(w, d, corner_radius, corner_facets, wall), h, wall)
}

/// A closed case `w × d × h` (outer corner at the origin) with walls, floor and lid `wall`
/// thick, its four vertical edges rounded as [`rounded_tray`]'s: issue 32's filleted box.
pub fn rounded_case(w: f64, d: f64, h: f64, corner_radius: f64, corner_facets: usize, wall: f64) -> Vec<Triangle> {
    assert!(h > 2.0 * wall, "a case is taller than its floor and lid");
    let outline = rounded_outline(w, d, corner_radius, corner_facets, wall);
    let outer = [DVec2::new(0.0, 0.0), DVec2::new(0.0, h)];
    let inner = [DVec2::new(-wall, h - wall), DVec2::new(-wall, wall)];
    let mut out = sweep_outline(&outline, &outer, false);
    out.extend(sweep_outline(&outline, &inner, false));
    out.extend(outline_cap(&outline, outer[0], false));
    out.extend(outline_cap(&outline, outer[1], true));
    out.extend(outline_cap(&outline, inner[0], false));
    out.extend(outline_cap(&outline, inner[1], true));
    out
}

/// The outer outline of [`rounded_tray`] and [`rounded_case`]: a `w × d` rectangle whose
/// corners are `corner_facets` facets on circles of `corner_radius`.
fn rounded_outline(w: f64, d: f64, corner_radius: f64, corner_facets: usize, wall: f64) -> Vec<DVec2> {
    let (r, f) = (corner_radius, corner_facets.max(1));
    let step = std::f64::consts::FRAC_PI_2 / f as f64;
    // Inner facets shrink by wall·tan(step/2) at each end: below r·cos(step/2) they stay.
    assert!(
        2.0 * r < w.min(d) && wall < r * (step / 2.0).cos(),
        "corners fit the tray and keep their facets inside"
    );
    let centres = [
        DVec2::new(w - r, r),
        DVec2::new(w - r, d - r),
        DVec2::new(r, d - r),
        DVec2::new(r, r),
    ];
    let mut outline = Vec::with_capacity(4 * (f + 1));
    for (c, centre) in centres.into_iter().enumerate() {
        let start = -std::f64::consts::FRAC_PI_2 + c as f64 * std::f64::consts::FRAC_PI_2;
        for j in 0..=f {
            let (s, co) = (start + j as f64 * step).sin_cos();
            outline.push(centre + DVec2::new(co, s) * r);
        }
    }
    outline
}

/// An open truncated `n`-sided cone shell around the z axis (no caps): outer corners on a
/// circle of `r_bottom` at z = 0 and `r_top` at z = `height` (the first on +x), the wall
/// `wall` thick perpendicular to each facet, its ends cut level.
///
/// Its development (the outer facets unrolled about their apex) is an annular sector of
/// `n·2·atan(a_b·tan(π/n) / √(H² + a_b²))` where `a_b = r_bottom·cos(π/n)` is the bottom
/// apothem and `H = height·r_bottom / (r_bottom − r_top)` the apex height; for a round cone
/// that is `360°·sin(half angle)`. For n = 24, r 60 → 35, height 50: a_b = 59.49, H = 120,
/// √(H² + a_b²) = 133.9, 24 × 2·atan(59.49·0.1317/133.9) = 160°, well under 360°, so the
/// shell unrolls into one flat part.
pub fn cone_shell(n: usize, r_bottom: f64, r_top: f64, height: f64, wall: f64) -> Vec<Triangle> {
    let cos = (std::f64::consts::PI / n as f64).cos();
    let (a_b, a_t) = (r_bottom * cos, r_top * cos);
    // Offsetting the slanted facet by `wall` along its normal moves it `wall·slant/height`
    // horizontally.
    let shift = wall * (height * height + (a_b - a_t).powi(2)).sqrt() / height;
    assert!(
        height > 0.0 && wall > 0.0 && shift < a_b.min(a_t),
        "a cone shell wall thinner than its apothems"
    );
    let profile = [
        DVec2::new(-shift, 0.0),
        DVec2::new(0.0, 0.0),
        DVec2::new(a_t - a_b, height),
        DVec2::new(a_t - a_b - shift, height),
    ];
    sweep_outline(&regular_outline(n, r_bottom), &profile, true)
}

/// Triangles of the parametric patch `f` over [0, 1]², `nu` × `nv` quads.
pub fn patch(nu: usize, nv: usize, f: impl Fn(f64, f64) -> DVec3) -> Vec<Triangle> {
    let mut out = Vec::with_capacity(2 * nu * nv);
    for i in 0..nu {
        for j in 0..nv {
            let p = |a: usize, b: usize| f(a as f64 / nu as f64, b as f64 / nv as f64);
            let (a, b, c, d) = (p(i, j), p(i + 1, j), p(i + 1, j + 1), p(i, j + 1));
            out.push([a, b, c]);
            out.push([a, c, d]);
        }
    }
    out
}

/// A closed hollow box `w × d × h` with walls `t` thick whose six outer faces carry a
/// texture of bumps up to `amplitude` high, about `period` apart, on a grid of `period / 4`
/// (the classifier's textured-box sample). Bumps vanish along the box's edges, so the outer
/// faces meet as a plain box does; the inner cavity is flat.
pub fn textured_box(size: DVec3, t: f64, amplitude: f64, period: f64) -> Vec<Triangle> {
    use std::f64::consts::PI;
    let mut out = Vec::new();
    for axis in 0..3 {
        for high in [false, true] {
            let (i, j) = ((axis + 1) % 3, (axis + 2) % 3);
            let (li, lj) = (size[i], size[j]);
            let (ki, kj) = ((li / period).round().max(1.0), (lj / period).round().max(1.0));
            let mut normal = DVec3::ZERO;
            normal[axis] = if high { 1.0 } else { -1.0 };
            let face = patch(4 * ki as usize, 4 * kj as usize, |u, v| {
                let mut p = DVec3::ZERO;
                p[axis] = if high { size[axis] } else { 0.0 };
                p[i] = u * li;
                p[j] = v * lj;
                // Exactly flat along the edges, where the next face's grid meets this one.
                let wave = |x: f64, k: f64| {
                    if x <= 0.0 || x >= 1.0 {
                        0.0
                    } else {
                        (PI * x * k).sin().powi(2)
                    }
                };
                let bump = wave(u, ki) * wave(v, kj);
                p + normal * amplitude * bump
            });
            // The low face's triangles turn round, so both faces wind outward.
            out.extend(
                face.into_iter()
                    .map(|[a, b, c]| if high { [a, b, c] } else { [a, c, b] }),
            );
        }
    }
    let cavity = cuboid(DVec3::splat(t), size - DVec3::splat(t));
    out.extend(cavity.into_iter().map(|[a, b, c]| [a, c, b]));
    out
}

/// A solid cylinder of `radius` and `height` on the z axis (base at z = 0) whose side
/// carries a diamond knurl `depth` deep with `ridges` ridges round it, tessellated finely
/// (segments of at most 1 mm): the classifier's knurled-cylinder sample. The caps are fans
/// through the knurled rims, so the solid is closed.
pub fn knurled_cylinder(radius: f64, height: f64, depth: f64, ridges: usize) -> Vec<Triangle> {
    use std::f64::consts::TAU;
    let around = ((TAU * radius).ceil() as usize).max(8 * ridges);
    let up = (height.ceil() as usize).max(2);
    let pitch = TAU * radius / ridges as f64;
    let at = |a: usize, k: usize| {
        let theta = TAU * (a % around) as f64 / around as f64;
        let z = height * k as f64 / up as f64;
        let s = radius * theta;
        let knurl = |x: f64| (x / pitch * TAU).sin().abs();
        let r = radius - depth * 0.5 * (knurl(s + z) + knurl(s - z));
        DVec3::new(r * theta.cos(), r * theta.sin(), z)
    };
    let mut out = Vec::with_capacity(2 * around * (up + 1));
    for a in 0..around {
        for k in 0..up {
            let (p, q, r, s) = (at(a, k), at(a + 1, k), at(a + 1, k + 1), at(a, k + 1));
            out.push([p, q, r]);
            out.push([p, r, s]);
        }
        let (bottom, top) = (DVec3::ZERO, DVec3::new(0.0, 0.0, height));
        out.push([bottom, at(a + 1, 0), at(a, 0)]);
        out.push([top, at(a, up), at(a + 1, up)]);
    }
    out
}

/// The bent-plate samples of issue 19 (file name, triangles), as `examples/bent_samples.rs`
/// writes them for the before/after figures.
pub fn bent_samples() -> Vec<(&'static str, Vec<Triangle>)> {
    vec![
        ("tube6.stl", tube(6, 50.0, 60.0, 3.0)),
        ("tube12.stl", tube(12, 50.0, 60.0, 3.0)),
        ("tube24.stl", tube(24, 50.0, 60.0, 3.0)),
        ("cup16.stl", cup(16, 40.0, 50.0, 3.0)),
        ("rounded_tray.stl", rounded_tray(160.0, 100.0, 40.0, 35.0, 4, 3.0)),
        ("cone24.stl", cone_shell(24, 60.0, 35.0, 50.0, 1.5)),
    ]
}

/// The variable that makes a missing corpus a failure instead of a skip (CI sets it).
pub const REQUIRE_CORPUS: &str = "PLATENER_REQUIRE_CORPUS";

/// The shared corpus of real models by other people (`../shared/corpus` beside the
/// repository, or the folder `PLATENER_CORPUS` names), for tests and benchmarks.
///
/// `Err` holds the message a test prints when it skips because the corpus is absent; with
/// `PLATENER_REQUIRE_CORPUS=1` (set by `.ci/run`) this panics instead, so CI never passes
/// without having run the corpus tests.
pub fn shared_corpus() -> Result<std::path::PathBuf, String> {
    let dir = std::env::var_os("PLATENER_CORPUS").map_or_else(
        || std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../../shared/corpus"),
        std::path::PathBuf::from,
    );
    if dir.is_dir() {
        return Ok(dir.canonicalize().unwrap_or(dir));
    }
    let message = format!("skipping: the shared corpus is not at {}", dir.display());
    if std::env::var_os(REQUIRE_CORPUS).is_some_and(|v| v == "1") {
        panic!("{message}, and {REQUIRE_CORPUS}=1 requires it");
    }
    Err(message)
}

/// Every `.stl` file under `dir` (recursively), sorted, so corpus tests walk models in one
/// order on every machine.
pub fn stl_files(dir: &std::path::Path) -> Vec<std::path::PathBuf> {
    let mut files: Vec<std::path::PathBuf> = std::fs::read_dir(dir)
        .into_iter()
        .flatten()
        .flatten()
        .flat_map(|e| {
            let p = e.path();
            if p.is_dir() { stl_files(&p) } else { vec![p] }
        })
        .filter(|p| p.extension().is_some_and(|e| e.eq_ignore_ascii_case("stl")))
        .collect();
    files.sort();
    files
}
