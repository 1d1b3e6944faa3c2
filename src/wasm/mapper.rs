//! The live mapper's bindings: a running [`Chain`] as the JavaScript class `Mapper`, and the
//! drawing helpers that show it on a `<canvas>`. In the mapper module (`ksmcmc.js`).
//!
//! As in the rest of this layer there is no logic here beyond converting and checking
//! arguments: stepping, the best world, the trace, the samples and the scene graph are the
//! library's; the pictures are [`crate::render`]'s. A page drives the chain from
//! `requestAnimationFrame`:
//!
//! ```js
//! const mapper = new Mapper(map, undefined, 1);
//! function frame() {
//!   mapper.runFor(8);                                   // about 8 ms of iterations
//!   drawMapper(canvas, mapper, { show: 'current', cloud: false });
//!   requestAnimationFrame(frame);
//! }
//! requestAnimationFrame(frame);
//! ```
//!
//! The best world's rooms and everything made from them (`world.json`, the labels, GeoJSON,
//! SVG, glTF, routes, the report, `overlay.png`) are the plan module's `Plan`
//! ([`super::plan`]), which `planInput()` feeds: the room layer is not needed for the first
//! frame, and leaving it out keeps this module small.

use super::{from_object, js_message, now_ms, put_rgba, seed_from_js, Map, Rendered};
use crate::floorplan::plan_input::PlanInput;
use crate::floorplan::settled::Settled;
use crate::floorplan::{edits, metrics, Chain, ChainConfig, Rect, World};
use crate::grid::{Cell, OccupancyMap};
use crate::render::{self, RenderOptions};
use serde::Deserialize;
use tiny_skia::Pixmap;
use wasm_bindgen::prelude::*;

#[wasm_bindgen(typescript_custom_section)]
const TS_TYPES: &str = r#"
/** Options of `drawMapper` and `renderMapperRgba`. */
export interface MapperDrawOptions {
  /** Which world to draw over the map (default 'current'). */
  show?: 'current' | 'best' | 'reference' | 'none';
  /** Overlay the posterior cloud: the last accepted worlds as thin lines (default false). */
  cloud?: boolean;
  /** Output pixels per map cell (default 1). */
  scale?: number;
  /**
   * Labels (default true): each room's type and id (as in `labelsPgm` and `roomsJson`) when the
   * world drawn has rooms (a plan's `worldJson()`); a chain's own world has none, so it gets no
   * labels unless `unitLabels` asks for the units'.
   */
  labels?: boolean;
  /** Label units rather than rooms: each unit's type and id (default false). */
  unitLabels?: boolean;
  /** The legend of the colours drawn, in a corner of the picture (default true). */
  legend?: boolean;
  /**
   * A `world.json` text to draw instead of the world `show` names, e.g. a plan's
   * `worldJson()` (the plan module's), which makes the picture its `overlay.png`.
   */
  world?: string;
}
"#;

/// The largest map the live mapper takes, in cells: 2^23 (e.g. 4096 x 2048). The chain keeps
/// several per-cell grids and the canvas a picture of the map; beyond this a browser tab runs
/// short of memory before the chain gets anywhere.
pub const MAX_MAPPER_CELLS: usize = 1 << 23;

/// The most iterations one `step` call may run: about a second natively on a large map. A page
/// that wants more calls `step` again from its next frame.
pub const MAX_STEP: f64 = 10_000_000.0;

/// The longest time budget of one `runFor` call, in milliseconds.
pub const MAX_BUDGET_MS: f64 = 60_000.0;

/// A floor-plan chain running on one map, for a page's frame loop.
#[wasm_bindgen]
pub struct Mapper {
    chain: Chain,
    map: OccupancyMap,
    config: ChainConfig,
    /// The map drawn at some scale, reused by every frame.
    base: Option<(u32, Pixmap)>,
    /// The best world, exported once per improvement, keyed by (best iteration, best log
    /// posterior), with its K(W, M) on the map.
    best: Option<((u64, u64), World, f64)>,
    /// The current world, exported once per iteration count: a frame draws it twice (map and
    /// scene graph), and exporting a large world costs milliseconds.
    current: Option<(u64, World)>,
    reference: Option<World>,
    /// Whether the best world has stopped improving (the library's rule).
    settled: Settled,
    setup_ms: f64,
    busy_ms: f64,
}

impl Mapper {
    /// The library chain.
    pub fn chain(&self) -> &Chain {
        &self.chain
    }

    /// The best world found so far (cached between improvements) and its K(W, M).
    fn best(&mut self) -> (&World, f64) {
        let key = (self.chain.best_iteration(), self.chain.best_log_posterior().to_bits());
        if self.best.as_ref().is_none_or(|(k, _, _)| *k != key) {
            let world = self.chain.best_world_typed();
            let k = metrics::prediction_rate(self.map.classified(), &world);
            self.best = Some((key, world, k));
        }
        let (_, world, k) = self.best.as_ref().expect("just filled");
        (world, *k)
    }

    /// The current world (cached until the chain moves).
    fn current(&mut self) -> &World {
        let it = self.chain.iteration();
        if self.current.as_ref().is_none_or(|(k, _)| *k != it) {
            self.current = Some((it, self.chain.world()));
        }
        &self.current.as_ref().expect("just filled").1
    }

    fn world_for(&mut self, show: Show) -> Option<World> {
        match show {
            Show::Current => Some(self.current().clone()),
            Show::Best => Some(self.best().0.clone()),
            Show::Reference => self.reference.clone(),
            Show::None => None,
        }
    }

    /// Forgets the worlds cached from the chain: it restarted, took edits or a new map.
    fn forget_worlds(&mut self) {
        self.best = None;
        self.current = None;
    }

    fn restart(&mut self, chain: Chain) {
        self.chain = chain;
        self.settled = Settled::for_floor(self.map.count(Cell::Free), self.chain.resolution());
        self.forget_worlds();
        self.busy_ms = 0.0;
    }

    /// Explains the map from now on under `sensor` (the chain's worlds rescored,
    /// [`Chain::set_sensor`]), its cached worlds and settle rule started afresh: the log
    /// posterior jumps with the table.
    #[cfg(feature = "wasm-explore")]
    pub(crate) fn set_sensor(&mut self, sensor: crate::floorplan::posterior::SensorModel) {
        self.chain.set_sensor(sensor);
        self.settled = Settled::for_floor(self.map.count(Cell::Free), self.chain.resolution());
        self.forget_worlds();
    }

    /// The picture `drawMapper` shows.
    pub fn picture(&mut self, options: &DrawOptions) -> Result<Pixmap, JsError> {
        let (w, h) = (self.map.width(), self.map.height());
        let scale = options.scale;
        render::check_size(w, h, scale)?;
        if self.base.as_ref().is_none_or(|(s, _)| *s != scale) {
            let opts = RenderOptions { scale, labels: false, legend: false };
            let base =
                render::try_render(self.map.classified(), None, &opts).map_err(|e| JsError::new(&e.to_string()))?;
            self.base = Some((scale, base));
        }
        let mut pixmap = self.base.as_ref().expect("just drawn").1.clone();
        let world = match &options.world {
            Some(text) => Some(World::from_json(text)?),
            None => self.world_for(options.show),
        };
        if let Some(mut world) = world {
            // Rooms first (issue 33): the labels are the rooms of the Rooms table; a world
            // without rooms (the chain's own) is labelled only when units are asked for.
            let labels = options.labels && (options.unit_labels || !world.rooms.is_empty());
            if options.unit_labels {
                world.rooms.clear();
            }
            render::draw_world(&mut pixmap, w, h, &world, &RenderOptions { scale, labels, legend: options.legend });
        }
        if options.cloud {
            let samples: Vec<&[Rect]> = self.chain.samples().map(|s| s.as_slice()).collect();
            render::draw_cloud(&mut pixmap, w, h, self.chain.frame(), &samples, scale);
        }
        Ok(pixmap)
    }

    /// The scene graph picture `drawSceneGraph` shows.
    pub fn graph_picture(&mut self, show: Show, width: u32, height: u32) -> Result<Pixmap, JsError> {
        let world =
            self.world_for(show).unwrap_or_else(|| World::empty(self.map.width() as u32, self.map.height() as u32));
        render::render_scene_graph(&world, width, height).map_err(|e| JsError::new(&format!("scene graph: {e}")))
    }
}

#[wasm_bindgen]
impl Mapper {
    /// Starts a chain on `map`: estimates the map's orientation (unless the config gives it),
    /// runs the wall detector and starts from the empty world.
    ///
    /// `configJson` is a JSON object with any subset of the chain's settings (see
    /// `chainConfigDefaults()`); fields it leaves out keep their defaults, unknown fields and
    /// values out of range are errors. `seed` is a whole number ≥ 0 as for `synth` (default 1,
    /// as `ksmcmc floorplan`). Throws if the map cannot be explained (no free cells, smaller
    /// than one unit, over 2^23 cells) or the config is bad.
    #[wasm_bindgen(constructor)]
    pub fn new(
        map: &Map,
        #[wasm_bindgen(js_name = configJson, unchecked_optional_param_type = "string")] config_json: Option<String>,
        #[wasm_bindgen(unchecked_optional_param_type = "number | bigint")] seed: Option<JsValue>,
    ) -> Result<Mapper, JsError> {
        let config = chain_config(config_json.as_deref())?;
        let seed = match seed {
            Some(s) if !s.is_undefined() && !s.is_null() => seed_from_js(&s)?,
            _ => 1,
        };
        let inner = map.inner();
        let cells = inner.width() * inner.height();
        if cells > MAX_MAPPER_CELLS {
            return Err(JsError::new(&format!(
                "the map is {}x{} = {cells} cells; the live mapper takes at most {MAX_MAPPER_CELLS} \
                 (e.g. 4096x2048): crop or downsample it",
                inner.width(),
                inner.height()
            )));
        }
        let t0 = now_ms();
        let chain = Chain::new(inner, config.clone(), seed).map_err(|e| JsError::new(&e.to_string()))?;
        let setup_ms = now_ms() - t0;
        let settled = Settled::for_floor(inner.count(Cell::Free), chain.resolution());
        Ok(Mapper {
            chain,
            map: inner.clone(),
            config,
            base: None,
            best: None,
            current: None,
            reference: None,
            settled,
            setup_ms,
            busy_ms: 0.0,
        })
    }

    /// Runs `n` iterations (a whole number, 0 to 10^7). Returns `n`.
    pub fn step(&mut self, n: f64) -> Result<f64, JsError> {
        let steps = super::iterations_from_js("step", n, MAX_STEP)?;
        let t0 = now_ms();
        self.settled.step(&mut self.chain, steps);
        self.busy_ms += now_ms() - t0;
        Ok(n)
    }

    /// Runs iterations until `budgetMs` milliseconds have passed by `performance.now()`,
    /// checking the clock every 16 iterations (so at least 16 run). Returns how many ran.
    /// `budgetMs` is a number from 0 to 60000.
    #[wasm_bindgen(js_name = runFor)]
    pub fn run_for(&mut self, #[wasm_bindgen(js_name = budgetMs)] budget_ms: f64) -> Result<f64, JsError> {
        let budget_ms = super::budget_from_js("runFor", budget_ms, MAX_BUDGET_MS)?;
        let t0 = now_ms();
        let done = self.settled.run_for(&mut self.chain, budget_ms, &mut now_ms);
        self.busy_ms += now_ms() - t0;
        Ok(done as f64)
    }

    /// Starts over from the empty world, with the same seed or another one: the chain is
    /// exactly the one the constructor makes for that seed (so the detectors run again).
    pub fn reset(
        &mut self,
        #[wasm_bindgen(unchecked_optional_param_type = "number | bigint")] seed: Option<JsValue>,
    ) -> Result<(), JsError> {
        let seed = match seed {
            Some(s) if !s.is_undefined() && !s.is_null() => seed_from_js(&s)?,
            _ => self.chain.seed(),
        };
        // A new chain rather than a clone of the first one: `Chain::clone` does not keep the
        // capacity of the trace's acceptance window, which the trace reads as its size.
        let t0 = now_ms();
        let mut chain = Chain::new(&self.map, self.config.clone(), seed).map_err(|e| JsError::new(&e.to_string()))?;
        chain.set_edits(self.chain.edits().clone()).map_err(|e| JsError::new(&e.to_string()))?;
        self.setup_ms = now_ms() - t0;
        self.restart(chain);
        Ok(())
    }

    /// Takes a new snapshot of the map and goes on from the current world instead of starting
    /// over: for a map that grows while a robot explores, or a paint stroke. Only what the
    /// changed cells reach is redone (the library's `Chain::update_map`). The map must keep its
    /// size. Returns how many cells changed (0 leaves everything as it was).
    #[wasm_bindgen(js_name = updateMap)]
    pub fn update_map(&mut self, map: &Map) -> Result<f64, JsError> {
        let t0 = now_ms();
        let update = self.chain.update_map(map.inner()).map_err(|e| JsError::new(&e.to_string()))?;
        self.busy_ms += now_ms() - t0;
        if update.changed_cells > 0 {
            self.map = map.inner().clone();
            self.settled = Settled::for_floor(self.map.count(Cell::Free), self.chain.resolution());
            self.base = None;
            self.forget_worlds();
        }
        Ok(update.changed_cells as f64)
    }

    /// Takes a person's corrections as hard evidence and goes on from the current world (as
    /// `ksmcmc floorplan --edits`): `editsJson` is a JSON list of
    /// `{"op": "merge", "at": [[x1, y1], [x2, y2]]}`, `{"op": "split", "line": [[x1, y1], [x2, y2]]}`,
    /// `{"op": "type", "at": [x, y], "type": "corridor"}` and `{"op": "name", "at": [x, y], "name": "Kitchen"}`
    /// in map cells. `[]` lifts every edit. While edits are in force, a `Plan` made with the
    /// previous plan's `roomLabels()` keeps its rooms' ids. Edits stay through `reset`. Throws,
    /// changing nothing, on bad JSON or a point off the map.
    #[wasm_bindgen(js_name = setEdits)]
    pub fn set_edits(&mut self, #[wasm_bindgen(js_name = editsJson)] edits_json: &str) -> Result<(), JsError> {
        let e = edits::Edits::parse(edits_json).map_err(|e| JsError::new(&e.to_string()))?;
        self.chain.set_edits(e).map_err(|e| JsError::new(&e.to_string()))?;
        self.forget_worlds();
        Ok(())
    }

    /// The edits in force, as the JSON list `setEdits` takes (`[]` for none).
    #[wasm_bindgen(js_name = editsJson)]
    pub fn edits_json(&self) -> String {
        self.chain.edits().to_json()
    }

    /// The iteration at which the chain settled: its best log posterior improved by less than
    /// 0.3 % over the last `settleWindow` iterations (looked at every 100 iterations; the same
    /// seed settles at the same iteration however the iterations are chunked). `undefined`
    /// while it has not, or since it improved again.
    #[wasm_bindgen(getter, js_name = settledAt)]
    pub fn settled_at(&self) -> Option<f64> {
        self.settled.settled_at().map(|i| i as f64)
    }

    /// Iterations without a real improvement that make the chain settled: 5 per m² of free
    /// floor, from 1,000 to 200,000.
    #[wasm_bindgen(getter, js_name = settleWindow)]
    pub fn settle_window(&self) -> f64 {
        self.settled.window() as f64
    }

    /// The last iteration (a multiple of 100) at which the best log posterior improved by more
    /// than 0.3 %.
    #[wasm_bindgen(getter, js_name = improvedAt)]
    pub fn improved_at(&self) -> Option<f64> {
        self.settled.improved_at().map(|i| i as f64)
    }

    /// Iterations run since the start (or the last reset).
    #[wasm_bindgen(getter)]
    pub fn iteration(&self) -> f64 {
        self.chain.iteration() as f64
    }

    /// The seed the chain started from.
    #[wasm_bindgen(getter)]
    pub fn seed(&self) -> u64 {
        self.chain.seed()
    }

    /// `log p(W|M)` of the current world (up to a constant).
    #[wasm_bindgen(getter, js_name = logPosterior)]
    pub fn log_posterior(&self) -> f64 {
        self.chain.log_posterior()
    }

    /// The best log posterior seen.
    #[wasm_bindgen(getter, js_name = bestLogPosterior)]
    pub fn best_log_posterior(&self) -> f64 {
        self.chain.best_log_posterior()
    }

    /// The iteration at which the best world was found.
    #[wasm_bindgen(getter, js_name = bestIteration)]
    pub fn best_iteration(&self) -> f64 {
        self.chain.best_iteration() as f64
    }

    /// Acceptance rate over the recent window of proposals (0 to 1).
    #[wasm_bindgen(getter)]
    pub fn acceptance(&self) -> f64 {
        self.chain.trace().acceptance()
    }

    /// Units in the current world.
    #[wasm_bindgen(getter)]
    pub fn units(&self) -> u32 {
        self.chain.units().len() as u32
    }

    /// Doors in the current world.
    #[wasm_bindgen(getter)]
    pub fn doors(&self) -> u32 {
        self.chain.current_rects().1.len() as u32
    }

    /// Units in the best world.
    #[wasm_bindgen(getter, js_name = bestUnits)]
    pub fn best_units(&mut self) -> u32 {
        self.best().0.units.len() as u32
    }

    /// Doors in the best world.
    #[wasm_bindgen(getter, js_name = bestDoors)]
    pub fn best_doors(&mut self) -> u32 {
        self.best().0.doors.len() as u32
    }

    /// `K(W, M)` (eq. 3.39) of the current world: the share of cells whose class it predicts,
    /// in the world frame.
    #[wasm_bindgen(getter, js_name = predictionRate)]
    pub fn prediction_rate(&self) -> f64 {
        self.chain.prediction_rate()
    }

    /// `K(W, M)` of the best world on the map's own cells, as `ksmcmc floorplan` reports it.
    #[wasm_bindgen(getter, js_name = bestPredictionRate)]
    pub fn best_prediction_rate(&mut self) -> f64 {
        self.best().1
    }

    /// Map width in cells.
    #[wasm_bindgen(getter)]
    pub fn width(&self) -> u32 {
        self.map.width() as u32
    }

    /// Map height in cells.
    #[wasm_bindgen(getter)]
    pub fn height(&self) -> u32 {
        self.map.height() as u32
    }

    /// The map's rotation the chain works in, degrees (estimated unless configured).
    #[wasm_bindgen(getter, js_name = rotationDeg)]
    pub fn rotation_deg(&self) -> f64 {
        self.chain.frame().angle.to_degrees()
    }

    /// Depth of the units' wall rings, cells.
    #[wasm_bindgen(getter, js_name = wallThickness)]
    pub fn wall_thickness(&self) -> i32 {
        self.chain.wall_thickness()
    }

    /// How many unit candidates the detectors proposed so far.
    #[wasm_bindgen(getter)]
    pub fn candidates(&self) -> u32 {
        self.chain.candidates().len() as u32
    }

    /// Milliseconds the constructor (or the last reset) spent setting up:
    /// orientation and detectors.
    #[wasm_bindgen(getter, js_name = setupMs)]
    pub fn setup_ms(&self) -> f64 {
        self.setup_ms
    }

    /// Milliseconds spent in `step` and `runFor` since the start or the last reset.
    #[wasm_bindgen(getter, js_name = elapsedMs)]
    pub fn elapsed_ms(&self) -> f64 {
        self.busy_ms
    }

    /// The map (a new `Map` on each read).
    #[wasm_bindgen(getter)]
    pub fn map(&self) -> Map {
        Map::new(self.map.clone())
    }

    /// The current world as `world.json` text.
    #[wasm_bindgen(js_name = worldJson)]
    pub fn world_json(&mut self) -> String {
        self.current().to_json()
    }

    /// The recorded trace from point `from` on (default 0): one point every
    /// `output.trace_every` iterations (100 by default) with the iteration, the current log
    /// posterior, the acceptance rate and the unit count. Pass the number of points already
    /// read to fetch only new ones.
    #[wasm_bindgen(
        unchecked_return_type = "{ iteration: Float64Array; logPosterior: Float64Array; acceptance: Float64Array; units: Uint32Array }"
    )]
    pub fn trace(&self, from: Option<u32>) -> Result<JsValue, JsError> {
        let points = &self.chain.trace().points;
        let from = (from.unwrap_or(0) as usize).min(points.len());
        let points = &points[from..];
        let it: Vec<f64> = points.iter().map(|p| p.iteration as f64).collect();
        let lp: Vec<f64> = points.iter().map(|p| p.log_posterior).collect();
        let acc: Vec<f64> = points.iter().map(|p| p.acceptance).collect();
        let units: Vec<u32> = points.iter().map(|p| p.size).collect();
        object(&[
            ("iteration", js_sys::Float64Array::from(&it[..]).into()),
            ("logPosterior", js_sys::Float64Array::from(&lp[..]).into()),
            ("acceptance", js_sys::Float64Array::from(&acc[..]).into()),
            ("units", js_sys::Uint32Array::from(&units[..]).into()),
        ])
    }

    /// Number of recorded trace points.
    #[wasm_bindgen(getter, js_name = traceLength)]
    pub fn trace_length(&self) -> u32 {
        self.chain.trace().points.len() as u32
    }

    /// The last accepted worlds (up to `output.samples`, 1000 by default), oldest first, as
    /// unit rectangles in the world frame: sample `i` holds units `offsets[i]` to
    /// `offsets[i + 1] - 1`, unit `u` is `rects[4u .. 4u + 4]` = x, y, w, h in cells. `frame`
    /// says how the world frame sits on the map (`angle` in radians; see `world.json`).
    #[wasm_bindgen(
        unchecked_return_type = "{ rects: Int32Array; offsets: Uint32Array; frame: { angle: number; worldSize: [number, number]; mapSize: [number, number] } }"
    )]
    pub fn samples(&self) -> Result<JsValue, JsError> {
        let mut rects = Vec::new();
        let mut offsets = vec![0u32];
        for sample in self.chain.samples() {
            for r in sample {
                rects.extend_from_slice(&[r.x, r.y, r.w, r.h]);
            }
            offsets.push((rects.len() / 4) as u32);
        }
        let f = self.chain.frame();
        let pair = |v: [u32; 2]| -> JsValue { js_sys::Array::of2(&v[0].into(), &v[1].into()).into() };
        let frame =
            object(&[("angle", f.angle.into()), ("worldSize", pair(f.world_size)), ("mapSize", pair(f.map_size))])?;
        object(&[
            ("rects", js_sys::Int32Array::from(&rects[..]).into()),
            ("offsets", js_sys::Uint32Array::from(&offsets[..]).into()),
            ("frame", frame),
        ])
    }

    /// Sets a world to compare with (`show: 'reference'`), e.g. a sample's `truth.json` or a
    /// saved result, or clears it with no argument. The world must be valid `world.json` for a
    /// map of this map's size whose units land on the map ([`World::fits`]); otherwise this
    /// throws and keeps the old reference.
    #[wasm_bindgen(js_name = setReference)]
    pub fn set_reference(
        &mut self,
        #[wasm_bindgen(js_name = worldJson)] world_json: Option<String>,
    ) -> Result<(), JsError> {
        let Some(text) = world_json else {
            self.reference = None;
            return Ok(());
        };
        let world = World::from_json(&text)?;
        world.fits(self.map.width(), self.map.height())?;
        self.reference = Some(world);
        Ok(())
    }

    /// Whether a reference world is set.
    #[wasm_bindgen(getter, js_name = hasReference)]
    pub fn has_reference(&self) -> bool {
        self.reference.is_some()
    }
}

/// Which world a picture shows.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize, Default)]
#[serde(rename_all = "lowercase")]
pub enum Show {
    /// The chain's current world.
    #[default]
    Current,
    /// The best world found so far.
    Best,
    /// The world set with `setReference`.
    Reference,
    /// No world: the map alone (with the cloud, if asked for).
    None,
}

/// Options of `drawMapper`, `renderMapperRgba` and `Mapper.toPng`.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct DrawOptions {
    /// Which world to draw over the map.
    pub show: Show,
    /// Overlay the posterior cloud (the last accepted worlds as thin lines).
    pub cloud: bool,
    /// Output pixels per map cell.
    pub scale: u32,
    /// Labels: each room's type and id when the world drawn has rooms, else none unless
    /// `unit_labels`.
    pub labels: bool,
    /// Label units (each unit's type and id) rather than rooms.
    #[serde(rename = "unitLabels")]
    pub unit_labels: bool,
    /// The legend of the colours drawn, in a corner.
    pub legend: bool,
    /// A `world.json` text to draw instead of `show`'s world (e.g. a plan's, with its rooms).
    pub world: Option<String>,
}

impl Default for DrawOptions {
    fn default() -> Self {
        DrawOptions {
            show: Show::Current,
            cloud: false,
            scale: 1,
            labels: true,
            unit_labels: false,
            legend: true,
            world: None,
        }
    }
}

impl DrawOptions {
    /// Reads options from a JavaScript object (`undefined` or `null`: the defaults).
    pub fn from_js(v: Option<&JsValue>) -> Result<DrawOptions, JsError> {
        let Some(v) = v.filter(|v| !v.is_undefined() && !v.is_null()) else {
            return Ok(DrawOptions::default());
        };
        if !v.is_object() {
            return Err(JsError::new("options: expected an object such as { show: 'best', cloud: true }"));
        }
        from_object(v).map_err(|e| {
            JsError::new(&format!(
                "options: {e} (show is 'current', 'best', 'reference' or 'none'; cloud, labels, unitLabels and \
                 legend are booleans; scale is a whole number of pixels per cell; world is world.json text)"
            ))
        })
    }
}

/// Options of `drawSceneGraph`.
#[derive(Debug, Clone, PartialEq, Deserialize, Default)]
#[serde(default, deny_unknown_fields)]
pub struct GraphOptions {
    /// Which world's graph to draw (default: the current one).
    pub show: Show,
    /// Picture width in pixels (default: the canvas's width).
    pub width: Option<u32>,
    /// Picture height in pixels (default: the canvas's height).
    pub height: Option<u32>,
}

impl GraphOptions {
    fn from_js(v: Option<&JsValue>) -> Result<GraphOptions, JsError> {
        let Some(v) = v.filter(|v| !v.is_undefined() && !v.is_null()) else {
            return Ok(GraphOptions::default());
        };
        if !v.is_object() {
            return Err(JsError::new("options: expected an object such as { show: 'best' }"));
        }
        from_object(v).map_err(|e| {
            JsError::new(&format!(
                "options: {e} (show is 'current', 'best', 'reference' or 'none'; width and height are \
                 whole numbers of pixels)"
            ))
        })
    }
}

/// Draws the map with the mapper's current or best world (or the reference, or none) and
/// optionally the posterior cloud on `canvas`, resizing it to the map's size times `scale`.
/// `options`: `{ show?: 'current' | 'best' | 'reference' | 'none', cloud?: boolean,
/// scale?: number, labels?: boolean, world?: string }`, by default the current world, no cloud,
/// scale 1, with labels; `world`, a `world.json` text, is drawn instead of `show`'s. Call it at
/// most once per animation frame.
#[wasm_bindgen(js_name = drawMapper)]
pub fn draw_mapper(
    canvas: &web_sys::HtmlCanvasElement,
    mapper: &mut Mapper,
    #[wasm_bindgen(unchecked_optional_param_type = "MapperDrawOptions")] options: Option<JsValue>,
) -> Result<(), JsError> {
    let options = DrawOptions::from_js(options.as_ref())?;
    let pixmap = mapper.picture(&options)?;
    put_rgba(canvas, pixmap.width(), pixmap.height(), &render::to_rgba(&pixmap))
}

/// The pixels `drawMapper` would put on a canvas.
#[wasm_bindgen(js_name = renderMapperRgba)]
pub fn render_mapper_rgba(
    mapper: &mut Mapper,
    #[wasm_bindgen(unchecked_optional_param_type = "MapperDrawOptions")] options: Option<JsValue>,
) -> Result<Rendered, JsError> {
    let options = DrawOptions::from_js(options.as_ref())?;
    let pixmap = mapper.picture(&options)?;
    Ok(Rendered::new(pixmap.width(), pixmap.height(), render::to_rgba(&pixmap)))
}

/// Draws the scene graph of the mapper's current world (or `show: 'best'` / `'reference'`) on
/// `canvas`: units as discs in their type's colour at their place on the map, doors as solid
/// edges, shared walls as dashed ones. The picture is `width` x `height` pixels (default: the
/// canvas's current size), and the canvas is resized to it.
#[wasm_bindgen(js_name = drawSceneGraph)]
pub fn draw_scene_graph(
    canvas: &web_sys::HtmlCanvasElement,
    mapper: &mut Mapper,
    #[wasm_bindgen(
        unchecked_optional_param_type = "{ show?: 'current' | 'best' | 'reference' | 'none'; width?: number; height?: number }"
    )]
    options: Option<JsValue>,
) -> Result<(), JsError> {
    let options = GraphOptions::from_js(options.as_ref())?;
    let width = options.width.unwrap_or(canvas.width());
    let height = options.height.unwrap_or(canvas.height());
    let pixmap = mapper.graph_picture(options.show, width, height)?;
    put_rgba(canvas, pixmap.width(), pixmap.height(), &render::to_rgba(&pixmap))
}

/// The pixels `drawSceneGraph` would draw, `width` x `height`.
#[wasm_bindgen(js_name = renderSceneGraphRgba)]
pub fn render_scene_graph_rgba(
    mapper: &mut Mapper,
    width: u32,
    height: u32,
    #[wasm_bindgen(unchecked_optional_param_type = "'current' | 'best' | 'reference' | 'none'")] show: Option<String>,
) -> Result<Rendered, JsError> {
    let show = match show.as_deref() {
        None | Some("current") => Show::Current,
        Some("best") => Show::Best,
        Some("reference") => Show::Reference,
        Some("none") => Show::None,
        Some(other) => {
            return Err(JsError::new(&format!("show: {other:?} is not 'current', 'best', 'reference' or 'none'")))
        }
    };
    let pixmap = mapper.graph_picture(show, width, height)?;
    Ok(Rendered::new(pixmap.width(), pixmap.height(), render::to_rgba(&pixmap)))
}

/// The chain's default settings as pretty JSON text: the fields a `configJson` may give.
#[wasm_bindgen(js_name = chainConfigDefaults)]
pub fn chain_config_defaults() -> String {
    serde_json::to_string_pretty(&ChainConfig::default()).unwrap_or_default()
}

/// The settings of a chain that follows a robot's growing map, as pretty JSON text
/// ([`ChainConfig::online`]: the defaults with the range-sensor table); a `configJson` for
/// `new Mapper` on the robot's first map, as the Exploration page and `ksmcmc explore` use.
#[wasm_bindgen(js_name = chainConfigOnline)]
pub fn chain_config_online() -> String {
    serde_json::to_string_pretty(&ChainConfig::online()).unwrap_or_default()
}

/// Parses a chain configuration: a JSON object whose fields override the defaults (see
/// [`ChainConfig::from_json`]).
pub fn chain_config(json: Option<&str>) -> Result<ChainConfig, JsError> {
    ChainConfig::from_json(json.unwrap_or("")).map_err(|e| JsError::new(&e.to_string()))
}

/// A plain JavaScript object with the given properties.
fn object(fields: &[(&str, JsValue)]) -> Result<JsValue, JsError> {
    let o = js_sys::Object::new();
    for (k, v) in fields {
        js_sys::Reflect::set(&o, &JsValue::from_str(k), v)
            .map_err(|e| JsError::new(&format!("cannot build the result: {}", js_message(&e))))?;
    }
    Ok(o.into())
}

/// The hand-off to the plan module, apart from the rest (see the module docs).
#[wasm_bindgen]
impl Mapper {
    /// What the plan module's `Plan` needs of the chain now, as JSON text (a [`PlanInput`]):
    /// the typed best world without rooms, the edits in force, whether knowledge supervision
    /// is on, the units' type marginals and the chain's counts and times for `report.json`.
    /// `new Plan(map.toPgm(), map.toYaml('map.pgm'), mapper.planInput())` then gives the best
    /// world's rooms and exports, byte for byte what `ksmcmc floorplan` writes after as many
    /// iterations.
    #[wasm_bindgen(js_name = planInput)]
    pub fn plan_input(&mut self) -> String {
        let input = PlanInput::of(&mut self.chain, self.busy_ms / 1000.0);
        PlanInput { setup_seconds: Some(self.setup_ms / 1000.0), ..input }.to_json()
    }
}
