//! # ksmcmc: knowledge-supervised MCMC
//!
//! ksmcmc explains raw perception with compact semantic models. Its first use case turns an
//! occupancy grid (a SLAM map) into a parametric, probabilistic floor plan: rectangular
//! [`floorplan::Unit`]s typed room / corridor / hall / other, their walls and doors, found by a
//! data-driven Metropolis-Hastings chain whose prior is shaped by rules in Markov logic. Its
//! second use case turns noisy 6D object poses on a table into a scene graph of support and
//! contact. Both follow Ziyuan Liu's dissertation *Knowledge-Supervised MCMC* (2014); equation
//! numbers in these docs refer to it.
//!
//! Data flows one way, and the modules follow that flow: each imports only modules above it
//! (what each imports is on the right), so there are no cycles.
//!
//! ```text
//!   grid                  -
//!   geometry              grid
//!   vision                grid, geometry
//!   mcmc                  -
//!   mln                   mcmc
//!   explore               grid, mcmc
//!   floorplan             grid, geometry, vision, mcmc, mln, explore
//!   tabletop              mcmc, mln
//!   render                grid, floorplan, tabletop
//!   wasm, CLI (src/bin)   any of the above
//! ```
//!
//! A map goes `grid -> vision -> floorplan (chain, world) -> render / world.json`, with `mln`
//! queried as a service for knowledge supervision; table-top poses go
//! `tabletop (chain, scene graph) -> render`.
//!
//! * [`grid`] loads occupancy maps (PGM, PNG, ROS `map.yaml`), classifies cells (eq. 3.7), and
//!   grows regions over them ([`grid::flood`]).
//! * [`geometry`] is plane geometry on the cell grid: rectangles, the world frame, cell counts
//!   by rectangle. `vision` and `floorplan` both build on it, so neither imports the other
//!   backwards.
//! * [`vision`] holds the bottom-up detectors, over grids and counts: Hough orientation, wall
//!   lines and wall-based unit candidates, free-space candidates, doors, possible furniture.
//! * [`mcmc`] is the generic Metropolis-Hastings machinery both use cases share: the random
//!   number generator, weighted draws, the acceptance test, trace points. It knows no kernel.
//! * [`floorplan`] holds the semantic world (units, doors, types), the chain with its kernels
//!   and their schedule (Tab. 3.2), rooms, scene graph, metrics, knowledge supervision and the
//!   synthetic generator.
//! * [`explore`] simulates a robot exploring a known map with a range sensor: the growing
//!   maps the online chain ([`floorplan::online`]) is measured on.
//! * [`mln`] is the Markov logic engine, usable on its own; the chains query it as a service.
//! * [`tabletop`] turns noisy 6D box poses into a support/contact scene graph (chapter 4).
//! * [`render`] draws maps, worlds and scene graphs with tiny-skia, natively and in the browser,
//!   and makes the 3D world as glTF 2.0 binary ([`render::model3d`]).
//! * `wasm` (only on `wasm32`) is a thin wasm-bindgen layer with no logic of its own.
//!
//! ```
//! use ksmcmc::grid::{Cell, OccupancyMap};
//!
//! // A 3x1 plain-text PGM: black (occupied), mid gray (unknown), white (free).
//! let map = OccupancyMap::from_bytes(b"P2 3 1 255\n0 128 255\n").unwrap();
//! assert_eq!(map.classified().row(0), &[Cell::Occupied, Cell::Unknown, Cell::Free]);
//! ```

#![forbid(unsafe_code)]
#![warn(missing_docs)]

pub mod explore;
pub mod floorplan;
pub mod geometry;
pub mod grid;
mod json;
pub mod mcmc;
pub mod mln;
pub mod render;
pub mod setting;
pub mod sort;
pub mod tabletop;
mod threads;
pub mod union_find;
pub mod vision;

#[cfg(target_arch = "wasm32")]
pub mod wasm;
