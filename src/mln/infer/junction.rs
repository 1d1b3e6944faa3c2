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
use std::cmp::Reverse;
use std::collections::BinaryHeap;

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

/// Maps an entry of a table over `vars` to the entry of a table over a subset `sub`: gathers
/// the bits of `sub`'s atoms, a byte of the index at a time through lookup tables.
struct Projection {
    bytes: Vec<[u32; 256]>,
}

impl Projection {
    fn new(sub: &[u32], vars: &[u32]) -> Self {
        let mut bytes = vec![[0u32; 256]; vars.len().div_ceil(8)];
        for (j, a) in sub.iter().enumerate() {
            let p = vars.iter().position(|v| v == a).expect("a sub-scope");
            for (b, t) in bytes[p / 8].iter_mut().enumerate() {
                *t |= ((b >> (p % 8)) as u32 & 1) << j;
            }
        }
        Projection { bytes }
    }

    /// The part of entry `x`'s index in the sub-table that the bits above `x`'s lowest byte
    /// give: the same for the 256 entries of a block ([`blocks`]), so a pass over a table in
    /// order looks up one byte an entry ([`Projection::low`]).
    #[inline]
    fn high(&self, x: usize) -> u32 {
        let mut i = 0;
        for (k, t) in self.bytes.iter().enumerate().skip(1) {
            i |= t[(x >> (8 * k)) & 255];
        }
        i
    }

    /// The lookup of the lowest byte: entry `x` is entry `low()[x & 255] | high(x)` of the
    /// sub-table.
    #[inline]
    fn low(&self) -> &[u32; 256] {
        &self.bytes[0]
    }
}

/// The entries `0..len` of a table in blocks of (at most) 256 that share their high bits.
fn blocks(len: usize) -> impl Iterator<Item = std::ops::Range<usize>> {
    (0..len).step_by(256).map(move |b| b..(b + 256).min(len))
}

/// Elimination order by least fill-in (ties: fewest neighbours), and the resulting cliques.
fn eliminate(net: &Network, max_clique: usize) -> Result<Vec<Clique>, TooWide> {
    let max_clique = max_clique.min(30);
    let n = net.atom_count();
    let mut adj = interaction_graph(net, max_clique)?;
    let mut alive = vec![true; n];
    let mut order_of = vec![usize::MAX; n];
    let mut cliques = Vec::with_capacity(n);
    let mut entries = 0usize;
    // Fill-in of eliminating v (pairs of its neighbours not yet adjacent), then its degree.
    // Atoms too wide to eliminate now wait at the back without their fill being counted.
    let score = |adj: &[Vec<u32>], v: usize| -> (usize, usize) {
        let nb = &adj[v];
        if nb.len() + 1 > max_clique {
            return (usize::MAX, nb.len());
        }
        let mut missing = 0;
        for (i, &a) in nb.iter().enumerate() {
            for &b in &nb[i + 1..] {
                if adj[a as usize].binary_search(&b).is_err() {
                    missing += 1;
                }
            }
        }
        (missing, nb.len())
    };
    let mut current: Vec<(usize, usize)> = (0..n).map(|v| score(&adj, v)).collect();
    let mut heap: BinaryHeap<Reverse<(usize, usize, u32)>> =
        (0..n).map(|v| Reverse((current[v].0, current[v].1, v as u32))).collect();
    let mut dirty = Vec::new();
    for step in 0..n {
        let v = loop {
            let Reverse((fill, degree, v)) = heap.pop().expect("an atom is left");
            if alive[v as usize] && current[v as usize] == (fill, degree) {
                break v as usize;
            }
        };
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
            let a = a as usize;
            let s = score(&adj, a);
            if s != current[a] {
                current[a] = s;
                heap.push(Reverse((s.0, s.1, a as u32)));
            }
        }
        alive[v] = false;
        order_of[v] = step;
        let mut vars = vec![v as u32];
        vars.extend(&nb);
        cliques.push(Clique { vars, parent: None, children: Vec::new(), potential: Vec::new() });
    }
    attach(net, &mut cliques, &order_of);
    Ok(cliques)
}

/// Every atom's neighbours (atoms sharing a feature with it), sorted; too wide if one
/// feature alone has more than `max_clique` atoms.
fn interaction_graph(net: &Network, max_clique: usize) -> Result<Vec<Vec<u32>>, TooWide> {
    let mut adj: Vec<Vec<u32>> = vec![Vec::new(); net.atom_count()];
    let mut scope = Vec::new();
    for f in 0..net.feature_count() {
        feature_scope(net, f, &mut scope);
        if scope.len() > max_clique {
            return Err(TooWide { clique: scope.len() });
        }
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
    Ok(adj)
}

/// Links the cliques into a tree (`order_of[atom]` is the step that eliminated it) and puts
/// each feature's table into one clique's potential.
fn attach(net: &Network, cliques: &mut [Clique], order_of: &[usize]) {
    let n = cliques.len();
    // The parent of a clique is that of its separator atom eliminated first.
    for i in 0..n {
        let parent = cliques[i].vars[1..].iter().map(|&a| order_of[a as usize]).min();
        if let Some(p) = parent {
            cliques[i].parent = Some(p);
            cliques[p].children.push(i);
        }
    }
    // Each feature goes to the smallest clique that holds its atoms (the clique of its atom
    // eliminated first always does).
    for c in cliques.iter_mut() {
        c.potential = vec![1.0; 1 << c.vars.len()];
    }
    let (mut table, mut scope) = (Vec::new(), Vec::new());
    for f in 0..net.feature_count() {
        feature_scope(net, f, &mut scope);
        let home = scope
            .iter()
            .map(|&a| order_of[a as usize])
            .filter(|&i| scope.iter().all(|a| cliques[i].vars.contains(a)))
            .min_by_key(|&i| (cliques[i].vars.len(), i))
            .unwrap();
        feature_table(net, f, &scope, &mut table);
        let clique = &mut cliques[home];
        let proj = Projection::new(&scope, &clique.vars);
        for block in blocks(clique.potential.len()) {
            let hi = proj.high(block.start);
            for (p, &lo) in clique.potential[block].iter_mut().zip(proj.low()) {
                *p *= table[(lo | hi) as usize];
            }
        }
    }
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

/// Marginal probability of every unknown atom with the number of clique-table entries the tree
/// needed (its work), or the clique size that made the tree too wide. `None` inside `Ok` means
/// the hard features cannot all be satisfied.
///
/// Each clique's table is read in as few passes as the two messages allow, every product and
/// sum taken in the order of the plain loops (so the marginals are the same bits): the sums
/// that normalise a table are chains of dependent additions, and run beside the other work of
/// a pass instead of in a pass of their own.
pub(crate) fn marginals(net: &Network, max_clique: usize) -> Result<Option<(Vec<f64>, u64)>, TooWide> {
    let mut cliques = eliminate(net, max_clique)?;
    let entries: u64 = cliques.iter().map(|c| 1u64 << c.vars.len()).sum();
    let n = cliques.len();
    // Clique i's entries onto its separator, within its parent's table.
    let to_parent: Vec<Option<Projection>> =
        cliques.iter().map(|c| c.parent.map(|p| Projection::new(&c.vars[1..], &cliques[p].vars))).collect();
    // Upward: full[i] = potential x messages from children; up[i] = full[i] summed over vars[0].
    let mut up: Vec<Vec<f64>> = vec![Vec::new(); n];
    let mut full: Vec<Vec<f64>> = vec![Vec::new(); n];
    for i in 0..n {
        let mut t = std::mem::take(&mut cliques[i].potential);
        let children: Vec<(&Projection, &[f64])> =
            cliques[i].children.iter().map(|&c| (to_parent[c].as_ref().unwrap(), up[c].as_slice())).collect();
        let (m, s) = upward(&mut t, &children);
        if s == 0.0 {
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
        let from_parent = std::mem::take(&mut down[i]);
        let mut z = -0.0;
        if cliques[i].parent.is_some() {
            for (x, v) in belief.iter_mut().enumerate() {
                *v *= from_parent[x >> 1];
                z += *v;
            }
        } else {
            z = belief.iter().sum::<f64>();
        }
        if z == 0.0 {
            return Ok(None);
        }
        let children = &cliques[i].children;
        let mut messages: Vec<Vec<f64>> = children.iter().map(|&c| vec![0.0; up[c].len()]).collect();
        let projections: Vec<&Projection> = children.iter().map(|&c| to_parent[c].as_ref().unwrap()).collect();
        let mut yes = -0.0;
        let mut highs = vec![0u32; children.len()];
        for block in blocks(belief.len()) {
            for (h, p) in highs.iter_mut().zip(&projections) {
                *h = p.high(block.start);
            }
            for x in block {
                let b = belief[x] / z;
                if x & 1 == 1 {
                    yes += b;
                }
                for ((m, p), &h) in messages.iter_mut().zip(&projections).zip(&highs) {
                    m[(p.low()[x & 255] | h) as usize] += b;
                }
            }
        }
        out[cliques[i].vars[0] as usize] = f64::clamp(yes, 0.0, 1.0);
        for (&c, mut m) in children.iter().zip(messages) {
            let mut s = -0.0;
            for (v, &u) in m.iter_mut().zip(&up[c]) {
                *v = if u > 0.0 { *v / u } else { 0.0 };
                s += *v;
            }
            scale(&mut m, s);
            down[c] = m;
        }
    }
    Ok(Some((out, entries)))
}

/// One clique's upward pass: multiplies its table `t` by each child's message (`(projection,
/// message)`, in the children's order) and sums it over its eliminated atom (bit 0); returns
/// that sum normalised and the total it was divided by (0: no entry is possible).
fn upward(t: &mut [f64], children: &[(&Projection, &[f64])]) -> (Vec<f64>, f64) {
    let mut m = vec![0.0; t.len() / 2];
    let mut s = -0.0;
    let mut highs = vec![0u32; children.len()];
    for block in blocks(t.len()) {
        for (h, (p, _)) in highs.iter_mut().zip(children) {
            *h = p.high(block.start);
        }
        for x in block.step_by(2) {
            let (mut a, mut b) = (t[x], t[x + 1]);
            for (&(p, u), &h) in children.iter().zip(&highs) {
                let lo = p.low();
                a *= u[(lo[x & 255] | h) as usize];
                b *= u[(lo[(x + 1) & 255] | h) as usize];
            }
            (t[x], t[x + 1]) = (a, b);
            let v = a + b;
            m[x >> 1] = v;
            s += v;
        }
    }
    scale(&mut m, s);
    (m, s)
}

/// Divides `t` by its total `s` (already summed, in order), unless that is 0.
fn scale(t: &mut [f64], s: f64) {
    if s > 0.0 {
        for v in t.iter_mut() {
            *v /= s;
        }
    }
}
