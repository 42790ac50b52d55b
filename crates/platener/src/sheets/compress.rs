//! Shortening the last sheet's used length after the left-first fill: ruin and recreate.
//!
//! The fill places each part once, where it was best when it came; parts that came late end
//! the sheet, and gaps left behind earlier parts stay empty. Each attempt here asks for a
//! shorter sheet: it takes away every part reaching past a target a little left of today's
//! right edge and a few random parts near that end (so a hole opens where a removed part can
//! go), then places the removed parts again, largest first, with the left-first rule, none
//! past the target. When all fit, the shorter layout is kept; when not, the step towards the
//! target shrinks (after the local search of Imamichi, Yagiura and Nagamochi, 2009, and the
//! strip shrinking of sparrow, with removal and re-insertion instead of overlap minimisation).
//! Attempts are counted, not timed, and the random choices come from the seed, so the result
//! is the same on every machine.

use glam::DVec2;
use platener_geom::rng::SplitMix64;

use super::blf::{Bin, Placed, right_edge};
use super::shape::NestShape;

/// The first step asked for: this share of the used length.
const FIRST_STEP: f64 = 0.01;
/// Steps never shrink below this, mm.
const MIN_STEP: f64 = 0.25;
/// Random parts taken away besides those past the target, at most.
const EXTRA: u64 = 6;
/// The random parts come from this share of the used length at its right end.
const NEAR_END: f64 = 0.5;

/// Shortens `placed` (one sheet whose free region is `lo..hi`) by up to `attempts` tries of
/// ruin and recreate; the better placements, or `None` when none was found.
pub(crate) fn compress(
    shapes: &[NestShape],
    placed: &[Placed],
    (lo, hi): (DVec2, DVec2),
    (attempts, seed): (u32, u64),
    cancelled: &(dyn Fn() -> bool + Sync),
) -> Option<Vec<Placed>> {
    let right = |p: &[Placed]| right_edge(p, lo.x);
    let mut best: Vec<Placed> = placed.to_vec();
    let mut step = (right(&best) - lo.x) * FIRST_STEP;
    let mut rng = SplitMix64::new(seed ^ 0x5EED_C0DE_5EED_C0DE);
    let mut improved = false;
    for _ in 0..attempts {
        if cancelled() || best.len() < 2 {
            break;
        }
        let now = right(&best);
        let target = now - step.max(MIN_STEP);
        match recreate(shapes, &best, (lo, hi), target, &mut rng) {
            Some(shorter) if right(&shorter) < now => {
                best = shorter;
                improved = true;
            }
            _ => step = (step * 0.7).max(MIN_STEP),
        }
    }
    improved.then_some(best)
}

/// One attempt: every part past `target` and a few random ones near the end taken away and
/// placed again before `target`; `None` when one of them no longer fits.
fn recreate(
    shapes: &[NestShape],
    placed: &[Placed],
    (lo, hi): (DVec2, DVec2),
    target: f64,
    rng: &mut SplitMix64,
) -> Option<Vec<Placed>> {
    let now = right_edge(placed, lo.x);
    let near = now - (now - lo.x) * NEAR_END;
    let mut out: Vec<bool> = placed.iter().map(|p| p.max.x > target).collect();
    let candidates: Vec<usize> = (0..placed.len())
        .filter(|&i| !out[i] && placed[i].max.x > near)
        .collect();
    let extra = (rng.next_u64() % (EXTRA + 1)) as usize;
    for _ in 0..extra.min(candidates.len()) {
        let pick = candidates[(rng.next_u64() % candidates.len() as u64) as usize];
        out[pick] = true;
    }
    let mut bin = Bin::rect(lo, hi)?;
    for (p, _) in placed.iter().zip(&out).filter(|(_, o)| !**o) {
        bin.put(p.clone(), &shapes[p.key]);
    }
    let mut removed: Vec<&Placed> = placed.iter().zip(&out).filter(|(_, o)| **o).map(|(p, _)| p).collect();
    removed.sort_by(|a, b| {
        shapes[b.key]
            .area
            .total_cmp(&shapes[a.key].area)
            .then(a.key.cmp(&b.key))
    });
    for p in removed {
        bin.place_before(p.key, &shapes[p.key], target)?;
    }
    Some(bin.placed)
}

#[cfg(test)]
mod tests {
    use glam::DVec2;
    use platener_geom::Polygon;

    use super::*;
    use crate::sheets::search::{first_fit, order};
    use crate::sheets::shape::nest_shape;
    use crate::sheets::tests::assert_free;

    /// Forty L-shapes and rectangles of mixed sizes, from a fixed sequence.
    fn shapes() -> Vec<NestShape> {
        let mut rng = SplitMix64::new(11);
        (0..40)
            .map(|k| {
                let (w, h) = (20.0 + 80.0 * rng.unit(), 15.0 + 60.0 * rng.unit());
                let ring: Vec<DVec2> = if k % 3 == 0 {
                    let (a, b) = (w * 0.4, h * 0.4);
                    [(0.0, 0.0), (w, 0.0), (w, b), (a, b), (a, h), (0.0, h)]
                        .map(|(x, y)| DVec2::new(x, y))
                        .to_vec()
                } else {
                    [(0.0, 0.0), (w, 0.0), (w, h), (0.0, h)]
                        .map(|(x, y)| DVec2::new(x, y))
                        .to_vec()
                };
                let p = Polygon::new(ring);
                nest_shape(&p, p.area(), 2.0, false).expect("a shape")
            })
            .collect()
    }

    /// Compressing a strip keeps every part, inside the strip and clear of every other (the
    /// collision engine asked part by part), and never lengthens it; on this set it shortens it.
    #[test]
    fn a_compressed_strip_is_shorter_and_still_free_of_overlaps() {
        let shapes = shapes();
        let items: Vec<usize> = (0..shapes.len()).collect();
        let region = (DVec2::ZERO, DVec2::new(5000.0, 300.0));
        let layout = first_fit(&shapes, &order(&shapes, &items, 0, 0), region.0, region.1, &|| false).expect("fits");
        let before = layout.used_right[0];
        let after = compress(&shapes, &layout.sheets[0], region, (64, 7), &|| false).expect("shorter");
        let right = right_edge(&after, 0.0);
        assert!(right < before - 1.0, "{before} → {right}");
        let mut keys: Vec<usize> = after.iter().map(|p| p.key).collect();
        keys.sort_unstable();
        assert_eq!(keys, items, "every part once");
        assert_free(&shapes, &after, region);
    }
}
