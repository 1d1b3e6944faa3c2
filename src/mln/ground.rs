//! Grounding: from a knowledge base, constants and evidence to a ground Markov network.
//!
//! Every grounding of every formula is simplified against the evidence as it is made: a
//! clause with a literal the evidence makes true is dropped, a literal the evidence makes
//! false is removed. What remains are clauses over the *unknown* atoms only, which is all
//! inference needs. With `simplify` on (the default), unit clauses of hard formulas are then
//! propagated: an atom a hard formula forces is fixed, and clauses it decides disappear.
//!
//! The result is flat: literals are `atom << 1 | negated` in one array, clauses are ranges of
//! it, a feature (one grounding of one formula, with its weight) is a range of clauses, and
//! each atom lists the clauses it occurs in. Samplers walk these arrays without allocating.
//!
//! Weights are made positive on the way: a grounding `F` with weight `w < 0` is stored as `!F`
//! with weight `-w`, and the constant `w` goes to [`Network::log_weight`]'s offset, since
//! `w [F] = w + (-w) [!F]`. Features with weight zero are left out.

use super::error::{ErrorKind, MlnError, Source};
use super::kb::{intern, Database, Evidence, GroundAtom, Mln, Weight};
use super::logic::{cnf, Expr, FoKind, FoLit, Nnf, Term};
use std::collections::{HashMap, HashSet};

/// How to ground: which predicates are queried, open or closed world, extra constants, limits.
#[derive(Debug, Clone)]
pub struct GroundConfig {
    /// Query predicates: their atoms not fixed by evidence are unknown (open world), and
    /// marginals / MAP values are reported for all their ground atoms. Empty: every
    /// open-world predicate is a query predicate.
    pub query: Vec<String>,
    /// Further open-world predicates (hidden: inferred but not reported).
    pub open_world: Vec<String>,
    /// Closed-world predicates: atoms the evidence does not mention are false.
    pub closed_world: Vec<String>,
    /// Constants per type, in addition to those the knowledge base declares or mentions.
    /// A type given here is closed: evidence with other constants of it is an error.
    pub domains: Vec<(String, Vec<String>)>,
    /// Most unknown ground atoms allowed.
    pub max_atoms: usize,
    /// Most ground clauses allowed.
    pub max_clauses: usize,
    /// Most variable assignments (groundings, including quantifier expansions) enumerated.
    pub max_groundings: u64,
    /// Propagate unit clauses of hard formulas (fix the atoms they force).
    pub simplify: bool,
}

impl Default for GroundConfig {
    fn default() -> Self {
        GroundConfig {
            query: Vec::new(),
            open_world: Vec::new(),
            closed_world: Vec::new(),
            domains: Vec::new(),
            max_atoms: 1_000_000,
            max_clauses: 4_000_000,
            max_groundings: 100_000_000,
            simplify: true,
        }
    }
}

impl GroundConfig {
    /// The default configuration querying `predicates`.
    pub fn query<S: AsRef<str>>(predicates: &[S]) -> Self {
        GroundConfig { query: predicates.iter().map(|s| s.as_ref().to_string()).collect(), ..Default::default() }
    }
}

/// Constants, domains and the numbering of all possible ground atoms.
#[derive(Debug, Clone)]
pub(crate) struct Space {
    pub names: Vec<String>,
    /// Per type: global constant ids, in order.
    pub domains: Vec<Vec<u32>>,
    /// Per type: global id -> position in the domain.
    pub local: Vec<HashMap<u32, u32>>,
    pub pred_names: Vec<String>,
    pub pred_types: Vec<Vec<u32>>,
    pub pred_offset: Vec<u64>,
    pub pred_strides: Vec<Vec<u64>>,
    pub total: u64,
}

/// The numbering of all possible ground atoms, as [`Space`] keeps it.
struct AtomNumbering {
    /// Per predicate: the key of its first ground atom.
    pred_offset: Vec<u64>,
    /// Per predicate: the key step of each argument.
    pred_strides: Vec<Vec<u64>>,
    /// The number of possible ground atoms.
    total: u64,
}

impl Space {
    pub fn new(mln: &Mln, db: &Database, extra: &[(String, Vec<String>)]) -> Result<Space, MlnError> {
        let mut names = mln.constants.clone();
        let mut index = mln.constant_index.clone();
        let nt = mln.types.len();
        let mut domains = vec![Vec::new(); nt];
        let mut local = vec![HashMap::new(); nt];
        let mut closed = vec![false; nt];
        fn add(domains: &mut [Vec<u32>], local: &mut [HashMap<u32, u32>], t: usize, c: u32) {
            if !local[t].contains_key(&c) {
                local[t].insert(c, domains[t].len() as u32);
                domains[t].push(c);
            }
        }
        for (t, ty) in mln.types.iter().enumerate() {
            if let Some((ids, _)) = &ty.declared {
                closed[t] = true;
                for &c in ids {
                    add(&mut domains, &mut local, t, c);
                }
            }
            for &c in &ty.mentioned {
                add(&mut domains, &mut local, t, c);
            }
        }
        for (tname, consts) in extra {
            let Some(&t) = mln.type_index.get(tname) else {
                return Err(MlnError::new(ErrorKind::UnknownType { name: tname.clone() }, None));
            };
            closed[t as usize] = true;
            for c in consts {
                if c.is_empty() || c.contains(|c: char| c.is_whitespace() || "(),".contains(c)) {
                    return Err(MlnError::config(format!("{c:?} is not a valid constant name")));
                }
                let id = intern(&mut names, &mut index, c);
                add(&mut domains, &mut local, t as usize, id);
            }
        }
        for atom in &db.atoms {
            let pred = mln.predicates.get(atom.pred as usize);
            let Some(pred) = pred.filter(|p| p.arg_types.len() == atom.args.len()) else {
                return Err(MlnError::config("the evidence database was built for a different knowledge base"));
            };
            for (arg, &t) in atom.args.iter().zip(&pred.arg_types) {
                let t = t as usize;
                let id = intern(&mut names, &mut index, arg);
                if !local[t].contains_key(&id) {
                    if closed[t] {
                        let kind =
                            ErrorKind::UnknownConstant { constant: arg.clone(), type_name: mln.types[t].name.clone() };
                        return Err(MlnError::new(kind, atom.at).in_text(Source::Evidence));
                    }
                    add(&mut domains, &mut local, t, id);
                }
            }
        }
        let AtomNumbering { pred_offset, pred_strides, total } = Space::numbering(mln, &domains)?;
        Ok(Space {
            names,
            domains,
            local,
            pred_names: mln.predicates.iter().map(|p| p.name.clone()).collect(),
            pred_types: mln.predicates.iter().map(|p| p.arg_types.clone()).collect(),
            pred_offset,
            pred_strides,
            total,
        })
    }

    /// Numbers all possible ground atoms, predicate after predicate, each row-major over its
    /// arguments' domains: per predicate its first key and its arguments' strides, and the total.
    fn numbering(mln: &Mln, domains: &[Vec<u32>]) -> Result<AtomNumbering, MlnError> {
        let mut total: u64 = 0;
        let mut pred_offset = Vec::new();
        let mut pred_strides = Vec::new();
        let overflow = || MlnError::too_large("possible ground atoms", u64::MAX);
        for p in &mln.predicates {
            let k = p.arg_types.len();
            let mut strides = vec![1u64; k];
            for i in (0..k.saturating_sub(1)).rev() {
                let size = domains[p.arg_types[i + 1] as usize].len() as u64;
                strides[i] = strides[i + 1].checked_mul(size).ok_or_else(overflow)?;
            }
            let count = match k {
                0 => 1,
                _ => strides[0].checked_mul(domains[p.arg_types[0] as usize].len() as u64).ok_or_else(overflow)?,
            };
            pred_offset.push(total);
            pred_strides.push(strides);
            total = total.checked_add(count).ok_or_else(overflow)?;
        }
        Ok(AtomNumbering { pred_offset, pred_strides, total })
    }

    /// The key of an evidence atom (all constants are in the domains by construction).
    fn evidence_key(&self, pred: u32, args: &[String], index: &HashMap<&str, u32>) -> u64 {
        let p = pred as usize;
        let mut key = self.pred_offset[p];
        for (i, a) in args.iter().enumerate() {
            let t = self.pred_types[p][i] as usize;
            key += self.local[t][&index[a.as_str()]] as u64 * self.pred_strides[p][i];
        }
        key
    }

    /// The key of a ground atom, if its predicate and constants belong to this space.
    fn try_key(&self, pred: u32, args: &[String], index: &HashMap<&str, u32>) -> Option<u64> {
        let p = pred as usize;
        let types = self.pred_types.get(p).filter(|t| t.len() == args.len())?;
        let mut key = self.pred_offset[p];
        for (i, a) in args.iter().enumerate() {
            let l = *self.local[types[i] as usize].get(index.get(a.as_str())?)?;
            key += l as u64 * self.pred_strides[p][i];
        }
        Some(key)
    }

    /// Per type name, its constants' names (every type of the knowledge base, in order).
    pub fn domain_names(&self, mln: &Mln) -> Vec<(String, Vec<String>)> {
        mln.types
            .iter()
            .zip(&self.domains)
            .map(|(t, d)| (t.name.clone(), d.iter().map(|&c| self.names[c as usize].clone()).collect()))
            .collect()
    }

    /// The key of an atom under an assignment of local indices to variable slots.
    fn key(&self, pred: u32, args: &[Term], assign: &[u32]) -> u64 {
        let p = pred as usize;
        let mut key = self.pred_offset[p];
        for (i, a) in args.iter().enumerate() {
            let l = match *a {
                Term::Var(s) => assign[s as usize],
                Term::Const(c) => self.local[self.pred_types[p][i] as usize][&c],
            };
            key += l as u64 * self.pred_strides[p][i];
        }
        key
    }

    /// The global constant id of a term under an assignment.
    fn constant(&self, t: Term, assign: &[u32], var_types: &[u32]) -> u32 {
        match t {
            Term::Var(s) => self.domains[var_types[s as usize] as usize][assign[s as usize] as usize],
            Term::Const(c) => c,
        }
    }

    /// Predicate and argument names of an atom key.
    pub fn atom(&self, pred: u32, key: u64) -> GroundAtom {
        let p = pred as usize;
        let mut r = key - self.pred_offset[p];
        let mut args = Vec::with_capacity(self.pred_types[p].len());
        for (i, &stride) in self.pred_strides[p].iter().enumerate() {
            let l = r / stride;
            r %= stride;
            let t = self.pred_types[p][i] as usize;
            args.push(self.names[self.domains[t][l as usize] as usize].clone());
        }
        GroundAtom { predicate: self.pred_names[p].clone(), args }
    }

    fn name_index(&self) -> HashMap<&str, u32> {
        self.names.iter().enumerate().map(|(i, n)| (n.as_str(), i as u32)).collect()
    }
}

const UNSEEN: u32 = u32::MAX;
const TRUE: u32 = u32::MAX - 1;
const FALSE: u32 = u32::MAX - 2;
/// Possible-atom spaces up to this size get a dense lookup table (4 bytes each).
const DENSE_LIMIT: u64 = 1 << 20;

/// What is known about every possible ground atom: evidence, or its unknown-atom index.
enum Table {
    Dense(Vec<u32>),
    Sparse(HashMap<u64, u32>),
}

impl Table {
    fn new(total: u64) -> Table {
        if total <= DENSE_LIMIT {
            Table::Dense(vec![UNSEEN; total as usize])
        } else {
            Table::Sparse(HashMap::new())
        }
    }

    #[inline]
    fn get(&self, key: u64) -> u32 {
        match self {
            Table::Dense(v) => v[key as usize],
            Table::Sparse(m) => m.get(&key).copied().unwrap_or(UNSEEN),
        }
    }

    fn set(&mut self, key: u64, v: u32) {
        match self {
            Table::Dense(t) => t[key as usize] = v,
            Table::Sparse(m) => {
                m.insert(key, v);
            }
        }
    }
}

/// A literal whose atom is unknown, before the atom has an index.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Pending {
    key: u64,
    pred: u32,
    negated: bool,
}

enum Val {
    True,
    False,
    Unknown(Pending),
}

/// A literal of a first-order clause, compiled for fast grounding.
enum Compiled {
    /// `key = base + sum(assign[slot] * stride)`.
    Atom {
        pred: u32,
        negated: bool,
        base: u64,
        parts: Vec<(u32, u64)>,
    },
    Eq {
        negated: bool,
        left: Term,
        right: Term,
    },
}

/// A reported query atom: fixed by evidence (or by hard formulas), or unknown.
#[derive(Debug, Clone)]
pub(crate) struct QueryAtom {
    pub atom: GroundAtom,
    pub value: QueryValue,
}

#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum QueryValue {
    Known(bool),
    Unknown(u32),
}

/// A ground Markov network over the unknown atoms, ready for inference.
///
/// Build it with [`Network::ground`]; query it with [`Network::infer_marginals`],
/// [`Network::map`] and [`Network::log_weight`].
#[derive(Debug, Clone)]
pub struct Network {
    pub(crate) space: Space,
    pub(crate) atom_key: Vec<u64>,
    pub(crate) atom_pred: Vec<u32>,
    /// Literals, `atom << 1 | negated`.
    pub(crate) lits: Vec<u32>,
    /// Clause `c` is `lits[clause_start[c]..clause_start[c + 1]]`.
    pub(crate) clause_start: Vec<u32>,
    pub(crate) clause_feature: Vec<u32>,
    /// Positive weight, or infinity for hard features.
    pub(crate) feature_weight: Vec<f64>,
    /// Feature `f` is clauses `feature_start[f]..feature_start[f + 1]`.
    pub(crate) feature_start: Vec<u32>,
    /// The formula each feature grounds (its index in [`Mln::formulas`]), or `u32::MAX` for
    /// soft evidence; weight learning counts true groundings per formula by it.
    pub(crate) feature_formula: Vec<u32>,
    /// Atom `a` occurs in `occ[occ_start[a]..occ_start[a + 1]]`, each `clause << 1 | negated`.
    pub(crate) occ_start: Vec<u32>,
    pub(crate) occ: Vec<u32>,
    /// Log weight of the worlds' constant part (evidence-decided groundings, sign flips).
    pub(crate) offset: f64,
    pub(crate) query: Vec<QueryAtom>,
}

impl Network {
    /// Grounds `mln` over the constants of its declarations, of `config.domains` and of the
    /// evidence, and simplifies by the evidence.
    ///
    /// Predicates are open world (unknown where the evidence is silent) if they are query
    /// predicates or listed in `config.open_world`, closed world (false where the evidence is
    /// silent) if listed in `config.closed_world`, and otherwise closed world exactly when the
    /// evidence mentions them (Alchemy's rule).
    pub fn ground(mln: &Mln, db: &Database, config: &GroundConfig) -> Result<Network, MlnError> {
        let space = Space::new(mln, db, &config.domains)?;
        let closed = world_assumptions(mln, db, config)?;
        let query: Vec<u32> = if config.query.is_empty() {
            (0..mln.predicates.len() as u32).filter(|&p| !closed[p as usize]).collect()
        } else {
            config.query.iter().map(|q| mln.predicate_index[q.as_str()]).collect()
        };
        let mut b = Builder::new(mln, space, config, closed);
        b.add_evidence(db)?;
        for (i, f) in mln.formulas.iter().enumerate() {
            b.add_formula(i, f)?;
        }
        let query = b.add_queries(&query)?;
        b.finish(query, config.simplify)
    }

    /// Number of unknown ground atoms.
    pub fn atom_count(&self) -> usize {
        self.atom_key.len()
    }

    /// Number of ground clauses.
    pub fn clause_count(&self) -> usize {
        self.clause_feature.len()
    }

    /// Number of ground features (weighted groundings of formulas and soft evidence; each is
    /// one or more clauses).
    pub fn feature_count(&self) -> usize {
        self.feature_weight.len()
    }

    /// Number of hard features.
    pub fn hard_feature_count(&self) -> usize {
        self.feature_weight.iter().filter(|w| w.is_infinite()).count()
    }

    /// Number of reported query atoms (unknown or fixed).
    pub fn query_count(&self) -> usize {
        self.query.len()
    }

    /// The name of unknown atom `i` (`i < atom_count()`).
    pub fn atom(&self, i: usize) -> GroundAtom {
        self.space.atom(self.atom_pred[i], self.atom_key[i])
    }

    /// The query atoms in report order (sorted by predicate, then constants) with their value
    /// if the evidence or the hard formulas fix it, or their unknown-atom index.
    pub fn query_atoms(&self) -> impl Iterator<Item = (&GroundAtom, Result<bool, usize>)> {
        self.query.iter().map(|q| {
            let v = match q.value {
                QueryValue::Known(b) => Ok(b),
                QueryValue::Unknown(i) => Err(i as usize),
            };
            (&q.atom, v)
        })
    }

    /// `sum_i w_i n_i(x)` of eq. (2.4) / (4.3) for the world that gives the unknown atoms the
    /// values `state` (indexed like [`Network::atom`]), atoms fixed by the evidence their
    /// evidence values and atoms forced by hard formulas (when grounded with `simplify`) their
    /// forced values; `-inf` if the world violates a hard formula. Includes soft-evidence unit
    /// clauses, which [`Mln::log_weight`] knows nothing of.
    ///
    /// # Panics
    /// If `state.len() != atom_count()`.
    pub fn log_weight(&self, state: &[bool]) -> f64 {
        assert_eq!(state.len(), self.atom_count(), "one value per unknown atom");
        let mut total = self.offset;
        for f in 0..self.feature_count() {
            let sat = self
                .clauses_of(f)
                .all(|c| self.clause_lits(c).iter().any(|&l| state[(l >> 1) as usize] != (l & 1 == 1)));
            let w = self.feature_weight[f];
            if sat {
                if w.is_finite() {
                    total += w;
                }
            } else if w.is_infinite() {
                return f64::NEG_INFINITY;
            }
        }
        total
    }

    /// The value of every unknown atom in the complete world `world`: true if it lists the
    /// atom as true, false otherwise (closed world). Atoms with constants outside this
    /// network's domains are ignored, as they cannot be among its atoms.
    pub(crate) fn values_in(&self, world: &Database) -> Vec<bool> {
        let index = self.space.name_index();
        let truth: HashSet<u64> = world
            .atoms
            .iter()
            .filter(|a| a.value == Evidence::True)
            .filter_map(|a| self.space.try_key(a.pred, &a.args, &index))
            .collect();
        self.atom_key.iter().map(|k| truth.contains(k)).collect()
    }

    #[inline]
    pub(crate) fn clause_lits(&self, c: usize) -> &[u32] {
        &self.lits[self.clause_start[c] as usize..self.clause_start[c + 1] as usize]
    }

    #[inline]
    pub(crate) fn clauses_of(&self, f: usize) -> std::ops::Range<usize> {
        self.feature_start[f] as usize..self.feature_start[f + 1] as usize
    }

    #[inline]
    pub(crate) fn occurrences(&self, a: usize) -> &[u32] {
        &self.occ[self.occ_start[a] as usize..self.occ_start[a + 1] as usize]
    }
}

/// Per predicate: closed world?
fn world_assumptions(mln: &Mln, db: &Database, config: &GroundConfig) -> Result<Vec<bool>, MlnError> {
    let n = mln.predicates.len();
    let lookup = |name: &String| {
        mln.predicate_index
            .get(name.as_str())
            .map(|&p| p as usize)
            .ok_or_else(|| MlnError::new(ErrorKind::UnknownPredicate { name: name.clone() }, None))
    };
    let mut open = vec![false; n];
    let mut closed = vec![false; n];
    for q in config.query.iter().chain(&config.open_world) {
        open[lookup(q)?] = true;
    }
    for c in &config.closed_world {
        let p = lookup(c)?;
        if open[p] {
            return Err(MlnError::config(format!("{c} is listed both as open world (or query) and as closed world")));
        }
        closed[p] = true;
    }
    for a in &db.atoms {
        let p = a.pred as usize;
        if p < n && !open[p] {
            closed[p] = true;
        }
    }
    Ok(closed)
}

struct Builder<'a> {
    mln: &'a Mln,
    space: Space,
    config: &'a GroundConfig,
    closed: Vec<bool>,
    table: Table,
    atom_key: Vec<u64>,
    atom_pred: Vec<u32>,
    lits: Vec<u32>,
    clause_start: Vec<u32>,
    clause_feature: Vec<u32>,
    feature_weight: Vec<f64>,
    feature_start: Vec<u32>,
    feature_formula: Vec<u32>,
    offset: f64,
    groundings: u64,
    /// One grounding's clauses of pending literals: clause `i` ends at `pending_end[i]`.
    pending: Vec<Pending>,
    pending_end: Vec<usize>,
}

/// Marks soft-evidence features in `feature_formula`.
const EVIDENCE: u32 = u32::MAX;

impl<'a> Builder<'a> {
    fn new(mln: &'a Mln, space: Space, config: &'a GroundConfig, closed: Vec<bool>) -> Self {
        Builder {
            mln,
            table: Table::new(space.total),
            space,
            config,
            closed,
            atom_key: Vec::new(),
            atom_pred: Vec::new(),
            lits: Vec::new(),
            clause_start: vec![0],
            clause_feature: Vec::new(),
            feature_weight: Vec::new(),
            feature_start: vec![0],
            feature_formula: Vec::new(),
            offset: 0.0,
            groundings: 0,
            pending: Vec::new(),
            pending_end: Vec::new(),
        }
    }

    fn add_evidence(&mut self, db: &Database) -> Result<(), MlnError> {
        let index = self.space.name_index();
        let keys: Vec<u64> = db.atoms.iter().map(|a| self.space.evidence_key(a.pred, &a.args, &index)).collect();
        drop(index);
        for (a, key) in db.atoms.iter().zip(keys) {
            match a.value {
                Evidence::True => self.table.set(key, TRUE),
                Evidence::False => self.table.set(key, FALSE),
                Evidence::Soft(p) => {
                    let w = libm::log(p / (1.0 - p));
                    let (v, c, negated) = if w < 0.0 { (-w, w, true) } else { (w, 0.0, false) };
                    self.pending.clear();
                    self.pending_end.clear();
                    self.pending.push(Pending { key, pred: a.pred, negated });
                    self.pending_end.push(1);
                    self.emit(EVIDENCE, v, c, false, &[])?;
                }
            }
        }
        Ok(())
    }

    #[inline]
    fn lookup(&self, key: u64, pred: u32, negated: bool) -> Val {
        match self.table.get(key) {
            TRUE => bool_val(!negated),
            FALSE => bool_val(negated),
            UNSEEN if self.closed[pred as usize] => bool_val(negated),
            _ => Val::Unknown(Pending { key, pred, negated }),
        }
    }

    /// The index of an unknown atom, made on first use.
    fn atom_index(&mut self, key: u64, pred: u32) -> Result<u32, MlnError> {
        let v = self.table.get(key);
        if v < FALSE {
            return Ok(v);
        }
        debug_assert_eq!(v, UNSEEN);
        let i = self.atom_key.len();
        if i >= self.config.max_atoms {
            return Err(MlnError::too_large("ground atoms", self.config.max_atoms as u64));
        }
        self.atom_key.push(key);
        self.atom_pred.push(pred);
        self.table.set(key, i as u32);
        Ok(i as u32)
    }

    fn count_groundings(&mut self, n: u64) -> Result<(), MlnError> {
        self.groundings = self.groundings.saturating_add(n);
        if self.groundings > self.config.max_groundings {
            return Err(MlnError::too_large("groundings", self.config.max_groundings));
        }
        Ok(())
    }

    fn add_formula(&mut self, index: usize, f: &super::kb::Formula) -> Result<(), MlnError> {
        let (v, c, negate) = match f.weight {
            Weight::Hard => (f64::INFINITY, 0.0, false),
            Weight::Soft(0.0) => return Ok(()),
            Weight::Soft(w) if w < 0.0 => (-w, w, true),
            Weight::Soft(w) => (w, 0.0, false),
        };
        let var_types: Vec<u32> = f.vars.iter().map(|v| v.ty.unwrap_or(0)).collect();
        let sizes: Vec<u32> =
            f.free.iter().map(|&s| self.space.domains[var_types[s as usize] as usize].len() as u32).collect();
        if sizes.contains(&0) {
            return Ok(()); // a type without constants: no groundings
        }
        let count = sizes.iter().try_fold(1u64, |acc, &s| acc.checked_mul(s as u64)).unwrap_or(u64::MAX);
        self.count_groundings(count)?;
        let mut assign = vec![0u32; f.vars.len()];
        let fo = if negate { &f.cnf_negated } else { &f.cnf };
        if let Some(clauses) = fo {
            let compiled: Vec<Vec<Compiled>> =
                clauses.iter().map(|c| c.iter().map(|l| self.compile(l)).collect()).collect();
            loop {
                let falsified = self.ground_clauses(&compiled, &assign, &var_types);
                self.emit(index as u32, v, c, falsified, &assign)?;
                if !next_assignment(&mut assign, &f.free, &sizes) {
                    return Ok(());
                }
            }
        }
        loop {
            let g = self.ground_nnf(&f.expr, negate, &mut assign, &var_types)?;
            let room = self.config.max_clauses.saturating_sub(self.clause_feature.len());
            let clauses =
                cnf(&g, room).map_err(|_| MlnError::too_large("ground clauses", self.config.max_clauses as u64))?;
            self.pending.clear();
            self.pending_end.clear();
            let mut falsified = false;
            for cl in &clauses {
                if cl.is_empty() {
                    falsified = true;
                }
                self.pending.extend_from_slice(cl);
                self.pending_end.push(self.pending.len());
            }
            self.emit(index as u32, v, c, falsified, &assign)?;
            if !next_assignment(&mut assign, &f.free, &sizes) {
                return Ok(());
            }
        }
    }

    fn compile(&self, l: &FoLit) -> Compiled {
        match &l.kind {
            FoKind::Atom { pred, args } => {
                let p = *pred as usize;
                let mut base = self.space.pred_offset[p];
                let mut parts = Vec::new();
                for (i, a) in args.iter().enumerate() {
                    let stride = self.space.pred_strides[p][i];
                    match *a {
                        Term::Var(s) => parts.push((s, stride)),
                        Term::Const(c) => {
                            base += self.space.local[self.space.pred_types[p][i] as usize][&c] as u64 * stride
                        }
                    }
                }
                Compiled::Atom { pred: *pred, negated: l.negated, base, parts }
            }
            FoKind::Eq(a, b) => Compiled::Eq { negated: l.negated, left: *a, right: *b },
        }
    }

    /// Grounds precompiled clauses into `pending`; returns whether a clause is falsified.
    fn ground_clauses(&mut self, compiled: &[Vec<Compiled>], assign: &[u32], var_types: &[u32]) -> bool {
        self.pending.clear();
        self.pending_end.clear();
        'clauses: for clause in compiled {
            let mark = self.pending.len();
            for lit in clause {
                let val = match lit {
                    Compiled::Atom { pred, negated, base, parts } => {
                        let key = parts.iter().fold(*base, |k, &(s, stride)| k + assign[s as usize] as u64 * stride);
                        self.lookup(key, *pred, *negated)
                    }
                    Compiled::Eq { negated, left, right } => {
                        let eq = self.space.constant(*left, assign, var_types)
                            == self.space.constant(*right, assign, var_types);
                        bool_val(eq != *negated)
                    }
                };
                match val {
                    Val::True => {
                        self.pending.truncate(mark);
                        continue 'clauses;
                    }
                    Val::False => {}
                    Val::Unknown(p) => self.pending.push(p),
                }
            }
            if self.pending.len() == mark {
                return true;
            }
            self.pending_end.push(self.pending.len());
        }
        false
    }

    /// One grounding of a formula with quantifiers, simplified by the evidence, negated if
    /// `negate`. Quantified variables are expanded over their domains.
    fn ground_nnf(
        &mut self,
        e: &Expr,
        negate: bool,
        assign: &mut [u32],
        types: &[u32],
    ) -> Result<Nnf<Pending>, MlnError> {
        Ok(match e {
            Expr::Atom { pred, args } => {
                let key = self.space.key(*pred, args, assign);
                match self.lookup(key, *pred, negate) {
                    Val::True => Nnf::True,
                    Val::False => Nnf::False,
                    Val::Unknown(p) => Nnf::Lit(p),
                }
            }
            Expr::Eq(a, b) => {
                let eq = self.space.constant(*a, assign, types) == self.space.constant(*b, assign, types);
                if eq != negate {
                    Nnf::True
                } else {
                    Nnf::False
                }
            }
            Expr::Not(x) => self.ground_nnf(x, !negate, assign, types)?,
            Expr::And(v) | Expr::Or(v) => {
                let conj = matches!(e, Expr::And(_)) != negate;
                let mut items = Vec::with_capacity(v.len());
                for x in v {
                    items.push(self.ground_nnf(x, negate, assign, types)?);
                }
                if conj {
                    Nnf::and(items)
                } else {
                    Nnf::or(items)
                }
            }
            Expr::Implies(a, b) => {
                let x = self.ground_nnf(a, !negate, assign, types)?;
                let y = self.ground_nnf(b, negate, assign, types)?;
                if negate {
                    Nnf::and(vec![x, y])
                } else {
                    Nnf::or(vec![x, y])
                }
            }
            Expr::Equiv(a, b) => {
                let (an, ap) =
                    (self.ground_nnf(a, !negate, assign, types)?, self.ground_nnf(a, negate, assign, types)?);
                let (bp, bn) = (self.ground_nnf(b, false, assign, types)?, self.ground_nnf(b, true, assign, types)?);
                Nnf::and(vec![Nnf::or(vec![an, bp]), Nnf::or(vec![ap, bn])])
            }
            Expr::Exists(slots, body) | Expr::Forall(slots, body) => {
                // EXIST is a disjunction over the domain, FORALL a conjunction; negation swaps.
                let conj = matches!(e, Expr::Forall(..)) != negate;
                self.ground_quantifier(slots, body, conj, negate, assign, types)?
            }
        })
    }

    /// The expansion of a quantifier over the domains of the variables in `slots`: the
    /// conjunction (`conj`) or disjunction of the groundings of `body`, stopping at the first
    /// that decides it.
    fn ground_quantifier(
        &mut self,
        slots: &[u32],
        body: &Expr,
        conj: bool,
        negate: bool,
        assign: &mut [u32],
        types: &[u32],
    ) -> Result<Nnf<Pending>, MlnError> {
        let sizes: Vec<u32> =
            slots.iter().map(|&s| self.space.domains[types[s as usize] as usize].len() as u32).collect();
        let mut items = Vec::new();
        if !sizes.contains(&0) {
            let count = sizes.iter().try_fold(1u64, |acc, &s| acc.checked_mul(s as u64)).unwrap_or(u64::MAX);
            self.count_groundings(count)?;
            for &s in slots {
                assign[s as usize] = 0;
            }
            loop {
                let g = self.ground_nnf(body, negate, assign, types)?;
                let decided = if conj { g == Nnf::False } else { g == Nnf::True };
                items.push(g);
                if decided || !next_assignment(assign, slots, &sizes) {
                    break;
                }
            }
        }
        Ok(if conj { Nnf::and(items) } else { Nnf::or(items) })
    }

    /// Adds the grounding in `pending` as a feature (or folds it into the offset).
    fn emit(&mut self, formula: u32, v: f64, c: f64, falsified: bool, assign: &[u32]) -> Result<(), MlnError> {
        let hard = v.is_infinite();
        if falsified {
            if hard {
                return Err(self.violation(formula, assign));
            }
            self.offset += c;
            return Ok(());
        }
        let f = self.feature_weight.len() as u32;
        let first_clause = self.clause_feature.len();
        let mut from = 0;
        for ci in 0..self.pending_end.len() {
            let to = self.pending_end[ci];
            let mark = self.lits.len();
            let mut tautology = false;
            for k in from..to {
                let p = self.pending[k];
                let a = self.atom_index(p.key, p.pred)?;
                let lit = a << 1 | p.negated as u32;
                let clause = &self.lits[mark..];
                if clause.contains(&(lit ^ 1)) {
                    tautology = true;
                    break;
                }
                if !clause.contains(&lit) {
                    self.lits.push(lit);
                }
            }
            from = to;
            if tautology {
                self.lits.truncate(mark);
                continue;
            }
            if self.clause_feature.len() >= self.config.max_clauses {
                return Err(MlnError::too_large("ground clauses", self.config.max_clauses as u64));
            }
            self.clause_start.push(self.lits.len() as u32);
            self.clause_feature.push(f);
        }
        if self.clause_feature.len() == first_clause {
            // Every clause is decided true.
            self.offset += c + if hard { 0.0 } else { v };
            return Ok(());
        }
        self.offset += c;
        self.feature_weight.push(v);
        self.feature_start.push(self.clause_feature.len() as u32);
        self.feature_formula.push(formula);
        Ok(())
    }

    fn violation(&self, formula: u32, assign: &[u32]) -> MlnError {
        let f = &self.mln.formulas[formula as usize];
        let bindings: Vec<String> = f
            .free
            .iter()
            .map(|&s| {
                let v = &f.vars[s as usize];
                let c = self.space.domains[v.ty.unwrap_or(0) as usize][assign[s as usize] as usize];
                format!("{} = {}", v.name, self.space.names[c as usize])
            })
            .collect();
        let with = if bindings.is_empty() { String::new() } else { format!(" with {}", bindings.join(", ")) };
        let message = format!("the evidence violates the hard formula `{}`{with}", f.text);
        MlnError::new(ErrorKind::Unsatisfiable { message }, Some(f.at)).in_text(Source::KnowledgeBase)
    }

    fn add_queries(&mut self, preds: &[u32]) -> Result<Vec<(u32, u64)>, MlnError> {
        let mut out = Vec::new();
        for &p in preds {
            let types = &self.space.pred_types[p as usize];
            let sizes: Vec<u32> = types.iter().map(|&t| self.space.domains[t as usize].len() as u32).collect();
            if sizes.contains(&0) {
                continue;
            }
            let count = sizes.iter().try_fold(1u64, |acc, &s| acc.checked_mul(s as u64)).unwrap_or(u64::MAX);
            if count > self.config.max_atoms as u64 {
                return Err(MlnError::too_large("ground atoms", self.config.max_atoms as u64));
            }
            let offset = self.space.pred_offset[p as usize];
            for k in 0..count {
                let key = offset + k;
                match self.table.get(key) {
                    TRUE | FALSE => {}
                    _ => {
                        self.atom_index(key, p)?;
                    }
                }
                out.push((p, key));
            }
        }
        Ok(out)
    }

    /// Unit propagation of hard clauses (if `simplify`), then renumbering into a [`Network`].
    fn finish(mut self, query: Vec<(u32, u64)>, simplify: bool) -> Result<Network, MlnError> {
        let n = self.atom_key.len();
        let nc = self.clause_feature.len();
        let nf = self.feature_weight.len();
        let mut fixed = vec![0u8; n]; // 0 unknown, 1 false, 2 true
        let mut clause_sat = vec![false; nc];
        let mut dead = vec![false; nf];
        if simplify {
            self.propagate(&mut fixed, &mut clause_sat, &mut dead)?;
        }
        let (keep_feature, used) = self.surviving(&dead, &clause_sat);
        let mut queried = vec![false; n];
        for &(_, key) in &query {
            let v = self.table.get(key);
            if v < FALSE {
                queried[v as usize] = true;
            }
        }
        let mut renumber = vec![u32::MAX; n];
        let mut atom_key = Vec::new();
        let mut atom_pred = Vec::new();
        for a in 0..n {
            if fixed[a] == 0 && (used[a] || queried[a]) {
                renumber[a] = atom_key.len() as u32;
                atom_key.push(self.atom_key[a]);
                atom_pred.push(self.atom_pred[a]);
            }
        }
        let mut lits = Vec::with_capacity(self.lits.len());
        let mut clause_start = vec![0u32];
        let mut clause_feature = Vec::new();
        let mut feature_weight = Vec::new();
        let mut feature_start = vec![0u32];
        let mut feature_formula = Vec::new();
        for f in (0..nf).filter(|&f| keep_feature[f]) {
            feature_formula.push(self.feature_formula[f]);
            let nf2 = feature_weight.len() as u32;
            let clauses = self.feature_start[f] as usize..self.feature_start[f + 1] as usize;
            for c in clauses.filter(|&c| !clause_sat[c]) {
                for &l in &self.lits[self.clause_start[c] as usize..self.clause_start[c + 1] as usize] {
                    let a = (l >> 1) as usize;
                    if fixed[a] == 0 {
                        lits.push(renumber[a] << 1 | (l & 1));
                    }
                }
                clause_start.push(lits.len() as u32);
                clause_feature.push(nf2);
            }
            feature_weight.push(self.feature_weight[f]);
            feature_start.push(clause_feature.len() as u32);
        }
        let (occ_start, occ) = occurrences(atom_key.len(), &lits, &clause_start);
        let query = self.resolve_queries(query, &fixed, &renumber);
        Ok(Network {
            space: self.space,
            atom_key,
            atom_pred,
            lits,
            clause_start,
            clause_feature,
            feature_weight,
            feature_start,
            feature_formula,
            occ_start,
            occ,
            offset: self.offset,
            query,
        })
    }

    /// The query atoms with their values: known from evidence or from propagation (`fixed`),
    /// or unknown with their atom's new number; sorted by atom.
    fn resolve_queries(&self, query: Vec<(u32, u64)>, fixed: &[u8], renumber: &[u32]) -> Vec<QueryAtom> {
        let mut query: Vec<QueryAtom> = query
            .into_iter()
            .map(|(p, key)| {
                let value = match self.table.get(key) {
                    TRUE => QueryValue::Known(true),
                    FALSE => QueryValue::Known(false),
                    a if fixed[a as usize] != 0 => QueryValue::Known(fixed[a as usize] == 2),
                    a => QueryValue::Unknown(renumber[a as usize]),
                };
                QueryAtom { atom: self.space.atom(p, key), value }
            })
            .collect();
        crate::sort::sort_by(&mut query, |a, b| a.atom.cmp(&b.atom));
        query
    }

    /// Unit propagation of the hard clauses: fixes atoms (`fixed`: 1 false, 2 true), marks the
    /// clauses that became true and the features one of whose clauses became false.
    fn propagate(&self, fixed: &mut [u8], clause_sat: &mut [bool], dead: &mut [bool]) -> Result<(), MlnError> {
        let (n, nc, nf) = (self.atom_key.len(), self.clause_feature.len(), self.feature_weight.len());
        let (occ_start, occ) = occurrences(n, &self.lits, &self.clause_start);
        let mut open: Vec<u32> = (0..nc).map(|c| self.clause_start[c + 1] - self.clause_start[c]).collect();
        let mut fixed_by = vec![u32::MAX; n];
        let mut queue: Vec<(u32, u32)> = Vec::new();
        for f in 0..nf {
            if self.feature_weight[f].is_infinite() {
                for c in self.feature_start[f]..self.feature_start[f + 1] {
                    if open[c as usize] == 1 {
                        queue.push((self.lits[self.clause_start[c as usize] as usize], f as u32));
                    }
                }
            }
        }
        while let Some((lit, f)) = queue.pop() {
            let a = (lit >> 1) as usize;
            let val = lit & 1 == 0;
            if fixed[a] != 0 {
                if (fixed[a] == 2) != val {
                    return Err(self.contradiction(a, f, fixed_by[a]));
                }
                continue;
            }
            fixed[a] = 1 + val as u8;
            fixed_by[a] = f;
            for &o in &occ[occ_start[a] as usize..occ_start[a + 1] as usize] {
                let c = (o >> 1) as usize;
                if clause_sat[c] {
                    continue;
                }
                if val != (o & 1 == 1) {
                    clause_sat[c] = true;
                    continue;
                }
                open[c] -= 1;
                let g = self.clause_feature[c] as usize;
                let hard = self.feature_weight[g].is_infinite();
                if open[c] == 0 {
                    if hard {
                        return Err(self.contradiction(a, g as u32, f));
                    }
                    dead[g] = true;
                } else if open[c] == 1 && hard {
                    let range = self.clause_start[c] as usize..self.clause_start[c + 1] as usize;
                    if let Some(&l) = self.lits[range].iter().find(|&&l| fixed[(l >> 1) as usize] == 0) {
                        queue.push((l, g as u32));
                    }
                }
            }
        }
        Ok(())
    }

    /// Which features survive (neither dead nor satisfied, whose weight joins the offset) and
    /// which atoms their open clauses use.
    fn surviving(&mut self, dead: &[bool], clause_sat: &[bool]) -> (Vec<bool>, Vec<bool>) {
        let (n, nf) = (self.atom_key.len(), self.feature_weight.len());
        // Which features and clauses survive, and which atoms they use.
        let mut used = vec![false; n];
        let mut keep_feature = vec![false; nf];
        for f in 0..nf {
            if dead[f] {
                continue;
            }
            let clauses = self.feature_start[f] as usize..self.feature_start[f + 1] as usize;
            if clauses.clone().all(|c| clause_sat[c]) {
                if self.feature_weight[f].is_finite() {
                    self.offset += self.feature_weight[f];
                }
                continue;
            }
            keep_feature[f] = true;
            for c in clauses.filter(|&c| !clause_sat[c]) {
                for &l in &self.lits[self.clause_start[c] as usize..self.clause_start[c + 1] as usize] {
                    used[(l >> 1) as usize] = true;
                }
            }
        }
        (keep_feature, used)
    }

    fn contradiction(&self, atom: usize, f: u32, g: u32) -> MlnError {
        let name = self.space.atom(self.atom_pred[atom], self.atom_key[atom]);
        let describe = |f: u32| match self.feature_formula.get(f as usize) {
            Some(&i) if i != EVIDENCE => {
                let fm = &self.mln.formulas[i as usize];
                format!("`{}` ({})", fm.text, fm.at)
            }
            _ => "the evidence".to_string(),
        };
        let at =
            self.feature_formula.get(f as usize).filter(|&&i| i != EVIDENCE).map(|&i| self.mln.formulas[i as usize].at);
        let message = format!(
            "the hard formulas cannot all hold given the evidence: {} and {} disagree on {name}",
            describe(f),
            describe(g)
        );
        MlnError::new(ErrorKind::Unsatisfiable { message }, at).in_text(Source::KnowledgeBase)
    }
}

#[inline]
fn bool_val(b: bool) -> Val {
    if b {
        Val::True
    } else {
        Val::False
    }
}

/// Advances `assign` over the slots like an odometer; false when it wraps around.
fn next_assignment(assign: &mut [u32], slots: &[u32], sizes: &[u32]) -> bool {
    for (i, &s) in slots.iter().enumerate().rev() {
        let v = &mut assign[s as usize];
        *v += 1;
        if *v < sizes[i] {
            return true;
        }
        *v = 0;
    }
    false
}

/// Atom -> clause incidence lists (`clause << 1 | negated`).
fn occurrences(n: usize, lits: &[u32], clause_start: &[u32]) -> (Vec<u32>, Vec<u32>) {
    let mut count = vec![0u32; n + 1];
    for &l in lits {
        count[(l >> 1) as usize + 1] += 1;
    }
    for i in 0..n {
        count[i + 1] += count[i];
    }
    let start = count.clone();
    let mut occ = vec![0u32; lits.len()];
    for c in 0..clause_start.len() - 1 {
        for &l in &lits[clause_start[c] as usize..clause_start[c + 1] as usize] {
            let a = (l >> 1) as usize;
            occ[count[a] as usize] = (c as u32) << 1 | (l & 1);
            count[a] += 1;
        }
    }
    (start, occ)
}

impl Mln {
    /// The unnormalised log probability `sum_i w_i n_i(x)` (eq. 2.4; the table-top prior of
    /// eq. 4.3 is its exponential) of the complete world `world`: atoms it lists as true are
    /// true, all others false. Hard formulas contribute nothing if satisfied and make the
    /// result `-inf` if violated. Constants come from the knowledge base, `config.domains` and
    /// the world; only `domains` and `max_groundings` of `config` matter here.
    pub fn log_weight(&self, world: &Database, config: &GroundConfig) -> Result<f64, MlnError> {
        if world.atoms.iter().any(|a| matches!(a.value, Evidence::Soft(_))) {
            return Err(MlnError::config("a world gives every atom true or false; it cannot hold soft evidence"));
        }
        let space = Space::new(self, world, &config.domains)?;
        let index = space.name_index();
        let truth: HashSet<u64> = world
            .atoms
            .iter()
            .filter(|a| a.value == Evidence::True)
            .map(|a| space.evidence_key(a.pred, &a.args, &index))
            .collect();
        let mut groundings = 0u64;
        let mut total = 0.0;
        for f in &self.formulas {
            if f.weight == Weight::Soft(0.0) {
                continue;
            }
            let types: Vec<u32> = f.vars.iter().map(|v| v.ty.unwrap_or(0)).collect();
            let sizes: Vec<u32> =
                f.free.iter().map(|&s| space.domains[types[s as usize] as usize].len() as u32).collect();
            if sizes.contains(&0) {
                continue;
            }
            let count = sizes.iter().try_fold(1u64, |acc, &s| acc.checked_mul(s as u64)).unwrap_or(u64::MAX);
            groundings = groundings.saturating_add(count);
            if groundings > config.max_groundings {
                return Err(MlnError::too_large("groundings", config.max_groundings));
            }
            let mut assign = vec![0u32; f.vars.len()];
            let mut n_true = 0u64;
            let mut eval = Evaluator {
                space: &space,
                truth: &truth,
                types: &types,
                count: &mut groundings,
                limit: config.max_groundings,
            };
            loop {
                if eval.holds(&f.expr, &mut assign)? {
                    n_true += 1;
                } else if f.weight == Weight::Hard {
                    return Ok(f64::NEG_INFINITY);
                }
                if !next_assignment(&mut assign, &f.free, &sizes) {
                    break;
                }
            }
            if let Weight::Soft(w) = f.weight {
                total += w * n_true as f64;
            }
        }
        Ok(total)
    }
}

/// Truth of a formula in a complete world.
struct Evaluator<'a> {
    space: &'a Space,
    truth: &'a HashSet<u64>,
    types: &'a [u32],
    count: &'a mut u64,
    limit: u64,
}

impl Evaluator<'_> {
    fn holds(&mut self, e: &Expr, assign: &mut [u32]) -> Result<bool, MlnError> {
        Ok(match e {
            Expr::Atom { pred, args } => self.truth.contains(&self.space.key(*pred, args, assign)),
            Expr::Eq(a, b) => {
                self.space.constant(*a, assign, self.types) == self.space.constant(*b, assign, self.types)
            }
            Expr::Not(x) => !self.holds(x, assign)?,
            Expr::And(v) => {
                for x in v {
                    if !self.holds(x, assign)? {
                        return Ok(false);
                    }
                }
                true
            }
            Expr::Or(v) => {
                for x in v {
                    if self.holds(x, assign)? {
                        return Ok(true);
                    }
                }
                false
            }
            Expr::Implies(a, b) => !self.holds(a, assign)? || self.holds(b, assign)?,
            Expr::Equiv(a, b) => self.holds(a, assign)? == self.holds(b, assign)?,
            Expr::Exists(slots, body) | Expr::Forall(slots, body) => {
                let exists = matches!(e, Expr::Exists(..));
                let sizes: Vec<u32> =
                    slots.iter().map(|&s| self.space.domains[self.types[s as usize] as usize].len() as u32).collect();
                if sizes.contains(&0) {
                    return Ok(!exists);
                }
                for &s in slots {
                    assign[s as usize] = 0;
                }
                loop {
                    *self.count += 1;
                    if *self.count > self.limit {
                        return Err(MlnError::too_large("groundings", self.limit));
                    }
                    if self.holds(body, assign)? == exists {
                        return Ok(exists);
                    }
                    if !next_assignment(assign, slots, &sizes) {
                        return Ok(!exists);
                    }
                }
            }
        })
    }
}
