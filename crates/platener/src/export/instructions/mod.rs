//! Step-by-step assembly instructions (issue 35): `assembly.html` for screens and
//! `assembly.pdf` for the bench, with a picture per step in `assembly/step-NN.png`.
//!
//! They follow plan.json's `assembly` (the order `assembly::order` computes from the
//! geometry): first the parts list per sheet, each part drawn small with its number, then one
//! step per part or run of parts. A run groups consecutive steps that go in the same way
//! (stacked layers threaded one after another on their shafts, for one) so that a plan of 80
//! parts reads as at most [`MAX_STEPS`] steps, as Roadkill's numbered subassemblies read
//! faster than pair-wise labels. Each step's picture is the assembly so far from the
//! thumbnail's camera, the parts placed before in grey, the new ones in their colours and an
//! arrow showing the way they move in; its text names the parts, the way, the edge numbers
//! engraved where they join (the same number on both parts of a joint) and every glued face.

pub mod html;
pub mod pdf;

use glam::DVec3;

use super::thumbnail;
use crate::plan::format::AssemblyStep;
use crate::plan::{Plan, PlanError};
use crate::scene::Assembly;

/// The most steps the instructions have; longer orders are grouped into runs.
pub const MAX_STEPS: usize = 16;
/// A step picture's size, pixels.
pub const PICTURE: (u32, u32) = (480, 360);
/// The grey of parts placed in earlier steps.
const PLACED: [u8; 3] = [200, 200, 200];

/// One step of the instructions.
#[derive(Debug, Clone)]
pub struct Instruction {
    /// 1-based.
    pub number: usize,
    /// The parts it adds.
    pub parts: Vec<u32>,
    /// What to do, sentence by sentence.
    pub lines: Vec<String>,
    /// The picture: RGB bytes, [`PICTURE`] pixels.
    pub picture: Vec<u8>,
}

impl Instruction {
    /// The picture's file in the ZIP.
    pub fn file(&self) -> String {
        format!("assembly/step-{:02}.png", self.number)
    }
}

/// A step as report.json lists it: its number, parts, sentences and picture's file.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct StepText {
    /// 1-based.
    pub number: usize,
    /// The parts it adds.
    pub parts: Vec<u32>,
    /// What to do.
    pub lines: Vec<String>,
    /// The picture's file in the ZIP.
    pub picture: String,
}

impl StepText {
    /// The text of `step`.
    pub fn of(step: &Instruction) -> Self {
        Self {
            number: step.number,
            parts: step.parts.clone(),
            lines: step.lines.clone(),
            picture: step.file(),
        }
    }
}

/// The steps of `plan`'s assembly, pictures drawn from `assembly` (its parts in 3D); none
/// when the plan has no order. `twins`: groups of identical parts that may take each other's
/// places (`verify::MismatchReport::interchangeable_parts`), told where the first of them
/// goes in.
pub fn instructions(plan: &Plan, assembly: &Assembly, twins: &[Vec<u32>]) -> Vec<Instruction> {
    let triangles: Vec<(u32, [DVec3; 3], [u8; 3])> = assembly.part_triangles().collect();
    let frame: Vec<([DVec3; 3], [u8; 3])> = triangles.iter().map(|(_, t, c)| (*t, *c)).collect();
    let runs = runs(&plan.assembly);
    let mut placed: Vec<u32> = Vec::new();
    let mut out = Vec::with_capacity(runs.len());
    for (k, run) in runs.iter().enumerate() {
        let parts: Vec<u32> = run.iter().flat_map(|s| s.parts.iter().copied()).collect();
        let direction = DVec3::from_array(run[0].direction);
        let drawn: Vec<([DVec3; 3], [u8; 3])> = triangles
            .iter()
            .filter_map(|(id, t, c)| {
                let colour = if parts.contains(id) {
                    Some(*c)
                } else {
                    placed.contains(id).then_some(PLACED)
                };
                colour.map(|c| (*t, c))
            })
            .collect();
        // A base (of the plan, or of one of its objects) is laid down, not moved onto anything.
        let starts = k == 0 || runs[k - 1][0].subassembly != run[0].subassembly;
        let arrow = (!starts)
            .then(|| arrow(&triangles, &parts, direction, &frame))
            .flatten();
        out.push(Instruction {
            number: k + 1,
            lines: lines(plan, run, (&placed, starts), twins),
            picture: thumbnail::rgb_picture(&drawn, &frame, PICTURE, arrow),
            parts: parts.clone(),
        });
        placed.extend(parts);
    }
    out
}

/// Consecutive steps grouped so that there are at most [`MAX_STEPS`]: a run holds steps
/// that move the same way, none forced or glued (those are told one by one).
fn runs(steps: &[AssemblyStep]) -> Vec<Vec<&AssemblyStep>> {
    let longest = steps.len().div_ceil(MAX_STEPS).max(1);
    let mut out: Vec<Vec<&AssemblyStep>> = Vec::new();
    for step in steps {
        let alone = |s: &AssemblyStep| s.forced || !s.glued.is_empty();
        match out.last_mut() {
            Some(run)
                if run.len() < longest
                    && run[0].direction == step.direction
                    && run[0].subassembly == step.subassembly
                    && !alone(run[0])
                    && !alone(step) =>
            {
                run.push(step)
            }
            _ => out.push(vec![step]),
        }
    }
    out
}

/// The arrow of a step: from outside the new parts' place, against the way they move, to
/// their centre; as long as the object is wide, a third of it.
fn arrow(
    triangles: &[(u32, [DVec3; 3], [u8; 3])],
    parts: &[u32],
    direction: DVec3,
    frame: &[([DVec3; 3], [u8; 3])],
) -> Option<[DVec3; 2]> {
    let points: Vec<DVec3> = triangles
        .iter()
        .filter(|(id, _, _)| parts.contains(id))
        .flat_map(|(_, t, _)| t.iter().copied())
        .collect();
    if points.is_empty() || direction.length_squared() < 0.5 {
        return None;
    }
    let centre = points.iter().sum::<DVec3>() / points.len() as f64;
    let (lo, hi) = frame.iter().flat_map(|(t, _)| t.iter()).fold(
        (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)),
        |(lo, hi), p| (lo.min(*p), hi.max(*p)),
    );
    let size = (hi - lo).length();
    let reach = points.iter().map(|p| (*p - centre).dot(-direction)).fold(0.0, f64::max);
    let end = centre - direction * reach;
    Some([end - direction * (size / 3.0), end])
}

/// The words for the way a part moves, for a maker looking from the front (the pictures'
/// camera: front right, above).
pub fn way(direction: [f64; 3]) -> String {
    let d = DVec3::from_array(direction);
    let named = [
        (DVec3::NEG_Z, "down from above"),
        (DVec3::Z, "up from below"),
        (DVec3::X, "in from the left"),
        (DVec3::NEG_X, "in from the right"),
        (DVec3::Y, "in from the front"),
        (DVec3::NEG_Y, "in from the back"),
    ];
    named.iter().find(|(n, _)| n.dot(d) > 0.999).map_or_else(
        || format!("in along ({:.2}, {:.2}, {:.2})", d.x, d.y, d.z),
        |(_, words)| words.to_string(),
    )
}

/// The parts listed by number up to this many; more are counted.
const LISTED: usize = 12;

/// The sentence that starts separate object `step.subassembly` of a plan in several: "Object
/// 2 of 3 (parts 4, 5 and 6): build it on its own."; empty for an object of one part (no
/// joint holds it); `None` for a plan that is one object.
fn object_line(plan: &Plan, step: &AssemblyStep) -> Option<String> {
    let n = step.subassembly?;
    let mut of: Vec<u32> = plan
        .assembly
        .iter()
        .filter(|s| s.subassembly == Some(n))
        .flat_map(|s| s.parts.iter().copied())
        .collect();
    if of.len() < 2 {
        return Some(String::new());
    }
    of.sort_unstable();
    let objects = plan.assembly.iter().filter_map(|s| s.subassembly).max().unwrap_or(n);
    let parts = if of.len() <= LISTED {
        format!("parts {}", list(&of))
    } else {
        format!("{} parts", of.len())
    };
    Some(format!("Object {n} of {objects} ({parts}): build it on its own."))
}

/// What to do in a step, sentence by sentence (`placed`: the parts placed before it, and
/// whether it starts the plan or one of its separate objects).
fn lines(plan: &Plan, run: &[&AssemblyStep], (placed, starts): (&[u32], bool), twins: &[Vec<u32>]) -> Vec<String> {
    let parts: Vec<u32> = run.iter().flat_map(|s| s.parts.iter().copied()).collect();
    let mut out = Vec::new();
    let names = list(&parts);
    let object = starts.then(|| object_line(plan, run[0])).flatten();
    let alone = object.as_deref() == Some("");
    out.extend(object.filter(|o| !o.is_empty()));
    out.push(if alone {
        format!("Lay part {names} down on its own: no joint holds it to the others.")
    } else if starts {
        format!("Lay part{} {names} down as the base.", plural(parts.len()))
    } else {
        format!(
            "Add part{} {names}: move {} {}.",
            plural(parts.len()),
            if parts.len() == 1 { "it" } else { "them" },
            way(run[0].direction)
        )
    });
    for step in run {
        let mut joins: Vec<String> = step
            .joints
            .iter()
            .filter_map(|&j| plan.joints.get(j))
            .map(|j| {
                let other = if step.parts.contains(&j.parts[0]) {
                    j.parts[1]
                } else {
                    j.parts[0]
                };
                format!("edge {} to part {other}", j.label)
            })
            .collect();
        joins.dedup();
        if !joins.is_empty() {
            let new = list(&step.parts);
            out.push(format!(
                "Part {new} joins {}: match the engraved numbers.",
                joins.join(", ")
            ));
        }
        for g in &step.glued {
            out.push(format!("Glue part {} face to face onto part {g}.", list(&step.parts)));
        }
        if step.forced {
            out.push(format!(
                "Part {} is locked in by its neighbours: flex it or the parts around it to get it in.",
                list(&step.parts)
            ));
        }
    }
    let first_time = |g: &&Vec<u32>| g.iter().any(|id| parts.contains(id)) && !g.iter().any(|id| placed.contains(id));
    for group in twins.iter().filter(first_time) {
        let which = if group.len() == 2 { "either" } else { "any" };
        out.push(format!(
            "Parts {} are identical: {which} one fits in {which} of their places.",
            list(group)
        ));
    }
    out
}

fn plural(n: usize) -> &'static str {
    if n == 1 { "" } else { "s" }
}

/// "3", "3 and 4", "3, 4 and 5".
fn list(ids: &[u32]) -> String {
    let words: Vec<String> = ids.iter().map(u32::to_string).collect();
    match words.split_last() {
        None => String::new(),
        Some((last, [])) => last.clone(),
        Some((last, rest)) => format!("{} and {last}", rest.join(", ")),
    }
}

/// The instructions' files: `assembly.html`, `assembly.pdf` and each step's picture; none
/// when the plan has no assembly order.
pub fn files(plan: &Plan, steps: &[Instruction], title: &str) -> Result<Vec<(String, Vec<u8>)>, PlanError> {
    if steps.is_empty() {
        return Ok(Vec::new());
    }
    let mut out = Vec::with_capacity(steps.len() + 2);
    for s in steps {
        let name = s.file();
        let png = thumbnail::encode(&s.picture, PICTURE.0, PICTURE.1, &name)?;
        out.push((name, png));
    }
    out.push(("assembly.html".to_string(), html::page(plan, steps, title).into_bytes()));
    out.push(("assembly.pdf".to_string(), pdf::document(plan, steps, title)?));
    Ok(out)
}
