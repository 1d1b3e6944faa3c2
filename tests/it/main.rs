//! The integration tests, one crate (one link of the library) with a module per area.
//!
//! Tests on real maps need `../shared/datasets` (or `KSMCMC_DATASETS`) and skip without it;
//! see [`common::datasets`].

mod chain;
mod chain_exact;
mod cli_explore;
mod cli_floorplan;
mod cli_render;
mod cli_route;
mod cli_synth;
mod common;
mod edits;
mod exports;
mod frontier;
mod grid;
mod hostile;
mod knowledge;
mod mln;
mod mln_cli;
mod model3d;
mod online;
mod pinned;
mod readme;
mod render;
mod route;
mod synth;
mod tabletop;
mod tabletop_cli;
mod tabletop_input;
mod tabletop_pinned;
mod vision;
mod wings;
mod world;
