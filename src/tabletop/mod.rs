//! Table-top scene analysis (chapter 4): scene graphs from noisy 6D object poses.
//!
//! A robot that is to clear a table needs more than where the objects are: it needs to know
//! that the box on top must go first, that one "object" is a pose estimator's hallucination,
//! and that something it cannot see holds another object up. The dissertation builds such an
//! abstract *scene graph* from uncertain 6D pose estimates with the same knowledge-supervised
//! MCMC as the floor plans: physical common sense written as rules in Markov logic
//! (Tab. 4.1 - 4.3) shapes the prior, a sensor model ties the poses to the image, and a
//! data-driven Metropolis-Hastings chain looks for the scene graph of highest posterior
//! (eqs. 4.1, 4.2).
//!
//! # The pieces, in the order the data flows
//!
//! | module | what | dissertation |
//! | --- | --- | --- |
//! | [`scene`] | `scene.json`: table, camera, objects as oriented boxes with keypoints | 4.5, 4.6 |
//! | [`geometry`] | oriented boxes: stable, contact (vertex / edge / facet), intersect, higher | 4.5.5, Fig. 4.10, 4.11 |
//! | [`evidence`] | the evidence atoms of Tab. 4.1 read off the boxes | 4.5.1, 4.5.5 |
//! | [`knowledge`] | Tab. 4.3 through [`crate::mln`]: the prior and the query probabilities | 4.5.2 - 4.5.4, eq. 4.3 |
//! | [`sensor`] | the likelihood: pinhole projection of keypoints with Gaussian pixel error | eq. 4.4 |
//! | [`chain`] | the data-driven MCMC over poses, the decision rule | 4.9, eqs. 4.5 - 4.7, 4.10.1 |
//! | [`graph`] | the scene graph (petgraph): support arrows, contact edges, flags; JSON | Fig. 4.1, 4.17 - 4.23 |
//! | [`synth`] | synthetic scenes with ground truth | |
//! | [`eval`] | scoring against ground truth, the 25-scene test | 4.10.1 |
//!
//! Drawing lives in [`crate::render::tabletop`].
//!
//! # For a front end
//!
//! [`TabletopChain`] is all a thin binding (such as a WebAssembly one) needs: build it from a
//! [`scene::Scene`] (parsed from JSON with [`scene::Scene::from_json`]), a [`ChainConfig`] and a
//! seed; call [`TabletopChain::step`] for a few iterations per frame; read the current or best
//! poses, and [`TabletopChain::best_analysis`] for query probabilities, decisions and the scene
//! graph ([`Analysis::graph_json`]). Nothing here reads files, the clock or threads, and the
//! same seed gives the same result natively and in WebAssembly (`tests/it/tabletop_pinned.rs`).
//!
//! ```
//! use ksmcmc::tabletop::scene::Scene;
//! use ksmcmc::tabletop::{ChainConfig, Decision, TabletopChain};
//!
//! // Two boxes side by side on a table, a third hovering over nothing: something must be
//! // hidden under it (rule r13).
//! let json = r#"{
//!   "table": { "size": [1.0, 0.6] },
//!   "camera": { "fx": 800, "fy": 800, "cx": 400, "cy": 300, "width": 800, "height": 600,
//!               "pose": { "t": [0, -0.7, 0.6], "q": [-0.92, 0, 0, 0.39] } },
//!   "objects": [
//!     { "id": "a", "size": [0.1, 0.1, 0.1], "pose": { "t": [0, 0, 0.05], "q": [0, 0, 0, 1] } },
//!     { "id": "b", "size": [0.1, 0.1, 0.2], "pose": { "t": [0.1, 0, 0.1], "q": [0, 0, 0, 1] } },
//!     { "id": "c", "size": [0.1, 0.1, 0.05], "pose": { "t": [-0.2, 0, 0.1], "q": [0, 0, 0, 1] } } ] }"#;
//! let scene = Scene::from_json(json)?;
//! let mut chain = TabletopChain::new(scene, ChainConfig::default(), 1)?;
//! chain.step(20);
//! let analysis = chain.best_analysis()?;
//! let hidden: Vec<_> = analysis.objects.iter().map(|o| o.hidden).collect();
//! assert_eq!(hidden, [Decision::False, Decision::False, Decision::True]);
//! let graph = analysis.graph_json();
//! assert_eq!(graph["edges"].as_array().unwrap().len(), 3); // two supports, one contact
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
pub mod chain;
mod decision;
pub mod eval;
pub mod evidence;
pub mod geometry;
pub mod graph;
pub mod knowledge;
pub mod scene;
pub mod sensor;
pub mod summary;
pub mod synth;

pub use chain::{Analysis, ChainConfig, Decision, DecisionRule, ObjectAnalysis, ProposalConfig, TabletopChain};

/// Why an analysis could not run.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub enum TabletopError {
    /// The scene is invalid.
    Scene(scene::SceneError),
    /// The configuration's JSON text does not parse, or is no object.
    Config(String),
    /// A setting of the configuration is out of its range: which, and what it must be.
    Setting(crate::setting::InvalidSetting),
    /// The knowledge base failed.
    Knowledge(crate::mln::MlnError),
}

impl std::fmt::Display for TabletopError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            TabletopError::Scene(e) => write!(f, "{e}"),
            TabletopError::Config(m) => write!(f, "invalid configuration: {m}"),
            TabletopError::Setting(e) => write!(f, "invalid configuration: {e}"),
            TabletopError::Knowledge(e) => write!(f, "knowledge base: {e}"),
        }
    }
}

impl std::error::Error for TabletopError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            TabletopError::Scene(e) => Some(e),
            TabletopError::Setting(e) => Some(e),
            TabletopError::Knowledge(e) => Some(e),
            TabletopError::Config(_) => None,
        }
    }
}
