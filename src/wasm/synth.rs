//! Synthetic floor plans in the browser: `synth`, the generator of `ksmcmc synth` with its
//! ground truth, byte for byte. The synth module (`ksmcmc_synth.js`), apart so that a page that
//! makes a sample map does not load the rest: it has no `Map` class, and a page reads the map
//! it makes with the mapper module's, `Map.fromYaml(s.mapYaml, s.mapPgm)`.

use super::seed_from_js;
use crate::floorplan::synth::{self, SynthConfig};
use crate::grid::Limits;
use wasm_bindgen::prelude::*;

/// A synthetic floor plan with its ground truth, as `synth()` returns it. The byte and text
/// getters are the files `ksmcmc synth --seed N --out DIR` writes, byte for byte.
#[wasm_bindgen]
#[derive(Debug, Clone)]
pub struct Synthetic {
    inner: synth::Synthetic,
}

#[wasm_bindgen]
impl Synthetic {
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

/// Parses a generator config: the JSON object's fields over the defaults (see
/// [`SynthConfig::parse_json`]; `generate` validates it).
pub fn synth_config(json: Option<&str>) -> Result<SynthConfig, JsError> {
    Ok(SynthConfig::parse_json(json.unwrap_or(""))?)
}
