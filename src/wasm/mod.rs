//! WebAssembly bindings: a thin wasm-bindgen layer over the library, compiled only for
//! `wasm32`.
//!
//! Nothing here has logic of its own: every function converts its arguments, calls the library
//! and converts the answer back. Every export returns `Result<_, JsError>`, so bad input becomes
//! a thrown JavaScript `Error` whose message is the library's own (the `Display` of
//! [`crate::grid::MapError`] and friends); malformed input never panics, because a panic
//! kills the whole module.
//!
//! The API comes as separately loaded modules, one per cargo feature, so that a page downloads
//! only what it uses (`make pkg` builds the crate once per module):
//!
//! * `wasm-mapper`, `ksmcmc.js`: maps ([`map`]), their pictures and the live floor-plan chain
//!   ([`mapper`]), with the built-in rules and their syntax check: what the live mapper needs
//!   for its first frame, and the one module most pages start with.
//! * `wasm-explore`, `ksmcmc_explore.js`: all of `ksmcmc.js` and the simulated robot of the
//!   Exploration page ([`explore`]), which runs beside a `Mapper` and hands it maps (objects of
//!   one module): the robot is 8 kB gzipped that the live mapper's first frame does without.
//! * `wasm-plan`, `ksmcmc_plan.js`: the room layer of a best world and everything made from it
//!   ([`plan`]: `world.json`, labels, room types, GeoJSON, SVG, glTF, routes, the report, PNG
//!   encoding), and routes and models of saved worlds. The live mapper's worker imports it
//!   once the chain has found units.
//! * `wasm-synth`, `ksmcmc_synth.js`: synthetic maps ([`synth`]), for the samples.
//! * `wasm-rules`, `ksmcmc_rules.js`: the knowledge tools ([`knowledge`]: inference, the log
//!   weight, weight learning) of the rules and prior pages.
//! * `wasm-tabletop`, `ksmcmc_tabletop.js`: the table-top analysis ([`tabletop`]).
//!
//! Modules do not share memory: what passes between them is bytes and text (a map's PGM and
//! YAML, `Mapper.planInput()`, a world's JSON), never an object. `start`, `version` and
//! `wasmHeapBytes` are in each.
//!
//! ```js
//! import init, { Map, drawToCanvas } from "./pkg/ksmcmc.js";
//! await init();
//! const map = Map.fromBytes(new Uint8Array(await file.arrayBuffer()));
//! console.log(map.width, map.height, map.counts());
//! drawToCanvas(document.querySelector("canvas"), map);
//! const synth = await import("./pkg/ksmcmc_synth.js");
//! await synth.default();
//! const s = synth.synth(7);         // same seed, same bytes as `ksmcmc synth --seed 7`
//! const made = Map.fromYaml(s.mapYaml, s.mapPgm);
//! ```
//!
//! Objects returned as classes (`Map`, `Rendered`, `Mapper`, `Explorer`, `Plan`, `Synthetic`)
//! live in wasm memory; call `.free()` on them when done, or let the garbage collector's
//! finaliser do it.

#[cfg(feature = "wasm-explore")]
mod explore;
#[cfg(any(feature = "wasm-mapper", feature = "wasm-rules"))]
pub mod knowledge;
#[cfg(feature = "wasm-mapper")]
mod map;
#[cfg(feature = "wasm-mapper")]
mod mapper;
#[cfg(feature = "wasm-plan")]
mod model3d;
#[cfg(feature = "wasm-plan")]
mod plan;
#[cfg(feature = "wasm-plan")]
mod route;
#[cfg(feature = "wasm-synth")]
mod synth;
#[cfg(feature = "wasm-tabletop")]
pub mod tabletop;

#[cfg(feature = "wasm-explore")]
pub use explore::Explorer;
#[cfg(feature = "wasm-mapper")]
pub use map::{draw_to_canvas, legend_json, render_rgba, Counts, Map, Rendered};
#[cfg(feature = "wasm-mapper")]
pub use mapper::{
    chain_config, chain_config_defaults, chain_config_online, draw_mapper, draw_scene_graph, render_mapper_rgba,
    render_scene_graph_rgba, DrawOptions, GraphOptions, Mapper, Show, MAX_BUDGET_MS, MAX_MAPPER_CELLS, MAX_STEP,
};
#[cfg(feature = "wasm-plan")]
pub use model3d::world_glb;
#[cfg(feature = "wasm-plan")]
pub use plan::{encode_png, graph_json, Plan};
#[cfg(feature = "wasm-plan")]
pub use route::plan_route;
#[cfg(feature = "wasm-synth")]
pub use synth::{synth, synth_config, Synthetic};

use wasm_bindgen::prelude::*;
use wasm_bindgen::Clamped;

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

#[cfg(any(feature = "wasm-mapper", feature = "wasm-tabletop"))]
#[wasm_bindgen]
extern "C" {
    /// `performance.now()`: milliseconds, sub-millisecond where the browser allows.
    #[wasm_bindgen(catch, js_namespace = performance, js_name = now)]
    fn performance_now() -> Result<f64, JsValue>;
}

/// The clock `runFor` uses: `performance.now()`, or `Date.now()` where there is no
/// `performance` object.
#[cfg(any(feature = "wasm-mapper", feature = "wasm-tabletop"))]
pub fn now_ms() -> f64 {
    performance_now().unwrap_or_else(|_| js_sys::Date::now())
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

/// A number of iterations from JavaScript, for `method` (`"step"`): a whole number from 0 to
/// `max`, or an error that says so.
#[cfg(any(feature = "wasm-mapper", feature = "wasm-tabletop"))]
pub(crate) fn iterations_from_js(method: &str, n: f64, max: f64) -> Result<u64, JsError> {
    if n.is_finite() && n >= 0.0 && n.fract() == 0.0 && n <= max {
        Ok(n as u64)
    } else {
        Err(JsError::new(&format!("{method}: {n} is not a number of iterations; give a whole number from 0 to {max}")))
    }
}

/// A time budget from JavaScript, for `method` (`"runFor"`): milliseconds from 0 to `max`.
#[cfg(any(feature = "wasm-mapper", feature = "wasm-tabletop"))]
pub(crate) fn budget_from_js(method: &str, ms: f64, max: f64) -> Result<f64, JsError> {
    if ms.is_finite() && (0.0..=max).contains(&ms) {
        Ok(ms)
    } else {
        Err(JsError::new(&format!("{method}: {ms} is not a time budget; give milliseconds from 0 to {max}")))
    }
}

/// The message of a thrown JavaScript value.
fn js_message(e: &JsValue) -> String {
    e.dyn_ref::<js_sys::Error>()
        .map(|e| String::from(e.message()))
        .or_else(|| e.as_string())
        .unwrap_or_else(|| format!("{e:?}"))
}

/// Reads an options object through its JSON text, so that unknown fields are refused
/// (serde-wasm-bindgen looks up only the fields it knows) and NaN, which JSON writes as
/// `null`, is no number.
#[cfg(any(feature = "wasm-mapper", feature = "wasm-plan"))]
pub(crate) fn from_object<T: serde::de::DeserializeOwned>(v: &JsValue) -> Result<T, String> {
    let text = js_sys::JSON::stringify(v).map_err(|e| js_message(&e))?;
    let text = text.as_string().unwrap_or_default();
    serde_json::from_str(&text).map_err(|e| e.to_string())
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
