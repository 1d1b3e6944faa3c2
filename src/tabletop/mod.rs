//! Table-top scene analysis (chapter 4): scene graphs from noisy 6D object poses.
pub mod chain;
pub mod eval;
pub mod evidence;
pub mod geometry;
pub mod graph;
pub mod knowledge;
pub mod scene;
pub mod sensor;
pub mod synth;

pub use chain::{Analysis, ChainConfig, Decision, DecisionRule, ObjectAnalysis, ProposalConfig, TabletopChain};

/// Why an analysis could not run.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub enum TabletopError {
    /// The scene is invalid.
    Scene(scene::SceneError),
    /// The configuration is invalid.
    Config(String),
    /// The knowledge base failed.
    Knowledge(crate::mln::MlnError),
}

impl std::fmt::Display for TabletopError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            TabletopError::Scene(e) => write!(f, "{e}"),
            TabletopError::Config(m) => write!(f, "invalid configuration: {m}"),
            TabletopError::Knowledge(e) => write!(f, "knowledge base: {e}"),
        }
    }
}

impl std::error::Error for TabletopError {}
