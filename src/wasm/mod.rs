//! WebAssembly bindings: a thin wasm-bindgen layer over [`crate::grid`], [`crate::render`] and
//! [`crate::floorplan::synth`], compiled only for `wasm32`.
//!
//! Nothing here has logic of its own: every function converts its arguments, calls the library
//! and converts the answer back. Every export returns `Result<_, JsError>`, so bad input becomes
//! a thrown JavaScript `Error` whose message is the library's own (the `Display` of
//! [`crate::grid::MapError`] and friends); malformed input never panics, because a panic
//! kills the whole module.
//!
//! ```js
//! import init, { Map, drawToCanvas, synth } from "./pkg/ksmcmc.js";
//! await init();
//! const map = Map.fromBytes(new Uint8Array(await file.arrayBuffer()));
//! console.log(map.width, map.height, map.counts());
//! drawToCanvas(document.querySelector("canvas"), map);
//! const s = synth(7);               // same seed, same bytes as `ksmcmc synth --seed 7`
//! ```
//!
//! Objects returned as classes (`Map`, `Rendered`, `Synthetic`) live in wasm memory; call
//! `.free()` on them when done, or let the garbage collector's finaliser do it.

mod explore;
pub mod knowledge;
mod mapper;
mod model3d;
mod route;
pub mod tabletop;

pub use explore::Explorer;
pub use mapper::{
    chain_config, chain_config_defaults, draw_mapper, draw_scene_graph, now_ms, render_mapper_rgba,
    render_scene_graph_rgba, DrawOptions, GraphOptions, Mapper, Show, MAX_BUDGET_MS, MAX_MAPPER_CELLS, MAX_STEP,
};
pub use model3d::world_glb;
pub use route::plan_route;

use crate::floorplan::synth::{self, SynthConfig};
use crate::floorplan::World;
use crate::grid::{Cell, Classifier, Grid, Limits, OccupancyMap};
use crate::render::{self, RenderOptions};
use serde::{Deserialize, Serialize};
use wasm_bindgen::prelude::*;
use wasm_bindgen::Clamped;

#[wasm_bindgen(typescript_custom_section)]
const TS_TYPES: &str = r#"
/** Options of `drawMapper`, `renderMapperRgba` and `Mapper.toPng`. */
export interface MapperDrawOptions {
  /** Which world to draw over the map (default 'current'). */
  show?: 'current' | 'best' | 'reference' | 'none';
  /** Overlay the posterior cloud: the last accepted worlds as thin lines (default false). */
  cloud?: boolean;
  /** Output pixels per map cell (default 1). */
  scale?: number;
  /** Each unit's type and id at its centre (default true). */
  labels?: boolean;
}
"#;

/// Installs the panic hook, so that a bug prints its message to the console instead of an
/// opaque `unreachable` trap. Runs by itself when the module is initialised.
#[wasm_bindgen(start)]
pub fn start() {
    console_error_panic_hook::set_once();
}

/// The crate version, e.g. `"0.1.0"`.
#[wasm_bindgen]
pub fn version() -> String {
    env!("CARGO_PKG_VERSION").to_string()
}

/// Bytes of linear memory this module holds (its wasm heap). Memory only grows, so this is the
/// high-water mark of everything allocated so far: the soak test (`make soak`) watches it for
/// leaks.
#[wasm_bindgen(js_name = wasmHeapBytes)]
pub fn wasm_heap_bytes() -> f64 {
    (core::arch::wasm32::memory_size(0) * 65536) as f64
}

/// The number of cells of each class in a map, as `map.counts()` returns it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub struct Counts {
    /// Free cells (code 0).
    pub free: u32,
    /// Unknown cells (code 1).
    pub unknown: u32,
    /// Occupied cells (code 2).
    pub occupied: u32,
}

/// A classified occupancy map.
///
/// Cell codes (eq. 3.7): 0 free, 1 unknown, 2 occupied; cells are row-major from the top-left.
#[wasm_bindgen]
#[derive(Debug, Clone)]
pub struct Map {
    inner: OccupancyMap,
}

impl Map {
    /// Wraps a library map.
    pub fn new(inner: OccupancyMap) -> Map {
        Map { inner }
    }

    /// The library map.
    pub fn inner(&self) -> &OccupancyMap {
        &self.inner
    }
}

#[wasm_bindgen]
impl Map {
    /// Loads a map image: a PGM (P2 or P5, 8 or 16 bits) or a PNG of any colour type, told
    /// apart by their first bytes. Cells are classified with the default intensity rule.
    /// Throws an `Error` that says what is wrong with the data.
    #[wasm_bindgen(js_name = fromBytes)]
    pub fn from_bytes(bytes: &[u8]) -> Result<Map, JsError> {
        Ok(Map::new(OccupancyMap::from_bytes(bytes)?))
    }

    /// Loads a ROS map_server pair: the text of `map.yaml` and the bytes of the image it
    /// names (the caller matches the `image:` name to a file). Cells are classified with the
    /// YAML's own rule and thresholds.
    #[wasm_bindgen(js_name = fromYaml)]
    pub fn from_yaml(
        #[wasm_bindgen(js_name = yamlText)] yaml_text: &str,
        #[wasm_bindgen(js_name = imageBytes)] image_bytes: &[u8],
    ) -> Result<Map, JsError> {
        Ok(Map::new(OccupancyMap::from_yaml_and_image(yaml_text, image_bytes, &Limits::default())?))
    }

    /// A map from cell codes, e.g. one a person painted: `codes` holds `width * height` bytes,
    /// each 0 (free), 1 (unknown) or 2 (occupied), row-major from the top-left.
    #[wasm_bindgen(js_name = fromCells)]
    pub fn from_cells(width: u32, height: u32, codes: &[u8]) -> Result<Map, JsError> {
        let (w, h) = Limits::default().check(width.into(), height.into())?;
        if codes.len() != w * h {
            return Err(JsError::new(&format!(
                "a {w}x{h} map needs {} cell codes, but {} were given",
                w * h,
                codes.len()
            )));
        }
        let mut cells = Vec::with_capacity(codes.len());
        for (i, &code) in codes.iter().enumerate() {
            let cell = Cell::from_code(code).ok_or_else(|| {
                JsError::new(&format!(
                    "cell code {code} at ({}, {}) is not 0 (free), 1 (unknown) or 2 (occupied)",
                    i % w,
                    i / w
                ))
            })?;
            cells.push(cell);
        }
        let grid = Grid::from_vec(w, h, cells).ok_or_else(|| JsError::new("cell count mismatch"))?;
        Ok(Map::new(OccupancyMap::from_classified(grid)))
    }

    /// Width in cells.
    #[wasm_bindgen(getter)]
    pub fn width(&self) -> u32 {
        self.inner.width() as u32
    }

    /// Height in cells.
    #[wasm_bindgen(getter)]
    pub fn height(&self) -> u32 {
        self.inner.height() as u32
    }

    /// How many cells are free, unknown and occupied.
    #[wasm_bindgen(unchecked_return_type = "{ free: number; unknown: number; occupied: number }")]
    pub fn counts(&self) -> Result<JsValue, JsError> {
        Ok(serde_wasm_bindgen::to_value(&self.counts_struct())?)
    }

    /// The cell codes, `width * height` bytes row-major: 0 free, 1 unknown, 2 occupied. A
    /// copy: change it and build a new map with `Map.fromCells`.
    pub fn cells(&self) -> Vec<u8> {
        self.inner.classified().cells().iter().map(|c| c.code()).collect()
    }

    /// The classified map as an 8-bit binary PGM in the ROS convention (occupied 0, unknown
    /// 205, free 254).
    #[wasm_bindgen(js_name = toPgm)]
    pub fn to_pgm(&self) -> Vec<u8> {
        self.inner.to_pgm()
    }

    /// The same image classified by another rule, as a new map: `'auto'` finds the background
    /// grays from the histogram and counts anti-aliased wall edges as occupied (what
    /// `ksmcmc floorplan --classify auto`, its default, does to plain images), `'fixed'` applies
    /// the default intensity thresholds (what `Map.fromBytes` does).
    pub fn reclassify(
        &self,
        #[wasm_bindgen(unchecked_param_type = "'auto' | 'fixed'")] rule: &str,
    ) -> Result<Map, JsError> {
        let classifier = match rule {
            "auto" => Classifier::auto(),
            "fixed" => Classifier::default(),
            other => return Err(JsError::new(&format!("classify: {other:?} is neither 'auto' nor 'fixed'"))),
        };
        let mut inner = self.inner.clone();
        inner.set_classifier(classifier)?;
        Ok(Map::new(inner))
    }

    /// The `map.yaml` text for `toPgm()` saved under the file name `imageName`.
    #[wasm_bindgen(js_name = toYaml)]
    pub fn to_yaml(&self, #[wasm_bindgen(js_name = imageName)] image_name: &str) -> String {
        self.inner.to_yaml(image_name)
    }
}

impl Map {
    /// The class counts as a Rust struct.
    pub fn counts_struct(&self) -> Counts {
        let n = |c| self.inner.count(c) as u32;
        Counts { free: n(Cell::Free), unknown: n(Cell::Unknown), occupied: n(Cell::Occupied) }
    }
}

/// Rendered pixels: `width * height` straight (not premultiplied) RGBA pixels, row-major.
#[wasm_bindgen]
#[derive(Debug, Clone)]
pub struct Rendered {
    width: u32,
    height: u32,
    rgba: Vec<u8>,
}

#[wasm_bindgen]
impl Rendered {
    /// Width in pixels.
    #[wasm_bindgen(getter)]
    pub fn width(&self) -> u32 {
        self.width
    }

    /// Height in pixels.
    #[wasm_bindgen(getter)]
    pub fn height(&self) -> u32 {
        self.height
    }

    /// The pixels, `4 * width * height` bytes, ready for `new ImageData(rgba, width)`. Each
    /// read makes a fresh copy.
    #[wasm_bindgen(getter)]
    pub fn rgba(&self) -> Clamped<Vec<u8>> {
        Clamped(self.rgba.clone())
    }
}

impl Rendered {
    /// Wraps straight RGBA pixels.
    pub fn new(width: u32, height: u32, rgba: Vec<u8>) -> Rendered {
        Rendered { width, height, rgba }
    }

    /// The pixels without a copy.
    pub fn rgba_bytes(&self) -> &[u8] {
        &self.rgba
    }
}

/// Renders a map, with the world of a `world.json` text over it if given, exactly as the
/// native renderer does. `scale` is output pixels per map cell (default 1); `labels` draws
/// each unit's type and id (default true).
#[wasm_bindgen(js_name = renderRgba)]
pub fn render_rgba(
    map: &Map,
    #[wasm_bindgen(js_name = worldJson)] world_json: Option<String>,
    scale: Option<u32>,
    labels: Option<bool>,
) -> Result<Rendered, JsError> {
    let options = options(map, scale, labels)?;
    let world = world_json.as_deref().map(World::from_json).transpose()?;
    let pixmap = render::render(map.inner.classified(), world.as_ref(), &options);
    Ok(Rendered { width: pixmap.width(), height: pixmap.height(), rgba: render::to_rgba(&pixmap) })
}

/// Renders like `renderRgba` and puts the pixels on `canvas` with `ImageData`, resizing the
/// canvas to the rendered size. Scale it for display with CSS (`image-rendering: pixelated`).
#[wasm_bindgen(js_name = drawToCanvas)]
pub fn draw_to_canvas(
    canvas: &web_sys::HtmlCanvasElement,
    map: &Map,
    #[wasm_bindgen(js_name = worldJson)] world_json: Option<String>,
    scale: Option<u32>,
    labels: Option<bool>,
) -> Result<(), JsError> {
    let rendered = render_rgba(map, world_json, scale, labels)?;
    put_rgba(canvas, rendered.width, rendered.height, rendered.rgba_bytes())
}

/// Puts straight RGBA pixels on a canvas with `ImageData`, resizing it to `width` x `height`.
/// The canvas is left as it was if the pixels cannot be put there.
pub fn put_rgba(canvas: &web_sys::HtmlCanvasElement, width: u32, height: u32, rgba: &[u8]) -> Result<(), JsError> {
    let js = |what: &str, e: JsValue| JsError::new(&format!("{what}: {}", js_message(&e)));
    let image = web_sys::ImageData::new_with_u8_clamped_array_and_sh(Clamped(rgba), width, height)
        .map_err(|e| js("cannot make ImageData", e))?;
    let context = canvas
        .get_context("2d")
        .map_err(|e| js("cannot get the canvas's 2d context", e))?
        .ok_or_else(|| JsError::new("the canvas has no 2d context (is it already used for WebGL?)"))?;
    let context: web_sys::CanvasRenderingContext2d =
        context.dyn_into().map_err(|e| js("not a 2d context", e.into()))?;
    if canvas.width() != width || canvas.height() != height {
        canvas.set_width(width);
        canvas.set_height(height);
    }
    context.put_image_data(&image, 0.0, 0.0).map_err(|e| js("cannot put the pixels", e))?;
    Ok(())
}

/// Checks scale and output size ([`render::check_size`]) before anything is allocated.
// `..defaults` keeps this compiling when the renderer grows options.
#[allow(clippy::needless_update)]
fn options(map: &Map, scale: Option<u32>, labels: Option<bool>) -> Result<RenderOptions, JsError> {
    let defaults = RenderOptions::default();
    let scale = scale.unwrap_or(defaults.scale);
    render::check_size(map.inner.width(), map.inner.height(), scale)?;
    Ok(RenderOptions { scale, labels: labels.unwrap_or(defaults.labels), ..defaults })
}

/// The message of a thrown JavaScript value.
/// A number of iterations from JavaScript, for `method` (`"step"`): a whole number from 0 to
/// `max`, or an error that says so.
pub(crate) fn iterations_from_js(method: &str, n: f64, max: f64) -> Result<u64, JsError> {
    if n.is_finite() && n >= 0.0 && n.fract() == 0.0 && n <= max {
        Ok(n as u64)
    } else {
        Err(JsError::new(&format!("{method}: {n} is not a number of iterations; give a whole number from 0 to {max}")))
    }
}

/// A time budget from JavaScript, for `method` (`"runFor"`): milliseconds from 0 to `max`.
pub(crate) fn budget_from_js(method: &str, ms: f64, max: f64) -> Result<f64, JsError> {
    if ms.is_finite() && (0.0..=max).contains(&ms) {
        Ok(ms)
    } else {
        Err(JsError::new(&format!("{method}: {ms} is not a time budget; give milliseconds from 0 to {max}")))
    }
}

fn js_message(e: &JsValue) -> String {
    e.dyn_ref::<js_sys::Error>()
        .map(|e| String::from(e.message()))
        .or_else(|| e.as_string())
        .unwrap_or_else(|| format!("{e:?}"))
}

/// A synthetic floor plan with its ground truth, as `synth()` returns it. The byte and text
/// getters are the files `ksmcmc synth --seed N --out DIR` writes, byte for byte.
#[wasm_bindgen]
#[derive(Debug, Clone)]
pub struct Synthetic {
    inner: synth::Synthetic,
}

#[wasm_bindgen]
impl Synthetic {
    /// The occupancy map (a new `Map` on each read).
    #[wasm_bindgen(getter)]
    pub fn map(&self) -> Map {
        Map::new(self.inner.map.clone())
    }

    /// `map.pgm`: the map as an 8-bit binary PGM.
    #[wasm_bindgen(getter, js_name = mapPgm)]
    pub fn map_pgm(&self) -> Vec<u8> {
        self.inner.map_pgm()
    }

    /// `map.yaml`: the map_server description naming `map.pgm`.
    #[wasm_bindgen(getter, js_name = mapYaml)]
    pub fn map_yaml(&self) -> String {
        self.inner.map_yaml()
    }

    /// `truth.json`: the true world, in `world.json` form.
    #[wasm_bindgen(getter, js_name = truthJson)]
    pub fn truth_json(&self) -> String {
        self.inner.truth_json()
    }

    /// `truth_labels.pgm`: per cell, index + 1 of its truth unit (0 elsewhere), 16-bit PGM.
    #[wasm_bindgen(getter, js_name = labelsPgm)]
    pub fn labels_pgm(&self) -> Vec<u8> {
        self.inner.labels_pgm()
    }
}

impl Synthetic {
    /// The library result.
    pub fn inner(&self) -> &synth::Synthetic {
        &self.inner
    }
}

/// Generates a synthetic floor plan with ground truth; same seed and config, same bytes as
/// the native `ksmcmc synth` on every platform.
///
/// `seed` is a non-negative integer: a `number` up to `Number.MAX_SAFE_INTEGER` (2^53 - 1),
/// or a `bigint` for the whole 64-bit range. `configJson` is a JSON object of generator
/// settings (e.g. `{"width": 200, "height": 150}`); fields it leaves out keep their defaults.
#[wasm_bindgen]
pub fn synth(
    #[wasm_bindgen(unchecked_param_type = "number | bigint")] seed: JsValue,
    #[wasm_bindgen(js_name = configJson)] config_json: Option<String>,
) -> Result<Synthetic, JsError> {
    let seed = seed_from_js(&seed)?;
    let config = synth_config(config_json.as_deref())?;
    // The generator allocates width x height cells: refuse what no map could hold, as the
    // loaders do, instead of aborting on a failed allocation.
    Limits::default().check(config.width.into(), config.height.into())?;
    Ok(Synthetic { inner: synth::generate(&config, seed)? })
}

/// Reads a seed: a safe non-negative integer `number`, or a `bigint` that fits in 64 bits.
pub fn seed_from_js(seed: &JsValue) -> Result<u64, JsError> {
    if let Some(x) = seed.as_f64() {
        return seed_from_f64(x);
    }
    if seed.is_bigint() {
        return u64::try_from(seed.clone())
            .map_err(|_| JsError::new("seed: a bigint seed must lie between 0 and 2^64 - 1"));
    }
    Err(JsError::new(&format!("seed: expected a non-negative integer, got {}", describe(seed))))
}

/// Reads a `number` seed.
pub fn seed_from_f64(x: f64) -> Result<u64, JsError> {
    const MAX_SAFE: f64 = 9_007_199_254_740_991.0; // 2^53 - 1
    if x.is_nan() {
        return Err(JsError::new("seed: NaN is not a seed; give a non-negative integer"));
    }
    if x < 0.0 {
        return Err(JsError::new(&format!("seed: {x} is negative; give a non-negative integer")));
    }
    if x.is_infinite() || x > MAX_SAFE {
        return Err(JsError::new(&format!(
            "seed: {x} is above 2^53 - 1 and cannot be told apart from its neighbours as a \
             number; pass it as a bigint (e.g. {x:.0}n) instead"
        )));
    }
    if x.fract() != 0.0 {
        return Err(JsError::new(&format!("seed: {x} is not a whole number")));
    }
    Ok(x as u64)
}

/// A short description of a JavaScript value for error messages.
fn describe(v: &JsValue) -> String {
    match v.as_string() {
        Some(s) => format!("the string {s:?}"),
        None if v.is_undefined() => "undefined".into(),
        None if v.is_null() => "null".into(),
        None => v.js_typeof().as_string().unwrap_or_default(),
    }
}

/// Parses a generator config: the JSON object's fields over the defaults (see
/// [`SynthConfig::parse_json`]; `generate` validates it).
pub fn synth_config(json: Option<&str>) -> Result<SynthConfig, JsError> {
    Ok(SynthConfig::parse_json(json.unwrap_or(""))?)
}
