//! Synthetic floor plans with ground truth (placeholder: being written).

use super::World;
use crate::grid::{Cell, Grid, OccupancyMap};

/// Parameters of the synthetic generator.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct SynthConfig {
    /// Map width in cells.
    pub width: u32,
    /// Map height in cells.
    pub height: u32,
}

impl Default for SynthConfig {
    fn default() -> Self {
        SynthConfig { width: 400, height: 300 }
    }
}

/// Why a configuration was refused.
#[derive(Debug, Clone, PartialEq)]
pub struct SynthError(pub String);

impl std::fmt::Display for SynthError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for SynthError {}

/// A generated map with its ground truth.
#[derive(Debug, Clone)]
pub struct Synthetic {
    /// The occupancy map a SLAM system would have produced.
    pub map: OccupancyMap,
    /// The true world (units with types, doors), in `world.json` form.
    pub truth: World,
    /// Per map cell: index + 1 of the truth unit it belongs to, 0 elsewhere.
    pub labels: Grid<u16>,
}

impl Synthetic {
    /// `map.pgm` bytes.
    pub fn map_pgm(&self) -> Vec<u8> {
        self.map.to_pgm()
    }
    /// `map.yaml` text naming `map.pgm`.
    pub fn map_yaml(&self) -> String {
        self.map.to_yaml("map.pgm")
    }
    /// `truth.json` text.
    pub fn truth_json(&self) -> String {
        self.truth.to_json()
    }
    /// `truth_labels.pgm` bytes: 16-bit binary PGM.
    pub fn labels_pgm(&self) -> Vec<u8> {
        crate::grid::pgm::encode_u16(self.labels.width(), self.labels.height(), self.labels.cells())
    }
}

/// Generates a synthetic floor plan; same config and seed, same result on every platform.
pub fn generate(config: &SynthConfig, seed: u64) -> Result<Synthetic, SynthError> {
    let _ = seed;
    let (w, h) = (config.width as usize, config.height as usize);
    let map = OccupancyMap::from_classified(Grid::new(w, h, Cell::Unknown));
    Ok(Synthetic { map, truth: World::empty(config.width, config.height), labels: Grid::new(w, h, 0) })
}
