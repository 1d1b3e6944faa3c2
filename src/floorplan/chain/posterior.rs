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
//!
//! * Evidence per area, not per cell (an extension): every term that counts cells (the
//!   likelihood, the overlap penalty) is weighted by the cell's area over the area of a
//!   [`REFERENCE_CELL_M`] cell, so that a building's posterior does not depend on the
//!   resolution it was mapped at. Eq. 3.6 treats cells as independent readings; a map of 2.5 cm
//!   cells does not hold four times the evidence of the same scan drawn at 5 cm, and without
//!   the weight the per-unit terms (the complexity prior, the rules) would weigh four times
//!   less on it, and four times more on a 10 cm map: rooms split on fine maps and merge on
//!   coarse ones.

use super::explain::Explanation;
use crate::setting::{check, InvalidSetting};
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
    /// Tab. 3.1 with its wall row as a range sensor reads walls: a wall cell reads occupied
    /// (its face) or unknown (behind the face, where no ray reaches), and seldom free:
    /// `p(free | wall)` 0.05 and `p(unknown | wall)` 0.15 instead of 0.1 and 0.1. The other rows
    /// are Tab. 3.1's. The dissertation gives its table as "an example" that "could be learned".
    ///
    /// Why it matters for a robot's own map: an outer wall is seen from inside only, a face and
    /// unknown cells behind it. Under the symmetric table a ring `t` deep on the face and the
    /// unseen cells behind it (`p(unknown | wall)`, free cells inside predicted free) costs per
    /// cell exactly what a ring on the face and the free cells in front of it costs
    /// (`p(free | wall)`, the unseen cells predicted unknown), and the inward ring is shorter
    /// around the corners: the chain eats floor along every outer wall. `ksmcmc explore` uses this table
    /// ([`crate::floorplan::ChainConfig::online`]).
    ///
    /// ```
    /// use ksmcmc::floorplan::posterior::SensorModel;
    ///
    /// let (sym, range) = (SensorModel::default().table, SensorModel::range_sensor().table);
    /// // Rows are the world's class (free, unknown, wall), columns the map's; each sums to 1.
    /// assert!(range.iter().all(|row| (row.iter().sum::<f64>() - 1.0).abs() < 1e-12));
    /// assert_eq!(sym[2][0], sym[2][1]);
    /// assert!(range[2][0] < range[2][1]);
    /// ```
    pub fn range_sensor() -> Self {
        let mut table = SensorModel::default().table;
        table[2] = [0.05, 0.15, 0.8];
        SensorModel { table }
    }

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
    pub fn validate(&self) -> Result<(), InvalidSetting> {
        for p in self.table.iter().flatten() {
            check(p.is_finite() && *p > 0.0 && *p <= 1.0, "table", *p, "a probability in (0, 1]")?;
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
    pub fn validate(&self) -> Result<(), InvalidSetting> {
        self.sensor.validate().map_err(|e| e.within("sensor"))?;
        let (p, cost, t) = (self.overlap_penalty, self.unit_cost, self.temperature);
        check(p.is_finite() && p > 0.0 && p <= 1.0, "overlap_penalty", p, "in (0, 1]")?;
        check(cost.is_finite() && cost >= 0.0, "unit_cost", cost, "a non-negative number")?;
        check(t.is_finite() && t > 0.0, "temperature", t, "a positive number")
    }
}

/// The cell side at which one cell counts as one reading of eq. 3.6, metres: 5 cm, the cell
/// of the maps the dissertation's sensor table (Tab. 3.1) and this crate's priors were set on,
/// and about a laser range finder's range noise, below which neighbouring cells repeat the
/// same reading. See [`cell_weight`].
pub const REFERENCE_CELL_M: f64 = 0.05;

/// How many readings one cell of a map of `resolution` metres is worth: its area over a
/// [`REFERENCE_CELL_M`] cell's. 1 at 5 cm (exactly), 4 at 10 cm, 1/4 at 2.5 cm. A resolution
/// that is not a positive number counts as 5 cm.
///
/// ```
/// use ksmcmc::floorplan::posterior::cell_weight;
/// assert_eq!(cell_weight(0.05), 1.0);
/// assert!((cell_weight(0.1) - 4.0).abs() < 1e-12 && (cell_weight(0.025) - 0.25).abs() < 1e-12);
/// ```
pub fn cell_weight(resolution: f64) -> f64 {
    let k = crate::grid::cell_size_m(resolution) / REFERENCE_CELL_M;
    k * k
}

/// Evaluates the log posterior from an [`Explanation`]'s integer counts.
#[derive(Debug, Clone, Copy)]
pub struct Posterior {
    log_sensor: [[f64; 3]; 3],
    log_overlap: f64,
    unit_cost: f64,
    inv_temperature: f64,
    cell_weight: f64,
}

impl Posterior {
    /// Precomputes the logarithms, for a map of [`REFERENCE_CELL_M`] cells.
    pub fn new(c: &PosteriorConfig) -> Self {
        Posterior::at_resolution(c, REFERENCE_CELL_M)
    }

    /// [`Posterior::new`] for a map of `resolution` metres per cell: each cell's terms weigh
    /// [`cell_weight`]`(resolution)`.
    pub fn at_resolution(c: &PosteriorConfig, resolution: f64) -> Self {
        Posterior {
            log_sensor: c.sensor.log_table(),
            log_overlap: libm::log(c.overlap_penalty),
            unit_cost: c.unit_cost,
            inv_temperature: 1.0 / c.temperature,
            cell_weight: cell_weight(resolution),
        }
    }

    /// `w (log p(M|W) + log α2) - λ n` for a world of `units` units (untempered), up to a
    /// constant, with `w` the [`cell_weight`].
    pub fn log_posterior(&self, e: &Explanation, units: usize) -> f64 {
        let n = e.confusion();
        let mut s = 0.0;
        for (counts, logs) in n.iter().zip(&self.log_sensor) {
            for (c, l) in counts.iter().zip(logs) {
                s += *c as f64 * l;
            }
        }
        (s + e.overlap() as f64 * self.log_overlap) * self.cell_weight - self.unit_cost * units as f64
    }

    /// What one cell's evidence weighs ([`cell_weight`]).
    pub fn cell_weight(&self) -> f64 {
        self.cell_weight
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::Rect;
    use crate::grid::{Cell, Grid};

    /// A room seen from inside: 20 x 20 free cells, its walls' faces occupied one cell deep,
    /// unknown beyond. With rings 3 deep, a unit can lay its ring on the face and the 2-cell
    /// band of unseen cells behind it (outward: 192 cells) or on the face and the 2-cell band
    /// of floor in front of it (inward: 144 cells). Under Tab. 3.1 both bands cost the same
    /// per cell (0.1 against 0.8), so the inward ring wins by its shorter band, and on a long
    /// wall the two tie; under the range-sensor table a ring cell read unknown costs less than
    /// one read free, and the outward ring wins.
    #[test]
    fn the_range_sensor_table_puts_a_ring_behind_the_face_it_saw() {
        let mut map = Grid::new(40, 40, Cell::Unknown);
        for y in 10..32 {
            for x in 10..32 {
                let face = x == 10 || x == 31 || y == 10 || y == 31;
                *map.at_mut(x, y) = if face { Cell::Occupied } else { Cell::Free };
            }
        }
        let (outward, inward) = (Rect::new(8, 8, 26, 26), Rect::new(10, 10, 22, 22));
        let score = |sensor: SensorModel, r: Rect| {
            let p = Posterior::new(&PosteriorConfig { sensor, ..Default::default() });
            p.log_posterior(&Explanation::recompute(&map, &[r], 3, &[]), 1)
        };
        let band = |r: Rect| (r.area() - Rect::new(r.x + 2, r.y + 2, r.w - 4, r.h - 4).area()) as f64;
        let (unseen, floor) = (band(outward), band(Rect::new(11, 11, 20, 20)));
        assert_eq!((unseen, floor), (192.0, 144.0));
        let ln = f64::ln;
        let sym = score(SensorModel::default(), outward) - score(SensorModel::default(), inward);
        let sym_expected = (unseen - floor) * (ln(0.1) - ln(0.8));
        assert!((sym - sym_expected).abs() < 1e-6, "Tab. 3.1: outward - inward = {sym}, expected {sym_expected}");
        let range = score(SensorModel::range_sensor(), outward) - score(SensorModel::range_sensor(), inward);
        let expected = unseen * (ln(0.15) - ln(0.8)) - floor * (ln(0.05) - ln(0.8));
        assert!((range - expected).abs() < 1e-6, "range sensor: outward - inward = {range}, expected {expected}");
        assert!(range > 0.0 && sym < 0.0);
    }
}
