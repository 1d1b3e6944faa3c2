//! The knowledge base of Tab. 4.1 - 4.3 as a service: the prior of eq. 4.3 and the query
//! probabilities of section 4.10.1, through the crate's Markov logic engine ([`crate::mln`]).
//!
//! The knowledge base is `samples/knowledge/tabletop.mln`, built into the library
//! ([`TABLETOP_MLN`]); another one can be given as text as long as it declares the ten
//! predicates of Tab. 4.1 and 4.2 with their arities.
//!
//! Constants: the table is `T`, object `i` (0-based, in scene order) is `O{i+1}`. Evidence
//! predicates are closed world (atoms the geometry does not make true are false); the four
//! query predicates are open world and inferred.
//!
//! # The prior (eq. 4.3)
//!
//! A scene graph hypothesis `M` is a possible world `x` of the ground network: the evidence
//! atoms that the poses determine, and values of the query atoms. The prior is its
//! unnormalised probability `exp(sum_i w_i n_i(x))`. The evidence fixes part of the world;
//! the query atoms take their most probable values given it (the MAP world, found exactly by
//! enumerating each connected part of the ground network, with MaxWalkSAT as the fallback
//! for parts too large to enumerate). So [`Knowledge::log_prior`] is
//! `max_q sum_i w_i n_i(evidence, q)`. A configuration that the rules cannot explain fully,
//! such as two stable objects intersecting (one of them must be a false estimate, against
//! rule r16), has a lower prior than one they can.
//!
//! The prior depends on the poses only through the evidence, which changes rarely as the
//! chain moves poses by millimetres; it is cached by evidence.
//!
//! ```
//! use ksmcmc::tabletop::evidence::{Evidence, Placed};
//! use ksmcmc::tabletop::geometry::{Obb, Tolerances};
//! use ksmcmc::tabletop::knowledge::Knowledge;
//! use nalgebra::{UnitQuaternion, Vector3};
//!
//! let table = Placed::new(Obb::table([1.0, 1.0], 0.05));
//! // A box hovering 5 cm above the table, touching nothing: something must hold it up.
//! let hovering = Obb::new(Vector3::new(0.0, 0.0, 0.1), UnitQuaternion::identity(), Vector3::new(0.1, 0.1, 0.1));
//! let ev = Evidence::compute(&[Placed::new(hovering)], &table, &Tolerances::default());
//! assert!(ev.hover(0));
//! let mut kb = Knowledge::new(1);
//! let q = kb.query(&ev).unwrap();
//! assert!(q[0].hidden > 0.6); // rule r13: a hovering object hides a support under it
//! assert!(q[0].false_estimate < 0.4); // rule r16: a stable one is rarely a false estimate
//! ```

use super::evidence::Evidence;
use crate::mln::{
    Database, Evidence as Atom, GroundConfig, InferenceConfig, MapConfig, MapMethod, Method, Mln, MlnError, Network,
};
use std::collections::HashMap;

/// The table-top knowledge base (Tab. 4.1 - 4.3), `samples/knowledge/tabletop.mln`.
pub const TABLETOP_MLN: &str = include_str!("../../samples/knowledge/tabletop.mln");

/// The evidence predicates of Tab. 4.1 with their arities.
pub const EVIDENCE_PREDICATES: [(&str, usize); 6] =
    [("stable", 1), ("table", 1), ("contact", 2), ("intersect", 2), ("hover", 1), ("higher", 2)];

/// The query predicates of Tab. 4.2.
pub const QUERY_PREDICATES: [&str; 4] = ["supported", "supportive", "hidden", "false"];

/// The most cached priors kept before the cache is emptied.
const CACHE_LIMIT: usize = 1 << 16;

/// The query probabilities of one object (or the table).
#[derive(Debug, Clone, Copy, PartialEq, Default, serde::Serialize)]
pub struct QueryProbabilities {
    /// `supported(o)`.
    pub supported: f64,
    /// `supportive(o)`.
    pub supportive: f64,
    /// `hidden(o)`: an unseen object lies under it.
    pub hidden: f64,
    /// `false(o)`: it is a false estimate.
    pub false_estimate: f64,
}

/// The knowledge base grounded over one scene's objects, with a cache of priors.
#[derive(Debug, Clone)]
pub struct Knowledge {
    mln: Mln,
    names: Vec<String>,
    cache: HashMap<Vec<u64>, f64>,
    hits: u64,
    misses: u64,
}

impl Knowledge {
    /// The built-in knowledge base ([`TABLETOP_MLN`]) over `objects` objects and the table.
    pub fn new(objects: usize) -> Knowledge {
        Knowledge::with_text(TABLETOP_MLN, objects).expect("the built-in knowledge base is valid")
    }

    /// A knowledge base from text. It must declare the predicates of Tab. 4.1 and 4.2 (names
    /// and arities as in [`EVIDENCE_PREDICATES`] and [`QUERY_PREDICATES`], the latter unary).
    pub fn with_text(text: &str, objects: usize) -> Result<Knowledge, MlnError> {
        let mln = Mln::parse(text)?;
        let wanted = EVIDENCE_PREDICATES.iter().copied().chain(QUERY_PREDICATES.iter().map(|&q| (q, 1)));
        for (name, arity) in wanted {
            match mln.predicate(name) {
                Some(p) if p.arity() == arity => {}
                Some(p) => {
                    return Err(MlnError::config(format!(
                        "the table-top knowledge base needs {name} with {arity} argument(s), not {}",
                        p.arity()
                    )))
                }
                None => {
                    return Err(MlnError::config(format!(
                        "the table-top knowledge base must declare the predicate {name} (Tab. 4.1 / 4.2)"
                    )))
                }
            }
        }
        let mut names: Vec<String> = (1..=objects).map(|i| format!("O{i}")).collect();
        names.push("T".to_string());
        Ok(Knowledge { mln, names, cache: HashMap::new(), hits: 0, misses: 0 })
    }

    /// The constant of each box: `O1 .. On` for the objects, then `T` for the table.
    pub fn names(&self) -> &[String] {
        &self.names
    }

    /// The parsed knowledge base.
    pub fn mln(&self) -> &Mln {
        &self.mln
    }

    /// Prior lookups answered from the cache, and computed.
    pub fn cache_stats(&self) -> (u64, u64) {
        (self.hits, self.misses)
    }

    fn ground_config(&self) -> GroundConfig {
        let mut config = GroundConfig::query(&QUERY_PREDICATES);
        config.closed_world = EVIDENCE_PREDICATES.iter().map(|(p, _)| p.to_string()).collect();
        // The argument type of the predicates: whatever the knowledge base calls it.
        let ty = self
            .mln
            .predicate("table")
            .map(|p| self.mln.argument_types(p)[0].to_string())
            .unwrap_or_else(|| "object".into());
        config.domains = vec![(ty, self.names.clone())];
        config
    }

    /// The evidence as an engine database.
    pub fn database(&self, ev: &Evidence) -> Result<Database, MlnError> {
        if ev.objects() + 1 != self.names.len() {
            return Err(MlnError::config(format!(
                "the evidence is about {} objects, the knowledge base was set up for {}",
                ev.objects(),
                self.names.len() - 1
            )));
        }
        let mut db = Database::new();
        for (pred, args) in ev.atoms(&self.names) {
            db.insert(&self.mln, pred, &args, Atom::True)?;
        }
        Ok(db)
    }

    /// The ground network of the knowledge base with this evidence.
    pub fn network(&self, ev: &Evidence) -> Result<Network, MlnError> {
        Network::ground(&self.mln, &self.database(ev)?, &self.ground_config())
    }

    /// `log p(M)` of eq. 4.3: the log weight `sum_i w_i n_i(x)` of the most probable world
    /// consistent with the evidence (see the module documentation). Cached by evidence.
    pub fn log_prior(&mut self, ev: &Evidence) -> Result<f64, MlnError> {
        let key = ev.key();
        if let Some(&v) = self.cache.get(&key) {
            self.hits += 1;
            return Ok(v);
        }
        self.misses += 1;
        let v = self.map_log_weight(ev)?;
        if self.cache.len() >= CACHE_LIMIT {
            self.cache.clear();
        }
        self.cache.insert(key, v);
        Ok(v)
    }

    /// [`Knowledge::log_prior`] without the cache.
    pub fn map_log_weight(&self, ev: &Evidence) -> Result<f64, MlnError> {
        let net = self.network(ev)?;
        let exact = MapConfig { method: MapMethod::Exact, ..Default::default() };
        let world = match net.map(&exact) {
            Ok(w) => w,
            // A connected part too large to enumerate: local search instead (seeded, so the
            // result is still a function of the evidence).
            Err(_) => net.map(&MapConfig { method: MapMethod::MaxWalkSat, tries: 5, ..Default::default() })?,
        };
        Ok(world.log_weight())
    }

    /// The query probabilities of every box (objects in order, then the table), exactly
    /// (junction tree) where the network allows, by MC-SAT otherwise.
    pub fn query(&self, ev: &Evidence) -> Result<Vec<QueryProbabilities>, MlnError> {
        let net = self.network(ev)?;
        let exact = InferenceConfig { method: Method::Exact, ..Default::default() };
        let marginals = match net.infer_marginals(&exact) {
            Ok(m) => m,
            Err(_) => {
                net.infer_marginals(&InferenceConfig { method: Method::McSat, samples: 20_000, ..Default::default() })?
            }
        };
        Ok(self
            .names
            .iter()
            .map(|name| {
                let p = |pred: &str| marginals.get(pred, &[name.as_str()]).unwrap_or(0.0);
                QueryProbabilities {
                    supported: p("supported"),
                    supportive: p("supportive"),
                    hidden: p("hidden"),
                    false_estimate: p("false"),
                }
            })
            .collect())
    }
}
