//! Disjoint sets (union-find) over `0..n`: the one implementation behind every
//! grouping of qmesh (vertex orbits of a file, components, regions of cells).
//!
//! A set is named by its smallest element: a union always hangs the larger root under
//! the smaller one, so every parent is at most its child and each root is the minimum
//! of its set. The names therefore do not depend on the order of the unions, which
//! lets [`SharedDisjointSets`] join sets on many threads and still give the result of
//! one thread.

use std::sync::atomic::{AtomicU32, Ordering::Relaxed};

/// Disjoint sets over `0..n`, each named by its smallest element.
#[derive(Clone, Debug)]
pub(crate) struct DisjointSets {
    parent: Vec<u32>,
}

impl DisjointSets {
    /// `n` sets of one element each.
    pub(crate) fn new(n: usize) -> Self {
        assert!(n <= u32::MAX as usize, "disjoint sets hold u32 elements");
        DisjointSets { parent: (0..n as u32).collect() }
    }

    /// Back to `n` sets of one element each (keeping the memory).
    pub(crate) fn reset(&mut self, n: usize) {
        assert!(n <= u32::MAX as usize, "disjoint sets hold u32 elements");
        self.parent.clear();
        self.parent.extend(0..n as u32);
    }

    /// The smallest element of the set of `x` (halving the path on the way).
    pub(crate) fn find(&mut self, mut x: u32) -> u32 {
        while self.parent[x as usize] != x {
            let up = self.parent[self.parent[x as usize] as usize];
            self.parent[x as usize] = up;
            x = up;
        }
        x
    }

    /// Joins the sets of `a` and `b`; whether they were apart.
    pub(crate) fn union(&mut self, a: u32, b: u32) -> bool {
        let (ra, rb) = (self.find(a), self.find(b));
        if ra == rb {
            return false;
        }
        self.parent[ra.max(rb) as usize] = ra.min(rb);
        true
    }
}

/// [`DisjointSets`] that many threads join at once (lock-free: a root is hung under
/// another by compare-and-swap, retried when another thread moved it first). Once the
/// threads are done, every set has the name one thread would have given it.
#[derive(Debug)]
pub(crate) struct SharedDisjointSets {
    parent: Vec<AtomicU32>,
}

impl SharedDisjointSets {
    /// `n` sets of one element each.
    pub(crate) fn new(n: usize) -> Self {
        assert!(n <= u32::MAX as usize, "disjoint sets hold u32 elements");
        SharedDisjointSets { parent: (0..n as u32).map(AtomicU32::new).collect() }
    }

    /// The smallest element of the set of `x` as far as the unions done so far go.
    pub(crate) fn find(&self, mut x: u32) -> u32 {
        loop {
            let up = self.parent[x as usize].load(Relaxed);
            if up == x {
                return x;
            }
            // Path halving: `x` may skip to its grandparent, which is in its set and
            // smaller still (a failed swap only means another thread moved it first).
            let grand = self.parent[up as usize].load(Relaxed);
            if grand != up {
                let _ = self.parent[x as usize].compare_exchange_weak(up, grand, Relaxed, Relaxed);
            }
            x = grand;
        }
    }

    /// Joins the sets of `a` and `b`.
    pub(crate) fn union(&self, a: u32, b: u32) {
        let (mut a, mut b) = (a, b);
        loop {
            (a, b) = (self.find(a), self.find(b));
            if a == b {
                return;
            }
            let (low, high) = (a.min(b), a.max(b));
            // `high` stays a root until hung: if another thread hung it first, retry
            // from the roots it leads to.
            if self.parent[high as usize].compare_exchange(high, low, Relaxed, Relaxed).is_ok() {
                return;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rayon::prelude::*;

    /// Pairs of a pseudo-random graph on `n` elements.
    fn links(n: u32, count: usize, seed: u64) -> Vec<(u32, u32)> {
        let mut r = crate::random::SplitMix64(seed);
        (0..count).map(|_| ((r.next_u64() % u64::from(n)) as u32, (r.next_u64() % u64::from(n)) as u32)).collect()
    }

    /// The smallest element reachable from each element, by a plain graph search.
    fn smallest_reachable(n: u32, links: &[(u32, u32)]) -> Vec<u32> {
        let mut around = vec![Vec::new(); n as usize];
        for &(a, b) in links {
            around[a as usize].push(b);
            around[b as usize].push(a);
        }
        let mut name = vec![u32::MAX; n as usize];
        for start in 0..n {
            if name[start as usize] != u32::MAX {
                continue;
            }
            // Elements are met in increasing order of their first one: `start` is the
            // smallest of its set.
            let mut stack = vec![start];
            name[start as usize] = start;
            while let Some(x) = stack.pop() {
                for &y in &around[x as usize] {
                    if name[y as usize] == u32::MAX {
                        name[y as usize] = start;
                        stack.push(y);
                    }
                }
            }
        }
        name
    }

    #[test]
    fn sets_are_named_by_their_smallest_element_whatever_the_order_of_unions() {
        for seed in 0..20 {
            let n = 2000;
            let mut pairs = links(n, 1500, seed);
            let expected = smallest_reachable(n, &pairs);
            let mut one = DisjointSets::new(n as usize);
            let apart = pairs.iter().filter(|&&(a, b)| one.union(a, b)).count();
            assert_eq!((0..n).map(|x| one.find(x)).collect::<Vec<_>>(), expected);
            let sets = (0..n).filter(|&x| expected[x as usize] == x).count();
            assert_eq!(apart, n as usize - sets, "each union that joins two sets makes one set fewer");
            pairs.reverse();
            let shared = SharedDisjointSets::new(n as usize);
            pairs.par_iter().with_max_len(16).for_each(|&(a, b)| shared.union(a, b));
            assert_eq!((0..n).map(|x| shared.find(x)).collect::<Vec<_>>(), expected, "seed {seed}");
        }
    }

    /// Many threads hanging roots of the same sets at once: a chain joined from both
    /// ends and from the middle.
    #[test]
    fn threads_joining_the_same_sets_agree() {
        let n = 100_000u32;
        let shared = SharedDisjointSets::new(n as usize);
        let order: Vec<u32> = (0..n - 1).map(|k| if k % 2 == 0 { k / 2 } else { n - 2 - k / 2 }).collect();
        order.par_iter().with_max_len(64).for_each(|&k| shared.union(k, k + 1));
        assert!((0..n).all(|x| shared.find(x) == 0));
    }
}
