//! Necks left by joints (issue 15: "no part has a neck narrower than twice its thickness").
//!
//! A finger slot cut near a plate's edge or close to one of its holes leaves a strip of
//! material that breaks when the part is handled. After the joints are cut and the outlines
//! cleaned, every plate part is searched for necks narrower than twice its thickness
//! ([`platener_geom::necks`]) that the plate did not have before its joints (a model's own
//! thin bars are the model's); each is reported with the part, its width and its place.
//! Widening one would move a slot or a finger, which belongs to the joints, so they are
//! reported, not changed.

use std::collections::BTreeMap;

use platener_geom::Polygon;
use platener_geom::necks::{Neck, neck_bounds, necks_except};
use rayon::prelude::*;

use crate::context::{StepContext, WarningKind};
use crate::plan::Part;
use crate::plates::Plates;

/// The necks of each part that its joints made: `(part id, necks)` for parts with any, in
/// part order. `plate_of` maps a part's id to its plate's index (dovetail keys have none and
/// are not checked).
pub fn joint_necks(parts: &[Part], plates: &Plates, plate_of: &BTreeMap<u32, usize>) -> Vec<(u32, Vec<Neck>)> {
    parts
        .par_iter()
        // A bent part's flat shape is no plate's: its necks are not the joints' doing.
        .filter(|part| part.kind != crate::plan::PartKind::Bent)
        .filter_map(|part| {
            let before: &Polygon = &plates.plates.get(*plate_of.get(&part.id)?)?.polygon;
            let width = 2.0 * part.thickness;
            let known = neck_bounds(before, width).ok()?;
            let made = necks_except(&part.polygon, width, &known).ok()?;
            (!made.is_empty()).then_some((part.id, made))
        })
        .collect()
}

/// Warns, naming the part, of every neck its joints left ([`joint_necks`]).
pub fn warn_necks(parts: &[Part], plates: &Plates, plate_of: &BTreeMap<u32, usize>, cx: &mut StepContext<'_>) {
    for (part, necks) in joint_necks(parts, plates, plate_of) {
        let t = parts.iter().find(|p| p.id == part).map_or(0.0, |p| p.thickness);
        let list: Vec<String> = necks
            .iter()
            .map(|n| format!("{:.2} mm at ({:.1}, {:.1})", n.width, n.at.x, n.at.y))
            .collect();
        cx.warn_part(
            WarningKind::Joints,
            Some(part),
            format!(
                "part {part}: its joints leave {} neck(s) narrower than twice its thickness ({:.1} mm): {}; \
                 it may break there",
                necks.len(),
                2.0 * t,
                list.join(", ")
            ),
        );
    }
}
