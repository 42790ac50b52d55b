//! Every part carries its number: a layer too thin for its digits (a cup's ring, a shell's
//! wall) gets a small tab on its outline that holds them.
//!
//! Whether a number fits is asked of the `labels` step's own placement
//! ([`crate::labels::label_part`], the same function on the same part), so the tab is added
//! exactly when the step would otherwise skip the number. The tab is a rectangle sized for the
//! number at [`TAB_SIZE`] plus its clearance on every side and [`SLACK`], standing out of the
//! outline along one axis (+x, −x, +y, −y, the first that is clear) at the outline's extreme
//! point that way (or 45° from it), reaching [`ATTACH`] into the material so it is one piece with it. It keeps
//! [`GAP`] from the layer's other islands and never fills a shaft's slot. The tab sticks out of
//! the model by its length, a few millimetres at the layer's edge: that is the price of a
//! number on a part with no room for one.
//!
//! When there is no room for a tab either (a rib hemmed in by its neighbours), the part's
//! footprint and number are engraved on the part of an adjacent layer it overlaps most: the
//! layer's neighbour reference, which also shows where to glue it.
//!
//! Before a tab, a tag (`L9`, `S2 L1-4`) that takes the room of the number gives way: the part
//! number is what assembly needs, the tag a convenience. A shaft never gets a tab (it would
//! reach into the layers beside its slots).

use glam::DVec2;
use platener_geom::{GridError, Polygon, boolean};

use super::shafts::boxes_meet;
use crate::draw::font;
use crate::labels::{self, clearance};
use crate::plan::{CutSettings, LabelMode, Mark, MarkKind, Part};

/// Cap height of the number on a tab, mm: readable, and small enough for a neat tab.
pub const TAB_SIZE: f64 = 2.5;
/// Room beyond the box on every side, mm (the label's placement samples positions).
const SLACK: f64 = 0.5;
/// How far the tab reaches into the part's material, mm.
const ATTACH: f64 = 0.5;
/// Free room kept between a tab and the layer's other islands, mm (their cuts stay apart).
const GAP: f64 = 1.0;

/// Whether the `labels` step finds room for `part`'s number.
pub(crate) fn number_fits(part: &Part, cut: &CutSettings) -> bool {
    cut.labels == LabelMode::None || labels::label_part(part, LabelMode::Parts, cut.kerf()).0.boxes.len() == 1
}

/// Adds `marks` (another part's number, engraved here) to `part` if its own number still
/// fits, and says whether it did.
pub(crate) fn add_keeping_number(part: &mut Part, marks: Vec<Mark>, cut: &CutSettings) -> bool {
    let before = part.marks.len();
    part.marks.extend(marks);
    if number_fits(part, cut) {
        return true;
    }
    part.marks.truncate(before);
    false
}

/// `polygon` (an island of a layer, as cut) with a tab for the number `id`, clear of `others`
/// (the layer's other islands) and of `slots` (the shafts' sections through it); `None` when no
/// side is clear.
pub(crate) fn with_tab(
    polygon: &Polygon,
    slots: &[Polygon],
    others: &[&Polygon],
    id: u32,
    kerf: f64,
) -> Result<Option<Polygon>, GridError> {
    with_tab_where(polygon, slots, others, id, kerf, |_| Ok(true))
}

/// [`with_tab`], trying the next place while `accept` refuses the tab (the material it adds)
/// at this one: the interlocked method's tabs must also keep clear of crossing slices.
pub(crate) fn with_tab_where(
    polygon: &Polygon,
    slots: &[Polygon],
    others: &[&Polygon],
    id: u32,
    kerf: f64,
    accept: impl Fn(&[Polygon]) -> Result<bool, GridError>,
) -> Result<Option<Polygon>, GridError> {
    let DVec2 { x: length, y: width } = tab_size(id, kerf);
    for (d, tip) in anchors(polygon) {
        let across = d.perp() * (width / 2.0);
        let base = tip - d * ATTACH;
        let end = tip + d * length;
        let mut tab = Polygon::new(vec![base - across, end - across, end + across, base + across]);
        tab.normalize_orientation();
        if others.iter().any(|o| near(&tab, o)) {
            continue;
        }
        let tab = boolean::difference(&[tab], slots)?;
        if !accept(&tab)? {
            continue;
        }
        let mut with: Vec<Polygon> = boolean::union(std::slice::from_ref(polygon), &tab)?;
        if with.len() == 1 {
            let mut p = with.remove(0);
            p.normalize_orientation();
            if p.holes.len() == polygon.holes.len() {
                return Ok(Some(p));
            }
        }
    }
    Ok(None)
}

/// Where a tab may stand, best first: per axis direction (+x, −x, +y, −y), the outline's
/// extreme point that way, then its extreme points 45° either side (a corner, when the middle
/// of that side faces a neighbour).
fn anchors(polygon: &Polygon) -> Vec<(DVec2, DVec2)> {
    let extreme = |a: DVec2| {
        polygon
            .outer
            .iter()
            .copied()
            .max_by(|p, q| p.dot(a).total_cmp(&q.dot(a)))
    };
    let axes = [DVec2::X, -DVec2::X, DVec2::Y, -DVec2::Y];
    let turns = [
        DVec2::X,
        DVec2::new(1.0, 1.0).normalize(),
        DVec2::new(1.0, -1.0).normalize(),
    ];
    turns
        .iter()
        .flat_map(|t| axes.iter().map(move |d| (*d, d.rotate(*t))))
        .filter_map(|(d, a)| extreme(a).map(|tip| (d, tip)))
        .collect()
}

/// Marks for `on` (a part of an adjacent layer) showing where the part `id` with outline
/// `footprint` rests on it and its number beside that: the last resort when the part has room
/// neither for its number nor for a tab. `None` when they do not overlap or nothing fits.
pub(crate) fn reference_marks(
    footprint: &Polygon,
    id: u32,
    on: &Part,
    kerf: f64,
) -> Result<Option<Vec<Mark>>, GridError> {
    let overlap = boolean::intersection(std::slice::from_ref(footprint), std::slice::from_ref(&on.polygon))?;
    let Some(largest) = overlap.iter().max_by(|a, b| a.area().total_cmp(&b.area())) else {
        return Ok(None);
    };
    let closed = |r: &[DVec2]| r.iter().chain(r.first()).copied().collect::<Vec<_>>();
    let outline: Vec<Mark> = overlap
        .iter()
        .map(|p| Mark {
            kind: MarkKind::Score,
            path: closed(&p.outer),
            side: None,
        })
        .collect();
    let mut with = on.clone();
    with.marks.extend(outline.iter().cloned());
    let (lo, hi) = largest.bounds();
    let Some(text) = number_near(&with, id, (lo + hi) / 2.0, kerf) else {
        return Ok(None);
    };
    Ok(Some(outline.into_iter().chain(text).collect()))
}

/// The engraved strokes of the number `id` on `on`, as near `at` as there is room (clear of
/// its marks); `None` when there is none.
pub(crate) fn number_near(on: &Part, id: u32, at: DVec2, kerf: f64) -> Option<Vec<Mark>> {
    let b = labels::place_near(on, &id.to_string(), at, kerf)?;
    let strokes = font::place_text(&b.text, b.size, b.origin, b.direction);
    Some(
        strokes
            .into_iter()
            .map(|path| Mark {
                kind: MarkKind::Label,
                path,
                side: None,
            })
            .collect(),
    )
}

/// Whether `tab` comes within [`GAP`] of `other` (bounds first, then exactly).
fn near(tab: &Polygon, other: &Polygon) -> bool {
    let grown = grown_box(tab, GAP);
    if !boxes_meet(&grown, other) {
        return false;
    }
    boolean::intersection(&[grown], std::slice::from_ref(other)).map_or(true, |o| !o.is_empty())
}

/// The bounds of `p` grown by `by`, as a polygon.
fn grown_box(p: &Polygon, by: f64) -> Polygon {
    let (lo, hi) = p.bounds();
    let (lo, hi) = (lo - DVec2::splat(by), hi + DVec2::splat(by));
    let mut b = Polygon::new(vec![lo, DVec2::new(hi.x, lo.y), hi, DVec2::new(lo.x, hi.y)]);
    b.normalize_orientation();
    b
}

/// The size of the tab [`with_tab`] adds for the number `id`: its length out of the outline
/// (plus [`ATTACH`] into it) and its width, mm.
pub fn tab_size(id: u32, kerf: f64) -> DVec2 {
    let c = clearance(TAB_SIZE, kerf);
    DVec2::new(
        font::text_width(&id.to_string(), TAB_SIZE) + 2.0 * (c + SLACK),
        TAB_SIZE + 2.0 * (c + SLACK),
    )
}

#[cfg(test)]
mod tests {
    use platener_geom::polygon::total_area;
    use platener_geom::{Frame, Ring};

    use super::*;
    use crate::plan::PartKind;

    fn circle(r: f64, center: DVec2) -> Ring {
        (0..180)
            .map(|i| {
                let a = i as f64 * std::f64::consts::TAU / 180.0;
                center + DVec2::new(a.cos(), a.sin()) * r
            })
            .collect()
    }

    fn ring(center: DVec2) -> Polygon {
        let mut p = Polygon {
            outer: circle(30.0, center),
            holes: vec![circle(28.8, center)],
        };
        p.normalize_orientation();
        p
    }

    fn layer(id: u32, polygon: Polygon) -> Part {
        Part {
            id,
            kind: PartKind::Layer,
            thickness: 3.0,
            polygon,
            frame: Frame::on_plane(glam::DVec3::ZERO, glam::DVec3::Z),
            marks: Vec::new(),
            edge_labels: Vec::new(),
            merged: Vec::new(),
            segments: Vec::new(),
            bends: Vec::new(),
        }
    }

    #[test]
    fn a_ring_too_thin_for_its_number_gets_it_on_a_tab() {
        let cut = CutSettings::default();
        let thin = ring(DVec2::ZERO);
        assert!(
            !number_fits(&layer(17, thin.clone()), &cut),
            "1.2 mm is too thin for digits"
        );
        let tabbed = with_tab(&thin, &[], &[], 17, cut.kerf())
            .expect("grid")
            .expect("room on +x");
        let size = tab_size(17, cut.kerf());
        // The tab stands out of the ring's rightmost point by its length; it adds its area less
        // the bit of ring it overlaps (under ATTACH × width).
        let (lo, hi) = tabbed.bounds();
        assert!(
            (hi.x - (30.0 + size.x)).abs() < 1e-3 && (lo.x + 30.0).abs() < 1e-3,
            "{lo} {hi}"
        );
        let added = tabbed.area() - thin.area();
        assert!(
            added <= size.x * size.y + ATTACH * size.y && added >= size.x * size.y,
            "{added}"
        );
        assert_eq!(tabbed.holes.len(), 1);
        let part = layer(17, tabbed.clone());
        assert!(number_fits(&part, &cut));
        let (labels, _) = labels::label_part(&part, LabelMode::Parts, cut.kerf());
        let b = &labels.boxes[0];
        assert_eq!(b.text, "17");
        assert!(b.size >= TAB_SIZE, "{}", b.size);
        // On the tab: the box lies in the part, beyond the ring (the tab's base reaches into it).
        let quad = Polygon::new(b.corners(0.0).to_vec());
        let outside = boolean::difference(std::slice::from_ref(&quad), std::slice::from_ref(&tabbed)).expect("grid");
        assert!(total_area(&outside) < 1e-6);
        assert!(
            b.corners(0.0).iter().all(|p| p.x > 30.0 - ATTACH),
            "{:?}",
            b.corners(0.0)
        );
    }

    #[test]
    fn a_tab_keeps_clear_of_the_layers_other_islands_and_of_slots() {
        let cut = CutSettings::default();
        let thin = ring(DVec2::ZERO);
        let mut neighbour = Polygon::new(platener_geom::polygon::rect(31.0, -20.0, 60.0, 20.0));
        neighbour.normalize_orientation();
        let tabbed = with_tab(&thin, &[], &[&neighbour], 5, cut.kerf())
            .expect("grid")
            .expect("room on −x");
        let (lo, hi) = tabbed.bounds();
        assert!(
            (hi.x - 30.0).abs() < 1e-3 && lo.x < -30.0 - tab_size(5, cut.kerf()).x + 1e-3,
            "{lo} {hi}"
        );
        // A slot (a notch at the left end) is not filled by the tab.
        let mut slot = Polygon::new(platener_geom::polygon::rect(-31.0, -1.5, -28.0, 1.5));
        slot.normalize_orientation();
        let notched = boolean::difference(std::slice::from_ref(&thin), std::slice::from_ref(&slot)).expect("grid");
        let notched = notched
            .into_iter()
            .max_by(|a, b| a.area().total_cmp(&b.area()))
            .expect("piece");
        let t = with_tab(&notched, &[slot.clone()], &[&neighbour], 5, cut.kerf()).expect("grid");
        // Beside the notch (it reaches past it on one side only) or elsewhere: never closing it
        // into a hole.
        let t = t.expect("room for a tab");
        assert_eq!(
            t.holes.len(),
            notched.holes.len(),
            "the notch stays open to the outside"
        );
        assert!(t.area() > notched.area() + 10.0, "a tab was added");
        let filled = boolean::intersection(std::slice::from_ref(&t), &[slot]).expect("grid");
        assert!(total_area(&filled) < 1e-6, "the slot stays open");
    }
}
