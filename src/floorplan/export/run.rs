//! A floor-plan run: a map in, the best world with its rooms, the room labels, the report and
//! the trace out, exactly as `ksmcmc floorplan` makes them.
//!
//! The command line and the Python package both call [`run`], so that the same map, seed and
//! settings give the same `world.json` and `labels.pgm` from either (the files themselves are
//! [`crate::render::Outputs`] of the result). By default a map whose walls follow several
//! directions is explained wing by wing ([`crate::floorplan::wings`]); with edits one chain explains it
//! under them. A caller that stops the chain by its own rule (a time limit, the settle rule)
//! steps the chain itself and hands it to [`Run::of_chain`].
//!
//! Native only: the run is timed with the system clock, which WebAssembly lacks (the browser's
//! plan comes through [`super::plan_input`]).

use super::report::{self, ChainSummary};
use crate::floorplan::chain::{Chain, ChainConfig, ChainError, RunRecord};
use crate::floorplan::edits::Edits;
use crate::floorplan::export::trace_csv;
use crate::floorplan::rooms::RoomConfig;
use crate::floorplan::wings::{WingConfig, Wings};
use crate::floorplan::world::World;
use crate::grid::{Grid, OccupancyMap};
use std::time::Instant;

/// What a run is asked to do.
#[derive(Debug, Clone)]
pub struct RunOptions {
    /// The chain's seed (the same seed, settings and map give the same result).
    pub seed: u64,
    /// Iterations per chain.
    pub iterations: u64,
    /// The chain's settings (detectors, kernels, knowledge supervision).
    pub config: ChainConfig,
    /// A person's corrections; a run with edits is one chain.
    pub edits: Option<Edits>,
    /// Whether a map whose walls follow several directions is explained wing by wing.
    pub wings: bool,
}

impl Default for RunOptions {
    /// Seed 1, 20,000 iterations, the default settings, no edits, wings on: `ksmcmc floorplan
    /// MAP --seed 1`.
    fn default() -> Self {
        RunOptions { seed: 1, iterations: 20_000, config: ChainConfig::default(), edits: None, wings: true }
    }
}

/// What a run found.
#[derive(Debug, Clone)]
pub struct Run {
    /// The best world with its rooms (`world.json`).
    pub world: World,
    /// The room labels (`labels.pgm`): per map cell the id of its room, 0 for none.
    pub labels: Grid<u16>,
    /// The report (`report.json`), without the map's name, which the caller knows.
    pub report: serde_json::Value,
    /// The trace (`trace.csv`) of the first chain.
    pub trace: String,
    /// Iterations run by the first chain.
    pub iterations: u64,
    /// Wall-clock seconds of the whole run.
    pub seconds: f64,
    /// The number of wings when the map was explained wing by wing in several directions.
    pub wings: Option<usize>,
}

/// Explains `map` as `options` say (module docs). Fails where the settings or the edits do not
/// fit the map, or the room layer fails.
pub fn run(map: &OccupancyMap, options: &RunOptions) -> Result<Run, ChainError> {
    let t0 = Instant::now();
    match &options.edits {
        None if options.wings => of_wings(map, options, t0),
        edits => {
            let mut chain = Chain::new(map, options.config.clone(), options.seed)?;
            if let Some(e) = edits {
                chain.set_edits(e.clone())?;
            }
            chain.step(options.iterations);
            Run::of_chain(chain, map, t0.elapsed().as_secs_f64())
        }
    }
}

impl Run {
    /// The result of a chain the caller has stepped, `seconds` after it started: its best
    /// world's rooms under its edits. The chain stops before the rooms are found
    /// ([`Chain::stop`]), to keep the peak memory of a large map down (its tables are tens of
    /// MB), as the wings' chains do.
    pub fn of_chain(chain: Chain, map: &OccupancyMap, seconds: f64) -> Result<Run, ChainError> {
        let mut chain = chain.stop();
        let trace = trace_csv(chain.trace());
        let typed = chain.best_world_typed();
        let mut report = report::summary(&chain, map, &typed, seconds);
        let iterations = chain.iteration();
        let (world, labels) = chain.best_world_with_rooms(&RoomConfig::default())?;
        report::add_rooms(&mut report, &world, &labels);
        Ok(Run { world, labels, report, trace, iterations, seconds, wings: None })
    }
}

/// A chain per wing where the walls follow several directions ([`Wings::run`]).
fn of_wings(map: &OccupancyMap, options: &RunOptions, t0: Instant) -> Result<Run, ChainError> {
    let (wing, rooms) = (WingConfig::default(), RoomConfig::default());
    let wings = Wings::run(map, &options.config, &wing, options.seed, options.iterations, &rooms)?;
    let seconds = t0.elapsed().as_secs_f64();
    let first = &wings.chains[0];
    let trace = trace_csv(first.trace());
    let mut report = report::summary(first, map, &wings.world, seconds);
    report::add_rooms(&mut report, &wings.world, &wings.labels);
    let summaries: Vec<_> = wings.chains[1..].iter().map(|c| ChainSummary::of(c, seconds)).collect();
    report::add_wings(&mut report, &wings.world, &summaries, seconds);
    let iterations = report["iterations"].as_u64().unwrap_or(0);
    let several = (summaries.len() > 1).then_some(summaries.len());
    Ok(Run { world: wings.world, labels: wings.labels, report, trace, iterations, seconds, wings: several })
}
