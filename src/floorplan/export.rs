//! The files of a floor-plan run, written the same way by `ksmcmc floorplan` and by the
//! browser's `Mapper`: `world.json`, `overlay.png`, `graph.json`, `trace.csv`, `labels.pgm`
//! and `report.json`.
//!
//! The room labels need only the best world and two grids of the chain, not its tables: a
//! [`RoomInput`] takes those from a [`Chain`], so that a caller short of memory drops the
//! chain before [`RoomInput::explain`] finds the rooms (tens of MB on a large map). The
//! [`Outputs`] are then made from the map, the world with its rooms, the labels, the report and
//! the trace.
//!
//! ```
//! use ksmcmc::floorplan::export::{Outputs, RoomInput};
//! use ksmcmc::floorplan::{report, rooms::RoomConfig, synth, Chain, ChainConfig};
//! let s = synth::generate(&synth::SynthConfig { width: 200, height: 150, ..Default::default() }, 3).unwrap();
//! let mut chain = Chain::new(&s.map, ChainConfig::default(), 1).unwrap();
//! chain.step(200);
//! let trace = ksmcmc::floorplan::export::trace_csv(chain.trace());
//! let input = RoomInput::of(&mut chain);
//! let mut summary = report::summary(&chain, &s.map, input.world(), 1.0);
//! drop(chain);
//! let (world, labels) = input.explain(&RoomConfig::default());
//! report::add_rooms(&mut summary, &world, &labels);
//! let out = Outputs::new(&s.map, &world, &labels, &summary, trace).unwrap();
//! let names: Vec<&str> = out.files().iter().map(|(name, _)| *name).collect();
//! assert_eq!(names, ["world.json", "overlay.png", "graph.json", "trace.csv", "labels.pgm", "report.json"]);
//! assert!(out.trace_csv.starts_with("iteration,log_posterior,acceptance,units\n"));
//! ```

use super::world::World;
use super::{graph, room_layer, rooms::RoomConfig, Chain, Trace};
use crate::grid::{Cell, Grid, OccupancyMap};
use crate::render::{self, RenderError};
use std::fmt::Write as _;

/// What the room labels need of a chain: its typed best world, the map in its own and in the
/// world frame, the resolution and whether knowledge supervision is on.
#[derive(Debug, Clone)]
pub struct RoomInput {
    world: World,
    map: Grid<Cell>,
    world_map: Grid<Cell>,
    resolution: f64,
    knowledge: bool,
    edits: super::edits::Edits,
}

impl RoomInput {
    /// Takes the typed best world ([`Chain::best_world_typed`]) and copies of the grids.
    pub fn of(chain: &mut Chain) -> RoomInput {
        RoomInput {
            world: chain.best_world_typed(),
            map: chain.map().clone(),
            world_map: chain.world_map().clone(),
            resolution: chain.resolution(),
            knowledge: chain.config().knowledge.enabled,
            edits: chain.edits().clone(),
        }
    }

    /// The typed best world, without rooms yet.
    pub fn world(&self) -> &World {
        &self.world
    }

    /// The world with its room layer and the room labels, as
    /// [`Chain::best_world_with_rooms`] gives them ([`room_layer::explain_world_rooms`]).
    pub fn explain(self, rooms: &RoomConfig) -> (World, Grid<u16>) {
        let RoomInput { mut world, map, world_map, resolution, knowledge, edits } = self;
        let labels =
            room_layer::explain_world_rooms(&mut world, &map, &world_map, rooms, resolution, knowledge, &edits);
        (world, labels)
    }
}

/// The six files of a run, as bytes and text.
#[derive(Debug, Clone, PartialEq)]
pub struct Outputs {
    /// `world.json`: the best world found (units, doors, object cells, rooms).
    pub world_json: String,
    /// `overlay.png`: the world drawn over the classified map ([`overlay_png`]).
    pub overlay_png: Vec<u8>,
    /// `graph.json`: the scene graph and the rooms ([`graph_json`]).
    pub graph_json: String,
    /// `trace.csv`: log posterior, acceptance rate and unit count over the run ([`trace_csv`]).
    pub trace_csv: String,
    /// `labels.pgm`: the 16-bit room segmentation ([`labels_pgm`]).
    pub labels_pgm: Vec<u8>,
    /// `report.json`: the run's summary ([`report_json`]).
    pub report_json: String,
}

impl Outputs {
    /// All six files of the world `world` (with its rooms) on `map`, its room `labels`, the
    /// `report` ([`super::report`]) and the `trace_csv`. Fails only if the overlay cannot be
    /// drawn (a map over [`render::MAX_PIXELS`] cells).
    pub fn new(
        map: &OccupancyMap,
        world: &World,
        labels: &Grid<u16>,
        report: &serde_json::Value,
        trace_csv: String,
    ) -> Result<Outputs, RenderError> {
        Ok(Outputs {
            world_json: world.to_json(),
            overlay_png: overlay_png(map.classified(), world)?,
            graph_json: graph_json(world),
            trace_csv,
            labels_pgm: labels_pgm(labels),
            report_json: report_json(report),
        })
    }

    /// The files by name, in the order `ksmcmc floorplan` writes them.
    pub fn files(&self) -> [(&'static str, &[u8]); 6] {
        [
            ("world.json", self.world_json.as_bytes()),
            ("overlay.png", &self.overlay_png),
            ("graph.json", self.graph_json.as_bytes()),
            ("trace.csv", self.trace_csv.as_bytes()),
            ("labels.pgm", &self.labels_pgm),
            ("report.json", self.report_json.as_bytes()),
        ]
    }
}

/// `overlay.png`: `world` over the classified `map` at scale 1, with labels.
pub fn overlay_png(map: &Grid<Cell>, world: &World) -> Result<Vec<u8>, RenderError> {
    let pixmap = render::try_render(map, Some(world), &Default::default())?;
    Ok(render::encode_png(&pixmap))
}

/// `graph.json`: the scene graph of `world` and its rooms ([`graph::world_json`]), pretty.
pub fn graph_json(world: &World) -> String {
    serde_json::to_string_pretty(&graph::world_json(world)).expect("a graph serialises")
}

/// The rooms of `world` as compact JSON: the `rooms` of `world.json`.
pub fn rooms_json(world: &World) -> String {
    serde_json::to_string(&world.rooms).expect("rooms serialise")
}

/// The type marginals of the rooms ([`super::room_types::room_types`]) as compact JSON: per
/// room `{"id", "marginals": {"room", "corridor", "hall", "other"} | null, "units": [{"id",
/// "type", "marginals"}]}`.
pub fn room_types_json(rooms: &[super::room_types::RoomTypes]) -> String {
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
