//! Screenshots as pixels: what the tests check of a rendered WebGL canvas (not blank, the
//! model's colour present, a highlight changed pixels).

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

    /// The share of pixels whose hue is that of `colour` (within 20°), saturated enough to
    /// tell: shading changes lightness, not hue, so a lit model keeps its hue.
    pub fn share_of_hue(&self, colour: [u8; 3]) -> f64 {
        let target = hue(colour).expect("a coloured reference");
        let n = self
            .pixels()
            .filter(|p| hue(*p).is_some_and(|h| (h - target).abs().min(360.0 - (h - target).abs()) < 20.0))
            .count();
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

/// `#rrggbb` (or a three.js colour number) as RGB.
pub fn parse_colour(hex: &str) -> [u8; 3] {
    let h = hex.trim_start_matches('#').trim_start_matches("0x");
    let v = u32::from_str_radix(h, 16).unwrap_or_else(|_| panic!("not a colour: {hex}"));
    [(v >> 16) as u8, (v >> 8) as u8, v as u8]
}
