//! Drawing on a sheet, below every step: the SVG writer (`svg`: true-size sheets, red cut
//! paths, blue engraving, numbers written the same way every time) and the single-stroke
//! font (`font`) that labels, legends and swatches engrave. The `labels` and `export` steps
//! and the swatches use them; they import nothing of the crate (issue 33: they were modules
//! of `export` and `labels`, so the swatches reached into steps).

pub mod font;
pub mod svg;
