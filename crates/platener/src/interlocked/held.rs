//! The pieces after slotting, which crossing holds which, and what is left out.
//!
//! A slice's material falls into pieces where the model's section does (two legs) or, rarely,
//! where every split height of a crossing cut it apart. A piece is held when a crossing's
//! slots grip it: its material beside its slot (the slot's walls, within [`GRIP`] of the
//! slot) shares heights with the other piece's material in the column. Pieces too small to
//! cut, and pieces no crossing holds (a tail that no slice of the other family meets), are
//! left out and said: an unheld piece would need glue, and the method exists to need none.

use platener_geom::{GridError, Polygon};
use serde::Serialize;

use super::Piece;
use super::cross::{Crossed, Crossing, TOUCH, column_extent, shared};
use super::place::Family;
use crate::cuttable::Rule;

/// How far beside its slot a piece's material counts as the slot's wall, mm.
pub(super) const GRIP: f64 = 0.5;

/// A piece left out of the plan.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct LeftOut {
    /// Its slice's name (A3).
    pub slice: String,
    /// Its area, mm².
    pub area: f64,
    /// Why.
    pub why: Why,
}

/// Why a piece was left out.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Why {
    /// Smaller than the smallest part.
    TooSmall,
    /// No crossing grips it: only glue would hold it.
    Unheld,
}

impl LeftOut {
    /// The warning for it.
    pub fn describe(&self) -> String {
        match self.why {
            Why::TooSmall => format!(
                "slice {}: a piece of {:.1} mm² is too small or thin to cut and was left out",
                self.slice, self.area
            ),
            Why::Unheld => format!(
                "slice {}: a piece of {:.1} mm² crosses no slice of the other family, so nothing would hold it without glue; left out (a smaller slice spacing reaches it)",
                self.slice, self.area
            ),
        }
    }
}

/// Pieces, the crossings that hold them and what was left out.
#[derive(Debug, Clone)]
pub struct Made {
    /// Every piece kept, A before B, numbered.
    pub pieces: Vec<Piece>,
    /// The crossings holding two kept pieces, their parts filled in.
    pub crossings: Vec<Crossing>,
    /// Pieces left out.
    pub left_out: Vec<LeftOut>,
}

impl Made {
    /// The order of assembly: every B piece stood up (by part id), then every A piece lowered.
    pub fn order(&self) -> Vec<u32> {
        let of = |f| self.pieces.iter().filter(move |p| p.family == f).map(|p| p.part);
        of(1).chain(of(0)).collect()
    }
}

/// The pieces of `crossed` (slots `2 half` wide), those `rule` keeps, and which crossing
/// holds which.
pub fn pieces(families: &[Family; 2], crossed: Crossed, half: f64, rule: &Rule) -> Result<Made, GridError> {
    let name = |f: usize, k: usize| format!("{}{}", families[f].letter, k + 1);
    let mut left_out: Vec<LeftOut> = crossed
        .too_small
        .iter()
        .map(|&(f, k, area)| LeftOut {
            slice: name(f, k),
            area,
            why: Why::TooSmall,
        })
        .collect();
    // Candidates: every piece worth cutting, by family, slice, position.
    let mut candidates: Vec<Piece> = Vec::new();
    for (f, slices) in crossed.material.iter().enumerate() {
        for (k, material) in slices.iter().enumerate() {
            let mut kept: Vec<Polygon> = Vec::new();
            for p in material {
                let mut p = p.clone();
                p.normalize_orientation();
                if rule.keeps(&p) {
                    kept.push(p);
                } else {
                    left_out.push(LeftOut {
                        slice: name(f, k),
                        area: p.area(),
                        why: Why::TooSmall,
                    });
                }
            }
            kept.sort_by(|a, b| {
                let (pa, pb) = (a.bounds().0, b.bounds().0);
                pa.x.total_cmp(&pb.x).then(pa.y.total_cmp(&pb.y))
            });
            candidates.extend(kept.into_iter().map(|polygon| Piece {
                family: f,
                slice: k,
                name: name(f, k),
                polygon,
                part: 0,
            }));
        }
    }
    let holds = grips(&candidates, &crossed.crossings, half)?;
    let held: Vec<bool> = (0..candidates.len())
        .map(|n| holds.iter().any(|(_, a, b)| *a == n || *b == n))
        .collect();
    let mut index = vec![usize::MAX; candidates.len()];
    let mut pieces = Vec::new();
    for (n, piece) in candidates.into_iter().enumerate() {
        if held[n] {
            index[n] = pieces.len();
            pieces.push(piece);
        } else {
            left_out.push(LeftOut {
                slice: piece.name.clone(),
                area: piece.polygon.area(),
                why: Why::Unheld,
            });
        }
    }
    name_pieces(&mut pieces);
    let crossings = holds
        .into_iter()
        .map(|(c, a, b)| Crossing {
            parts: [pieces[index[a]].part, pieces[index[b]].part],
            ..crossed.crossings[c].clone()
        })
        .collect();
    Ok(Made {
        pieces,
        crossings,
        left_out,
    })
}

/// Part ids in order, and a number after the name of each piece of a slice in several (the
/// engraving font has capitals only, so B2a would read B2A).
fn name_pieces(pieces: &mut [Piece]) {
    for n in 0..pieces.len() {
        pieces[n].part = n as u32 + 1;
        let same: Vec<usize> = (0..pieces.len())
            .filter(|&m| (pieces[m].family, pieces[m].slice) == (pieces[n].family, pieces[n].slice))
            .collect();
        if same.len() > 1 {
            let rank = same.iter().position(|&m| m == n).unwrap_or(0);
            pieces[n].name = format!("{}-{}", pieces[n].name, rank + 1);
        }
    }
}

/// `(crossing, A piece, B piece)` for every pair of candidates a crossing's slots grip
/// together (indices into `crossings` and `candidates`).
fn grips(candidates: &[Piece], crossings: &[Crossing], half: f64) -> Result<Vec<(usize, usize, usize)>, GridError> {
    let mut out = Vec::new();
    for (c, crossing) in crossings.iter().enumerate() {
        if crossing.shared.is_none() {
            continue;
        }
        let of = |f: usize| {
            candidates
                .iter()
                .enumerate()
                .filter(move |(_, p)| p.family == f && p.slice == crossing.slices[f])
        };
        for (a, pa) in of(0) {
            for (b, pb) in of(1) {
                if grip(&pa.polygon, &pb.polygon, crossing, half)? {
                    out.push((c, a, b));
                }
            }
        }
    }
    Ok(out)
}

/// Whether `a` and `b` (an A and a B piece of `crossing`'s slices, slots `2 t` wide) hold
/// each other there: one's slot walls share heights with the other's material in the column.
fn grip(a: &Polygon, b: &Polygon, crossing: &Crossing, t: f64) -> Result<bool, GridError> {
    let (a, b) = (std::slice::from_ref(a), std::slice::from_ref(b));
    let [xa, xb] = crossing.at;
    let walls_a = shared(&column_extent(a, xa, t + GRIP)?, &column_extent(b, xb, t)?);
    let walls_b = shared(&column_extent(a, xa, t)?, &column_extent(b, xb, t + GRIP)?);
    Ok([walls_a, walls_b].into_iter().flatten().any(|[lo, hi]| hi - lo > TOUCH))
}
