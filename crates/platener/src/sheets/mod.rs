//! Step `sheets`: nesting parts onto sheets (the thesis' ShapeLayouter).
//!
//! Parts are grouped by thickness, each group nested on its own sheets. Collision detection is
//! jagua-rs's engine; the placement heuristic is ours: small parts first go into the holes of
//! large ones ([`holes`]), then the rest fill sheets left-first ([`blf`]) in several part
//! orders, keeping the best ([`search`]). Every part lands on exactly one sheet: a part larger
//! than the sheet gets a sheet of its own, sized to it, with a warning. The layout depends only
//! on the parts, the settings and the seed.

mod blf;
mod compress;
mod holes;
mod search;
mod separate;
mod shape;
#[cfg(test)]
mod tests;

use glam::DVec2;
use serde::Serialize;

use crate::context::StepContext;
use crate::kerf::CutPaths;
use crate::plan::{CutSettings, Part, PlanError, PlanInput, SheetPlacement, SheetSize};
use holes::Child;
use search::{best_layout, fit_height, fits_empty, sheet_region};
use shape::{NestShape, nest_shape, rotate};

/// One sheet of material.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Sheet {
    /// 0-based index over all sheets (thinnest material first).
    pub index: u32,
    /// Material thickness, mm.
    pub thickness: f64,
    /// Width, mm (SVG x).
    pub width: f64,
    /// Height, mm (SVG y).
    pub height: f64,
    /// Ids of the parts on it, ascending.
    pub parts: Vec<u32>,
    /// Nominal area of those parts, mm².
    pub parts_area: f64,
    /// Used area: the sheet's height times the length up to the rightmost cut plus the margin
    /// (the rest is one offcut strip along the right-hand side), mm².
    pub used_area: f64,
    /// `parts_area / used_area`.
    pub density: f64,
}

/// The snapshot of step `sheets`.
#[derive(Debug, Clone, Serialize)]
pub struct Nesting {
    /// The sheets, by index.
    pub sheets: Vec<Sheet>,
    /// Where each part sits, in the input's part order.
    pub placements: Vec<SheetPlacement>,
}

/// Nests `parts` (with cut paths `cut`, same order) onto sheets; a part that fits no sheet of
/// the size asked for is an error naming it. `cancelled` is polled between parts.
pub fn nest(
    parts: &[Part],
    cut: &CutPaths,
    settings: &CutSettings,
    cancelled: &(dyn Fn() -> bool + Sync),
) -> Result<Nesting, PlanError> {
    settings.validate()?;
    let shapes: Vec<NestShape> = parts
        .iter()
        .zip(&cut.parts)
        .map(|(part, c)| {
            nest_shape(&c.cut, part.polygon.area(), settings.spacing, settings.fine_rotations).ok_or_else(|| {
                PlanError::Part {
                    part: part.id,
                    message: "its cut path cannot be nested (no area after growing by the spacing)".into(),
                }
            })
        })
        .collect::<Result<_, _>>()?;
    let mut thicknesses: Vec<f64> = parts.iter().map(|p| p.thickness).collect();
    thicknesses.sort_by(f64::total_cmp);
    thicknesses.dedup();
    let mut nesting = Nesting {
        sheets: Vec::new(),
        placements: vec![
            SheetPlacement {
                index: 0,
                x: 0.0,
                y: 0.0,
                rotation: 0.0
            };
            parts.len()
        ],
    };
    for thickness in thicknesses {
        let group = Group {
            parts,
            shapes: &shapes,
            settings,
            cancelled,
            thickness,
            members: (0..parts.len()).filter(|&i| parts[i].thickness == thickness).collect(),
        };
        group.nest(&mut nesting)?;
    }
    finish_sheets(&mut nesting, parts, &shapes, settings);
    Ok(nesting)
}

/// A shape's placement: (sheet index, angle, translation).
type Placement = (usize, f64, DVec2);

/// The parts of one thickness, nested together: what every phase of it reads.
struct Group<'a> {
    parts: &'a [Part],
    shapes: &'a [NestShape],
    settings: &'a CutSettings,
    cancelled: &'a (dyn Fn() -> bool + Sync),
    thickness: f64,
    /// The parts of this thickness (indices into `parts`), in order.
    members: Vec<usize>,
}

impl Group<'_> {
    /// Nests the group onto new sheets of `nesting`: small parts into the holes of larger
    /// ones, the rest onto sheets of the set size or onto the stock listed for the thickness,
    /// in its order ([`Group::nest_on_stock`]).
    fn nest(&self, nesting: &mut Nesting) -> Result<(), PlanError> {
        let (shapes, settings, spacing) = (self.shapes, self.settings, self.settings.spacing);
        let stock = settings.stock_of(self.thickness);
        // A part no sheet holds ends the plan before the holes are filled (a part too large
        // for an empty sheet fits no hole of a part that fits one).
        let sizes: Vec<(f64, f64)> = match settings.sheet {
            _ if !stock.is_empty() => stock.iter().map(|s| (s.width, s.height)).collect(),
            SheetSize::Fixed { width, height } => vec![(width, height)],
            SheetSize::Fit => Vec::new(),
        };
        let fits_some = |i: usize| {
            sizes.iter().any(|&(w, h)| {
                let region = sheet_region(w, h, settings.margin, spacing);
                fits_empty(&shapes[i], region.1 - region.0)
            })
        };
        if let Some(&i) = self.members.iter().find(|&&i| !sizes.is_empty() && !fits_some(i)) {
            return Err(self.too_large(i, &stock));
        }
        let by_area = search::order(shapes, &self.members, 0, 0);
        let hosted = if settings.fill_holes {
            holes::fill_holes(shapes, &by_area, spacing, self.cancelled)
        } else {
            vec![None; shapes.len()]
        };
        let top: Vec<usize> = self.members.iter().copied().filter(|&i| hosted[i].is_none()).collect();
        let mut placed: Vec<Option<Placement>> = vec![None; shapes.len()];
        if stock.is_empty() {
            let (width, height) = self.sheet_size(&top);
            let region = sheet_region(width, height, settings.margin, spacing);
            if let Some(&i) = top.iter().find(|&&i| !fits_empty(&shapes[i], region.1 - region.0)) {
                return Err(self.too_large(i, &stock));
            }
            let layout = self.layout(&top, width, height)?;
            self.take_sheets(nesting, &mut placed, &layout, layout.sheets.len(), (width, height));
        } else {
            self.nest_on_stock(nesting, &mut placed, &top, &stock)?;
        }
        resolve_children(&mut placed, &hosted, &self.members);
        self.record(nesting, &placed)
    }

    /// The best layout of `items` on sheets of `width` × `height` mm.
    fn layout(&self, items: &[usize], width: f64, height: f64) -> Result<search::Layout, PlanError> {
        let settings = self.settings;
        let region = sheet_region(width, height, settings.margin, settings.spacing);
        let cancelled = self.cancelled;
        best_layout(
            self.shapes,
            items,
            region,
            settings.nest_tries,
            settings.seed,
            cancelled,
        )
        .ok_or_else(|| {
            if cancelled() {
                PlanError::Cancelled { step: "sheets" }
            } else {
                PlanError::Setting {
                    name: "sheet",
                    message: format!("{width} × {height} mm leaves no room inside the margins"),
                }
            }
        })
    }

    /// Adds the first `count` sheets of `layout` (each `size`) to `nesting` and records where
    /// their parts are in `placed`.
    fn take_sheets(
        &self,
        nesting: &mut Nesting,
        placed: &mut [Option<Placement>],
        layout: &search::Layout,
        count: usize,
        (width, height): (f64, f64),
    ) {
        for sheet in layout.sheets.iter().take(count) {
            let index = nesting.sheets.len();
            for p in sheet {
                let (angle, t) = self.shapes[p.key].templates[p.template].placement(p.pos);
                placed[p.key] = Some((index, angle, t));
            }
            nesting.sheets.push(empty_sheet(self.thickness, width, height));
        }
    }

    /// Whether part `i` fits an empty sheet of `kind` within the margins.
    fn fits_kind(&self, i: usize, kind: &crate::plan::StockSheet) -> bool {
        let region = sheet_region(kind.width, kind.height, self.settings.margin, self.settings.spacing);
        fits_empty(&self.shapes[i], region.1 - region.0)
    }

    /// The last sheet of `layout` (on stock kind `k`, as many as needed) nested again on the
    /// smallest other kind with a sheet free that holds all of its parts on one sheet: a maker
    /// who lists `3:600x400, 3:300x200` cuts the leftovers from the small sheet. `None` when no
    /// smaller kind holds them.
    fn smaller_last(
        &self,
        layout: &search::Layout,
        stock: &[crate::plan::StockSheet],
        k: usize,
        free: &[Option<usize>],
    ) -> Result<Option<(usize, search::Layout)>, PlanError> {
        let Some(last) = layout.sheets.last() else {
            return Ok(None);
        };
        let items: Vec<usize> = last.iter().map(|p| p.key).collect();
        let area = |j: usize| stock[j].width * stock[j].height;
        let mut smaller: Vec<usize> = (0..stock.len())
            .filter(|&j| j != k && area(j) < area(k) && free[j] != Some(0))
            .filter(|&j| items.iter().all(|&i| self.fits_kind(i, &stock[j])))
            .collect();
        smaller.sort_by(|&a, &b| area(a).total_cmp(&area(b)).then(a.cmp(&b)));
        for j in smaller {
            let other = self.layout(&items, stock[j].width, stock[j].height)?;
            if other.sheets.len() == 1 {
                return Ok(Some((j, other)));
            }
        }
        Ok(None)
    }

    /// Nests `top` onto `stock` in its order: each kind of sheet takes as many of the
    /// remaining parts as its count of sheets holds (offcuts listed first are used first); the
    /// last sheet of a kind listed without a count goes onto a smaller kind when one holds it
    /// ([`Self::smaller_last`]); parts left when the stock is used up end the plan with an
    /// error naming them.
    fn nest_on_stock(
        &self,
        nesting: &mut Nesting,
        placed: &mut [Option<Placement>],
        top: &[usize],
        stock: &[crate::plan::StockSheet],
    ) -> Result<(), PlanError> {
        let mut left: Vec<usize> = top.to_vec();
        // Sheets of each kind still free (`None`: as many as needed).
        let mut free: Vec<Option<usize>> = stock.iter().map(|k| k.count.map(|n| n as usize)).collect();
        for (k, kind) in stock.iter().enumerate() {
            let fitting: Vec<usize> = left.iter().copied().filter(|&i| self.fits_kind(i, kind)).collect();
            if fitting.is_empty() || free[k] == Some(0) {
                continue;
            }
            let layout = self.layout(&fitting, kind.width, kind.height)?;
            let mut count = free[k].map_or(layout.sheets.len(), |n| layout.sheets.len().min(n));
            let smaller = if free[k].is_none() {
                self.smaller_last(&layout, stock, k, &free)?
            } else {
                None
            };
            if smaller.is_some() {
                count -= 1;
            }
            self.take_sheets(nesting, placed, &layout, count, (kind.width, kind.height));
            if let Some((j, last)) = smaller {
                self.take_sheets(nesting, placed, &last, 1, (stock[j].width, stock[j].height));
                free[j] = free[j].map(|n| n - 1);
            }
            free[k] = free[k].map(|n| n - count);
            left.retain(|&i| placed[i].is_none());
        }
        if left.is_empty() {
            return Ok(());
        }
        let mut ids: Vec<u32> = left.iter().map(|&i| self.parts[i].id).collect();
        ids.sort_unstable();
        let listed: Vec<String> = stock.iter().map(crate::plan::StockSheet::text).collect();
        Err(PlanError::Setting {
            name: "stock",
            message: format!(
                "the {} mm sheets in stock ({}) hold {} of the {} parts of that thickness: parts {} need more; \
                 add sheets to `stock`, or leave a count out for as many as needed",
                crate::draw::svg::num(self.settings.nominal(self.thickness)),
                listed.join(", "),
                top.len() - left.len(),
                top.len(),
                ids.iter().map(u32::to_string).collect::<Vec<_>>().join(", ")
            ),
        })
    }

    /// The sheet size for the parts `top` (those not nested into holes): the set one, or
    /// one just large enough.
    fn sheet_size(&self, top: &[usize]) -> (f64, f64) {
        let (shapes, settings) = (self.shapes, self.settings);
        match settings.sheet {
            SheetSize::Fixed { width, height } => (width, height),
            SheetSize::Fit => {
                let h = round_up(fit_height(
                    shapes,
                    top,
                    settings.margin,
                    settings.spacing,
                    self.cancelled,
                ));
                let long: f64 = top
                    .iter()
                    .map(|&i| shapes[i].templates[0].size.max_element())
                    .sum::<f64>()
                    + 2.0 * settings.margin;
                (long, h)
            }
        }
    }

    /// Part `i` does not fit the sheet in any orientation: the sheet is too
    /// small for this model (a part on a sheet of its own would be cut from a sheet the user
    /// does not have), so the plan stops here, naming the part, its size and what to do.
    /// With `stock` listed for the thickness, the message names the stock instead.
    fn too_large(&self, i: usize, stock: &[crate::plan::StockSheet]) -> PlanError {
        let smallest = self.shapes[i]
            .templates
            .iter()
            .map(|t| t.size)
            .min_by(|a, b| (a.x * a.y).total_cmp(&(b.x * b.y)))
            .unwrap_or_default();
        let what = format!("part {}", self.parts[i].id);
        if !stock.is_empty() {
            let listed: Vec<String> = stock.iter().map(crate::plan::StockSheet::text).collect();
            return PlanError::Setting {
                name: "stock",
                message: format!(
                    "{what} is {:.1} × {:.1} mm (cut path and spacing) and fits none of the sheets in stock ({}) \
                     within their {} mm margins: add a larger sheet to `stock`, or scale the model down (`scale`)",
                    smallest.x,
                    smallest.y,
                    listed.join(", "),
                    self.settings.margin
                ),
            };
        }
        PlanError::Setting {
            name: "sheet",
            message: self
                .settings
                .oversize_message(&what, "cut path and spacing", smallest.x, smallest.y),
        }
    }

    /// Records every member's placement in `nesting`.
    fn record(&self, nesting: &mut Nesting, placed: &[Option<Placement>]) -> Result<(), PlanError> {
        for &i in &self.members {
            let (sheet, angle, t) = placed[i].ok_or_else(|| PlanError::Part {
                part: self.parts[i].id,
                message: "was not placed; please report this".into(),
            })?;
            nesting.placements[i] = SheetPlacement {
                index: sheet as u32,
                x: t.x,
                y: t.y,
                rotation: normalized_degrees(angle),
            };
        }
        Ok(())
    }
}

fn empty_sheet(thickness: f64, width: f64, height: f64) -> Sheet {
    Sheet {
        index: 0,
        thickness,
        width,
        height,
        parts: Vec::new(),
        parts_area: 0.0,
        used_area: 0.0,
        density: 0.0,
    }
}

/// Places hosted parts through their hosts (hosts may be hosted themselves).
fn resolve_children(placed: &mut [Option<(usize, f64, DVec2)>], hosted: &[Option<Child>], group: &[usize]) {
    // Each pass resolves one more level of nesting; depth is at most the group size.
    for _ in 0..group.len() {
        let mut progress = false;
        for &i in group {
            if placed[i].is_some() {
                continue;
            }
            if let Some(child) = &hosted[i]
                && let Some((sheet, a, t)) = placed[child.host]
            {
                let (angle, tr) = holes::compose((a, t), child);
                placed[i] = Some((sheet, angle, tr));
                progress = true;
            }
        }
        if !progress {
            break;
        }
    }
}

/// Sheet sizes we choose are rounded up to 0.1 mm, so the numbers in plan.json and in the
/// SVG's `width="…mm"` are the same short decimals.
fn round_up(mm: f64) -> f64 {
    (mm * 10.0 - 1e-9).ceil() / 10.0
}

/// Degrees in [0, 360), with values a rounding away from 360 written as 0.
fn normalized_degrees(angle: f64) -> f64 {
    let d = angle.to_degrees().rem_euclid(360.0);
    if d > 360.0 - 1e-9 { 0.0 } else { d }
}

/// Indexes sheets, lists their parts, measures used length and density. In `fit` mode the
/// sheet is trimmed to its used length.
fn finish_sheets(nesting: &mut Nesting, parts: &[Part], shapes: &[NestShape], settings: &CutSettings) {
    let mut right = vec![0.0f64; nesting.sheets.len()];
    for (i, p) in nesting.placements.iter().enumerate() {
        let s = p.index as usize;
        nesting.sheets[s].parts.push(parts[i].id);
        nesting.sheets[s].parts_area += shapes[i].area;
        let (angle, t) = (p.rotation.to_radians(), DVec2::new(p.x, p.y));
        let far = shapes[i]
            .cut
            .outer
            .iter()
            .map(|q| rotate(*q, angle).x + t.x)
            .fold(0.0, f64::max);
        right[s] = right[s].max(far);
    }
    for (k, sheet) in nesting.sheets.iter_mut().enumerate() {
        sheet.index = k as u32;
        sheet.parts.sort_unstable();
        let used = (right[k] + settings.margin).min(sheet.width);
        if settings.sheet == SheetSize::Fit && settings.stock_of(sheet.thickness).is_empty() {
            sheet.width = round_up(used);
        }
        sheet.used_area = used * sheet.height;
        sheet.density = if sheet.used_area > 0.0 {
            sheet.parts_area / sheet.used_area
        } else {
            0.0
        };
    }
}

/// Extra margins (mm) nesting is retried with when jagua-rs panics. jagua-rs 1.1 sorts edges
/// into its quadtree in f32 and asserts that against an f64 oracle; an edge lying exactly on a
/// quadrant's split line can trip the assertion (seen: the table sample stacked in 1 mm
/// layers). The split lines follow the sheet region, so a margin wider by a few hundredths of
/// a millimetre (not a round number) moves them off the edge; the plan changes by as much.
const RETRY_MARGINS: [f64; 3] = [0.0137, 0.0291, 0.0533];

/// Step `sheets`: every part placed on a sheet of its thickness. A panic inside the nester is
/// retried with a slightly wider margin ([`RETRY_MARGINS`]); the last one propagates (the
/// conversion reports it as an internal error).
pub fn run(input: &PlanInput, cut: &CutPaths, cx: &StepContext<'_>) -> Result<Nesting, PlanError> {
    let attempt = |settings: &crate::plan::CutSettings| {
        std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
            nest(&input.parts, cut, settings, &|| cx.is_cancelled())
        }))
    };
    let mut outcome = attempt(&input.settings);
    for extra in RETRY_MARGINS {
        if outcome.is_ok() {
            break;
        }
        let mut wider = input.settings.clone();
        wider.margin += extra;
        outcome = attempt(&wider);
    }
    outcome.unwrap_or_else(|payload| std::panic::resume_unwind(payload))
}
