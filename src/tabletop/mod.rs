//! Table-top scene analysis (chapter 4): scene graphs from noisy 6D object poses.
pub mod evidence;
pub mod geometry;
pub mod knowledge;
pub mod scene;
pub mod sensor;
