//! Sorting through one copy of the standard library's sort, for the WebAssembly package's size.
//!
//! Every `sort_by` call site makes the compiler instantiate the standard sort for its element
//! type and comparator: one to ten kilobytes of code each time. In the browser that code is
//! downloaded before the first frame: the mapper module had 80 sort functions, 94 kB (33 kB
//! gzipped) of its 1.2 MB (BENCHMARKS.md, "The WebAssembly package"). [`sort_by`] sorts the
//! positions `0..n` with a comparator behind `dyn`, so the sort itself is in a module once,
//! and then moves the elements into that order. It is stable, as [`slice::sort_by`], so it
//! gives what `sort_by` gives, and what `sort_unstable_by` gives whenever no two elements
//! compare equal unless they are equal (integers, distinct keys). An indirect call per
//! comparison makes it somewhat slower: it is for sorts outside the chain's inner loop.
//!
//! ```
//! let mut v = vec![(2, 'a'), (1, 'b'), (2, 'c'), (0, 'd')];
//! ksmcmc::sort::sort_by_key(&mut v, |p| p.0);
//! assert_eq!(v, [(0, 'd'), (1, 'b'), (2, 'a'), (2, 'c')]);
//! ```

use std::cmp::Ordering;

/// Sorts `v` by `compare`, stably: the order `v.sort_by(compare)` gives.
pub fn sort_by<T>(v: &mut [T], mut compare: impl FnMut(&T, &T) -> Ordering) {
    let mut order: Vec<usize> = (0..v.len()).collect();
    sort_positions(&mut order, &mut |a, b| compare(&v[a], &v[b]));
    permute(v, order);
}

/// Sorts `v` by the key `key` gives, stably: the order `v.sort_by_key(key)` gives.
pub fn sort_by_key<T, K: Ord>(v: &mut [T], mut key: impl FnMut(&T) -> K) {
    sort_by(v, |a, b| key(a).cmp(&key(b)))
}

/// Sorts `v`, stably: the order `v.sort()` gives, and `v.sort_unstable()` for values that are
/// equal only when identical.
pub fn sort<T: Ord>(v: &mut [T]) {
    sort_by(v, T::cmp)
}

/// The one instantiation of the standard sort: positions, compared through `dyn`. Never
/// inlined, so that its code is not copied into each caller.
#[inline(never)]
fn sort_positions(order: &mut [usize], compare: &mut dyn FnMut(usize, usize) -> Ordering) {
    order.sort_by(|&a, &b| compare(a, b));
}

/// Puts `v[order[i]]` at `i` for every `i`, following the permutation's cycles with swaps.
fn permute<T>(v: &mut [T], mut order: Vec<usize>) {
    for start in 0..v.len() {
        let mut at = start;
        // A cycle start -> order[start] -> ... -> start; each element placed is marked done
        // (order[i] == i), so a later start skips it.
        while order[at] != start && order[at] != at {
            let next = order[at];
            v.swap(at, next);
            order[at] = at;
            at = next;
        }
        order[at] = at;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sorts_as_the_standard_stable_sort_does() {
        let mut x = 0x2545_f491_4f6c_dd1d_u64;
        for n in [0, 1, 2, 3, 7, 20, 33, 500] {
            let mut v: Vec<(u8, usize)> = (0..n)
                .map(|i| {
                    x ^= x << 13;
                    x ^= x >> 7;
                    x ^= x << 17;
                    ((x % 5) as u8, i)
                })
                .collect();
            let mut want = v.clone();
            want.sort_by_key(|p| p.0);
            sort_by_key(&mut v, |p| p.0);
            assert_eq!(v, want, "n = {n}: ties keep their order");
            let mut w: Vec<u64> = v.iter().map(|p| p.1 as u64 * 7919 % 101).collect();
            let mut unstable = w.clone();
            unstable.sort_unstable();
            sort(&mut w);
            assert_eq!(w, unstable);
            sort_by(&mut w, |a, b| b.cmp(a));
            assert!(w.windows(2).all(|p| p[0] >= p[1]));
        }
    }

    #[test]
    fn permutes_every_cycle() {
        let mut v = vec!['a', 'b', 'c', 'd', 'e', 'f'];
        permute(&mut v, vec![2, 0, 1, 5, 4, 3]);
        assert_eq!(v, ['c', 'a', 'b', 'f', 'e', 'd']);
    }
}
