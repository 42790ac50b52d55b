//! The fixed colour palette of the scenes: deterministic, so a plate keeps its colour from one
//! run to the next and the GLB bytes depend on the input only.

/// Twelve distinguishable colours (sRGB), after Paul Tol's "muted" and "bright" schemes, in
/// the order they are handed out.
const PALETTE: [(&str, [u8; 3]); 12] = [
    ("blue", [0x44, 0x77, 0xAA]),
    ("red", [0xEE, 0x66, 0x77]),
    ("green", [0x22, 0x88, 0x33]),
    ("yellow", [0xCC, 0xBB, 0x44]),
    ("cyan", [0x66, 0xCC, 0xEE]),
    ("purple", [0xAA, 0x33, 0x77]),
    ("teal", [0x44, 0xAA, 0x99]),
    ("sand", [0xDD, 0xCC, 0x77]),
    ("wine", [0x88, 0x22, 0x55]),
    ("olive", [0x99, 0x99, 0x33]),
    ("indigo", [0x33, 0x22, 0x88]),
    ("rose", [0xCC, 0x66, 0x77]),
];

/// The colour of what is not one of a set (the model as read, small groups drawn together).
const GREY: (&str, [u8; 3]) = ("grey", [0xBB, 0xBB, 0xBB]);

/// A colour of the palette, or grey.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub(crate) struct Colour(Option<usize>);

impl Colour {
    /// Grey: the neutral colour.
    pub(crate) const GREY: Colour = Colour(None);

    /// The colour of the `i`-th item of a set (0-based), repeating after twelve.
    pub(crate) fn nth(i: usize) -> Self {
        Colour(Some(i % PALETTE.len()))
    }

    fn entry(self) -> (&'static str, [u8; 3]) {
        self.0.map_or(GREY, |i| PALETTE[i])
    }

    /// A name for the material.
    pub(crate) fn name(self) -> &'static str {
        self.entry().0
    }

    /// sRGB bytes, as an image shows them.
    pub(crate) fn srgb(self) -> [u8; 3] {
        self.entry().1
    }

    /// Linear RGB in 0..1, as glTF's `baseColorFactor` wants (sRGB decoded).
    pub(crate) fn linear(self) -> [f64; 3] {
        self.entry().1.map(|c| {
            let s = f64::from(c) / 255.0;
            if s <= 0.04045 {
                s / 12.92
            } else {
                ((s + 0.055) / 1.055).powf(2.4)
            }
        })
    }
}
