//! The posterior `p(W|M) ∝ p(M|W) p(W)` (eq. 3.2) in log space.
//!
//! * Likelihood (eq. 3.6): a product over cells of the sensor table `p(C_M | C_W)` (Tab. 3.1).
//! * Prior (eq. 3.3): `α1 · α2`. `α2 = ψ2^Σ(σ(c)-1)` penalises cells covered by more than one
//!   unit (eq. 3.5), except cells that are wall for every unit covering them: neighbouring
//!   rooms share their walls, and a shared wall is not an overlap (an extension of the
//!   dissertation's model, which left the question open). `α1 = ψ1^θ` penalises corners that are not right angles (eq. 3.4); units
//!   here are exact axis-aligned rectangles in the world frame, so every corner is a right
//!   angle, `θ = 0` and `α1 = 1` structurally — there is nothing for it to penalise.
//!
//! * A complexity prior `exp(-λ n)` on the number of units `n` (an extension): without it,
//!   thin units lying along thick, jagged walls buy a few matched cells each, and the world
//!   fills with slivers no person would draw.
//!
//! A temperature `T` flattens the posterior to `p^(1/T)`; `T = 1` is the papers' model.

use super::explain::Explanation;
use serde::{Deserialize, Serialize};

/// The sensor look-up table `p(C_M | C_W)` of Tab. 3.1.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct SensorModel {
    /// `table[C_W][C_M]` with classes indexed free 0, unknown 1, occupied/wall 2 (eq. 3.7/3.8).
    pub table: [[f64; 3]; 3],
}

impl Default for SensorModel {
    /// Tab. 3.1: 0.8 when the world predicts the map's class, 0.1 otherwise.
    fn default() -> Self {
        SensorModel { table: [[0.8, 0.1, 0.1], [0.1, 0.8, 0.1], [0.1, 0.1, 0.8]] }
    }
}

impl SensorModel {
    /// `log p(C_M = m | C_W = w)` as `[m][w]`, the layout of [`Explanation::confusion`].
    pub fn log_table(&self) -> [[f64; 3]; 3] {
        let mut l = [[0.0; 3]; 3];
        for (w, row) in self.table.iter().enumerate() {
            for (m, p) in row.iter().enumerate() {
                l[m][w] = libm::log(*p);
            }
        }
        l
    }

    /// Every entry must be a probability above zero.
    pub fn validate(&self) -> Result<(), String> {
        for row in &self.table {
            for p in row {
                if !(p.is_finite() && *p > 0.0 && *p <= 1.0) {
                    return Err(format!("sensor table entry {p} is not a probability in (0, 1]"));
                }
            }
        }
        Ok(())
    }
}

/// The numbers that define the posterior.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct PosteriorConfig {
    /// Sensor table (Tab. 3.1).
    pub sensor: SensorModel,
    /// `ψ2` of eq. 3.5: the factor per extra unit covering a cell, in (0, 1].
    pub overlap_penalty: f64,
    /// Temperature `T`: the chain samples `p(W|M)^(1/T)`.
    pub temperature: f64,
    /// `λ`: log prior cost of each unit (nats). 0 is the dissertation's prior.
    pub unit_cost: f64,
}

impl Default for PosteriorConfig {
    fn default() -> Self {
        PosteriorConfig { sensor: SensorModel::default(), overlap_penalty: 0.2, temperature: 1.0, unit_cost: 30.0 }
    }
}

impl PosteriorConfig {
    /// Checks every number.
    pub fn validate(&self) -> Result<(), String> {
        self.sensor.validate()?;
        if !(self.overlap_penalty.is_finite() && self.overlap_penalty > 0.0 && self.overlap_penalty <= 1.0) {
            return Err(format!("overlap_penalty {} is not in (0, 1]", self.overlap_penalty));
        }
        if !(self.unit_cost.is_finite() && self.unit_cost >= 0.0) {
            return Err(format!("unit_cost {} must be a non-negative number", self.unit_cost));
        }
        if !(self.temperature.is_finite() && self.temperature > 0.0) {
            return Err(format!("temperature {} must be a positive number", self.temperature));
        }
        Ok(())
    }
}

/// Evaluates the log posterior from an [`Explanation`]'s integer counts.
#[derive(Debug, Clone, Copy)]
pub struct Posterior {
    log_sensor: [[f64; 3]; 3],
    log_overlap: f64,
    unit_cost: f64,
    inv_temperature: f64,
}

impl Posterior {
    /// Precomputes the logarithms.
    pub fn new(c: &PosteriorConfig) -> Self {
        Posterior {
            log_sensor: c.sensor.log_table(),
            log_overlap: libm::log(c.overlap_penalty),
            unit_cost: c.unit_cost,
            inv_temperature: 1.0 / c.temperature,
        }
    }

    /// `log p(M|W) + log α2 - λ n` for a world of `units` units (untempered), up to a constant.
    pub fn log_posterior(&self, e: &Explanation, units: usize) -> f64 {
        let n = e.confusion();
        let mut s = 0.0;
        for (counts, logs) in n.iter().zip(&self.log_sensor) {
            for (c, l) in counts.iter().zip(logs) {
                s += *c as f64 * l;
            }
        }
        s + e.overlap() as f64 * self.log_overlap - self.unit_cost * units as f64
    }

    /// The tempered log density the chain targets.
    pub fn log_target(&self, e: &Explanation, units: usize) -> f64 {
        self.log_posterior(e, units) * self.inv_temperature
    }

    /// `1 / T`.
    pub fn inv_temperature(&self) -> f64 {
        self.inv_temperature
    }
}
