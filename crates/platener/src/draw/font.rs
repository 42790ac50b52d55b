//! A small single-stroke font: digits, capitals and a few symbols as polylines.
//!
//! Lasers engrave lines, not filled glyphs, and the user's machine may lack any font we could
//! name, so text is drawn as strokes. Glyphs live on a 4 × 6 unit grid (cap height 6, baseline
//! 0, y up) and advance by 6 units; a text of size `s` mm has caps `s` mm tall. Lowercase is
//! drawn as capitals; an unknown character as `?`.

use glam::DVec2;

/// Cap height in font units.
const CAP: f64 = 6.0;
/// Advance per character in font units (4 for the glyph, 2 for the gap).
const ADVANCE: f64 = 6.0;
/// Glyph width in font units.
const GLYPH_WIDTH: f64 = 4.0;

type Stroke = &'static [(f64, f64)];

const RING_O: Stroke = &[
    (1.0, 0.0),
    (0.0, 1.0),
    (0.0, 5.0),
    (1.0, 6.0),
    (3.0, 6.0),
    (4.0, 5.0),
    (4.0, 1.0),
    (3.0, 0.0),
    (1.0, 0.0),
];
const BOWL_P: Stroke = &[
    (0.0, 0.0),
    (0.0, 6.0),
    (3.0, 6.0),
    (4.0, 5.0),
    (4.0, 4.0),
    (3.0, 3.0),
    (0.0, 3.0),
];

/// The strokes of one character.
#[allow(
    clippy::too_many_lines,
    reason = "a table: the strokes of every character the font has"
)]
fn glyph(c: char) -> &'static [Stroke] {
    match c.to_ascii_uppercase() {
        '0' => &[RING_O, &[(3.5, 5.0), (0.5, 1.0)]],
        '1' => &[&[(1.0, 5.0), (2.0, 6.0), (2.0, 0.0)], &[(1.0, 0.0), (3.0, 0.0)]],
        '2' => &[&[
            (0.0, 5.0),
            (1.0, 6.0),
            (3.0, 6.0),
            (4.0, 5.0),
            (4.0, 4.0),
            (0.0, 0.0),
            (4.0, 0.0),
        ]],
        '3' => &[
            &[
                (0.0, 5.0),
                (1.0, 6.0),
                (3.0, 6.0),
                (4.0, 5.0),
                (4.0, 4.0),
                (3.0, 3.0),
                (1.5, 3.0),
            ],
            &[(3.0, 3.0), (4.0, 2.0), (4.0, 1.0), (3.0, 0.0), (1.0, 0.0), (0.0, 1.0)],
        ],
        '4' => &[&[(3.0, 0.0), (3.0, 6.0), (0.0, 2.0), (4.0, 2.0)]],
        '5' => &[&[
            (4.0, 6.0),
            (0.0, 6.0),
            (0.0, 3.5),
            (3.0, 3.5),
            (4.0, 2.5),
            (4.0, 1.0),
            (3.0, 0.0),
            (1.0, 0.0),
            (0.0, 1.0),
        ]],
        '6' => &[&[
            (4.0, 5.0),
            (3.0, 6.0),
            (1.0, 6.0),
            (0.0, 5.0),
            (0.0, 1.0),
            (1.0, 0.0),
            (3.0, 0.0),
            (4.0, 1.0),
            (4.0, 2.5),
            (3.0, 3.5),
            (1.0, 3.5),
            (0.0, 2.5),
        ]],
        '7' => &[&[(0.0, 6.0), (4.0, 6.0), (1.5, 0.0)]],
        '8' => &[&[
            (1.0, 3.0),
            (0.0, 4.0),
            (0.0, 5.0),
            (1.0, 6.0),
            (3.0, 6.0),
            (4.0, 5.0),
            (4.0, 4.0),
            (3.0, 3.0),
            (1.0, 3.0),
            (0.0, 2.0),
            (0.0, 1.0),
            (1.0, 0.0),
            (3.0, 0.0),
            (4.0, 1.0),
            (4.0, 2.0),
            (3.0, 3.0),
        ]],
        '9' => &[&[
            (0.0, 1.0),
            (1.0, 0.0),
            (3.0, 0.0),
            (4.0, 1.0),
            (4.0, 5.0),
            (3.0, 6.0),
            (1.0, 6.0),
            (0.0, 5.0),
            (0.0, 3.5),
            (1.0, 2.5),
            (3.0, 2.5),
            (4.0, 3.5),
        ]],
        'A' => &[
            &[(0.0, 0.0), (0.0, 4.0), (2.0, 6.0), (4.0, 4.0), (4.0, 0.0)],
            &[(0.0, 2.5), (4.0, 2.5)],
        ],
        'B' => &[BOWL_P, &[(3.0, 3.0), (4.0, 2.0), (4.0, 1.0), (3.0, 0.0), (0.0, 0.0)]],
        'C' => &[&[
            (4.0, 5.0),
            (3.0, 6.0),
            (1.0, 6.0),
            (0.0, 5.0),
            (0.0, 1.0),
            (1.0, 0.0),
            (3.0, 0.0),
            (4.0, 1.0),
        ]],
        'D' => &[&[
            (0.0, 0.0),
            (0.0, 6.0),
            (2.5, 6.0),
            (4.0, 4.5),
            (4.0, 1.5),
            (2.5, 0.0),
            (0.0, 0.0),
        ]],
        'E' => &[
            &[(4.0, 6.0), (0.0, 6.0), (0.0, 0.0), (4.0, 0.0)],
            &[(0.0, 3.0), (3.0, 3.0)],
        ],
        'F' => &[&[(4.0, 6.0), (0.0, 6.0), (0.0, 0.0)], &[(0.0, 3.0), (3.0, 3.0)]],
        'G' => &[&[
            (4.0, 5.0),
            (3.0, 6.0),
            (1.0, 6.0),
            (0.0, 5.0),
            (0.0, 1.0),
            (1.0, 0.0),
            (3.0, 0.0),
            (4.0, 1.0),
            (4.0, 3.0),
            (2.0, 3.0),
        ]],
        'H' => &[
            &[(0.0, 0.0), (0.0, 6.0)],
            &[(4.0, 0.0), (4.0, 6.0)],
            &[(0.0, 3.0), (4.0, 3.0)],
        ],
        'I' => &[
            &[(1.0, 6.0), (3.0, 6.0)],
            &[(2.0, 6.0), (2.0, 0.0)],
            &[(1.0, 0.0), (3.0, 0.0)],
        ],
        'J' => &[&[(4.0, 6.0), (4.0, 1.0), (3.0, 0.0), (1.0, 0.0), (0.0, 1.0)]],
        'K' => &[
            &[(0.0, 0.0), (0.0, 6.0)],
            &[(4.0, 6.0), (0.0, 2.0)],
            &[(1.5, 3.5), (4.0, 0.0)],
        ],
        'L' => &[&[(0.0, 6.0), (0.0, 0.0), (4.0, 0.0)]],
        'M' => &[&[(0.0, 0.0), (0.0, 6.0), (2.0, 3.0), (4.0, 6.0), (4.0, 0.0)]],
        'N' => &[&[(0.0, 0.0), (0.0, 6.0), (4.0, 0.0), (4.0, 6.0)]],
        'O' => &[RING_O],
        'P' => &[BOWL_P],
        'Q' => &[RING_O, &[(2.5, 1.5), (4.0, 0.0)]],
        'R' => &[BOWL_P, &[(2.0, 3.0), (4.0, 0.0)]],
        'S' => &[&[
            (4.0, 5.0),
            (3.0, 6.0),
            (1.0, 6.0),
            (0.0, 5.0),
            (0.0, 4.0),
            (1.0, 3.0),
            (3.0, 3.0),
            (4.0, 2.0),
            (4.0, 1.0),
            (3.0, 0.0),
            (1.0, 0.0),
            (0.0, 1.0),
        ]],
        'T' => &[&[(0.0, 6.0), (4.0, 6.0)], &[(2.0, 6.0), (2.0, 0.0)]],
        'U' => &[&[(0.0, 6.0), (0.0, 1.0), (1.0, 0.0), (3.0, 0.0), (4.0, 1.0), (4.0, 6.0)]],
        'V' => &[&[(0.0, 6.0), (2.0, 0.0), (4.0, 6.0)]],
        'W' => &[&[(0.0, 6.0), (1.0, 0.0), (2.0, 4.0), (3.0, 0.0), (4.0, 6.0)]],
        'X' => &[&[(0.0, 0.0), (4.0, 6.0)], &[(0.0, 6.0), (4.0, 0.0)]],
        'Y' => &[&[(0.0, 6.0), (2.0, 3.0), (4.0, 6.0)], &[(2.0, 3.0), (2.0, 0.0)]],
        'Z' => &[&[(0.0, 6.0), (4.0, 6.0), (0.0, 0.0), (4.0, 0.0)]],
        '.' => &[&[(1.5, 0.0), (2.5, 0.0), (2.5, 1.0), (1.5, 1.0), (1.5, 0.0)]],
        '-' => &[&[(0.5, 3.0), (3.5, 3.0)]],
        '+' => &[&[(0.5, 3.0), (3.5, 3.0)], &[(2.0, 1.5), (2.0, 4.5)]],
        '=' => &[&[(0.5, 2.0), (3.5, 2.0)], &[(0.5, 4.0), (3.5, 4.0)]],
        ':' => &[
            &[(1.5, 0.5), (2.5, 0.5), (2.5, 1.5), (1.5, 1.5), (1.5, 0.5)],
            &[(1.5, 3.5), (2.5, 3.5), (2.5, 4.5), (1.5, 4.5), (1.5, 3.5)],
        ],
        '/' => &[&[(0.0, 0.0), (4.0, 6.0)]],
        '#' => &[
            &[(1.3, 0.5), (1.3, 5.5)],
            &[(2.7, 0.5), (2.7, 5.5)],
            &[(0.0, 2.0), (4.0, 2.0)],
            &[(0.0, 4.0), (4.0, 4.0)],
        ],
        '*' => &[
            &[(2.0, 1.0), (2.0, 5.0)],
            &[(0.5, 2.0), (3.5, 4.0)],
            &[(0.5, 4.0), (3.5, 2.0)],
        ],
        '(' => &[&[(3.0, 6.0), (1.5, 4.5), (1.5, 1.5), (3.0, 0.0)]],
        ')' => &[&[(1.0, 6.0), (2.5, 4.5), (2.5, 1.5), (1.0, 0.0)]],
        ' ' => &[],
        _ => &[
            &[
                (0.0, 5.0),
                (1.0, 6.0),
                (3.0, 6.0),
                (4.0, 5.0),
                (4.0, 4.0),
                (2.0, 2.5),
                (2.0, 1.5),
            ],
            &[(2.0, 0.5), (2.0, 0.0)],
        ],
    }
}

/// Width in mm of `text` at cap height `size` mm (from the first glyph's left to the last
/// glyph's right edge).
pub fn text_width(text: &str, size: f64) -> f64 {
    let n = text.chars().count();
    if n == 0 {
        return 0.0;
    }
    ((n - 1) as f64 * ADVANCE + GLYPH_WIDTH) * size / CAP
}

/// The strokes of `text` at cap height `size` mm, in the text's own frame: baseline on y = 0,
/// caps up to y = `size`, starting at x = 0 (y up).
pub fn text_strokes(text: &str, size: f64) -> Vec<Vec<DVec2>> {
    let scale = size / CAP;
    let mut out = Vec::new();
    for (i, c) in text.chars().enumerate() {
        let x0 = i as f64 * ADVANCE;
        for stroke in glyph(c) {
            out.push(
                stroke
                    .iter()
                    .map(|&(x, y)| DVec2::new((x0 + x) * scale, y * scale))
                    .collect(),
            );
        }
    }
    out
}

/// Strokes of `text` placed in a y-down frame (SVG sheets, part frames as laid on the sheet):
/// the text's bottom-left corner at `origin`, its baseline along `direction` (unit), reading
/// correctly on screen.
pub fn place_text(text: &str, size: f64, origin: DVec2, direction: DVec2) -> Vec<Vec<DVec2>> {
    // In a y-down frame "up" is the baseline direction turned by −90° (mathematically).
    let up = DVec2::new(direction.y, -direction.x);
    text_strokes(text, size)
        .into_iter()
        .map(|s| s.into_iter().map(|p| origin + direction * p.x + up * p.y).collect())
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_supported_character_stays_in_its_cell() {
        let text = "0123456789ABCDEFGHIJKLMNOPQRSTUVWXYZ.-+=:/#*() ?";
        let size = 3.0;
        let strokes = text_strokes(text, size);
        let w = text_width(text, size);
        for p in strokes.iter().flatten() {
            assert!(p.x >= -1e-12 && p.x <= w + 1e-12, "{p}");
            assert!(p.y >= -1e-12 && p.y <= size + 1e-12, "{p}");
        }
        // Every glyph but the space draws something.
        assert_eq!(text_strokes("8", 1.0).len(), 1);
        assert!(text_strokes(" ", 1.0).is_empty());
    }

    #[test]
    fn placed_text_reads_left_to_right_with_caps_up_on_screen() {
        let s = place_text("1", 6.0, DVec2::new(10.0, 20.0), DVec2::X);
        // The stem of the 1 goes from the baseline (y = 20) up the screen (smaller y).
        let ys: Vec<f64> = s.iter().flatten().map(|p| p.y).collect();
        let (lo, hi) = ys.iter().fold((f64::MAX, f64::MIN), |(a, b), y| (a.min(*y), b.max(*y)));
        assert!((hi - 20.0).abs() < 1e-12 && (lo - 14.0).abs() < 1e-12);
        assert!((text_width("12", 6.0) - 10.0).abs() < 1e-12);
    }
}
