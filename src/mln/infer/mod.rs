//! Inference on a ground network: marginals (exact, MC-SAT, Gibbs) and the most probable
//! world (MaxWalkSAT, exact).
//!
//! All methods share one piece of bookkeeping, [`Counts`]: per clause the number of true
//! literals, per feature the number of unsatisfied clauses. Flipping an atom touches only the
//! clauses it occurs in, so a flip and the change in log weight it causes cost time in
//! proportion to the atom's degree, not the network's size.

mod exact;
mod gibbs;
mod junction;
mod maxwalksat;
mod mcsat;

use super::error::{ErrorKind, MlnError, UnknownMethod};
use super::ground::{Network, QueryValue};
use super::kb::GroundAtom;
use crate::mcmc::Rng;

/// MC-SAT's chain, visiting each sampled world (weight learning estimates counts with it).
pub(crate) use mcsat::run as mcsat_run;

/// How to compute marginals.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Method {
    /// Exact if the junction tree's cliques have at most [`AUTO_EXACT_ATOMS`] atoms, MC-SAT
    /// otherwise.
    Auto,
    /// Exact: sum-product on a junction tree (variable elimination in min-fill order) if its
    /// cliques have at most `max_exact_atoms` atoms, else enumeration of each connected part
    /// of at most `max_exact_atoms` atoms; an error if neither fits.
    Exact,
    /// Exact, by enumerating all worlds of each connected part (Gray-code order, incremental
    /// weights); refuses parts of more than `max_exact_atoms` unknown atoms.
    Enumerate,
    /// MC-SAT (Poon and Domingos 2006): slice sampling with SampleSAT.
    McSat,
    /// Gibbs sampling, blocked over atoms tied by hard formulas, Rao-Blackwellised.
    Gibbs,
}

/// [`Method::Auto`] is exact when the junction tree's cliques have at most this many atoms.
pub const AUTO_EXACT_ATOMS: usize = 16;

impl std::str::FromStr for Method {
    type Err = UnknownMethod;
    fn from_str(s: &str) -> Result<Self, UnknownMethod> {
        match s {
            "auto" => Ok(Method::Auto),
            "exact" => Ok(Method::Exact),
            "enumerate" => Ok(Method::Enumerate),
            "mcsat" | "mc-sat" => Ok(Method::McSat),
            "gibbs" => Ok(Method::Gibbs),
            _ => Err(UnknownMethod::new(s, "inference method", "auto, exact, enumerate, mcsat or gibbs")),
        }
    }
}

/// Parameters of marginal inference.
#[derive(Debug, Clone)]
pub struct InferenceConfig {
    /// The method.
    pub method: Method,
    /// Seed of the random number generator; equal seeds give equal results.
    pub seed: u64,
    /// Samples averaged: MC-SAT steps, or Gibbs sweeps over all atoms.
    pub samples: u32,
    /// Steps (sweeps) discarded before averaging.
    pub burn_in: u32,
    /// Exact inference refuses junction-tree cliques, and enumerated connected parts, with more
    /// unknown atoms than this (2^n table entries or worlds).
    pub max_exact_atoms: usize,
    /// MC-SAT: how to draw a world from the slice.
    pub slice: SliceMoves,
    /// MC-SAT: Gibbs sweeps interleaved after each MC-SAT step (0: pure MC-SAT). Both leave
    /// the distribution invariant; the Gibbs sweeps speed up local mixing.
    pub gibbs_sweeps: u32,
    /// Gibbs: atoms tied together by hard formulas are sampled jointly in blocks of up to this
    /// many atoms (2^n states each); larger groups fall back to single-atom moves.
    pub max_block: usize,
    /// Flips WalkSAT may take to find a first world satisfying the hard formulas.
    pub walksat_flips: u64,
}

impl Default for InferenceConfig {
    fn default() -> Self {
        InferenceConfig {
            method: Method::Auto,
            seed: 1,
            samples: 5_000,
            burn_in: 100,
            max_exact_atoms: 24,
            slice: SliceMoves::Uniform,
            gibbs_sweeps: 1,
            max_block: 10,
            walksat_flips: 1_000_000,
        }
    }
}

/// How MC-SAT draws a world uniformly from the worlds satisfying the kept features.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum SliceMoves {
    /// One sweep per sample: each atom, and each block of up to `max_block` atoms tied by hard
    /// formulas, is redrawn uniformly among its values that keep every kept clause satisfied.
    /// Leaves the uniform distribution on the slice exactly invariant (the default).
    Uniform,
    /// SampleSAT as in Poon and Domingos (2006), after Wei, Erenrich and Selman (2004):
    /// `steps` moves (0: twice the number of unknown atoms, at least 20), each a WalkSAT move
    /// with probability `walksat_probability` while a kept clause is unsatisfied, otherwise a
    /// simulated-annealing move at `temperature` (in unsatisfied clauses); then WalkSAT until
    /// the world is on the slice. Its draws are not exactly uniform, which biases marginals
    /// (by up to 0.08 on the shipped indoor example). With `walksat_probability` 0, a run that
    /// ends off the slice is rejected instead: exact, but slow to mix.
    SampleSat {
        /// Moves per sample.
        steps: u32,
        /// Annealing temperature.
        temperature: f64,
        /// Probability of a WalkSAT move.
        walksat_probability: f64,
    },
}

/// How to find the most probable world.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MapMethod {
    /// MaxWalkSAT (Kautz, Selman and Jiang 1997): local search, hard clauses first.
    MaxWalkSat,
    /// Enumeration of each connected part (up to `max_exact_atoms` unknown atoms); exact.
    Exact,
}

/// Parameters of MAP inference.
#[derive(Debug, Clone)]
pub struct MapConfig {
    /// The method.
    pub method: MapMethod,
    /// Seed of the random number generator.
    pub seed: u64,
    /// MaxWalkSAT restarts from random worlds.
    pub tries: u32,
    /// MaxWalkSAT flips per try (it stops early once every clause is satisfied).
    pub max_flips: u64,
    /// MaxWalkSAT: probability of flipping a random atom of the chosen clause instead of the
    /// best one.
    pub noise: f64,
    /// Exact: refuse connected parts with more unknown atoms than this.
    pub max_exact_atoms: usize,
}

impl Default for MapConfig {
    fn default() -> Self {
        MapConfig {
            method: MapMethod::MaxWalkSat,
            seed: 1,
            tries: 3,
            max_flips: 10_000,
            noise: 0.3,
            max_exact_atoms: 24,
        }
    }
}

/// Marginal probabilities of the query atoms.
#[derive(Debug, Clone)]
pub struct Marginals {
    atoms: Vec<(GroundAtom, f64)>,
    unknown: Vec<f64>,
    exact: bool,
    work: u64,
}

impl Marginals {
    /// Whether the marginals are exact (junction tree or enumeration) rather than sampled.
    pub fn is_exact(&self) -> bool {
        self.exact
    }

    /// How much work the inference did, in table entries or clause visits: the junction tree's
    /// clique-table entries, enumeration's worlds times clauses, or the samplers' samples times
    /// ground clauses. Deterministic, unlike its time, so callers can budget by it.
    pub fn work(&self) -> u64 {
        self.work
    }

    /// Query atoms and their probability of being true, sorted by predicate, then constants.
    pub fn iter(&self) -> impl Iterator<Item = (&GroundAtom, f64)> {
        self.atoms.iter().map(|(a, p)| (a, *p))
    }

    /// The probability of `predicate(args)`, if it is a query atom.
    pub fn get(&self, predicate: &str, args: &[&str]) -> Option<f64> {
        let i = self
            .atoms
            .binary_search_by(|(a, _)| {
                a.predicate
                    .as_str()
                    .cmp(predicate)
                    .then_with(|| a.args.iter().map(String::as_str).cmp(args.iter().copied()))
            })
            .ok()?;
        Some(self.atoms[i].1)
    }

    /// Number of query atoms.
    pub fn len(&self) -> usize {
        self.atoms.len()
    }

    /// Whether there are no query atoms.
    pub fn is_empty(&self) -> bool {
        self.atoms.is_empty()
    }

    /// The probability of every unknown atom of the network, indexed like [`Network::atom`].
    pub fn unknown_atoms(&self) -> &[f64] {
        &self.unknown
    }
}

/// The most probable world found.
#[derive(Debug, Clone)]
pub struct MapWorld {
    atoms: Vec<(GroundAtom, bool)>,
    state: Vec<bool>,
    log_weight: f64,
}

impl MapWorld {
    /// Query atoms and their values, sorted by predicate, then constants.
    pub fn iter(&self) -> impl Iterator<Item = (&GroundAtom, bool)> {
        self.atoms.iter().map(|(a, v)| (a, *v))
    }

    /// The value of every unknown atom, indexed like [`Network::atom`].
    pub fn state(&self) -> &[bool] {
        &self.state
    }

    /// `sum_i w_i n_i(x)` of this world ([`Network::log_weight`]).
    pub fn log_weight(&self) -> f64 {
        self.log_weight
    }
}

impl Network {
    /// Marginal probabilities of the query atoms (atoms fixed by evidence or by hard formulas
    /// get exactly 0 or 1).
    pub fn infer_marginals(&self, config: &InferenceConfig) -> Result<Marginals, MlnError> {
        check_inference(config)?;
        let mut rng = Rng::seed(config.seed);
        let clauses = self.clause_count() as u64;
        let sampled = clauses.saturating_mul(config.samples as u64);
        let enumerated = clauses.saturating_mul(1u64.checked_shl(self.atom_count() as u32).unwrap_or(u64::MAX));
        let (unknown, exact, work) = match config.method {
            Method::Exact => match junction::marginals(self, config.max_exact_atoms) {
                Ok(Some((m, entries))) => (m, true, entries),
                Ok(None) => return Err(unsatisfiable(NO_WORLD)),
                Err(_) => (exact::marginals(self, config.max_exact_atoms)?, true, enumerated),
            },
            Method::Auto => match junction::marginals(self, AUTO_EXACT_ATOMS) {
                Ok(Some((m, entries))) => (m, true, entries),
                Ok(None) => return Err(unsatisfiable(NO_WORLD)),
                Err(_) => (mcsat::marginals(self, config, &mut rng)?, false, sampled),
            },
            Method::Enumerate => (exact::marginals(self, config.max_exact_atoms)?, true, enumerated),
            Method::McSat => (mcsat::marginals(self, config, &mut rng)?, false, sampled),
            Method::Gibbs => (gibbs::marginals(self, config, &mut rng)?, false, sampled),
        };
        let atoms = self
            .query
            .iter()
            .map(|q| {
                let p = match q.value {
                    QueryValue::Known(b) => b as u8 as f64,
                    QueryValue::Unknown(i) => unknown[i as usize],
                };
                (q.atom.clone(), p)
            })
            .collect();
        Ok(Marginals { atoms, unknown, exact, work })
    }

    /// The most probable world (MAP / MPE) over all unknown atoms, reported for the query atoms.
    pub fn map(&self, config: &MapConfig) -> Result<MapWorld, MlnError> {
        if !(0.0..=1.0).contains(&config.noise) || config.tries == 0 {
            return Err(MlnError::config("MaxWalkSAT needs 0 <= noise <= 1 and at least one try"));
        }
        let state = match config.method {
            MapMethod::Exact => exact::map(self, config.max_exact_atoms)?,
            MapMethod::MaxWalkSat => {
                let mut rng = Rng::seed(config.seed);
                maxwalksat::maxwalksat(self, config, &mut rng)?
            }
        };
        let atoms = self
            .query
            .iter()
            .map(|q| {
                let v = match q.value {
                    QueryValue::Known(b) => b,
                    QueryValue::Unknown(i) => state[i as usize],
                };
                (q.atom.clone(), v)
            })
            .collect();
        Ok(MapWorld { atoms, log_weight: self.log_weight(&state), state })
    }
}

fn check_inference(c: &InferenceConfig) -> Result<(), MlnError> {
    if matches!(c.method, Method::McSat | Method::Gibbs | Method::Auto) && c.samples == 0 {
        return Err(MlnError::config("sampling needs at least one sample"));
    }
    if let SliceMoves::SampleSat { temperature, walksat_probability, .. } = c.slice {
        if !(temperature > 0.0 && temperature.is_finite()) {
            return Err(MlnError::config("the SampleSAT temperature must be positive"));
        }
        if !(0.0..=1.0).contains(&walksat_probability) {
            return Err(MlnError::config("the WalkSAT probability must lie in [0, 1]"));
        }
    }
    if c.max_block > 20 {
        return Err(MlnError::config("Gibbs blocks of more than 20 atoms (2^20 states) are not supported"));
    }
    Ok(())
}

/// Truth counts of a world: the state every method updates flip by flip.
pub(crate) struct Counts<'a> {
    pub net: &'a Network,
    pub value: Vec<bool>,
    /// Per clause: true literals.
    pub true_count: Vec<u32>,
    /// Per feature: unsatisfied clauses.
    pub unsat: Vec<u32>,
    /// Hard features with an unsatisfied clause.
    pub hard_unsat: u32,
    /// Multi-clause features touched by the flip being evaluated.
    scratch: Vec<i32>,
    marked: Vec<bool>,
    touched: Vec<u32>,
}

impl<'a> Counts<'a> {
    pub fn new(net: &'a Network, value: Vec<bool>) -> Self {
        let nc = net.clause_count();
        let nf = net.feature_count();
        let mut true_count = vec![0u32; nc];
        for (c, tc) in true_count.iter_mut().enumerate() {
            *tc = net.clause_lits(c).iter().filter(|&&l| value[(l >> 1) as usize] != (l & 1 == 1)).count() as u32;
        }
        let mut unsat = vec![0u32; nf];
        let mut hard_unsat = 0;
        for (f, u) in unsat.iter_mut().enumerate() {
            *u = net.clauses_of(f).filter(|&c| true_count[c] == 0).count() as u32;
            if *u > 0 && net.feature_weight[f].is_infinite() {
                hard_unsat += 1;
            }
        }
        Counts {
            net,
            value,
            true_count,
            unsat,
            hard_unsat,
            scratch: vec![0; nf],
            marked: vec![false; nf],
            touched: Vec::new(),
        }
    }

    /// What flipping atom `a` would change: (hard features violated, satisfied soft weight).
    /// The world's log weight changes by the second if the first is 0.
    pub fn delta(&mut self, a: usize) -> (i32, f64) {
        let net = self.net;
        let v = self.value[a];
        let (mut hard, mut soft) = (0i32, 0.0f64);
        for &o in net.occurrences(a) {
            let c = (o >> 1) as usize;
            let tc = self.true_count[c];
            // +1: the clause becomes unsatisfied, -1: satisfied.
            let d = if v != (o & 1 == 1) {
                if tc != 1 {
                    continue;
                }
                1
            } else {
                if tc != 0 {
                    continue;
                }
                -1
            };
            let f = net.clause_feature[c] as usize;
            if net.feature_start[f + 1] - net.feature_start[f] == 1 {
                let w = net.feature_weight[f];
                if w.is_infinite() {
                    hard += d;
                } else {
                    soft -= d as f64 * w;
                }
            } else {
                if !self.marked[f] {
                    self.marked[f] = true;
                    self.touched.push(f as u32);
                }
                self.scratch[f] += d;
            }
        }
        for &f in &self.touched {
            let f = f as usize;
            let before = self.unsat[f] as i32;
            let after = before + self.scratch[f];
            self.scratch[f] = 0;
            self.marked[f] = false;
            if (before == 0) != (after == 0) {
                let d = if after > 0 { 1 } else { -1 };
                let w = net.feature_weight[f];
                if w.is_infinite() {
                    hard += d;
                } else {
                    soft -= d as f64 * w;
                }
            }
        }
        self.touched.clear();
        (hard, soft)
    }

    /// Flips atom `a`, calling `changed(clause, now_satisfied)` for every clause whose status
    /// changes.
    #[inline]
    pub fn flip_with(&mut self, a: usize, mut changed: impl FnMut(usize, bool)) {
        let net = self.net;
        let v = self.value[a];
        for &o in net.occurrences(a) {
            let c = (o >> 1) as usize;
            let f = net.clause_feature[c] as usize;
            if v != (o & 1 == 1) {
                self.true_count[c] -= 1;
                if self.true_count[c] == 0 {
                    self.unsat[f] += 1;
                    if self.unsat[f] == 1 && net.feature_weight[f].is_infinite() {
                        self.hard_unsat += 1;
                    }
                    changed(c, false);
                }
            } else {
                self.true_count[c] += 1;
                if self.true_count[c] == 1 {
                    self.unsat[f] -= 1;
                    if self.unsat[f] == 0 && net.feature_weight[f].is_infinite() {
                        self.hard_unsat -= 1;
                    }
                    changed(c, true);
                }
            }
        }
        self.value[a] = !v;
    }

    /// The probability that atom `a` is true given all other atoms: the Rao-Blackwellised
    /// estimate of its marginal from the current world.
    pub fn conditional(&mut self, a: usize) -> f64 {
        let (dh, ds) = self.delta(a);
        let p_flip = if dh > 0 {
            0.0
        } else if dh < 0 {
            1.0
        } else {
            1.0 / (1.0 + libm::exp(-ds))
        };
        if self.value[a] {
            1.0 - p_flip
        } else {
            p_flip
        }
    }

    #[inline]
    pub fn flip(&mut self, a: usize) {
        self.flip_with(a, |_, _| {});
    }
}

/// A random world satisfying the hard features (WalkSAT on them), for the samplers to start from.
pub(crate) fn satisfy_hard(net: &Network, flips: u64, rng: &mut Rng) -> Result<Vec<bool>, MlnError> {
    maxwalksat::walksat_hard(net, flips, rng)
}

/// Blocks of atoms tied together by hard features, for joint moves: groups of up to
/// `max_block` atoms stay together, larger groups are split into single atoms.
pub(crate) fn hard_blocks(net: &Network, max_block: usize) -> Vec<Vec<u32>> {
    let mut blocks = Vec::new();
    for g in atom_groups(net, |f| net.feature_weight[f].is_infinite()) {
        if g.len() <= max_block.max(1) {
            blocks.push(g);
        } else {
            blocks.extend(g.into_iter().map(|a| vec![a]));
        }
    }
    blocks
}

/// Groups of atoms, each sorted, ordered by their first atom; only features passing
/// `include` tie their atoms together.
pub(crate) fn atom_groups(net: &Network, include: impl Fn(usize) -> bool) -> Vec<Vec<u32>> {
    let n = net.atom_count();
    let mut uf = crate::union_find::UnionFind::new(n);
    for f in (0..net.feature_count()).filter(|&f| include(f)) {
        let mut first = None;
        for c in net.clauses_of(f) {
            for &l in net.clause_lits(c) {
                let a = l >> 1;
                match first {
                    None => first = Some(a),
                    Some(b) => {
                        uf.union(a as usize, b as usize);
                    }
                }
            }
        }
    }
    let mut index = vec![u32::MAX; n];
    let mut groups: Vec<Vec<u32>> = Vec::new();
    for a in 0..n as u32 {
        let r = uf.find(a as usize);
        if index[r] == u32::MAX {
            index[r] = groups.len() as u32;
            groups.push(Vec::new());
        }
        groups[index[r] as usize].push(a);
    }
    groups
}

pub(crate) const NO_WORLD: &str = "no world satisfies the hard formulas given the evidence";

pub(crate) fn unsatisfiable(message: &str) -> MlnError {
    MlnError::new(ErrorKind::Unsatisfiable { message: message.into() }, None)
}
