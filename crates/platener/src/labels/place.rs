//! Finding room for a label on a part: a text box, grown by a clearance, must lie inside the
//! part minus its holes and clear of other labels and marks.
//!
//! The inside test is a boolean difference on the project grid (box minus part must be empty),
//! after cheap point tests have weeded out most candidates. Label boxes are rectangles, so
//! label-against-label uses the separating-axis test.

use glam::DVec2;
use platener_geom::polygon::Polygon;
use platener_geom::tolerance::GRID_NOISE_AREA;
use platener_geom::{Ring, boolean, offset};

use crate::draw::font::text_width;

/// Most points [`Room::inner_points`] samples per piece of the inset part.
const INNER_POINTS: usize = 256;

/// Smallest text size engraved, mm: below this a laser's engraving is hard to read.
pub const MIN_SIZE: f64 = 1.5;

/// The clearance a label of size `size` keeps from the part's nominal edges, holes, marks and
/// other labels, mm: half a millimetre plus a tenth of the size, plus half the `kerf` (hole cut
/// paths lie that far inside the material).
pub fn clearance(size: f64, kerf: f64) -> f64 {
    0.5 + 0.1 * size + kerf / 2.0
}

/// A placed text: its bottom-left corner, baseline direction and size, in the part's frame.
#[derive(Debug, Clone, PartialEq)]
pub struct TextBox {
    /// The text.
    pub text: String,
    /// Cap height, mm.
    pub size: f64,
    /// Bottom-left corner of the text (y-down frame, as laid on the sheet).
    pub origin: DVec2,
    /// Unit baseline direction.
    pub direction: DVec2,
}

impl TextBox {
    /// A box of `text` at `size` centred on `center`, reading along `direction`.
    pub fn centered(text: &str, size: f64, center: DVec2, direction: DVec2) -> Self {
        let up = up_of(direction);
        let origin = center - direction * (text_width(text, size) / 2.0) - up * (size / 2.0);
        Self {
            text: text.to_string(),
            size,
            origin,
            direction,
        }
    }

    /// The box's corners grown by `grow` on every side.
    pub fn corners(&self, grow: f64) -> [DVec2; 4] {
        let (d, up) = (self.direction, up_of(self.direction));
        let w = text_width(&self.text, self.size);
        let o = self.origin - d * grow - up * grow;
        let (dx, dy) = (d * (w + 2.0 * grow), up * (self.size + 2.0 * grow));
        [o, o + dx, o + dx + dy, o + dy]
    }
}

/// "Up" of a text reading along `d` in a y-down frame.
pub fn up_of(d: DVec2) -> DVec2 {
    DVec2::new(d.y, -d.x)
}

/// The area a part offers to labels, and what is already on it.
pub struct Room<'a> {
    polygon: &'a Polygon,
    kerf: f64,
    taken: Vec<[DVec2; 4]>,
    marks: Vec<[DVec2; 2]>,
}

impl<'a> Room<'a> {
    /// The room of `polygon` (normalised) cut with `kerf`, with mark polylines to keep clear of.
    pub fn new(polygon: &'a Polygon, marks: &[Vec<DVec2>], kerf: f64) -> Self {
        let marks = marks.iter().flat_map(|m| m.windows(2).map(|w| [w[0], w[1]])).collect();
        Self {
            polygon,
            kerf,
            taken: Vec::new(),
            marks,
        }
    }

    /// Whether `label` (grown by its clearance) fits; see the module docs.
    pub fn fits(&self, label: &TextBox) -> bool {
        let quad = label.corners(self.clearance(label.size));
        let center = (quad[0] + quad[2]) / 2.0;
        if !quad.iter().chain([&center]).all(|p| self.polygon.contains(*p)) {
            return false;
        }
        if self.taken.iter().any(|t| convex_overlap(t, &quad)) {
            return false;
        }
        if self.marks.iter().any(|s| segment_hits_quad(*s, &quad)) {
            return false;
        }
        // Holes or notches may still reach into the box between its corners. When no edge of
        // the part enters the box, it is inside (its corners are): the boolean, costly on a
        // part of thousands of vertices tried at hundreds of places, only decides the rest.
        if !self.edges_enter(&quad) {
            return true;
        }
        let ring: Ring = quad.to_vec();
        match boolean::difference(&[Polygon::new(ring)], std::slice::from_ref(self.polygon)) {
            // Grid rounding of the boolean is far below any real crossing (a 1.5 mm label
            // crossing an edge by 0.01 mm leaves 0.015 mm²).
            Ok(outside) => outside.iter().map(Polygon::area).sum::<f64>() <= GRID_NOISE_AREA,
            Err(_) => false,
        }
    }

    /// Whether an edge of the part's outline or holes touches or crosses `quad`.
    fn edges_enter(&self, quad: &[DVec2; 4]) -> bool {
        let (lo, hi) = quad
            .iter()
            .fold((quad[0], quad[0]), |(lo, hi), p| (lo.min(*p), hi.max(*p)));
        std::iter::once(&self.polygon.outer)
            .chain(&self.polygon.holes)
            .flat_map(|ring| ring.iter().zip(ring.iter().cycle().skip(1)))
            .any(|(a, b)| {
                let (elo, ehi) = (a.min(*b), a.max(*b));
                elo.cmple(hi).all() && lo.cmple(ehi).all() && segment_hits_quad([*a, *b], quad)
            })
    }

    /// The clearance of a label of `size` on this part.
    pub fn clearance(&self, size: f64) -> f64 {
        clearance(size, self.kerf)
    }

    /// Records a placed label so later ones keep clear of it.
    pub fn take(&mut self, label: &TextBox) {
        self.taken.push(label.corners(0.0));
    }

    /// Keeps every label clear of the convex quadrilateral `area` (a bent part's bend zone:
    /// text engraved there would be stretched over the hinge, or cut by its slits).
    pub fn block(&mut self, area: [DVec2; 4]) {
        self.taken.push(area);
    }

    /// Up to `n` well-separated points deep inside the polygon, deepest first, with their
    /// distance to the boundary (a sampled pole of inaccessibility, 24 × 24 grid).
    pub fn deep_points(&self, n: usize) -> Vec<(DVec2, f64)> {
        const STEPS: usize = 24;
        let (lo, hi) = self.polygon.bounds();
        let size = hi - lo;
        let mut pts = Vec::new();
        for i in 0..STEPS {
            for j in 0..STEPS {
                let p = lo + size * DVec2::new((i as f64 + 0.5) / STEPS as f64, (j as f64 + 0.5) / STEPS as f64);
                if self.polygon.contains(p) {
                    pts.push((p, self.polygon.boundary_distance(p)));
                }
            }
        }
        pts.sort_by(|a, b| {
            b.1.total_cmp(&a.1)
                .then(a.0.x.total_cmp(&b.0.x))
                .then(a.0.y.total_cmp(&b.0.y))
        });
        let mut out: Vec<(DVec2, f64)> = Vec::new();
        let spread = size.max_element() / STEPS as f64 * 2.5;
        for (p, d) in pts {
            if out.iter().all(|(q, _)| q.distance(p) > spread) {
                out.push((p, d));
                if out.len() == n {
                    break;
                }
            }
        }
        out
    }

    /// Points of a grid (0.5 mm, coarser on large parts: at most about [`INNER_POINTS`]) that lie
    /// at least `inset` inside the part: where a label `2·inset` tall may be centred. Finds room
    /// the coarse [`Room::deep_points`] grid steps over (a tab a few millimetres wide).
    pub fn inner_points(&self, inset: f64) -> Vec<DVec2> {
        let Ok(inner) = offset::offset(std::slice::from_ref(self.polygon), -inset) else {
            return Vec::new();
        };
        let mut out = Vec::new();
        for piece in &inner {
            let (lo, hi) = piece.bounds();
            let size = hi - lo;
            let step = (size.x * size.y / INNER_POINTS as f64).sqrt().max(0.5);
            let (nx, ny) = ((size.x / step) as usize, (size.y / step) as usize);
            for i in 0..=nx {
                for j in 0..=ny {
                    let p = lo
                        + DVec2::new(i as f64, j as f64) * step
                        + (size - DVec2::new(nx as f64, ny as f64) * step) / 2.0;
                    if piece.contains(p) {
                        out.push(p);
                    }
                }
            }
        }
        out
    }

    /// Whether `p` lies inside the part.
    pub fn contains(&self, p: DVec2) -> bool {
        self.polygon.contains(p)
    }
}

/// Separating-axis test of two convex quadrilaterals (touching counts as overlap).
fn convex_overlap(a: &[DVec2; 4], b: &[DVec2; 4]) -> bool {
    for poly in [a, b] {
        for i in 0..4 {
            let e = poly[(i + 1) % 4] - poly[i];
            let axis = DVec2::new(-e.y, e.x);
            let span = |q: &[DVec2; 4]| {
                q.iter()
                    .map(|p| p.dot(axis))
                    .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| (lo.min(v), hi.max(v)))
            };
            let (alo, ahi) = span(a);
            let (blo, bhi) = span(b);
            if ahi < blo || bhi < alo {
                return false;
            }
        }
    }
    true
}

/// Whether segment `s` touches the convex quadrilateral `q`.
fn segment_hits_quad(s: [DVec2; 2], q: &[DVec2; 4]) -> bool {
    let inside = |p: DVec2| {
        let signs: Vec<f64> = (0..4).map(|i| (q[(i + 1) % 4] - q[i]).perp_dot(p - q[i])).collect();
        signs.iter().all(|v| *v >= 0.0) || signs.iter().all(|v| *v <= 0.0)
    };
    if inside(s[0]) || inside(s[1]) {
        return true;
    }
    (0..4).any(|i| segments_cross(s[0], s[1], q[i], q[(i + 1) % 4]))
}

fn segments_cross(a: DVec2, b: DVec2, c: DVec2, d: DVec2) -> bool {
    let o = |p: DVec2, q: DVec2, r: DVec2| (q - p).perp_dot(r - p);
    let (d1, d2, d3, d4) = (o(c, d, a), o(c, d, b), o(a, b, c), o(a, b, d));
    (d1 * d2 <= 0.0) && (d3 * d4 <= 0.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    use platener_geom::polygon::rect;

    #[test]
    fn a_label_over_a_hole_or_an_edge_does_not_fit() {
        let mut p = Polygon {
            outer: rect(0.0, 0.0, 50.0, 30.0),
            holes: vec![rect(20.0, 10.0, 30.0, 20.0)],
        };
        p.normalize_orientation();
        let room = Room::new(&p, &[], 0.2);
        assert!(room.fits(&TextBox::centered("12", 4.0, DVec2::new(10.0, 15.0), DVec2::X)));
        // Corners all outside the hole, but the hole cuts through the box's middle.
        assert!(!room.fits(&TextBox::centered("88888888", 4.0, DVec2::new(25.0, 15.0), DVec2::X)));
        assert!(!room.fits(&TextBox::centered("12", 4.0, DVec2::new(2.0, 15.0), DVec2::X)));
        let deep = room.deep_points(3);
        assert!(deep[0].1 > 7.0, "{deep:?}");
    }

    #[test]
    fn labels_and_marks_keep_clear_of_each_other() {
        let mut p = Polygon::new(rect(0.0, 0.0, 60.0, 30.0));
        p.normalize_orientation();
        let bend = vec![vec![DVec2::new(40.0, 0.0), DVec2::new(40.0, 30.0)]];
        let mut room = Room::new(&p, &bend, 0.2);
        let a = TextBox::centered("1", 4.0, DVec2::new(15.0, 15.0), DVec2::X);
        assert!(room.fits(&a));
        room.take(&a);
        assert!(!room.fits(&TextBox::centered("2", 4.0, DVec2::new(17.0, 15.0), DVec2::X)));
        assert!(!room.fits(&TextBox::centered("3", 4.0, DVec2::new(40.0, 15.0), DVec2::Y)));
        assert!(room.fits(&TextBox::centered("4", 4.0, DVec2::new(50.0, 15.0), DVec2::Y)));
    }
}
