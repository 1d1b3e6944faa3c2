//! Markov logic networks: knowledge as weighted first-order rules, queried as probabilities.
//!
//! Both use cases of the dissertation ask a knowledge base questions. The floor-plan chain
//! asks how likely two adjacent units are to have walls of the same length, `SaLe(u_p,u_q)`,
//! given their geometry (section 3.8, Tab. 3.3 - 3.5); the table-top chain asks how probable a
//! scene graph is under physical rules (section 4.5, eq. 4.3). A Markov logic network
//! (Richardson and Domingos 2006; chapter 2.2) answers both: a set of first-order formulas
//! `F_i` with weights `w_i` which, given constants, defines the distribution
//! `P(x) = exp(sum_i w_i n_i(x)) / Z` over worlds `x`, where `n_i(x)` counts the true
//! groundings of `F_i` (eq. 2.4). A world violating a soft formula is less probable, not
//! impossible; hard formulas (infinite weight) do make it impossible.
//!
//! This module is self-contained: it depends on the rest of the crate only for the
//! deterministic random number generator [`crate::mcmc::Rng`], does no I/O, and runs
//! unchanged in WebAssembly.
//!
//! # Workflow
//!
//! 1. [`Mln::parse`] reads a knowledge base; [`Database::parse`] (or [`Database::insert`])
//!    the evidence.
//! 2. [`Network::ground`] grounds the formulas over the constants, simplifying every grounding
//!    by the evidence, and returns a compact ground network over the unknown atoms.
//! 3. [`Network::infer_marginals`] gives query marginals, [`Network::map`] the most probable
//!    world, [`Network::log_weight`] (or [`Mln::log_weight`] on a complete world) the
//!    unnormalised log probability `sum_i w_i n_i(x)` of eq. 4.3.
//!
//! [`learn_weights`] goes the other way: from complete training worlds to the weights of the
//! soft formulas, by pseudo-likelihood or discriminatively ([`LearnMethod`]), and
//! [`Learned::to_mln`] writes the knowledge base back with them.
//!
//! ```
//! use ksmcmc::mln::{Database, GroundConfig, InferenceConfig, Method, Mln, Network};
//!
//! let mln = Mln::parse(
//!     "Smokes(person)\n\
//!      Cancer(person)\n\
//!      log(0.9/0.1) Smokes(x) => Cancer(x)   // smoking causes cancer, 9 times in 10\n",
//! )?;
//! let db = Database::parse("Smokes(Anna)", &mln)?;
//! let net = Network::ground(&mln, &db, &GroundConfig::query(&["Cancer"]))?;
//! let config = InferenceConfig { method: Method::Exact, ..Default::default() };
//! let p = net.infer_marginals(&config)?.get("Cancer", &["Anna"]).unwrap();
//! assert!((p - 0.9).abs() < 1e-12);
//! # Ok::<(), ksmcmc::mln::MlnError>(())
//! ```
//!
//! # Knowledge-base format
//!
//! The Alchemy / ProbCog / pracmln text format, one statement per line:
//!
//! ```text
//! // comments run to the end of the line; /* block comments */ too
//! unit = {U1, U2, U3}                  // optional: a closed domain for a type
//! Adj(unit, unit)                      // a predicate declaration: name and argument types
//! Room(unit)
//! 1.5 Room(x) ^ Adj(x,y) => Room(y)    // a soft formula: weight, then formula
//! log(0.9/0.1) Hall(x) => !Room(x)     // weights are arithmetic: numbers, + - * / ( ), log, exp
//! Adj(x,y) => Adj(y,x).                // a hard formula ends in '.' and has no weight
//! 0.5 Room(x) => EXIST y (Adj(x,y) ^ Room(y))
//! ```
//!
//! * Connectives, tightest first: `!` (not), `^` (and), `v` (or), `=>` (implies, groups to
//!   the right), `<=>` (equivalence); parentheses group. `x = y` and `x != y` compare
//!   constants.
//! * `EXIST x,y F` (also `exist`) and `FORALL x F` (also `forall`) quantify; the body reaches
//!   as far right as possible. Free variables are universally quantified, as usual.
//! * Names starting with a lower-case letter (or `_`) are variables, names starting with a
//!   capital or digit are constants. Predicate names may be either (`false(o)` is fine).
//! * A bare atom on a line of its own, without weight or period, declares a predicate; its
//!   arguments are type names. Predicates must be declared before formulas use them.
//! * Formulas with quantifiers are converted to clauses one grounding at a time, after the
//!   evidence has simplified them, which keeps `EXIST` over large domains tractable.
//!
//! Evidence databases hold one ground atom per line: `Adj(U1,U2)` (true), `!Adj(U1,U3)`
//! (false) or `0.8 RoLi(U1)` (soft evidence, see below); `//` comments and blank lines as
//! above.
//!
//! # Domains, open and closed world
//!
//! A type's constants are those of its `type = {...}` declaration, those the formulas mention,
//! those given in [`GroundConfig::domains`], and those the evidence mentions. A type declared
//! in the knowledge base or given in `domains` is *closed*: evidence naming another constant
//! of it is an error ([`ErrorKind::UnknownConstant`]), since it is most likely a typo. Other
//! types are open and grow with the evidence.
//!
//! Query predicates and those in [`GroundConfig::open_world`] are open world: their atoms the
//! evidence does not mention are unknown and inferred. Predicates in
//! [`GroundConfig::closed_world`] are closed world: unmentioned atoms are false. The rest
//! follow Alchemy: closed world if the evidence mentions the predicate at all, open
//! otherwise. (So an evidence predicate none of whose atoms happens to be true in a scene
//! must be listed in `closed_world`, or given as `!Pred(...)` lines, to count as false.)
//!
//! # Hard formulas and soft evidence
//!
//! Hard formulas are constraints, not large weights, in every method: exact inference gives
//! violating worlds probability zero, MC-SAT always keeps hard clauses, Gibbs sampling starts
//! from a world satisfying them (found by WalkSAT) and gives moves that violate one
//! probability zero (sampling atoms tied by hard formulas jointly), and MaxWalkSAT compares
//! worlds by hard violations first. Evidence contradicting a hard formula is an error
//! ([`ErrorKind::Unsatisfiable`]) naming the formula and the constants.
//!
//! Soft evidence `p Pred(A)` adds the unit clause `Pred(A)` with weight `log(p / (1 - p))`:
//! alone, the atom's marginal is exactly `p`; together with the formulas, `p` acts as prior
//! odds that the formulas then update (it is not a constraint on the posterior marginal).
//! `p !Pred(A)` means `(1 - p) Pred(A)`.
//!
//! # Inference
//!
//! * [`Method::Exact`]: sum-product message passing on a junction tree (variable elimination
//!   in min-fill order), exact and fast whenever the network is thin, as both use cases'
//!   networks are (the indoor rules over 20 units: cliques of at most 12 atoms, about 3 ms);
//!   falls back to enumeration for small connected parts, and refuses the rest.
//! * [`Method::Enumerate`]: enumeration of each connected part of the ground network
//!   (Gray-code order, incremental weights); refuses parts above `max_exact_atoms` (24).
//! * [`Method::McSat`]: MC-SAT; the uniform draw from the slice is made by moves that stay on
//!   it ([`SliceMoves::Uniform`], exact) or by Poon and Domingos' SampleSAT
//!   ([`SliceMoves::SampleSat`]: WalkSAT and simulated annealing, slightly biased). One Gibbs
//!   sweep follows each step by default ([`InferenceConfig::gibbs_sweeps`]).
//! * [`Method::Gibbs`]: Gibbs sampling, blocked over atoms tied by hard formulas.
//! * [`Method::Auto`] (the default): the junction tree when its cliques have at most
//!   [`AUTO_EXACT_ATOMS`] atoms, MC-SAT otherwise.
//! * [`MapMethod::MaxWalkSat`] / [`MapMethod::Exact`] for the most probable world.
//!
//! Both samplers report Rao-Blackwellised estimates: the average over the chain of each
//! atom's probability given all others, not of its sampled value. Sampling is for networks
//! too wide for the junction tree; on the thin networks of the two use cases the samplers
//! mix slowly where whole groups of atoms must change together (a hall and the `SaLe` atoms
//! of all its neighbours), which exact inference does not mind.
//!
//! Ground networks are flat arrays (literals `atom << 1 | negated`, clauses and features as
//! ranges, atom-to-clause incidence lists) with per-clause true-literal counts updated flip by
//! flip, so samplers and local search allocate nothing in their inner loops.
//!
//! Everything random draws from one [`crate::mcmc::Rng`] seeded from the configuration, so a
//! seed fixes the result on every platform.

mod error;
mod ground;
mod infer;
mod kb;
mod lbfgs;
mod learn;
mod logic;
mod syntax;

pub use error::{ErrorKind, MlnError, Position, RuleError, Source, UnknownMethod};

/// Longest knowledge base text [`Mln::parse`] reads, bytes (16 MiB; the samples are a few KB).
pub const MAX_KB_BYTES: usize = 16 << 20;
/// Longest evidence text [`Database::parse`] reads, bytes (64 MiB: training databases of many
/// worlds are the largest).
pub const MAX_EVIDENCE_BYTES: usize = 64 << 20;

/// The error for text over `limit` bytes.
pub(crate) fn text_too_long(what: &str, len: usize, limit: usize, name: &str) -> MlnError {
    MlnError::config(format!(
        "the {what} is {len} bytes, over the limit of {limit} bytes ({name}); split it or check that \
         this is the file you meant"
    ))
}
pub use ground::{GroundConfig, Network};
pub use infer::{InferenceConfig, MapConfig, MapMethod, MapWorld, Marginals, Method, SliceMoves, AUTO_EXACT_ATOMS};
pub use kb::{Database, Evidence, Formula, GroundAtom, Mln, Predicate, Weight};
pub use learn::{learn_weights, LearnConfig, LearnMethod, Learned, Learner};
