//! Semantic floor plans: the world `W = {U, T, R}`, the chain that finds it, the rooms a
//! person would draw, what is made of them, and the synthetic generator.
//!
//! Data flows one way through the folders, and each imports only those before it:
//!
//! * [`world`]: the world (units, doors, rooms, the frame), `world.json`, a person's edits,
//!   and what is measured of a world (K(W,M), contacts between regions);
//! * [`frontier`]: placeholders, the frontiers between free and unknown space, and what the
//!   rules say lies beyond them;
//! * [`knowledge`]: the Markov logic that types units and shapes the prior (a service to the
//!   chain and the rooms);
//! * [`rooms`]: the room layer, units grouped into rooms and typed;
//! * [`chain`]: the Markov chain (its state over an incremental [`Explanation`], the kernels
//!   and their schedule, the posterior, the trace and the settle rule), and the chain that
//!   follows a growing map ([`online`]); its best world's rooms come from [`rooms`];
//! * [`wings`]: a building whose walls run several ways, a chain per wing;
//! * [`export`]: a finished run and its files (`world.json`, labels, the scene graph, GeoJSON,
//!   SVG, the report), the same for the command line, the browser and Python ([`run`]);
//! * [`route`]: routes through the rooms and doors of a finished run;
//! * [`synth`]: generated floors with their truth.
//!
//! A [`World`] is what the chain samples and what every exporter writes; `world.json` is its
//! serialised form (schema in [`world`]). Callers drive a [`Chain`] and read worlds, traces
//! and reports from it.

pub mod chain;
pub mod export;
pub mod frontier;
pub mod knowledge;
pub mod rooms;
pub mod route;
pub mod synth;
pub mod wings;
pub mod world;

// The modules of the folders that callers name, at the paths they have always had.
pub use chain::{online, posterior, settled};
#[cfg(not(target_arch = "wasm32"))]
pub use export::run;
pub use export::{geojson, georef, graph, outline, plan_input, report, shapes};
pub use wings::wing_doors;
pub use world::{edits, metrics, topology, unexplained};
// The chain's internals, for the rest of the crate.
pub(crate) use chain::{explain, kernels, schedule, state, trace};

pub use chain::{Chain, ChainConfig, ChainError, DetectorConfig, OutputConfig, RunRecord, Stopped};
pub use explain::Explanation;
pub use kernels::KernelConfig;
pub use schedule::{Kernel, KernelWeights, Phase, Schedule};
pub use state::{DoorLimits, DoorSizes};
pub use trace::Trace;
pub use world::{Door, Frame, Rect, Room, UnexplainedArea, Unit, UnitType, World, WorldError, WORLD_FORMAT};
