//! Exact marginals on a junction tree (variable elimination, two passes).
//!
//! Ground networks of the two use cases are large but thin: an indoor unit's type atoms
//! interact only with those of its neighbours, through their `SaLe` atoms. Eliminating atoms
//! one by one (min-fill order) turns the network into a tree of cliques, each an atom and the
//! neighbours it had when eliminated; if every clique stays small, sum-product message passing
//! on that tree gives every marginal exactly, in time linear in the number of cliques and
//! exponential only in their size.
//!
//! Each feature becomes a factor over its atoms, `1` where satisfied and `exp(-w)` where not
//! (hard features: `0`), which is `exp(w [F])` up to a constant. Messages are normalised as
//! they are made, so nothing under- or overflows.

use crate::mln::ground::Network;

/// Why the tree could not be built: cliques would exceed the limit.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct TooWide {
    /// Size of the clique that broke the limit.
    pub clique: usize,
}

/// Total table entries allowed over all cliques (32 MB of `f64`).
const MAX_ENTRIES: usize = 1 << 22;

struct Clique {
    /// `vars[0]` is the eliminated atom, the rest its separator; bit `j` of a table index is
    /// the value of `vars[j]`.
    vars: Vec<u32>,
    parent: Option<usize>,
    children: Vec<usize>,
    /// Product of the factors assigned here.
    potential: Vec<f64>,
}

/// Bit positions of `sub`'s atoms within `vars`.
fn positions(sub: &[u32], vars: &[u32]) -> Vec<u8> {
    sub.iter().map(|a| vars.iter().position(|v| v == a).expect("sub-scope") as u8).collect()
}

/// The index into a table over `sub` of the entry `x` of a table over `vars`.
#[inline]
fn project(x: usize, pos: &[u8]) -> usize {
    pos.iter().enumerate().fold(0, |i, (j, &p)| i | ((x >> p) & 1) << j)
}

/// Elimination order by least fill-in (ties: fewest neighbours), and the resulting cliques.
fn eliminate(net: &Network, max_clique: usize) -> Result<Vec<Clique>, TooWide> {
    let max_clique = max_clique.min(30);
    let n = net.atom_count();
    let mut adj: Vec<Vec<u32>> = vec![Vec::new(); n];
    let mut scope = Vec::new();
    for f in 0..net.feature_count() {
        feature_scope(net, f, &mut scope);
        for &a in &scope {
            for &b in &scope {
                if a != b {
                    adj[a as usize].push(b);
                }
            }
        }
    }
    for v in adj.iter_mut() {
        v.sort_unstable();
        v.dedup();
    }
    let mut alive = vec![true; n];
    let mut order_of = vec![usize::MAX; n];
    let mut cliques = Vec::with_capacity(n);
    let mut entries = 0usize;
    // Fill-in of eliminating v: pairs of its neighbours that are not yet adjacent.
    let fill = |adj: &[Vec<u32>], v: usize| -> usize {
        let nb = &adj[v];
        let mut missing = 0;
        for (i, &a) in nb.iter().enumerate() {
            for &b in &nb[i + 1..] {
                if adj[a as usize].binary_search(&b).is_err() {
                    missing += 1;
                }
            }
        }
        missing
    };
    let mut score: Vec<(usize, usize)> = (0..n).map(|v| (fill(&adj, v), adj[v].len())).collect();
    let mut dirty = Vec::new();
    for step in 0..n {
        let v = (0..n).filter(|&v| alive[v]).min_by_key(|&v| (score[v], v)).unwrap();
        let nb = std::mem::take(&mut adj[v]);
        if nb.len() + 1 > max_clique {
            return Err(TooWide { clique: nb.len() + 1 });
        }
        entries += 1 << (nb.len() + 1);
        if entries > MAX_ENTRIES {
            return Err(TooWide { clique: nb.len() + 1 });
        }
        for &a in &nb {
            let list = &mut adj[a as usize];
            list.retain(|&b| b as usize != v);
            for &b in &nb {
                if b != a {
                    if let Err(i) = list.binary_search(&b) {
                        list.insert(i, b);
                    }
                }
            }
        }
        // Only the neighbours and their neighbours can have a new score.
        dirty.clear();
        for &a in &nb {
            dirty.push(a);
            dirty.extend(&adj[a as usize]);
        }
        dirty.sort_unstable();
        dirty.dedup();
        for &a in &dirty {
            score[a as usize] = (fill(&adj, a as usize), adj[a as usize].len());
        }
        alive[v] = false;
        order_of[v] = step;
        let mut vars = vec![v as u32];
        vars.extend(&nb);
        cliques.push(Clique { vars, parent: None, children: Vec::new(), potential: Vec::new() });
    }
    // The parent of a clique is that of its separator atom eliminated first.
    for i in 0..n {
        let parent = cliques[i].vars[1..].iter().map(|&a| order_of[a as usize]).min();
        if let Some(p) = parent {
            cliques[i].parent = Some(p);
            cliques[p].children.push(i);
        }
    }
    // Each feature goes to the clique of its atom eliminated first.
    for c in cliques.iter_mut() {
        c.potential = vec![1.0; 1 << c.vars.len()];
    }
    let mut table = Vec::new();
    for f in 0..net.feature_count() {
        feature_scope(net, f, &mut scope);
        let home = scope.iter().map(|&a| order_of[a as usize]).min().unwrap();
        feature_table(net, f, &scope, &mut table);
        let clique = &mut cliques[home];
        let pos = positions(&scope, &clique.vars);
        for (x, p) in clique.potential.iter_mut().enumerate() {
            *p *= table[project(x, &pos)];
        }
    }
    Ok(cliques)
}

/// The sorted atoms of a feature.
fn feature_scope(net: &Network, f: usize, out: &mut Vec<u32>) {
    out.clear();
    for c in net.clauses_of(f) {
        out.extend(net.clause_lits(c).iter().map(|&l| l >> 1));
    }
    out.sort_unstable();
    out.dedup();
}

/// `exp(w [F]) / exp(w)` over the feature's atoms: 1 satisfied, `exp(-w)` (or 0 if hard) not.
fn feature_table(net: &Network, f: usize, scope: &[u32], out: &mut Vec<f64>) {
    let w = net.feature_weight[f];
    let violated = if w.is_infinite() { 0.0 } else { libm::exp(-w) };
    out.clear();
    for x in 0..1usize << scope.len() {
        let sat = net.clauses_of(f).all(|c| {
            net.clause_lits(c).iter().any(|&l| {
                let j = scope.binary_search(&(l >> 1)).unwrap();
                (x >> j & 1 == 1) != (l & 1 == 1)
            })
        });
        out.push(if sat { 1.0 } else { violated });
    }
}

fn normalise(t: &mut [f64]) -> f64 {
    let s: f64 = t.iter().sum();
    if s > 0.0 {
        for v in t.iter_mut() {
            *v /= s;
        }
    }
    s
}

/// Marginal probability of every unknown atom, or the clique size that made the tree too wide.
/// `None` inside `Ok` means the hard features cannot all be satisfied.
pub(crate) fn marginals(net: &Network, max_clique: usize) -> Result<Option<Vec<f64>>, TooWide> {
    let mut cliques = eliminate(net, max_clique)?;
    let n = cliques.len();
    // Upward: full[i] = potential x messages from children; up[i] = full[i] summed over vars[0].
    let mut up: Vec<Vec<f64>> = vec![Vec::new(); n];
    let mut full: Vec<Vec<f64>> = vec![Vec::new(); n];
    for i in 0..n {
        let mut t = std::mem::take(&mut cliques[i].potential);
        for &c in &cliques[i].children {
            let pos = positions(&cliques[c].vars[1..], &cliques[i].vars);
            for (x, v) in t.iter_mut().enumerate() {
                *v *= up[c][project(x, &pos)];
            }
        }
        let mut m = vec![0.0; t.len() / 2];
        for (x, &v) in t.iter().enumerate() {
            m[x >> 1] += v;
        }
        if normalise(&mut m) == 0.0 {
            return Ok(None);
        }
        up[i] = m;
        full[i] = t;
    }
    // Downward, parents before children: belief = full x message from the parent, and the
    // message to a child is the belief summed onto its separator, divided by the child's own
    // upward message (0 / 0 = 0: such entries have zero belief anyway).
    let mut out = vec![0.0; n];
    let mut down: Vec<Vec<f64>> = vec![Vec::new(); n];
    for i in (0..n).rev() {
        let mut belief = std::mem::take(&mut full[i]);
        if cliques[i].parent.is_some() {
            for (x, v) in belief.iter_mut().enumerate() {
                *v *= down[i][x >> 1];
            }
        }
        let z = normalise(&mut belief);
        if z == 0.0 {
            return Ok(None);
        }
        out[cliques[i].vars[0] as usize] = belief.iter().skip(1).step_by(2).sum::<f64>().clamp(0.0, 1.0);
        for &c in &cliques[i].children {
            let pos = positions(&cliques[c].vars[1..], &cliques[i].vars);
            let mut m = vec![0.0; up[c].len()];
            for (x, &v) in belief.iter().enumerate() {
                m[project(x, &pos)] += v;
            }
            for (v, &u) in m.iter_mut().zip(&up[c]) {
                *v = if u > 0.0 { *v / u } else { 0.0 };
            }
            normalise(&mut m);
            down[c] = m;
        }
        down[i] = Vec::new();
    }
    Ok(Some(out))
}
