//! The table-top analysis' bindings: a running [`TabletopChain`] as the JavaScript class
//! `Tabletop`, the scene generator, and the knowledge base text with its syntax check.
//!
//! As in the rest of this layer there is no logic here beyond converting and checking
//! arguments: the chain, the analysis and the pictures are [`crate::tabletop`]'s and
//! [`crate::render::tabletop`]'s.
//!
//! ```js
//! const tt = new Tabletop(tabletopSynth(5), undefined, 1);
//! function frame() {
//!   tt.runFor(8);
//!   tt.drawView(view);
//!   tt.drawGraph(graph);
//!   requestAnimationFrame(frame);
//! }
//! ```

use super::now_ms;
use super::{put_rgba, seed_from_js};
use crate::mln::RuleError;
use crate::render;
use crate::render::tabletop::{draw_graph, draw_view, marks, ViewOptions};
use crate::tabletop::knowledge::{Knowledge, TABLETOP_MLN};
use crate::tabletop::scene::Scene;
use crate::tabletop::summary::AnalysisSummary;
use crate::tabletop::synth::{self, SynthConfig};
use crate::tabletop::{Analysis, ChainConfig, TabletopChain};
use wasm_bindgen::prelude::*;

/// The most iterations one `step` call may run.
const MAX_TT_STEP: f64 = 1_000_000.0;

/// The longest time budget of one `runFor` call, in milliseconds.
const MAX_TT_BUDGET_MS: f64 = 60_000.0;

fn err(e: impl std::fmt::Display) -> JsError {
    JsError::new(&e.to_string())
}

fn seed_or(seed: Option<JsValue>, default: u64) -> Result<u64, JsError> {
    match seed {
        Some(s) if !s.is_undefined() && !s.is_null() => seed_from_js(&s),
        _ => Ok(default),
    }
}

fn chain_config(json: Option<&str>) -> Result<ChainConfig, JsError> {
    ChainConfig::from_json(json.unwrap_or("")).map_err(err)
}

/// A table-top chain over one scene, for a page's frame loop.
#[wasm_bindgen]
pub struct Tabletop {
    chain: TabletopChain,
    scene: Scene,
    config: ChainConfig,
    seed: u64,
    rules: String,
    /// The best analysis, keyed by (best iteration, best log posterior).
    best: Option<((u64, u64), Analysis)>,
}

impl Tabletop {
    fn build(scene: &Scene, config: ChainConfig, seed: u64, rules: &str) -> Result<TabletopChain, JsError> {
        let knowledge =
            Knowledge::with_text(rules, scene.objects.len()).map_err(|e| JsError::new(&format!("rules: {e}")))?;
        TabletopChain::with_knowledge(scene.clone(), config, seed, knowledge).map_err(err)
    }

    fn best(&mut self) -> Result<&Analysis, JsError> {
        let key = (self.chain.best_iteration(), self.chain.best_log_posterior().to_bits());
        if self.best.as_ref().is_none_or(|(k, _)| *k != key) {
            self.best = Some((key, self.chain.best_analysis().map_err(err)?));
        }
        Ok(&self.best.as_ref().expect("just filled").1)
    }
}

#[wasm_bindgen]
impl Tabletop {
    /// Starts a chain on a scene (`scene.json` text). `configJson` gives any subset of the
    /// chain's settings, `seed` is a whole number ≥ 0 (default 1), `rulesText` a knowledge
    /// base in place of the built-in one. Throws with the library's message on bad input.
    #[wasm_bindgen(constructor)]
    pub fn new(
        #[wasm_bindgen(js_name = sceneJson)] scene_json: &str,
        #[wasm_bindgen(js_name = configJson, unchecked_optional_param_type = "string")] config_json: Option<String>,
        #[wasm_bindgen(unchecked_optional_param_type = "number | bigint")] seed: Option<JsValue>,
        #[wasm_bindgen(js_name = rulesText, unchecked_optional_param_type = "string")] rules_text: Option<String>,
    ) -> Result<Tabletop, JsError> {
        let scene = Scene::from_json(scene_json).map_err(err)?;
        let config = chain_config(config_json.as_deref())?;
        let seed = seed_or(seed, 1)?;
        let rules = rules_text.unwrap_or_else(|| TABLETOP_MLN.to_string());
        let chain = Self::build(&scene, config, seed, &rules)?;
        Ok(Tabletop { chain, scene, config, seed, rules, best: None })
    }

    /// Runs `n` iterations (a whole number, 0 to 10^6). Returns `n`.
    pub fn step(&mut self, n: f64) -> Result<f64, JsError> {
        let steps = super::iterations_from_js("step", n, MAX_TT_STEP)?;
        self.chain.step(steps as u32);
        Ok(n)
    }

    /// Runs single iterations until `budgetMs` milliseconds have passed (at least one).
    /// Returns how many ran.
    #[wasm_bindgen(js_name = runFor)]
    pub fn run_for(&mut self, #[wasm_bindgen(js_name = budgetMs)] budget_ms: f64) -> Result<f64, JsError> {
        let budget_ms = super::budget_from_js("runFor", budget_ms, MAX_TT_BUDGET_MS)?;
        let t0 = now_ms();
        let mut done = 0u32;
        loop {
            self.chain.step(1);
            done += 1;
            if now_ms() - t0 >= budget_ms {
                return Ok(done as f64);
            }
        }
    }

    /// Replaces the knowledge base and starts the chain over (same scene, config and seed).
    /// On an error the old rules and chain stay.
    #[wasm_bindgen(js_name = setRules)]
    pub fn set_rules(&mut self, text: &str) -> Result<(), JsError> {
        let chain = Self::build(&self.scene, self.config, self.seed, text)?;
        self.chain = chain;
        self.rules = text.to_string();
        self.best = None;
        Ok(())
    }

    /// The knowledge base text in use.
    #[wasm_bindgen(getter)]
    pub fn rules(&self) -> String {
        self.rules.clone()
    }

    /// Iterations run.
    #[wasm_bindgen(getter)]
    pub fn iteration(&self) -> f64 {
        self.chain.iteration() as f64
    }

    /// Objects in the scene.
    #[wasm_bindgen(getter)]
    pub fn objects(&self) -> u32 {
        self.scene.objects.len() as u32
    }

    /// The current log posterior.
    #[wasm_bindgen(getter, js_name = logPosterior)]
    pub fn log_posterior(&self) -> f64 {
        self.chain.log_posterior()
    }

    /// The best log posterior seen.
    #[wasm_bindgen(getter, js_name = bestLogPosterior)]
    pub fn best_log_posterior(&self) -> f64 {
        self.chain.best_log_posterior()
    }

    /// The best analysis as JSON text: `{ iteration, logPosterior, logPrior, logLikelihood,
    /// objects: [{ id, stable, hover, p_hidden, p_false, supported, supportive, hidden, false,
    /// truth }], graph }`, decisions `"true"`, `"false"` or `"undecided"`, `truth` the scene's
    /// ground truth `{ hidden, false }` or null.
    #[wasm_bindgen(js_name = analysisJson)]
    pub fn analysis_json(&mut self) -> Result<String, JsError> {
        let (iteration, best_lp) = (self.chain.iteration(), self.chain.best_log_posterior());
        self.best()?;
        let a = &self.best.as_ref().expect("just filled").1;
        Ok(serde_json::to_string(&AnalysisSummary::new(&self.scene, a, iteration, best_lp))?)
    }

    /// Draws the best analysis' scene graph on `canvas` (resized to the picture).
    #[wasm_bindgen(js_name = drawGraph)]
    pub fn draw_graph(&mut self, canvas: &web_sys::HtmlCanvasElement) -> Result<(), JsError> {
        let pixmap = draw_graph(&self.best()?.graph);
        put_rgba(canvas, pixmap.width(), pixmap.height(), &render::to_rgba(&pixmap))
    }

    /// Draws the camera view of the best poses, flagged objects marked, on `canvas` (resized
    /// to the picture, at most `maxWidth` pixels wide, default 1024).
    #[wasm_bindgen(js_name = drawView)]
    pub fn draw_view(
        &mut self,
        canvas: &web_sys::HtmlCanvasElement,
        #[wasm_bindgen(js_name = maxWidth, unchecked_optional_param_type = "number")] max_width: Option<u32>,
    ) -> Result<(), JsError> {
        let options = ViewOptions { max_width: max_width.unwrap_or(1024).clamp(16, 4096), ..ViewOptions::default() };
        let a = self.best()?;
        let poses: Vec<_> = a.objects.iter().map(|o| o.pose).collect();
        let m = marks(a);
        let pixmap = draw_view(&self.scene, &poses, &m, &options);
        put_rgba(canvas, pixmap.width(), pixmap.height(), &render::to_rgba(&pixmap))
    }
}

/// A synthetic scene with ground truth as `scene.json` text: the same scene as the library's
/// generator for `seed` (default 1). `configJson` gives any subset of the generator's settings.
#[wasm_bindgen(js_name = tabletopSynth)]
pub fn tabletop_synth(
    #[wasm_bindgen(unchecked_optional_param_type = "number | bigint")] seed: Option<JsValue>,
    #[wasm_bindgen(js_name = configJson, unchecked_optional_param_type = "string")] config_json: Option<String>,
) -> Result<String, JsError> {
    let seed = seed_or(seed, 1)?;
    let config = SynthConfig::from_json(config_json.as_deref().unwrap_or("")).map_err(err)?;
    Ok(synth::generate(&config, seed).map_err(err)?.to_json())
}

/// The built-in table-top knowledge base (`tabletop.mln`).
#[wasm_bindgen(js_name = tabletopRulesDefault)]
pub fn tabletop_rules_default() -> String {
    TABLETOP_MLN.to_string()
}

/// Checks a knowledge base: `null` if it is usable for the table-top analysis, otherwise
/// `{ line, column, message }` (line and column 0 when the error has no place in the text).
/// Unlike `checkRules`, which only parses, this also checks the table-top predicates.
#[wasm_bindgen(js_name = tabletopCheckRules)]
pub fn check_rules(text: &str) -> Result<JsValue, JsError> {
    match Knowledge::with_text(text, 1) {
        Ok(_) => Ok(JsValue::NULL),
        Err(e) => Ok(serde_wasm_bindgen::to_value(&RuleError::from(&e))?),
    }
}
