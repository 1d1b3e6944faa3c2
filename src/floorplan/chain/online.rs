//! The floor plan following a robot that explores (dissertation § 3.5, Fig. 3.40), and what a
//! warm chain saves over starting again.
//!
//! [`explore`] drives a simulated robot ([`crate::explore`]) over a true map. Every
//! `update_every_m` metres it hands the robot's map to the chain ([`Chain::update_map`]) and
//! runs `iterations` more. To measure the warm start it also starts a cold chain on the same
//! snapshot, with the same seed and up to five times as many iterations (a cold chain that
//! never comes back counts its whole budget, so the budget must leave it room to show what
//! it needs: `cold_budget`), and notes for each how many
//! iterations it took to come within 0.1 % of the better of the two best log posteriors (the
//! reference). A warm chain that keeps most of its world needs few; a cold one climbs from the
//! empty world every time. The cold chain's walls are as thick as the warm chain's rings at
//! that update (measured on walls seen from both sides, which the cold chain alone would
//! measure on the snapshot as seen from one), so that both climb the same posterior.
//!
//! Pass [`ChainConfig::online`] for a robot's map, as `ksmcmc explore` does: its range-sensor
//! table lays a wall's ring behind the face the robot saw.
//!
//! A [`Guide`] ([`explore_guided`]) steers the robot: after each update it may give targets
//! (the plan's placeholders weighed for a goal, `export::guide`) and it may end the
//! exploration when what it looks for is found. [`explore`] follows the nearest frontier.

pub use super::guide::GoalGuide;
use super::posterior::SensorModel;
use super::{Chain, ChainConfig, ChainError};
use crate::explore::{ExploreConfig, ExploreError, Explorer, Target};
use crate::floorplan::metrics;
use crate::grid::{Cell, OccupancyMap};
use serde::{Deserialize, Serialize};

/// How the chain follows the robot.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct OnlineConfig {
    /// The robot and its sensor.
    pub explore: ExploreConfig,
    /// Metres driven between two updates of the chain's map (default 10).
    pub update_every_m: f64,
    /// Iterations the chain runs after each update (default 20,000).
    pub iterations: u64,
    /// Most updates; the robot stops there even if frontiers remain (default 200).
    pub max_updates: usize,
    /// Whether to run a cold chain on every snapshot to compare (default true).
    pub measure_cold: bool,
    /// Iterations the cold chain of each update may run, at least `iterations`; 0 (the
    /// default) is [`COLD_FACTOR`] times `iterations`. A cold chain that never comes back
    /// counts its whole budget, fewer than it needs: with the warm chain's budget alone, most
    /// cold chains on the generated floors did (BENCHMARKS, "Cold chains given room").
    pub cold_budget: u64,
    /// Whether a finished exploration ends as `ksmcmc floorplan` would explain its last map
    /// (default true; [`Renewal`]). Once the robot has no frontier left the map stops
    /// changing and its walls are seen from both sides wherever the robot could go, so the
    /// warm chain takes the whole-map sensor table ([`SensorModel::default`], Tab. 3.1) in
    /// place of the range-sensor table and climbs for the cold budget; a fresh chain with
    /// that table, measuring its walls on the last map, climbs as long, and replaces the warm
    /// chain if its best log posterior is higher (units the warm chain made while the map was
    /// partial are otherwise never undone).
    pub renew: bool,
}

impl Default for OnlineConfig {
    fn default() -> Self {
        OnlineConfig {
            explore: ExploreConfig::default(),
            update_every_m: 10.0,
            iterations: 20_000,
            max_updates: 200,
            measure_cold: true,
            cold_budget: 0,
            renew: true,
        }
    }
}

/// How many times the warm chain's iterations a cold chain may run by default
/// ([`OnlineConfig::cold_budget`]).
pub const COLD_FACTOR: u64 = 5;

/// How close to the reference counts as back (eq.: `L ≥ L_ref - 0.001 |L_ref|`).
pub const WITHIN: f64 = 0.001;

/// How often (iterations) the best log posterior is sampled to find when a chain came back.
pub const STRIDE: u64 = 100;

/// One update of the chain's map.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct UpdateRecord {
    /// 1 for the first update (0 is the chain's start on the first snapshot).
    pub update: usize,
    /// The robot's cell `[column, row]`.
    pub robot: [usize; 2],
    /// Metres driven so far.
    pub travelled_m: f64,
    /// Free and occupied cells of the robot's map.
    pub seen_free: usize,
    /// Occupied cells of the robot's map.
    pub seen_occupied: usize,
    /// Cells whose class changed since the last update (world frame).
    pub changed_cells: usize,
    /// Unit candidates the wall detector scored again.
    pub candidates_added: usize,
    /// Iterations the warm chain needed to come within 0.1 % of the reference (the whole
    /// budget if it did not).
    pub warm_iterations: u64,
    /// The same for the cold chain; `None` when cold chains are not measured.
    pub cold_iterations: Option<u64>,
    /// Whether the warm chain came within 0.1 % in its budget.
    pub warm_reached: bool,
    /// Whether the cold chain did.
    pub cold_reached: Option<bool>,
    /// The better best log posterior of the two chains.
    pub reference_log_posterior: f64,
    /// The warm chain's best after its iterations.
    pub warm_best_log_posterior: f64,
    /// The cold chain's best after its iterations.
    pub cold_best_log_posterior: Option<f64>,
    /// Units of the warm chain's best world.
    pub units: usize,
    /// K(W, M) of the warm chain's best world on the robot's map.
    pub cell_prediction_rate: f64,
    /// The cells where the robot scanned since the last update.
    pub scans: Vec<[usize; 2]>,
}

/// Why an exploration could not run.
#[derive(Debug, Clone, PartialEq)]
pub enum OnlineError {
    /// The robot cannot explore the map.
    Explore(ExploreError),
    /// The chain cannot start on the first snapshot, or an update was refused.
    Chain(ChainError),
    /// A setting is out of range.
    Config(String),
    /// The guide could not weigh the plan's frontiers.
    Guide(ChainError),
}

impl std::fmt::Display for OnlineError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            OnlineError::Explore(e) => e.fmt(f),
            OnlineError::Chain(e) => e.fmt(f),
            OnlineError::Config(m) => write!(f, "online settings: {m}"),
            OnlineError::Guide(m) => write!(f, "choosing where to explore: {m}"),
        }
    }
}

impl std::error::Error for OnlineError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            OnlineError::Explore(e) => Some(e),
            OnlineError::Chain(e) | OnlineError::Guide(e) => Some(e),
            OnlineError::Config(_) => None,
        }
    }
}

impl OnlineConfig {
    /// The iterations each cold chain may run ([`OnlineConfig::cold_budget`]).
    pub fn cold_iterations(&self) -> u64 {
        match self.cold_budget {
            0 => COLD_FACTOR.saturating_mul(self.iterations),
            b => b.max(self.iterations),
        }
    }

    /// Checks every setting, saying which is out of range.
    pub fn validate(&self) -> Result<(), OnlineError> {
        self.explore.validate().map_err(OnlineError::Explore)?;
        if !(self.update_every_m.is_finite() && self.update_every_m > 0.0) {
            return Err(OnlineError::Config(format!("update_every_m {} must be positive", self.update_every_m)));
        }
        if self.iterations == 0 || self.iterations > 100_000_000 {
            return Err(OnlineError::Config(format!("iterations {} must be 1 to 10^8", self.iterations)));
        }
        if self.cold_budget > 500_000_000 {
            return Err(OnlineError::Config(format!(
                "cold_budget {} must be at most 5 x 10^8 (0: five times the iterations)",
                self.cold_budget
            )));
        }
        if self.max_updates == 0 || self.max_updates > 100_000 {
            return Err(OnlineError::Config(format!("max_updates {} must be 1 to 100000", self.max_updates)));
        }
        Ok(())
    }
}

/// The end of a finished exploration ([`OnlineConfig::renew`]): the warm chain under the
/// whole-map sensor table, and a fresh chain under it.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Renewal {
    /// Iterations each chain ran under the whole-map table (the cold budget).
    pub iterations: u64,
    /// The warm chain's best log posterior on the last map, before the table changed.
    pub range_sensor_log_posterior: f64,
    /// K(W, M) of the warm chain's best world then.
    pub range_sensor_cell_prediction_rate: f64,
    /// Units of its best world then.
    pub range_sensor_units: usize,
    /// The warm chain's best log posterior on the last map under the whole-map table.
    pub warm_log_posterior: f64,
    /// The fresh chain's.
    pub fresh_log_posterior: f64,
    /// Units of the warm chain's best world.
    pub warm_units: usize,
    /// Units of the fresh chain's best world.
    pub fresh_units: usize,
    /// K(W, M) of the warm chain's best world on the last map.
    pub warm_cell_prediction_rate: f64,
    /// K(W, M) of the fresh chain's.
    pub fresh_cell_prediction_rate: f64,
    /// Whether the fresh chain replaced the warm one (its best log posterior is higher).
    pub adopted: bool,
}

/// A finished exploration.
#[derive(Debug, Clone)]
pub struct Exploration {
    /// The chain on the robot's last map: the warm chain, or the fresh chain that replaced it
    /// ([`Exploration::renewal`]).
    pub chain: Chain,
    /// The robot, at its last cell.
    pub explorer: Explorer,
    /// Every update, in order.
    pub timeline: Vec<UpdateRecord>,
    /// The fresh chain at the end, when the robot finished and [`OnlineConfig::renew`] asked
    /// for one.
    pub renewal: Option<Renewal>,
}

impl Exploration {
    /// Updates after the start.
    pub fn updates(&self) -> usize {
        self.timeline.len()
    }

    /// Warm iterations summed over the updates.
    pub fn warm_iterations(&self) -> u64 {
        self.timeline.iter().map(|r| r.warm_iterations).sum()
    }

    /// Cold iterations summed over the updates (`None` if not measured).
    pub fn cold_iterations(&self) -> Option<u64> {
        self.timeline.iter().map(|r| r.cold_iterations).sum()
    }
}

/// What steers an exploration: where the robot should look next, and when it has found what
/// it looks for.
pub trait Guide {
    /// The targets the robot weighs until the next update, given the chain after it took the
    /// robot's map ([`Explorer::set_targets`]); none: the nearest frontier.
    fn targets(&mut self, chain: &mut Chain, explorer: &Explorer) -> Result<Vec<Target>, ChainError>;

    /// Whether the robot has found what it looks for and may stop (checked as it drives,
    /// every 16 cells).
    fn found(&mut self, _explorer: &Explorer) -> bool {
        false
    }
}

/// The nearest frontier, to the end: the guide of [`explore`].
#[derive(Debug, Clone, Copy, Default)]
pub struct Nearest;

impl Guide for Nearest {
    fn targets(&mut self, _chain: &mut Chain, _explorer: &Explorer) -> Result<Vec<Target>, ChainError> {
        Ok(Vec::new())
    }
}

/// Explores `truth` with a simulated robot and follows it with a chain (module docs).
/// `progress` sees each update as it is made.
///
/// ```
/// use ksmcmc::floorplan::online::{explore, OnlineConfig};
/// use ksmcmc::floorplan::{synth, ChainConfig};
/// let s = synth::generate(&synth::SynthConfig { width: 200, height: 140, ..Default::default() }, 2)?;
/// let config = OnlineConfig { update_every_m: 6.0, iterations: 3000, ..Default::default() };
/// let run = explore(&s.map, &ChainConfig::default(), &config, 1, &mut |_| {})?;
/// assert!(run.updates() >= 2);
/// assert!(run.warm_iterations() <= run.cold_iterations().unwrap());
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn explore(
    truth: &OccupancyMap,
    chain_config: &ChainConfig,
    config: &OnlineConfig,
    seed: u64,
    progress: &mut dyn FnMut(&UpdateRecord),
) -> Result<Exploration, OnlineError> {
    explore_guided(truth, chain_config, config, seed, progress, &mut Nearest)
}

/// [`explore`] steered by `guide`: after the chain's start and each update the robot takes the
/// guide's targets, and it stops (with an update on its last map) once the guide has found
/// what it looks for.
pub fn explore_guided(
    truth: &OccupancyMap,
    chain_config: &ChainConfig,
    config: &OnlineConfig,
    seed: u64,
    progress: &mut dyn FnMut(&UpdateRecord),
    guide: &mut dyn Guide,
) -> Result<Exploration, OnlineError> {
    config.validate()?;
    let mut explorer = Explorer::new(truth, config.explore, seed).map_err(OnlineError::Explore)?;
    let mut next = config.update_every_m;
    let mut found = drive(&mut explorer, next, guide);
    let mut chain = Chain::new(&explorer.snapshot(), chain_config.clone(), seed).map_err(OnlineError::Chain)?;
    chain.step(config.iterations);
    explorer.set_targets(guide.targets(&mut chain, &explorer).map_err(OnlineError::Guide)?);
    let mut timeline = Vec::new();
    let mut scanned = explorer.scans().len();
    while !found && !explorer.is_done() && timeline.len() < config.max_updates {
        next += config.update_every_m;
        found = drive(&mut explorer, next, guide);
        let record = update(&mut chain, &explorer, chain_config, config, seed, timeline.len() + 1, scanned)?;
        scanned = explorer.scans().len();
        progress(&record);
        timeline.push(record);
        if !found {
            explorer.set_targets(guide.targets(&mut chain, &explorer).map_err(OnlineError::Guide)?);
            // A guide may find what it looks for in the plan itself.
            found = guide.found(&explorer);
        }
    }
    let renewal = if config.renew && explorer.is_done() {
        Some(renew(&mut chain, &explorer.snapshot(), chain_config, config, seed)?)
    } else {
        None
    };
    Ok(Exploration { chain, explorer, timeline, renewal })
}

/// The end of a finished exploration on its last map `last` ([`OnlineConfig::renew`]): the
/// warm chain under the whole-map table, and a fresh chain with it, each for the cold budget; the fresh chain replaces `chain` if its best log posterior is
/// higher.
fn renew(
    chain: &mut Chain,
    last: &OccupancyMap,
    chain_config: &ChainConfig,
    config: &OnlineConfig,
    seed: u64,
) -> Result<Renewal, OnlineError> {
    // K(W, M) on the last map and the units of a chain's best world, which is built once.
    let k_and_units = |c: &Chain| {
        let best = c.best_world();
        (metrics::prediction_rate(last.classified(), &best), best.units.len())
    };
    let range_lp = chain.best_log_posterior();
    let (range_k, range_units) = k_and_units(chain);
    let sensor = SensorModel::default();
    chain.set_sensor(sensor);
    chain.step(config.cold_iterations());
    // The fresh chain measures its walls on the last map, as `ksmcmc floorplan` does (unless
    // the configuration sets them): their unseen cores read unknown there, and a ring as deep
    // as the walls seen from both sides predicts them occupied.
    let mut whole = chain_config.clone();
    whole.posterior.sensor = sensor;
    let mut fresh = Chain::new(last, whole, seed).map_err(OnlineError::Chain)?;
    fresh.step(config.cold_iterations());
    let (warm_log_posterior, fresh_log_posterior) = (chain.best_log_posterior(), fresh.best_log_posterior());
    let ((warm_k, warm_units), (fresh_k, fresh_units)) = (k_and_units(chain), k_and_units(&fresh));
    let renewal = Renewal {
        iterations: config.cold_iterations(),
        range_sensor_log_posterior: range_lp,
        range_sensor_cell_prediction_rate: range_k,
        range_sensor_units: range_units,
        warm_log_posterior,
        fresh_log_posterior,
        warm_units,
        fresh_units,
        warm_cell_prediction_rate: warm_k,
        fresh_cell_prediction_rate: fresh_k,
        adopted: fresh_log_posterior > warm_log_posterior,
    };
    if renewal.adopted {
        *chain = fresh;
    }
    Ok(renewal)
}

/// Drives until the robot has travelled `until_m` metres, has nothing left to explore or
/// has found what `guide` looks for (then returns true).
fn drive(explorer: &mut Explorer, until_m: f64, guide: &mut dyn Guide) -> bool {
    loop {
        if guide.found(explorer) {
            return true;
        }
        if explorer.travelled_m() >= until_m || !explorer.advance(16) {
            return guide.found(explorer);
        }
    }
}

/// One update: the warm chain takes the snapshot, a cold one starts on it, both run.
fn update(
    chain: &mut Chain,
    explorer: &Explorer,
    chain_config: &ChainConfig,
    config: &OnlineConfig,
    seed: u64,
    index: usize,
    scanned: usize,
) -> Result<UpdateRecord, OnlineError> {
    let snapshot = explorer.snapshot();
    let change = chain.update_map(&snapshot).map_err(OnlineError::Chain)?;
    let warm = climb(chain, config.iterations);
    let cold = if config.measure_cold {
        // The same model as the warm chain's: its walls as thick as the warm chain's rings
        // (a cold chain would measure them on this snapshot as seen from one side).
        let ring_m = chain.wall_thickness() as f64 * chain.resolution();
        let same = ChainConfig { wall_thickness_m: Some(ring_m), ..chain_config.clone() };
        let mut c = Chain::new(&snapshot, same, seed).map_err(OnlineError::Chain)?;
        Some(climb(&mut c, config.cold_iterations()))
    } else {
        None
    };
    let last = |curve: &[f64]| *curve.last().expect("a curve has its start");
    let reference = cold.as_deref().map_or(last(&warm), |c| last(c).max(last(&warm)));
    let (warm_iterations, warm_reached) = came_back(&warm, reference, config.iterations);
    let cold_back = cold.as_deref().map(|c| came_back(c, reference, config.cold_iterations()));
    let best = chain.best_world();
    let robot = explorer.robot();
    Ok(UpdateRecord {
        update: index,
        robot: [robot.0, robot.1],
        travelled_m: explorer.travelled_m(),
        seen_free: explorer.seen_count(Cell::Free),
        seen_occupied: explorer.seen_count(Cell::Occupied),
        changed_cells: change.changed_cells,
        candidates_added: change.candidates_added,
        warm_iterations,
        cold_iterations: cold_back.map(|b| b.0),
        warm_reached,
        cold_reached: cold_back.map(|b| b.1),
        reference_log_posterior: reference,
        warm_best_log_posterior: last(&warm),
        cold_best_log_posterior: cold.as_deref().map(last),
        units: best.units.len(),
        cell_prediction_rate: metrics::prediction_rate(snapshot.classified(), &best),
        scans: explorer.scans()[scanned..].iter().map(|&(x, y)| [x, y]).collect(),
    })
}

/// Runs `iterations`, sampling the best log posterior before the first and every [`STRIDE`].
fn climb(chain: &mut Chain, iterations: u64) -> Vec<f64> {
    let mut curve = vec![chain.best_log_posterior()];
    let mut done = 0;
    while done < iterations {
        let k = STRIDE.min(iterations - done);
        chain.step(k);
        done += k;
        curve.push(chain.best_log_posterior());
    }
    curve
}

/// Iterations until `curve` (sampled every [`STRIDE`]) first comes within [`WITHIN`] of
/// `reference`, and whether it did; `budget` if it never did.
fn came_back(curve: &[f64], reference: f64, budget: u64) -> (u64, bool) {
    let threshold = reference - WITHIN * reference.abs();
    match curve.iter().position(|&l| l >= threshold) {
        Some(k) => ((k as u64 * STRIDE).min(budget), true),
        None => (budget, false),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn came_back_counts_strides_until_the_threshold() {
        let curve = [-2000.0, -1500.0, -1001.0, -1000.5, -1000.0];
        // Within 0.1 % of -1000 is -1001 or better: the third sample, 200 iterations in.
        assert_eq!(came_back(&curve, -1000.0, 400), (200, true));
        assert_eq!(came_back(&curve[..2], -1000.0, 100), (100, false));
        assert_eq!(came_back(&curve, -2000.0, 400), (0, true));
    }
}
