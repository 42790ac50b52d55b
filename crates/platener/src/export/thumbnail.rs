//! `thumbnail.png`: the assembled object drawn small, for the gallery's cards.
//!
//! A card showing the first sheet's top-left corner is mostly white; what a visitor wants to
//! see is the object. The triangles are those of `assembly.glb` ([`Assembly`]), drawn by a
//! small software rasterizer so no GPU, browser or new dependency is needed: a z-buffer,
//! flat shading with a fixed light, an orthographic view from the front right and above
//! (the page's 3D view's direction) fitted to the object, and [`SUPERSAMPLE`]² samples per
//! pixel averaged for smooth edges. Everything is f64 arithmetic in a fixed order, so the
//! same parts give the same bytes (PNG encoded by tiny-skia, which resvg already brings).

use glam::{DVec2, DVec3};
use resvg::tiny_skia::Pixmap;

use crate::plan::PlanError;
use crate::scene::Assembly;

/// The thumbnail's name in the ZIP.
pub const FILE: &str = "thumbnail.png";
/// The thumbnail's width, pixels.
pub const WIDTH: u32 = 320;
/// The thumbnail's height, pixels.
pub const HEIGHT: u32 = 240;
/// Samples per pixel along each axis.
const SUPERSAMPLE: u32 = 2;
/// The background (the gallery card's white).
pub const BACKGROUND: [u8; 3] = [255, 255, 255];
/// Room left around the object, as a share of the picture's width or height.
const MARGIN: f64 = 0.06;
/// Where the camera looks from, model coordinates (Z up): front right, above; the page's
/// viewer looks from the same side.
const EYE: DVec3 = DVec3::new(1.0, -1.2, 0.8);
/// Where the light comes from (fixed, so the picture depends on the parts only): above, a
/// little left of the camera, so the three visible sides of a box differ in brightness.
const LIGHT: DVec3 = DVec3::new(0.3, -0.9, 1.4);
/// The share of the light every face gets, lit or not.
const AMBIENT: f64 = 0.45;

/// The thumbnail of `assembly` as PNG bytes, [`WIDTH`] × [`HEIGHT`]; an assembly with nothing
/// to draw gives a blank picture.
pub fn thumbnail(assembly: &Assembly) -> Result<Vec<u8>, PlanError> {
    let triangles: Vec<([DVec3; 3], [u8; 3])> = assembly.triangles().collect();
    picture(&triangles, &triangles, (WIDTH, HEIGHT), None, FILE)
}

/// The arrow's colour: a dark red no part has.
pub const ARROW: [u8; 3] = [190, 30, 30];

/// [`rgb_picture`] as PNG bytes (`name` for errors).
pub fn picture(
    triangles: &[([DVec3; 3], [u8; 3])],
    frame: &[([DVec3; 3], [u8; 3])],
    (width, height): (u32, u32),
    arrow: Option<[DVec3; 2]>,
    name: &str,
) -> Result<Vec<u8>, PlanError> {
    encode(
        &rgb_picture(triangles, frame, (width, height), arrow),
        width,
        height,
        name,
    )
}

/// `triangles` drawn from the thumbnail's camera, fitted to `frame` (so the pictures of one
/// object's assembly steps share one view), `width` × `height` pixels, with an `arrow` from its
/// first model point to its second drawn on top: RGB bytes, row by row.
pub fn rgb_picture(
    triangles: &[([DVec3; 3], [u8; 3])],
    frame: &[([DVec3; 3], [u8; 3])],
    (width, height): (u32, u32),
    arrow: Option<[DVec3; 2]>,
) -> Vec<u8> {
    let finite = |t: &&([DVec3; 3], [u8; 3])| t.0.iter().all(|p| p.is_finite());
    let mut framed: Vec<([DVec3; 3], [u8; 3])> = frame.iter().filter(finite).copied().collect();
    framed.extend(arrow.map(|[a, _]| ([a, a, a], ARROW)));
    let mut canvas = Canvas::new(width * SUPERSAMPLE, height * SUPERSAMPLE);
    if let Some(view) = View::fitted(&framed, canvas.width, canvas.height) {
        // The solids are closed and face outward (plan-format.md), so a triangle facing away
        // is hidden behind its own solid: skipping it halves the work.
        for (t, colour) in triangles
            .iter()
            .filter(finite)
            .filter(|(t, _)| facing(t, view.toward_eye))
        {
            canvas.fill(view.project(t), shade(t, *colour));
        }
        if let Some([from, to]) = arrow {
            draw_arrow(&mut canvas, &view, from, to);
        }
    }
    canvas.downsampled(SUPERSAMPLE)
}

/// An arrow from `from` to `to` (model points) over everything drawn: a shaft and a head, in
/// samples; none when it points at the eye (too short on screen to read).
fn draw_arrow(canvas: &mut Canvas, view: &View, from: DVec3, to: DVec3) {
    let [a, b, _] = view.project(&[from, to, to]);
    let (a, b) = (a.truncate(), b.truncate());
    let length = a.distance(b);
    let k = f64::from(SUPERSAMPLE);
    if length < 12.0 * k {
        return;
    }
    let u = (b - a) / length;
    let n = u.perp();
    let (half, head, wide) = (1.5 * k, (14.0 * k).min(length / 2.0), 6.0 * k);
    let neck = b - u * head;
    let top = 1e12;
    let at = |p: DVec2| p.extend(top);
    canvas.fill([at(a + n * half), at(a - n * half), at(neck - n * half)], ARROW);
    canvas.fill([at(a + n * half), at(neck - n * half), at(neck + n * half)], ARROW);
    canvas.fill([at(neck + n * wide), at(neck - n * wide), at(b)], ARROW);
}

/// The orthographic camera: screen axes and the scale and offset that fit the object.
struct View {
    right: DVec3,
    up: DVec3,
    toward_eye: DVec3,
    scale: f64,
    offset: DVec2,
    /// The depth of the object's farthest point: depths are measured from one below it.
    far: f64,
}

impl View {
    /// The camera that fits every corner of `triangles` into `width` × `height` samples with
    /// [`MARGIN`] around; `None` with nothing to draw.
    fn fitted(triangles: &[([DVec3; 3], [u8; 3])], width: u32, height: u32) -> Option<View> {
        let toward_eye = EYE.normalize();
        let right = (-toward_eye).cross(DVec3::Z).normalize();
        let up = right.cross(-toward_eye);
        let mut view = View {
            right,
            up,
            toward_eye,
            scale: 1.0,
            offset: DVec2::ZERO,
            far: 0.0,
        };
        let (lo, hi) = triangles
            .iter()
            .flat_map(|(t, _)| t.iter())
            .map(|p| view.screen(*p))
            .fold(None, |acc: Option<(DVec2, DVec2)>, p| {
                Some(acc.map_or((p, p), |(a, b)| (a.min(p), b.max(p))))
            })?;
        view.far = triangles
            .iter()
            .flat_map(|(t, _)| t.iter())
            .map(|p| p.dot(toward_eye))
            .fold(f64::INFINITY, f64::min);
        let (w, h) = (f64::from(width), f64::from(height));
        let extent = (hi - lo).max(DVec2::splat(1e-9));
        view.scale = ((w * (1.0 - 2.0 * MARGIN)) / extent.x).min((h * (1.0 - 2.0 * MARGIN)) / extent.y);
        // Centred; y grows downwards on the picture.
        let centre = (lo + hi) / 2.0 * view.scale;
        view.offset = DVec2::new(w / 2.0 - centre.x, h / 2.0 + centre.y);
        Some(view)
    }

    /// A point's position across and up the screen, mm (before fitting).
    fn screen(&self, p: DVec3) -> DVec2 {
        DVec2::new(p.dot(self.right), p.dot(self.up))
    }

    /// A triangle's corners as sample coordinates (x right, y down) and depth towards the eye
    /// (at least 1: see [`Canvas`]).
    fn project(&self, t: &[DVec3; 3]) -> [DVec3; 3] {
        t.map(|p| {
            let s = self.screen(p) * self.scale;
            DVec3::new(
                self.offset.x + s.x,
                self.offset.y - s.y,
                p.dot(self.toward_eye) - self.far + 1.0,
            )
        })
    }
}

/// Whether triangle `t` (counter-clockwise seen from outside) faces the eye.
fn facing(t: &[DVec3; 3], toward_eye: DVec3) -> bool {
    (t[1] - t[0]).cross(t[2] - t[0]).dot(toward_eye) > 0.0
}

/// A face's colour: its part's colour times the light on it (Lambert).
fn shade(t: &[DVec3; 3], colour: [u8; 3]) -> [u8; 3] {
    let n = (t[1] - t[0]).cross(t[2] - t[0]).normalize_or_zero();
    let light = n.dot(LIGHT.normalize()).max(0.0);
    let k = AMBIENT + (1.0 - AMBIENT) * light;
    colour.map(|c| (f64::from(c) * k).round().clamp(0.0, 255.0) as u8)
}

/// A picture being drawn: colours (RGB bytes) and the depth of what is drawn at each sample,
/// as height above the object's farthest point plus one, so zero (the cheapest fill) means
/// nothing is drawn there.
struct Canvas {
    width: u32,
    height: u32,
    colour: Vec<u8>,
    depth: Vec<f64>,
}

impl Canvas {
    fn new(width: u32, height: u32) -> Self {
        let n = (width * height) as usize;
        Canvas {
            width,
            height,
            colour: BACKGROUND.repeat(n),
            depth: vec![0.0; n],
        }
    }

    /// Fills the samples whose centres lie in triangle `t` (sample coordinates, depth in z)
    /// and are nearer the eye than what is there. Row by row: the three barycentric weights
    /// are linear in x, so each row's run of inside samples is solved for, not tested sample
    /// by sample (a thumbnail per method of every conversion has to be cheap).
    fn fill(&mut self, t: [DVec3; 3], colour: [u8; 3]) {
        let Some(weights) = Weights::of(t) else {
            return;
        };
        let y0 = t.iter().map(|p| p.y).fold(f64::INFINITY, f64::min).floor().max(0.0) as u32;
        let y1 = t
            .iter()
            .map(|p| p.y)
            .fold(f64::NEG_INFINITY, f64::max)
            .ceil()
            .min(f64::from(self.height)) as u32;
        for y in y0..y1 {
            let cy = f64::from(y) + 0.5;
            let Some((from, to)) = weights.run(cy, f64::from(self.width)) else {
                continue;
            };
            let row = (y * self.width) as usize;
            for x in from..to {
                let z = weights.depth(f64::from(x) + 0.5, cy);
                let i = row + x as usize;
                if z > self.depth[i] {
                    self.depth[i] = z;
                    self.colour[3 * i..3 * i + 3].copy_from_slice(&colour);
                }
            }
        }
    }

    /// The picture's RGB bytes with each `k` × `k` block of samples averaged into one pixel.
    fn downsampled(&self, k: u32) -> Vec<u8> {
        let (w, h, k) = ((self.width / k) as usize, (self.height / k) as usize, k as usize);
        let stride = 3 * self.width as usize;
        let n = (k * k) as u32;
        let mut sums = vec![0u32; 3 * w];
        let mut out = Vec::with_capacity(3 * w * h);
        for y in 0..h {
            sums.fill(0);
            for row in self.colour[y * k * stride..(y + 1) * k * stride].chunks_exact(stride) {
                // Each pixel's k samples of this row are 3k consecutive bytes.
                for (sum, block) in sums.chunks_exact_mut(3).zip(row.chunks_exact(3 * k)) {
                    for sample in block.chunks_exact(3) {
                        sum[0] += u32::from(sample[0]);
                        sum[1] += u32::from(sample[1]);
                        sum[2] += u32::from(sample[2]);
                    }
                }
            }
            out.extend(sums.iter().map(|s| ((s + n / 2) / n) as u8));
        }
        out
    }
}

/// A triangle's three barycentric weights as linear functions of the sample position, and
/// its depth as one: `w_i(x, y) = k_i · (x, y, 1)`.
struct Weights {
    k: [DVec3; 3],
    z: DVec3,
}

impl Weights {
    /// `None` for a triangle with no area on screen (seen edge-on).
    fn of([a, b, c]: [DVec3; 3]) -> Option<Weights> {
        // The weight of a corner is the signed area of the opposite edge and the point, over
        // the whole triangle's.
        let edge = |p: DVec3, q: DVec3| DVec3::new(p.y - q.y, q.x - p.x, q.y * p.x - q.x * p.y);
        let area = edge(b, c).dot(a.truncate().extend(1.0));
        if area.abs() < 1e-12 {
            return None;
        }
        let k = [edge(b, c) / area, edge(c, a) / area, edge(a, b) / area];
        let z = k[0] * a.z + k[1] * b.z + k[2] * c.z;
        Some(Weights { k, z })
    }

    /// The samples `from..to` of row `y` (sample centres at x + 0.5) inside the triangle,
    /// within `0..width`; `None` when none is.
    fn run(&self, y: f64, width: f64) -> Option<(u32, u32)> {
        // A hair of slack, so a sample centre on an edge two triangles share is never missed
        // by both.
        let (mut lo, mut hi) = (0.5_f64, width - 0.5);
        for k in &self.k {
            let c = k.y * y + k.z + 1e-9;
            if k.x > 0.0 {
                lo = lo.max(-c / k.x);
            } else if k.x < 0.0 {
                hi = hi.min(-c / k.x);
            } else if c < 0.0 {
                return None;
            }
        }
        let (from, to) = ((lo - 0.5).ceil(), (hi - 0.5).floor() + 1.0);
        (from < to).then_some((from as u32, to as u32))
    }

    /// The depth at sample centre (x, y).
    fn depth(&self, x: f64, y: f64) -> f64 {
        self.z.x * x + self.z.y * y + self.z.z
    }
}

/// RGB bytes of a `width` × `height` picture as an opaque PNG (`name` for errors).
pub(crate) fn encode(rgb: &[u8], width: u32, height: u32, name: &str) -> Result<Vec<u8>, PlanError> {
    let mut pixmap =
        Pixmap::new(width, height).ok_or_else(|| PlanError::write(name, format!("no {width} × {height} picture")))?;
    for (px, c) in pixmap.data_mut().chunks_exact_mut(4).zip(rgb.chunks_exact(3)) {
        px.copy_from_slice(&[c[0], c[1], c[2], 255]);
    }
    pixmap.encode_png().map_err(|e| PlanError::write(name, e))
}

#[cfg(test)]
mod tests;
