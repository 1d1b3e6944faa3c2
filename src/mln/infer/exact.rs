//! Exact inference by enumeration, one connected part of the network at a time.
//!
//! Atoms that share no feature are independent, so the worlds of each connected part can be
//! enumerated on their own: 2^k worlds for a part of k atoms instead of 2^n for the network.
//! Worlds are visited in Gray-code order, so each differs from the last by one flip, and the
//! log weight is updated incrementally. Worlds violating a hard feature get weight zero.
//!
//! Two passes: the first finds the largest log weight (to scale by, so nothing overflows),
//! the second sums the weights. An atom's true mass is summed a whole run at a time: its value
//! only changes when it flips, so the mass of a run is the difference of two running totals.

use super::{atom_groups, unsatisfiable, Counts, NO_WORLD};
use crate::mln::error::{ErrorKind, MlnError};
use crate::mln::ground::Network;

fn components(net: &Network, limit: usize) -> Result<Vec<Vec<u32>>, MlnError> {
    let groups = atom_groups(net, |_| true);
    let largest = groups.iter().map(Vec::len).max().unwrap_or(0);
    if largest > limit || largest > 30 {
        return Err(MlnError::new(ErrorKind::TooManyUnknownAtoms { atoms: largest, limit }, None));
    }
    Ok(groups)
}

/// Hard features violated by the all-false world, per component.
fn initial_hard(net: &Network, counts: &Counts, groups: &[Vec<u32>]) -> Vec<i64> {
    let mut of_atom = vec![0u32; net.atom_count()];
    for (g, atoms) in groups.iter().enumerate() {
        for &a in atoms {
            of_atom[a as usize] = g as u32;
        }
    }
    let mut hard = vec![0i64; groups.len()];
    for f in 0..net.feature_count() {
        if net.feature_weight[f].is_infinite() && counts.unsat[f] > 0 {
            let a = net.clause_lits(net.clauses_of(f).start)[0] >> 1;
            hard[of_atom[a as usize] as usize] += 1;
        }
    }
    hard
}

/// Pass one over a component: the best log weight (relative to all-false) and the Gray index
/// of a world reaching it. Leaves the atoms false.
fn best(counts: &mut Counts, atoms: &[u32], hard0: i64) -> (f64, u32) {
    let k = atoms.len();
    let mut hard = hard0;
    let mut logw = 0.0;
    let (mut best, mut best_i) = (if hard == 0 { 0.0 } else { f64::NEG_INFINITY }, 0u32);
    for i in 1u32..1 << k {
        let a = atoms[i.trailing_zeros() as usize] as usize;
        let (dh, ds) = counts.delta(a);
        counts.flip(a);
        hard += dh as i64;
        logw += ds;
        if hard == 0 && logw > best {
            best = logw;
            best_i = i;
        }
    }
    counts.flip(atoms[k - 1] as usize); // Gray code 2^k - 1 has only the top atom set
    (best, best_i)
}

/// Probability of each unknown atom.
pub(crate) fn marginals(net: &Network, limit: usize) -> Result<Vec<f64>, MlnError> {
    let groups = components(net, limit)?;
    let mut counts = Counts::new(net, vec![false; net.atom_count()]);
    let hard0 = initial_hard(net, &counts, &groups);
    let mut out = vec![0.0; net.atom_count()];
    let mut mass = Vec::new();
    let mut last = Vec::new();
    for (g, atoms) in groups.iter().enumerate() {
        let k = atoms.len();
        let (top, _) = best(&mut counts, atoms, hard0[g]);
        if top == f64::NEG_INFINITY {
            return Err(unsatisfiable(NO_WORLD));
        }
        mass.clear();
        mass.resize(k, 0.0);
        last.clear();
        last.resize(k, 0.0);
        let mut hard = hard0[g];
        let mut logw = 0.0;
        let mut total = if hard == 0 { libm::exp(-top) } else { 0.0 };
        for i in 1u32..1 << k {
            let j = i.trailing_zeros() as usize;
            let a = atoms[j] as usize;
            let (dh, ds) = counts.delta(a);
            if counts.value[a] {
                mass[j] += total - last[j];
            }
            last[j] = total;
            counts.flip(a);
            hard += dh as i64;
            logw += ds;
            if hard == 0 {
                total += libm::exp(logw - top);
            }
        }
        for j in 0..k {
            if counts.value[atoms[j] as usize] {
                mass[j] += total - last[j];
            }
            out[atoms[j] as usize] = (mass[j] / total).clamp(0.0, 1.0);
        }
        counts.flip(atoms[k - 1] as usize);
    }
    Ok(out)
}

/// A most probable world.
pub(crate) fn map(net: &Network, limit: usize) -> Result<Vec<bool>, MlnError> {
    let groups = components(net, limit)?;
    let mut counts = Counts::new(net, vec![false; net.atom_count()]);
    let hard0 = initial_hard(net, &counts, &groups);
    let mut state = vec![false; net.atom_count()];
    for (g, atoms) in groups.iter().enumerate() {
        let (top, i) = best(&mut counts, atoms, hard0[g]);
        if top == f64::NEG_INFINITY {
            return Err(unsatisfiable(NO_WORLD));
        }
        let gray = i ^ (i >> 1);
        for (j, &a) in atoms.iter().enumerate() {
            state[a as usize] = gray >> j & 1 == 1;
        }
    }
    Ok(state)
}
