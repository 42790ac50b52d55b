//! Finding equal items among millions, fast and deterministically.
//!
//! Hashing millions of wide keys (a triangle's nine coordinates) into one table is bound by
//! cache misses. Instead each item gets a 64-bit fingerprint; (fingerprint, index) pairs are
//! sorted in parallel, and only items with equal fingerprints are compared exactly. The result
//! names, for each item, the first item equal to it, whatever the thread count.

use std::hash::{Hash, Hasher};

use rayon::prelude::*;

use crate::weld::CellHasher;

/// A 64-bit fingerprint of anything hashable (deterministic across runs and machines).
pub fn fingerprint<T: Hash + ?Sized>(item: &T) -> u64 {
    let mut h = CellHasher::default();
    item.hash(&mut h);
    h.finish()
}

/// For each item, the index of the first item equal to it (itself when it is the first).
pub fn first_equal<T: Hash + Eq + Sync + Send + Clone>(items: &[T]) -> Vec<u32> {
    let mut pairs: Vec<(u64, u32)> = items
        .par_iter()
        .enumerate()
        .map(|(i, t)| (fingerprint(t), i as u32))
        .collect();
    pairs.par_sort_unstable();
    // Gather the items in sorted order (independent loads, in parallel), so the equality
    // checks below read memory in sequence instead of jumping around.
    let sorted: Vec<T> = pairs.par_iter().map(|&(_, i)| items[i as usize].clone()).collect();
    let mut first: Vec<u32> = (0..items.len() as u32).collect();
    let mut reps: Vec<usize> = Vec::new();
    let mut start = 0;
    while start < pairs.len() {
        let fp = pairs[start].0;
        let end = start + pairs[start..].iter().take_while(|p| p.0 == fp).count();
        reps.clear();
        // Within a run indices ascend, so the first of each equal set comes first.
        for k in start..end {
            match reps.iter().find(|&&r| sorted[r] == sorted[k]) {
                Some(&r) => first[pairs[k].1 as usize] = pairs[r].1,
                None => reps.push(k),
            }
        }
        start = end;
    }
    first
}

/// Numbers the distinct items in order of first appearance: returns each item's number and
/// the index of each number's first item.
pub fn number_distinct<T: Hash + Eq + Sync + Send + Clone>(items: &[T]) -> (Vec<u32>, Vec<u32>) {
    let first = first_equal(items);
    let mut id = vec![0u32; items.len()];
    let mut firsts = Vec::new();
    for i in 0..items.len() {
        let f = first[i] as usize;
        if f == i {
            id[i] = firsts.len() as u32;
            firsts.push(i as u32);
        } else {
            id[i] = id[f];
        }
    }
    (id, firsts)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_in_order_of_first_appearance() {
        let items = [7u64, 3, 7, 9, 3, 3, 1];
        let (id, firsts) = number_distinct(&items);
        assert_eq!(id, vec![0, 1, 0, 2, 1, 1, 3]);
        assert_eq!(firsts, vec![0, 1, 3, 6]);
        assert_eq!(first_equal(&items), vec![0, 1, 0, 3, 1, 1, 6]);
    }
}
