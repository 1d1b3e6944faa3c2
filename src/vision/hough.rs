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
/// The conversions go through `i64`, one instruction each way on x86-64 (through `usize` they
/// are branches around the sign bit); `v` is far below 2^63, so the two agree.
fn round_positive(v: f64) -> usize {
    let t = v as i64;
    (t + i64::from(v - t as f64 >= 0.5)) as usize
}

/// The centres of `grid`'s occupied cells that vote: at most `max_points`, every `stride`-th in
/// row order.
fn voters(grid: &Grid<Cell>, max_points: usize) -> Vec<(f64, f64)> {
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
    points
}

/// Below this many votes the transform runs on one thread: starting threads costs tens of
/// microseconds, a million votes about a millisecond.
#[cfg(not(target_arch = "wasm32"))]
const VOTES_PER_THREAD: usize = 1 << 22;

/// Every point's vote at every angle of `trig`, into `votes` (a row of `n_rho` per angle).
/// Angle by angle, so that one angle's row of votes stays in the cache while every point
/// votes in it (point by point, each vote landed in another row: 9 % of a Cartesium run went
/// to the cache misses).
fn vote(votes: &mut [u32], n_rho: usize, trig: &[(f64, f64)], points: &[(f64, f64)], diag: f64) {
    for (row, &(c, s)) in votes.chunks_exact_mut(n_rho).zip(trig) {
        for &(fx, fy) in points {
            row[round_positive(fx * c + fy * s + diag)] += 1;
        }
    }
}

/// [`vote`], natively on as many threads as the machine has cores (at most four) when there
/// are enough votes to share: each thread takes a band of angles and writes only its rows, so
/// the votes are the same whatever the number of threads. WebAssembly has one thread.
fn vote_all(votes: &mut [u32], n_rho: usize, trig: &[(f64, f64)], points: &[(f64, f64)], diag: f64) {
    #[cfg(not(target_arch = "wasm32"))]
    {
        let threads = crate::threads::threads_for(points.len().saturating_mul(trig.len()), VOTES_PER_THREAD);
        if threads > 1 {
            let band = trig.len().div_ceil(threads);
            std::thread::scope(|s| {
                for (rows, angles) in votes.chunks_mut(band * n_rho).zip(trig.chunks(band)) {
                    s.spawn(move || vote(rows, n_rho, angles, points, diag));
                }
            });
            return;
        }
    }
    vote(votes, n_rho, trig, points, diag);
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
        let points = voters(grid, max_points);
        vote_all(&mut votes, n_rho, &trig, &points, diag);
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

    #[test]
    fn the_votes_are_the_same_on_one_thread_and_on_several() {
        // Scattered cells, enough of them (60,000 points at 720 angles) for several threads.
        let (w, h) = (900usize, 700usize);
        let cells =
            (0..w * h).map(|i| if (i * 2_654_435_761) % 97 < 10 { Cell::Occupied } else { Cell::Free }).collect();
        let grid = Grid::from_vec(w, h, cells).unwrap();
        let hough = Hough::occupied(&grid, 720, 60_000);
        let points: usize = hough.votes[..hough.n_rho].iter().map(|&v| v as usize).sum();
        assert!(points * 720 >= 2 * VOTES_PER_THREAD, "{points} points are too few to share");
        let mut one = vec![0u32; hough.votes.len()];
        let trig: Vec<(f64, f64)> = (0..720).map(|t| (libm::cos(hough.theta(t)), libm::sin(hough.theta(t)))).collect();
        let pts = voters(&grid, 60_000);
        assert_eq!(pts.len(), points, "every point votes once at each angle");
        vote(&mut one, hough.n_rho, &trig, &pts, hough.rho_offset);
        assert_eq!(one, hough.votes);
    }
}
