//! Keeping part of a stack, numbered after other parts.
//!
//! The classifier's `layers` step builds a stack among plates and keeps only the groups of
//! layers its shafts hold to a plate: a group nothing holds could not be put in place. What is
//! left must read as a stack built that way: islands indexed densely per layer (shafts and
//! unjoined pairs and bosses point at them by index) and part ids numbered without gaps, bottom layer
//! first, then the shafts, as [`super::assemble`] numbers them.

use std::collections::BTreeMap;

use super::Stack;

impl Stack {
    /// Keeps the islands and shafts whose part ids `keep` accepts; a kept shaft loses its slots
    /// in islands not kept, and goes when it has none left.
    pub(crate) fn retain_parts(&mut self, keep: impl Fn(u32) -> bool) {
        let mut new_index: Vec<Vec<Option<usize>>> = Vec::with_capacity(self.layers.len());
        for layer in &mut self.layers {
            let mut map = Vec::with_capacity(layer.islands.len());
            let mut next = 0;
            for island in &layer.islands {
                map.push(keep(island.part).then(|| {
                    next += 1;
                    next - 1
                }));
            }
            layer.islands.retain(|i| keep(i.part));
            new_index.push(map);
        }
        for shaft in &mut self.shafts {
            shaft.bands.retain_mut(|band| match new_index[band.layer][band.island] {
                Some(i) => {
                    band.island = i;
                    true
                }
                None => false,
            });
        }
        self.shafts.retain(|s| keep(s.part) && !s.bands.is_empty());
        let kept = |k: usize, lower: &mut usize, upper: &mut usize| {
            let pair = new_index[k][*lower].zip(new_index[k + 1][*upper]);
            pair.inspect(|&p| (*lower, *upper) = p).is_some()
        };
        self.unjoined.retain_mut(|u| kept(u.layer, &mut u.lower, &mut u.upper));
        self.bosses.retain_mut(|b| kept(b.layer, &mut b.lower, &mut b.upper));
    }

    /// Numbers the parts from `first` on (islands bottom up, then shafts); returns each old id's
    /// new one.
    pub(crate) fn number_from(&mut self, first: u32) -> BTreeMap<u32, u32> {
        let mut map = BTreeMap::new();
        let islands = self
            .layers
            .iter_mut()
            .flat_map(|l| l.islands.iter_mut())
            .map(|i| &mut i.part);
        for (next, part) in (first..).zip(islands.chain(self.shafts.iter_mut().map(|s| &mut s.part))) {
            map.insert(*part, next);
            *part = next;
        }
        map
    }

    /// Removes layer `k`, which has no island left: the layers above move down one index (and
    /// the stack's frame up one layer when it is the bottom one).
    pub(crate) fn remove_layer(&mut self, k: usize) {
        debug_assert!(self.layers[k].islands.is_empty());
        self.layers.remove(k);
        self.plan.count -= 1;
        if k == 0 {
            self.plan.frame = self.plan.frame.shifted(self.plan.thickness);
        }
        let down = |layer: &mut usize| {
            if *layer > k {
                *layer -= 1;
            }
        };
        for shaft in &mut self.shafts {
            shaft.bands.iter_mut().for_each(|b| down(&mut b.layer));
        }
        self.unjoined.retain(|u| u.layer != k && u.layer + 1 != k);
        self.unjoined.iter_mut().for_each(|u| down(&mut u.layer));
        self.bosses.retain(|b| b.layer != k && b.layer + 1 != k);
        self.bosses.iter_mut().for_each(|b| down(&mut b.layer));
        self.dropped.iter_mut().for_each(|d| down(&mut d.layer));
        self.kept_small.iter_mut().for_each(|s| down(&mut s.layer));
        for (i, layer) in self.layers.iter_mut().enumerate() {
            layer.number = i as u32 + 1;
            layer.z = self.plan.bottom(i);
        }
    }
}

#[cfg(test)]
mod tests {
    use glam::DVec3;

    use super::super::assemble::assemble;
    use super::super::shafts::place;
    use super::super::{AxisChoice, SlicePlan, Stack, islands_of, slice};
    use crate::mesh::Mesh;
    use crate::settings::StackedSettings;
    use crate::weld::weld_soup;
    use platener_fixtures::samples::two_bodies;

    /// The stack of two separate bodies (a sphere and a torus), 3 mm layers along z.
    fn two_stacks() -> Stack {
        let w = weld_soup(&two_bodies(20.0), 0.0);
        let mesh = Mesh::build(w.vertices, &w.triangles, 1e-9);
        let plan = SlicePlan::new(&mesh, DVec3::Z, AxisChoice::Given, 3.0).expect("triangles");
        let sliced = slice(&mesh, &plan, 1e-6);
        let settings = StackedSettings::default();
        let islands = islands_of(&sliced, &super::super::island_rule(3.0, &settings)).expect("on the grid");
        let placed = place(&islands.islands, &settings, 3.0).expect("on the grid");
        assemble(plan, 3.0, islands, placed, sliced.stats).expect("on the grid")
    }

    /// Every band and unjoined pair names an island that exists.
    fn assert_consistent(stack: &Stack) {
        for shaft in &stack.shafts {
            assert!(!shaft.bands.is_empty());
            for b in &shaft.bands {
                assert!(b.island < stack.layers[b.layer].islands.len(), "{b:?}");
            }
        }
        for u in &stack.unjoined {
            assert!(u.lower < stack.layers[u.layer].islands.len());
            assert!(u.upper < stack.layers[u.layer + 1].islands.len());
        }
        for b in &stack.bosses {
            assert!(b.lower < stack.layers[b.layer].islands.len());
            assert!(b.upper < stack.layers[b.layer + 1].islands.len());
        }
        for (k, layer) in stack.layers.iter().enumerate() {
            assert_eq!(layer.number, k as u32 + 1);
            assert!((layer.z - stack.plan.bottom(k)).abs() < 1e-12);
        }
    }

    #[test]
    fn keeping_one_body_keeps_its_islands_and_shafts_indexed_and_numbered_densely() {
        let mut stack = two_stacks();
        // The sphere lies at model x < 30, the torus beyond 50.
        let split = stack.plan.frame.to_local(DVec3::new(40.0, 0.0, 0.0)).x;
        let torus: Vec<u32> = stack
            .layers
            .iter()
            .flat_map(|l| &l.islands)
            .filter(|i| i.outline.bounds().0.x > split)
            .map(|i| i.part)
            .collect();
        let islands_before: usize = stack.layers.iter().map(|l| l.islands.len()).sum();
        let shafts_before = stack.shafts.len();
        let torus_shafts: Vec<u32> = stack
            .shafts
            .iter()
            .filter(|s| {
                s.bands
                    .iter()
                    .all(|b| torus.contains(&stack.layers[b.layer].islands[b.island].part))
            })
            .map(|s| s.part)
            .collect();
        assert!(!torus.is_empty() && !torus_shafts.is_empty());
        stack.retain_parts(|p| !torus.contains(&p) && !torus_shafts.contains(&p));
        let islands_after: usize = stack.layers.iter().map(|l| l.islands.len()).sum();
        assert_eq!(islands_after, islands_before - torus.len());
        assert_eq!(stack.shafts.len(), shafts_before - torus_shafts.len());
        assert_consistent(&stack);
        assert!(
            stack
                .layers
                .iter()
                .flat_map(|l| &l.islands)
                .all(|i| i.outline.bounds().1.x < split)
        );
        let map = stack.number_from(100);
        let ids = super::super::glued::part_ids(&stack);
        assert_eq!(map.len(), ids.len());
        assert_eq!(ids, (100..100 + map.len() as u32).collect::<Vec<_>>());
    }

    #[test]
    fn removing_an_emptied_bottom_layer_moves_the_stack_up_one_layer() {
        let mut stack = two_stacks();
        let (count, origin) = (stack.layers.len(), stack.plan.frame.origin);
        let bottom: Vec<u32> = stack.layers[0].islands.iter().map(|i| i.part).collect();
        stack.retain_parts(|p| !bottom.contains(&p));
        stack.remove_layer(0);
        assert_eq!(stack.layers.len(), count - 1);
        assert_eq!(stack.plan.count, count - 1);
        assert!((stack.plan.frame.origin - (origin + DVec3::Z * 3.0)).length() < 1e-12);
        assert_consistent(&stack);
    }
}
