//! The files of a floor-plan run, as bytes and text: what `ksmcmc floorplan` writes, what the
//! Python package's `FloorPlan.save` writes, and what the browser's plan hands out.
//!
//! They live with the pictures, not in the floor plan: three of them are drawn (`overlay.png`,
//! `world.svg`, `world.glb`), and the floor plan never imports the renderer; the rest are the
//! floor plan's own texts ([`crate::floorplan::export`]).
//!
//! ```
//! use ksmcmc::floorplan::export::{trace_csv, RoomInput};
//! use ksmcmc::floorplan::{report, rooms::RoomConfig, synth, Chain, ChainConfig};
//! use ksmcmc::render::Outputs;
//! let s = synth::generate(&synth::SynthConfig { width: 200, height: 150, ..Default::default() }, 3).unwrap();
//! let mut chain = Chain::new(&s.map, ChainConfig::default(), 1).unwrap();
//! chain.step(200);
//! let trace = trace_csv(chain.trace());
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

use super::model3d::{world_glb, Model3dError, Model3dOptions};
use super::RenderError;
use crate::floorplan::export::{graph_json, labels_pgm, report_json};
use crate::floorplan::georef::{Georef, MapOrigin};
use crate::floorplan::shapes::{floor_shapes, ShapeError};
use crate::floorplan::{geojson, World};
use crate::grid::{Cell, Grid, OccupancyMap};

/// Why the files of a run could not be made.
#[derive(Debug, Clone, PartialEq)]
pub enum ExportError {
    /// `overlay.png` cannot be drawn (a map over [`super::MAX_PIXELS`] cells).
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

impl std::error::Error for ExportError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            ExportError::Overlay(e) => Some(e),
            ExportError::Shapes(e) => Some(e),
            ExportError::Model3d(e) => Some(e),
        }
    }
}

/// The nine files of a run, as bytes and text.
#[derive(Debug, Clone, PartialEq)]
pub struct Outputs {
    /// `world.json`: the best world found (units, doors, object cells, rooms).
    pub world_json: String,
    /// `overlay.png`: the world drawn over the classified map ([`overlay_png`]).
    pub overlay_png: Vec<u8>,
    /// `graph.json`: the scene graph and the rooms ([`graph_json`]).
    pub graph_json: String,
    /// `trace.csv`: log posterior, acceptance rate and unit count over the run ([`crate::floorplan::export::trace_csv`]).
    pub trace_csv: String,
    /// `labels.pgm`: the 16-bit room segmentation ([`labels_pgm`]).
    pub labels_pgm: Vec<u8>,
    /// `report.json`: the run's summary ([`report_json`]).
    pub report_json: String,
    /// `world.geojson`: the rooms and doors in IMDF shape ([`geojson`]).
    pub world_geojson: String,
    /// `world.svg`: the floor plan as a vector drawing ([`super::svg`]).
    pub world_svg: String,
    /// `world.glb`: the 3D world, glTF 2.0 binary ([`world_glb`]).
    pub world_glb: Vec<u8>,
}

impl Outputs {
    /// All nine files of the world `world` (with its rooms) on `map`, its room `labels`, the
    /// `report` ([`crate::floorplan::report`]) and the `trace_csv`; `world.geojson` in longitude and
    /// latitude with a `georef`, else in metres of the map frame; the 3D world with the heights
    /// of `model`. Fails if the overlay cannot be drawn (a map over [`super::MAX_PIXELS`]
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
            world_svg: super::svg::svg(&shapes, world, map.yaml().resolution),
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
    let pixmap = super::try_render(map, Some(world), &Default::default())?;
    Ok(super::encode_png(&pixmap))
}
