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

/// How many threads a detector shares `work` among, natively: the machine's cores, at most
/// four, and at least `per_thread` of the work each (starting a thread costs tens of
/// microseconds); 1 when there is too little to share or one core.
#[cfg(not(target_arch = "wasm32"))]
fn threads_for(work: usize, per_thread: usize) -> usize {
    let cores = std::thread::available_parallelism().map_or(1, |p| p.get().min(4));
    cores.min(work / per_thread.max(1)).max(1)
}
