//! Screenshots as pixels: what the tests check of a rendered WebGL canvas (not blank, the
//! model's colour present, a highlight changed pixels), and the checks themselves.

/// An RGBA image decoded from a PNG.
pub struct Image {
    pub width: u32,
    pub height: u32,
    pub rgba: Vec<u8>,
}

impl Image {
    /// Decodes a PNG screenshot (8-bit RGB or RGBA, as Chromium writes them).
    pub fn from_png(png: &[u8]) -> Image {
        let mut decoder = png::Decoder::new(std::io::Cursor::new(png));
        decoder.set_transformations(png::Transformations::EXPAND | png::Transformations::STRIP_16);
        let mut reader = decoder.read_info().expect("a PNG");
        let mut buf = vec![0; reader.output_buffer_size().expect("size")];
        let info = reader.next_frame(&mut buf).expect("a frame");
        buf.truncate(info.buffer_size());
        let rgba = match info.color_type {
            png::ColorType::Rgba => buf,
            png::ColorType::Rgb => buf.chunks(3).flat_map(|p| [p[0], p[1], p[2], 255]).collect(),
            other => panic!("unexpected PNG colour type {other:?}"),
        };
        Image {
            width: info.width,
            height: info.height,
            rgba,
        }
    }

    /// Every pixel's RGB.
    pub fn pixels(&self) -> impl Iterator<Item = [u8; 3]> + '_ {
        self.rgba.chunks(4).map(|p| [p[0], p[1], p[2]])
    }

    /// The most common colour: the background of a canvas with a model in it.
    pub fn background(&self) -> [u8; 3] {
        let mut counts = std::collections::HashMap::new();
        for p in self.pixels() {
            *counts.entry(p).or_insert(0usize) += 1;
        }
        counts
            .into_iter()
            .max_by_key(|&(_, n)| n)
            .map(|(c, _)| c)
            .unwrap_or_default()
    }

    /// The share of pixels farther than `tolerance` (per channel) from `colour`.
    pub fn share_unlike(&self, colour: [u8; 3], tolerance: u8) -> f64 {
        let n = self.pixels().filter(|p| !near(*p, colour, tolerance)).count();
        n as f64 / f64::from((self.width * self.height).max(1))
    }

    /// How many pixels differ (by more than `tolerance`) between two images of one size.
    pub fn changed_pixels(&self, other: &Image, tolerance: u8) -> usize {
        assert_eq!((self.width, self.height), (other.width, other.height), "same size");
        self.pixels()
            .zip(other.pixels())
            .filter(|(a, b)| !near(*a, *b, tolerance))
            .count()
    }
}

/// Whether two colours are within `tolerance` on every channel.
pub fn near(a: [u8; 3], b: [u8; 3], tolerance: u8) -> bool {
    a.iter().zip(b).all(|(x, y)| x.abs_diff(y) <= tolerance)
}

/// A colour's hue in degrees, None for greys (saturation under 0.25) and near-black.
pub fn hue([r, g, b]: [u8; 3]) -> Option<f64> {
    let (r, g, b) = (f64::from(r) / 255.0, f64::from(g) / 255.0, f64::from(b) / 255.0);
    let max = r.max(g).max(b);
    let min = r.min(g).min(b);
    let d = max - min;
    if max < 0.1 || d / max < 0.25 {
        return None;
    }
    let h = if max == r {
        60.0 * ((g - b) / d).rem_euclid(6.0)
    } else if max == g {
        60.0 * ((b - r) / d + 2.0)
    } else {
        60.0 * ((r - g) / d + 4.0)
    };
    Some(h)
}

/// The share of the canvas in the scenes' grey.
pub fn grey_share(img: &Image) -> f64 {
    img.pixels().filter(|p| is_scene_grey(*p)).count() as f64 / f64::from(img.width * img.height)
}

/// The share of the canvas in saturated colours, and how many 30° hue bins hold more than
/// 200 pixels (several plates in their own palette colours).
pub fn palette_share(img: &Image) -> (f64, usize) {
    let mut bins = std::collections::BTreeMap::new();
    for h in img.pixels().filter_map(hue) {
        *bins.entry((h / 30.0) as u32).or_insert(0usize) += 1;
    }
    let coloured: usize = bins.values().sum();
    let hues = bins.values().filter(|&&n| n > 200).count();
    (coloured as f64 / f64::from(img.width * img.height), hues)
}

/// A view's pixels hold its model: not blank, and the view's colours. `model` and
/// `wireframe` draw the mesh in the scene's grey; the others in palette colours, several.
pub fn assert_view_rendered(view: &str, img: &Image) {
    let drawn = img.share_unlike(img.background(), 8);
    assert!(
        drawn > 0.02,
        "{view}: only {:.2} % of the canvas differs from its background",
        drawn * 100.0
    );
    if matches!(view, "model" | "wireframe") {
        let grey = grey_share(img);
        assert!(grey > 0.01, "{view}: the model's grey covers {:.2} %", grey * 100.0);
    } else {
        let (share, hues) = palette_share(img);
        assert!(
            share > 0.02 && hues >= 2,
            "{view}: palette colours {:.2} % in {hues} hues",
            share * 100.0
        );
    }
}

/// The same checks fail on the viewer before any model is loaded (so they can fail).
pub fn assert_viewer_empty(img: &Image) {
    let (share, _) = palette_share(img);
    assert!(grey_share(img) < 0.01 && share < 0.02, "the empty viewer looks drawn");
}

/// A pixel of the scenes' grey (#BBBBBB) as lit: neutral, and darker than anything the
/// bluish grid blends to with the background, so a canvas with only the grid has none.
pub fn is_scene_grey(p: [u8; 3]) -> bool {
    let (max, min) = (
        p.iter().max().copied().unwrap_or(0),
        p.iter().min().copied().unwrap_or(0),
    );
    max - min <= 4 && max < 216 && min > 40
}
