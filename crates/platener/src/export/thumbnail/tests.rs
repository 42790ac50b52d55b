use std::collections::BTreeSet;

use resvg::tiny_skia::Pixmap;

use super::*;
use crate::pipeline::StepId;
use crate::settings::Settings;
use platener_fixtures::samples::closed_box;

/// The parts of the plate method for a closed 100 × 80 × 60 mm box of 3 mm walls.
fn box_assembly() -> Assembly {
    let state = crate::bends::tests::run_plate(closed_box(100.0, 80.0, 60.0, 3.0), Settings::default());
    assert!(state.records.iter().any(|r| r.name == StepId::Parts.name()));
    let parts = &state.final_parts().as_ref().expect("parts").parts;
    assert_eq!(parts.len(), 6, "a box of six plates");
    Assembly::new(parts).expect("draws")
}

/// The PNG decoded: its size and its pixels' colours.
fn pixels(png: &[u8]) -> (u32, u32, Vec<[u8; 3]>) {
    let p = Pixmap::decode_png(png).expect("a PNG");
    let colours = p.pixels().iter().map(|c| [c.red(), c.green(), c.blue()]).collect();
    (p.width(), p.height(), colours)
}

#[test]
fn a_box_fills_a_fifth_of_its_thumbnail_shaded_by_side_and_the_bytes_repeat() {
    let assembly = box_assembly();
    let png = thumbnail(&assembly).expect("renders");
    let (w, h, colours) = pixels(&png);
    assert_eq!((w, h), (WIDTH, HEIGHT));
    let drawn = colours.iter().filter(|c| **c != BACKGROUND).count();
    let share = drawn as f64 / colours.len() as f64;
    assert!(share >= 0.2, "the box covers {:.1} % of its thumbnail", share * 100.0);
    // The object is centred and kept off the edges: the border rows and columns are background.
    let border = (0..w)
        .flat_map(|x| [(x, 0), (x, h - 1)])
        .chain((0..h).flat_map(|y| [(0, y), (w - 1, y)]));
    for (x, y) in border {
        assert_eq!(colours[(y * w + x) as usize], BACKGROUND, "({x}, {y}) touches the edge");
    }
    // Three visible sides, three brightnesses (beyond the antialiased edges' blends).
    let mut counts = std::collections::BTreeMap::new();
    for c in colours.iter().filter(|c| **c != BACKGROUND) {
        *counts.entry(*c).or_insert(0usize) += 1;
    }
    let big: BTreeSet<_> = counts.iter().filter(|(_, n)| **n > 500).map(|(c, _)| *c).collect();
    assert!(big.len() >= 3, "flat shading shows the box's sides apart: {big:?}");
    assert_eq!(thumbnail(&box_assembly()).expect("renders"), png, "byte-identical");
}

#[test]
fn nothing_to_draw_gives_a_blank_thumbnail() {
    let png = thumbnail(&Assembly::new(&[]).expect("empty")).expect("renders");
    let (w, h, colours) = pixels(&png);
    assert_eq!((w, h), (WIDTH, HEIGHT));
    assert!(colours.iter().all(|c| *c == BACKGROUND));
}
