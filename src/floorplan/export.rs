//! The files of a floor-plan run, written the same way by `ksmcmc floorplan` and by the
//! browser's `Mapper`: `world.json`, `overlay.png`, `graph.json`, `trace.csv`, `labels.pgm`,
//! `report.json`, the floor plan for other tools, `world.geojson` ([`super::geojson`]) and
//! `world.svg` ([`crate::render::svg`]), and `world.glb` (the 3D world, [`crate::render::model3d`]).
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
//! let (world, labels) = input.explain(&RoomConfig::default()).unwrap();
//! report::add_rooms(&mut summary, &world, &labels);
//! let out = Outputs::new(&s.map, &world, &labels, &summary, trace, None, &Default::default()).unwrap();
//! let names: Vec<&str> = out.files().iter().map(|(name, _)| *name).collect();
//! assert_eq!(
//!     names,
//!     ["world.json", "overlay.png", "graph.json", "trace.csv", "labels.pgm", "report.json", "world.geojson", "world.svg", "world.glb"]
//! );
//! assert!(out.trace_csv.starts_with("iteration,log_posterior,acceptance,units\n"));
//! ```

use super::georef::{Georef, MapOrigin};
use super::knowledge::KnowledgeConfig;
use super::rooms::{Grouping, RoomConfig, RoomError, RoomLayer, RoomMaps};
use super::shapes::{floor_shapes, ShapeError};
use super::world::{World, WorldError};
use super::{geojson, graph, Chain, Trace};
use crate::grid::{Cell, Grid, OccupancyMap};
use crate::render::model3d::{world_glb, Model3dError, Model3dOptions};
use crate::render::{self, RenderError};
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
            return Err(WorldError(format!(
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

/// Why the files of a run could not be made.
#[derive(Debug, Clone, PartialEq)]
pub enum ExportError {
    /// `overlay.png` cannot be drawn (a map over [`render::MAX_PIXELS`] cells).
    Overlay(RenderError),
    /// The room shapes of `world.geojson` and `world.svg` cannot be made (an invalid world, or
    /// labels of another size).
    Shapes(ShapeError),
    /// The 3D world cannot be made (heights out of range).
    Model3d(Model3dError),
}

impl std::fmt::Display for ExportError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            ExportError::Overlay(e) => write!(f, "overlay.png: {e}"),
            ExportError::Shapes(e) => write!(f, "world.geojson and world.svg: {e}"),
            ExportError::Model3d(e) => write!(f, "world.glb: {e}"),
        }
    }
}

impl std::error::Error for ExportError {}

/// The nine files of a run, as bytes and text.
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
    /// `world.geojson`: the rooms and doors in IMDF shape ([`geojson`]).
    pub world_geojson: String,
    /// `world.svg`: the floor plan as a vector drawing ([`render::svg`]).
    pub world_svg: String,
    /// `world.glb`: the 3D world, glTF 2.0 binary ([`world_glb`]).
    pub world_glb: Vec<u8>,
}

impl Outputs {
    /// All nine files of the world `world` (with its rooms) on `map`, its room `labels`, the
    /// `report` ([`super::report`]) and the `trace_csv`; `world.geojson` in longitude and
    /// latitude with a `georef`, else in metres of the map frame; the 3D world with the heights
    /// of `model`. Fails if the overlay cannot be drawn (a map over [`render::MAX_PIXELS`]
    /// cells), the world or labels are not valid, or the heights are out of range.
    pub fn new(
        map: &OccupancyMap,
        world: &World,
        labels: &Grid<u16>,
        report: &serde_json::Value,
        trace_csv: String,
        georef: Option<&Georef>,
        model: &Model3dOptions,
    ) -> Result<Outputs, ExportError> {
        let shapes = floor_shapes(world, labels).map_err(ExportError::Shapes)?;
        Ok(Outputs {
            world_glb: world_glb(world, map.yaml().resolution, model).map_err(ExportError::Model3d)?,
            world_json: world.to_json(),
            overlay_png: overlay_png(map.classified(), world).map_err(ExportError::Overlay)?,
            graph_json: graph_json(world),
            trace_csv,
            labels_pgm: labels_pgm(labels),
            report_json: report_json(report),
            world_geojson: geojson::geojson(&shapes, &MapOrigin::of(map), georef),
            world_svg: render::svg::svg(&shapes, world, map.yaml().resolution),
        })
    }

    /// The files by name, in the order `ksmcmc floorplan` writes them.
    pub fn files(&self) -> [(&'static str, &[u8]); 9] {
        [
            ("world.json", self.world_json.as_bytes()),
            ("overlay.png", &self.overlay_png),
            ("graph.json", self.graph_json.as_bytes()),
            ("trace.csv", self.trace_csv.as_bytes()),
            ("labels.pgm", &self.labels_pgm),
            ("report.json", self.report_json.as_bytes()),
            ("world.geojson", self.world_geojson.as_bytes()),
            ("world.svg", self.world_svg.as_bytes()),
            ("world.glb", &self.world_glb),
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
