//! Cutting joint regions into fingers, tabs and slots, and applying them to the plates.

use glam::DVec2;
use platener_geom::boolean::{difference, union_all};
use platener_geom::offset::offset;
use platener_geom::{GridError, Polygon};

use super::connect::{Region, band};
use super::{Connection, ConnectionKind, JointSettings, JointStyle, Joints};
use crate::plates::Plate;

/// Number of segments for a joint `len` long: the odd count nearest to `len / width`, never
/// narrower than `min_feature`, and at least three (a tab between two fingers) when there is room.
pub(super) fn segment_count(len: f64, width: f64, min_feature: f64) -> usize {
    let mut n = ((len / width).round() as usize).max(1);
    if n.is_multiple_of(2) {
        n = if len / (n + 1) as f64 >= min_feature {
            n + 1
        } else {
            n - 1
        };
    }
    while n > 1 && len / (n as f64) < min_feature {
        n -= 2;
    }
    if n == 1 && len / 3.0 >= min_feature {
        n = 3;
    }
    n
}

/// The jointed edge of `plate` along `region`: the region's boundary line nearest the plate's
/// own middle, over the region's length.
fn edge_of(plate: &Plate, region: &Polygon, axis: glam::DVec3) -> [DVec2; 2] {
    let f = &plate.frame;
    let along = DVec2::new(axis.dot(f.u), axis.dot(f.v)).normalize_or_zero();
    let across = along.perp();
    let (mut a0, mut a1, mut q0, mut q1) = (f64::INFINITY, f64::NEG_INFINITY, f64::INFINITY, f64::NEG_INFINITY);
    for p in &region.outer {
        a0 = a0.min(along.dot(*p));
        a1 = a1.max(along.dot(*p));
        q0 = q0.min(across.dot(*p));
        q1 = q1.max(across.dot(*p));
    }
    let (lo, hi) = plate.polygon.bounds();
    let mid = across.dot((lo + hi) / 2.0);
    let q = if (mid - q0).abs() < (mid - q1).abs() { q0 } else { q1 };
    [along * a0 + across * q, along * a1 + across * q]
}

/// The barb of a JimJoint finger on `plate`: the finger between `s0` and `s1` along the axis,
/// widened by `barb` on both sides towards its tip (the side of the region away from the
/// plate), clipped to the joint region.
fn barb(
    plate: &Plate,
    region: &Polygon,
    axis: glam::DVec3,
    s0: f64,
    s1: f64,
    barb: f64,
) -> Result<Vec<Polygon>, GridError> {
    let f = &plate.frame;
    let along = DVec2::new(axis.dot(f.u), axis.dot(f.v)).normalize_or_zero();
    let across = along.perp();
    let c = axis.dot(f.origin);
    let [base0, _] = edge_of(plate, region, axis);
    let q_base = across.dot(base0);
    let (q0, q1) = region
        .outer
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), p| {
            (lo.min(across.dot(*p)), hi.max(across.dot(*p)))
        });
    let q_tip = if (q_base - q0).abs() < (q_base - q1).abs() {
        q1
    } else {
        q0
    };
    let at = |a: f64, q: f64| along * (a - c) + across * q;
    let mut wedge = Polygon::new(vec![
        at(s0, q_base),
        at(s1, q_base),
        at(s1 + barb, q_tip),
        at(s0 - barb, q_tip),
    ]);
    wedge.normalize_orientation();
    platener_geom::boolean::intersection(std::slice::from_ref(region), &[wedge])
}

/// Gaps narrower than this (mm) between a plate and its joint regions are grid noise.
const HAIRLINE: f64 = 0.01;

/// The union of a plate and its joint regions. A region computed through another plate's
/// frame can miss its plate by a grid step; a closing (grow, then shrink, with sharp miter
/// corners) fills such hairlines without moving any real edge.
fn joined(pieces: &[Polygon]) -> Result<Vec<Polygon>, GridError> {
    let union = union_all(pieces)?;
    if union.len() <= 1 {
        return Ok(union);
    }
    offset(&offset(&union, HAIRLINE)?, -HAIRLINE)
}

pub(super) fn apply(
    plates: &[Plate],
    regions: Vec<Region>,
    settings: &JointSettings,
    style: JointStyle,
) -> Result<Joints, GridError> {
    // Every plate grows into its joint regions first…
    let mut grown: Vec<Vec<Polygon>> = plates.iter().map(|p| vec![p.polygon.clone()]).collect();
    for r in &regions {
        grown[r.a].extend(r.reach_a.iter().cloned());
        grown[r.b].extend(r.reach_b.iter().cloned());
    }
    let mut outlines: Vec<Vec<Polygon>> = grown.iter().map(|g| joined(g)).collect::<Result<_, _>>()?;
    // …then gives up the segments its partner owns.
    let mut cuts: Vec<Vec<Polygon>> = vec![Vec::new(); plates.len()];
    let mut barbs: Vec<Vec<Polygon>> = vec![Vec::new(); plates.len()];
    let mut connections = Vec::with_capacity(regions.len());
    let mut edges: Vec<Vec<(u32, [DVec2; 2])>> = vec![Vec::new(); plates.len()];
    for (k, r) in regions.iter().enumerate() {
        let (pa, pb) = (&plates[r.a], &plates[r.b]);
        let t = pa.thickness.max(pb.thickness);
        let len = r.range.1 - r.range.0;
        let segments = match r.kind {
            ConnectionKind::Cross => 2,
            _ => segment_count(len, settings.finger_factor * t, (t / 2.0).max(1.0)),
        };
        for s in 0..segments {
            let owner = match r.kind {
                ConnectionKind::Corner => [r.a, r.b][s % 2],
                ConnectionKind::Tee => {
                    let through = r.through.unwrap_or(r.a);
                    let ending = if through == r.a { r.b } else { r.a };
                    [through, ending][s % 2]
                }
                ConnectionKind::Cross => [r.a, r.b][s],
            };
            let step = len / segments as f64;
            let (s0, s1) = (r.range.0 + step * s as f64, r.range.0 + step * (s + 1) as f64);
            // The first and last segments reach past the range (the region's ends).
            let s0 = if s == 0 { s0 - 1e3 } else { s0 };
            let s1 = if s + 1 == segments { s1 + 1e3 } else { s1 };
            if owner == r.a {
                cuts[r.b].extend(band(pb, &r.in_b, r.axis, s0, s1)?);
            } else {
                cuts[r.a].extend(band(pa, &r.in_a, r.axis, s0, s1)?);
            }
            // JimJoint: the owner's finger widens towards its tip, into its partner's fingers.
            if style == JointStyle::Jim && r.kind != ConnectionKind::Cross {
                let (p, region) = if owner == r.a { (pa, &r.in_a) } else { (pb, &r.in_b) };
                let (a0, a1) = (r.range.0 + step * s as f64, r.range.0 + step * (s + 1) as f64);
                let b = (0.1 * step).min(0.25 * pa.thickness.min(pb.thickness));
                barbs[owner].extend(barb(p, region, r.axis, a0, a1, b)?);
            }
        }
        let label = k as u32 + 1;
        edges[r.a].push((label, edge_of(pa, &r.in_a, r.axis)));
        edges[r.b].push((label, edge_of(pb, &r.in_b, r.axis)));
        connections.push(Connection {
            plates: [r.a as u32, r.b as u32],
            kind: r.kind,
            style: if r.kind == ConnectionKind::Cross {
                JointStyle::Finger
            } else {
                style
            },
            angle_deg: r.angle_deg,
            line: [
                r.center + r.axis * (r.range.0 - r.axis.dot(r.center)),
                r.center + r.axis * (r.range.1 - r.axis.dot(r.center)),
            ],
            segments,
            label,
        });
    }
    let mut warnings = Vec::new();
    let mut finals = Vec::with_capacity(plates.len());
    for (i, outline) in outlines.iter_mut().enumerate() {
        let mut pieces = difference(outline, &cuts[i])?;
        if !barbs[i].is_empty() {
            pieces.extend(barbs[i].iter().cloned());
            pieces = union_all(&pieces)?;
        }
        pieces.sort_by(|a, b| b.area().total_cmp(&a.area()));
        if pieces.len() > 1 {
            warnings.push(format!(
                "plate {} would fall into {} pieces at its joints; the largest is kept",
                i + 1,
                pieces.len()
            ));
        }
        finals.push(pieces.into_iter().next().unwrap_or_else(|| plates[i].polygon.clone()));
    }
    Ok(Joints {
        outlines: finals,
        connections,
        edges,
        warnings,
    })
}
