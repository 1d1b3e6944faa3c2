//! Knowledge-base bindings for the rules editor and the prior-shaping page: thin wrappers over
//! [`crate::mln`] and [`crate::floorplan::knowledge`]. The syntax check is in the mapper module
//! and the rules module; the built-in rules' text, the inference, the log weight and weight
//! learning only in the rules module (`ksmcmc_rules.js`): the mapper module's chain parses the
//! built-in rules without their comments, which keeps it under its 500 kB budget (issue 12).
//!
//! ```js
//! import init, { checkRules, inferWorld, mlnLogWeight, builtinIndoorRules } from "./pkg/ksmcmc_rules.js";
//! await init();
//! checkRules("Room(unit)\n1 Room(x) =>");   // { line: 2, column: 13, message: "..." }
//! const out = JSON.parse(inferWorld(builtinIndoorRules(), plan.worldJson(), 0.05));
//! mlnLogWeight("Left(pt)\n2 Left(x)", "Left(X)"); // 2
//! ```

#[cfg(feature = "wasm-rules")]
use crate::floorplan::{knowledge, knowledge::WorldInference, World};
#[cfg(feature = "wasm-rules")]
use crate::mln::{Database, GroundConfig};
use crate::mln::{Mln, RuleError};
use wasm_bindgen::prelude::*;

#[cfg(feature = "wasm-rules")]
/// The built-in indoor knowledge base (Tab. 3.3 - 3.5) as text, with its comments.
#[wasm_bindgen(js_name = builtinIndoorRules)]
pub fn builtin_indoor_rules() -> String {
    knowledge::BUILTIN_INDOOR.to_string()
}

#[cfg(feature = "wasm-rules")]
/// The hand-set indoor knowledge base (Tab. 3.5 as transcribed), beside the learned default.
#[wasm_bindgen(js_name = handSetIndoorRules)]
pub fn hand_set_indoor_rules() -> String {
    knowledge::HAND_SET_INDOOR.to_string()
}

#[cfg(feature = "wasm-rules")]
/// The built-in frontier rules (`samples/knowledge/frontier-learned.mln`: weights learned on
/// generated floors explored in part) as text: what weighs the placeholders of a plan.
#[wasm_bindgen(js_name = builtinFrontierRules)]
pub fn builtin_frontier_rules() -> String {
    crate::floorplan::frontier::BUILTIN_FRONTIER_RULES.to_string()
}

#[cfg(feature = "wasm-rules")]
/// The frontier rules with hand-set weights (`samples/knowledge/frontier.mln`, where each rule
/// is explained).
#[wasm_bindgen(js_name = handSetFrontierRules)]
pub fn hand_set_frontier_rules() -> String {
    crate::floorplan::frontier::FRONTIER_RULES.to_string()
}

#[cfg(feature = "wasm-rules")]
/// Checks frontier rules as a chain's `knowledge.frontier_kb` is checked: `null` when they
/// parse and declare the queries (`NewRoom` and the `Beyond*` kinds, each of one place), else
/// `{line, column, message}` (line 0 when the fault is no one line's).
#[wasm_bindgen(js_name = checkFrontierRules, unchecked_return_type = "{ line: number; column: number; message: string } | null")]
pub fn check_frontier_rules(text: &str) -> Result<JsValue, JsError> {
    match crate::floorplan::frontier::FrontierRules::parse(text) {
        Ok(_) => Ok(JsValue::NULL),
        Err(e) => Ok(serde_wasm_bindgen::to_value(&RuleError::from(&e))?),
    }
}

#[cfg(feature = "wasm-rules")]
/// Learns the weights of knowledge base `rules` from a labelled world (`world.json` text with
/// typed units, e.g. a sample's `truth.json`) at `resolution` metres per cell, by
/// pseudo-likelihood (`method` "pll", the default: milliseconds) or discriminatively
/// ("discriminative": MC-SAT, seconds; run it in a worker). Returns the knowledge base text
/// with the learned weights; throws with the reason when the world or the rules do not fit.
#[wasm_bindgen(js_name = learnRules)]
pub fn learn_rules(
    rules: &str,
    #[wasm_bindgen(js_name = worldJson)] world_json: &str,
    resolution: f64,
    #[wasm_bindgen(unchecked_optional_param_type = "'pll' | 'discriminative'")] method: Option<String>,
) -> Result<String, JsError> {
    let world = World::from_json(world_json).map_err(|e| JsError::new(&e.to_string()))?;
    let method = method
        .as_deref()
        .unwrap_or("pll")
        .parse()
        .map_err(|e: crate::mln::UnknownMethod| JsError::new(&e.to_string()))?;
    let config = crate::mln::LearnConfig { method, ..Default::default() };
    knowledge::learn_from_worlds(rules, &[world], resolution, &config, "Weights learned in the rules editor")
        .map_err(|e| JsError::new(&e.to_string()))
}

/// Parses a knowledge base: `null` when it is fine, else `{line, column, message}`.
#[wasm_bindgen(js_name = checkRules, unchecked_return_type = "{ line: number; column: number; message: string } | null")]
pub fn check_rules(text: &str) -> Result<JsValue, JsError> {
    match Mln::parse(text) {
        Ok(_) => Ok(JsValue::NULL),
        Err(e) => Ok(serde_wasm_bindgen::to_value(&RuleError::from(&e))?),
    }
}

#[cfg(feature = "wasm-rules")]
/// The evidence `worldJson` (a `world.json` text) gives at `resolution` metres per cell, and
/// what the knowledge base `rulesText` infers from it, as JSON text
/// `{evidence: [{predicate, args, value}], types: {U1: {kind, room, corr, hall, other}},
/// sameLength: [{p, q, probability}]}` (pairs above the default threshold). Throws on a bad
/// knowledge base (message with line and column) or world.
#[wasm_bindgen(js_name = inferWorld)]
pub fn infer_world(
    #[wasm_bindgen(js_name = rulesText)] rules_text: &str,
    #[wasm_bindgen(js_name = worldJson)] world_json: &str,
    resolution: f64,
) -> Result<String, JsError> {
    if !(resolution.is_finite() && resolution > 0.0) {
        return Err(JsError::new(&format!("inferWorld: resolution {resolution} must be a positive number")));
    }
    let world = World::from_json(world_json).map_err(|e| JsError::new(&e.to_string()))?;
    let inference = WorldInference::new(rules_text, &world, resolution).map_err(|e| JsError::new(&e.to_string()))?;
    Ok(inference.to_json())
}

#[cfg(feature = "wasm-rules")]
/// The unnormalised log probability `sum_i w_i n_i(x)` of the complete world `evidenceText`
/// (one ground atom per line; unlisted atoms are false) under the knowledge base `rulesText`.
/// `-Infinity` when a hard formula is violated. Throws on bad text (message with line and
/// column).
#[wasm_bindgen(js_name = mlnLogWeight)]
pub fn mln_log_weight(
    #[wasm_bindgen(js_name = rulesText)] rules_text: &str,
    #[wasm_bindgen(js_name = evidenceText)] evidence_text: &str,
) -> Result<f64, JsError> {
    let mln = Mln::parse(rules_text).map_err(|e| JsError::new(&e.to_string()))?;
    let world = Database::parse(evidence_text, &mln).map_err(|e| JsError::new(&e.to_string()))?;
    mln.log_weight(&world, &GroundConfig::default()).map_err(|e| JsError::new(&e.to_string()))
}
