//! MaxWalkSAT (Kautz, Selman and Jiang 1997), with hard clauses first.
//!
//! Local search for the world of largest `sum_i w_i n_i(x)`: pick an unsatisfied clause (a
//! hard one while any is unsatisfied, else a soft one), and flip either a random atom of it
//! (with probability `noise`) or the atom whose flip leaves the best world. Worlds are
//! compared by the number of violated hard features first, the unsatisfied soft weight
//! second, so no amount of soft weight buys a hard violation. The best world seen over all
//! tries is returned; the search stops early once nothing is unsatisfied.

use super::{Counts, MapConfig};
use crate::mcmc::Rng;
use crate::mln::error::{ErrorKind, MlnError};
use crate::mln::ground::Network;

/// Unsatisfied clauses of one kind, with O(1) insertion and removal.
struct ClauseSet {
    list: Vec<u32>,
    pos: Vec<u32>,
}

impl ClauseSet {
    fn new(n: usize) -> Self {
        ClauseSet { list: Vec::new(), pos: vec![u32::MAX; n] }
    }

    fn insert(&mut self, c: usize) {
        self.pos[c] = self.list.len() as u32;
        self.list.push(c as u32);
    }

    fn remove(&mut self, c: usize) {
        let i = self.pos[c] as usize;
        let last = self.list.pop().unwrap();
        if last as usize != c {
            self.list[i] = last;
            self.pos[last as usize] = i as u32;
        }
        self.pos[c] = u32::MAX;
    }

    fn clear(&mut self) {
        for &c in &self.list {
            self.pos[c as usize] = u32::MAX;
        }
        self.list.clear();
    }
}

struct Search<'a> {
    counts: Counts<'a>,
    hard: ClauseSet,
    soft: ClauseSet,
    /// Unsatisfied soft weight.
    cost: f64,
}

impl<'a> Search<'a> {
    fn new(net: &'a Network, state: Vec<bool>) -> Self {
        let mut s = Search {
            counts: Counts::new(net, vec![false; state.len()]),
            hard: ClauseSet::new(net.clause_count()),
            soft: ClauseSet::new(net.clause_count()),
            cost: 0.0,
        };
        s.reset(state);
        s
    }

    fn reset(&mut self, state: Vec<bool>) {
        let net = self.counts.net;
        self.counts = Counts::new(net, state);
        self.hard.clear();
        self.soft.clear();
        self.cost = 0.0;
        for c in 0..net.clause_count() {
            if self.counts.true_count[c] == 0 {
                self.set_for(c).insert(c);
            }
        }
        for f in 0..net.feature_count() {
            if self.counts.unsat[f] > 0 && net.feature_weight[f].is_finite() {
                self.cost += net.feature_weight[f];
            }
        }
    }

    fn set_for(&mut self, c: usize) -> &mut ClauseSet {
        let net = self.counts.net;
        if net.feature_weight[net.clause_feature[c] as usize].is_infinite() {
            &mut self.hard
        } else {
            &mut self.soft
        }
    }

    fn flip(&mut self, a: usize) {
        let net = self.counts.net;
        let (hard, soft) = (&mut self.hard, &mut self.soft);
        self.counts.flip_with(a, |c, now_sat| {
            let set =
                if net.feature_weight[net.clause_feature[c] as usize].is_infinite() { &mut *hard } else { &mut *soft };
            if now_sat {
                set.remove(c);
            } else {
                set.insert(c);
            }
        });
    }

    /// Flips a chosen atom of a random unsatisfied clause from `hard` (or `soft` if false).
    fn step(&mut self, from_hard: bool, noise: f64, hard_only: bool, rng: &mut Rng) {
        let set = if from_hard { &self.hard } else { &self.soft };
        let c = set.list[rng.below(set.list.len() as u32) as usize] as usize;
        let net = self.counts.net;
        let lits = net.clause_lits(c);
        let a = if rng.uniform() < noise {
            (lits[rng.below(lits.len() as u32) as usize] >> 1) as usize
        } else {
            let mut best = (i32::MAX, f64::NEG_INFINITY, 0usize);
            for &l in lits {
                let a = (l >> 1) as usize;
                let (dh, ds) = self.counts.delta(a);
                let ds = if hard_only { 0.0 } else { ds };
                if dh < best.0 || (dh == best.0 && ds > best.1) {
                    best = (dh, ds, a);
                }
            }
            best.2
        };
        let (_, ds) = self.counts.delta(a);
        self.flip(a);
        self.cost -= ds;
    }
}

/// The best world found: fewest violated hard features, then least unsatisfied soft weight.
pub(crate) fn maxwalksat(net: &Network, config: &MapConfig, rng: &mut Rng) -> Result<Vec<bool>, MlnError> {
    let n = net.atom_count();
    let random = |rng: &mut Rng| (0..n).map(|_| rng.uniform() < 0.5).collect::<Vec<bool>>();
    let mut search = Search::new(net, random(rng));
    let mut best_state = search.counts.value.clone();
    let mut best = (search.counts.hard_unsat, search.cost);
    'tries: for t in 0..config.tries {
        if t > 0 {
            search.reset(random(rng));
        }
        for _ in 0..config.max_flips {
            let current = (search.counts.hard_unsat, search.cost);
            if current.0 < best.0 || (current.0 == best.0 && current.1 < best.1 - 1e-9) {
                best = current;
                best_state.clone_from(&search.counts.value);
            }
            if search.hard.list.is_empty() && search.soft.list.is_empty() {
                break 'tries; // everything satisfied: optimal
            }
            let from_hard = !search.hard.list.is_empty();
            search.step(from_hard, config.noise, false, rng);
        }
        let current = (search.counts.hard_unsat, search.cost);
        if current.0 < best.0 || (current.0 == best.0 && current.1 < best.1 - 1e-9) {
            best = current;
            best_state.clone_from(&search.counts.value);
        }
    }
    if best.0 > 0 {
        return Err(MlnError::new(
            ErrorKind::NoSatisfyingWorld { flips: config.max_flips * config.tries as u64 },
            None,
        ));
    }
    Ok(best_state)
}

/// A random world satisfying every hard feature: WalkSAT on the hard clauses only.
pub(crate) fn walksat_hard(net: &Network, max_flips: u64, rng: &mut Rng) -> Result<Vec<bool>, MlnError> {
    let n = net.atom_count();
    let state: Vec<bool> = (0..n).map(|_| rng.uniform() < 0.5).collect();
    let mut search = Search::new(net, state);
    let mut flips = 0;
    while !search.hard.list.is_empty() {
        if flips == max_flips {
            return Err(MlnError::new(ErrorKind::NoSatisfyingWorld { flips }, None));
        }
        search.step(true, 0.5, true, rng);
        flips += 1;
    }
    Ok(search.counts.value)
}
