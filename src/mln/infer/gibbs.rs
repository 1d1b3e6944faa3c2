//! Gibbs sampling that honours hard formulas.
//!
//! The chain starts from a world satisfying every hard feature (found by WalkSAT) and never
//! leaves that set: a move into a world violating a hard feature has probability zero. Single
//! flips alone would then freeze atoms that hard formulas tie together (with `SaLe(p,q) =>
//! SaLe(q,p)` hard, neither atom of a pair can change alone), so atoms connected by hard
//! features are grouped into blocks and each block is resampled jointly from its exact
//! conditional distribution (its 2^k states enumerated in Gray-code order). Blocks larger than
//! `max_block` fall back to single-atom moves, which keeps the chain correct but may leave it
//! unable to reach every world; MC-SAT is the better tool for such networks.
//!
//! Estimates are Rao-Blackwellised: each step adds the conditional probability that an atom is
//! true rather than its sampled value, which cuts the variance at no extra cost.

use super::{hard_blocks, satisfy_hard, Counts, InferenceConfig};
use crate::mcmc::Rng;
use crate::mln::error::MlnError;
use crate::mln::ground::Network;

pub(crate) fn marginals(net: &Network, config: &InferenceConfig, rng: &mut Rng) -> Result<Vec<f64>, MlnError> {
    let n = net.atom_count();
    if n == 0 {
        return Ok(Vec::new());
    }
    let start = satisfy_hard(net, config.walksat_flips, rng)?;
    let mut counts = Counts::new(net, start);
    let blocks = hard_blocks(net, config.max_block);
    let widest = blocks.iter().map(Vec::len).max().unwrap_or(1);
    let mut logw = vec![0.0f64; 1 << widest];
    let mut sums = vec![0.0f64; n];
    for step in 0..config.burn_in as u64 + config.samples as u64 {
        sweep(&mut counts, &blocks, &mut logw, &mut sums, step >= config.burn_in as u64, rng);
    }
    let m = config.samples as f64;
    Ok(sums.into_iter().map(|s| (s / m).clamp(0.0, 1.0)).collect())
}

/// One Gibbs sweep over all blocks; adds the Rao-Blackwellised estimates to `sums` if `record`.
pub(crate) fn sweep(
    counts: &mut Counts,
    blocks: &[Vec<u32>],
    logw: &mut [f64],
    sums: &mut [f64],
    record: bool,
    rng: &mut Rng,
) {
    for block in blocks {
        if let [a] = block[..] {
            let a = a as usize;
            let (dh, ds) = counts.delta(a);
            let p_flip = if dh > 0 { 0.0 } else { 1.0 / (1.0 + libm::exp(-ds)) };
            if record {
                sums[a] += if counts.value[a] { 1.0 - p_flip } else { p_flip };
            }
            if rng.uniform() < p_flip {
                counts.flip(a);
            }
        } else {
            resample_block(counts, block, logw, sums, record, rng);
        }
    }
}

/// Draws a block's atoms jointly from their conditional distribution given the rest.
fn resample_block(counts: &mut Counts, block: &[u32], logw: &mut [f64], sums: &mut [f64], record: bool, rng: &mut Rng) {
    let states = 1usize << block.len();
    let (here, z) = enumerate_block(counts, block, logw);
    if record {
        add_block_marginals(counts, block, &logw[..states], z, here, sums);
    }
    let mut u = rng.uniform() * z;
    let mut pick = states - 1;
    for (i, &w) in logw[..states].iter().enumerate() {
        if u < w {
            pick = i;
            break;
        }
        u -= w;
    }
    while logw[pick] == 0.0 {
        pick -= 1; // rounding at the end of the scan: take the last state with weight
    }
    move_block(counts, block, here, pick);
}

/// Visits a block's 2^k joint states in Gray-code order, starting from the current world
/// (which satisfies the hard features), and fills `weights[i]` with the unnormalised
/// conditional probability of Gray state `i` (zero if it violates a hard feature), scaled so
/// the largest is 1. Leaves the world in the last state; returns its Gray code and the total.
pub(crate) fn enumerate_block(counts: &mut Counts, block: &[u32], weights: &mut [f64]) -> (usize, f64) {
    let states = 1usize << block.len();
    let (mut hard, mut lw) = (0i32, 0.0f64);
    weights[0] = 0.0;
    let mut top = 0.0f64;
    for i in 1..states {
        let a = block[i.trailing_zeros() as usize] as usize;
        let (dh, ds) = counts.delta(a);
        counts.flip(a);
        hard += dh;
        lw += ds;
        weights[i] = if hard == 0 { lw } else { f64::NEG_INFINITY };
        top = top.max(weights[i]);
    }
    let mut z = 0.0;
    for w in weights[..states].iter_mut() {
        *w = libm::exp(*w - top);
        z += *w;
    }
    ((states - 1) ^ ((states - 1) >> 1), z)
}

/// Adds each block atom's conditional probability of being true to `sums`; the world is in
/// Gray state `here` of the enumeration.
pub(crate) fn add_block_marginals(
    counts: &Counts,
    block: &[u32],
    weights: &[f64],
    z: f64,
    here: usize,
    sums: &mut [f64],
) {
    // In Gray state i, atom j differs from its starting value iff bit j of gray(i) is set.
    let start: usize =
        block.iter().enumerate().map(|(j, &a)| ((counts.value[a as usize] as usize) ^ (here >> j & 1)) << j).sum();
    for (j, &a) in block.iter().enumerate() {
        let mut p = 0.0;
        for (i, &w) in weights.iter().enumerate() {
            if (start ^ i ^ (i >> 1)) >> j & 1 == 1 {
                p += w;
            }
        }
        sums[a as usize] += p / z;
    }
}

/// Moves a block from Gray state `here` to Gray state index `pick`.
pub(crate) fn move_block(counts: &mut Counts, block: &[u32], here: usize, pick: usize) {
    let diff = here ^ (pick ^ (pick >> 1));
    for (j, &a) in block.iter().enumerate() {
        if diff >> j & 1 == 1 {
            counts.flip(a as usize);
        }
    }
}
