//! Stock thicker than the model's walls (issue 32, item 6). A plate extruded from one face is
//! a sheet deep whatever lies behind the face; where the model's wall is thinner, the part
//! stands out of the model (a case with 1–2 mm walls cut from 3 mm sheet kept 59 % of its
//! parts' volume inside the model, and nothing said so). The wall behind each extruded plate
//! is measured on a grid of columns through its thickness (`wall_share`); when the wall,
//! weighted by the plates' areas, is thinner than the sheet by more than [`THICKER`], the step
//! says so and what to do.

use glam::{DVec2, DVec3};

use super::{Plate, PlateKind};
use crate::assembly::Inside;

/// Sheets thicker than the walls by more than this factor are reported.
pub const THICKER: f64 = 1.3;
/// Extruded plates covering less than this share of all plates' area are not judged: a few
/// extruded tabs say little about the walls.
const MIN_SHARE: f64 = 0.2;
/// Columns per plate side, and levels through the thickness.
const COLUMNS: usize = 8;
const LEVELS: usize = 8;

/// The walls behind the extruded plates, when thinner than their sheets.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ThickStock {
    /// The model's wall behind the extruded plates, area-weighted, mm.
    pub wall: f64,
    /// Their sheet thickness (area-weighted), mm.
    pub sheet: f64,
    /// The extruded plates' share of all plates' area.
    pub share: f64,
}

impl ThickStock {
    /// The report's sentence, naming the settings to change.
    pub fn message(&self) -> String {
        format!(
            "the sheets ({:.1} mm) are thicker than the model's walls (about {:.1} mm behind the plates made from \
             one face, {:.0} % of the plates' area): those parts stand out of the model; choose sheets of about \
             {:.1} mm (`thickness`) or scale the model up about ×{:.1} (`scale`)",
            self.sheet,
            self.wall,
            100.0 * self.share,
            self.wall,
            self.sheet / self.wall.max(0.1)
        )
    }
}

/// Whether the extruded `plates` stand on walls thinner than their sheets (see the module doc).
pub(crate) fn thick_stock(plates: &[Plate], inside: &Inside<'_>) -> Option<ThickStock> {
    let total: f64 = plates.iter().map(|p| p.area).sum();
    let (mut area, mut wall, mut sheet) = (0.0, 0.0, 0.0);
    for p in plates.iter().filter(|p| p.kind == PlateKind::Extruded) {
        if let Some(share) = wall_share(p, inside) {
            area += p.area;
            wall += p.area * share * p.thickness;
            sheet += p.area * p.thickness;
        }
    }
    if total <= 0.0 || area < MIN_SHARE * total {
        return None;
    }
    let found = ThickStock {
        wall: wall / area,
        sheet: sheet / area,
        share: area / total,
    };
    (found.sheet > THICKER * found.wall).then_some(found)
}

/// The wall behind plate `p` as a share of its thickness, averaged over its columns: each
/// column is probed at levels through the thickness; the run of inside levels from the end
/// that is inside is the wall there (a column inside at both ends has the whole thickness; one
/// outside at both ends lies over a gap, a slot or beyond the model's edge, and says nothing).
/// `None` when no column says anything.
fn wall_share(p: &Plate, inside: &Inside<'_>) -> Option<f64> {
    let (lo, hi) = p.polygon.bounds();
    let step = (hi - lo) / COLUMNS as f64;
    let (mut sum, mut columns) = (0.0, 0usize);
    for i in 0..COLUMNS {
        for j in 0..COLUMNS {
            let q = lo + DVec2::new((i as f64 + 0.5) * step.x, (j as f64 + 0.5) * step.y);
            if !p.polygon.contains(q) {
                continue;
            }
            let level = |k: usize| {
                let z = (k as f64 + 0.5) / LEVELS as f64 * p.thickness;
                inside.contains(p.frame.to_model(DVec3::new(q.x, q.y, z)))
            };
            let run = match (level(0), level(LEVELS - 1)) {
                (true, true) => LEVELS,
                (true, false) => (0..LEVELS).take_while(|&k| level(k)).count(),
                (false, true) => (0..LEVELS).rev().take_while(|&k| level(k)).count(),
                (false, false) => continue,
            };
            sum += run as f64 / LEVELS as f64;
            columns += 1;
        }
    }
    (columns > 0).then(|| sum / columns as f64)
}
