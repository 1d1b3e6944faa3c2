//! MC-SAT (Poon and Domingos 2006): slice sampling over the satisfied features.
//!
//! Each step keeps every feature the current world satisfies with probability
//! `1 - exp(-w)` (hard features always), then draws a new world that satisfies all kept
//! features, uniformly. Near-deterministic dependencies, which trap Gibbs sampling, are no
//! obstacle: the kept set changes every step.
//!
//! The uniform draw is the crux. [`SliceMoves::Uniform`] (the default) starts from the current
//! world, which satisfies the kept features, and redraws every atom uniformly among the values
//! that keep all kept clauses satisfied: SampleSAT's annealing moves at temperature zero, made
//! systematic. Atoms tied by hard features (with `SaLe(p,q) => SaLe(q,p)` hard, one atom of a
//! pair cannot change alone) are redrawn jointly, as a block. Each move leaves the uniform
//! distribution on the slice invariant, so the chain has exactly the network's distribution.
//!
//! [`SliceMoves::SampleSat`] is Poon and Domingos' SampleSAT: a fixed number of moves, each a
//! WalkSAT move (with some probability, while a kept clause is unsatisfied) or a simulated-
//! annealing move, and WalkSAT to finish on the slice. Its draws are not quite uniform, so its
//! marginals carry a bias.
//!
//! Each step is followed by `gibbs_sweeps` sweeps of Gibbs sampling (default one). Both kinds
//! of move leave the network's distribution invariant, so the mixture does too; MC-SAT crosses
//! deterministic structure, Gibbs mixes locally where a slice pins atoms down (a selected
//! multi-clause feature such as a grounded `FORALL` lets single atoms move only in concert).
//! On the smokers example this cuts the error at equal samples several-fold.
//!
//! Estimates are Rao-Blackwellised: after each step every atom (every block) adds its
//! conditional probability of being true given the rest, under the network's distribution,
//! rather than its sampled value. This is unbiased for any chain with the right stationary
//! distribution and removes most of the variance.

use super::gibbs::{self, add_block_marginals, enumerate_block, move_block};
use super::{hard_blocks, satisfy_hard, Counts, InferenceConfig, SliceMoves};
use crate::mcmc::Rng;
use crate::mln::error::MlnError;
use crate::mln::ground::Network;

/// Largest clause-count change with a precomputed acceptance probability.
const TABLE: usize = 32;

pub(crate) fn marginals(net: &Network, config: &InferenceConfig, rng: &mut Rng) -> Result<Vec<f64>, MlnError> {
    let n = net.atom_count();
    if n == 0 {
        return Ok(Vec::new());
    }
    let blocks = hard_blocks(net, config.max_block);
    let widest = blocks.iter().map(Vec::len).max().unwrap_or(1);
    let mut weights = vec![0.0f64; 1 << widest];
    let mut sums = vec![0.0f64; n];
    run(net, config, rng, |counts| {
        for block in &blocks {
            if let [a] = block[..] {
                sums[a as usize] += counts.conditional(a as usize);
            } else {
                let (here, z) = enumerate_block(counts, block, &mut weights);
                add_block_marginals(counts, block, &weights[..1 << block.len()], z, here, &mut sums);
                move_block(counts, block, here, 0);
            }
        }
    })?;
    let m = config.samples as f64;
    Ok(sums.into_iter().map(|c| (c / m).clamp(0.0, 1.0)).collect())
}

/// Runs the chain: `config.burn_in` steps, then `config.samples` steps after each of which
/// `visit` sees the world (and must leave it as it found it).
pub(crate) fn run(
    net: &Network,
    config: &InferenceConfig,
    rng: &mut Rng,
    mut visit: impl FnMut(&mut Counts),
) -> Result<(), MlnError> {
    if net.atom_count() == 0 {
        for _ in 0..config.samples {
            visit(&mut Counts::new(net, Vec::new()));
        }
        return Ok(());
    }
    let start = satisfy_hard(net, config.walksat_flips, rng)?;
    let n = net.atom_count();
    let mut s = Slice::new(net, start, config);
    let keep: Vec<f64> =
        net.feature_weight.iter().map(|&w| if w.is_infinite() { 1.0 } else { -libm::expm1(-w) }).collect();
    let blocks = hard_blocks(net, config.max_block);
    let widest = blocks.iter().map(Vec::len).max().unwrap_or(1);
    let mut valid = vec![false; 1 << widest];
    let mut weights = vec![0.0f64; 1 << widest];
    for it in 0..config.burn_in as u64 + config.samples as u64 {
        s.select(&keep, rng);
        match config.slice {
            SliceMoves::Uniform => s.sweep(&blocks, &mut valid, rng),
            SliceMoves::SampleSat { steps, .. } => {
                s.sample_sat(if steps > 0 { steps as usize } else { (2 * n).max(20) }, rng)
            }
        }
        for _ in 0..config.gibbs_sweeps {
            gibbs::sweep(&mut s.counts, &blocks, &mut weights, &mut [], false, rng);
        }
        if it >= config.burn_in as u64 {
            visit(&mut s.counts);
        }
    }
    Ok(())
}

struct Slice<'a> {
    counts: Counts<'a>,
    /// Clauses kept this step.
    selected: Vec<bool>,
    selected_list: Vec<u32>,
    /// Kept clauses now unsatisfied, and each clause's position in that list.
    unsat: Vec<u32>,
    unsat_pos: Vec<u32>,
    /// Atoms flipped in the current SampleSAT run.
    flipped: Vec<u32>,
    /// `exp(-d / T)` for annealing moves that break `d` kept clauses.
    accept: [f64; TABLE + 1],
    walk: f64,
}

impl<'a> Slice<'a> {
    fn new(net: &'a Network, start: Vec<bool>, config: &InferenceConfig) -> Self {
        let (temperature, walk) = match config.slice {
            SliceMoves::Uniform => (1.0, 0.0),
            SliceMoves::SampleSat { temperature, walksat_probability, .. } => (temperature, walksat_probability),
        };
        let mut accept = [0.0; TABLE + 1];
        for (d, p) in accept.iter_mut().enumerate() {
            *p = libm::exp(-(d as f64) / temperature);
        }
        Slice {
            counts: Counts::new(net, start),
            selected: vec![false; net.clause_count()],
            selected_list: Vec::new(),
            unsat: Vec::new(),
            unsat_pos: vec![u32::MAX; net.clause_count()],
            flipped: Vec::new(),
            accept,
            walk,
        }
    }

    /// Keeps each satisfied feature with probability `keep[f]`.
    fn select(&mut self, keep: &[f64], rng: &mut Rng) {
        for &c in &self.selected_list {
            self.selected[c as usize] = false;
        }
        self.selected_list.clear();
        let net = self.counts.net;
        for (f, &p) in keep.iter().enumerate() {
            if self.counts.unsat[f] == 0 && (p >= 1.0 || rng.uniform() < p) {
                for c in net.clauses_of(f) {
                    self.selected[c] = true;
                    self.selected_list.push(c as u32);
                }
            }
        }
    }

    /// Change in unsatisfied kept clauses if atom `a` flips.
    #[inline]
    fn delta(&self, a: usize) -> i32 {
        let v = self.counts.value[a];
        let mut d = 0;
        for &o in self.counts.net.occurrences(a) {
            let c = (o >> 1) as usize;
            if !self.selected[c] {
                continue;
            }
            let tc = self.counts.true_count[c];
            if v != (o & 1 == 1) {
                d += (tc == 1) as i32;
            } else {
                d -= (tc == 0) as i32;
            }
        }
        d
    }

    /// One sweep of moves within the slice: each block of atoms is redrawn uniformly among its
    /// values that keep every kept clause satisfied.
    fn sweep(&mut self, blocks: &[Vec<u32>], valid: &mut [bool], rng: &mut Rng) {
        for block in blocks {
            if let [a] = block[..] {
                let a = a as usize;
                if self.delta(a) == 0 && rng.uniform() < 0.5 {
                    self.counts.flip(a);
                }
                continue;
            }
            let states = 1usize << block.len();
            let mut d = 0;
            valid[0] = true;
            let mut count = 1u32;
            for (i, ok) in valid.iter_mut().enumerate().take(states).skip(1) {
                let a = block[i.trailing_zeros() as usize] as usize;
                d += self.delta(a);
                self.counts.flip(a);
                *ok = d == 0;
                count += *ok as u32;
            }
            let mut r = rng.below(count);
            let mut pick = 0;
            for (i, &ok) in valid[..states].iter().enumerate() {
                if ok {
                    if r == 0 {
                        pick = i;
                        break;
                    }
                    r -= 1;
                }
            }
            move_block(&mut self.counts, block, (states - 1) ^ ((states - 1) >> 1), pick);
        }
    }

    /// Flips an atom during SampleSAT, keeping the list of unsatisfied kept clauses.
    fn flip_tracked(&mut self, a: usize) {
        let (selected, unsat, pos) = (&self.selected, &mut self.unsat, &mut self.unsat_pos);
        self.counts.flip_with(a, |c, now_sat| {
            if !selected[c] {
                return;
            }
            if now_sat {
                let i = pos[c] as usize;
                let last = unsat.pop().unwrap();
                if last as usize != c {
                    unsat[i] = last;
                    pos[last as usize] = i as u32;
                }
                pos[c] = u32::MAX;
            } else {
                pos[c] = unsat.len() as u32;
                unsat.push(c as u32);
            }
        });
        self.flipped.push(a as u32);
    }

    /// One SampleSAT run of `steps` moves from the current world (on the slice). Ends on the
    /// slice: finished by WalkSAT if it uses WalkSAT moves, otherwise rejected (back to the
    /// starting world) if it ends off the slice.
    fn sample_sat(&mut self, steps: usize, rng: &mut Rng) {
        let n = self.counts.value.len() as u32;
        self.flipped.clear();
        for _ in 0..steps {
            if self.walk > 0.0 && !self.unsat.is_empty() && rng.uniform() < self.walk {
                self.walksat_move(rng);
                continue;
            }
            let a = rng.below(n) as usize;
            let d = self.delta(a);
            if d <= 0 || rng.uniform() < self.accept[(d as usize).min(TABLE)] {
                self.flip_tracked(a);
            }
        }
        if self.walk > 0.0 {
            let mut budget = 100 * steps;
            while !self.unsat.is_empty() && budget > 0 {
                self.walksat_move(rng);
                budget -= 1;
            }
        }
        if !self.unsat.is_empty() {
            let mut undo = std::mem::take(&mut self.flipped);
            while let Some(a) = undo.pop() {
                self.flip_tracked(a as usize);
            }
            self.flipped = undo;
        }
    }

    /// WalkSAT: in a random unsatisfied kept clause, flip a random atom (half the time) or the
    /// one that leaves the fewest kept clauses unsatisfied.
    fn walksat_move(&mut self, rng: &mut Rng) {
        let c = self.unsat[rng.below(self.unsat.len() as u32) as usize] as usize;
        let lits = self.counts.net.clause_lits(c);
        let a = if rng.uniform() < 0.5 {
            (lits[rng.below(lits.len() as u32) as usize] >> 1) as usize
        } else {
            let mut best = (i32::MAX, 0usize);
            for &l in lits {
                let a = (l >> 1) as usize;
                let d = self.delta(a);
                if d < best.0 {
                    best = (d, a);
                }
            }
            best.1
        };
        self.flip_tracked(a);
    }
}
