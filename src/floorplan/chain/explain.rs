//! How well a world explains a map, kept up to date cell by cell.
//!
//! The likelihood (eq. 3.6) and the overlap factor `α2` (eq. 3.5) are products over cells, so
//! their logarithms are sums of per-cell terms that depend only on the map class `C_M` and the
//! predicted class `C_W` (eq. 3.8) of the cell, and on how many units cover it. Instead of
//! summing floating-point terms, [`Explanation`] keeps *integer* counts: the 3x3 confusion
//! matrix `n[C_M][C_W]` and the total overlap `Σ max(0, σ(c) - 1)`. The log posterior is then a
//! dot product with the log sensor table, exact and free of drift however long the chain runs,
//! and the cell prediction rate `K(W, M)` of eq. 3.39 is the matrix's trace over its total.
//!
//! A proposal changes only the cells of the rectangles it touches, so updating costs
//! O(changed cells), not O(map). Each cell's counters are interleaved in one 4-byte record so
//! an update touches one cache line.

use crate::geometry::Rect;
use crate::grid::{Cell, Grid};

/// Predicted class of a cell, eq. 3.8: `0` free, `1` unknown, `2` wall; door cells are free.
#[inline]
fn predicted(cover: u8, wall: u8, door: u8) -> usize {
    if door > 0 {
        0
    } else if wall > 0 {
        2
    } else if cover > 0 {
        0
    } else {
        1
    }
}

/// The overlap exponent of one cell, `σ(c) - 1` of eq. 3.5, except on shared walls: a cell in
/// the wall ring of *every* unit covering it is a wall two rooms share, as buildings are built,
/// not two units claiming the same space, so it is not penalised.
#[inline]
fn overlap(cover: u8, wall: u8) -> i64 {
    if cover > 1 && wall < cover {
        (cover - 1) as i64
    } else {
        0
    }
}

/// Moves `n` cells that held the record `c` from the counts of `c` to those of `c` changed by
/// `delta` ([`CellState::changed`]): the confusion matrix (`counts.0`) and the overlap
/// (`counts.1`).
#[inline]
fn settle(counts: &mut ([[i64; 3]; 3], i64), c: CellState, n: i64, delta: (u32, u32)) {
    let new = c.changed(delta);
    let row = &mut counts.0[c.cm() as usize];
    row[c.predicted()] -= n;
    row[new.predicted()] += n;
    counts.1 += n * (new.overlap() - c.overlap());
}

/// How many records at the start of `cells` have the counters `upper` (a record without its
/// map class byte): eight at a time while a whole block matches, then one at a time. Both
/// passes here are written branch-free per block so the compiler vectorises them; a loop that
/// stopped at every change of the map class mispredicted a branch every few cells.
#[inline]
fn same_counters(cells: &[CellState], upper: u32) -> usize {
    let mut n = 0;
    for block in cells.chunks_exact(8) {
        if block.iter().fold(0, |acc, c| acc | ((c.0 & !0xff) ^ upper)) != 0 {
            break;
        }
        n += 8;
    }
    n + cells[n..].iter().take_while(|c| c.0 & !0xff == upper).count()
}

/// How many records of `cells` hold each map class (eq. 3.7 code).
#[inline]
fn class_counts(cells: &[CellState]) -> [i64; 3] {
    let (mut unknown, mut occupied) = (0u32, 0u32);
    for c in cells {
        unknown += (c.0 & 0xff == Cell::Unknown as u32) as u32;
        occupied += (c.0 & 0xff == Cell::Occupied as u32) as u32;
    }
    let (unknown, occupied) = (unknown as i64, occupied as i64);
    let mut n = [0i64; 3];
    n[Cell::Unknown as usize] = unknown;
    n[Cell::Occupied as usize] = occupied;
    n[Cell::Free as usize] = cells.len() as i64 - unknown - occupied;
    n
}

/// One cell's counters, a byte each in one word: its map class `C_M` (eq. 3.7 code), how many
/// units cover it (`σ(c)` in eq. 3.5), how many units' wall rings and how many doors hold it.
/// One word, so [`Explanation::touch_run`] compares and changes a cell in one step.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
struct CellState(u32);

/// Where each counter sits in a [`CellState`].
const COVER: u32 = 8;
const WALL: u32 = 16;
const DOOR: u32 = 24;

impl CellState {
    fn of_class(cm: u8) -> CellState {
        CellState(cm as u32)
    }
    fn cm(self) -> u8 {
        self.0 as u8
    }
    fn cover(self) -> u8 {
        (self.0 >> COVER) as u8
    }
    fn wall(self) -> u8 {
        (self.0 >> WALL) as u8
    }
    fn door(self) -> u8 {
        (self.0 >> DOOR) as u8
    }
    fn predicted(self) -> usize {
        predicted(self.cover(), self.wall(), self.door())
    }
    fn overlap(self) -> i64 {
        overlap(self.cover(), self.wall())
    }
    /// The record with the counters changed by `delta`, the word to add and the word to take
    /// away ([`packed_delta`]). No counter leaves 0..=255 (no cell is covered by 256 units), so
    /// no byte carries into the next.
    #[inline]
    fn changed(self, (add, sub): (u32, u32)) -> CellState {
        CellState(self.0.wrapping_add(add).wrapping_sub(sub))
    }
}

/// The changes of the cover, wall and door counters as the word to add and the word to take
/// away from a [`CellState`].
fn packed_delta(dcover: i8, dwall: i8, ddoor: i8) -> (u32, u32) {
    let (mut add, mut sub) = (0, 0);
    for (d, at) in [(dcover, COVER), (dwall, WALL), (ddoor, DOOR)] {
        if d >= 0 {
            add |= (d as u32) << at;
        } else {
            sub |= (d.unsigned_abs() as u32) << at;
        }
    }
    (add, sub)
}

/// The per-cell bookkeeping of one world against one (world-frame) classified map.
#[derive(Debug, Clone)]
pub struct Explanation {
    width: usize,
    height: usize,
    cells: Vec<CellState>,
    /// `confusion[C_M][C_W]`: how many cells of map class `C_M` the world predicts as `C_W`.
    confusion: [[i64; 3]; 3],
    /// `Σ_c max(0, σ(c) - 1)`, the exponent of `ψ2` in eq. 3.5, shared walls excepted.
    overlap: i64,
    /// A unit added or taken out whose change the counts hold but the cells do not yet
    /// ([`Explanation::apply_unit`]).
    pending: Option<Pending>,
    /// A bit a cell, set where the cell is free on the map and covered by no unit: what the
    /// free-space detector reads at every refresh, a word of 64 cells at a time
    /// ([`FreeSpace::unexplained_word`](crate::vision::freespace::FreeSpace::unexplained_word)).
    /// Kept as the cells are written, which the chain does only for the moves it accepts:
    /// reading every cell at every refresh (33 in a default run) cost Cartesium 1 ms each.
    unexplained: Vec<u64>,
}

/// A unit added (`sign = 1`) or taken out (`-1`), `t` cells of wall deep, with the counts
/// before it: most births and deaths the chain proposes are refused and undone at once, and
/// the counts alone decide, so the cells are written only when the next change comes.
#[derive(Debug, Clone, Copy)]
struct Pending {
    rect: Rect,
    t: i32,
    sign: i8,
    before: ([[i64; 3]; 3], i64),
}

impl Explanation {
    /// The explanation of an empty world: every cell predicted unknown.
    pub fn new(map: &Grid<Cell>) -> Self {
        let mut confusion = [[0i64; 3]; 3];
        let cells: Vec<CellState> = map
            .cells()
            .iter()
            .map(|&c| {
                confusion[c as usize][1] += 1;
                CellState::of_class(c as u8)
            })
            .collect();
        let unexplained = unexplained_bits(&cells);
        Explanation {
            width: map.width(),
            height: map.height(),
            cells,
            confusion,
            overlap: 0,
            pending: None,
            unexplained,
        }
    }

    /// Grid width.
    pub fn width(&self) -> usize {
        self.width
    }

    /// Grid height.
    pub fn height(&self) -> usize {
        self.height
    }

    /// The confusion counts `n[C_M][C_W]`.
    pub fn confusion(&self) -> &[[i64; 3]; 3] {
        &self.confusion
    }

    /// The overlap count of eq. 3.5.
    pub fn overlap(&self) -> i64 {
        self.overlap
    }

    /// The cell prediction rate `K(W, M)` of eq. 3.39: the share of cells where `C_M = C_W`.
    pub fn prediction_rate(&self) -> f64 {
        let hits: i64 = (0..3).map(|i| self.confusion[i][i]).sum();
        hits as f64 / self.cells.len().max(1) as f64
    }

    /// Predicted class `C_W` of cell `(x, y)` (a unit still pending not counted: [`Explanation::apply_unit`]).
    pub fn predicted(&self, x: usize, y: usize) -> Cell {
        Cell::from_code(self.cells[y * self.width + x].predicted() as u8).expect("0..=2")
    }

    /// How many units cover cell `(x, y)` (a unit still pending not counted: [`Explanation::apply_unit`]).
    pub fn cover(&self, x: usize, y: usize) -> u8 {
        self.cells[y * self.width + x].cover()
    }

    /// Map class of cell `(x, y)`.
    pub fn map_class(&self, x: usize, y: usize) -> Cell {
        Cell::from_code(self.cells[y * self.width + x].cm()).expect("0..=2")
    }

    /// Changes the map class of cell `i` (row-major) to `cm`, keeping the confusion counts
    /// exact: the map grew or was corrected there ([`crate::floorplan::Chain::update_map`]).
    pub fn set_map_class(&mut self, i: usize, cm: Cell) {
        self.write_pending();
        let c = self.cells[i];
        let p = c.predicted();
        self.confusion[c.cm() as usize][p] -= 1;
        self.cells[i] = CellState(c.0 & !0xff | cm as u32);
        self.confusion[cm as usize][p] += 1;
        self.mark_unexplained(i..i + 1, false);
    }

    /// Changes the counts of the cells `run` (row-major indices, one row's stretch) by the
    /// same amounts, keeping the confusion and overlap counts exact. Every change of the
    /// counters goes through here: one copy of the per-cell loop, which the unit moves, their
    /// undos and the doors share (the mapper module has no room for a copy per caller).
    ///
    /// Neighbouring cells mostly hold the same record (a wall's cells, a room's floor), and the
    /// same record changes the counts the same way: the loop only counts how many cells in a
    /// row hold it and settles the counts once per stretch of equal records
    /// ([`settle`]), so a hall's birth is a pass of compares and byte adds, not
    /// two read-modify-writes of the counts per cell (office_g's births of 100,000-cell halls
    /// made this loop 46 % of a run).
    ///
    /// Without `write` only the counts change (a pending unit, [`Pending`]).
    #[inline(never)]
    fn touch_run(&mut self, run: std::ops::Range<usize>, dcover: i8, dwall: i8, ddoor: i8, write: bool) {
        let delta = packed_delta(dcover, dwall, ddoor);
        let mut counts = (self.confusion, self.overlap);
        let cells = &mut self.cells[run.clone()];
        // Stretches of one cover, wall and door count (they change only at other units'
        // edges), each settled once per map class (which changes wherever the scan is noisy).
        let mut i = 0;
        while i < cells.len() {
            let upper = cells[i].0 & !0xff;
            let j = i + 1 + same_counters(&cells[i + 1..], upper);
            for (cm, n) in class_counts(&cells[i..j]).into_iter().enumerate().filter(|&(_, n)| n > 0) {
                settle(&mut counts, CellState(upper | cm as u32), n, delta);
            }
            i = j;
        }
        if write {
            for c in cells.iter_mut() {
                *c = c.changed(delta);
            }
        }
        (self.confusion, self.overlap) = counts;
        if write && dcover != 0 {
            self.mark_unexplained(run, dcover > 0);
        }
    }

    /// Sets the unexplained bits of the cells `run` from the cells; with `covered` the cells
    /// are all covered now (a unit came), so their bits are cleared without reading them.
    /// A word at a time, and only the run's bits in it: a unit's side walls are runs of a
    /// few cells on every row.
    fn mark_unexplained(&mut self, run: std::ops::Range<usize>, covered: bool) {
        let mut i = run.start;
        while i < run.end {
            let (k, offset) = (i / 64, i % 64);
            let end = run.end.min(64 * k + 64);
            let n = end - i;
            let mask = if n == 64 { u64::MAX } else { ((1u64 << n) - 1) << offset };
            let bits = if covered { 0 } else { unexplained_word(&self.cells[i..end]) << offset };
            self.unexplained[k] = self.unexplained[k] & !mask | bits;
            i = end;
        }
    }

    /// Writes the change of a unit added or taken out into the cells ([`Explanation::apply_unit`]); its counts are in.
    #[inline(never)]
    pub fn write_pending(&mut self) {
        if let Some(p) = self.pending.take() {
            // The counts hold the change already: write the cells and keep the counts.
            let counts = (self.confusion, self.overlap);
            self.unit_runs(p.rect, p.t, p.sign, true);
            (self.confusion, self.overlap) = counts;
        }
    }

    /// Adds (`sign = 1`) or removes (`sign = -1`) a unit: its rectangle covers cells and its
    /// outer ring, `t` cells deep, is wall. The rectangle must lie inside the grid.
    ///
    /// The counts change at once and the cells when [`Explanation::write_pending`] or the next
    /// change comes: undoing it (the same unit with the other sign) only puts
    /// the counts back, so a refused birth or death of a hall reads its cells once instead of
    /// writing them twice. Until then the cells read as before it.
    pub fn apply_unit(&mut self, r: Rect, t: i32, sign: i8) {
        if let Some(p) = self.pending {
            if (p.rect, p.t, p.sign) == (r, t, -sign) {
                (self.confusion, self.overlap) = p.before;
                self.pending = None;
                return;
            }
            self.write_pending();
        }
        let before = (self.confusion, self.overlap);
        self.unit_runs(r, t, sign, false);
        self.pending = Some(Pending { rect: r, t, sign, before });
    }

    /// [`Explanation::apply_unit`]'s change, row by row, to the counts and, with `write`, the
    /// cells.
    #[inline(never)]
    fn unit_runs(&mut self, r: Rect, t: i32, sign: i8, write: bool) {
        debug_assert!(r.x >= 0 && r.y >= 0 && r.right() as usize <= self.width && r.bottom() as usize <= self.height);
        let (x0, x1) = (r.x as usize, r.right() as usize);
        let (y0, y1) = (r.y as usize, r.bottom() as usize);
        let t = t.max(1) as usize;
        // Interior columns [i0, i1); empty when the unit is all wall.
        let i0 = (x0 + t).min(x1);
        let i1 = x1.saturating_sub(t).max(i0);
        for y in y0..y1 {
            let base = y * self.width;
            if y < y0 + t || y + t >= y1 {
                self.touch_run(base + x0..base + x1, sign, sign, 0, write);
            } else {
                self.touch_run(base + x0..base + i0, sign, sign, 0, write);
                self.touch_run(base + i0..base + i1, sign, 0, 0, write);
                self.touch_run(base + i1..base + x1, sign, sign, 0, write);
            }
        }
    }

    /// Takes the units `old` out and puts the units `new` in (each `t` cells of wall deep, as
    /// [`Explanation::apply_unit`]), touching only the cells whose cover or wall count
    /// changes: a unit grown or shrunk by a row, split or merged, changes a band along the
    /// moved edges, not its whole area (office_g's halls of 100,000 cells made `apply_unit`
    /// half of a run). The counts end as `apply_unit` on each would leave them.
    pub fn replace_units(&mut self, old: &[Rect], new: &[Rect], t: i32) {
        self.write_pending();
        let t = t.max(1) as usize;
        // Each unit with the sign of its change: one loop over them all (a loop per slice
        // cost the mapper module 624 bytes gzipped).
        let signed: Vec<(Rect, i8)> = old.iter().map(|&r| (r, -1)).chain(new.iter().map(|&r| (r, 1))).collect();
        let (mut y0, mut y1) = (usize::MAX, 0);
        for (r, _) in &signed {
            (y0, y1) = (y0.min(r.y as usize), y1.max(r.bottom() as usize));
        }
        let mut cuts: Vec<usize> = Vec::with_capacity(4 * signed.len());
        for y in y0..y1 {
            cuts.clear();
            for &(r, _) in &signed {
                row_cuts(r, t, y, &mut cuts);
            }
            cuts.sort_unstable();
            cuts.dedup();
            for span in cuts.windows(2) {
                let (a, b) = (span[0], span[1]);
                let (mut dcover, mut dwall) = (0i8, 0i8);
                for &(r, sign) in &signed {
                    let (c, w) = cover_wall(r, t, a, y);
                    (dcover, dwall) = (dcover + sign * c, dwall + sign * w);
                }
                if dcover != 0 || dwall != 0 {
                    let base = y * self.width;
                    self.touch_run(base + a..base + b, dcover, dwall, 0, true);
                }
            }
        }
    }

    /// Adds or removes a door rectangle: its cells are predicted free.
    pub fn apply_door(&mut self, r: Rect, sign: i8) {
        self.write_pending();
        for y in r.y as usize..r.bottom() as usize {
            let base = y * self.width;
            self.touch_run(base + r.x as usize..base + r.right() as usize, 0, 0, sign, true);
        }
    }

    /// Recomputes everything from scratch for a set of unit and door rectangles; the incremental
    /// state must always equal this.
    pub fn recompute(map: &Grid<Cell>, units: &[Rect], t: i32, doors: &[Rect]) -> Self {
        let mut e = Explanation::new(map);
        let w = e.width;
        for c in e.cells.iter_mut() {
            *c = CellState::of_class(c.cm());
        }
        for r in units {
            for y in r.y..r.bottom() {
                for x in r.x..r.right() {
                    e.cells[y as usize * w + x as usize].0 += (1 << COVER) + ((r.in_ring(x, y, t) as u32) << WALL);
                }
            }
        }
        for r in doors {
            for y in r.y..r.bottom() {
                for x in r.x..r.right() {
                    e.cells[y as usize * w + x as usize].0 += 1 << DOOR;
                }
            }
        }
        e.confusion = [[0; 3]; 3];
        e.overlap = 0;
        for c in &e.cells {
            e.confusion[c.cm() as usize][c.predicted()] += 1;
            e.overlap += c.overlap();
        }
        e.unexplained = unexplained_bits(&e.cells);
        e
    }

    /// Whether two explanations agree on every counter, neither with a change pending.
    pub fn same_as(&self, other: &Explanation) -> bool {
        self.pending.is_none()
            && other.pending.is_none()
            && self.confusion == other.confusion
            && self.overlap == other.overlap
            && self.cells == other.cells
            && self.unexplained == other.unexplained
    }
}

/// The free-space detector asks which free cells no unit covers.
impl crate::vision::freespace::FreeSpace for Explanation {
    fn width(&self) -> usize {
        self.width
    }
    fn height(&self) -> usize {
        self.height
    }
    #[inline]
    fn is_unexplained(&self, i: usize) -> bool {
        let c = self.cells[i];
        c.cm() == Cell::Free as u8 && c.cover() == 0
    }

    /// The bits kept as the cells change (`Explanation::mark_unexplained`): `base` is a
    /// multiple of 64, as the detector's scan asks.
    #[inline]
    fn unexplained_word(&self, base: usize) -> u64 {
        debug_assert_eq!(base % 64, 0);
        self.unexplained.get(base / 64).copied().unwrap_or(0)
    }
}

/// Bit `j` set where `cells[j]` (at most 64) is free on the map and covered by no unit
/// ([`FreeSpace::is_unexplained`](crate::vision::freespace::FreeSpace::is_unexplained)).
fn unexplained_word(cells: &[CellState]) -> u64 {
    // Free (class 0) and covered by no unit: the record's two low bytes are zero.
    const _: () = assert!(Cell::Free as u32 == 0);
    const LOW: u32 = (1 << WALL) - 1;
    cells.iter().enumerate().fold(0u64, |w, (j, c)| w | (u64::from(c.0 & LOW == 0) << j))
}

/// [`unexplained_word`] of every 64 cells.
fn unexplained_bits(cells: &[CellState]) -> Vec<u64> {
    cells.chunks(64).map(unexplained_word).collect()
}

/// Where, along row `y`, what unit `r` (walls `t` deep) contributes to a cell may change: its
/// ends, and on rows between its top and bottom walls the ends of its interior. Nothing on rows
/// it does not cover.
fn row_cuts(r: Rect, t: usize, y: usize, cuts: &mut Vec<usize>) {
    let (x0, x1, top, bottom) = (r.x as usize, r.right() as usize, r.y as usize, r.bottom() as usize);
    if y < top || y >= bottom {
        return;
    }
    cuts.extend([x0, x1]);
    if !(y < top + t || y + t >= bottom) {
        let i0 = (x0 + t).min(x1);
        cuts.extend([i0, x1.saturating_sub(t).max(i0)]);
    }
}

/// What unit `r` (walls `t` deep) adds to cell (`x`, `y`): cover 1 inside it, and wall 1 on
/// its ring ([`Rect::in_ring`]), as [`Explanation::apply_unit`] and
/// [`Explanation::recompute`] count them.
fn cover_wall(r: Rect, t: usize, x: usize, y: usize) -> (i8, i8) {
    let (x, y) = (x as i32, y as i32);
    (i8::from(r.contains(x, y)), i8::from(r.in_ring(x, y, t as i32)))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn map() -> Grid<Cell> {
        let mut g = Grid::new(12, 9, Cell::Free);
        for x in 0..12 {
            *g.at_mut(x, 0) = Cell::Occupied;
            *g.at_mut(x, 8) = Cell::Unknown;
        }
        g
    }

    #[test]
    fn a_pending_unit_counts_at_once_and_its_undo_puts_the_counts_back() {
        let m = map();
        let mut e = Explanation::new(&m);
        let (a, b) = (Rect::new(0, 0, 6, 5), Rect::new(4, 2, 8, 7));
        e.apply_unit(a, 1, 1);
        e.apply_unit(b, 1, 1);
        let want = Explanation::recompute(&m, &[a, b], 1, &[]);
        assert!(e.pending.is_some() && !e.same_as(&want));
        assert_eq!((e.confusion(), e.overlap()), (want.confusion(), want.overlap()));
        // Undone: the counts are back and b's cells were never written.
        e.apply_unit(b, 1, -1);
        assert!(e.pending.is_none() && e.same_as(&Explanation::recompute(&m, &[a], 1, &[])));
        // Taken out, pending, then b put in: a's change is written first; then a door.
        e.apply_unit(a, 1, -1);
        e.apply_unit(b, 1, 1);
        e.apply_door(Rect::new(5, 3, 2, 1), 1);
        assert!(e.same_as(&Explanation::recompute(&m, &[b], 1, &[Rect::new(5, 3, 2, 1)])));
        e.apply_unit(b, 1, -1);
        e.write_pending();
        assert!(e.same_as(&Explanation::recompute(&m, &[], 1, &[Rect::new(5, 3, 2, 1)])));
    }

    /// A noisy map (the class changes every few cells, as a scan's does) and units that
    /// overlap, come and go and are replaced: the counts stay those of a recount, and the
    /// unexplained words those read cell by cell, on a map whose rows do not fill whole words.
    #[test]
    fn noisy_maps_keep_counts_and_unexplained_words_exact() {
        use crate::vision::freespace::FreeSpace;
        let (w, h) = (150, 70);
        let mut seed = 7u64;
        let mut next = move |n: u64| {
            seed = seed.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            ((seed >> 33) % n) as i32
        };
        let mut m = Grid::new(w, h, Cell::Free);
        for c in m.cells_mut() {
            *c = [Cell::Free, Cell::Free, Cell::Unknown, Cell::Occupied][next(4) as usize];
        }
        let word_by_cells = |e: &Explanation, base: usize| -> u64 {
            (base..(base + 64).min(w * h)).fold(0, |acc, i| acc | (u64::from(e.is_unexplained(i)) << (i - base)))
        };
        let mut e = Explanation::new(&m);
        let mut units: Vec<Rect> = Vec::new();
        for step in 0..60 {
            let (rw, rh) = (5 + next(30), 5 + next(20));
            let r = Rect::new(next(w as u64 - rw as u64), next(h as u64 - rh as u64), rw, rh);
            match step % 3 {
                0 => {
                    e.apply_unit(r, 2, 1);
                    units.push(r);
                }
                1 if !units.is_empty() => {
                    let old = units.remove(next(units.len() as u64) as usize);
                    e.replace_units(&[old], &[r], 2);
                    units.push(r);
                }
                _ => {
                    let i = next((w * h) as u64) as usize;
                    let cm = [Cell::Free, Cell::Unknown, Cell::Occupied][next(3) as usize];
                    e.set_map_class(i, cm);
                    m.cells_mut()[i] = cm;
                }
            }
            e.write_pending();
            assert!(e.same_as(&Explanation::recompute(&m, &units, 2, &[])), "step {step}");
            for base in (0..w * h).step_by(64) {
                assert_eq!(e.unexplained_word(base), word_by_cells(&e, base), "step {step}, word {}", base / 64);
            }
        }
        let unexplained = (0..w * h).filter(|&i| e.is_unexplained(i)).count();
        let free = m.cells().iter().filter(|&&c| c == Cell::Free).count();
        assert!(unexplained > 0 && unexplained < free, "both kinds of free cell: {unexplained} of {free}");
    }

    #[test]
    fn incremental_equals_recompute() {
        let m = map();
        let mut e = Explanation::new(&m);
        let a = Rect::new(0, 0, 6, 5);
        let b = Rect::new(4, 2, 8, 7);
        let d = Rect::new(5, 3, 2, 1);
        e.apply_unit(a, 1, 1);
        e.apply_unit(b, 1, 1);
        e.apply_door(d, 1);
        e.write_pending();
        assert!(e.same_as(&Explanation::recompute(&m, &[a, b], 1, &[d])));
        // a ∩ b is columns 4..6 x rows 2..5, six cells. a's ring there is column 5 and row 4,
        // b's is column 4 and row 2: (4, 4) and (5, 2) are wall for both (a shared wall, not
        // penalised); the other four are overlaps.
        assert_eq!(e.overlap(), 4);
        e.apply_unit(a, 1, -1);
        e.write_pending();
        assert!(e.same_as(&Explanation::recompute(&m, &[b], 1, &[d])));
        e.apply_door(d, -1);
        e.apply_unit(b, 1, -1);
        // Thick rings, including units that are all wall.
        for t in 2..5 {
            for r in [Rect::new(1, 1, 9, 7), Rect::new(0, 0, 4, 3), Rect::new(2, 3, 10, 6)] {
                e.apply_unit(r, t, 1);
                e.write_pending();
                assert!(e.same_as(&Explanation::recompute(&m, &[r], t, &[])), "{r:?} t={t}");
                e.apply_unit(r, t, -1);
            }
        }
        e.write_pending();
        assert!(e.same_as(&Explanation::new(&m)));
        let total: i64 = e.confusion().iter().flatten().sum();
        assert_eq!(total, 108);
    }

    #[test]
    fn replacing_units_equals_taking_them_out_and_putting_them_in() {
        let m = map();
        let rects = [
            Rect::new(0, 0, 6, 5),
            Rect::new(4, 2, 8, 7),
            Rect::new(1, 1, 9, 7),
            Rect::new(1, 1, 10, 7),
            Rect::new(1, 0, 9, 7),
            Rect::new(0, 0, 12, 9),
            Rect::new(2, 3, 3, 2),
            Rect::new(5, 1, 2, 8),
        ];
        let d = Rect::new(5, 3, 2, 1);
        for t in 1..4 {
            // Every one-for-one, one-for-two and two-for-one replacement among the rectangles,
            // over a world that already holds a unit and a door.
            for (i, &a) in rects.iter().enumerate() {
                for (j, &b) in rects.iter().enumerate() {
                    let c = rects[(i + j + 1) % rects.len()];
                    for (old, new) in [(vec![a], vec![b]), (vec![a], vec![b, c]), (vec![a, c], vec![b])] {
                        let mut e = Explanation::new(&m);
                        e.apply_unit(rects[6], t, 1);
                        e.apply_door(d, 1);
                        for &r in &old {
                            e.apply_unit(r, t, 1);
                        }
                        e.replace_units(&old, &new, t);
                        let units: Vec<Rect> = std::iter::once(rects[6]).chain(new.iter().copied()).collect();
                        assert!(e.same_as(&Explanation::recompute(&m, &units, t, &[d])), "{old:?} -> {new:?}, t={t}");
                    }
                }
            }
        }
    }

    #[test]
    fn prediction_rate_counts_matches() {
        let m = map();
        let mut e = Explanation::new(&m);
        // Empty world predicts unknown everywhere: only the 12 unknown cells match.
        assert_eq!(e.prediction_rate(), 12.0 / 108.0);
        // A unit over rows 0..8: row 0 wall (occupied: match), rows 1..7 interior free except
        // the side columns (walls, mismatching free map cells), row 7 bottom wall mismatch.
        e.apply_unit(Rect::new(0, 0, 12, 8), 1, 1);
        e.write_pending();
        let hits = 12 + 10 * 6 + 12;
        assert_eq!(e.prediction_rate(), hits as f64 / 108.0);
        assert_eq!(e.predicted(0, 3), Cell::Occupied);
        assert_eq!(e.predicted(3, 3), Cell::Free);
        assert_eq!(e.predicted(3, 8), Cell::Unknown);
    }
}
