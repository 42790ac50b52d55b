//! Raised details cut from a thinner sheet (issue 32). Lettering and relief standing on a
//! plate are engraved as their outline on the face they stand on; when the maker offers a
//! sheet as thin as they stand tall (a keychain's 1.25 mm letters on its 2.5 mm tag, `-t 2.5
//! -t 1.25`), each is also a part of that sheet, glued on its engraved outline: a `glued`
//! joint in plan.json and an entry of its `glued` list, so the glue is named wherever the
//! plan is shown, never hidden. Before, the plates step found such letters as plates of the
//! thin sheet that no joint held: loose parts, and the smaller ones left out as fragments.
//!
//! A detail qualifies when its measured height is an offered sheet thinner than its plate
//! (within [`HEIGHT_SLACK`]). A plate of that sheet that builds it and no joint holds is
//! glued as it is; a detail no plate builds becomes a part of its footprint when that passes
//! the smallest-part rule at the sheet; a detail another plate builds (a table's leg) is not
//! one. The others stay engraved only.

use std::collections::BTreeSet;

use platener_geom::{Frame, Polygon};

use crate::cuttable::Rule;
use crate::joints::Joints;
use crate::plan::{Glue, Joint, JointKind, Part};
use crate::plates::{Elevation, Feature, Plates, Side};

/// How far a detail's height may be from the sheet it is cut from: a tenth of the sheet,
/// at least 0.1 mm (the height is measured at the mesh's vertices, the sheet is nominal).
const HEIGHT_SLACK: f64 = 0.1;

/// A raised detail to glue on the plate it stands on.
pub(super) struct Detail {
    /// The plate it stands on.
    base: usize,
    /// The plate of the thin sheet that builds it, or `None` (then a part is made of its
    /// footprint).
    plate: Option<usize>,
    /// Its footprint, in the base plate's frame, and the face it stands on.
    footprint: (Polygon, Side),
    /// The sheet it is cut from, mm.
    sheet: f64,
    /// The area glued, mm².
    area: f64,
    /// A plate lying face to face on its base ([`laminated`]), not a raised detail.
    laminated: bool,
}

/// The raised details of `plates` to cut from the thinner sheets of `offered` (parts at
/// least `min_area` big) and glue; plates no joint of `joints` holds only.
pub(super) fn details(plates: &Plates, joints: Option<&Joints>, offered: &[f64], min_area: f64) -> Vec<Detail> {
    let slabs: Vec<_> = plates.plates.iter().map(crate::plates::Plate::slab).collect();
    let held: BTreeSet<usize> = joints
        .map(|j| {
            j.connections
                .iter()
                .flat_map(|c| c.plates.map(|p| p as usize))
                .collect()
        })
        .unwrap_or_default();
    let mut out = Vec::new();
    for f in &plates.features {
        let base = &plates.plates[f.plate as usize];
        let Some(sheet) = sheet_for(f, base.thickness, offered) else {
            continue;
        };
        let plate = match crate::plates::builder(f, &slabs) {
            Some(q) if (plates.plates[q].thickness - sheet).abs() < 1e-6 && !held.contains(&q) => Some(q),
            Some(_) => continue,
            None if Rule::for_sheet(sheet, 0.0, min_area).keeps(&f.region) => None,
            None => continue,
        };
        out.push(Detail {
            base: f.plate as usize,
            plate,
            footprint: (f.region.clone(), f.side),
            sheet,
            area: f.area,
            laminated: false,
        });
    }
    out.extend(laminated(plates, &held, &out, min_area));
    out
}

/// Plates lying face to face on another plate that no joint holds (a 2.5 mm tag found as two
/// 1.25 mm plates when only 1.25 mm sheet fits its letters): each is glued to the plate it
/// shares most area with, at least `min_area`.
fn laminated(plates: &Plates, held: &BTreeSet<usize>, found: &[Detail], min_area: f64) -> Vec<Detail> {
    // Plates already glued on or to as raised details.
    let glued = glued_plates(found);
    let mut pairs: BTreeSet<(usize, usize)> = BTreeSet::new();
    let mut out = Vec::new();
    for (q, plate) in plates.plates.iter().enumerate() {
        if held.contains(&q) || glued.contains(&q) {
            continue;
        }
        let best = (0..plates.plates.len())
            .filter(|&b| b != q)
            .filter_map(|b| Some((b, face_contact(&plates.plates[b], plate)?)))
            .filter(|&(_, area)| area >= min_area)
            .max_by(|x, y| x.1.total_cmp(&y.1).then(y.0.cmp(&x.0)));
        if let Some((b, area)) = best
            && pairs.insert((b.min(q), b.max(q)))
        {
            out.push(Detail {
                base: b,
                plate: Some(q),
                footprint: (Polygon::default(), Side::Up),
                sheet: plate.thickness,
                area,
                laminated: true,
            });
        }
    }
    out
}

/// The area over which plate `q` lies face to face on plate `b` (parallel, one's face in the
/// plane of the other's), if it does.
fn face_contact(b: &crate::plates::Plate, q: &crate::plates::Plate) -> Option<f64> {
    if b.frame.n.dot(q.frame.n).abs() < 0.999 {
        return None;
    }
    let (lo, hi) = (b.bounds(), q.bounds());
    if !(lo.0.cmple(hi.1 + 0.05).all() && hi.0.cmple(lo.1 + 0.05).all()) {
        return None;
    }
    let depth = |z: f64| b.frame.to_local(q.frame.to_model(q.polygon.outer[0].extend(z))).z;
    let touching = [0.0, q.thickness]
        .iter()
        .any(|&z| [0.0, b.thickness].iter().any(|&face| (depth(z) - face).abs() < 0.05));
    if !touching {
        return None;
    }
    let onto = |ring: &Vec<glam::DVec2>| -> Vec<glam::DVec2> {
        ring.iter()
            .map(|p| b.frame.to_local(q.frame.to_model(p.extend(0.0))).truncate())
            .collect()
    };
    let mut shadow = Polygon {
        outer: onto(&q.polygon.outer),
        holes: q.polygon.holes.iter().map(onto).collect(),
    };
    shadow.normalize_orientation();
    let shared =
        platener_geom::boolean::intersection(std::slice::from_ref(&b.polygon), std::slice::from_ref(&shadow)).ok()?;
    Some(platener_geom::polygon::total_area(&shared))
}

/// The plates that `details` glues on or to (held, though no joint holds them).
pub(super) fn glued_plates(details: &[Detail]) -> BTreeSet<usize> {
    details
        .iter()
        .flat_map(|d| d.plate.into_iter().chain([d.base]))
        .collect()
}

/// Glues each of `details` on its base's part (`ids`): a part of its footprint numbered after
/// `parts` where no plate builds it, a `glued` joint numbered after `connections`, and a
/// `glued` entry; says what it did, per base part.
pub(super) fn glue(
    details: &[Detail],
    plates: &Plates,
    ids: &[Option<u32>],
    (parts, connections, glued): (&mut Vec<Part>, &mut Vec<Joint>, &mut Vec<Glue>),
) -> Vec<String> {
    let mut next_id = parts.iter().map(|p| p.id).max().unwrap_or(0);
    let mut label = connections.iter().map(|c| c.label).max().unwrap_or(0);
    // Per base part and kind (raised detail, laminated plate): the sheet and the parts glued.
    let mut made: std::collections::BTreeMap<(u32, bool), (f64, Vec<u32>)> = std::collections::BTreeMap::new();
    for d in details {
        let Some(base) = ids[d.base] else {
            continue;
        };
        let id = match d.plate {
            Some(q) => match ids[q] {
                Some(id) => id,
                None => continue,
            },
            None => {
                next_id += 1;
                let p = &plates.plates[d.base];
                let (region, side) = &d.footprint;
                let frame = standing_frame(&p.frame, *side, p.thickness, d.sheet);
                parts.push(Part::plate(next_id, d.sheet, region.clone(), frame));
                next_id
            }
        };
        label += 1;
        connections.push(Joint {
            parts: [base, id],
            kind: JointKind::Glued,
            angle_deg: 0.0,
            label,
        });
        glued.push(Glue {
            parts: [base, id],
            area: d.area,
        });
        made.entry((base, d.laminated))
            .or_insert((d.sheet, Vec::new()))
            .1
            .push(id);
    }
    made.into_iter()
        .map(|((base, laminated), (sheet, ids))| {
            let list: Vec<String> = ids.iter().map(u32::to_string).collect();
            if laminated {
                format!(
                    "part {base}: part(s) {} lie face to face on it and no joint holds them: glue them on",
                    list.join(", ")
                )
            } else {
                format!(
                    "part {base}: {} raised detail(s) are cut from the {sheet} mm sheet (parts {}); glue each on \
                     its outline engraved on part {base}",
                    ids.len(),
                    list.join(", ")
                )
            }
        })
        .collect()
}

/// The offered sheet thinner than the plate that a raised feature stands as tall as.
fn sheet_for(f: &Feature, plate: f64, offered: &[f64]) -> Option<f64> {
    let height = f.height.filter(|_| f.relief == Elevation::Raised)?;
    offered
        .iter()
        .copied()
        .filter(|&t| t < plate - 1e-9 && (height - t).abs() <= (HEIGHT_SLACK * t).max(0.1))
        .min_by(|a, b| (a - height).abs().total_cmp(&(b - height).abs()))
}

/// Where a detail's part lies: on the face it stands on, outside the plate (the face at
/// local z = 0 for [`Side::Up`], at the plate's thickness for [`Side::Down`]), `sheet` thick.
fn standing_frame(frame: &Frame, side: Side, plate: f64, sheet: f64) -> Frame {
    match side {
        Side::Up => frame.shifted(-sheet),
        Side::Down => frame.shifted(plate),
    }
}
