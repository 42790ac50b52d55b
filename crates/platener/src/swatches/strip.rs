//! The kerf test strip (`platener test-strip`): measure the kerf of a laser and material.
//!
//! The sheet holds two parts, cut exactly along the drawn lines (no kerf compensation: the
//! kerf is what we want to find out):
//! - a **strip** with a row of rectangular holes numbered 1…[`HOLE_COUNT`] and an engraved
//!   table hole → kerf;
//! - a **spike** (a small key) whose tip is [`SPIKE_WIDTH`] wide.
//!
//! A cut line removes `k / 2` on each side, so the real spike is `S − k` wide and the real hole
//! `n` is `w(n) + k` wide. Hole `n` is drawn `w(n) = S − 2·kerf(n)` wide with
//! `kerf(n) = (n − 1) · KERF_STEP`; the spike fits it exactly when `S − k = S − 2·kerf(n) + k`,
//! i.e. when `k = kerf(n)`. The hole the spike fits snugly names the kerf:
//! `kerf = (S − w) / 2 = (n − 1) × 0.025 mm`, from 0 to 0.4 mm.

use glam::DVec2;
use platener_geom::Polygon;

use crate::draw::font::{place_text, text_width};
use crate::draw::svg::{Engraved, SvgGroup, SvgStyle, num, sheet_svg};
use crate::plan::{MAX_KERF, Material, PlanError};

/// Width of the spike's tip, mm (the "known width").
pub const SPIKE_WIDTH: f64 = 6.0;
/// Kerf difference between neighbouring holes, mm.
pub const KERF_STEP: f64 = 0.025;
/// Number of holes: kerfs 0, 0.025, …, 0.4 mm.
pub const HOLE_COUNT: u32 = 17;
/// Sheet thickness difference between neighbouring slots, mm.
pub const SLOT_STEP: f64 = 0.05;
/// Number of slots: sheets from 0.4 mm thinner to 0.4 mm thicker than nominal (3 mm plywood
/// measures 2.6–3.4 mm).
pub const SLOT_COUNT: u32 = 17;
/// The narrowest slot drawn, mm: a sheet too thin for the row (paper) gets none.
const MIN_SLOT: f64 = 0.3;
/// Text size of the slots' thicknesses, mm (they stand under slots 10 mm apart).
const SLOT_TEXT: f64 = 1.8;
/// Border between the sheet edge and the parts, mm.
const MARGIN: f64 = 5.0;
/// Hole centre to hole centre, mm.
const PITCH: f64 = SPIKE_WIDTH + 4.0;
/// Text size of hole numbers and the table, mm.
const TEXT: f64 = 2.5;
/// Thicknesses accepted, mm.
const MAX_THICKNESS: f64 = 50.0;

/// The kerf hole `n` (1-based) stands for, mm: `(n − 1) · KERF_STEP`.
pub fn hole_kerf(n: u32) -> f64 {
    f64::from(n.saturating_sub(1)) * KERF_STEP
}

/// The drawn width of hole `n`, mm: `SPIKE_WIDTH − 2 · hole_kerf(n)`.
pub fn hole_width(n: u32) -> f64 {
    SPIKE_WIDTH - 2.0 * hole_kerf(n)
}

/// The hole whose kerf is nearest to `kerf`.
pub fn hole_for_kerf(kerf: f64) -> u32 {
    ((kerf / KERF_STEP).round().clamp(0.0, f64::from(HOLE_COUNT - 1)) as u32) + 1
}

/// One hole of the strip.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StripHole {
    /// Its engraved number, 1-based.
    pub number: u32,
    /// The kerf it stands for, mm.
    pub kerf: f64,
    /// Its drawn width (along the strip), mm.
    pub width: f64,
}

/// One slot of the strip's slot row: the spike turned on its side, as thick as the sheet,
/// enters the slots of sheets at least as thick as it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StripSlot {
    /// The sheet thickness it fits snugly with the kerf in use, mm (engraved under it).
    pub sheet: f64,
    /// Its drawn width (along the strip): `sheet − kerf`, mm.
    pub width: f64,
}

/// The sheet thickness slot `n` (1-based) fits, for sheets sold as `thickness` mm.
pub fn slot_sheet(thickness: f64, n: u32) -> f64 {
    thickness + (f64::from(n) - f64::from(SLOT_COUNT.div_ceil(2))) * SLOT_STEP
}

/// The test strip sheet, in sheet coordinates (mm, y down).
#[derive(Debug, Clone)]
pub struct TestStrip {
    /// The sheet thickness it is drawn for, mm (the slot row's middle slot).
    pub thickness: f64,
    /// Sheet width, mm.
    pub width: f64,
    /// Sheet height, mm.
    pub height: f64,
    /// The strip with its holes (cut as drawn).
    pub strip: Polygon,
    /// The spike key (cut as drawn); its tip is the edge with the largest y.
    pub spike: Polygon,
    /// Engraving on the strip: hole numbers and the table.
    pub strip_engrave: Vec<Vec<DVec2>>,
    /// Engraving on the spike: its width.
    pub spike_engrave: Vec<Vec<DVec2>>,
    /// The holes, left to right.
    pub holes: Vec<StripHole>,
    /// The slot row, left to right (the strip's polygon has their rings after the holes');
    /// empty for sheets too thin to slot.
    pub slots: Vec<StripSlot>,
    /// The hole of the material's default kerf.
    pub default_hole: u32,
    /// The hole marked `*` in the table: the kerf in use (the material's default unless a
    /// plan was cut with another, see [`test_strip_marking`]).
    pub marked_hole: u32,
    /// The engraved table as text, header first (`9=0.200*`, …).
    pub table: Vec<String>,
}

use platener_geom::polygon::rect;

/// The table line of hole `n`, e.g. `9=0.200*`.
fn table_entry(n: u32, marked: bool) -> String {
    format!("{n}={:.3}{}", hole_kerf(n), if marked { "*" } else { "" })
}

/// Lays out the test strip for sheets `thickness` mm thick of `material`, the material's
/// default kerf starred.
pub fn test_strip(thickness: f64, material: Material) -> Result<TestStrip, PlanError> {
    test_strip_marking(thickness, material, material.default_kerf())
}

/// [`test_strip`] with the hole nearest `kerf` starred in the table: the kerf a plan was cut
/// with, so a strip printed after a kerf change marks the kerf in use, not the default.
///
/// Holes are `thickness + 1` mm long across the strip, so the spike (as thick as the sheet)
/// enters them whatever the real thickness, and only the width decides the fit.
pub fn test_strip_marking(thickness: f64, material: Material, kerf: f64) -> Result<TestStrip, PlanError> {
    check(thickness, kerf)?;
    let (default_hole, marked_hole) = (hole_for_kerf(material.default_kerf()), hole_for_kerf(kerf));
    let hole_len = thickness + 1.0;
    let (x0, y0) = (MARGIN, MARGIN);
    let holes_top = y0 + 4.0;
    let numbers_base = holes_top + hole_len + 1.5 + TEXT;
    let mut engrave = Vec::new();
    let mut holes = Vec::new();
    let mut hole_rings = Vec::new();
    for n in 1..=HOLE_COUNT {
        let cx = x0 + 4.0 + SPIKE_WIDTH / 2.0 + f64::from(n - 1) * PITCH;
        let w = hole_width(n);
        // Clockwise in the y-down frame's maths sense: holes run opposite to the outline.
        let mut ring = rect(cx - w / 2.0, holes_top, cx + w / 2.0, holes_top + hole_len);
        ring.reverse();
        hole_rings.push(ring);
        let label = n.to_string();
        let origin = DVec2::new(cx - text_width(&label, TEXT) / 2.0, numbers_base);
        engrave.extend(place_text(&label, TEXT, origin, DVec2::X));
        holes.push(StripHole {
            number: n,
            kerf: hole_kerf(n),
            width: w,
        });
    }
    // The table: header, then columns of five entries.
    let rows = 5u32;
    let col_w = text_width(&table_entry(HOLE_COUNT, true), TEXT) + 4.0;
    let line = TEXT * 1.6;
    let header_base = numbers_base + 3.0 + TEXT;
    let header = format!("HOLE=KERF MM  *{} {}MM", material.name(), num(thickness));
    engrave.extend(place_text(&header, TEXT, DVec2::new(x0 + 4.0, header_base), DVec2::X));
    let mut table = vec![header.clone()];
    for n in 1..=HOLE_COUNT {
        let (col, row) = ((n - 1) / rows, (n - 1) % rows);
        let origin = DVec2::new(
            x0 + 4.0 + f64::from(col) * col_w,
            header_base + f64::from(row + 1) * line,
        );
        let entry = table_entry(n, n == marked_hole);
        engrave.extend(place_text(&entry, TEXT, origin, DVec2::X));
        table.push(entry);
    }
    let table_w = f64::from(HOLE_COUNT.div_ceil(rows)) * col_w;
    let holes_w = 8.0 + SPIKE_WIDTH + f64::from(HOLE_COUNT - 1) * PITCH;
    let row = slot_row(
        thickness,
        kerf,
        DVec2::new(x0, header_base + f64::from(rows) * line + 3.0),
    );
    let strip_w = holes_w
        .max(8.0 + table_w)
        .max(8.0 + text_width(&header, TEXT))
        .max(row.width);
    engrave.extend(row.engrave);
    hole_rings.extend(row.rings);
    let strip = Polygon {
        outer: rect(x0, y0, x0 + strip_w, row.bottom),
        holes: hole_rings,
    };
    let strip_bottom = row.bottom;
    let (spike, spike_engrave, spike_corner) = spike_key(DVec2::new(x0 + strip_w + 5.0, y0), thickness);
    Ok(TestStrip {
        thickness,
        width: spike_corner.x + MARGIN,
        height: strip_bottom.max(spike_corner.y) + MARGIN,
        strip,
        spike,
        strip_engrave: engrave,
        spike_engrave,
        holes,
        slots: row.slots,
        default_hole,
        marked_hole,
        table,
    })
}

/// The spike key from `top_left`: a handle with the spike hanging below it (towards larger
/// y), its width engraved on the handle; and its box's far corner.
fn spike_key(top_left: DVec2, thickness: f64) -> (Polygon, Vec<Vec<DVec2>>, DVec2) {
    let (kx, y0) = (top_left.x, top_left.y);
    let (handle_w, handle_h) = (SPIKE_WIDTH + 10.0, 10.0);
    let spike_len = 2.0 * thickness + 3.0;
    let (sx0, sx1) = (kx + 5.0, kx + 5.0 + SPIKE_WIDTH);
    let spike = Polygon::new(vec![
        DVec2::new(kx, y0),
        DVec2::new(kx + handle_w, y0),
        DVec2::new(kx + handle_w, y0 + handle_h),
        DVec2::new(sx1, y0 + handle_h),
        DVec2::new(sx1, y0 + handle_h + spike_len),
        DVec2::new(sx0, y0 + handle_h + spike_len),
        DVec2::new(sx0, y0 + handle_h),
        DVec2::new(kx, y0 + handle_h),
    ]);
    let key_label = format!("{:.3}", SPIKE_WIDTH);
    let key_origin = DVec2::new(kx + (handle_w - text_width(&key_label, TEXT)) / 2.0, y0 + 2.0 + TEXT);
    let engrave = place_text(&key_label, TEXT, key_origin, DVec2::X);
    (spike, engrave, DVec2::new(kx + handle_w, y0 + handle_h + spike_len))
}

/// The slot row of the strip, from `top_left` down: its slots, their rings (cut as drawn),
/// the engraving (each slot's sheet thickness under it, and a header), the width the strip
/// needs for it and the y where the strip ends below it.
struct SlotRow {
    slots: Vec<StripSlot>,
    rings: Vec<Vec<DVec2>>,
    engrave: Vec<Vec<DVec2>>,
    width: f64,
    bottom: f64,
}

/// Slots `sheet − kerf` wide, so that with the kerf in use the slot of the real sheet
/// thickness is exactly as wide as the sheet: the slot the spike, turned on its side, enters
/// snugly names the thickness to give as `3@2.85`, and the next narrower one a press fit.
/// Slots run [`SPIKE_WIDTH`] + 1 mm along y, so only the sheet's thickness decides the fit.
fn slot_row(thickness: f64, kerf: f64, top_left: DVec2) -> SlotRow {
    let widest = slot_sheet(thickness, SLOT_COUNT) - kerf;
    if slot_sheet(thickness, 1) - kerf < MIN_SLOT {
        return SlotRow {
            slots: Vec::new(),
            rings: Vec::new(),
            engrave: Vec::new(),
            width: 0.0,
            bottom: top_left.y,
        };
    }
    let pitch = PITCH.max(widest + 4.0);
    let (top, length) = (top_left.y + 2.0, SPIKE_WIDTH + 1.0);
    let label_base = top + length + 1.5 + SLOT_TEXT;
    let mut row = SlotRow {
        slots: Vec::new(),
        rings: Vec::new(),
        engrave: Vec::new(),
        width: 8.0 + widest + f64::from(SLOT_COUNT - 1) * pitch,
        bottom: 0.0,
    };
    for n in 1..=SLOT_COUNT {
        let cx = top_left.x + 4.0 + widest / 2.0 + f64::from(n - 1) * pitch;
        let sheet = slot_sheet(thickness, n);
        let w = sheet - kerf;
        let mut ring = rect(cx - w / 2.0, top, cx + w / 2.0, top + length);
        ring.reverse();
        row.rings.push(ring);
        let label = format!("{sheet:.2}");
        let origin = DVec2::new(cx - text_width(&label, SLOT_TEXT) / 2.0, label_base);
        row.engrave.extend(place_text(&label, SLOT_TEXT, origin, DVec2::X));
        row.slots.push(StripSlot { sheet, width: w });
    }
    let header = format!("SLOT=SHEET MM  KERF {}MM", num(kerf));
    let header_base = label_base + 3.0 + TEXT;
    row.engrave.extend(place_text(
        &header,
        TEXT,
        DVec2::new(top_left.x + 4.0, header_base),
        DVec2::X,
    ));
    row.width = row.width.max(8.0 + text_width(&header, TEXT));
    row.bottom = header_base + 3.0;
    row
}

/// Refuses a thickness or a kerf the strip cannot be drawn for.
fn check(thickness: f64, kerf: f64) -> Result<(), PlanError> {
    if !(thickness.is_finite() && thickness > 0.0 && thickness <= MAX_THICKNESS) {
        return Err(PlanError::Setting {
            name: "thickness",
            message: format!("{thickness} mm must be in (0, {MAX_THICKNESS}]"),
        });
    }
    if !(kerf.is_finite() && (0.0..MAX_KERF).contains(&kerf)) {
        return Err(PlanError::Setting {
            name: "kerf",
            message: format!("{kerf} mm must be at least 0 and under {MAX_KERF} mm"),
        });
    }
    Ok(())
}

impl TestStrip {
    /// The sheet as SVG: the strip is `part-1`, the spike `part-2`.
    pub fn svg(&self) -> String {
        let rings = |p: &Polygon| {
            // Holes first, the outline last, as in every sheet ([`crate::export::order`]).
            p.holes
                .iter()
                .cloned()
                .chain(std::iter::once(p.outer.clone()))
                .collect()
        };
        let groups = [
            SvgGroup {
                id: "part-1".into(),
                cut: rings(&self.strip),
                slits: Vec::new(),
                engrave: self.strip_engrave.iter().cloned().map(Engraved::text).collect(),
            },
            SvgGroup {
                id: "part-2".into(),
                cut: rings(&self.spike),
                slits: Vec::new(),
                engrave: self.spike_engrave.iter().cloned().map(Engraved::text).collect(),
            },
        ];
        sheet_svg(self.width, self.height, &groups, &SvgStyle::CUT)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn holes_map_to_kerfs_by_the_stated_formula() {
        assert_eq!(hole_kerf(1), 0.0);
        assert!((hole_kerf(HOLE_COUNT) - 0.4).abs() < 1e-12);
        for n in 1..=HOLE_COUNT {
            assert!(((SPIKE_WIDTH - hole_width(n)) / 2.0 - hole_kerf(n)).abs() < 1e-12);
            assert_eq!(hole_for_kerf(hole_kerf(n)), n);
        }
        assert_eq!(hole_for_kerf(Material::Wood.default_kerf()), 9);
    }

    #[test]
    fn the_strip_holds_its_holes_and_the_spike_stands_apart() {
        let s = test_strip(3.0, Material::Wood).expect("valid thickness");
        assert_eq!(s.strip.holes.len(), (HOLE_COUNT + SLOT_COUNT) as usize);
        for h in &s.strip.holes {
            assert!(
                h.iter()
                    .all(|p| s.strip.contains(*p) || platener_geom::polygon::ring_contains(&s.strip.outer, *p))
            );
        }
        let (lo, hi) = s.strip.bounds();
        let (klo, khi) = s.spike.bounds();
        assert!(klo.x > hi.x && khi.x < s.width && khi.y < s.height && lo.x > 0.0);
        assert!(test_strip(-1.0, Material::Wood).is_err());
    }

    /// The slot row: slot n is drawn `sheet − kerf` wide for sheets 0.4 mm thinner to 0.4 mm
    /// thicker than nominal, the middle one the nominal sheet, every slot inside the strip,
    /// below the holes and apart from its neighbours; paper gets none.
    #[test]
    fn the_slot_row_names_the_sheet_thickness_each_slot_fits() {
        let kerf = 0.15;
        let s = test_strip_marking(3.0, Material::Wood, kerf).expect("strip");
        assert_eq!(s.slots.len(), SLOT_COUNT as usize);
        assert!((s.slots[0].sheet - 2.6).abs() < 1e-9 && (s.slots[16].sheet - 3.4).abs() < 1e-9);
        assert!(
            (s.slots[8].sheet - 3.0).abs() < 1e-9,
            "the middle slot is the nominal sheet"
        );
        let rings = &s.strip.holes[HOLE_COUNT as usize..];
        let lowest_hole = s.strip.holes[..HOLE_COUNT as usize]
            .iter()
            .flatten()
            .map(|p| p.y)
            .fold(f64::MIN, f64::max);
        let mut last_right = f64::MIN;
        for (slot, ring) in s.slots.iter().zip(rings) {
            let (lo, hi) = platener_geom::boxes::bounds2(ring.iter().copied());
            assert!((hi.x - lo.x - (slot.sheet - kerf)).abs() < 1e-9, "drawn sheet − kerf");
            assert!((slot.width - (hi.x - lo.x)).abs() < 1e-9);
            assert!(
                (hi.y - lo.y - (SPIKE_WIDTH + 1.0)).abs() < 1e-9,
                "the spike's width enters freely"
            );
            assert!(lo.y > lowest_hole && lo.x > last_right + 3.0, "apart");
            assert!(
                ring.iter()
                    .all(|p| platener_geom::polygon::ring_contains(&s.strip.outer, *p))
            );
            last_right = hi.x;
        }
        assert!(test_strip(0.3, Material::Paper).expect("paper").slots.is_empty());
        assert_eq!(
            test_strip(0.3, Material::Paper).expect("paper").strip.holes.len(),
            HOLE_COUNT as usize
        );
    }

    #[test]
    fn the_table_stars_the_kerf_in_use() {
        let default = test_strip(3.0, Material::Wood).expect("strip");
        assert_eq!((default.default_hole, default.marked_hole), (9, 9));
        assert!(default.table.contains(&"9=0.200*".to_string()), "{:?}", default.table);
        let recut = test_strip_marking(3.0, Material::Wood, 0.3).expect("strip");
        assert_eq!((recut.default_hole, recut.marked_hole), (9, 13));
        let starred: Vec<&String> = recut.table.iter().filter(|e| e.ends_with('*')).collect();
        assert_eq!(starred, ["13=0.300*"], "only the kerf in use is starred");
        // The engraving is the table's: the star moves from hole 9 to hole 13 (and the slot
        // row, made for the kerf in use, names it).
        assert_ne!(recut.strip_engrave, default.strip_engrave);
        let narrower = recut.slots.iter().zip(&default.slots);
        assert!(narrower.clone().all(|(r, d)| (d.width - r.width - 0.1).abs() < 1e-9));
        for kerf in [-0.1, f64::NAN, MAX_KERF] {
            assert!(test_strip_marking(3.0, Material::Wood, kerf).is_err(), "{kerf}");
        }
    }
}
