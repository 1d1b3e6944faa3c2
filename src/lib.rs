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
//! Data flows one way, and the modules follow that flow:
//!
//! ```text
//! grid  ->  vision (detectors)  ->  mcmc (chain, kernels, posterior)  ->  floorplan (world)  ->  render / export
//!                                      ^
//!                                     mln (Markov logic, queried as a service)
//! ```
//!
//! * [`grid`] loads occupancy maps (PGM, PNG, ROS `map.yaml`) and classifies cells (eq. 3.7).
//! * [`vision`] holds the bottom-up detectors: Hough orientation, wall lines and wall-based unit
//!   candidates, free-space candidates, doors.
//! * [`mcmc`] is the generic Metropolis-Hastings machinery both use cases share.
//! * [`floorplan`] holds the semantic world (units, doors, types), the chain and its kernels,
//!   rooms, scene graph, metrics, knowledge supervision and the synthetic generator.
//! * [`mln`] is the Markov logic engine, usable on its own.
//! * [`tabletop`] turns noisy 6D box poses into a support/contact scene graph (chapter 4).
//! * [`render`] draws maps, worlds and scene graphs with tiny-skia, natively and in the browser.
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

pub mod floorplan;
pub mod geometry;
pub mod grid;
pub mod mcmc;
pub mod mln;
pub mod render;
pub mod tabletop;
pub mod vision;

#[cfg(target_arch = "wasm32")]
pub mod wasm;
