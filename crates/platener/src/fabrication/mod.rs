//! How long making the object takes, both ways (issue 35): cutting its sheets on the laser
//! and putting the parts together, against printing the model on an FDM printer. The
//! CHI'15 paper's measure is the machines' times alone (print over laser); report.json gives
//! that and the speed-up counting the maker's hands too.
//!
//! The laser's time per sheet is its cut path (`export::order`) at the laser setting's speeds
//! for the sheet's material and thickness ([`crate::plan::laser`]); the handwork is a fixed
//! time per sheet, per part and per joint by kind ([`handwork`]); the print time is
//! [`print::estimate`] of the model.

pub mod handwork;
pub mod print;

use serde::Serialize;

use crate::plan::{LaserSpeeds, PrintEstimate};

/// What cutting one sheet costs the laser's head, mm and pierces (`export::order::CutPath`'s
/// figures, named here so this module reads no step).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct SheetPath {
    /// Cut length, mm.
    pub cut: f64,
    /// Engraving and scoring length, mm.
    pub engrave: f64,
    /// Travel with the beam off, mm.
    pub travel: f64,
    /// Cut paths started.
    pub pierces: usize,
}

/// Seconds the laser takes for one sheet: each length at its speed, plus each pierce.
pub fn laser_seconds(path: SheetPath, speeds: LaserSpeeds) -> f64 {
    path.cut / speeds.cut
        + path.engrave / speeds.engrave
        + path.travel / speeds.travel
        + path.pierces as f64 * speeds.pierce
}

/// report.json's `fabrication`: the object's making time both ways.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Fabrication {
    /// The laser setting the times are for (`co2`, or a kind and the maker's speeds).
    pub laser: String,
    /// The laser's time for every sheet, s.
    pub laser_seconds: f64,
    /// Loading, focusing and unloading the sheets, s.
    pub sheet_seconds: f64,
    /// Taking the parts out and putting them together, s ([`handwork`]).
    pub assembly_seconds: f64,
    /// All three, s.
    pub total_seconds: f64,
    /// Printing the model instead, s (the reference slicer profile; omitted without a model).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub print_seconds: Option<f64>,
    /// The printer and profile the print time assumes.
    pub print_profile: &'static str,
    /// Print time over laser time: the paper's speed-up.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub speed_up: Option<f64>,
    /// Print time over the total, handwork included.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub speed_up_with_assembly: Option<f64>,
}

/// What the reference print profile is, in words (docs/performance.md calibrates it).
pub const PRINT_PROFILE: &str = "Prusa MK3S, PLA, 0.20 mm layers, 2 perimeters, 15 % infill, no supports";

/// A speed-up ≥ this is the paper's headline class ("at least 10× faster").
pub const SPEED_UP_CLASS: f64 = 10.0;

impl Fabrication {
    /// The making time of a plan whose sheets take `laser_seconds` on the laser, with
    /// `handwork` seconds of sheets and assembly, against `print`.
    pub fn new(laser: String, laser_seconds: f64, handwork: handwork::Handwork, print: Option<PrintEstimate>) -> Self {
        let total = laser_seconds + handwork.sheets + handwork.assembly;
        let ratio = |over: f64| print.filter(|_| over > 0.0).map(|p| p.seconds / over);
        Self {
            laser,
            laser_seconds,
            sheet_seconds: handwork.sheets,
            assembly_seconds: handwork.assembly,
            total_seconds: total,
            print_seconds: print.map(|p| p.seconds),
            print_profile: PRINT_PROFILE,
            speed_up: ratio(laser_seconds),
            speed_up_with_assembly: ratio(total),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_sheets_time_is_each_length_at_its_speed() {
        let speeds = LaserSpeeds {
            cut: 15.0,
            engrave: 150.0,
            travel: 300.0,
            pierce: 0.2,
        };
        let path = SheetPath {
            cut: 1500.0,
            engrave: 300.0,
            travel: 900.0,
            pierces: 10,
        };
        assert!((laser_seconds(path, speeds) - (100.0 + 2.0 + 3.0 + 2.0)).abs() < 1e-12);
    }

    #[test]
    fn the_speed_up_is_print_over_laser() {
        let print = PrintEstimate {
            seconds: 36_000.0,
            layers: 300,
            filament_mm3: 1.0,
            volume_mm3: 1.0,
        };
        let hands = handwork::Handwork {
            sheets: 120.0,
            assembly: 480.0,
        };
        let f = Fabrication::new("co2".into(), 600.0, hands, Some(print));
        assert_eq!(f.total_seconds, 1200.0);
        assert_eq!((f.speed_up, f.speed_up_with_assembly), (Some(60.0), Some(30.0)));
        assert_eq!(Fabrication::new("co2".into(), 600.0, hands, None).speed_up, None);
    }
}
