//! The Hough transform for straight lines (Duda & Hart), the detector behind wall lines,
//! split lines and the map's dominant orientation.
//!
//! Each occupied cell `(x, y)` votes for every line `x cos θ + y sin θ = ρ` through it; walls
//! show up as peaks. Angles are sampled uniformly over `[0, π)`; `ρ` in one-cell bins.

use crate::grid::{Cell, Grid};

/// A Hough accumulator.
#[derive(Debug, Clone)]
pub struct Hough {
    /// Number of angle bins over `[0, π)`.
    pub n_theta: usize,
    /// Number of distance bins.
    pub n_rho: usize,
    /// Offset added to `ρ` to make bins non-negative.
    pub rho_offset: f64,
    /// Votes, `[theta][rho]`.
    pub votes: Vec<u32>,
}

/// `libm::round(v) as usize` for `v >= 0` (a rho offset by the diagonal is never negative),
/// exactly, without the library call in the innermost loop of [`Hough::occupied`]: the
/// fraction `v - trunc(v)` is exact below 2^52, and a half rounds up, as `round` does.
fn round_positive(v: f64) -> usize {
    let t = v as usize;
    t + usize::from(v - t as f64 >= 0.5)
}

impl Hough {
    /// Accumulates votes from the occupied cells of `grid` (at most `max_points` of them, taken
    /// at a regular stride so large maps stay fast).
    pub fn occupied(grid: &Grid<Cell>, n_theta: usize, max_points: usize) -> Hough {
        let (w, h) = (grid.width() as f64, grid.height() as f64);
        let diag = libm::ceil(libm::sqrt(w * w + h * h));
        let n_rho = 2 * diag as usize + 1;
        let mut votes = vec![0u32; n_theta * n_rho];
        let trig: Vec<(f64, f64)> = (0..n_theta)
            .map(|t| {
                let th = std::f64::consts::PI * t as f64 / n_theta as f64;
                (libm::cos(th), libm::sin(th))
            })
            .collect();
        let total = grid.cells().iter().filter(|&&c| c == Cell::Occupied).count();
        let stride = total.div_ceil(max_points.max(1)).max(1);
        let mut points = Vec::with_capacity(total / stride + 1);
        let mut k = 0usize;
        for y in 0..grid.height() {
            for x in 0..grid.width() {
                if *grid.at(x, y) != Cell::Occupied {
                    continue;
                }
                k += 1;
                if k % stride == 0 {
                    points.push((x as f64 + 0.5, y as f64 + 0.5));
                }
            }
        }
        // Angle by angle, so that one angle's row of votes stays in the cache while every
        // point votes in it (point by point, each vote landed in another row: 9 % of a
        // Cartesium run went to the cache misses).
        for (row, &(c, s)) in votes.chunks_exact_mut(n_rho).zip(&trig) {
            for &(fx, fy) in &points {
                row[round_positive(fx * c + fy * s + diag)] += 1;
            }
        }
        Hough { n_theta, n_rho, rho_offset: diag, votes }
    }

    /// The angle of bin `t`, radians.
    pub fn theta(&self, t: usize) -> f64 {
        std::f64::consts::PI * t as f64 / self.n_theta as f64
    }

    /// How peaked the votes at angle bin `t` are: the sum of squared votes. Many cells on few
    /// lines (walls at this angle) score high; scattered cells score low.
    pub fn peakiness(&self, t: usize) -> f64 {
        self.votes[t * self.n_rho..(t + 1) * self.n_rho].iter().map(|&v| (v as f64) * (v as f64)).sum()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn round_positive_is_libm_round() {
        let mut values =
            vec![0.0, 0.5, 1.5, 2.5, 0.49999999999999994, 1.4999999999999998, 2.5000000000000004, 1e6 + 0.5];
        // Values a Hough rho takes: cell centres on a 1237 x 672 map at many angles.
        for i in 0..20_000u32 {
            let th = std::f64::consts::PI * f64::from(i % 720) / 720.0;
            let (fx, fy) = (f64::from(i % 1237) + 0.5, f64::from(i * 7 % 672) + 0.5);
            values.push(fx * libm::cos(th) + fy * libm::sin(th) + 1408.0);
        }
        for v in values {
            assert_eq!(round_positive(v), libm::round(v) as usize, "{v:e}");
        }
    }
}
