//! **A chain that has stopped** ([`Stopped`]): what is left of a [`Chain`] for its rooms and
//! its report once it will run no more ([`Chain::stop`]), and what a report reads of either
//! ([`RunRecord`]).
//!
//! Why: a chain's sampling tables (the explanation of every cell, the summed-area tables of the
//! map's classes and of the cells that may be objects, the detectors' working memory) take
//! 4 bytes a cell of the world frame each, about 31 MB on Cartesium's 1.57 million cells, and
//! the room layer's tables of the walls take as much again while it reads them. A run that
//! finds its rooms after its chains have stopped (the CLI's, wing by wing: [`super::super::wings`])
//! need not hold both at once. A stopped chain keeps the best world, the two grids, the
//! knowledge engine that types its worlds (with its cache, so the types are those the chain
//! would give) and the record of the run, and nothing that only stepping needs.

use super::trace::Trace;
use super::{typed, world_with_rooms, Chain, ChainConfig};
use crate::floorplan::edits::Edits;
use crate::floorplan::knowledge::{Inferred, Knowledge};
use crate::floorplan::rooms::{Grouping, RoomConfig, RoomError, RoomLayer, RoomMaps};
use crate::floorplan::world::{Frame, World};
use crate::grid::{Cell, Grid};
use crate::vision::orientation::WallProfile;

/// What a run's report reads of its chain, running ([`Chain`]) or stopped ([`Stopped`]):
/// counts, seed, frame, knowledge status and the trace
/// ([`crate::floorplan::report::ChainSummary`]).
pub trait RunRecord {
    /// Iterations run.
    fn iteration(&self) -> u64;
    /// The best log posterior seen.
    fn best_log_posterior(&self) -> f64;
    /// Iteration at which the best world was found.
    fn best_iteration(&self) -> u64;
    /// The seed the chain started from.
    fn seed(&self) -> u64;
    /// How the world frame sits on the map.
    fn frame(&self) -> &Frame;
    /// Depth of the units' wall rings, cells.
    fn wall_thickness(&self) -> i32;
    /// The configuration.
    fn config(&self) -> &ChainConfig;
    /// Why knowledge inference stopped, if it failed.
    fn knowledge_error(&self) -> Option<&str>;
    /// How many knowledge inferences ran (cache misses).
    fn inferences(&self) -> u64;
    /// Unit types and same-length pairs from the last inference.
    fn inferred(&self) -> &Inferred;
    /// Statistics of the run.
    fn trace(&self) -> &Trace;
    /// The Hough profile of the map's walls, when the chain estimated its angle from it.
    fn wall_profile(&self) -> Option<&WallProfile>;
}

impl RunRecord for Chain {
    fn iteration(&self) -> u64 {
        Chain::iteration(self)
    }
    fn best_log_posterior(&self) -> f64 {
        Chain::best_log_posterior(self)
    }
    fn best_iteration(&self) -> u64 {
        Chain::best_iteration(self)
    }
    fn seed(&self) -> u64 {
        Chain::seed(self)
    }
    fn frame(&self) -> &Frame {
        Chain::frame(self)
    }
    fn wall_thickness(&self) -> i32 {
        Chain::wall_thickness(self)
    }
    fn config(&self) -> &ChainConfig {
        Chain::config(self)
    }
    fn knowledge_error(&self) -> Option<&str> {
        Chain::knowledge_error(self)
    }
    fn inferences(&self) -> u64 {
        Chain::inferences(self)
    }
    fn inferred(&self) -> &Inferred {
        Chain::inferred(self)
    }
    fn trace(&self) -> &Trace {
        Chain::trace(self)
    }
    fn wall_profile(&self) -> Option<&WallProfile> {
        Chain::wall_profile(self)
    }
}

/// A chain that will run no more (module docs): its best world, the grids and the knowledge
/// that type and group it into rooms, and the record of its run.
pub struct Stopped {
    config: ChainConfig,
    frame: Frame,
    map: Grid<Cell>,
    world_map: Grid<Cell>,
    resolution: f64,
    /// The best world, untyped ([`Chain::best_world`]).
    best: World,
    knowledge: Option<Knowledge>,
    typer: Option<Knowledge>,
    edits: Edits,
    trace: Trace,
    walls: Option<WallProfile>,
    iteration: u64,
    best_log_posterior: f64,
    best_iteration: u64,
    seed: u64,
    wall_thickness: i32,
    knowledge_error: Option<String>,
    inferred: Inferred,
}

impl Chain {
    /// Stops the chain for good (module docs): keeps what its rooms and its report need and
    /// frees its sampling tables. The stopped chain's worlds, types and rooms are those this
    /// chain would give.
    ///
    /// ```
    /// use ksmcmc::floorplan::{rooms::RoomConfig, synth, Chain, ChainConfig};
    /// let s = synth::generate(&synth::SynthConfig { width: 160, height: 120, ..Default::default() }, 3).unwrap();
    /// let mut chain = Chain::new(&s.map, ChainConfig::default(), 1).unwrap();
    /// chain.step(300);
    /// let rooms = chain.best_world_with_rooms(&RoomConfig::default()).unwrap();
    /// assert!(chain.stop().best_world_with_rooms(&RoomConfig::default()).unwrap() == rooms);
    /// ```
    pub fn stop(mut self) -> Stopped {
        let best = self.best_world();
        self.make_typer();
        Stopped {
            best,
            wall_thickness: self.state.wall,
            config: self.config,
            frame: self.frame,
            map: self.map,
            world_map: self.world_map,
            resolution: self.resolution,
            knowledge: self.knowledge,
            typer: self.typer,
            edits: self.edits,
            trace: self.trace,
            walls: self.walls,
            iteration: self.iteration,
            best_log_posterior: self.best_log_posterior,
            best_iteration: self.best_iteration,
            seed: self.seed,
            knowledge_error: self.knowledge_error,
            inferred: self.inferred,
        }
    }
}

impl Stopped {
    /// The best world found, untyped ([`Chain::best_world`]).
    pub fn best_world(&self) -> &World {
        &self.best
    }

    /// The best world typed by the chain's knowledge ([`Chain::best_world_typed`]).
    pub fn best_world_typed(&mut self) -> World {
        let typer = self.knowledge.as_mut().or(self.typer.as_mut());
        typed(typer, &self.edits, self.resolution, self.best.clone()).0
    }

    /// The typed best world with its rooms and the room labels
    /// ([`Chain::best_world_with_rooms`]).
    pub fn best_world_with_rooms(&mut self, rooms: &RoomConfig) -> Result<(World, Grid<u16>), RoomError> {
        let layer = RoomLayer::new(*rooms, &self.config.knowledge)?;
        let maps = RoomMaps { map: &self.map, world_map: &self.world_map, resolution: self.resolution };
        // The fields one by one: the typer is borrowed mutably beside the maps and the edits.
        let typer = self.knowledge.as_mut().or(self.typer.as_mut());
        world_with_rooms(&layer, self.best.clone(), typer, &self.edits, maps)
    }

    /// The rooms of `world` found again where the walls part them ([`Chain::rooms_by_walls`]).
    pub fn rooms_by_walls(
        &self,
        world: &mut World,
        rooms: &RoomConfig,
        angles: &[f64],
    ) -> Result<Grid<u16>, RoomError> {
        RoomLayer::new(*rooms, &self.config.knowledge)?.explain(world, self.room_maps(), Grouping::Walls(angles))
    }

    /// The maps the room layer reads for this chain's worlds.
    fn room_maps(&self) -> RoomMaps<'_> {
        RoomMaps { map: &self.map, world_map: &self.world_map, resolution: self.resolution }
    }

    /// The classified map the chain explained, in the map's own frame.
    pub fn map(&self) -> &Grid<Cell> {
        &self.map
    }

    /// The classified map in the world frame.
    pub fn world_map(&self) -> &Grid<Cell> {
        &self.world_map
    }

    /// Metres per cell of the map.
    pub fn resolution(&self) -> f64 {
        self.resolution
    }

    /// The edits in force when the chain stopped.
    pub fn edits(&self) -> &Edits {
        &self.edits
    }
}

impl RunRecord for Stopped {
    fn iteration(&self) -> u64 {
        self.iteration
    }
    fn best_log_posterior(&self) -> f64 {
        self.best_log_posterior
    }
    fn best_iteration(&self) -> u64 {
        self.best_iteration
    }
    fn seed(&self) -> u64 {
        self.seed
    }
    fn frame(&self) -> &Frame {
        &self.frame
    }
    fn wall_thickness(&self) -> i32 {
        self.wall_thickness
    }
    fn config(&self) -> &ChainConfig {
        &self.config
    }
    fn knowledge_error(&self) -> Option<&str> {
        self.knowledge_error.as_deref()
    }
    fn inferences(&self) -> u64 {
        self.knowledge.as_ref().map_or(0, |k| k.inferences)
    }
    fn inferred(&self) -> &Inferred {
        &self.inferred
    }
    fn trace(&self) -> &Trace {
        &self.trace
    }
    fn wall_profile(&self) -> Option<&WallProfile> {
        self.walls.as_ref()
    }
}
