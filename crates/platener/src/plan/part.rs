//! What the methods hand to the cutting-plan steps: parts with their nominal geometry, and joints.
//!
//! The plate method (plates with finger joints) and the stacked method (layers and shafts) both
//! end in this form, so kerf compensation, labels, nesting and export never know which method
//! made a part.

use glam::DVec2;
use platener_geom::{Frame, Polygon};
use serde::{Deserialize, Serialize};

/// What a part is, as in plan.json's `kind`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum PartKind {
    /// A flat plate.
    Plate,
    /// Several plates merged into one part with bend lines (living hinges).
    Bent,
    /// A layer of the stacked method.
    Layer,
    /// A shaft of the stacked method.
    Shaft,
}

/// What a mark drawn on a part is, as in plan.json's `marks[].kind`: only `cut`, `score` and
/// `label` (the spec's three). `Cut` marks are cut through without removing material (red);
/// the others are engraved (blue).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum MarkKind {
    /// Cut through but removing nothing: living-hinge slits, perforation dashes (plan.json's
    /// `cut`, drawn red like the outline; kerf compensation leaves them as they are).
    Cut,
    /// Engraved or scored, not cut through: a bend line to fold or heat along, the outline of
    /// a feature on one face (engraved or embossed text, a pocket, a standoff's footprint), a
    /// stacked layer's outline on the layer below (plan.json's `score`). Plans written before
    /// version 2 also called these `engrave` or `bend`; both still read as `score`.
    #[serde(alias = "engrave", alias = "bend")]
    Score,
    /// Text and numbers (made by the `labels` step).
    Label,
}

/// The face of a part a mark is on, as the part lies on the laser's bed (plan.json's
/// `marks[].side`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum MarkSide {
    /// The face up on the sheet: engraved as drawn.
    Top,
    /// The face down on the sheet: engraving it means turning the part over, and the mark
    /// then reads mirrored.
    Bottom,
}

/// An engraved open polyline in the part's own 2D frame.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Mark {
    /// What it is.
    pub kind: MarkKind,
    /// The polyline, in mm.
    pub path: Vec<DVec2>,
    /// The face it belongs on, for marks of one face (a feature's score); `None` for marks
    /// drawn on the face up (labels, bend lines). Optional in plan.json (added, not renamed).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub side: Option<MarkSide>,
}

/// A jointed edge of a part whose connection number is engraved next to it, on the inside.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EdgeLabel {
    /// The connection's number ([`Joint::label`]).
    pub connection: u32,
    /// The edge, in the part's own 2D frame (its direction does not matter).
    pub segment: [DVec2; 2],
}

/// One part to cut: its nominal shape (joints included, no kerf), where it sits in the model,
/// and what to engrave on it.
#[derive(Debug, Clone, PartialEq)]
pub struct Part {
    /// Unique, 1-based; also the number engraved on the part.
    pub id: u32,
    /// What it is.
    pub kind: PartKind,
    /// Sheet thickness in mm; parts are nested on sheets of their own thickness.
    pub thickness: f64,
    /// The nominal shape in the part's 2D frame: outer ring and holes, any orientation (the
    /// steps normalise to outer counter-clockwise, holes clockwise).
    pub polygon: Polygon,
    /// Where the part sits in the model: local (x, y, z) → model, z from 0 to `thickness`.
    pub frame: Frame,
    /// Marks the method draws (bend lines…); labels are added by the `labels` step.
    pub marks: Vec<Mark>,
    /// Jointed edges whose connection number should be engraved on this part.
    pub edge_labels: Vec<EdgeLabel>,
    /// For bent parts: the ids of the plates merged into it (plan.json's `merged`).
    pub merged: Vec<u32>,
    /// For bent parts: the flat pieces between bend zones, each placed in the model by its
    /// own frame (plan.json's `segments`; the first one's frame is `frame`). Empty otherwise.
    pub segments: Vec<Segment>,
    /// For bent parts: where and how the flat part is bent (plan.json's `bends`).
    pub bends: Vec<Bend>,
}

/// How a bent part is made to bend along a bend line (plan.json's `bends[].style`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum BendStyle {
    /// Rows of staggered slits whose links twist (wood, MDF): a bend zone of some width.
    LivingHinge,
    /// A dashed cut to fold along (cardboard).
    Perforation,
    /// A scored line to fold along (thin paper).
    Score,
    /// An engraved guide line; the part is bent over a heater along it (acrylic).
    Heat,
}

impl BendStyle {
    /// The name used in plan.json and on the command line.
    pub fn name(self) -> &'static str {
        match self {
            BendStyle::LivingHinge => "living-hinge",
            BendStyle::Perforation => "perforation",
            BendStyle::Score => "score",
            BendStyle::Heat => "heat",
        }
    }
}

/// The slit pattern of a living hinge (plan.json's `bends[].pattern`, an extension; absent
/// means `lattice`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Default, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum HingePattern {
    /// Staggered slits whose links are designed from their torsion (docs/bending.md).
    #[default]
    Lattice,
    /// The straight-cut flex of boxes.py: slits 4 t long with t bridges, rows 0.5 t apart,
    /// bent to the radius makers find it takes (5 t in plywood).
    Straight,
}

impl HingePattern {
    /// The name used in plan.json, on the command line and on the swatch.
    pub fn name(self) -> &'static str {
        match self {
            HingePattern::Lattice => "lattice",
            HingePattern::Straight => "straight",
        }
    }

    /// Whether this is the default (plan.json leaves it out).
    pub fn is_lattice(&self) -> bool {
        *self == HingePattern::Lattice
    }
}

/// One flat piece of a bent part: a region of the part's flat shape and the rigid frame that
/// places it in the model (local z from 0 to the thickness, as for a plate).
#[derive(Debug, Clone, PartialEq)]
pub struct Segment {
    /// The region, in the part's own 2D frame.
    pub polygon: Polygon,
    /// Where that region sits in the model.
    pub frame: Frame,
}

/// One bend of a bent part, in the part's own 2D frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Bend {
    /// The bend line (the middle of the bend zone), end to end across the part.
    pub line: [DVec2; 2],
    /// The angle the two sides enclose once bent, degrees (180 = flat).
    pub angle_deg: f64,
    /// How the material is made to bend.
    pub style: BendStyle,
    /// A living hinge's slit pattern (plan.json extension `bends[].pattern`).
    pub pattern: HingePattern,
    /// Width of the bend zone on the flat part, mm, centred on `line`: the strip that curves
    /// (plan.json extension `bends[].width`; the neutral axis' arc length, so the flat
    /// length includes the bend allowance).
    pub width: f64,
    /// The indices of the two segments it joins, into [`Part::segments`] (plan.json
    /// extension `bends[].segments`).
    pub segments: [usize; 2],
}

impl Part {
    /// A plate with no marks or labels; the fields can be set afterwards.
    pub fn plate(id: u32, thickness: f64, polygon: Polygon, frame: Frame) -> Self {
        Self {
            id,
            kind: PartKind::Plate,
            thickness,
            polygon,
            frame,
            marks: Vec::new(),
            edge_labels: Vec::new(),
            merged: Vec::new(),
            segments: Vec::new(),
            bends: Vec::new(),
        }
    }
}

/// How two parts are joined, as in plan.json's `joints[].kind`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum JointKind {
    /// Finger (box) joint.
    Finger,
    /// The thesis' jim joint.
    Jim,
    /// Dovetail.
    Dovetail,
    /// Tab and slot, for T-junctions.
    Slot,
    /// Cross-lap (halved) joint.
    Halved,
    /// The two plates are one bent part.
    Bend,
    /// Stacked layers on a shaft.
    Shaft,
    /// The seam of a bent part closed by a glue flap (paper and card): `parts` names the
    /// bent part twice (plan.json extension).
    Flap,
    /// A raised detail cut from a thinner sheet, glued face to face on its outline engraved
    /// on the part it stands on (plan.json extension; the pair is in `glued` too).
    Glued,
    /// A stack of discs (a standoff cut from the sheet) held on the part it stands on by a
    /// screw through the standoff's own hole, cut through that part too (plan.json
    /// extension): each disc is joined to the one it lies on, the first to the part.
    Screw,
}

/// A connection between two parts.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Joint {
    /// The two parts' ids.
    pub parts: [u32; 2],
    /// The kind of joint.
    pub kind: JointKind,
    /// The angle enclosed by the plates, in degrees.
    pub angle_deg: f64,
    /// The connection number engraved next to the edge on both parts.
    pub label: u32,
}

/// A closed `score` mark on `side` along every ring of `regions` (one-sided features, the
/// classifier's engraved textures).
pub fn score_rings(regions: &[Polygon], side: MarkSide) -> impl Iterator<Item = Mark> + '_ {
    regions
        .iter()
        .flat_map(|p| std::iter::once(&p.outer).chain(&p.holes))
        .filter(|r| r.len() >= 3)
        .map(move |r| Mark {
            kind: MarkKind::Score,
            path: r.iter().copied().chain(r.first().copied()).collect(),
            side: Some(side),
        })
}
