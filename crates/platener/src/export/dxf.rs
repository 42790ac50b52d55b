//! DXF sheets for laser software that prefers DXF: R2000, `$INSUNITS` = 4 (mm), closed
//! LWPOLYLINEs on layer CUT (red) with the parts' slits as open ones, engraving as open LWPOLYLINEs on layer ENGRAVE (blue),
//! and the sheet's outline on layer SHEET (grey), switched off and not plotted.
//!
//! DXF's y axis points up, the SVG's down: y is written as `height − y`, so the sheet looks the
//! same in both (this flips the drawing's coordinates, not the parts: both views show the sheet
//! as seen from above). The dxf crate stamps files with the current time and random GUIDs; they
//! are pinned to its epoch and the nil GUID so the same sheet gives the same bytes.

use chrono::{Local, TimeZone, Utc};
use dxf::entities::{Entity, EntityType, LwPolyline};
use dxf::enums::{AcadVersion, Units};
use dxf::tables::Layer;
use dxf::{Color, Drawing, LwPolylineVertex};
use glam::DVec2;

use crate::draw::svg::SvgGroup;
use crate::plan::PlanError;

/// Layer of cut paths.
pub const CUT_LAYER: &str = "CUT";
/// Layer of engraving.
pub const ENGRAVE_LAYER: &str = "ENGRAVE";
/// Layer of the sheet's outline: off and not plotted, a frame to place the material by.
pub const SHEET_LAYER: &str = "SHEET";
/// AutoCAD colour index of grey.
const GREY: u8 = 8;
/// AutoCAD colour index of red.
const RED: u8 = 1;
/// AutoCAD colour index of blue.
const BLUE: u8 = 5;

fn pin_header(drawing: &mut Drawing) {
    let h = &mut drawing.header;
    h.version = AcadVersion::R2000;
    h.default_drawing_units = Units::Millimeters;
    // The dxf crate's own epoch (1900-01-01 local): written as exactly 2415021.0 in any zone.
    if let Some(epoch) = Local.with_ymd_and_hms(1900, 1, 1, 0, 0, 0).earliest() {
        h.creation_date = epoch;
        h.update_date = epoch;
    }
    if let Some(epoch) = Utc.with_ymd_and_hms(1900, 1, 1, 0, 0, 0).earliest() {
        h.creation_date_universal = epoch;
        h.update_date_universal = epoch;
    }
    h.fingerprint_guid = uuid::Uuid::nil();
    h.version_guid = uuid::Uuid::nil();
}

fn polyline(points: &[DVec2], closed: bool, layer: &str, height: f64) -> Entity {
    let mut pl = LwPolyline::default();
    pl.set_is_closed(closed);
    pl.vertices = points
        .iter()
        .map(|p| LwPolylineVertex {
            x: p.x,
            y: height - p.y,
            ..Default::default()
        })
        .collect();
    let mut e = Entity::new(EntityType::LwPolyline(pl));
    e.common.layer = layer.to_string();
    e
}

/// The DXF file of one sheet `width` × `height` mm holding `groups` (sheet coordinates, y
/// down).
pub fn sheet_dxf(width: f64, height: f64, groups: &[SvgGroup], file: &str) -> Result<Vec<u8>, PlanError> {
    let mut drawing = Drawing::new();
    pin_header(&mut drawing);
    for (name, color) in [(CUT_LAYER, RED), (ENGRAVE_LAYER, BLUE)] {
        drawing.add_layer(Layer {
            name: name.to_string(),
            color: Color::from_index(color),
            ..Default::default()
        });
    }
    // The sheet's outline first, on a layer CAD programs hide and plot nothing of, so a
    // program that honours layers cuts nothing of it.
    drawing.add_layer(Layer {
        name: SHEET_LAYER.to_string(),
        color: Color::from_index(GREY),
        is_layer_on: false,
        is_layer_plotted: false,
        ..Default::default()
    });
    let sheet = platener_geom::polygon::rect(0.0, 0.0, width, height);
    drawing.add_entity(polyline(&sheet, true, SHEET_LAYER, height));
    // In cut order (`export::order`): each part's engraving, slits, then rings (holes before
    // the outline, as they are ordered).
    for g in groups {
        for line in g.engrave.iter().map(|e| &e.path) {
            drawing.add_entity(polyline(line, false, ENGRAVE_LAYER, height));
        }
        for slit in &g.slits {
            drawing.add_entity(polyline(slit, false, CUT_LAYER, height));
        }
        for ring in &g.cut {
            drawing.add_entity(polyline(ring, true, CUT_LAYER, height));
        }
    }
    let mut out = Vec::new();
    drawing.save(&mut out).map_err(|e| PlanError::write(file, e))?;
    Ok(out)
}

/// A polyline read back from a DXF.
#[derive(Debug, Clone, PartialEq)]
pub struct DxfPolyline {
    /// Its layer.
    pub layer: String,
    /// Whether it is closed.
    pub closed: bool,
    /// Its points in sheet coordinates (y down).
    pub points: Vec<DVec2>,
}

/// Reads the polylines of a DXF written by [`sheet_dxf`] for a sheet `height` mm tall (for
/// tests and checks).
pub fn read_polylines(bytes: &[u8], height: f64) -> Result<Vec<DxfPolyline>, PlanError> {
    let drawing = Drawing::load(&mut std::io::Cursor::new(bytes)).map_err(|e| PlanError::write("dxf (reading)", e))?;
    Ok(drawing
        .entities()
        .filter_map(|e| match &e.specific {
            EntityType::LwPolyline(pl) => Some(DxfPolyline {
                layer: e.common.layer.clone(),
                closed: pl.is_closed(),
                points: pl.vertices.iter().map(|v| DVec2::new(v.x, height - v.y)).collect(),
            }),
            _ => None,
        })
        .collect())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_sheet_round_trips_with_layers_units_and_fixed_stamps() {
        let g = SvgGroup {
            id: "part-1".into(),
            cut: vec![vec![DVec2::new(1.0, 1.0), DVec2::new(11.0, 1.0), DVec2::new(11.0, 6.0)]],
            slits: vec![vec![DVec2::new(4.0, 2.0), DVec2::new(4.0, 5.0)]],
            engrave: vec![crate::draw::svg::Engraved::score(vec![
                DVec2::new(2.0, 2.0),
                DVec2::new(3.0, 3.0),
            ])],
        };
        let a = sheet_dxf(600.0, 400.0, std::slice::from_ref(&g), "t.dxf").expect("writes");
        let b = sheet_dxf(600.0, 400.0, std::slice::from_ref(&g), "t.dxf").expect("writes");
        assert_eq!(a, b);
        let text = String::from_utf8_lossy(&a);
        assert!(text.contains("$INSUNITS\r\n 70\r\n     4") || text.contains("$INSUNITS\n 70\n     4"));
        assert!(text.contains("AC1015"), "R2000");
        let mut back = read_polylines(&a, 400.0).expect("reads");
        assert_eq!(back.len(), 4);
        // The sheet's outline first, on its own layer, which is off and not plotted.
        let sheet = back.remove(0);
        assert_eq!((sheet.layer.as_str(), sheet.closed), (SHEET_LAYER, true));
        let (lo, hi) = platener_geom::boxes::bounds2(sheet.points.iter().copied());
        assert_eq!((lo, hi), (DVec2::ZERO, DVec2::new(600.0, 400.0)));
        let drawing = Drawing::load(&mut std::io::Cursor::new(&a)).expect("loads");
        let layer = drawing
            .layers()
            .find(|l| l.name == SHEET_LAYER)
            .expect("the sheet layer");
        assert!(!layer.is_layer_on && !layer.is_layer_plotted);
        // In cut order: engraving, the slit (cut, open, as drawn), then the ring.
        assert_eq!((back[0].layer.as_str(), back[0].closed), (ENGRAVE_LAYER, false));
        assert_eq!((back[1].layer.as_str(), back[1].closed), (CUT_LAYER, false));
        assert_eq!(back[1].points, g.slits[0]);
        assert_eq!((back[2].layer.as_str(), back[2].closed), (CUT_LAYER, true));
        assert_eq!(back[2].points, g.cut[0]);
    }
}
