//! Layers no shaft joins: the groups of parts the shafts hold, and where only glue holds
//! those groups to each other.
//!
//! A stack whose layers rest on each other without a shaft through them (a bracket of four
//! thin layers, a teapot's handle) is not one assembly: it is as many groups as the shafts
//! make, and the user glues them. Counting them as one would hide it; counting them as the
//! model's separate solids (a checker comparing groups with solids) would too. So the plan
//! names them: plan.json's `glued` lists every pair of touching parts of *different* shaft
//! groups with the area they share, and the step warns naming each group. A pair left unjoined
//! inside one group (held through other layers) is not listed: nothing falls apart there.

use super::Stack;
use crate::assembly::UnionFind;
use crate::plan::Glue;

/// The pairs of parts of different shaft groups that touch and must be glued, and the
/// warning naming those groups (none when nothing needs glue).
pub(crate) fn glued(stack: &Stack) -> (Vec<Glue>, Option<String>) {
    let (ids, mut groups) = shaft_groups(stack);
    let index = |part: u32| ids.binary_search(&part).expect("every island is a part");
    let glue: Vec<Glue> = stack
        .unjoined
        .iter()
        .map(|u| Glue {
            parts: [
                stack.layers[u.layer].islands[u.lower].part,
                stack.layers[u.layer + 1].islands[u.upper].part,
            ],
            area: u.overlap,
        })
        .filter(|g| groups.root(index(g.parts[0])) != groups.root(index(g.parts[1])))
        .collect();
    if glue.is_empty() {
        return (glue, None);
    }
    let mut roots: Vec<usize> = glue
        .iter()
        .flat_map(|g| g.parts)
        .map(|p| groups.root(index(p)))
        .collect();
    roots.sort_unstable();
    roots.dedup();
    let named: Vec<String> = roots
        .iter()
        .map(|&r| {
            let members: Vec<u32> = (0..ids.len())
                .filter(|&i| groups.root(i) == r)
                .map(|i| ids[i])
                .collect();
            format!("[{}]", crate::labels::id_ranges(&members))
        })
        .collect();
    let pairs: Vec<String> = glue.iter().map(|g| format!("{}–{}", g.parts[0], g.parts[1])).collect();
    let warning = format!(
        "no shaft holds these {} groups of parts together, only glue: {}; glue parts {}",
        roots.len(),
        named.join(", "),
        pairs.join(", ")
    );
    (glue, Some(warning))
}

/// Every part id of the stack (islands and shafts), ascending, and the groups the shafts hold
/// together (indices into the ids).
pub(crate) fn shaft_groups(stack: &Stack) -> (Vec<u32>, UnionFind) {
    let ids = part_ids(stack);
    let index = |part: u32| ids.binary_search(&part).expect("every island is a part");
    let mut groups = UnionFind::new(ids.len());
    for shaft in &stack.shafts {
        for b in &shaft.bands {
            groups.join(index(shaft.part), index(stack.layers[b.layer].islands[b.island].part));
        }
    }
    (ids, groups)
}

/// Every part id of the stack (islands and shafts), ascending.
pub(super) fn part_ids(stack: &Stack) -> Vec<u32> {
    let mut ids: Vec<u32> = stack
        .layers
        .iter()
        .flat_map(|l| l.islands.iter().map(|i| i.part))
        .chain(stack.shafts.iter().map(|s| s.part))
        .collect();
    ids.sort_unstable();
    ids
}
