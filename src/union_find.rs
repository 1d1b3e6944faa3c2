//! One disjoint-set forest for the whole crate, as petgraph keeps one `UnionFind`.
//!
//! The room layer joins units into rooms, the route planner joins door contacts into passages,
//! and the Markov logic engine joins atoms tied by hard formulas into blocks. Each wants the
//! same thing: the sets numbered in a fixed order whatever order the unions came in, so that
//! results are deterministic. Here the smaller root always wins a union, so every set's root
//! is its smallest member.
//!
//! ```
//! use ksmcmc::union_find::UnionFind;
//! let mut sets = UnionFind::new(5);
//! sets.union(4, 2);
//! sets.union(2, 3);
//! assert_eq!((sets.find(4), sets.find(3), sets.find(1)), (2, 2, 1));
//! assert!(sets.same(3, 4) && !sets.same(0, 4));
//! ```

/// A disjoint-set forest over `0..n`, with path halving; a set's root is its smallest member.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct UnionFind {
    parent: Vec<u32>,
}

impl UnionFind {
    /// `n` singleton sets. `n` must fit in a `u32` (every caller indexes cells or atoms of
    /// structures already held in memory, far fewer).
    pub fn new(n: usize) -> UnionFind {
        assert!(n <= u32::MAX as usize, "a UnionFind holds at most u32::MAX elements");
        UnionFind { parent: (0..n as u32).collect() }
    }

    /// The number of elements.
    pub fn len(&self) -> usize {
        self.parent.len()
    }

    /// Whether there are no elements.
    pub fn is_empty(&self) -> bool {
        self.parent.is_empty()
    }

    /// The root (smallest member) of `a`'s set.
    pub fn find(&mut self, a: usize) -> usize {
        let mut a = a as u32;
        while self.parent[a as usize] != a {
            let p = self.parent[a as usize];
            self.parent[a as usize] = self.parent[p as usize];
            a = p;
        }
        a as usize
    }

    /// Joins the sets of `a` and `b`; the smaller root becomes the root of both. Returns
    /// whether they were apart.
    pub fn union(&mut self, a: usize, b: usize) -> bool {
        let (ra, rb) = (self.find(a), self.find(b));
        if ra == rb {
            return false;
        }
        let (lo, hi) = (ra.min(rb), ra.max(rb));
        self.parent[hi] = lo as u32;
        true
    }

    /// Whether `a` and `b` are in one set.
    pub fn same(&mut self, a: usize, b: usize) -> bool {
        self.find(a) == self.find(b)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Against a brute-force partition: after every union, `same` agrees with sets merged by
    /// relabelling, and each root is its set's smallest member.
    #[test]
    fn agrees_with_relabelled_sets() {
        let n = 40;
        let mut sets = UnionFind::new(n);
        let mut label: Vec<usize> = (0..n).collect();
        let mut state = 12345u64;
        for _ in 0..200 {
            state = state.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            let (a, b) = ((state >> 33) as usize % n, (state >> 45) as usize % n);
            let apart = label[a] != label[b];
            assert_eq!(sets.union(a, b), apart);
            let (from, to) = (label[a].max(label[b]), label[a].min(label[b]));
            label.iter_mut().filter(|l| **l == from).for_each(|l| *l = to);
            for x in 0..n {
                let smallest = (0..n).find(|&y| label[y] == label[x]).unwrap();
                assert_eq!(sets.find(x), smallest);
            }
        }
    }
}
