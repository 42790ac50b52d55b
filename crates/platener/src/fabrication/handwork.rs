//! The maker's time around the laser: loading each sheet, taking each part out, closing each
//! joint. Rough figures from assembling our own sample plans, stated so that a plan of many
//! small parts and joints does not look as quick as its laser time alone says; the score's
//! effort reads the same total (docs/score.md).

use crate::plan::JointKind;

/// Loading, aligning, focusing and unloading one sheet, s.
pub const SHEET_SECONDS: f64 = 120.0;
/// Taking one part out of its sheet and checking it, s.
pub const PART_SECONDS: f64 = 20.0;

/// Seconds to close one joint of `kind`.
pub fn joint_seconds(kind: JointKind) -> f64 {
    match kind {
        // Lined up and pressed home along a whole edge.
        JointKind::Finger | JointKind::Dovetail => 30.0,
        // Snapped or slid in.
        JointKind::Jim | JointKind::Slot | JointKind::Flap => 20.0,
        // Slid down one slot.
        JointKind::Halved => 10.0,
        // A layer threaded on its shafts.
        JointKind::Shaft => 15.0,
        // Heated or folded along a line.
        JointKind::Bend => 60.0,
        // Glue spread and clamped (not the drying).
        JointKind::Glued => 60.0,
        // Driven in.
        JointKind::Screw => 30.0,
    }
}

/// The maker's seconds for a plan: its sheets, and its parts and joints (the assembly).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Handwork {
    /// Sheets, s.
    pub sheets: f64,
    /// Parts and joints, s.
    pub assembly: f64,
}

impl Handwork {
    /// The handwork of `sheets` sheets, `parts` parts and joints of `kinds`.
    pub fn new(sheets: usize, parts: usize, kinds: impl IntoIterator<Item = JointKind>) -> Self {
        Self {
            sheets: sheets as f64 * SHEET_SECONDS,
            assembly: parts as f64 * PART_SECONDS + kinds.into_iter().map(joint_seconds).sum::<f64>(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_box_takes_its_parts_and_its_twelve_edges() {
        let h = Handwork::new(1, 6, [JointKind::Finger; 12]);
        assert_eq!(h.sheets, 120.0);
        assert_eq!(h.assembly, 6.0 * 20.0 + 12.0 * 30.0);
    }
}
