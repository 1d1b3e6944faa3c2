//! The five reversible kernel pairs (section 3.5) and their proposal probabilities `Q`
//! (section 3.5.3).
//!
//! Every kernel draws its move from an explicit distribution, and the same distribution is
//! evaluated for the reverse move in the proposed world, so the Metropolis-Hastings ratio of
//! eq. 3.9 is exact. The dissertation approximates `Q` as equal for SHRINK/DILATE and
//! INTERCHANGE; here it is computed, because it is cheap and keeps detailed balance exact
//! (tested by exact enumeration on a small map).
//!
//! | kernel | choice of element | probability |
//! |---|---|---|
//! | ADD | candidate `r` by `ω_r` (eqs. 3.10, 3.15 - 3.17), mixed with a uniform rectangle | `(1-ε) ω_r/Σω + ε / N` |
//! | REMOVE | unit by `b_r` (eq. 3.21) | `b_r / Σ b` |
//! | SPLIT | unit uniformly, then a cut line by its wall evidence (eq. 3.18) | `1/n · ω_e / Σ ω` |
//! | MERGE, INTERCHANGE | unit `r` uniformly, then `s` by `a_r(s) = 1/d(c_r, c_s)` (eq. 3.20) | `1/n · (a_r(s)/Σa_r + a_s(r)/Σa_s)` |
//! | SHRINK, DILATE | unit by `b_r`, wall by `v_w` (eq. 3.22), distance by a discretised half-Gaussian | product |
//! | ALLOCATE | detected door by `ω_g` (eq. 3.23), mixed with a uniform door | as ADD |
//! | DELETE | door by `z_g` (eq. 3.28) | `z_g / Σ z` |
//!
//! The uniform parts of ADD and ALLOCATE make every world reachable, so the chain is ergodic
//! even where the detectors miss something.

use super::schedule::Kernel;
use super::state::{door_rect, facing, Axis, DoorLimits, DoorSpec, Move, State, Undo};
use crate::floorplan::world::Rect;
use crate::mcmc::{Cumulative, Rng};
use crate::setting::{check, InvalidSetting};
use crate::vision::doors;
use serde::{Deserialize, Serialize};
use std::collections::HashMap;

/// Parameters of the kernels' proposal distributions.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct KernelConfig {
    /// Smallest unit side, m (in cells: two walls and at least one free cell, 3 or more).
    /// 0.5 m: narrower than a closet a person steps into.
    pub min_side_m: f64,
    /// Largest number of units.
    pub max_units: usize,
    /// `h_b` of eq. 3.21: cap on `1/ω_r` when choosing units to change or remove.
    pub h_b: f64,
    /// `h_v` of eq. 3.22: cap on `1/ω_w` when choosing a wall to move.
    pub h_v: f64,
    /// `h_g` of eq. 3.28: cap on `1/ω_g` when choosing a door to delete.
    pub h_g: f64,
    /// Standard deviation of the SHRINK/DILATE wall shift, m (at least 0.3 cells). 0.15 m: a
    /// wall's thickness, the scale on which a unit's wall misses the map's.
    pub shift_sigma_m: f64,
    /// Share of ADD proposals drawn uniformly from all rectangles instead of the candidates.
    pub uniform_add: f64,
    /// Share of ALLOCATE proposals drawn uniformly from all possible doors.
    pub uniform_door: f64,
    /// Weight every possible cut line gets in SPLIT besides its wall evidence, so any split of
    /// a unit can be proposed (and so any MERGE reversed).
    pub split_epsilon: f64,
}

impl Default for KernelConfig {
    fn default() -> Self {
        KernelConfig {
            min_side_m: 0.5,
            max_units: 200,
            h_b: 20.0,
            h_v: 20.0,
            h_g: 20.0,
            shift_sigma_m: 0.15,
            uniform_add: 0.02,
            uniform_door: 0.05,
            split_epsilon: 0.25,
        }
    }
}

impl KernelConfig {
    /// Checks every number.
    pub fn validate(&self) -> Result<(), InvalidSetting> {
        let (side, sigma, n) = (self.min_side_m, self.shift_sigma_m, self.max_units);
        check(side > 0.0 && side <= 100.0, "min_side_m", side, "metres above 0, at most 100")?;
        check(sigma > 0.0 && sigma <= 50.0, "shift_sigma_m", sigma, "metres above 0, at most 50")?;
        check(n > 0 && n <= 250, "max_units", n as f64, "between 1 and 250")?;
        for (name, v) in [("h_b", self.h_b), ("h_v", self.h_v), ("h_g", self.h_g)] {
            check(v.is_finite() && v > 0.0, name, v, "a positive number")?;
        }
        for (name, v) in [("uniform_add", self.uniform_add), ("uniform_door", self.uniform_door)] {
            check(v.is_finite() && v > 0.0 && v <= 1.0, name, v, "in (0, 1]")?;
        }
        let e = self.split_epsilon;
        check(e.is_finite() && e > 0.0, "split_epsilon", e, "a positive number")
    }

    /// The smallest unit side in cells of `resolution` metres: rounded, at least 3.
    ///
    /// ```
    /// use ksmcmc::floorplan::KernelConfig;
    /// let k = KernelConfig::default();
    /// assert_eq!((k.min_side_cells(0.05), k.min_side_cells(0.1), k.min_side_cells(0.5)), (10, 5, 3));
    /// assert_eq!((k.shift_sigma_cells(0.05), k.shift_sigma_cells(0.025)), (3.0, 6.0));
    /// ```
    pub fn min_side_cells(&self, resolution: f64) -> i32 {
        (libm::round(self.min_side_m / crate::grid::cell_size_m(resolution)).min(1e6) as i32).max(3)
    }

    /// The wall shift's standard deviation in cells of `resolution` metres (to a millionth of a
    /// cell, so that 0.15 m at 0.05 m is 3 exactly), at least 0.3.
    pub fn shift_sigma_cells(&self, resolution: f64) -> f64 {
        (libm::round(self.shift_sigma_m / crate::grid::cell_size_m(resolution) * 1e6) / 1e6).clamp(0.3, 1e6)
    }
}

/// A weighted pool of rectangles for ADD.
#[derive(Debug, Clone, Default)]
pub struct Candidates {
    rects: Vec<Rect>,
    cumulative: Cumulative,
    lookup: HashMap<Rect, usize>,
}

impl Candidates {
    /// A pool from weighted rectangles; duplicates keep their first weight.
    pub fn new(items: impl IntoIterator<Item = (Rect, f64)>) -> Self {
        let mut c = Candidates::default();
        c.extend(items);
        c
    }

    /// Adds rectangles not yet in the pool.
    pub fn extend(&mut self, items: impl IntoIterator<Item = (Rect, f64)>) {
        let mut weights: Vec<f64> = (0..self.rects.len()).map(|i| self.cumulative.weight(i)).collect();
        for (r, w) in items {
            if !self.lookup.contains_key(&r) {
                self.lookup.insert(r, self.rects.len());
                self.rects.push(r);
                weights.push(w);
            }
        }
        self.cumulative = Cumulative::new(weights);
    }

    /// Drops the rectangles `drop` selects and adds `items` (new rectangles go last, in order):
    /// how the online chain replaces the candidates a map change reaches. Returns how many
    /// were dropped.
    pub fn replace_where(
        &mut self,
        drop: impl Fn(Rect) -> bool,
        items: impl IntoIterator<Item = (Rect, f64)>,
    ) -> usize {
        let kept: Vec<(Rect, f64)> = self.iter().filter(|&(r, _)| !drop(r)).collect();
        let dropped = self.rects.len() - kept.len();
        *self = Candidates::new(kept);
        self.extend(items);
        dropped
    }

    /// Number of candidates.
    pub fn len(&self) -> usize {
        self.rects.len()
    }

    /// Whether the pool is empty.
    pub fn is_empty(&self) -> bool {
        self.rects.is_empty()
    }

    /// All candidates with their weights.
    pub fn iter(&self) -> impl Iterator<Item = (Rect, f64)> + '_ {
        self.rects.iter().enumerate().map(|(i, r)| (*r, self.cumulative.weight(i)))
    }

    fn probability(&self, r: Rect) -> f64 {
        self.lookup.get(&r).map_or(0.0, |&i| self.cumulative.probability(i))
    }
}

/// Doors detected for the current unit geometry, cached by [`State::generation`].
#[derive(Debug, Clone, Default)]
struct DoorCache {
    generation: Option<u64>,
    /// Facing pairs `(lo, hi, axis)` with their number of possible spans.
    pairs: Vec<(u32, u32, Axis, i32, i32, f64)>,
    pair_lookup: HashMap<(u32, u32, Axis), usize>,
    doors: Vec<DoorSpec>,
    cumulative: Cumulative,
    lookup: HashMap<DoorSpec, usize>,
}

/// Draws moves and evaluates their probabilities.
#[derive(Debug, Clone)]
pub struct Proposer {
    config: KernelConfig,
    /// The configuration's smallest unit side in cells of the map.
    base_min_side: i32,
    /// The ADD pool.
    pub candidates: Candidates,
    doors: DoorCache,
    shift: Cumulative,
    scratch: Cumulative,
    /// The four walls' `v_w` (eq. 3.22) of the unit being reshaped.
    sides: Cumulative,
    scratch_weights: Vec<f64>,
    uniform_count: f64,
    min_side: i32,
    wall: i32,
}

fn spans(s: i32, e: i32, limits: &DoorLimits) -> f64 {
    let n = e - s + 1;
    (limits.min_len..=limits.max_len).map(|l| (n - l + 1).max(0) as f64).sum()
}

/// Number of `(start, length)` pairs with `length >= min` in `0..n`.
fn interval_count(n: i64, min: i64) -> i64 {
    if n < min {
        0
    } else {
        (n - min + 1) * (n - min + 2) / 2
    }
}

/// The other way to cut the L shape formed by `r` and `s` into two rectangles sharing a wall
/// `t` cells deep, as new rectangles for `r`'s slot and `s`'s slot; `None` unless `r ∪ s` is
/// such an L.
pub fn interchange(r: Rect, s: Rect, t: i32) -> Option<(Rect, Rect)> {
    if let Some((rest, full)) = l_case(r, s, t) {
        return Some((rest, full));
    }
    l_case(s, r, t).map(|(rest, full)| (full, rest))
}

/// `full` spans the bounding box in one direction and `part` sits beside it, aligned with one
/// edge and shorter. Returns (rest of `full` beside the new band, the new full band).
fn l_case(full: Rect, part: Rect, t: i32) -> Option<(Rect, Rect)> {
    let bx = full.x.min(part.x);
    let by = full.y.min(part.y);
    let br = full.right().max(part.right());
    let bb = full.bottom().max(part.bottom());
    // full spans the whole width; part is above or below it, sharing a wall t deep.
    if full.x == bx
        && full.right() == br
        && part.w < full.w
        && (part.y == full.bottom() - t || part.bottom() - t == full.y)
    {
        if part.x != bx && part.right() != br {
            return None;
        }
        let band = Rect::new(part.x, by, part.w, bb - by);
        let rest = if part.x == bx {
            Rect::new(part.right() - t, full.y, br - part.right() + t, full.h)
        } else {
            Rect::new(bx, full.y, part.x - bx + t, full.h)
        };
        return Some((rest, band));
    }
    // full spans the whole height; part is left or right of it.
    if full.y == by
        && full.bottom() == bb
        && part.h < full.h
        && (part.x == full.right() - t || part.right() - t == full.x)
    {
        if part.y != by && part.bottom() != bb {
            return None;
        }
        let band = Rect::new(bx, part.y, br - bx, part.h);
        let rest = if part.y == by {
            Rect::new(full.x, part.bottom() - t, full.w, bb - part.bottom() + t)
        } else {
            Rect::new(full.x, by, full.w, part.y - by + t)
        };
        return Some((rest, band));
    }
    None
}

/// The bounding box of two rectangles that tile it side by side sharing a wall `t` deep, and
/// the cut between them (the first column or row of the shared wall).
pub fn merge_of(r: Rect, s: Rect, t: i32) -> Option<(Rect, bool, i32)> {
    if r.y == s.y && r.h == s.h && (r.right() - t == s.x || s.right() - t == r.x) {
        let x = r.x.min(s.x);
        return Some((Rect::new(x, r.y, r.w + s.w - t, r.h), true, r.x.max(s.x)));
    }
    if r.x == s.x && r.w == s.w && (r.bottom() - t == s.y || s.bottom() - t == r.y) {
        let y = r.y.min(s.y);
        return Some((Rect::new(r.x, y, r.w, r.h + s.h - t), false, r.y.max(s.y)));
    }
    None
}

/// The two parts of `u` cut at column (`vertical`) or row `k`: they share the wall of depth
/// `t` that starts there, as two rooms share the wall between them.
pub fn split_at(u: Rect, vertical: bool, k: i32, t: i32) -> (Rect, Rect) {
    if vertical {
        (Rect::new(u.x, u.y, k + t - u.x, u.h), Rect::new(k, u.y, u.right() - k, u.h))
    } else {
        (Rect::new(u.x, u.y, u.w, k + t - u.y), Rect::new(u.x, k, u.w, u.bottom() - k))
    }
}

/// Moves wall `side` (0 left, 1 right, 2 top, 3 bottom) of `r` outwards by `d` cells
/// (inwards for negative `d`).
pub fn shifted(r: Rect, side: usize, d: i32) -> Rect {
    match side {
        0 => Rect::new(r.x - d, r.y, r.w + d, r.h),
        1 => Rect::new(r.x, r.y, r.w + d, r.h),
        2 => Rect::new(r.x, r.y - d, r.w, r.h + d),
        _ => Rect::new(r.x, r.y, r.w, r.h + d),
    }
}

/// The smallest unit side for rings `wall` deep (two rings and a free cell at least), and how
/// many rectangles with sides of at least that fit a `width` x `height` grid (the uniform ADD
/// proposal's count).
fn sizes(base_min_side: i32, wall: i32, width: i32, height: i32) -> (i32, f64) {
    let min_side = base_min_side.max(2 * wall + 1);
    let n = min_side as i64;
    (min_side, (interval_count(width as i64, n) * interval_count(height as i64, n)) as f64)
}

impl Proposer {
    /// Forgets the doors detected so far: they were found on a map that has since changed.
    pub fn forget_doors(&mut self) {
        self.doors.generation = None;
    }

    /// Proposes for units with wall rings `wall` deep from now on (on a `width` x `height`
    /// world-frame grid), as [`Proposer::new`] would have.
    pub fn set_wall(&mut self, wall: i32, width: i32, height: i32) {
        self.wall = wall;
        (self.min_side, self.uniform_count) = sizes(self.base_min_side, wall, width, height);
        self.forget_doors();
    }

    /// A proposer for a `width` x `height` world of `resolution` metres a cell with the given
    /// ADD candidates.
    pub fn new(
        config: KernelConfig,
        resolution: f64,
        candidates: Candidates,
        width: i32,
        height: i32,
        wall: i32,
    ) -> Self {
        let base_min_side = config.min_side_cells(resolution);
        let (min_side, uniform_count) = sizes(base_min_side, wall, width, height);
        let sigma = config.shift_sigma_cells(resolution);
        let m = libm::ceil(4.0 * sigma).max(1.0) as i32;
        let s2 = 2.0 * sigma * sigma;
        let shift = Cumulative::new((1..=m).map(|d| libm::exp(-((d * d) as f64) / s2)));
        Proposer {
            config,
            base_min_side,
            candidates,
            doors: DoorCache::default(),
            shift,
            scratch: Cumulative::default(),
            sides: Cumulative::default(),
            scratch_weights: Vec::new(),
            uniform_count,
            min_side,
            wall,
        }
    }

    fn b_weights(&mut self, s: &State) {
        self.scratch_weights.clear();
        for u in &s.units {
            let w = s.unit_weight(u.rect());
            self.scratch_weights.push(if w > 0.0 { (1.0 / w).min(self.config.h_b) } else { self.config.h_b });
        }
        self.scratch.rebuild(self.scratch_weights.iter().copied());
    }

    fn v_weights(&self, s: &State, r: Rect) -> [f64; 4] {
        s.wall_weights(r).map(|w| if w > 0.0 { (1.0 / w).min(self.config.h_v) } else { self.config.h_v })
    }

    fn cut_weight(s: &State, u: Rect, vertical: bool, k: i32, eps: f64) -> f64 {
        // Wall evidence along the cut: occupied cells in the new shared wall, inside the unit's
        // interior (the Hough accumulator at 0 / 90 degrees, eq. 3.18), per ring row.
        let t = s.wall;
        let ev = if vertical {
            s.occupied_in(Rect::new(k, u.y + t, t, u.h - 2 * t))
        } else {
            s.occupied_in(Rect::new(u.x + t, k, u.w - 2 * t, t))
        };
        eps + ev as f64 / t as f64
    }

    /// Cuts `k` leaving both parts at least `min_side` cells: the first part is `k + t - x`.
    fn cut_range(&self, u: Rect, vertical: bool) -> (i32, i32) {
        let m = self.min_side;
        let t = self.wall;
        if vertical {
            (u.x + m - t, u.right() - m)
        } else {
            (u.y + m - t, u.bottom() - m)
        }
    }

    fn cut_weights(&mut self, s: &State, u: Rect) {
        self.scratch_weights.clear();
        let eps = self.config.split_epsilon;
        for vertical in [true, false] {
            let (a, b) = self.cut_range(u, vertical);
            for k in a..=b {
                self.scratch_weights.push(Self::cut_weight(s, u, vertical, k, eps));
            }
        }
        self.scratch.rebuild(self.scratch_weights.iter().copied());
    }

    fn pair_weights(&mut self, s: &State, r: usize) {
        let (cx, cy) = s.units[r].rect().center();
        self.scratch_weights.clear();
        for (k, u) in s.units.iter().enumerate() {
            let w = if k == r {
                0.0
            } else {
                let (x, y) = u.rect().center();
                1.0 / libm::sqrt((x - cx) * (x - cx) + (y - cy) * (y - cy)).max(0.5)
            };
            self.scratch_weights.push(w);
        }
        self.scratch.rebuild(self.scratch_weights.iter().copied());
    }

    /// `Q` of ADD proposing `r`.
    pub fn q_add(&self, r: Rect) -> f64 {
        let p_unif = if self.candidates.is_empty() { 1.0 } else { self.config.uniform_add };
        (1.0 - p_unif) * self.candidates.probability(r) + p_unif / self.uniform_count
    }

    /// `Q` of REMOVE choosing unit `i`.
    pub fn q_remove(&mut self, s: &State, i: usize) -> f64 {
        self.b_weights(s);
        self.scratch.probability(i)
    }

    /// `Q` of SPLIT cutting unit `i` into `first` (left/upper) and `second`.
    pub fn q_split(&mut self, s: &State, i: usize, vertical: bool, k: i32) -> f64 {
        let u = s.units[i].rect();
        let (a, b) = self.cut_range(u, vertical);
        if k < a || k > b {
            return 0.0;
        }
        self.cut_weights(s, u);
        let total = self.scratch.total();
        Self::cut_weight(s, u, vertical, k, self.config.split_epsilon) / total / s.units.len() as f64
    }

    /// `Q` of choosing the unordered pair `{i, j}` (MERGE and INTERCHANGE).
    pub fn q_pair(&mut self, s: &State, i: usize, j: usize) -> f64 {
        let n = s.units.len() as f64;
        self.pair_weights(s, i);
        let a = self.scratch.probability(j);
        self.pair_weights(s, j);
        let b = self.scratch.probability(i);
        (a + b) / n
    }

    /// `Q` of SHRINK/DILATE moving wall `side` of unit `i` by `d` cells (either sign).
    pub fn q_shift(&mut self, s: &State, i: usize, side: usize, d: i32) -> f64 {
        let m = d.unsigned_abs() as usize;
        if m == 0 || m > self.shift.len() {
            return 0.0;
        }
        self.b_weights(s);
        let pu = self.scratch.probability(i);
        let v = self.v_weights(s, s.units[i].rect());
        let pv = v[side] / v.iter().sum::<f64>();
        pu * pv * self.shift.probability(m - 1)
    }

    fn refresh_doors(&mut self, s: &State) {
        if self.doors.generation == Some(s.generation) {
            return;
        }
        let limits = s.door_limits;
        let c = &mut self.doors;
        c.generation = Some(s.generation);
        c.pairs.clear();
        c.pair_lookup.clear();
        c.doors.clear();
        c.lookup.clear();
        let mut weights = Vec::new();
        for a in &s.units {
            for b in &s.units {
                for axis in [Axis::Horizontal, Axis::Vertical] {
                    let Some((st, en)) = facing(a.rect(), b.rect(), axis, limits.max_gap, s.wall) else { continue };
                    let n = spans(st, en, &limits);
                    if n <= 0.0 {
                        continue;
                    }
                    c.pair_lookup.insert((a.id, b.id, axis), c.pairs.len());
                    c.pairs.push((a.id, b.id, axis, st, en, n));
                    let (lo, hi) = (a.rect(), b.rect());
                    let spec = |start, end| DoorSpec { lo: a.id, hi: b.id, axis, start, end };
                    let band = doors::Band { lo, hi, axis, wall: s.wall, start: st, end: en };
                    let door = |first, last| door_rect(lo, hi, &spec(first, last), &limits, s.wall);
                    for ((first, last), w) in doors::detect(s.counts(), &band, door) {
                        let d = spec(first, last);
                        if !c.lookup.contains_key(&d) {
                            c.lookup.insert(d, c.doors.len());
                            c.doors.push(d);
                            weights.push(w);
                        }
                    }
                }
            }
        }
        c.cumulative = Cumulative::new(weights);
    }

    /// `Q` of ALLOCATE proposing door `d`.
    pub fn q_allocate(&mut self, s: &State, d: &DoorSpec) -> f64 {
        self.refresh_doors(s);
        let c = &self.doors;
        if c.pairs.is_empty() {
            return 0.0;
        }
        let p_unif = if c.doors.is_empty() { 1.0 } else { self.config.uniform_door };
        let cand = c.lookup.get(d).map_or(0.0, |&i| c.cumulative.probability(i));
        let len = d.end - d.start + 1;
        let unif = match c.pair_lookup.get(&(d.lo, d.hi, d.axis)) {
            Some(&p) => {
                let (_, _, _, st, en, n) = c.pairs[p];
                let ok = d.start >= st && d.end <= en && len >= s.door_limits.min_len && len <= s.door_limits.max_len;
                if ok {
                    1.0 / c.pairs.len() as f64 / n
                } else {
                    0.0
                }
            }
            None => 0.0,
        };
        (1.0 - p_unif) * cand + p_unif * unif
    }

    fn z_weights(&mut self, s: &State) {
        self.scratch_weights.clear();
        for d in &s.doors {
            let w = s.door_rect_of(d).map_or(0.0, |r| s.free_in(r) as f64 / r.area() as f64);
            self.scratch_weights.push(if w > 0.0 { (1.0 / w).min(self.config.h_g) } else { self.config.h_g });
        }
        self.scratch.rebuild(self.scratch_weights.iter().copied());
    }

    /// `Q` of DELETE choosing door `k`.
    pub fn q_delete(&mut self, s: &State, k: usize) -> f64 {
        self.z_weights(s);
        self.scratch.probability(k)
    }

    fn draw_uniform_rect(&self, s: &State, rng: &mut Rng) -> Rect {
        let m = self.min_side;
        let axis = |rng: &mut Rng, size: i32| -> (i32, i32) {
            let total = interval_count(size as i64, m as i64);
            let mut k = (rng.uniform() * total as f64) as i64;
            k = k.min(total - 1);
            for len in m..=size {
                let count = (size - len + 1) as i64;
                if k < count {
                    return (k as i32, len);
                }
                k -= count;
            }
            (0, size)
        };
        let (x, w) = axis(rng, s.width());
        let (y, h) = axis(rng, s.height());
        Rect::new(x, y, w, h)
    }

    /// Draws a move for `kernel` in state `s`, with its forward probability `Q(W'|W)`.
    pub fn propose(&mut self, kernel: Kernel, s: &State, rng: &mut Rng) -> Option<(Move, f64)> {
        let n = s.units.len();
        match kernel {
            Kernel::Add => {
                if s.width() < self.min_side || s.height() < self.min_side {
                    return None;
                }
                let p_unif = if self.candidates.is_empty() { 1.0 } else { self.config.uniform_add };
                let r = if rng.uniform() < p_unif {
                    self.draw_uniform_rect(s, rng)
                } else {
                    self.candidates.rects[self.candidates.cumulative.draw(rng)?]
                };
                Some((Move::Add(r), self.q_add(r)))
            }
            Kernel::Remove => {
                if n == 0 {
                    return None;
                }
                self.b_weights(s);
                let i = self.scratch.draw(rng)?;
                Some((Move::Remove(i), self.scratch.probability(i)))
            }
            Kernel::Split => self.propose_split(s, rng),
            Kernel::Merge | Kernel::Interchange => {
                if n < 2 {
                    return None;
                }
                let i = rng.below(n as u32) as usize;
                self.pair_weights(s, i);
                let j = self.scratch.draw(rng)?;
                let (r, t) = (s.units[i].rect(), s.units[j].rect());
                let m = if kernel == Kernel::Merge {
                    let (merged, _, _) = merge_of(r, t, self.wall)?;
                    Move::Merge { i, j, merged }
                } else {
                    let (a, b) = interchange(r, t, self.wall)?;
                    Move::Repartition { i, j, a, b }
                };
                let q = self.q_pair(s, i, j);
                Some((m, q))
            }
            Kernel::Shrink | Kernel::Dilate => {
                if n == 0 {
                    return None;
                }
                self.b_weights(s);
                let i = self.scratch.draw(rng)?;
                let u = s.units[i].rect();
                // v_w lies in (0, h_v]: the draw never fails.
                let v = self.v_weights(s, u);
                self.sides.rebuild(v);
                let side = self.sides.draw(rng).unwrap_or(3);
                let m = self.shift.draw(rng)? as i32 + 1;
                let d = if kernel == Kernel::Dilate { m } else { -m };
                let q = self.q_shift(s, i, side, d);
                Some((Move::Reshape { index: i, rect: shifted(u, side, d) }, q))
            }
            Kernel::Allocate => self.propose_allocate(s, rng),
            Kernel::Delete => {
                if s.doors.is_empty() {
                    return None;
                }
                self.z_weights(s);
                let k = self.scratch.draw(rng)?;
                Some((Move::Delete(k), self.scratch.probability(k)))
            }
        }
    }

    /// SPLIT: a unit uniformly, then a cut by its wall evidence (eq. 3.18).
    fn propose_split(&mut self, s: &State, rng: &mut Rng) -> Option<(Move, f64)> {
        let n = s.units.len();
        if n == 0 {
            return None;
        }
        let i = rng.below(n as u32) as usize;
        let u = s.units[i].rect();
        self.cut_weights(s, u);
        let c = self.scratch.draw(rng)?;
        let q = self.scratch.probability(c) / n as f64;
        let (va, vb) = self.cut_range(u, true);
        let nv = (vb - va + 1).max(0) as usize;
        let (vertical, k) =
            if c < nv { (true, va + c as i32) } else { (false, self.cut_range(u, false).0 + (c - nv) as i32) };
        let (first, second) = split_at(u, vertical, k, self.wall);
        Some((Move::Split { index: i, first, second }, q))
    }

    /// ALLOCATE: a detected door by `ω_g` (eq. 3.23), or a uniform door between a facing pair.
    fn propose_allocate(&mut self, s: &State, rng: &mut Rng) -> Option<(Move, f64)> {
        self.refresh_doors(s);
        let c = &self.doors;
        if c.pairs.is_empty() {
            return None;
        }
        let p_unif = if c.doors.is_empty() { 1.0 } else { self.config.uniform_door };
        let d = if rng.uniform() < p_unif {
            let (lo, hi, axis, st, en, _) = c.pairs[rng.below(c.pairs.len() as u32) as usize];
            // Uniform over (start, length) with min_len <= length <= max_len.
            let lim = s.door_limits;
            let total = spans(st, en, &lim);
            let mut k = ((rng.uniform() * total) as i64).min(total as i64 - 1);
            let (mut start, mut len) = (st, lim.min_len);
            for l in lim.min_len..=lim.max_len {
                let count = (en - st + 1 - l + 1).max(0) as i64;
                if k < count {
                    (start, len) = (st + k as i32, l);
                    break;
                }
                k -= count;
            }
            DoorSpec { lo, hi, axis, start, end: start + len - 1 }
        } else {
            c.doors[c.cumulative.draw(rng)?]
        };
        let q = self.q_allocate(s, &d);
        Some((Move::Allocate(d), q))
    }

    /// `Q(W|W')`: the probability that the reverse kernel proposes the way back, evaluated in
    /// the new state `s` after `m` was applied (`undo` describes what it changed).
    pub fn reverse_q(&mut self, m: &Move, undo: &Undo, s: &State) -> f64 {
        match (m, undo) {
            (Move::Add(_), _) => self.q_remove(s, s.units.len() - 1),
            (Move::Remove(_), Undo::Removed { unit, .. }) => self.q_add(unit.rect()),
            (Move::Split { index, .. }, _) => self.q_pair(s, *index, s.units.len() - 1),
            (Move::Merge { i, j, .. }, Undo::Merged { ui, uj, .. }) => {
                let mi = if i > j { i - 1 } else { *i };
                match merge_of(ui.rect(), uj.rect(), self.wall) {
                    Some((_, vertical, k)) => self.q_split(s, mi, vertical, k),
                    None => 0.0,
                }
            }
            (Move::Reshape { index, rect }, Undo::Replaced { old, .. }) => {
                let before = old[0].1.rect();
                // Which wall moved, and by how much (positive outwards in the new state's terms).
                let moves = [
                    before.x - rect.x,
                    rect.right() - before.right(),
                    before.y - rect.y,
                    rect.bottom() - before.bottom(),
                ];
                match moves.iter().position(|&d| d != 0) {
                    Some(side) => self.q_shift(s, *index, side, -moves[side]),
                    None => 0.0,
                }
            }
            (Move::Repartition { i, j, .. }, _) => self.q_pair(s, *i, *j),
            (Move::Allocate(_), _) => self.q_delete(s, s.doors.len() - 1),
            (Move::Delete(_), Undo::Deleted { door, .. }) => self.q_allocate(s, door),
            _ => 0.0,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn interchange_is_its_own_inverse() {
        for t in 1..=3 {
            // Top band full width, bottom-left part sharing a wall t deep: an L.
            let r = Rect::new(0, 0, 10, 4 + t);
            let s = Rect::new(0, 4, 6, 5 + t);
            let (a, b) = interchange(r, s, t).unwrap();
            assert_eq!(b, Rect::new(0, 0, 6, 9 + t));
            assert_eq!(interchange(a, b, t), Some((r, s)));
            // All eight L orientations round-trip.
            for (r, s) in [
                (Rect::new(0, 0, 10, 4 + t), Rect::new(4, 4, 6, 5)),
                (Rect::new(0, 5 - t, 10, 4 + t), Rect::new(0, 0, 6, 5)),
                (Rect::new(0, 5 - t, 10, 4 + t), Rect::new(4, 0, 6, 5)),
                (Rect::new(0, 0, 4 + t, 10), Rect::new(4, 0, 5, 6)),
                (Rect::new(0, 0, 4 + t, 10), Rect::new(4, 4, 5, 6)),
                (Rect::new(5 - t, 0, 4 + t, 10), Rect::new(0, 0, 5, 6)),
                (Rect::new(5 - t, 0, 4 + t, 10), Rect::new(0, 4, 5, 6)),
            ] {
                let (a, b) = interchange(r, s, t).unwrap_or_else(|| panic!("{r:?} {s:?} t={t}"));
                // The union is the same L: areas add up the same with the shared wall counted once.
                let overlap = |p: Rect, q: Rect| p.intersection(&q).map_or(0, |i| i.area());
                assert_eq!(a.area() + b.area() - overlap(a, b), r.area() + s.area() - overlap(r, s));
                assert_eq!(interchange(a, b, t), Some((r, s)), "{r:?} {s:?} t={t}");
            }
            // Not an L: a plain split, a gap, a T.
            assert_eq!(interchange(Rect::new(0, 0, 5 + t, 5), Rect::new(5, 0, 5, 5), t), None);
            assert_eq!(interchange(Rect::new(0, 0, 10, 4), Rect::new(0, 5, 6, 5), t), None);
            assert_eq!(interchange(Rect::new(0, 0, 10, 4 + t), Rect::new(2, 4, 6, 5), t), None);
        }
    }

    #[test]
    fn merge_and_split_are_inverse() {
        let u = Rect::new(3, 4, 20, 9);
        for t in 1..=3 {
            for (vertical, k) in [(true, 10), (false, 8)] {
                let (a, b) = split_at(u, vertical, k, t);
                assert!(a.intersection(&b).is_some(), "the parts share a wall");
                assert_eq!(merge_of(a, b, t), Some((u, vertical, k)));
                assert_eq!(merge_of(b, a, t), Some((u, vertical, k)));
            }
            assert_eq!(merge_of(Rect::new(0, 0, 5, 5), Rect::new(6, 0, 5, 5), t), None);
        }
    }
}
