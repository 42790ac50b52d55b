//! Step `labels`: part and connection numbers engraved as single-stroke text.
//!
//! Assembly aid (the thesis' AssemblyInstructions): every part carries its number, large, at
//! the point deepest inside it; every jointed edge carries `#` and its connection number, small,
//! next to the edge on the inside of the part, on both parts of the joint, so the user finds
//! which edge meets which. A label is shrunk (down to [`MIN_SIZE`]) or moved until its box,
//! grown by a clearance, lies inside the part minus its holes and clear of marks (cut slits
//! too), other labels and a bent part's bend zones (the strip that curves); when nothing fits
//! it is skipped with a warning. Labels are engraved (blue) with the built-in stroke [`font`],
//! so no font is needed on the user's machine.

mod place;

use glam::DVec2;
use rayon::prelude::*;
use serde::Serialize;

pub use place::{MIN_SIZE, TextBox, clearance};
use place::{Room, up_of};

use crate::context::{StepContext, Warning, WarningKind};
use crate::draw::font;
use platener_geom::Polygon;

use crate::plan::{Bend, EdgeLabel, LabelMode, Mark, MarkKind, Part, PlanInput};

/// Sizes tried for part numbers, mm, largest first.
const PART_SIZES: [f64; 8] = [8.0, 6.0, 5.0, 4.0, 3.0, 2.5, 2.0, MIN_SIZE];
/// Sizes tried for connection numbers, mm, largest first.
const EDGE_SIZES: [f64; 5] = [4.0, 3.0, 2.5, 2.0, MIN_SIZE];
/// Positions along an edge tried for its label, as fractions of the edge, best first.
const ALONG: [f64; 5] = [0.5, 0.35, 0.65, 0.2, 0.8];
/// Step (mm) by which an edge label moves away from its edge when it does not fit.
const INWARD_STEP: f64 = 0.5;

/// One part's labels.
#[derive(Debug, Clone, Serialize)]
pub struct PartLabels {
    /// The part's id.
    pub id: u32,
    /// The placed texts (part number first).
    #[serde(skip)]
    pub boxes: Vec<TextBox>,
    /// Their strokes as `label` marks, in the part's frame.
    pub marks: Vec<Mark>,
}

/// The snapshot of step `labels`: per part (input order), the label marks.
#[derive(Debug, Clone, Serialize)]
pub struct Labels {
    /// What was asked for.
    pub mode: LabelMode,
    /// Per part, in the input's order.
    pub parts: Vec<PartLabels>,
}

/// The text engraved next to a jointed edge.
pub fn connection_text(connection: u32) -> String {
    format!("#{connection}")
}

/// Labels all `parts`, with a warning for each label that found no room.
pub fn label_parts(parts: &[Part], mode: LabelMode, kerf: f64) -> (Labels, Vec<Warning>) {
    let done: Vec<(PartLabels, Vec<Warning>)> = parts.par_iter().map(|p| label_part(p, mode, kerf)).collect();
    let mut labels = Labels {
        mode,
        parts: Vec::with_capacity(parts.len()),
    };
    let mut warnings = Vec::new();
    // Many small parts (dovetail keys) without room for a number make one warning, not one each.
    let mut unnumbered = Vec::new();
    for (part, found) in done {
        for w in found {
            match w.part {
                Some(id) if w.message.ends_with(NO_ROOM_FOR_NUMBER) => unnumbered.push(id),
                _ => warnings.push(w),
            }
        }
        labels.parts.push(part);
    }
    match unnumbered[..] {
        [] => {}
        [id] => warnings.push(Warning {
            step: "labels",
            kind: WarningKind::CuttingPlan,
            part: Some(id),
            message: format!("part {id}{NO_ROOM_FOR_NUMBER}"),
        }),
        _ => warnings.push(Warning {
            step: "labels",
            kind: WarningKind::CuttingPlan,
            part: None,
            message: format!(
                "{} parts ({}) have no room for their numbers; they are not engraved",
                unnumbered.len(),
                id_ranges(&unnumbered)
            ),
        }),
    }
    (labels, warnings)
}

const NO_ROOM_FOR_NUMBER: &str = " has no room for its number; it is not engraved";

/// Ids (ascending) as compact ranges: `3, 5–9, 12`.
pub fn id_ranges(ids: &[u32]) -> String {
    let mut out: Vec<String> = Vec::new();
    let mut i = 0;
    while i < ids.len() {
        let mut j = i;
        while j + 1 < ids.len() && ids[j + 1] == ids[j] + 1 {
            j += 1;
        }
        out.push(if j > i {
            format!("{}–{}", ids[i], ids[j])
        } else {
            ids[i].to_string()
        });
        i = j + 1;
    }
    out.join(", ")
}

/// The labels of one part cut with `kerf` mm.
pub fn label_part(part: &Part, mode: LabelMode, kerf: f64) -> (PartLabels, Vec<Warning>) {
    let polygon = normalized(part);
    let mut room = room_of(part, &polygon, kerf);
    let mut boxes = Vec::new();
    let mut warnings = Vec::new();
    let mut warn = |message: String| {
        warnings.push(Warning {
            step: "labels",
            kind: WarningKind::CuttingPlan,
            part: Some(part.id),
            message,
        })
    };
    if mode != LabelMode::None {
        match place_number(&room, &polygon, part.id) {
            Some(b) => {
                room.take(&b);
                boxes.push(b);
            }
            None => warn(format!("part {}{NO_ROOM_FOR_NUMBER}", part.id)),
        }
    }
    if mode == LabelMode::Edges {
        for edge in &part.edge_labels {
            match place_edge(&room, edge, part.thickness) {
                Some(b) => {
                    room.take(&b);
                    boxes.push(b);
                }
                None => warn(format!(
                    "part {}: no room for connection {} next to its edge; it is not engraved",
                    part.id,
                    connection_text(edge.connection)
                )),
            }
        }
    }
    let marks = boxes
        .iter()
        .flat_map(|b| font::place_text(&b.text, b.size, b.origin, b.direction))
        .map(|path| Mark {
            kind: MarkKind::Label,
            path,
            side: None,
        })
        .collect();
    (
        PartLabels {
            id: part.id,
            boxes,
            marks,
        },
        warnings,
    )
}

/// `part`'s shape, outer ring counter-clockwise and holes clockwise, as [`Room`] wants it.
fn normalized(part: &Part) -> Polygon {
    let mut polygon = part.polygon.clone();
    polygon.normalize_orientation();
    polygon
}

/// Where labels may go on `part` (its `polygon`, normalised): clear of all its marks (cut
/// slits included) and of its bend zones.
fn room_of<'a>(part: &Part, polygon: &'a Polygon, kerf: f64) -> Room<'a> {
    let mark_paths: Vec<Vec<DVec2>> = part.marks.iter().map(|m| m.path.clone()).collect();
    let mut room = Room::new(polygon, &mark_paths, kerf);
    let (lo, hi) = polygon.bounds();
    for bend in &part.bends {
        room.block(bend_zone(bend, lo.distance(hi)));
    }
    room
}

/// The bend zone of `bend` (the strip of its width centred on its line) as a quadrilateral,
/// its line extended by `reach` at both ends so the strip crosses the whole part.
pub fn bend_zone(bend: &Bend, reach: f64) -> [DVec2; 4] {
    let [a, b] = bend.line;
    let along = (b - a).try_normalize().unwrap_or(DVec2::X);
    let across = along.perp() * (bend.width / 2.0);
    let (a, b) = (a - along * reach, b + along * reach);
    [a - across, b - across, b + across, a + across]
}

/// A baseline direction that reads left to right on screen (or upwards when vertical).
fn readable(d: DVec2) -> DVec2 {
    if d.x > 1e-9 || (d.x.abs() <= 1e-9 && d.y < 0.0) {
        d
    } else {
        -d
    }
}

/// The part number at the deepest points, horizontal, upright or along the longest edge.
fn place_number(room: &Room<'_>, polygon: &Polygon, id: u32) -> Option<TextBox> {
    let text = id.to_string();
    let longest = {
        let r = &polygon.outer;
        (0..r.len())
            .map(|i| r[(i + 1) % r.len()] - r[i])
            .max_by(|a, b| a.length_squared().total_cmp(&b.length_squared()))
            .and_then(|d| d.try_normalize())
            .map_or(DVec2::X, readable)
    };
    let directions = [DVec2::X, DVec2::new(0.0, -1.0), longest];
    let fits = |size: f64, center: DVec2| {
        directions
            .iter()
            .map(|d| TextBox::centered(&text, size, center, *d))
            .find(|b| room.fits(b))
    };
    let deep = room.deep_points(8);
    let depth = deep.first().map_or(0.0, |d| d.1);
    PART_SIZES.into_iter().find_map(|size| {
        let at_deep = || deep.iter().find_map(|(center, _)| fits(size, *center));
        // The coarse grid can step over narrow room (a tab on a thin ring): then look where a
        // label of this size could be centred, exactly.
        let inner = || {
            room.inner_points(size / 2.0 + room.clearance(size))
                .into_iter()
                .find_map(|center| fits(size, center))
        };
        (size <= 2.0 * depth).then(at_deep).flatten().or_else(inner)
    })
}

/// `text` placed on `part` as near `target` as fits (3 mm down to [`MIN_SIZE`]), clear of the
/// part's marks: a reference to another part engraved where it belongs (a stacked layer's
/// number on the layer it rests on).
pub fn place_near(part: &Part, text: &str, target: DVec2, kerf: f64) -> Option<TextBox> {
    let polygon = normalized(part);
    let room = room_of(part, &polygon, kerf);
    [3.0, 2.5, 2.0, MIN_SIZE].into_iter().find_map(|size| {
        let mut centers = room.inner_points(size / 2.0 + room.clearance(size));
        centers.sort_by(|a, b| {
            a.distance_squared(target)
                .total_cmp(&b.distance_squared(target))
                .then(a.x.total_cmp(&b.x))
                .then(a.y.total_cmp(&b.y))
        });
        centers.into_iter().take(64).find_map(|c| {
            [DVec2::X, DVec2::new(0.0, -1.0)]
                .into_iter()
                .map(|d| TextBox::centered(text, size, c, d))
                .find(|b| room.fits(b))
        })
    })
}

/// A connection number next to `edge`, inside the part, as large and as close as fits.
fn place_edge(room: &Room<'_>, edge: &EdgeLabel, thickness: f64) -> Option<TextBox> {
    let [a, b] = edge.segment;
    let len = a.distance(b);
    let along = (b - a).try_normalize()?;
    let dir = readable(along);
    // Inside is the side where points beyond any finger (two thicknesses in) lie in the part.
    let normal = DVec2::new(-along.y, along.x);
    let probe = 2.0 * thickness + 1.0;
    let inside = |n: DVec2| {
        ALONG
            .iter()
            .filter(|t| room.contains(a + (b - a) * **t + n * probe))
            .count()
    };
    let inward = if inside(-normal) > inside(normal) {
        -normal
    } else {
        normal
    };
    let text = connection_text(edge.connection);
    let max_size = 0.8 * len / font::text_width(&text, 1.0);
    let max_inward = 2.0 * thickness + 4.0;
    for size in EDGE_SIZES.into_iter().filter(|s| *s <= max_size) {
        // The box's extent across the edge: its height when reading along the edge.
        let half_across =
            size / 2.0 * up_of(dir).dot(inward).abs() + font::text_width(&text, size) / 2.0 * dir.dot(inward).abs();
        for t in ALONG {
            let mut gap = room.clearance(size);
            while gap <= max_inward {
                let center = a + (b - a) * t + inward * (gap + half_across);
                let candidate = TextBox::centered(&text, size, center, dir);
                if room.fits(&candidate) {
                    return Some(candidate);
                }
                gap += INWARD_STEP;
            }
        }
    }
    None
}

/// Step `labels`: part and connection numbers of every part, as engraved marks.
pub fn run(input: &PlanInput, cx: &mut StepContext<'_>) -> Labels {
    let (labels, warnings) = label_parts(&input.parts, input.settings.labels, input.settings.kerf());
    cx.extend(warnings);
    labels
}

#[cfg(test)]
mod tests;
