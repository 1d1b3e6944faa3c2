//! Semantic floor plans: the world `W = {U, T, R}`, the chain that finds it (its kernels and
//! their schedule, the posterior, knowledge supervision), what is measured of it, routes
//! through its rooms and doors ([`route`]), and the synthetic generator.
//!
//! A [`World`] is what the chain samples and what every exporter writes; `world.json` is its
//! serialised form (schema in [`world`]). The chain's working state (units and doors over an
//! incremental [`Explanation`], the moves that change it, the proposal distributions) is
//! internal: callers drive a [`Chain`] and read worlds, traces and reports from it.
//! [`export`] turns a finished run into its files, the same for the command line and the
//! browser.

pub mod chain;
pub mod edits;
pub(crate) mod explain;
pub mod export;
pub mod geojson;
pub mod georef;
pub mod graph;
pub(crate) mod kernels;
pub mod knowledge;
pub mod metrics;
pub mod online;

pub mod outline;
pub mod plan_input;
pub mod posterior;
pub mod report;

pub mod rooms;
pub mod route;
#[cfg(not(target_arch = "wasm32"))]
pub mod run;
mod schedule;
pub mod settled;
pub mod shapes;
pub(crate) mod state;
pub mod synth;
pub mod topology;
mod trace;
pub mod unexplained;

pub mod wing_doors;
pub mod wings;
pub mod world;

pub use chain::{Chain, ChainConfig, ChainError, DetectorConfig, OutputConfig};
pub use explain::Explanation;
pub use kernels::KernelConfig;
pub use schedule::{Kernel, KernelWeights, Phase, Schedule};
pub use state::{DoorLimits, DoorSizes};
pub use trace::Trace;
pub use world::{Door, Frame, Rect, Room, UnexplainedArea, Unit, UnitType, World, WorldError, WORLD_FORMAT};
