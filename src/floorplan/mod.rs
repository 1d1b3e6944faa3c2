//! Semantic floor plans: the world `W = {U, T, R}` and the synthetic generator.
//!
//! A [`World`] is what the chain samples and what every exporter writes; `world.json` is its
//! serialised form (schema in [`world`]).

pub mod chain;
pub mod explain;
pub mod graph;
pub mod kernels;
pub mod knowledge;
pub mod metrics;
pub mod posterior;
pub mod report;
pub mod rooms;
pub mod settled;
pub mod state;
pub mod synth;
pub mod unexplained;
pub mod world;

pub use chain::{Chain, ChainConfig, ChainError, DetectorConfig, OutputConfig};
pub use world::{Door, Frame, Rect, UnexplainedArea, Unit, UnitType, World, WorldError, WORLD_FORMAT};
