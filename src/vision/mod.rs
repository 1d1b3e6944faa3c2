//! Bottom-up detectors that make the chain data-driven (section 3.5.2): Hough lines, the
//! dominant wall orientation, wall-based and free-space unit candidates, doors.

pub mod doors;
pub mod freespace;
pub mod hidden;
pub mod hough;
pub mod orientation;
pub mod walls;
