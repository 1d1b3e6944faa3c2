//! The free-space unit (FSU) detector (Fig. 3.13): connected components of free cells that the
//! current world leaves unexplained become unit candidates, for rooms whose walls the WBU
//! detector missed (unexplored or hidden behind furniture).

use crate::geometry::Rect;
use crate::grid::flood::{Flood, Neighbours};
use crate::grid::{Cell, Grid};

/// What the detector sees: a grid of cells, some of them free space the current world leaves
/// unexplained (the chain's explanation implements it; so does a bare map, as the empty world).
pub trait FreeSpace {
    /// Grid width.
    fn width(&self) -> usize;
    /// Grid height.
    fn height(&self) -> usize;
    /// Whether cell `i` (row-major, `y * width + x`) is free on the map and covered by no
    /// unit.
    fn is_unexplained(&self, i: usize) -> bool;

    /// Bit `j` set where cell `base + j` is unexplained, for the cells of the map among
    /// `base..base + 64` ([`FreeSpace::is_unexplained`] a word at a time); `base` is a multiple
    /// of 64. The chain's explanation keeps these words as its cells change.
    fn unexplained_word(&self, base: usize) -> u64 {
        let cells = self.width() * self.height();
        let mut word = 0u64;
        for i in base..(base + 64).min(cells) {
            word |= u64::from(self.is_unexplained(i)) << (i - base);
        }
        word
    }
}

/// A map explained by the empty world: every free cell is unexplained.
impl FreeSpace for Grid<Cell> {
    fn width(&self) -> usize {
        Grid::width(self)
    }
    fn height(&self) -> usize {
        Grid::height(self)
    }
    fn is_unexplained(&self, i: usize) -> bool {
        self.cells()[i] == Cell::Free
    }
}

/// Bounding boxes (grown by one cell for the walls) of 4-connected components of free cells
/// covered by no unit, holding at least `min_cells` cells, each trimmed to its dense core: sides
/// whose edge row or column is less than 40 % unexplained free space are moved inwards, so
/// that a fan of scan rays yields the dense part near its source rather than a box that is
/// mostly unknown.
pub fn unexplained(e: &impl FreeSpace, min_cells: usize) -> Vec<Rect> {
    unexplained_with(e, min_cells, &mut Scratch::default())
}

/// Working memory of the detector, kept by a caller that runs it again and again (the chain
/// refreshes it every few hundred iterations): a map-sized visited mask and a stack, which
/// would otherwise be allocated and zeroed, page by page, at every refresh.
#[derive(Debug, Clone, Default)]
pub struct Scratch {
    /// One bit a cell (a byte a cell would be 1.5 MB on a rotated 1237x672 map).
    seen: Vec<u64>,
    /// The flood fill's stack.
    flood: Flood,
}

/// [`unexplained`] with working memory the caller keeps between calls.
pub fn unexplained_with(e: &impl FreeSpace, min_cells: usize, scratch: &mut Scratch) -> Vec<Rect> {
    let boxes = components(e, min_cells, scratch);
    if boxes.is_empty() {
        return boxes;
    }
    boxes.into_iter().filter_map(|b| dense_core(e, b)).collect()
}

/// Unexplained free cells in `r` (clipped to the map), counted cell by cell: `dense_core`
/// only asks about one-cell lines, and a summed-area table of the whole map, rebuilt at every
/// refresh, cost more than all its questions (and 4 bytes a cell).
fn unexplained_in(e: &impl FreeSpace, r: Rect) -> u32 {
    let (w, h) = (e.width() as i32, e.height() as i32);
    let mut n = 0;
    for y in r.y.max(0)..r.bottom().min(h) {
        for x in r.x.max(0)..r.right().min(w) {
            n += e.is_unexplained(y as usize * w as usize + x as usize) as u32;
        }
    }
    n
}

fn dense_core(e: &impl FreeSpace, mut r: Rect) -> Option<Rect> {
    let count = |line: Rect| unexplained_in(e, line);
    let dense = |line: Rect| count(line) as f64 >= 0.4 * line.area() as f64;
    loop {
        if r.w < 3 || r.h < 3 {
            return None;
        }
        let sides = [
            Rect::new(r.x + 1, r.y, 1, r.h),
            Rect::new(r.right() - 2, r.y, 1, r.h),
            Rect::new(r.x, r.y + 1, r.w, 1),
            Rect::new(r.x, r.bottom() - 2, r.w, 1),
        ];
        // Trim the sparsest side first, one cell at a time.
        let worst = (0..4).filter(|&i| !dense(sides[i])).min_by(|&a, &b| {
            let fa = count(sides[a]) as f64 / sides[a].area() as f64;
            let fb = count(sides[b]) as f64 / sides[b].area() as f64;
            fa.total_cmp(&fb)
        });
        match worst {
            None => return Some(r),
            Some(0) => r = Rect::new(r.x + 1, r.y, r.w - 1, r.h),
            Some(1) => r = Rect::new(r.x, r.y, r.w - 1, r.h),
            Some(2) => r = Rect::new(r.x, r.y + 1, r.w, r.h - 1),
            _ => r = Rect::new(r.x, r.y, r.w, r.h - 1),
        }
    }
}

fn components(e: &impl FreeSpace, min_cells: usize, scratch: &mut Scratch) -> Vec<Rect> {
    let (w, h) = (e.width(), e.height());
    let Scratch { seen, flood } = scratch;
    seen.clear();
    seen.resize((w * h).div_ceil(64), 0);
    let mut out = Vec::new();
    scan_words(e, &mut |e, start, seen| component(e, start, min_cells, seen, flood, &mut out), seen);
    out
}

/// Calls `found(e, start, seen)` for each unexplained cell not yet `seen`, in cell order
/// (`found` marks its component seen), reading a word of 64 cells at a time. Once the chain
/// has covered most of the floor most of the map is explained, and reading a cell at a time
/// (`scan_cells`) was most of a refresh's cost.
fn scan_words<E: FreeSpace>(e: &E, found: &mut dyn FnMut(&E, usize, &mut [u64]), seen: &mut [u64]) {
    for k in 0..seen.len() {
        let base = 64 * k;
        let mut fresh = e.unexplained_word(base);
        loop {
            fresh &= !seen[k];
            if fresh == 0 {
                break;
            }
            found(e, base + fresh.trailing_zeros() as usize, seen);
        }
    }
}

/// [`scan_words`] a cell at a time: the same cells in the same order, which a test holds the
/// word scan to.
#[cfg(test)]
fn scan_cells<E: FreeSpace>(e: &E, found: &mut dyn FnMut(&E, usize, &mut [u64]), seen: &mut [u64]) {
    for start in 0..e.width() * e.height() {
        if seen[start / 64] & (1 << (start % 64)) == 0 && e.is_unexplained(start) {
            found(e, start, seen);
        }
    }
}

/// The component of `start` (unexplained, not yet seen), flooded and marked seen; its box
/// grown by one cell onto `out` if it holds at least `min_cells` cells.
fn component(
    e: &impl FreeSpace,
    start: usize,
    min_cells: usize,
    seen: &mut [u64],
    flood: &mut Flood,
    out: &mut Vec<Rect>,
) {
    let (w, h) = (e.width(), e.height());
    // Marks cell `i` seen; false if it already was.
    let mark = |seen: &mut [u64], i: usize| {
        let (word, bit) = (i / 64, 1u64 << (i % 64));
        let fresh = seen[word] & bit == 0;
        seen[word] |= bit;
        fresh
    };
    let (sx, sy) = (start % w, start / w);
    let (mut x0, mut y0, mut x1, mut y1, mut n) = (sx, sy, sx, sy, 0usize);
    let enter = |j: usize| e.is_unexplained(j) && mark(seen, j);
    flood.fill(w, h, [start], Neighbours::Four, enter, |i| {
        let (x, y) = (i % w, i / w);
        n += 1;
        (x0, y0, x1, y1) = (x0.min(x), y0.min(y), x1.max(x), y1.max(y));
    });
    if n >= min_cells {
        let gx0 = x0.saturating_sub(1);
        let gy0 = y0.saturating_sub(1);
        let gx1 = (x1 + 1).min(w - 1);
        let gy1 = (y1 + 1).min(h - 1);
        out.push(Rect::new(gx0 as i32, gy0 as i32, (gx1 - gx0 + 1) as i32, (gy1 - gy0 + 1) as i32));
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Free rectangles on an unknown background.
    fn map(w: usize, h: usize, rooms: &[(usize, usize, usize, usize)]) -> Grid<Cell> {
        let mut g = Grid::new(w, h, Cell::Unknown);
        for &(x0, y0, rw, rh) in rooms {
            for y in y0..y0 + rh {
                for x in x0..x0 + rw {
                    *g.at_mut(x, y) = Cell::Free;
                }
            }
        }
        g
    }

    #[test]
    fn kept_scratch_gives_the_same_candidates_as_fresh_memory() {
        let big = map(90, 70, &[(5, 5, 30, 20), (50, 10, 25, 40), (10, 40, 8, 8)]);
        let small = map(40, 30, &[(2, 2, 20, 12), (25, 15, 10, 10)]);
        let mut scratch = Scratch::default();
        // Big map, then a smaller one (stale bits past its end), then the big one again.
        for e in [&big, &small, &big, &small] {
            assert_eq!(unexplained_with(e, 60, &mut scratch), unexplained(e, 60));
        }
        // The rooms' boxes, grown by one cell for the walls; the 8x8 room (64 cells) is above
        // the 60-cell floor, and the largest room (1000 cells) is the only one at 1000.
        let found = unexplained(&big, 60);
        assert_eq!(found.len(), 3, "{found:?}");
        assert!(found.contains(&Rect::new(4, 4, 32, 22)), "{found:?}");
        assert_eq!(unexplained(&big, 1000), vec![Rect::new(49, 9, 27, 42)]);
        assert!(unexplained(&big, 1001).is_empty());
    }

    /// A scan of a map: [`scan_cells`] or [`scan_words`].
    type Scan = fn(&Grid<Cell>, &mut dyn FnMut(&Grid<Cell>, usize, &mut [u64]), &mut [u64]);

    #[test]
    fn the_word_scan_finds_the_cells_the_cell_scan_finds_in_order() {
        // Unexplained cells scattered over a map whose size is no multiple of 64, and some
        // already seen: both scans must report the same starts in the same order.
        let (w, h) = (37, 23);
        let mut g = Grid::new(w, h, Cell::Unknown);
        let mut x = 12345u64;
        for c in g.cells_mut() {
            x = x.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            if (x >> 33) % 3 == 0 {
                *c = Cell::Free;
            }
        }
        let mut seen0 = vec![0u64; (w * h).div_ceil(64)];
        for (k, s) in seen0.iter_mut().enumerate() {
            *s = 0x9e37_79b9_7f4a_7c15u64.rotate_left(k as u32 * 7);
        }
        let run = |scan: Scan| {
            let mut seen = seen0.clone();
            let mut starts = Vec::new();
            // Each start marks itself and the cell after it seen, as a small component would.
            scan(
                &g,
                &mut |_, i, seen| {
                    starts.push(i);
                    for j in [i, i + 1] {
                        if j < w * h {
                            seen[j / 64] |= 1 << (j % 64);
                        }
                    }
                },
                &mut seen,
            );
            (starts, seen)
        };
        let (cells, words) = (run(scan_cells), run(scan_words));
        assert!(cells.0.len() > 50, "{}", cells.0.len());
        assert_eq!(cells, words);
    }
}
