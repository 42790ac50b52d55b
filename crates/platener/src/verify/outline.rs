//! Whether a part's outline is one a laser can cut: the kernel's validity check
//! ([`platener_geom::validity`]) on the part's outline and holes, as messages naming the ring
//! and the place. The same check repairs outlines where parts are made (`repair`), so a
//! plan platener wrote passes it; a plan edited by hand or written by an older version may not.

use platener_geom::{Polygon, Problem, RingId, validate};

use crate::plan::PlanPart;

/// Findings listed per part, at most.
const MOST: usize = 5;

/// What is wrong with the part's outline and holes (empty when it is valid): rings that
/// cross, touch or run back along themselves, holes outside the outline or inside another,
/// and material narrower than `min_width` (the plan's kerf).
pub fn outline_findings(part: &PlanPart, min_width: f64) -> Vec<String> {
    let polygon = Polygon {
        outer: part.outline.clone(),
        holes: part.holes.clone(),
    };
    let name = |r: RingId| match r {
        RingId::Outer => "the outline".to_string(),
        RingId::Hole(i) => format!("hole {}", i + 1),
    };
    validate(&polygon, min_width)
        .into_iter()
        .take(MOST)
        .map(|f| {
            let (ring, at) = (name(f.ring), format!("({:.3}, {:.3})", f.at.x, f.at.y));
            match f.problem {
                Problem::Crossing { other } | Problem::Touching { other } if other != f.ring => {
                    format!("{ring} and {} touch at {at}", name(other))
                }
                Problem::Crossing { .. } | Problem::Touching { .. } => format!("{ring} touches itself at {at}"),
                Problem::Spike => format!("{ring} runs back along itself at {at}"),
                Problem::HoleOutside => format!("{ring} lies outside the outline"),
                Problem::HoleInHole { other } => format!("{ring} lies inside hole {}", other + 1),
                Problem::Orientation => {
                    format!("{ring} runs the wrong way round (plan.json: outlines counter-clockwise, holes clockwise)")
                }
                Problem::Narrow => format!("{ring} is narrower than {min_width:.2} mm at {at}"),
                other => format!("{ring}: {other:?} at {at}"),
            }
        })
        .collect()
}
