//! A bent part in the model: the rigid pieces it is made of.
//!
//! A bent part is cut flat and then bent along its bend zones. Whoever rebuilds it in 3D
//! (the assembly analysis, `verify`, the score, `assembly.glb`) needs it as rigid pieces:
//! each flat segment placed by its own frame, and each bend zone cut into slices across its
//! width, each slice placed by the frame of the arc at its middle. Both the library's
//! [`Part`] and plan.json's [`PlanPart`] go through the one core [`pieces_of`], so the
//! rebuilt shapes cannot differ between `convert` and `verify`.
//!
//! The convention (docs/architecture.md, issue 19): the zone is the strip of `width` centred
//! on the bend line; its neutral (mid-thickness) surface bends as a circular arc of radius
//! `width / turn`, tangent to both segments' mid-planes, so the flat width equals the arc
//! length (bend allowance with K = 0.5).

use glam::{DQuat, DVec2, DVec3};
use platener_geom::slab::Slab;
use platener_geom::{Frame, GridError, Polygon, boolean};

use super::format::PlanPart;
use super::part::{Bend, Part, PartKind};

/// The most a slice of a bend zone turns, radians (5°).
const MAX_SLICE_TURN: f64 = 5.0 * std::f64::consts::PI / 180.0;
/// The most a slice's flat middle strays from the true arc (its sagitta), mm: slices of
/// large radii are made narrower so their ends meet the arc within this.
const MAX_SAGITTA: f64 = 0.005;
/// The most slices one bend zone is cut into.
const MAX_SLICES: usize = 720;
/// How far (mm) the end of a bend zone may lie from where its second segment says it is.
pub const MAX_MISMATCH: f64 = 0.05;

/// Why a bent part cannot be rebuilt in 3D from its segments and bends.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum BentError {
    /// A bend names a segment that does not exist, or the same segment twice.
    #[error("part {part}: bend {bend} joins segments {segments:?}, but the part has {count} segments")]
    Segments {
        /// The part's id.
        part: u32,
        /// The bend's index.
        bend: usize,
        /// Its segment indices.
        segments: [usize; 2],
        /// How many segments the part has.
        count: usize,
    },
    /// A bend whose angle, width or line cannot be bent.
    #[error("part {part}: bend {bend} {message}")]
    Bend {
        /// The part's id.
        part: u32,
        /// The bend's index.
        bend: usize,
        /// What is wrong with it.
        message: String,
    },
    /// The end of a bend zone does not meet its second segment where that segment's frame puts
    /// it: the segments and the bend disagree.
    #[error("part {part}: bend {bend} ends {distance:.3} mm from where segment {segment} lies")]
    Mismatch {
        /// The part's id.
        part: u32,
        /// The bend's index.
        bend: usize,
        /// The segment it should meet.
        segment: usize,
        /// The largest distance found, mm.
        distance: f64,
    },
    /// The zone's outline could not be clipped (coordinates off the kernel's grid).
    #[error("part {part}: bend zone cannot be clipped: {error}")]
    Grid {
        /// The part's id.
        part: u32,
        /// The kernel's error.
        error: GridError,
    },
}

/// The frame of plan.json's `[R | t]` rows (R's columns u, v, n).
pub fn frame_from_matrix(m: &[[f64; 4]; 3]) -> Frame {
    let column = |j: usize| DVec3::new(m[0][j], m[1][j], m[2][j]);
    Frame {
        u: column(0),
        v: column(1),
        n: column(2),
        origin: column(3),
    }
}

/// What [`pieces_of`] needs of a bend, whichever form the part came in.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BendGeometry {
    /// The middle of the zone, in the flat frame.
    pub line: [DVec2; 2],
    /// The angle the sides enclose once bent, degrees (180 = flat).
    pub angle_deg: f64,
    /// The zone's width on the flat part, mm.
    pub width: f64,
    /// The segments it joins (indices).
    pub segments: [usize; 2],
}

impl From<&Bend> for BendGeometry {
    fn from(b: &Bend) -> Self {
        Self {
            line: b.line,
            angle_deg: b.angle_deg,
            width: b.width,
            segments: b.segments,
        }
    }
}

impl Part {
    /// The rigid pieces of this part in the model: for a bent part its segments and its bend
    /// zones' slices, otherwise the part itself.
    pub fn pieces(&self) -> Result<Vec<Slab>, BentError> {
        if self.kind != PartKind::Bent || self.segments.is_empty() {
            return Ok(vec![slab(&self.polygon, self.frame, self.thickness)]);
        }
        let segments: Vec<(Polygon, Frame)> = self.segments.iter().map(|s| (s.polygon.clone(), s.frame)).collect();
        let bends: Vec<BendGeometry> = self.bends.iter().map(BendGeometry::from).collect();
        pieces_of(self.id, &self.polygon, self.thickness, &segments, &bends)
    }
}

impl PlanPart {
    /// The rigid pieces of this part in the model, as [`Part::pieces`], read from plan.json.
    pub fn pieces(&self) -> Result<Vec<Slab>, BentError> {
        let polygon = Polygon {
            outer: self.outline.clone(),
            holes: self.holes.clone(),
        };
        if self.kind != PartKind::Bent || self.segments.is_empty() {
            return Ok(vec![slab(&polygon, frame_from_matrix(&self.transform), self.thickness)]);
        }
        let segments: Vec<(Polygon, Frame)> = self
            .segments
            .iter()
            .map(|s| {
                let p = Polygon {
                    outer: s.outline.clone(),
                    holes: s.holes.clone(),
                };
                (p, frame_from_matrix(&s.transform))
            })
            .collect();
        let bends: Vec<BendGeometry> = self
            .bends
            .iter()
            .map(|b| BendGeometry {
                line: b.line,
                angle_deg: b.angle,
                width: b.width,
                segments: b.segments,
            })
            .collect();
        pieces_of(self.id, &polygon, self.thickness, &segments, &bends)
    }
}

fn slab(polygon: &Polygon, frame: Frame, thickness: f64) -> Slab {
    Slab {
        frame,
        polygon: polygon.clone(),
        thickness,
    }
}

/// The pieces of bent part `part` (flat shape `polygon`): every segment as it is, then every
/// bend zone's slices in bend order, each the flat shape clipped to the slice's strip.
pub fn pieces_of(
    part: u32,
    polygon: &Polygon,
    thickness: f64,
    segments: &[(Polygon, Frame)],
    bends: &[BendGeometry],
) -> Result<Vec<Slab>, BentError> {
    let mut out: Vec<Slab> = segments.iter().map(|(p, f)| slab(p, *f, thickness)).collect();
    for (index, bend) in bends.iter().enumerate() {
        let zone = Zone::new(part, index, bend, segments, thickness)?;
        for (u0, u1) in zone.slices() {
            let strip = zone.strip(u0, u1);
            let clipped = boolean::intersection(&[strip], std::slice::from_ref(polygon))
                .map_err(|error| BentError::Grid { part, error })?;
            let frame = zone.frame_at((u0 + u1) / 2.0);
            out.extend(clipped.iter().map(|p| slab(p, frame, thickness)));
        }
    }
    Ok(out)
}

/// One bend zone, set up in the model: u runs across the zone from 0 (segment i's edge) to
/// `width` (segment j's edge).
#[derive(Debug, Clone, Copy)]
pub struct Zone {
    /// The bend line's first point, flat frame.
    origin: DVec2,
    /// Unit vector along the line, flat frame.
    along: DVec2,
    /// The line's length: the zone spans it, no further (in a net of many plates the line's
    /// extension crosses other plates).
    length: f64,
    /// Unit vector across the line towards segment j, flat frame.
    across: DVec2,
    width: f64,
    /// The total turn, radians (0 for a flat "bend").
    turn: f64,
    /// Segment i's frame.
    start: Frame,
    /// The bend axis: a point and the rotation axis whose positive sense turns the part.
    axis_point: DVec3,
    axis: DVec3,
}

impl Zone {
    /// The zone of `bend` (index `index` of part `part`), checked against both segments.
    pub fn new(
        part: u32,
        index: usize,
        bend: &BendGeometry,
        segments: &[(Polygon, Frame)],
        thickness: f64,
    ) -> Result<Self, BentError> {
        let [i, j] = bend.segments;
        if i == j || i >= segments.len() || j >= segments.len() {
            return Err(BentError::Segments {
                part,
                bend: index,
                segments: bend.segments,
                count: segments.len(),
            });
        }
        let bad = |message: &str| BentError::Bend {
            part,
            bend: index,
            message: message.into(),
        };
        let [p0, p1] = bend.line;
        let along = (p1 - p0)
            .try_normalize()
            .ok_or_else(|| bad("has a line of no length"))?;
        if !(bend.width.is_finite() && bend.width > 0.0) {
            return Err(bad("has no positive width"));
        }
        if !(0.0..=180.0).contains(&bend.angle_deg) {
            return Err(bad("has an angle outside 0–180°"));
        }
        // Across the line, towards segment j: the side j's vertices lie on on average.
        let side = |s: &Polygon| {
            let n = s.outer.len().max(1) as f64;
            s.outer.iter().map(|p| along.perp().dot(*p - p0)).sum::<f64>() / n
        };
        let (si, sj) = (side(&segments[i].0), side(&segments[j].0));
        // A segment that joints left without material (a small facet between bends) still
        // places its neighbours' zones by its frame: the other segment gives the side.
        let sj = match (si == 0.0, sj == 0.0) {
            (true, true) => return Err(bad("joins two segments without material")),
            (false, true) => -si,
            _ => sj,
        };
        if si * sj > 0.0 {
            return Err(bad("does not lie between the segments it joins"));
        }
        let flat = Self {
            origin: p0,
            along,
            length: (p1 - p0).length(),
            across: along.perp() * sj.signum(),
            width: bend.width,
            turn: (180.0 - bend.angle_deg).to_radians(),
            start: segments[i].1,
            axis_point: DVec3::ZERO,
            axis: DVec3::ZERO,
        };
        let mut best: Option<(f64, Zone)> = None;
        // The part turns towards one side of segment i: the one that puts the zone's end
        // where segment j's frame says it is.
        for sense in [1.0, -1.0] {
            let zone = flat.towards(thickness, sense);
            let miss = zone.mismatch(&segments[j].1, thickness);
            if best.as_ref().is_none_or(|(m, _)| miss < *m) {
                best = Some((miss, zone));
            }
        }
        let (miss, zone) = best.expect("two senses tried");
        if miss > MAX_MISMATCH {
            return Err(BentError::Mismatch {
                part,
                bend: index,
                segment: j,
                distance: miss,
            });
        }
        Ok(zone)
    }

    /// The zone turning towards `sense` × segment i's normal (its flat fields kept).
    fn towards(self, thickness: f64, sense: f64) -> Self {
        let w = self.start.u * self.across.x + self.start.v * self.across.y;
        let edge = (self.origin - self.across * (self.width / 2.0)).extend(thickness / 2.0);
        Self {
            axis_point: self.start.to_model(edge) + self.start.n * (sense * self.radius()),
            // (w × n) × w = n: turning about w × n takes w towards n.
            axis: w.cross(self.start.n) * sense,
            ..self
        }
    }

    /// The neutral axis' radius, mm (0 for a flat "bend").
    fn radius(&self) -> f64 {
        if self.turn > 0.0 { self.width / self.turn } else { 0.0 }
    }

    /// How far (mm) the zone's end lies from segment j's `end` frame: the largest distance
    /// over the ends of j's edge, on both faces.
    fn mismatch(&self, end: &Frame, thickness: f64) -> f64 {
        let last = self.frame_at(self.width);
        let edge = self.origin + self.across * (self.width / 2.0);
        let mut worst: f64 = 0.0;
        for p in [edge, edge + self.along * self.width.max(1.0)] {
            for z in [0.0, thickness] {
                let local = p.extend(z);
                worst = worst.max(last.to_model(local).distance(end.to_model(local)));
            }
        }
        worst
    }

    /// The rigid frame of the zone at `u` (0 ≤ u ≤ width): flat-frame points on the line
    /// `u` from the zone's start go to the arc there, tangent to it.
    pub fn frame_at(&self, u: f64) -> Frame {
        let shift = self.across * u;
        let base = Frame {
            origin: self.start.origin - (self.start.u * shift.x + self.start.v * shift.y),
            ..self.start
        };
        let rotation = DQuat::from_axis_angle(self.axis, self.turn * u / self.width);
        // Arc length u along the neutral axis: the edge point rotated about the axis.
        Frame {
            origin: self.axis_point + rotation * (base.origin - self.axis_point),
            u: rotation * base.u,
            v: rotation * base.v,
            n: rotation * base.n,
        }
    }

    /// The slices' ranges of u: equal slices, each turning at most 5° and straying from the
    /// arc by at most [`MAX_SAGITTA`].
    pub fn slices(&self) -> Vec<(f64, f64)> {
        let radius = self.radius();
        // Sagitta of a slice turning d: radius · d² / 8.
        let by_sagitta = self.turn * (radius / (8.0 * MAX_SAGITTA)).sqrt();
        let n = ((self.turn / MAX_SLICE_TURN).max(by_sagitta).ceil() as usize).clamp(1, MAX_SLICES);
        let step = self.width / n as f64;
        (0..n).map(|k| (k as f64 * step, (k + 1) as f64 * step)).collect()
    }

    /// The strip of the flat frame between u0 and u1 across the line, along the line's length.
    fn strip(&self, u0: f64, u1: f64) -> Polygon {
        let at = |u: f64, s: f64| self.origin + self.across * (u - self.width / 2.0) + self.along * s;
        let mut strip = Polygon::new(vec![at(u0, 0.0), at(u1, 0.0), at(u1, self.length), at(u0, self.length)]);
        strip.normalize_orientation();
        strip
    }

    /// The zone's turn, radians.
    pub fn turn(&self) -> f64 {
        self.turn
    }
}

/// A bent strip for tests, examples and benchmarks: segments of `lengths` (mm, along the flat
/// x axis) and `wide` mm across, joined by bend zones of `zone` mm turning by `turns_deg`
/// (positive: towards the first segment's normal), all bend axes parallel to the model's y.
/// The first segment lies on z = 0..thickness from x = 0, heading +x. The frames are found by
/// walking the neutral axis in the xz plane (not by [`Zone`]), so they check it.
pub fn sample_strip(id: u32, thickness: f64, wide: f64, lengths: &[f64], turns_deg: &[f64], zone: f64) -> Part {
    use super::part::{BendStyle, Segment};
    use platener_geom::polygon::rect;
    let (mut at, mut heading, mut x) = (DVec2::new(0.0, thickness / 2.0), 0.0_f64, 0.0);
    let (mut segments, mut bends) = (Vec::new(), Vec::new());
    for (k, &length) in lengths.iter().enumerate() {
        let (s, c) = heading.sin_cos();
        let (u, n) = (DVec3::new(c, 0.0, s), DVec3::new(-s, 0.0, c));
        let mid = DVec3::new(at.x, 0.0, at.y);
        let frame = Frame {
            origin: mid - u * x - n * (thickness / 2.0),
            u,
            v: DVec3::Y,
            n,
        };
        segments.push(Segment {
            polygon: Polygon::new(rect(x, 0.0, x + length, wide)),
            frame,
        });
        at += DVec2::new(c, s) * length;
        x += length;
        let Some(&turn_deg) = turns_deg.get(k) else { break };
        let turn = turn_deg.to_radians();
        let radius = zone / turn.abs();
        let side = DVec2::new(-s, c) * (radius * turn.signum());
        let centre = at + side;
        heading += turn;
        at = centre - DVec2::new(-heading.sin(), heading.cos()) * (radius * turn.signum());
        bends.push(Bend {
            line: [DVec2::new(x + zone / 2.0, 0.0), DVec2::new(x + zone / 2.0, wide)],
            angle_deg: 180.0 - turn_deg.abs(),
            style: BendStyle::LivingHinge,
            pattern: crate::plan::HingePattern::Lattice,
            width: zone,
            segments: [k, k + 1],
        });
        x += zone;
    }
    let mut part = Part::plate(id, thickness, Polygon::new(rect(0.0, 0.0, x, wide)), segments[0].frame);
    part.kind = PartKind::Bent;
    part.segments = segments;
    part.bends = bends;
    part
}

#[cfg(test)]
#[path = "bent_tests.rs"]
mod tests;
