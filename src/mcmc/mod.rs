//! The generic Metropolis-Hastings machinery shared by both use cases.
//!
//! Nothing here knows about floor plans or table tops: weighted selection of proposal elements
//! (eqs. 3.15 - 3.17), the acceptance test of eq. 3.9 in log space, a deterministic random
//! number generator, and the bookkeeping a browser frame loop wants (trace points, acceptance
//! window, a ring buffer of recent samples). The floor-plan kernels, their schedule (Tab. 3.2)
//! and per-kernel counts live in [`crate::floorplan`]; the table-top moves in
//! [`crate::tabletop`].
//!
//! ```
//! use ksmcmc::mcmc::{accept, Rng};
//! let mut rng = Rng::seed(7);
//! // A move that doubles the target density is always accepted.
//! assert!(accept(2f64.ln(), &mut rng));
//! ```

mod ring;
mod trace;
mod weights;

pub use ring::Ring;
pub use trace::{AcceptanceWindow, TracePoint};
pub use weights::Cumulative;

use rand::{Rng as _, SeedableRng};

/// The chains' random number generator: ChaCha8, seeded from a `u64`.
///
/// ChaCha gives the same stream on every platform, so the same seed gives the same chain
/// natively and in WebAssembly. Callers draw only fixed-width integers and `f64`s from it
/// (never `usize`, whose width differs between the two).
#[derive(Debug, Clone)]
pub struct Rng(rand_chacha::ChaCha8Rng);

impl Rng {
    /// A generator seeded with `seed`.
    pub fn seed(seed: u64) -> Self {
        Rng(rand_chacha::ChaCha8Rng::seed_from_u64(seed))
    }

    /// Uniform in `[0, 1)`.
    #[inline]
    pub fn uniform(&mut self) -> f64 {
        self.0.gen::<f64>()
    }

    /// Uniform integer in `0..n` (`n > 0`).
    #[inline]
    pub fn below(&mut self, n: u32) -> u32 {
        debug_assert!(n > 0);
        self.0.gen_range(0..n)
    }

    /// Uniform integer in `lo..=hi`.
    #[inline]
    pub fn range_i32(&mut self, lo: i32, hi: i32) -> i32 {
        self.0.gen_range(lo..=hi)
    }

    /// An index in `0..n`, drawn through `u32` (as [`Rng::below`]) so that 32-bit wasm and
    /// 64-bit hosts consume the stream alike; `n` must be in `1..=u32::MAX`.
    #[inline]
    pub fn index(&mut self, n: usize) -> usize {
        debug_assert!(n >= 1 && n <= u32::MAX as usize);
        self.below(n as u32) as usize
    }

    /// Uniform integer in `lo..=hi`; `lo`, without drawing, when the range is empty or one
    /// value.
    #[inline]
    pub fn between(&mut self, lo: i32, hi: i32) -> i32 {
        if hi <= lo {
            lo
        } else {
            self.range_i32(lo, hi)
        }
    }

    /// True with probability `p`.
    #[inline]
    pub fn chance(&mut self, p: f64) -> bool {
        self.uniform() < p
    }

    /// A standard normal deviate (Box-Muller with libm, identical on every platform).
    pub fn normal(&mut self) -> f64 {
        let u1 = 1.0 - self.uniform(); // (0, 1]
        let u2 = self.uniform();
        libm::sqrt(-2.0 * libm::log(u1)) * libm::cos(std::f64::consts::TAU * u2)
    }
}

/// The Metropolis-Hastings test of eq. 3.9 in log space: accept with probability
/// `min(1, exp(log_ratio))`, where `log_ratio = log p(W'|M) - log p(W|M) + log Q(W|W') - log Q(W'|W)`.
#[inline]
pub fn accept(log_ratio: f64, rng: &mut Rng) -> bool {
    if log_ratio >= 0.0 {
        return true;
    }
    if log_ratio.is_nan() {
        return false;
    }
    rng.uniform() < libm::exp(log_ratio)
}
