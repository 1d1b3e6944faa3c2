//! The analysis as JSON for its readers: the live page's summary of the best analysis
//! ([`AnalysisSummary`]) and `report.json` of `ksmcmc tabletop` ([`RunReport`], with the
//! evidence relations as [`EvidencePairs`]).
//!
//! Both are plain [`Serialize`] structs built from an [`Analysis`] and its [`Scene`], so the
//! command line and the WebAssembly bindings write them with serde and hold no JSON of their
//! own. Fields are declared in the order serde_json sorts object keys, which keeps the bytes
//! those readers wrote before.

use super::chain::ProposalStats;
use super::eval::{score, Score};
use super::evidence::Evidence;
use super::scene::Scene;
use super::{Analysis, ChainConfig, Decision, ObjectAnalysis, TabletopChain};
use serde::Serialize;

/// The best analysis as the live page shows it (`Tabletop.analysisJson()`).
///
/// ```
/// use ksmcmc::tabletop::synth::{generate, SynthConfig};
/// use ksmcmc::tabletop::{summary::AnalysisSummary, ChainConfig, TabletopChain};
/// let scene = generate(&SynthConfig::default(), 5).unwrap();
/// let mut chain = TabletopChain::new(scene.clone(), ChainConfig::default(), 1).unwrap();
/// chain.step(2);
/// let a = chain.best_analysis().unwrap();
/// let s = AnalysisSummary::new(&scene, &a, chain.iteration(), chain.best_log_posterior());
/// let v: serde_json::Value = serde_json::to_value(&s).unwrap();
/// assert_eq!(v["iteration"], 2);
/// assert_eq!(v["objects"].as_array().unwrap().len(), scene.objects.len());
/// assert!(v["objects"][0]["truth"].is_object()); // generated scenes know their truth
/// ```
#[derive(Debug, Clone, Serialize)]
pub struct AnalysisSummary<'a> {
    /// The scene graph ([`Analysis::graph_json`]).
    pub graph: serde_json::Value,
    /// Iterations run.
    pub iteration: u64,
    /// `log p(D|M)` of the best state.
    #[serde(rename = "logLikelihood")]
    pub log_likelihood: f64,
    /// The best log posterior.
    #[serde(rename = "logPosterior")]
    pub log_posterior: f64,
    /// `log p(M)` of the best state.
    #[serde(rename = "logPrior")]
    pub log_prior: f64,
    /// Per object, in scene order.
    pub objects: Vec<ObjectSummary<'a>>,
}

/// One object of an [`AnalysisSummary`].
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ObjectSummary<'a> {
    /// `false(o)` under the decision rule.
    #[serde(rename = "false")]
    pub false_estimate: Decision,
    /// `hidden(o)` under the decision rule.
    pub hidden: Decision,
    /// `hover(o)`.
    pub hover: bool,
    /// Its id in the scene.
    pub id: &'a str,
    /// P(false(o)).
    pub p_false: f64,
    /// P(hidden(o)).
    pub p_hidden: f64,
    /// `stable(o)`.
    pub stable: bool,
    /// P(supported(o)).
    pub supported: f64,
    /// P(supportive(o)).
    pub supportive: f64,
    /// The scene's ground truth for it, if the scene has one.
    pub truth: Option<TruthFlags>,
}

/// The ground truth of one object, as the summary gives it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub struct TruthFlags {
    /// It is a false estimate.
    #[serde(rename = "false")]
    pub false_estimate: bool,
    /// An unseen object lies under it.
    pub hidden: bool,
}

impl<'a> AnalysisSummary<'a> {
    /// The summary of `analysis` of `scene` after `iteration` iterations, whose best log
    /// posterior is `log_posterior`.
    pub fn new(scene: &Scene, analysis: &'a Analysis, iteration: u64, log_posterior: f64) -> AnalysisSummary<'a> {
        let objects = analysis
            .objects
            .iter()
            .zip(&scene.objects)
            .map(|(o, s)| ObjectSummary {
                false_estimate: o.false_estimate,
                hidden: o.hidden,
                hover: o.hover,
                id: &o.id,
                p_false: o.probabilities.false_estimate,
                p_hidden: o.probabilities.hidden,
                stable: o.stable,
                supported: o.probabilities.supported,
                supportive: o.probabilities.supportive,
                truth: s.truth.as_ref().map(|t| TruthFlags { false_estimate: t.false_estimate, hidden: t.hidden }),
            })
            .collect();
        AnalysisSummary {
            graph: analysis.graph_json(),
            iteration,
            log_likelihood: analysis.log_likelihood,
            log_posterior,
            log_prior: analysis.log_prior,
            objects,
        }
    }
}

/// The evidence relations as pairs of object ids (`"table"` last): contact and intersection
/// (each pair once, lower index first), and which object is higher than which.
#[derive(Debug, Clone, PartialEq, Eq, Serialize)]
pub struct EvidencePairs<'a> {
    /// Objects in contact.
    pub contact: Vec<[&'a str; 2]>,
    /// `[a, b]`: `a` is higher than `b`.
    pub higher: Vec<[&'a str; 2]>,
    /// Objects whose boxes intersect.
    pub intersect: Vec<[&'a str; 2]>,
}

impl<'a> EvidencePairs<'a> {
    /// The relations of `evidence` over the objects of `scene` and the table.
    pub fn new(scene: &'a Scene, evidence: &Evidence) -> EvidencePairs<'a> {
        let ids: Vec<&str> = scene.objects.iter().map(|o| o.id.as_str()).chain(["table"]).collect();
        let pairs = |f: &dyn Fn(usize, usize) -> bool, symmetric: bool| {
            let mut v = Vec::new();
            for i in 0..ids.len() {
                for j in 0..ids.len() {
                    if i != j && (!symmetric || i < j) && f(i, j) {
                        v.push([ids[i], ids[j]]);
                    }
                }
            }
            v
        };
        EvidencePairs {
            contact: pairs(&|i, j| evidence.contact(i, j), true),
            higher: pairs(&|i, j| evidence.higher(i, j), false),
            intersect: pairs(&|i, j| evidence.intersect(i, j), true),
        }
    }
}

/// `report.json` of `ksmcmc tabletop`: the run's settings and times, the refined objects,
/// the best state's log probabilities, the proposal and prior-cache counts, the evidence, the
/// score against the scene's truth (when it has one) and the configuration.
#[derive(Debug, Clone, Serialize)]
pub struct RunReport<'a> {
    /// The scene's name (its path on the command line).
    pub scene: String,
    /// The seed.
    pub seed: u64,
    /// Iterations run.
    pub iterations: u32,
    /// Seconds of the whole run.
    pub seconds: f64,
    /// Milliseconds per iteration of sampling (0 without iterations).
    pub ms_per_iteration: f64,
    /// Milliseconds of setup.
    pub setup_ms: f64,
    /// Milliseconds of the final inference.
    pub inference_ms: f64,
    /// The analysis of each object.
    pub objects: &'a [ObjectAnalysis],
    /// `log p(M)` of the best state.
    pub log_prior: f64,
    /// `log p(D|M)` of the best state.
    pub log_likelihood: f64,
    /// The best log posterior.
    pub log_posterior: f64,
    /// The iteration of the best state.
    pub best_iteration: u64,
    /// What the proposals did.
    pub proposals: ProposalStats,
    /// Priors taken from the cache and computed.
    pub prior_cache: PriorCache,
    /// The evidence of the best state.
    pub evidence: EvidencePairs<'a>,
    /// The score against the scene's truth, if it has one.
    pub score: Option<Score>,
    /// The chain's configuration.
    pub config: &'a ChainConfig,
}

/// The prior cache's counts.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub struct PriorCache {
    /// Priors found in the cache.
    pub hits: u64,
    /// Priors computed.
    pub computed: u64,
}

/// The times of a run, in seconds.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Timings {
    /// Building the chain.
    pub setup: f64,
    /// The iterations.
    pub sampling: f64,
    /// The final inference.
    pub inference: f64,
    /// The whole run.
    pub total: f64,
}

impl<'a> RunReport<'a> {
    /// The report of `chain` (started from `seed`, run `iterations` times, scene named
    /// `scene`) with its best `analysis` and the `timings`.
    pub fn new(
        chain: &'a TabletopChain,
        analysis: &'a Analysis,
        scene: &str,
        seed: u64,
        iterations: u32,
        timings: Timings,
    ) -> RunReport<'a> {
        let has_truth = chain.scene().objects.iter().any(|o| o.truth.is_some());
        let (hits, computed) = chain.prior_cache_stats();
        RunReport {
            scene: scene.to_string(),
            seed,
            iterations,
            seconds: timings.total,
            ms_per_iteration: if iterations > 0 { 1000.0 * timings.sampling / iterations as f64 } else { 0.0 },
            setup_ms: 1000.0 * timings.setup,
            inference_ms: 1000.0 * timings.inference,
            objects: &analysis.objects,
            log_prior: analysis.log_prior,
            log_likelihood: analysis.log_likelihood,
            log_posterior: chain.best_log_posterior(),
            best_iteration: chain.best_iteration(),
            proposals: chain.stats(),
            prior_cache: PriorCache { hits, computed },
            evidence: EvidencePairs::new(chain.scene(), &analysis.evidence),
            score: has_truth.then(|| score(chain.scene(), analysis)),
            config: chain.config(),
        }
    }

    /// `report.json`'s text: pretty, every object's keys sorted (as serde_json orders a
    /// `Value`), and a final newline.
    pub fn to_json(&self) -> String {
        let value = serde_json::to_value(self).expect("a report serialises");
        serde_json::to_string_pretty(&value).expect("a JSON value serialises") + "\n"
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::tabletop::synth::{generate, SynthConfig};
    use crate::tabletop::{ChainConfig, TabletopChain};
    use serde_json::json;

    /// The structs write the bytes that the bindings' and the command line's `json!` objects
    /// (keys sorted by serde_json) wrote before them.
    #[test]
    fn the_structs_write_what_the_json_objects_wrote() {
        let scene = generate(&SynthConfig::default(), 3).unwrap();
        let mut chain = TabletopChain::new(scene.clone(), ChainConfig::default(), 2).unwrap();
        chain.step(3);
        let a = chain.best_analysis().unwrap();
        let objects: Vec<_> = a
            .objects
            .iter()
            .zip(&scene.objects)
            .map(|(o, s)| {
                json!({
                    "id": o.id, "stable": o.stable, "hover": o.hover,
                    "p_hidden": o.probabilities.hidden, "p_false": o.probabilities.false_estimate,
                    "supported": o.probabilities.supported, "supportive": o.probabilities.supportive,
                    "hidden": o.hidden, "false": o.false_estimate,
                    "truth": s.truth.as_ref().map(|t| json!({ "hidden": t.hidden, "false": t.false_estimate })),
                })
            })
            .collect();
        let old = json!({
            "iteration": chain.iteration(), "logPosterior": chain.best_log_posterior(),
            "logPrior": a.log_prior, "logLikelihood": a.log_likelihood,
            "objects": objects, "graph": a.graph_json(),
        });
        let new = AnalysisSummary::new(&scene, &a, chain.iteration(), chain.best_log_posterior());
        assert_eq!(serde_json::to_string(&new).unwrap(), old.to_string());

        let pairs = EvidencePairs::new(&scene, &a.evidence);
        assert!(!pairs.contact.is_empty(), "objects rest on the table");
        let old = json!({ "contact": pairs.contact, "intersect": pairs.intersect, "higher": pairs.higher });
        assert_eq!(serde_json::to_string_pretty(&pairs).unwrap(), serde_json::to_string_pretty(&old).unwrap());

        let t = Timings { setup: 0.25, sampling: 0.5, inference: 0.125, total: 1.0 };
        let report = RunReport::new(&chain, &a, "s.json", 2, 3, t);
        let (hits, misses) = chain.prior_cache_stats();
        let old = json!({
            "scene": "s.json", "seed": 2, "iterations": 3, "seconds": 1.0,
            "ms_per_iteration": 1000.0 * 0.5 / 3.0, "setup_ms": 250.0, "inference_ms": 125.0,
            "objects": a.objects, "log_prior": a.log_prior, "log_likelihood": a.log_likelihood,
            "log_posterior": chain.best_log_posterior(), "best_iteration": chain.best_iteration(),
            "proposals": chain.stats(), "prior_cache": { "hits": hits, "computed": misses },
            "evidence": pairs, "score": Some(crate::tabletop::eval::score(&scene, &a)), "config": chain.config(),
        });
        assert_eq!(report.to_json(), serde_json::to_string_pretty(&old).unwrap() + "\n");
    }
}
