//! Random draws that give the same numbers on every target.
//!
//! `rand` samples a `usize` range through `usize` itself, so `gen_range(0..v.len())` consumes
//! the stream differently on 32-bit wasm and 64-bit hosts. Every draw here goes through `u32`,
//! `i32` or `f64`, whose sampling is the same everywhere.

use rand::Rng;
use rand_chacha::ChaCha8Rng;

/// The generator's random stream.
pub(super) type Stream = ChaCha8Rng;

/// An index in `0..n`; `n` must be at least 1.
pub(super) fn below(rng: &mut Stream, n: usize) -> usize {
    debug_assert!(n >= 1 && n <= u32::MAX as usize);
    rng.gen_range(0..n as u32) as usize
}

/// An integer in `lo..=hi`; `lo` when the range is empty.
pub(super) fn between(rng: &mut Stream, lo: i32, hi: i32) -> i32 {
    if hi <= lo {
        lo
    } else {
        rng.gen_range(lo..=hi)
    }
}

/// A number in `[0, 1)`.
pub(super) fn unit(rng: &mut Stream) -> f64 {
    rng.gen::<f64>()
}

/// True with probability `p`.
pub(super) fn chance(rng: &mut Stream, p: f64) -> bool {
    unit(rng) < p
}
