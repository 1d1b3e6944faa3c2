//! The data-driven MCMC of section 4.9: refine the poses, and with them the scene graph,
//! under the posterior `p(M|D) ~ p(D|M) p(M)` (eq. 4.1).
//!
//! # One iteration
//!
//! An iteration is a sweep over the objects. For each object in turn, with the current pose
//! estimate `e_{t,0}`:
//!
//! 1. draw `n` new estimates `e_{t,i}` by adding Gaussian noise to `e_{t,0}` (Fig. 4.16;
//!    see *The noise* below);
//! 2. weight each by the sensor model, `weight(e) = p(D|e)` (eq. 4.4, [`super::sensor`]);
//! 3. the best of them, `e*`, makes the new scene graph `M_{t+1}`: the evidence of the moved
//!    box is recomputed ([`super::evidence`]) and with it the prior `p(M_{t+1})` (eq. 4.3,
//!    [`super::knowledge`]);
//! 4. accept `M_{t+1}` with the Metropolis-Hastings probability of eq. 4.5, whose proposal
//!    probabilities are eqs. 4.6 and 4.7:
//!
//! ```text
//! lambda = min(1, p(M_{t+1}|D) Q(M_t|M_{t+1}) / (p(M_t|D) Q(M_{t+1}|M_t)))           (4.5)
//! Q(M_{t+1}|M_t) = weight(e*)      / (sum_i weight(e_{t,i}) + weight(e_{t,0}))       (4.6)
//! Q(M_t|M_{t+1}) = weight(e_{t,0}) / (sum_i weight(e_{t,i}) + weight(e_{t,0}))       (4.7)
//! ```
//!
//! Everything is computed in log space. Note what the proposal does to eq. 4.5: the
//! likelihood ratio `p(D|e*) / p(D|e_{t,0})` in the posterior ratio is exactly cancelled by
//! `Q(M_t|M_{t+1}) / Q(M_{t+1}|M_t) = weight(e_{t,0}) / weight(e*)`, so `lambda` is the prior
//! ratio `p(M_{t+1}) / p(M_t)` alone. The data steer the chain through the choice of the best
//! of `n` candidates, the knowledge through acceptance: a move that makes the scene less
//! plausible (say, pushes a stable object into another) is accepted only with the ratio of
//! the two worlds' probabilities, one that makes it more plausible always. The chain thus
//! wanders around the poses the data favour, drawn towards the configurations the knowledge
//! favours; the state of highest posterior it visits is the answer.
//!
//! # The noise
//!
//! A pose has six degrees of freedom: a translation (table frame) and a rotation vector
//! applied about the box centre ([`super::sensor::retract`]). How far a candidate should move
//! along each depends on the data: keypoints pin an object down to a fraction of a millimetre
//! across the line of sight but much less along it. So the noise is Gaussian with the
//! covariance `(I + P)^-1`, where `I` is the information the keypoints give about the pose
//! (eq. 4.4's Fisher information at the scene's estimate,
//! [`super::sensor::keypoint_information`]) and `P = diag(1/sigma_t^2, 1/sigma_r^2)` bounds the
//! steps ([`ProposalConfig::sigma_t`], [`ProposalConfig::sigma_r`]; the only term for objects
//! without keypoints). The candidates scale this noise by [`ProposalConfig::scales`] in turn, so
//! that some explore and some refine.
//!
//! The chain remembers the state of highest posterior seen (the MAP estimate of eq. 4.2);
//! [`TabletopChain::best_analysis`] infers the query probabilities for it.
//!
//! Same scene, configuration and seed: same chain, natively and in WebAssembly (ChaCha via
//! [`crate::mcmc::Rng`], transcendental functions from libm).
//!
//! ```
//! use ksmcmc::tabletop::{synth, ChainConfig, TabletopChain};
//!
//! let scene = synth::generate(&synth::SynthConfig::default(), 3).unwrap();
//! let mut chain = TabletopChain::new(scene, ChainConfig::default(), 1).unwrap();
//! let start = chain.best_log_posterior();
//! chain.step(10);
//! assert_eq!(chain.iteration(), 10);
//! assert!(chain.best_log_posterior() >= start);
//! let analysis = chain.best_analysis().unwrap();
//! assert_eq!(analysis.objects.len(), chain.scene().objects.len());
//! ```

use super::evidence::{Evidence, Placed};
use super::geometry::Tolerances;
use super::graph::{self, SceneGraph};
use super::knowledge::{Knowledge, QueryProbabilities};
use super::scene::{Pose, Projector, Scene, SceneError};
use super::sensor::{
    keypoint_information, keypoint_log_likelihood, pose_log_likelihood, retract, rotation_from_vector, SensorConfig,
};
use super::TabletopError;
use crate::mcmc::{accept, Rng, TracePoint};
use crate::setting::{check, InvalidSetting};
use nalgebra::{Isometry3, Matrix6, Translation3, Vector3, Vector6};
use serde::{Deserialize, Serialize};

/// How new pose estimates are drawn (section 4.9, Fig. 4.16).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct ProposalConfig {
    /// Candidates `n` drawn per proposal (default 10).
    pub candidates: u32,
    /// Largest standard deviation of the translation noise per axis, metres (default 0.005).
    pub sigma_t: f64,
    /// Largest standard deviation of the rotation noise per axis, radians (default 0.03).
    pub sigma_r: f64,
    /// Scales of the noise relative to the pose uncertainty, used by the candidates in turn
    /// (default 4, 2, 1, 0.5: long steps while the pose is far from what the data say, short
    /// ones close to it).
    pub scales: [f64; 4],
}

impl Default for ProposalConfig {
    fn default() -> Self {
        ProposalConfig { candidates: 10, sigma_t: 0.005, sigma_r: 0.03, scales: [4.0, 2.0, 1.0, 0.5] }
    }
}

pub use super::decision::{Decision, DecisionRule};

/// Everything that configures the analysis. Every field has a default; JSON with any subset
/// of fields deserialises onto the defaults.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct ChainConfig {
    /// Tolerances of the geometric tests.
    pub tolerances: Tolerances,
    /// The likelihood.
    pub sensor: SensorConfig,
    /// The data-driven proposals.
    pub proposal: ProposalConfig,
    /// Thresholds of the decisions.
    pub decision: DecisionRule,
    /// Scale of the log prior in the posterior: 1 is eq. 4.1, 0 ignores the knowledge while
    /// sampling (the query probabilities still use it). Default 1.
    pub prior_weight: f64,
}

impl Default for ChainConfig {
    fn default() -> Self {
        ChainConfig {
            tolerances: Tolerances::default(),
            sensor: SensorConfig::default(),
            proposal: ProposalConfig::default(),
            decision: DecisionRule::default(),
            prior_weight: 1.0,
        }
    }
}

impl ChainConfig {
    /// Parses a JSON config (missing fields take their defaults; blank text is the defaults)
    /// and validates it: what `ksmcmc tabletop --config` and the wasm `Tabletop` read.
    ///
    /// ```
    /// use ksmcmc::tabletop::ChainConfig;
    /// let c = ChainConfig::from_json(r#"{"prior_weight": 2}"#).unwrap();
    /// assert_eq!(c.prior_weight, 2.0);
    /// let e = ChainConfig::from_json(r#"{"proposal": {"candidates": 0}}"#).unwrap_err();
    /// assert!(e.to_string().starts_with("invalid configuration: proposal.candidates 0 must be"));
    /// ```
    pub fn from_json(text: &str) -> Result<ChainConfig, TabletopError> {
        let c = ChainConfig::parse_json(text)?;
        c.validate()?;
        Ok(c)
    }

    /// Parses a JSON config like [`ChainConfig::from_json`] but leaves validation to the caller.
    pub fn parse_json(text: &str) -> Result<ChainConfig, TabletopError> {
        crate::json::settings(text, r#"{"prior_weight": 2}"#).map_err(TabletopError::Config)
    }

    /// Checks every number, naming the field at fault.
    pub fn validate(&self) -> Result<(), TabletopError> {
        self.check_settings().map_err(TabletopError::Setting)
    }

    fn check_settings(&self) -> Result<(), InvalidSetting> {
        self.tolerances.validate().map_err(|e| e.within("tolerances"))?;
        self.sensor.validate().map_err(|e| e.within("sensor"))?;
        let (p, d) = (&self.proposal, &self.decision);
        let n = p.candidates;
        check(n > 0 && n <= 10_000, "proposal.candidates", n as f64, "between 1 and 10000")?;
        for (name, v) in [("proposal.sigma_t", p.sigma_t), ("proposal.sigma_r", p.sigma_r)] {
            check(v.is_finite() && v > 0.0, name, v, "a positive number")?;
        }
        for &v in &p.scales {
            check(v.is_finite() && v > 0.0 && v <= 100.0, "proposal.scales", v, "positive numbers up to 100")?;
        }
        check((0.0..=1.0).contains(&d.false_below), "decision.false_below", d.false_below, "in [0, 1]")?;
        let ok = d.true_above <= 1.0 && d.true_above >= d.false_below;
        check(ok, "decision.true_above", d.true_above, "from decision.false_below to 1")?;
        let w = self.prior_weight;
        check(w.is_finite() && w >= 0.0, "prior_weight", w, "a non-negative number")
    }
}

/// The analysis of one object.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ObjectAnalysis {
    /// Its id in the scene.
    pub id: String,
    /// The pose analysed.
    pub pose: Pose,
    /// `stable(o)`.
    pub stable: bool,
    /// `hover(o)`.
    pub hover: bool,
    /// The query probabilities.
    pub probabilities: QueryProbabilities,
    /// `hidden(o)` under the decision rule.
    pub hidden: Decision,
    /// `false(o)` under the decision rule.
    pub false_estimate: Decision,
}

/// The result of analysing one state: query probabilities, decisions and the scene graph.
#[derive(Debug, Clone)]
pub struct Analysis {
    /// Per object, in scene order.
    pub objects: Vec<ObjectAnalysis>,
    /// The evidence of the state.
    pub evidence: Evidence,
    /// `log p(M)` (eq. 4.3).
    pub log_prior: f64,
    /// `log p(D|M)` (eq. 4.4, summed over the objects).
    pub log_likelihood: f64,
    /// The scene graph.
    pub graph: SceneGraph,
}

impl Analysis {
    /// The scene graph as JSON ([`graph::to_json`]).
    pub fn graph_json(&self) -> serde_json::Value {
        graph::to_json(&self.graph)
    }
}

/// What the proposals did.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize)]
pub struct ProposalStats {
    /// Data-driven proposals made (one per object per iteration).
    pub proposals: u64,
    /// Proposals accepted by eq. 4.5.
    pub accepted: u64,
    /// Proposals rejected because the knowledge base could not evaluate their evidence (0
    /// unless a custom knowledge base is broken).
    pub prior_failures: u64,
}

impl ProposalStats {
    /// Accepted proposals per proposal (0 before the first).
    pub fn acceptance(&self) -> f64 {
        if self.proposals == 0 {
            0.0
        } else {
            self.accepted as f64 / self.proposals as f64
        }
    }
}

#[derive(Debug, Clone)]
struct Snapshot {
    poses: Vec<Isometry3<f64>>,
    log_likelihood: f64,
    log_prior: f64,
    iteration: u64,
}

/// Most points a table-top chain's trace holds before it is thinned ([`TabletopChain::trace`]).
pub const MAX_TRACE_POINTS: usize = 10_000;

/// The chain: a scene, its current and best poses, and the knowledge base.
#[derive(Debug, Clone)]
pub struct TabletopChain {
    scene: Scene,
    config: ChainConfig,
    knowledge: Knowledge,
    rng: Rng,
    projector: Projector,
    estimates: Vec<Isometry3<f64>>,
    poses: Vec<Isometry3<f64>>,
    placed: Vec<Placed>,
    table: Placed,
    log_lik: Vec<f64>,
    evidence: Evidence,
    log_prior: f64,
    best: Snapshot,
    iteration: u64,
    stats: ProposalStats,
    trace: Vec<TracePoint>,
    /// A trace point is recorded every `trace_every` iterations ([`MAX_TRACE_POINTS`]).
    trace_every: u64,
    candidate_lik: Vec<f64>,
    steps: Vec<Matrix6<f64>>,
}

/// A pose with Gaussian noise: translation `sigma_t` per axis, rotation vector `sigma_r` per
/// axis (applied in the table frame about the box centre).
pub fn perturb(pose: &Isometry3<f64>, sigma_t: f64, sigma_r: f64, rng: &mut Rng) -> Isometry3<f64> {
    let dt = Vector3::new(rng.normal(), rng.normal(), rng.normal()) * sigma_t;
    let dr = rotation_from_vector(&(Vector3::new(rng.normal(), rng.normal(), rng.normal()) * sigma_r));
    Isometry3::from_parts(Translation3::from(pose.translation.vector + dt), dr * pose.rotation)
}

/// `log(sum(exp(x)))` without overflow.
fn log_sum_exp(xs: impl Iterator<Item = f64> + Clone) -> f64 {
    let m = xs.clone().fold(f64::NEG_INFINITY, f64::max);
    if !m.is_finite() {
        return m;
    }
    m + libm::log(xs.map(|x| libm::exp(x - m)).sum::<f64>())
}

impl TabletopChain {
    /// A chain over a scene (validated here), starting from its estimated poses, with the
    /// built-in knowledge base.
    pub fn new(scene: Scene, config: ChainConfig, seed: u64) -> Result<TabletopChain, TabletopError> {
        let n = scene.objects.len();
        Self::with_knowledge(scene, config, seed, Knowledge::new(n))
    }

    /// A chain with a knowledge base of one's own (see [`Knowledge::with_text`]).
    pub fn with_knowledge(
        mut scene: Scene,
        config: ChainConfig,
        seed: u64,
        knowledge: Knowledge,
    ) -> Result<TabletopChain, TabletopError> {
        config.validate()?;
        scene.validate().map_err(TabletopError::Scene)?;
        let n = scene.objects.len();
        if knowledge.names().len() != n + 1 {
            return Err(TabletopError::Config(format!(
                "the knowledge base was set up for {} objects, the scene has {n}",
                knowledge.names().len() - 1
            )));
        }
        let estimates: Vec<_> = scene.objects.iter().map(|o| o.pose.isometry()).collect();
        let table = Placed::new(scene.table.obb());
        let placed: Vec<_> = scene.objects.iter().zip(&estimates).map(|(o, p)| Placed::new(o.obb_at(p))).collect();
        let evidence = Evidence::compute(&placed, &table, &config.tolerances);
        let mut chain = TabletopChain {
            projector: scene.camera.projector(),
            log_lik: Vec::new(),
            poses: estimates.clone(),
            estimates,
            placed,
            table,
            evidence,
            log_prior: 0.0,
            best: Snapshot { poses: Vec::new(), log_likelihood: 0.0, log_prior: 0.0, iteration: 0 },
            knowledge,
            rng: Rng::seed(seed),
            config,
            scene,
            iteration: 0,
            stats: ProposalStats::default(),
            trace: Vec::new(),
            trace_every: 1,
            candidate_lik: Vec::new(),
            steps: Vec::new(),
        };
        chain.steps = (0..n).map(|i| chain.step_factor(i)).collect();
        chain.log_lik = (0..n).map(|i| chain.likelihood(i, &chain.poses[i])).collect();
        chain.log_prior = chain.knowledge.log_prior(&chain.evidence).map_err(TabletopError::Knowledge)?;
        chain.best = Snapshot {
            poses: chain.poses.clone(),
            log_likelihood: chain.log_lik.iter().sum(),
            log_prior: chain.log_prior,
            iteration: 0,
        };
        chain.record();
        Ok(chain)
    }

    /// `log p(D|M)` of object `i` at `pose`: eq. 4.4 with keypoints, the pose Gaussian
    /// without ([`super::sensor`]).
    fn likelihood(&self, i: usize, pose: &Isometry3<f64>) -> f64 {
        let o = &self.scene.objects[i];
        if o.keypoints.is_empty() {
            pose_log_likelihood(pose, &self.estimates[i], &self.config.sensor)
        } else {
            keypoint_log_likelihood(&self.projector, pose, &o.keypoints, &self.config.sensor)
        }
    }

    /// The factor `L` of the proposal covariance `L L^T = (I + P)^-1` of object `i`, where `I`
    /// is the information the keypoints give about its pose at the estimate and `P` the
    /// precision of the largest steps, `diag(1/sigma_t^2 x3, 1/sigma_r^2 x3)`.
    fn step_factor(&self, i: usize) -> Matrix6<f64> {
        let o = &self.scene.objects[i];
        let p = &self.config.proposal;
        let (pt, pr) = (1.0 / (p.sigma_t * p.sigma_t), 1.0 / (p.sigma_r * p.sigma_r));
        let mut a = Matrix6::from_diagonal(&Vector6::new(pt, pt, pt, pr, pr, pr));
        if !o.keypoints.is_empty() {
            a += keypoint_information(&self.projector, &self.estimates[i], &o.keypoints, &self.config.sensor);
        }
        let fallback =
            Matrix6::from_diagonal(&Vector6::new(p.sigma_t, p.sigma_t, p.sigma_t, p.sigma_r, p.sigma_r, p.sigma_r));
        let Some(cov) = a.cholesky().map(|c| c.inverse()) else { return fallback };
        cov.cholesky().map(|c| c.l()).unwrap_or(fallback)
    }

    fn posterior(&self, log_lik: f64, log_prior: f64) -> f64 {
        log_lik + self.config.prior_weight * log_prior
    }

    fn record(&mut self) {
        if self.iteration % self.trace_every != 0 {
            return;
        }
        let lp = self.log_posterior();
        let acceptance = self.stats.acceptance();
        self.trace.push(TracePoint {
            iteration: self.iteration,
            log_posterior: lp,
            acceptance,
            size: self.scene.objects.len() as u32,
        });
        if self.trace.len() >= MAX_TRACE_POINTS {
            // Every other point goes, and points come half as often: the trace still spans the
            // whole run at an even stride, in bounded memory (the soak test saw a page left
            // running grow its heap by tens of MB, one point per iteration).
            let mut k = 0usize;
            self.trace.retain(|_| {
                k += 1;
                k % 2 == 1
            });
            self.trace_every *= 2;
        }
    }

    /// Runs `n` iterations (sweeps over all objects).
    pub fn step(&mut self, n: u32) {
        for _ in 0..n {
            for i in 0..self.scene.objects.len() {
                self.propose(i);
            }
            self.iteration += 1;
            self.record();
        }
    }

    /// One data-driven proposal for object `i` (steps 1 - 4 of the module documentation).
    fn propose(&mut self, i: usize) {
        let p = self.config.proposal;
        let current = self.poses[i];
        let w0 = self.log_lik[i];
        let (mut e_star, mut w_star) = (current, f64::NEG_INFINITY);
        self.candidate_lik.clear();
        for c in 0..p.candidates {
            let z = Vector6::from_fn(|_, _| self.rng.normal());
            let e = retract(&current, &(self.steps[i] * z * p.scales[c as usize % p.scales.len()]));
            let w = self.likelihood(i, &e);
            self.candidate_lik.push(w);
            if w > w_star {
                (e_star, w_star) = (e, w);
            }
        }
        if !w_star.is_finite() {
            // No candidate can be evaluated (only with absurd input): stay.
            return;
        }
        self.stats.proposals += 1;
        // Eqs. 4.6 and 4.7 share the denominator.
        let denom = log_sum_exp(self.candidate_lik.iter().copied().chain(std::iter::once(w0)));
        let (log_q_forward, log_q_back) = (w_star - denom, w0 - denom);

        let old_placed = std::mem::replace(&mut self.placed[i], Placed::new(self.scene.objects[i].obb_at(&e_star)));
        let old_evidence = self.evidence.clone();
        self.evidence.update(i, &self.placed, &self.table, &self.config.tolerances);
        let new_prior = match self.knowledge.log_prior(&self.evidence) {
            Ok(v) => v,
            Err(_) => {
                self.stats.prior_failures += 1;
                f64::NEG_INFINITY
            }
        };
        let total: f64 = self.log_lik.iter().sum();
        let old_post = self.posterior(total, self.log_prior);
        let new_total = total - w0 + w_star;
        let new_post = self.posterior(new_total, new_prior);
        // Eq. 4.5 in log space.
        let log_lambda = new_post - old_post + log_q_back - log_q_forward;
        if new_prior.is_finite() && accept(log_lambda, &mut self.rng) {
            self.stats.accepted += 1;
            self.poses[i] = e_star;
            self.log_lik[i] = w_star;
            self.log_prior = new_prior;
            if new_post > self.posterior(self.best.log_likelihood, self.best.log_prior) {
                self.best = Snapshot {
                    poses: self.poses.clone(),
                    log_likelihood: self.log_lik.iter().sum(),
                    log_prior: new_prior,
                    iteration: self.iteration + 1,
                };
            }
        } else {
            self.placed[i] = old_placed;
            self.evidence = old_evidence;
        }
    }

    /// The scene as given (validated; quaternions normalised).
    pub fn scene(&self) -> &Scene {
        &self.scene
    }

    /// The configuration.
    pub fn config(&self) -> &ChainConfig {
        &self.config
    }

    /// Iterations run.
    pub fn iteration(&self) -> u64 {
        self.iteration
    }

    /// Counts of proposals and acceptances so far.
    pub fn stats(&self) -> ProposalStats {
        self.stats
    }

    /// Prior lookups answered from the cache, and computed.
    pub fn prior_cache_stats(&self) -> (u64, u64) {
        self.knowledge.cache_stats()
    }

    /// Log posterior of the current state.
    pub fn log_posterior(&self) -> f64 {
        self.posterior(self.log_lik.iter().sum(), self.log_prior)
    }

    /// Log posterior of the best state.
    pub fn best_log_posterior(&self) -> f64 {
        self.posterior(self.best.log_likelihood, self.best.log_prior)
    }

    /// The iteration at which the best state was found.
    pub fn best_iteration(&self) -> u64 {
        self.best.iteration
    }

    /// The trace: one point per iteration (and one for the start) until it holds
    /// [`MAX_TRACE_POINTS`]; then every other point is dropped and points are recorded half as
    /// often, so that a long run keeps an evenly spaced trace of bounded size.
    pub fn trace(&self) -> &[TracePoint] {
        &self.trace
    }

    /// The current poses, in scene order.
    pub fn current_poses(&self) -> Vec<Pose> {
        self.poses.iter().map(Pose::from_isometry).collect()
    }

    /// The poses of the best state.
    pub fn best_poses(&self) -> Vec<Pose> {
        self.best.poses.iter().map(Pose::from_isometry).collect()
    }

    /// The current evidence.
    pub fn evidence(&self) -> &Evidence {
        &self.evidence
    }

    /// The scene with the best poses in place of the estimates.
    pub fn best_scene(&self) -> Scene {
        let mut scene = self.scene.clone();
        for (o, p) in scene.objects.iter_mut().zip(self.best_poses()) {
            o.pose = p;
        }
        scene
    }

    /// Analyses the current state.
    pub fn current_analysis(&self) -> Result<Analysis, TabletopError> {
        self.analyse(&self.poses.clone())
    }

    /// Analyses the best state: its query probabilities, decisions and scene graph.
    pub fn best_analysis(&self) -> Result<Analysis, TabletopError> {
        self.analyse(&self.best.poses.clone())
    }

    fn analyse(&self, poses: &[Isometry3<f64>]) -> Result<Analysis, TabletopError> {
        let tol = &self.config.tolerances;
        let placed: Vec<_> = self.scene.objects.iter().zip(poses).map(|(o, p)| Placed::new(o.obb_at(p))).collect();
        let evidence = Evidence::compute(&placed, &self.table, tol);
        let probabilities = self.knowledge.query(&evidence).map_err(TabletopError::Knowledge)?;
        let log_prior = self.knowledge.map_log_weight(&evidence).map_err(TabletopError::Knowledge)?;
        let rule = &self.config.decision;
        let objects: Vec<ObjectAnalysis> = self
            .scene
            .objects
            .iter()
            .enumerate()
            .map(|(i, o)| ObjectAnalysis {
                id: o.id.clone(),
                pose: Pose::from_isometry(&poses[i]),
                stable: evidence.stable(i),
                hover: evidence.hover(i),
                probabilities: probabilities[i],
                hidden: rule.decide(probabilities[i].hidden),
                false_estimate: rule.decide(probabilities[i].false_estimate),
            })
            .collect();
        let boxes: Vec<_> = placed.iter().map(|p| p.obb).collect();
        let ids: Vec<&str> = self.scene.objects.iter().map(|o| o.id.as_str()).collect();
        let graph = graph::build(&ids, &boxes, &self.table.obb, &evidence, &probabilities, rule, tol);
        let log_likelihood = (0..poses.len()).map(|i| self.likelihood(i, &poses[i])).sum();
        Ok(Analysis { objects, evidence, log_prior, log_likelihood, graph })
    }
}

impl From<SceneError> for TabletopError {
    fn from(e: SceneError) -> Self {
        TabletopError::Scene(e)
    }
}
