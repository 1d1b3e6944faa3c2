//! A simulated robot in the browser: the Exploration page drives an `Explorer` over a map and
//! hands its growing map to `Mapper.updateMap`. The simulation is [`crate::explore`]'s. In the
//! mapper module (`ksmcmc.js`, feature `wasm-mapper`), beside the chain: its snapshots are that
//! module's `Map`s, and the page loads nothing else (8 kB of the module gzipped).

use super::{Map, Mapper};
use crate::explore::{ExploreConfig, Explorer as Robot};
use crate::grid::Cell;
use wasm_bindgen::prelude::*;

/// The most cells one `advance` call drives (a page calls it again from its next frame).
pub const MAX_ADVANCE: f64 = 1_000_000.0;

/// A robot with a 2D range sensor exploring a map it does not know (`ksmcmc explore`'s).
#[derive(Debug)]
#[wasm_bindgen]
pub struct Explorer {
    robot: Robot,
}

#[wasm_bindgen]
impl Explorer {
    /// A robot on `truth`, which scans once where it starts. `configJson` is a JSON object
    /// with any of `range_m` (default 8), `scan_every_m` (0.5), `start` (`[column, row]`;
    /// default a free cell drawn from `seed`) and `give_up_m` (1). Throws, saying why, for
    /// bad settings or a start that is off the map or not free.
    #[wasm_bindgen(constructor)]
    pub fn new(
        truth: &Map,
        #[wasm_bindgen(js_name = configJson, unchecked_optional_param_type = "string")] config_json: Option<String>,
        #[wasm_bindgen(unchecked_optional_param_type = "number | bigint")] seed: Option<JsValue>,
    ) -> Result<Explorer, JsError> {
        let config = match config_json.as_deref() {
            Some(text) => ExploreConfig::from_json(text)?,
            None => ExploreConfig::default(),
        };
        let seed = match seed {
            Some(s) if !s.is_undefined() && !s.is_null() => super::seed_from_js(&s)?,
            _ => 1,
        };
        Ok(Explorer { robot: Robot::new(truth.inner(), config, seed)? })
    }

    /// Drives up to `cells` cells (a whole number, 0 to 10^6), scanning on the way. Returns
    /// whether there is more to explore.
    pub fn advance(&mut self, cells: f64) -> Result<bool, JsError> {
        let n = super::iterations_from_js("advance", cells, MAX_ADVANCE)?;
        Ok(self.robot.advance(n as usize))
    }

    /// Whether the robot has no frontier left.
    #[wasm_bindgen(getter)]
    pub fn done(&self) -> bool {
        self.robot.is_done()
    }

    /// The robot's cell: `[column, row]`.
    #[wasm_bindgen(getter)]
    pub fn robot(&self) -> Vec<u32> {
        let (x, y) = self.robot.robot();
        vec![x as u32, y as u32]
    }

    /// Metres driven so far.
    #[wasm_bindgen(getter, js_name = travelledM)]
    pub fn travelled_m(&self) -> f64 {
        self.robot.travelled_m()
    }

    /// How many scans the robot has made.
    #[wasm_bindgen(getter)]
    pub fn scans(&self) -> u32 {
        self.robot.scans().len() as u32
    }

    /// The cells where scans `from..` were made, flat: `[x0, y0, x1, y1, ...]`.
    #[wasm_bindgen(js_name = scanCells)]
    pub fn scan_cells(&self, from: u32) -> Vec<u32> {
        let scans = self.robot.scans();
        let from = (from as usize).min(scans.len());
        scans[from..].iter().flat_map(|&(x, y)| [x as u32, y as u32]).collect()
    }

    /// Free cells of the robot's map.
    #[wasm_bindgen(getter, js_name = seenFree)]
    pub fn seen_free(&self) -> u32 {
        self.robot.seen_count(Cell::Free) as u32
    }

    /// The robot's map so far, with the true map's resolution and origin: give it to
    /// `Mapper.updateMap` (or to `new Mapper` the first time).
    pub fn snapshot(&self) -> Map {
        Map::new(self.robot.snapshot())
    }
}

#[wasm_bindgen]
impl Mapper {
    /// The end of an exploration (`ksmcmc explore`'s renewal, `OnlineConfig::renew`): once the
    /// robot has no frontier left, its walls are seen from both sides wherever it could go, so
    /// the chain takes the whole-map sensor table (Tab. 3.1) in place of the range-sensor
    /// table of `chainConfigOnline`, going on from its world (both worlds rescored). The page
    /// then runs a fresh chain with that table beside it and keeps the one with the higher best
    /// log posterior.
    #[wasm_bindgen(js_name = useWholeMapSensor)]
    pub fn use_whole_map_sensor(&mut self) {
        self.set_sensor(crate::floorplan::posterior::SensorModel::default());
    }
}
