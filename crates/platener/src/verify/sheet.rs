//! Every part on a sheet the plan has, inside it: a part larger than its sheet, or placed
//! past its edge, would be cut short by the laser.

use glam::DVec2;

use super::{Check, Failure};
use crate::plan::Plan;

/// How far (mm) a nominal outline may reach past the sheet's edge: rounding of plan.json's
/// numbers, far below a kerf.
const EDGE_SLACK: f64 = 0.01;

/// One failure per part that is larger than its sheet, outside it, or on a sheet the plan
/// does not have.
pub(super) fn findings(plan: &Plan) -> Vec<Failure> {
    let mut out = Vec::new();
    for part in &plan.parts {
        let fail = |message: String| Failure {
            check: Check::Sheet,
            parts: vec![part.id],
            message,
        };
        let Some(sheet) = plan.sheets.iter().find(|s| s.index == part.sheet.index) else {
            out.push(fail(format!(
                "part {} is placed on sheet {}, which the plan does not have",
                part.id, part.sheet.index
            )));
            continue;
        };
        let placed = platener_geom::polygon::bounds_of(part.outline.iter().map(|p| part.sheet.apply(*p)));
        let size = placed.1 - placed.0;
        let sheet_size = DVec2::new(sheet.width, sheet.height);
        let fits = |s: DVec2| s.cmple(sheet_size + EDGE_SLACK).all();
        if !fits(size) && !fits(DVec2::new(size.y, size.x)) {
            out.push(fail(format!(
                "part {} ({:.1} × {:.1} mm) is larger than sheet {} ({:.0} × {:.0} mm)",
                part.id, size.x, size.y, sheet.index, sheet.width, sheet.height
            )));
        } else if placed.0.cmplt(DVec2::splat(-EDGE_SLACK)).any() || !placed.1.cmple(sheet_size + EDGE_SLACK).all() {
            out.push(fail(format!(
                "part {} reaches outside sheet {} ({:.0} × {:.0} mm): it spans x {:.1}…{:.1}, y {:.1}…{:.1}",
                part.id, sheet.index, sheet.width, sheet.height, placed.0.x, placed.1.x, placed.0.y, placed.1.y
            )));
        }
    }
    out
}
