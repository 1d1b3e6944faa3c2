//! Bottom-up detectors that make the chain data-driven (section 3.5.2): Hough lines, the
//! dominant wall orientation, wall-based and free-space unit candidates, doors, and the cells
//! that may be furniture.
//!
//! They take grids, cell counts and rectangles ([`crate::geometry`]), never the chain's state,
//! so that data flows one way: grid, then vision, then the floor plan.

pub mod doors;
pub mod freespace;
pub mod hough;
pub mod objects;
pub mod orientation;
pub mod regions;
pub mod walls;
