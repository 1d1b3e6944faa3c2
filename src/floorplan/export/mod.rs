//! **The export folder** owns what is made of a finished run: the room input a chain hands
//! the room layer ([`RoomInput`]), the texts of its files (`world.json`, `graph.json` with the
//! scene graph of [`graph`], `labels.pgm`, `report.json` of [`report`], `trace.csv`), room
//! shapes, GeoJSON and its placing on the Earth ([`geojson`], [`georef`]), the plan input the
//! browser hands between its modules ([`plan_input`]) and the run itself ([`run`], native). It
//! may import every other folder of the floor plan; none of them imports it, and it imports
//! nothing of the renderer: the files that are pictures (`overlay.png`, `world.svg`,
//! `world.glb`) and the nine files together are [`crate::render::Outputs`].
//!
//! The room labels need only the best world and two grids of the chain, not its tables: a
//! [`RoomInput`] takes those from a [`Chain`], so that a caller short of memory drops the
//! chain before [`RoomInput::explain`] finds the rooms (tens of MB on a large map). The files
//! are then made from the map, the world with its rooms, the labels, the report and the trace.

pub mod geojson;
pub mod georef;
pub mod graph;
pub mod outline;
pub mod plan_input;
pub mod report;
#[cfg(not(target_arch = "wasm32"))]
pub mod run;
pub mod shapes;

use super::knowledge::KnowledgeConfig;
use super::rooms::{Grouping, RoomConfig, RoomError, RoomLayer, RoomMaps};
use super::world::{World, WorldError};
use super::{Chain, Trace};
use crate::grid::{Cell, Grid, OccupancyMap};
use std::fmt::Write as _;

/// What the room labels need of a chain: its typed best world, the map in its own and in the
/// world frame, the resolution, its knowledge configuration (whether knowledge supervision is
/// on, the room rules and the indoor rules that type the rooms) and a person's edits.
#[derive(Debug, Clone)]
pub struct RoomInput {
    world: World,
    map: Grid<Cell>,
    world_map: Grid<Cell>,
    resolution: f64,
    knowledge: KnowledgeConfig,
    edits: super::edits::Edits,
    /// Set by [`RoomInput::by_walls`]: the wall directions of the building's other wings.
    by_walls: Option<Vec<f64>>,
}

impl RoomInput {
    /// Takes the typed best world ([`Chain::best_world_typed`]) and copies of the grids.
    pub fn of(chain: &mut Chain) -> RoomInput {
        RoomInput {
            world: chain.best_world_typed(),
            map: chain.map().clone(),
            world_map: chain.world_map().clone(),
            resolution: chain.resolution(),
            knowledge: chain.config().knowledge.clone(),
            edits: chain.edits().clone(),
            by_walls: None,
        }
    }

    /// The room input of a typed `world` the chain found on `map`, without the chain: the grids
    /// are made again as [`Chain::new`] made them (solid masses hollow, the map turned by the
    /// world's frame angle), so that [`RoomInput::explain`] gives what
    /// [`Chain::best_world_with_rooms`] gave. Refused if the world was made for another map.
    ///
    /// ```
    /// use ksmcmc::floorplan::export::RoomInput;
    /// use ksmcmc::floorplan::{rooms::RoomConfig, synth, Chain, ChainConfig};
    /// let s = synth::generate(&synth::SynthConfig { width: 160, height: 120, ..Default::default() }, 3).unwrap();
    /// let mut chain = Chain::new(&s.map, ChainConfig::default(), 1).unwrap();
    /// chain.step(300);
    /// let input = RoomInput::for_map(chain.best_world_typed(), &s.map, true, Default::default()).unwrap();
    /// assert!(input.explain(&RoomConfig::default()) == chain.best_world_with_rooms(&RoomConfig::default()));
    /// ```
    pub fn for_map(
        world: World,
        map: &OccupancyMap,
        knowledge: bool,
        edits: super::edits::Edits,
    ) -> Result<RoomInput, WorldError> {
        world.fits(map.width(), map.height())?;
        world.require_one_direction("finding rooms")?;
        let resolution = map.yaml().resolution;
        let (world_map, frame) = crate::vision::orientation::to_world_frame(map.classified(), world.frame.angle);
        if frame.world_size != world.frame.world_size {
            return Err(WorldError::new(format!(
                "world.json: frame.world_size is {:?}, but this map turned by frame.angle gives {:?}: the \
                 world was made for another map",
                world.frame.world_size, frame.world_size
            )));
        }
        Ok(RoomInput {
            world,
            map: map.classified().clone(),
            world_map,
            resolution,
            knowledge: KnowledgeConfig { enabled: knowledge, ..KnowledgeConfig::default() },
            edits,
            by_walls: None,
        })
    }

    /// The same input with other room rules (`None`: the built-in ones); they apply when
    /// knowledge supervision is on.
    pub fn with_room_rules(mut self, rules: Option<String>) -> RoomInput {
        self.knowledge.room_kb = rules;
        self
    }

    /// The same input with other frontier rules (`None`: the built-in ones), which weigh the
    /// placeholders with knowledge supervision or without.
    pub fn with_frontier_rules(mut self, rules: Option<String>) -> RoomInput {
        self.knowledge.frontier_kb = rules;
        self
    }

    /// The training world of the room rules for this input's world, with `truth` the truth
    /// labels of the map ([`super::rooms::room_training`]).
    pub fn room_training(
        &self,
        truth: &Grid<u16>,
        rooms: &RoomConfig,
    ) -> Result<super::rooms::RoomTraining, RoomError> {
        super::rooms::room_training(&self.world, &self.map, &self.world_map, truth, rooms, self.resolution)
    }

    /// The typed best world, without rooms yet.
    pub fn world(&self) -> &World {
        &self.world
    }

    /// The same input with its rooms found where the walls part them, in a building that no
    /// wall direction holds most of, with `angles` the other wings' wall directions
    /// ([`Grouping::Walls`], [`super::wings`]).
    pub fn by_walls(mut self, angles: &[f64]) -> RoomInput {
        self.by_walls = Some(angles.to_vec());
        self
    }

    /// The world with its room layer and the room labels, as
    /// [`Chain::best_world_with_rooms`] gives them ([`RoomLayer::explain`]), or by the walls
    /// ([`RoomInput::by_walls`]).
    pub fn explain(self, rooms: &RoomConfig) -> Result<(World, Grid<u16>), RoomError> {
        let RoomInput { mut world, map, world_map, resolution, knowledge, edits, by_walls } = self;
        let layer = RoomLayer::new(*rooms, &knowledge)?;
        let maps = RoomMaps { map: &map, world_map: &world_map, resolution };
        let grouping = match &by_walls {
            Some(angles) => Grouping::Walls(angles),
            None => Grouping::Units(&edits),
        };
        let labels = layer.explain(&mut world, maps, grouping)?;
        Ok((world, labels))
    }
}

/// `graph.json`: the scene graph of `world` and its rooms ([`graph::world_json`]), pretty.
pub fn graph_json(world: &World) -> String {
    serde_json::to_string_pretty(&graph::world_json(world)).expect("a graph serialises")
}

/// The rooms of `world` as compact JSON: the `rooms` of `world.json`.
pub fn rooms_json(world: &World) -> String {
    serde_json::to_string(&world.rooms).expect("rooms serialise")
}

/// The placeholders of `world` as compact JSON: the `placeholders` of `world.json`
/// ([`crate::floorplan::frontier`]), `[]` for none.
pub fn placeholders_json(world: &World) -> String {
    serde_json::to_string(&world.placeholders).expect("placeholders serialise")
}

/// The type marginals of the rooms ([`super::rooms::room_types`]) as compact JSON: per
/// room `{"id", "marginals": {"room", "corridor", "hall", "other"} | null, "units": [{"id",
/// "type", "marginals"}]}`.
pub fn room_types_json(rooms: &[super::rooms::RoomTypes]) -> String {
    serde_json::to_string(rooms).expect("room types serialise")
}

/// `labels.pgm`: the room id per cell as a 16-bit binary PGM.
pub fn labels_pgm(labels: &Grid<u16>) -> Vec<u8> {
    crate::grid::pgm::encode_u16(labels.width(), labels.height(), labels.cells())
}

/// `report.json`: the report, pretty.
pub fn report_json(report: &serde_json::Value) -> String {
    serde_json::to_string_pretty(report).expect("a JSON value serialises")
}

/// `trace.csv`: a header, then one line per recorded point,
/// `iteration,log_posterior,acceptance,units`.
pub fn trace_csv(trace: &Trace) -> String {
    let mut csv = String::from("iteration,log_posterior,acceptance,units\n");
    for p in &trace.points {
        let _ = writeln!(csv, "{},{:.3},{:.4},{}", p.iteration, p.log_posterior, p.acceptance, p.size);
    }
    csv
}
