//! Groups of parts held together by joints.

/// Groups of parts joined by joints, or of anything joined pairwise (union–find with path
/// halving).
pub(crate) struct UnionFind(Vec<usize>);

impl UnionFind {
    /// Every part in a group of its own.
    pub(crate) fn new(n: usize) -> Self {
        Self((0..n).collect())
    }
    /// The group of `i`: its lowest member.
    pub(crate) fn root(&mut self, mut i: usize) -> usize {
        while self.0[i] != i {
            self.0[i] = self.0[self.0[i]];
            i = self.0[i];
        }
        i
    }
    /// Puts the groups of `a` and `b` together.
    pub(crate) fn join(&mut self, a: usize, b: usize) {
        let (ra, rb) = (self.root(a), self.root(b));
        if ra != rb {
            self.0[ra.max(rb)] = ra.min(rb);
        }
    }
}
