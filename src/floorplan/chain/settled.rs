//! When a chain has settled: its best world has stopped getting better.
//!
//! The rule: the chain is *settled* at iteration `i` when, over the last `window` iterations,
//! the best log posterior has improved by less than `relative` of its magnitude. `window`
//! scales with the floor in square metres ([`PER_M2`] iterations per m² of free floor, from
//! [`MIN_WINDOW`] to [`MAX_WINDOW`]): a larger building holds more units for the chain to
//! visit, and the same building reads the same at any resolution.
//!
//! The numbers are the ones `ksmcmc evaluate --only settle` chooses: the fewest iterations
//! among candidate rules whose plans are as good as the 20,000 iterations of `ksmcmc
//! floorplan`'s default (mean precision and recall within 0.005, no map 0.02 worse) on
//! generated floors and the ten benchmark floors. Left out of the choice one floor at a time,
//! the rule chosen on the rest stops the held-out floors at 27,480 iterations on average with
//! precision +0.0004 and recall -0.0017 against 20,000 (BENCHMARKS, "The live mapper: time to
//! a settled plan"). The rule before (a quarter of the free cells, 0.01 %) ran the chain five
//! to twenty times longer for the same plan.
//!
//! The rule looks at the chain only at iterations that are multiples of [`STRIDE`], so however
//! the iterations are chunked (a page's frames, a command's one long run) the same seed gives
//! the same verdict at the same iteration. [`Settled::step`] and [`Settled::run_for`] drive a
//! chain and stop at those checkpoints to look.
//!
//! ```
//! use ksmcmc::floorplan::{settled::Settled, Chain, ChainConfig};
//! use ksmcmc::grid::{Cell, Grid, OccupancyMap};
//!
//! let mut cells = Grid::new(40, 30, Cell::Free);
//! for x in 0..40 { *cells.at_mut(x, 0) = Cell::Occupied; *cells.at_mut(x, 29) = Cell::Occupied; }
//! for y in 0..30 { *cells.at_mut(0, y) = Cell::Occupied; *cells.at_mut(39, y) = Cell::Occupied; }
//! let map = OccupancyMap::from_classified(cells);
//! let mut chain = Chain::new(&map, ChainConfig::default(), 1).unwrap();
//! let mut settled = Settled::for_floor(map.count(Cell::Free), chain.resolution());
//! while settled.settled_at().is_none() && chain.iteration() < 100_000 {
//!     settled.step(&mut chain, 1000);
//! }
//! assert!(settled.settled_at().is_some());
//! ```

use crate::floorplan::Chain;

/// The rule looks at the chain every `STRIDE` iterations (at multiples of it).
pub const STRIDE: u64 = 100;
/// Iterations without a real improvement per square metre of free floor that make a chain
/// settled.
pub const PER_M2: f64 = 5.0;
/// The fewest iterations without a real improvement that make a chain settled.
pub const MIN_WINDOW: u64 = 1_000;
/// The most iterations without a real improvement that a chain needs to be settled.
pub const MAX_WINDOW: u64 = 200_000;
/// An improvement of the best log posterior by less than this share of its magnitude (0.3 %)
/// does not count.
pub const RELATIVE: f64 = 3e-3;

/// Watches a chain's best log posterior for the settled rule (module docs).
#[derive(Clone, Debug)]
pub struct Settled {
    window: u64,
    relative: f64,
    /// The last checkpoint at which the best improved for real, and the best then.
    anchor: Option<(u64, f64)>,
    settled_at: Option<u64>,
}

impl Settled {
    /// The rule with its window scaled to a floor of `free_cells` free cells of `resolution`
    /// metres.
    pub fn for_floor(free_cells: usize, resolution: f64) -> Settled {
        Settled::scaled(free_cells, resolution, PER_M2, MIN_WINDOW, RELATIVE)
    }

    /// A rule of this form with other numbers (`ksmcmc evaluate --only settle` weighs
    /// candidates): `per_m2` iterations of window per m² of free floor, from `min_window` to
    /// [`MAX_WINDOW`], and threshold `relative`.
    pub fn scaled(free_cells: usize, resolution: f64, per_m2: f64, min_window: u64, relative: f64) -> Settled {
        let area_m2 = free_cells as f64 * resolution * resolution;
        let window = ((per_m2 * area_m2).round() as u64).clamp(min_window, MAX_WINDOW);
        Settled::new(window, relative)
    }

    /// The rule with a given window (rounded up to a multiple of [`STRIDE`]) and relative
    /// threshold.
    pub fn new(window: u64, relative: f64) -> Settled {
        Settled { window: window.max(STRIDE).div_ceil(STRIDE) * STRIDE, relative, anchor: None, settled_at: None }
    }

    /// Iterations without a real improvement that make the chain settled.
    pub fn window(&self) -> u64 {
        self.window
    }

    /// The first checkpoint at which the chain was settled, if it has been (it stays settled
    /// until the best improves for real again, which clears it).
    pub fn settled_at(&self) -> Option<u64> {
        self.settled_at
    }

    /// The last checkpoint at which the best log posterior improved for real.
    pub fn improved_at(&self) -> Option<u64> {
        self.anchor.map(|(i, _)| i)
    }

    /// Looks at the chain; call it at multiples of [`STRIDE`] ([`Settled::step`] and
    /// [`Settled::run_for`] do), for example to watch one chain with several rules.
    pub fn look(&mut self, chain: &Chain) {
        let (iteration, best) = (chain.iteration(), chain.best_log_posterior());
        match self.anchor {
            Some((_, was)) if best - was <= self.relative * was.abs().max(1.0) => {}
            _ => {
                self.anchor = Some((iteration, best));
                self.settled_at = None;
            }
        }
        let (since, _) = self.anchor.expect("just set");
        if self.settled_at.is_none() && iteration >= since + self.window {
            self.settled_at = Some(iteration);
        }
    }

    /// Iterations from the chain's iteration to its next checkpoint.
    fn to_checkpoint(chain: &Chain) -> u64 {
        STRIDE - chain.iteration() % STRIDE
    }

    /// Runs `n` iterations of `chain`, looking at every checkpoint on the way.
    pub fn step(&mut self, chain: &mut Chain, n: u64) {
        if self.anchor.is_none() && chain.iteration() % STRIDE == 0 {
            self.look(chain);
        }
        let mut left = n;
        while left > 0 {
            let k = Self::to_checkpoint(chain).min(left);
            chain.step(k);
            left -= k;
            if chain.iteration() % STRIDE == 0 {
                self.look(chain);
            }
        }
    }

    /// Runs iterations of `chain` until `budget_ms` milliseconds have passed by `now`, looking
    /// at every checkpoint; checks the clock every 16 iterations, as [`Chain::run_for`]. Returns
    /// the number of iterations run.
    pub fn run_for(&mut self, chain: &mut Chain, budget_ms: f64, now: &mut dyn FnMut() -> f64) -> u64 {
        let start = now();
        let mut done = 0;
        loop {
            self.step(chain, 16);
            done += 16;
            let elapsed = now() - start;
            if elapsed >= budget_ms || elapsed.is_nan() {
                return done;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::floorplan::ChainConfig;
    use crate::grid::{Cell, Grid, OccupancyMap};

    fn room() -> OccupancyMap {
        let mut cells = Grid::new(60, 40, Cell::Free);
        for x in 0..60 {
            *cells.at_mut(x, 0) = Cell::Occupied;
            *cells.at_mut(x, 39) = Cell::Occupied;
        }
        for y in 0..40 {
            *cells.at_mut(0, y) = Cell::Occupied;
            *cells.at_mut(59, y) = Cell::Occupied;
            if y < 30 {
                *cells.at_mut(30, y) = Cell::Occupied;
            }
        }
        OccupancyMap::from_classified(cells)
    }

    fn chain() -> Chain {
        let mut config = ChainConfig::default();
        config.knowledge.enabled = false;
        Chain::new(&room(), config, 7).unwrap()
    }

    #[test]
    fn the_window_scales_with_the_floor_in_square_metres() {
        assert_eq!(Settled::for_floor(100, 0.05).window(), MIN_WINDOW);
        // 1,000 m² at 0.05 m: 400,000 cells.
        assert_eq!(Settled::for_floor(400_000, 0.05).window(), 5_000);
        assert_eq!(Settled::for_floor(404_040, 0.05).window(), 5_100, "a multiple of the stride");
        // The same floor at 0.025 and 0.10 m.
        assert_eq!(Settled::for_floor(1_600_000, 0.025).window(), 5_000);
        assert_eq!(Settled::for_floor(100_000, 0.10).window(), 5_000);
        assert_eq!(Settled::for_floor(usize::MAX / 2, 0.05).window(), MAX_WINDOW);
    }

    #[test]
    fn a_small_map_settles_and_the_verdict_does_not_depend_on_the_chunks() {
        let run = |chunk: u64| {
            let mut c = chain();
            let mut s = Settled::new(2_000, RELATIVE);
            while s.settled_at().is_none() && c.iteration() < 60_000 {
                s.step(&mut c, chunk);
            }
            (s.settled_at(), s.improved_at(), c.best_log_posterior())
        };
        let (at, improved, _) = run(1_000);
        let at = at.expect("a 60x40 room settles within 60,000 iterations");
        let improved = improved.unwrap();
        assert_eq!(at % STRIDE, 0);
        assert!(at >= improved + 2_000 && at < improved + 2_000 + STRIDE, "settled {at}, improved {improved}");
        assert_eq!(run(37).0, Some(at));
        assert_eq!(run(100).0, Some(at));
        // run_for looks at the same checkpoints.
        let mut c = chain();
        let mut s = Settled::new(2_000, RELATIVE);
        let mut ticks = 0.0;
        while s.settled_at().is_none() && c.iteration() < 60_000 {
            s.run_for(&mut c, 5.0, &mut || {
                ticks += 1.0;
                ticks
            });
        }
        assert_eq!(s.settled_at(), Some(at));
    }

    #[test]
    fn an_improving_chain_is_not_settled() {
        let mut c = chain();
        let mut s = Settled::new(2_000, RELATIVE);
        s.step(&mut c, 1_500);
        assert_eq!(s.settled_at(), None, "fewer iterations than the window");
        // A huge threshold: no improvement counts, so it settles exactly one window in.
        let mut c = chain();
        let mut s = Settled::new(2_000, 1e9);
        s.step(&mut c, 2_050);
        assert_eq!(s.improved_at(), Some(0));
        assert_eq!(s.settled_at(), Some(2_000));
    }
}
