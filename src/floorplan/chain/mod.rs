//! **The chain folder** owns the Markov chain: its state over an incremental
//! [`Explanation`] (`state`, `explain`), the kernels and their schedule, the posterior and
//! sensor model ([`posterior`]), the trace, the settle rule ([`settled`]) and the chain that
//! follows a growing map ([`online`]). It may import the world, knowledge, the room layer (for
//! a chain's rooms), vision and the grid; nothing of the exports or the wings.
//!
//! The data-driven Markov chain (Algorithm 1): propose with a kernel chosen by the schedule
//! (Tab. 3.2), accept by Metropolis-Hastings (eq. 3.9), remember the best world.
//!
//! The chain is built for a browser frame loop: [`Chain::step`] runs a fixed number of
//! iterations, [`Chain::run_for`] runs until a time budget is spent (the caller supplies the
//! clock, so the same code runs natively and in WebAssembly), and the current world, the best
//! (MAP) world, the trace and the last accepted worlds can be read at any time.
//!
//! ```
//! use ksmcmc::floorplan::{Chain, ChainConfig};
//! use ksmcmc::grid::{Cell, Grid, OccupancyMap};
//!
//! // A 30 x 20 room: walls around free space.
//! let mut g = Grid::new(30, 20, Cell::Free);
//! for x in 0..30 { *g.at_mut(x, 0) = Cell::Occupied; *g.at_mut(x, 19) = Cell::Occupied; }
//! for y in 0..20 { *g.at_mut(0, y) = Cell::Occupied; *g.at_mut(29, y) = Cell::Occupied; }
//! let map = OccupancyMap::from_classified(g);
//! let mut chain = Chain::new(&map, ChainConfig::default(), 1).unwrap();
//! chain.step(300);
//! let best = chain.best_world();
//! assert_eq!(best.units.len(), 1);
//! assert!(chain.best_prediction_rate() > 0.99);
//! ```

pub(crate) mod explain;
pub(crate) mod kernels;
pub mod online;
pub mod posterior;
pub(crate) mod schedule;
pub mod settled;
pub(crate) mod state;
mod stopped;
pub(crate) mod trace;

use self::explain::Explanation;
use self::kernels::{Candidates, KernelConfig, Proposer};
use self::posterior::{Posterior, PosteriorConfig};
use self::schedule::{Kernel, Schedule};
use self::state::{DoorLimits, DoorSizes, DoorSpec, Move, State};
use self::trace::Trace;
use super::world::{Door, Frame, Rect, Unit, UnitType, World};
use crate::grid::{Cell, Grid, OccupancyMap};
use crate::mcmc::{accept, Cumulative, Ring, Rng, TracePoint};
use crate::setting::{check, InvalidSetting};
use crate::vision;
use serde::{Deserialize, Serialize};

mod guide;
mod update;
pub use stopped::{RunRecord, Stopped};
pub use update::MapUpdate;

/// Bottom-up detectors feeding the chain.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct DetectorConfig {
    /// The wall-based unit detector, lengths in metres.
    pub walls: vision::walls::WallSizes,
    /// Iteration after which the free-space unit detector runs (4000 in the dissertation).
    pub free_space_start: u64,
    /// How often (iterations) it runs after that.
    pub free_space_every: u64,
    /// Smallest unexplained free component it proposes, m². 0.15 m²: a few cells of a
    /// scan's noise are no space to explain.
    pub free_space_min_m2: f64,
    /// Map rotation in degrees; `None` estimates the dominant wall orientation.
    pub rotation_deg: Option<f64>,
}

impl Default for DetectorConfig {
    fn default() -> Self {
        DetectorConfig {
            walls: Default::default(),
            free_space_start: 4000,
            free_space_every: 500,
            free_space_min_m2: 0.15,
            rotation_deg: None,
        }
    }
}

/// A configuration's lengths in cells of one map, turned once from its resolution: what the
/// chain's state, kernels and detectors read.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct ChainCells {
    /// The door limits ([`ChainConfig::doors`]).
    pub(crate) doors: DoorLimits,
    /// The smallest unit side ([`KernelConfig::min_side_cells`]).
    pub(crate) min_side: i32,
    /// The wall detector ([`DetectorConfig::walls`]).
    pub(crate) walls: vision::walls::WallConfig,
    /// The free-space detector's smallest component ([`DetectorConfig::free_space_min_m2`]).
    pub(crate) free_space_min: usize,
    /// The wall ring's depth, if configured ([`ChainConfig::wall_thickness_m`]).
    pub(crate) wall: Option<i32>,
}

/// The thickest wall ring a configuration may ask for, metres: exterior walls of masonry are
/// up to about half a metre thick, interior ones 0.1 - 0.3 m; a ring of a metre explains no
/// wall a map shows.
pub const MAX_WALL_THICKNESS_M: f64 = 1.0;

/// `m` metres of wall in whole cells of `r` metres ([`crate::grid::whole_cells`]), at least
/// one cell and at most [`vision::walls::MAX_RING_M`].
fn wall_cells(m: f64, r: f64) -> i32 {
    (crate::grid::whole_cells(m, r) as i32).clamp(1, vision::walls::max_ring_cells(r))
}

impl ChainConfig {
    /// This configuration's lengths in cells of a map of `resolution` metres.
    pub(crate) fn cells(&self, resolution: f64) -> ChainCells {
        let r = crate::grid::cell_size_m(resolution);
        ChainCells {
            doors: self.doors.cells(r),
            min_side: self.kernels.min_side_cells(r),
            walls: self.detectors.walls.cells(r),
            free_space_min: libm::round(self.detectors.free_space_min_m2 / (r * r)).min(1e12) as usize,
            wall: self.wall_thickness_m.map(|m| wall_cells(m, r)),
        }
    }
}

/// Everything that configures a chain. Every field has a documented default; JSON with any
/// subset of fields deserialises onto the defaults.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, Default)]
#[serde(default, deny_unknown_fields)]
pub struct ChainConfig {
    /// The posterior (sensor table, overlap penalty, temperature).
    pub posterior: PosteriorConfig,
    /// Kernel selection probabilities by iteration (Tab. 3.2).
    pub schedule: Schedule,
    /// Proposal distributions.
    pub kernels: KernelConfig,
    /// Door geometry, metres (turned into cells from the map's resolution).
    pub doors: DoorSizes,
    /// Detectors.
    pub detectors: DetectorConfig,
    /// Depth of every unit's wall ring, metres (issue 31: lengths in metres), turned into the
    /// nearest whole number of cells from the map's resolution (one cell to
    /// [`vision::walls::MAX_RING_M`]); `None`, the
    /// default, estimates it from the map's walls ([`vision::walls::ring_depth`]). The
    /// dissertation's model is one cell; thicker rings let units predict thick walls. At most
    /// [`MAX_WALL_THICKNESS_M`].
    pub wall_thickness_m: Option<f64>,
    /// Output bookkeeping.
    pub output: OutputConfig,
    /// Knowledge supervision (section 3.8).
    pub knowledge: super::knowledge::KnowledgeConfig,
}

/// What the chain records for display.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct OutputConfig {
    /// How many recent accepted worlds to keep (the posterior cloud).
    pub samples: usize,
    /// Record a trace point every this many iterations.
    pub trace_every: u64,
    /// Window (proposals) of the acceptance rate.
    pub acceptance_window: usize,
}

impl Default for OutputConfig {
    fn default() -> Self {
        OutputConfig { samples: 1000, trace_every: 100, acceptance_window: 500 }
    }
}

/// Longest chain or synth configuration text read, bytes (1 MiB).
pub const MAX_CONFIG_JSON_BYTES: usize = 1 << 20;

impl ChainConfig {
    /// Checks every number, naming the field at fault.
    pub fn validate(&self) -> Result<(), ChainError> {
        self.check_settings().map_err(ChainError::Config)
    }

    fn check_settings(&self) -> Result<(), InvalidSetting> {
        self.posterior.validate().map_err(|e| e.within("posterior"))?;
        self.schedule.validate().map_err(|e| e.within("schedule"))?;
        self.kernels.validate().map_err(|e| e.within("kernels"))?;
        self.doors.validate().map_err(|e| e.within("doors"))?;
        self.detectors.walls.validate().map_err(|e| e.within("detectors.walls"))?;
        let (d, o) = (&self.detectors, &self.output);
        let a = d.free_space_min_m2;
        check(a.is_finite() && (0.0..=1e6).contains(&a), "detectors.free_space_min_m2", a, "an area from 0 to 1e6 m²")?;
        check(d.free_space_every > 0, "detectors.free_space_every", d.free_space_every as f64, "at least 1")?;
        if let Some(r) = d.rotation_deg {
            check(r.is_finite(), "detectors.rotation_deg", r, "a number of degrees")?;
        }
        if let Some(t) = self.wall_thickness_m {
            // Walls are 0.1 - 0.5 m thick; leaving it out measures the map's.
            let ok = t.is_finite() && t > 0.0 && t <= MAX_WALL_THICKNESS_M;
            check(ok, "wall_thickness_m", t, "metres above 0, at most 1")?;
        }
        self.knowledge.validate()?;
        check(o.samples <= 100_000, "output.samples", o.samples as f64, "at most 100000")?;
        check(o.trace_every > 0, "output.trace_every", o.trace_every as f64, "at least 1")?;
        check(o.acceptance_window > 0, "output.acceptance_window", o.acceptance_window as f64, "at least 1")
    }

    /// Parses a configuration from JSON text: an object whose fields override the defaults
    /// (blank text is the defaults). Unknown fields are refused, naming their path and the
    /// fields known there, for a typo would otherwise be silently ignored; then every value is
    /// checked ([`ChainConfig::validate`]).
    ///
    /// ```
    /// use ksmcmc::floorplan::ChainConfig;
    ///
    /// let c = ChainConfig::from_json(r#"{"posterior": {"temperature": 2}}"#).unwrap();
    /// assert_eq!(c.posterior.temperature, 2.0);
    /// let e = ChainConfig::from_json(r#"{"posterior": {"temprature": 2}}"#).unwrap_err();
    /// assert!(e.to_string().contains("unknown field `posterior.temprature`; the fields here are"));
    /// ```
    pub fn from_json(text: &str) -> Result<ChainConfig, ChainError> {
        ChainConfig::from_json_over(&ChainConfig::default(), text)
    }

    /// The defaults for a chain that follows a robot's growing map (`ksmcmc explore`, the
    /// Exploration page): [`ChainConfig::default`] with the range-sensor table
    /// ([`self::posterior::SensorModel::range_sensor`]), under which a wall's ring lies in the wall
    /// behind the face the robot saw, not in the floor before it.
    ///
    /// ```
    /// use ksmcmc::floorplan::{posterior::SensorModel, ChainConfig};
    ///
    /// let online = ChainConfig::online();
    /// assert_eq!(online.posterior.sensor, SensorModel::range_sensor());
    /// // Fields a configuration does not give keep these defaults.
    /// let c = ChainConfig::from_json_over(&online, r#"{"posterior": {"temperature": 2}}"#).unwrap();
    /// assert_eq!((c.posterior.temperature, c.posterior.sensor), (2.0, SensorModel::range_sensor()));
    /// ```
    pub fn online() -> ChainConfig {
        let mut c = ChainConfig::default();
        c.posterior.sensor = self::posterior::SensorModel::range_sensor();
        c
    }

    /// [`ChainConfig::from_json`] with the fields the text does not give taken from `base`
    /// instead of the defaults.
    pub fn from_json_over(base: &ChainConfig, text: &str) -> Result<ChainConfig, ChainError> {
        if text.len() > MAX_CONFIG_JSON_BYTES {
            return Err(ChainError::Json(format!(
                "the configuration is {} bytes, over the limit of {MAX_CONFIG_JSON_BYTES} bytes \
                 (MAX_CONFIG_JSON_BYTES); a chain configuration is a few dozen fields",
                text.len()
            )));
        }
        if text.trim().is_empty() {
            return Ok(base.clone());
        }
        let given: serde_json::Value = serde_json::from_str(text).map_err(|e| {
            let hint = if text.contains("NaN") || text.contains("Infinity") {
                " (NaN and Infinity are not numbers in JSON, nor allowed values: give finite numbers)"
            } else {
                ""
            };
            ChainError::Json(format!("{e}{hint}"))
        })?;
        if !given.is_object() {
            return Err(ChainError::Json(
                "expected a JSON object such as {\"posterior\": {\"temperature\": 2}}".into(),
            ));
        }
        let mut merged = serde_json::to_value(base).expect("a configuration serialises");
        unknown_fields(&given, &merged, "")?;
        overlay(&mut merged, given);
        let config: ChainConfig = serde_json::from_value(merged).map_err(|e| ChainError::Json(e.to_string()))?;
        config.validate()?;
        Ok(config)
    }
}

/// The wall detector's unit candidates on a world-frame map, those that fit a unit with rings
/// `wall` deep ([`self::state::fits_unit`]).
fn wall_candidates(world_map: &Grid<Cell>, faces: &(Vec<i32>, Vec<i32>), cells: &ChainCells, wall: i32) -> Candidates {
    let min_side = cells.min_side;
    let found = vision::walls::candidates_where(world_map, faces, min_side, &cells.walls, &|_| true);
    Candidates::new(found.into_iter().filter(|&(r, _)| self::state::fits_unit(r, min_side, wall)))
}

/// Writes `given`'s fields over `base`'s, object by object (other values replace).
fn overlay(base: &mut serde_json::Value, given: serde_json::Value) {
    match (base, given) {
        (serde_json::Value::Object(b), serde_json::Value::Object(g)) => {
            for (key, value) in g {
                match b.get_mut(&key) {
                    Some(slot) => overlay(slot, value),
                    None => {
                        b.insert(key, value);
                    }
                }
            }
        }
        (slot, value) => *slot = value,
    }
}

/// Refuses object keys that the defaults do not have, naming the path and the known keys.
fn unknown_fields(given: &serde_json::Value, known: &serde_json::Value, path: &str) -> Result<(), ChainError> {
    let (serde_json::Value::Object(g), serde_json::Value::Object(k)) = (given, known) else {
        return Ok(());
    };
    for (key, value) in g {
        let here = if path.is_empty() { key.clone() } else { format!("{path}.{key}") };
        match k.get(key) {
            Some(default) => unknown_fields(value, default, &here)?,
            None => {
                let names: Vec<&str> = k.keys().map(String::as_str).collect();
                return Err(ChainError::Json(format!(
                    "unknown field `{here}`; the fields here are {}",
                    names.join(", ")
                )));
            }
        }
    }
    Ok(())
}

/// Why a chain could not start.
#[derive(Debug, Clone, PartialEq)]
pub enum ChainError {
    /// A configuration value is unusable: which, and what it must be.
    Config(crate::setting::InvalidSetting),
    /// A configuration's JSON text does not parse, is no object, or has an unknown field.
    Json(String),
    /// The knowledge base does not parse or ground.
    Knowledge(crate::mln::MlnError),
    /// The map cannot be explained (too small, no free space).
    Map(String),
    /// A person's edits do not fit the map ([`Chain::set_edits`]).
    Edits(String),
    /// The room layer could not find the rooms of the chain's world.
    Rooms(super::rooms::RoomError),
}

impl std::fmt::Display for ChainError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            ChainError::Config(m) => write!(f, "invalid chain configuration: {m}"),
            ChainError::Json(m) => write!(f, "chain config: {m}"),
            ChainError::Knowledge(m) => write!(f, "knowledge base: {m}"),
            ChainError::Map(m) => write!(f, "cannot explain this map: {m}"),
            ChainError::Edits(m) => write!(f, "{m}"),
            ChainError::Rooms(e) => write!(f, "{e}"),
        }
    }
}

impl std::error::Error for ChainError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            ChainError::Rooms(e) => Some(e),
            ChainError::Config(e) => Some(e),
            ChainError::Knowledge(e) => Some(e),
            _ => None,
        }
    }
}

impl From<super::rooms::RoomError> for ChainError {
    fn from(e: super::rooms::RoomError) -> ChainError {
        ChainError::Rooms(e)
    }
}

/// A snapshot of units and doors.
#[derive(Debug, Clone, Default)]
struct Snapshot {
    units: Vec<Unit>,
    doors: Vec<DoorSpec>,
}

/// `world` typed by `typer` under `edits` (their types and names are evidence), and the
/// inference that typed it; `None` (the units keep the chain's types) if there is no typer
/// or it failed on this world.
fn typed(
    typer: Option<&mut super::knowledge::Knowledge>,
    edits: &super::edits::Edits,
    resolution: f64,
    mut world: World,
) -> (World, Option<super::knowledge::Inferred>) {
    let given = super::knowledge::edit_facts(edits, &world);
    let inferred = typer.and_then(|k| k.infer_given(&world, resolution, &given).ok());
    if let Some(inferred) = &inferred {
        for u in &mut world.units {
            u.kind = inferred.types.get(&u.id).map_or(u.kind, |t| t.0);
        }
    }
    (world, inferred)
}

/// The typed `best` world with its room layer filled in by `layer`, and the room labels,
/// grouped by units under `edits` ([`Chain::best_world_with_rooms`], [`Stopped`]).
fn world_with_rooms(
    layer: &super::rooms::RoomLayer,
    best: World,
    typer: Option<&mut super::knowledge::Knowledge>,
    edits: &super::edits::Edits,
    maps: super::rooms::RoomMaps<'_>,
) -> Result<(World, Grid<u16>), super::rooms::RoomError> {
    let grouping = super::rooms::Grouping::Units(edits);
    let (walls, (mut world, _)) = crate::threads::join(
        || layer.read_walls(&best, maps, grouping),
        || typed(typer, edits, maps.resolution, best.clone()),
    );
    let labels = layer.explain_read(&mut world, maps, grouping, &walls)?;
    Ok((world, labels))
}

/// What a chain is made of besides its settings ([`Chain::with_parts`]): the frame, the
/// world-frame map, the map, the unit candidates and the object cells.
type Parts = (Frame, Grid<Cell>, Grid<Cell>, Candidates, Option<vision::objects::ObjectCells>);

/// How much the semantic sensor model gains for an unknown and an occupied object cell in a
/// unit that may hold objects, per cell, so weighted as the likelihood's cells are
/// ([`self::posterior::cell_weight`]).
fn object_gain(config: &ChainConfig, resolution: f64) -> [f64; 2] {
    let (sensor, k) = (config.posterior.sensor.table, &config.knowledge);
    let w = self::posterior::cell_weight(resolution);
    [
        (libm::log(k.object[1]) - libm::log(sensor[0][1])).max(0.0) * w,
        (libm::log(k.object[2]) - libm::log(sensor[0][2])).max(0.0) * w,
    ]
}

/// The object cells the knowledge terms count, when knowledge is on.
fn objects_for(world_map: &Grid<Cell>, resolution: f64, config: &ChainConfig) -> Option<vision::objects::ObjectCells> {
    config.knowledge.enabled.then(|| object_cells(world_map, resolution, config, object_gain(config, resolution)))
}

/// The map cells that may be objects, counted for the knowledge terms. Unknown object cells
/// use up the share of a unit's interior that may be objects even when they earn nothing, so
/// both classes are counted if either is forgiven (`object_gain` above zero).
fn object_cells(
    world_map: &Grid<Cell>,
    resolution: f64,
    config: &ChainConfig,
    object_gain: [f64; 2],
) -> vision::objects::ObjectCells {
    let any = object_gain.iter().any(|&g| g > 0.0);
    vision::objects::ObjectCells::counting(world_map, resolution, config.knowledge.max_object_m, [any, any])
}

/// A running data-driven MCMC chain over semantic worlds of one map.
#[derive(Debug, Clone)]
pub struct Chain {
    config: ChainConfig,
    frame: Frame,
    world_map: Grid<Cell>,
    map: Grid<Cell>,
    state: State,
    proposer: Proposer,
    posterior: Posterior,
    rng: Rng,
    seed: u64,
    iteration: u64,
    log_target: f64,
    best: Snapshot,
    best_log_posterior: f64,
    best_iteration: u64,
    trace: Trace,
    samples: Ring<Vec<Rect>>,
    phase_tables: Vec<Cumulative>,
    phase_index: usize,
    /// The iteration the kernel schedule counts from: 0, or the last map update's
    /// ([`Chain::update_map`]), after which the schedule's phases run again.
    schedule_origin: u64,
    knowledge: Option<super::knowledge::Knowledge>,
    inferred: super::knowledge::Inferred,
    resolution: f64,
    /// The configuration's lengths in cells of this map ([`ChainConfig::cells`]).
    cells: ChainCells,
    /// `log p(C_M | object) - log p(C_M | free)` for unknown and occupied map cells, floored at
    /// zero: a cell is an object only where that explains it better.
    object_gain: [f64; 2],
    /// The map cells that may be objects (knowledge mode only).
    objects: Option<crate::vision::objects::ObjectCells>,
    knowledge_error: Option<String>,
    /// The first iteration at which knowledge may be inferred again (see
    /// [`KnowledgeConfig::time_share`](super::knowledge::KnowledgeConfig::time_share)).
    next_inference: u64,
    /// The free-space detector's working memory, kept between refreshes.
    free_space_scratch: vision::freespace::Scratch,
    /// Types final worlds in the weak-prior mode (built-in rules), created on first use.
    typer: Option<super::knowledge::Knowledge>,
    /// A person's edits, hard evidence ([`Chain::set_edits`]).
    edits: super::edits::Edits,
    /// The wall faces (columns, rows) the wall detector last built candidates on; `None` for
    /// a chain given its candidates ([`Chain::with_candidates`]), whose pool the chain keeps.
    faces: Option<(Vec<i32>, Vec<i32>)>,
    /// The Hough profile of the walls of `map` when the chain estimated its angle from it
    /// ([`Chain::wall_profile`]); `None` otherwise, and once the map has changed.
    walls: Option<vision::orientation::WallProfile>,
}

impl Chain {
    /// A chain for `map`: estimates the map's orientation (unless configured), runs the
    /// wall-based detector, and starts from the empty world.
    pub fn new(map: &OccupancyMap, config: ChainConfig, seed: u64) -> Result<Chain, ChainError> {
        config.validate()?;
        let classified = map.classified();
        let resolution = map.yaml().resolution;
        let cells = config.cells(resolution);
        let min = cells.min_side as usize;
        if classified.width() < min || classified.height() < min {
            return Err(ChainError::Map(format!(
                "the map is {}x{} cells, smaller than the smallest unit ({min}x{min}); \
                 units need two walls and free space between them",
                classified.width(),
                classified.height()
            )));
        }
        if map.count(Cell::Free) == 0 {
            return Err(ChainError::Map(
                "the map has no free cells, so there is no space to explain; check the \
                 classification thresholds (is the image inverted? try negate)"
                    .into(),
            ));
        }
        // The walls' Hough profile, kept for the wings and the report (the same map's).
        let walls = config.detectors.rotation_deg.is_none().then(|| vision::orientation::WallProfile::of(classified));
        let angle = match config.detectors.rotation_deg {
            Some(deg) => deg.to_radians(),
            None => {
                let a = walls.as_ref().map_or(0.0, vision::orientation::WallProfile::dominant_angle);
                // Below half a degree the resampling would only blur the map.
                if a.abs() < 0.5f64.to_radians() {
                    0.0
                } else {
                    a
                }
            }
        };
        let (world_map, frame) = vision::orientation::to_world_frame(classified, angle);
        let wall = cells.wall.unwrap_or_else(|| vision::walls::ring_depth(classified, angle, resolution));
        let faces = vision::walls::faces_of(&world_map, &cells.walls);
        // One after the other: counted beside the candidates, the object cells saved Cartesium
        // 10 - 20 ms but held their tables beside the candidates' (peak 63.6 -> 67 - 69 MB).
        let candidates = wall_candidates(&world_map, &faces, &cells, wall);
        let objects = objects_for(&world_map, resolution, &config);
        let parts = (frame, world_map, classified.clone(), candidates, objects);
        let mut chain = Self::with_parts(config, parts, wall, resolution, seed)?;
        chain.faces = Some(faces);
        chain.walls = walls;
        Ok(chain)
    }

    /// The Hough profile of the walls of the map the chain was made for
    /// ([`vision::orientation::WallProfile`]), when the chain estimated the map's angle from
    /// it; `None` when the angle was given, and once [`Chain::update_map`] changed the map.
    /// The wings and the report read the wall directions off it instead of transforming the
    /// same map again.
    pub fn wall_profile(&self) -> Option<&vision::orientation::WallProfile> {
        self.walls.as_ref()
    }

    /// A chain on an upright world-frame map with an explicit ADD candidate pool (no detectors,
    /// no rotation): for tests, teaching pages and callers with their own detectors. A bare
    /// grid says nothing of its cells: they are taken as the benchmark maps' 5 cm.
    pub fn with_candidates(
        map: &Grid<Cell>,
        config: ChainConfig,
        candidates: Vec<(Rect, f64)>,
        seed: u64,
    ) -> Result<Chain, ChainError> {
        config.validate()?;
        let frame = Frame::identity(map.width() as u32, map.height() as u32);
        let resolution = crate::grid::BENCHMARK_CELL_M;
        let wall = config.cells(resolution).wall.unwrap_or(1);
        let objects = objects_for(map, resolution, &config);
        let parts = (frame, map.clone(), map.clone(), Candidates::new(candidates), objects);
        Self::with_parts(config, parts, wall, resolution, seed)
    }

    /// A chain on `parts`: the frame, the world-frame map, the map, the unit candidates and the
    /// object cells ([`objects_for`]).
    fn with_parts(
        config: ChainConfig,
        parts: Parts,
        wall: i32,
        resolution: f64,
        seed: u64,
    ) -> Result<Chain, ChainError> {
        let (frame, world_map, map, candidates, objects) = parts;
        let knowledge = if config.knowledge.enabled {
            Some(super::knowledge::Knowledge::new(&config.knowledge).map_err(ChainError::Knowledge)?)
        } else {
            None
        };
        let object_gain = object_gain(&config, resolution);
        let cells = config.cells(resolution);
        let state = State::new(&world_map, cells.doors, wall);
        let proposer = Proposer::new(config.kernels, resolution, candidates, state.width(), state.height(), wall);
        let posterior = Posterior::at_resolution(&config.posterior, resolution);
        let log_target = posterior.log_target(&state.explanation, 0);
        let phase_tables = config.schedule.phases.iter().map(|p| Cumulative::new(p.weights.0)).collect();
        let best_log_posterior = posterior.log_posterior(&state.explanation, 0);
        Ok(Chain {
            trace: Trace::new(config.output.acceptance_window, config.output.trace_every),
            samples: Ring::new(config.output.samples),
            config,
            frame,
            world_map,
            map,
            state,
            proposer,
            posterior,
            rng: Rng::seed(seed),
            seed,
            iteration: 0,
            log_target,
            best: Snapshot::default(),
            best_log_posterior,
            best_iteration: 0,
            phase_tables,
            phase_index: 0,
            schedule_origin: 0,
            knowledge,
            inferred: Default::default(),
            resolution,
            cells,
            object_gain,
            objects,
            knowledge_error: None,
            next_inference: 0,
            free_space_scratch: Default::default(),
            typer: None,
            edits: Default::default(),
            faces: None,
            walls: None,
        })
    }

    /// The knowledge terms of the log posterior (untempered): the semantic sensor model's
    /// object cells in rooms, halls and other units, and the same-length factors of eq. 3.34.
    fn knowledge_term(&self) -> f64 {
        self.knowledge_term_for(&self.state.units)
    }

    fn knowledge_term_for(&self, units: &[Unit]) -> f64 {
        if self.inferred.types.is_empty() {
            return 0.0;
        }
        let t = self.state.wall;
        let mut s = 0.0;
        for u in units {
            // Only corridors hold no objects. A unit born since the last inference has no type
            // yet and is scored as the non-corridor most units are: scoring it as a corridor
            // would make every SPLIT or MERGE forfeit the objects of the units it replaces, and
            // freeze whatever world the first inference saw.
            let tolerant = !matches!(self.inferred.types.get(&u.id), Some((UnitType::Corridor, _)));
            if let (true, Some(objects)) = (tolerant && u.w > 2 * t && u.h > 2 * t, &self.objects) {
                let inside = Rect::new(u.x + t, u.y + t, u.w - 2 * t, u.h - 2 * t);
                // Object cells, up to the allowed share of the interior, unknown ones first.
                let cap = (self.config.knowledge.object_share * inside.area() as f64) as u32;
                let unknown = objects.unknown_in(inside).min(cap);
                let occupied = objects.occupied_in(inside).min(cap - unknown);
                s += unknown as f64 * self.object_gain[0] + occupied as f64 * self.object_gain[1];
            }
        }
        let sigma = self.config.knowledge.same_length_sigma;
        for &(p, q, prob) in &self.inferred.same_length {
            let (Some(a), Some(b)) = (units.iter().find(|u| u.id == p), units.iter().find(|u| u.id == q)) else {
                continue;
            };
            if let Some((la, lb)) = super::knowledge::connecting_walls(a, b, t) {
                let d = (la - lb) as f64;
                s += super::knowledge::same_length_log_factor(d, sigma, prob);
            }
        }
        s
    }

    /// Makes the current world the best one, with log posterior `lp`.
    #[inline]
    fn keep_as_best(&mut self, lp: f64) {
        self.best_log_posterior = lp;
        self.best_iteration = self.iteration;
        self.best.units.clone_from(&self.state.units);
        self.best.doors.clone_from(&self.state.doors);
    }

    /// Removes the unit in slot `i` of the current world, with its doors.
    fn remove_unit_with_doors(&mut self, i: usize) {
        let id = self.state.units[i].id;
        while let Some(k) = self.state.doors.iter().position(|d| d.lo == id || d.hi == id) {
            self.state.apply(&Move::Delete(k));
        }
        self.state.apply(&Move::Remove(i));
    }

    /// The full log posterior of the current world: likelihood, prior and knowledge terms.
    fn full_log_posterior(&self) -> f64 {
        self.posterior.log_posterior(&self.state.explanation, self.state.units.len()) + self.knowledge_term()
    }

    /// Share of the map's free cells covered by units (knowledge switches on above a threshold).
    pub fn coverage(&self) -> f64 {
        let n = self.state.explanation.confusion()[0];
        let free: i64 = n.iter().sum();
        if free == 0 {
            0.0
        } else {
            1.0 - n[1] as f64 / free as f64
        }
    }

    /// The current world with the chain's own unit ids (exports renumber them).
    fn internal_world(&self) -> World {
        self.outline(&self.state.units, &self.state.doors)
    }

    /// The best world with the chain's own unit ids, for inference on it.
    fn internal_best_world(&self) -> World {
        self.outline(&self.best.units, &self.best.doors)
    }

    /// The units and doors of a world of this chain as a [`World`], with the chain's own ids;
    /// a door whose units are missing or no longer face each other is left out.
    fn outline(&self, units: &[Unit], doors: &[DoorSpec]) -> World {
        let mut w = World::empty(self.frame.map_size[0], self.frame.map_size[1]);
        w.frame = self.frame;
        w.wall_thickness = self.state.wall;
        w.units = units.to_vec();
        let rect_of = |id: u32| units.iter().find(|u| u.id == id).map(|u| u.rect());
        for (k, d) in doors.iter().enumerate() {
            let (Some(lo), Some(hi)) = (rect_of(d.lo), rect_of(d.hi)) else { continue };
            if let Some(r) = self::state::door_rect(lo, hi, d, &self.cells.doors, self.state.wall) {
                w.doors.push(Door {
                    id: k as u32 + 1,
                    units: [d.lo, d.hi],
                    x0: r.x,
                    y0: r.y,
                    x1: r.right() - 1,
                    y1: r.bottom() - 1,
                    opening: false,
                });
            }
        }
        w
    }

    /// Runs knowledge inference on the current world now, if knowledge is enabled; the types
    /// and same-length pairs then shape the posterior until the next inference. Returns the
    /// inference work done ([`crate::mln::Marginals::work`], 0 for cached results).
    pub fn infer_knowledge(&mut self) -> Result<u64, ChainError> {
        let world = self.internal_world();
        let resolution = self.resolution;
        let given = super::knowledge::edit_facts(&self.edits, &world);
        let Some(k) = self.knowledge.as_mut() else { return Ok(0) };
        let inferred = k.infer_given(&world, resolution, &given).map_err(ChainError::Knowledge)?;
        let mut work = k.last_work;
        for u in &mut self.state.units {
            u.kind = inferred.types.get(&u.id).map_or(UnitType::Unknown, |t| t.0);
        }
        if inferred != self.inferred {
            // The target changed: rescore the current world and the best one under it.
            let best_base = self.best_log_posterior - self.knowledge_term_for(&self.best.units);
            self.inferred = inferred;
            let lp = self.full_log_posterior();
            self.log_target = lp * self.posterior.inv_temperature();
            self.best_log_posterior = best_base + self.knowledge_term_for(&self.best.units);
            if lp > self.best_log_posterior || self.best.units.is_empty() {
                self.keep_as_best(lp);
            }
        }
        // The best world may be an older one the current inference did not see: type it by
        // inference on itself (cached by evidence, so free while it stays the best).
        if !self.best.units.is_empty() {
            let best = self.internal_best_world();
            let given = super::knowledge::edit_facts(&self.edits, &best);
            if let Some(k) = self.knowledge.as_mut() {
                let typed = k.infer_given(&best, resolution, &given).map_err(ChainError::Knowledge)?;
                work += k.last_work;
                for u in &mut self.best.units {
                    u.kind = typed.types.get(&u.id).map_or(UnitType::Unknown, |t| t.0);
                }
            }
        }
        Ok(work)
    }

    /// The best world with unit types inferred now on this final world: with the chain's own
    /// knowledge base when knowledge supervised it (units added since its last inference would
    /// otherwise stay untyped), otherwise with the built-in indoor rules (the weak-prior mode
    /// types its result only at the end). What `ksmcmc floorplan` writes as `world.json`.
    pub fn best_world_typed(&mut self) -> World {
        self.best_world_inferred().0
    }

    /// [`Chain::best_world_typed`] and the inference that typed it: every unit's four type
    /// marginals (`None` if the knowledge base failed on this world; its units then keep the
    /// chain's types). The inference is cached by its evidence, so asking again for the same
    /// best world costs nothing and changes nothing in the chain.
    pub fn best_world_inferred(&mut self) -> (World, Option<super::knowledge::Inferred>) {
        let world = self.best_world();
        self.make_typer();
        let typer = self.knowledge.as_mut().or(self.typer.as_mut());
        typed(typer, &self.edits, self.resolution, world)
    }

    /// Without a knowledge base, the built-in rules type this chain's worlds: made on first
    /// use.
    fn make_typer(&mut self) {
        if self.knowledge.is_none() && self.typer.is_none() {
            self.typer = super::knowledge::Knowledge::new(&Default::default()).ok();
        }
    }

    /// Takes a person's edits as hard evidence ([`super::edits`]) and goes on from the current
    /// world: units whose interior a split wall crosses are removed (with their doors) from the
    /// current world, the best world is the current one if it had such units, and from now on
    /// no move that breaks a split is proposed or accepted. Merges, types and names bind the
    /// room layer ([`Chain::best_world_with_rooms`]) and the Markov logic inference. An empty
    /// list lifts every edit. Refused, with nothing changed, if a point is off the map.
    ///
    /// ```
    /// use ksmcmc::floorplan::{edits::Edits, synth, Chain, ChainConfig};
    /// let s = synth::generate(&synth::SynthConfig { width: 200, height: 150, ..Default::default() }, 3).unwrap();
    /// let mut chain = Chain::new(&s.map, ChainConfig::default(), 1).unwrap();
    /// chain.step(2000);
    /// chain.set_edits(Edits::parse(r#"[{"op": "split", "line": [[100, 0], [100, 149]]}]"#)?)?;
    /// chain.step(2000);
    /// // No unit spans the wall at x = 100 (the map is upright, so world = map cells).
    /// let t = chain.wall_thickness();
    /// assert!(chain.best_world().units.iter().all(|u| u.x + u.w - t <= 100 || u.x + t > 100));
    /// assert!(chain.set_edits(Edits::parse(r#"[{"op": "name", "at": [900, 1], "name": "A"}]"#)?).is_err());
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn set_edits(&mut self, edits: super::edits::Edits) -> Result<(), ChainError> {
        edits.check_map(self.map.width(), self.map.height()).map_err(|e| ChainError::Edits(e.to_string()))?;
        let walls = edits.world_wall_cells(&self.map, &self.frame);
        self.edits = edits;
        self.state.forbid(&walls);
        while let Some(i) = self.state.units.iter().position(|u| self.state.breaks_forbidden(u.rect())) {
            self.remove_unit_with_doors(i);
        }
        let lp = self.full_log_posterior();
        self.log_target = lp * self.posterior.inv_temperature();
        if self.best.units.iter().any(|u| self.state.breaks_forbidden(u.rect())) || self.best.units.is_empty() {
            self.keep_as_best(lp);
        }
        if self.knowledge.is_some() && !self.state.units.is_empty() {
            // New type evidence changes the target at once, not at the next inference.
            if let Err(e) = self.infer_knowledge() {
                self.knowledge_error = Some(e.to_string());
                self.knowledge = None;
            }
        }
        Ok(())
    }

    /// The edits in force ([`Chain::set_edits`]).
    pub fn edits(&self) -> &super::edits::Edits {
        &self.edits
    }

    /// Why knowledge inference stopped, if it failed (the chain goes on without it).
    pub fn knowledge_error(&self) -> Option<&str> {
        self.knowledge_error.as_deref()
    }

    /// Unit types and same-length pairs from the last inference.
    pub fn inferred(&self) -> &super::knowledge::Inferred {
        &self.inferred
    }

    /// How many knowledge inferences ran (cache misses).
    pub fn inferences(&self) -> u64 {
        self.knowledge.as_ref().map_or(0, |k| k.inferences)
    }

    /// Metres per cell of the map.
    pub fn resolution(&self) -> f64 {
        self.resolution
    }

    /// The seed the chain started from.
    pub fn seed(&self) -> u64 {
        self.seed
    }

    /// The configuration.
    pub fn config(&self) -> &ChainConfig {
        &self.config
    }

    /// Iterations run so far.
    pub fn iteration(&self) -> u64 {
        self.iteration
    }

    /// How the world frame sits on the map.
    pub fn frame(&self) -> &Frame {
        &self.frame
    }

    /// The classified map in the world frame.
    pub fn world_map(&self) -> &Grid<Cell> {
        &self.world_map
    }

    /// Depth of the units' wall rings, cells.
    pub fn wall_thickness(&self) -> i32 {
        self.state.wall
    }

    /// The ADD candidates the detectors found.
    pub fn candidates(&self) -> &Candidates {
        &self.proposer.candidates
    }

    /// The chain's bookkeeping of the current world.
    pub fn explanation(&self) -> &Explanation {
        &self.state.explanation
    }

    /// `log p(W|M)` of the current world (untempered, up to a constant), knowledge terms
    /// included once knowledge is active.
    pub fn log_posterior(&self) -> f64 {
        self.full_log_posterior()
    }

    /// The best log posterior seen.
    pub fn best_log_posterior(&self) -> f64 {
        self.best_log_posterior
    }

    /// Iteration at which the best world was found.
    pub fn best_iteration(&self) -> u64 {
        self.best_iteration
    }

    /// `K(W, M)` of the current world in the world frame (eq. 3.39).
    pub fn prediction_rate(&self) -> f64 {
        self.state.explanation.prediction_rate()
    }

    /// `K(W, M)` of the best world on the original map (eq. 3.39).
    pub fn best_prediction_rate(&self) -> f64 {
        super::metrics::prediction_rate(&self.map, &self.best_world())
    }

    /// Statistics of the run.
    pub fn trace(&self) -> &Trace {
        &self.trace
    }

    /// Current units, in slot order.
    pub fn units(&self) -> &[Unit] {
        &self.state.units
    }

    /// The last accepted worlds' unit rectangles (world frame), oldest first.
    pub fn samples(&self) -> impl Iterator<Item = &Vec<Rect>> {
        self.samples.iter()
    }

    /// The current world.
    pub fn world(&self) -> World {
        self.export(&self.state.units, &self.state.doors)
    }

    /// The best (maximum a posteriori) world found so far.
    pub fn best_world(&self) -> World {
        self.export(&self.best.units, &self.best.doors)
    }

    fn export(&self, units: &[Unit], doors: &[DoorSpec]) -> World {
        // Exports number units 1..=n in slot order, and doors name them by those numbers.
        let mut w = self.outline(units, doors);
        let new_id = |id: u32| units.iter().position(|u| u.id == id).map_or(0, |k| k as u32 + 1);
        for u in &mut w.units {
            u.id = new_id(u.id);
        }
        for d in &mut w.doors {
            d.units = d.units.map(new_id);
        }
        // Object cells: unknown map cells inside a unit's free space (furniture, clutter).
        let t = self.state.wall;
        for u in units {
            for y in u.y + t..u.y + u.h - t {
                for x in u.x + t..u.x + u.w - t {
                    if *self.world_map.at(x as usize, y as usize) == Cell::Unknown {
                        w.object_cells.push([x, y]);
                    }
                }
            }
        }
        w.object_cells.sort_unstable();
        w.object_cells.dedup();
        let unit_rects: Vec<Rect> = units.iter().map(|u| u.rect()).collect();
        let door_rects: Vec<Rect> = w.doors.iter().map(|d| d.rect()).collect();
        w.unexplained = super::unexplained::unexplained_areas(
            &self.world_map,
            &unit_rects,
            &door_rects,
            super::unexplained::MIN_UNEXPLAINED_CELLS,
        );
        w
    }

    fn refresh_free_space(&mut self) {
        let rects = vision::freespace::unexplained_with(
            &self.state.explanation,
            self.cells.free_space_min,
            &mut self.free_space_scratch,
        );
        let (min, wall) = (self.cells.min_side, self.state.wall);
        let items: Vec<(Rect, f64)> = rects
            .into_iter()
            .filter(|&r| self::state::fits_unit(r, min, wall))
            .map(|r| (r, self.state.unit_weight(r).max(0.2)))
            .collect();
        self.proposer.candidates.extend(items);
    }

    fn current_weights(&mut self) -> usize {
        let phases = &self.config.schedule.phases;
        let since = self.iteration - self.schedule_origin;
        while self.phase_index + 1 < phases.len() && phases[self.phase_index].until.is_some_and(|u| since > u) {
            self.phase_index += 1;
        }
        self.phase_index
    }

    /// Runs `n` iterations.
    pub fn step(&mut self, n: u64) {
        for _ in 0..n {
            self.iterate();
        }
    }

    /// Runs iterations until `budget_ms` milliseconds have passed by `now` (a clock in
    /// milliseconds, e.g. `performance.now()` in a browser), checking the clock every 16
    /// iterations, so a frame's budget is overrun by at most a few milliseconds even on large
    /// maps. Returns the number of iterations run.
    pub fn run_for(&mut self, budget_ms: f64, now: &mut dyn FnMut() -> f64) -> u64 {
        let start = now();
        let mut done = 0;
        loop {
            self.step(16);
            done += 16;
            // A clock that returns NaN stops the loop rather than spinning forever.
            let elapsed = now() - start;
            if elapsed >= budget_ms || elapsed.is_nan() {
                return done;
            }
        }
    }

    /// Runs iterations for a wall-clock duration (native only).
    #[cfg(not(target_arch = "wasm32"))]
    pub fn run_for_duration(&mut self, budget: std::time::Duration) -> u64 {
        let t0 = std::time::Instant::now();
        self.run_for(budget.as_secs_f64() * 1000.0, &mut || t0.elapsed().as_secs_f64() * 1000.0)
    }

    fn iterate(&mut self) {
        self.iteration += 1;
        let d = &self.config.detectors;
        if self.iteration >= d.free_space_start && (self.iteration - d.free_space_start) % d.free_space_every == 0 {
            self.refresh_free_space();
        }
        if self.knowledge.is_some()
            && self.iteration >= self.next_inference
            && self.iteration % self.config.knowledge.every == 0
            && self.coverage() >= self.config.knowledge.coverage
        {
            match self.infer_knowledge() {
                Ok(work) => {
                    // Space inferences out by their cost, deterministically (work, not time).
                    let k = &self.config.knowledge;
                    let gap = work as f64 / (super::knowledge::WORK_PER_ITERATION * k.time_share);
                    self.next_inference = self.iteration + (gap.min(1e12) as u64).max(k.every);
                }
                Err(e) => {
                    self.knowledge_error = Some(e.to_string());
                    self.knowledge = None;
                }
            }
        }
        let phase = self.current_weights();
        let table = &self.phase_tables[phase];
        let Some(k) = table.draw(&mut self.rng) else { return };
        let kernel = Kernel::ALL[k];
        let phi_fwd = table.probability(kernel.index());
        let phi_rev = table.probability(kernel.reverse().index());
        let accepted = self.try_kernel(kernel, phi_fwd, phi_rev);
        self.trace.record(kernel, accepted);
        if self.iteration % self.trace.every == 0 {
            let point = TracePoint {
                iteration: self.iteration,
                log_posterior: self.log_posterior(),
                acceptance: self.trace.acceptance(),
                size: self.state.units.len() as u32,
            };
            self.trace.points.push(point);
        }
    }

    fn try_kernel(&mut self, kernel: Kernel, phi_fwd: f64, phi_rev: f64) -> bool {
        let Some((mv, q_fwd)) = self.proposer.propose(kernel, &self.state, &mut self.rng) else { return false };
        let k = &self.config.kernels;
        if q_fwd <= 0.0 || phi_rev <= 0.0 || !self.state.is_valid(&mv, self.cells.min_side, k.max_units) {
            return false;
        }
        // The counts decide; a birth's or death's cells are written only if it is taken.
        let (undo, generation, next_id) = self.state.apply_pending(&mv);
        let q_rev = self.proposer.reverse_q(&mv, &undo, &self.state);
        let new_target = self.full_log_posterior() * self.posterior.inv_temperature();
        let log_ratio = new_target - self.log_target + libm::log(phi_rev * q_rev) - libm::log(phi_fwd * q_fwd);
        if q_rev > 0.0 && accept(log_ratio, &mut self.rng) {
            self.state.explanation.write_pending();
            self.log_target = new_target;
            let lp = new_target / self.posterior.inv_temperature();
            if lp > self.best_log_posterior {
                self.keep_as_best(lp);
            }
            if self.config.output.samples > 0 {
                let mut rects = Vec::with_capacity(self.state.units.len());
                rects.extend(self.state.units.iter().map(|u| u.rect()));
                self.samples.push(rects);
            }
            true
        } else {
            self.state.undo(undo, generation, next_id);
            false
        }
    }

    /// The room segmentation of the best world on the original map (every open pair of units joined, [`super::rooms`]).
    pub fn best_labels(&self, rooms: &super::rooms::RoomConfig) -> Grid<u16> {
        self.labels(&self.best_world(), rooms)
    }

    /// The room segmentation of `world`, a world of this chain such as [`Chain::best_world`]
    /// or [`Chain::best_world_typed`] (unit types do not change it), on the original map.
    pub fn labels(&self, world: &World, rooms: &super::rooms::RoomConfig) -> Grid<u16> {
        super::rooms::room_labels(world, &self.map, &self.world_map, &rooms.cells(self.resolution))
    }

    /// The room layer of this chain's settings: `rooms`' lengths, and with knowledge
    /// supervision the room rules (the configuration's `knowledge.room_kb`, by default the
    /// built-in ones) and its indoor rules ([`super::rooms::RoomLayer::new`]).
    pub fn room_layer(
        &self,
        rooms: &super::rooms::RoomConfig,
    ) -> Result<super::rooms::RoomLayer, super::rooms::RoomError> {
        super::rooms::RoomLayer::new(*rooms, &self.config.knowledge)
    }

    /// The maps the room layer reads for this chain's worlds.
    fn room_maps(&self) -> super::rooms::RoomMaps<'_> {
        super::rooms::RoomMaps { map: &self.map, world_map: &self.world_map, resolution: self.resolution }
    }

    /// The typed best world ([`Chain::best_world_typed`]) with its room layer filled in, and
    /// the room labels (one id per room, `labels.pgm`), grouped by units under the chain's
    /// edits ([`super::rooms::RoomLayer::explain`], [`Chain::room_layer`]).
    pub fn best_world_with_rooms(
        &mut self,
        rooms: &super::rooms::RoomConfig,
    ) -> Result<(World, Grid<u16>), super::rooms::RoomError> {
        let layer = self.room_layer(rooms)?;
        let best = self.best_world();
        self.make_typer();
        // The walls are read while the world is typed: the room layer's first stage asks only
        // where the units lie, and typing a large world (MC-SAT over a network the junction
        // tree cannot take) costs about as much.
        let typer = self.knowledge.as_mut().or(self.typer.as_mut());
        let maps = super::rooms::RoomMaps { map: &self.map, world_map: &self.world_map, resolution: self.resolution };
        world_with_rooms(&layer, best, typer, &self.edits, maps)
    }

    /// Finds the rooms of `world` again (a typed world of this chain, such as the one
    /// [`Chain::best_world_with_rooms`] gave) for a building that none of its wall directions
    /// holds most of: the rooms are where the walls, their gaps along the directions `angles`
    /// too and the doorways part the floor ([`super::rooms::Grouping::Walls`];
    /// [`super::wings`] decides when). Returns the room labels.
    pub fn rooms_by_walls(
        &self,
        world: &mut World,
        rooms: &super::rooms::RoomConfig,
        angles: &[f64],
    ) -> Result<Grid<u16>, super::rooms::RoomError> {
        self.room_layer(rooms)?.explain(world, self.room_maps(), super::rooms::Grouping::Walls(angles))
    }

    /// The classified map the chain explains, in the map's own frame.
    pub fn map(&self) -> &Grid<Cell> {
        &self.map
    }

    /// Checks the incremental bookkeeping against a full recomputation (for tests).
    pub fn check_consistency(&self) -> bool {
        let (units, doors) = self.state.rects();
        self.state.explanation.same_as(&Explanation::recompute(&self.world_map, &units, self.state.wall, &doors))
    }

    /// The current world's units and doors as internal records (for tests and the wasm layer).
    pub fn current_rects(&self) -> (Vec<Rect>, Vec<Rect>) {
        self.state.rects()
    }
}
