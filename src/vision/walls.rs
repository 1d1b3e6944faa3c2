//! The wall-based unit (WBU) detector (eqs. 3.10 - 3.17, Fig. 3.12).
//!
//! In the upright world frame, walls are horizontal or vertical, so the Hough transform reduces
//! to its 0° and 90° columns: the occupied cells of each row and each column. A row holding a
//! long run of occupied cells is a wall line; adjacent wall rows are one thick wall, whose two
//! faces are both places where a unit's wall ring can sit. Extending every wall line across the
//! map divides it into sub-areas; every rectangle whose four sides lie on wall lines is a
//! recombination of sub-areas and a unit candidate. Candidates are weighted by their weakest
//! wall (eq. 3.10), each wall by its share of occupied cells (eq. 3.11).

use crate::geometry::{AreaCounts, Rect};
use crate::grid::{Cell, Grid};
use crate::setting::{check, InvalidSetting};

/// Parameters of the WBU detector, in cells of one map ([`WallSizes::cells`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WallConfig {
    /// Shortest run of occupied cells that counts as a wall segment.
    pub min_segment: i32,
    /// Largest gap (cells) bridged inside a wall segment (scan dropouts).
    pub max_gap: i32,
    /// Most wall lines kept per axis, strongest first.
    pub max_lines: usize,
    /// Smallest wall weight `ω_w` a candidate's walls may have.
    pub min_wall_weight: f64,
    /// Most candidates kept, best weights first.
    pub max_candidates: usize,
    /// Tolerance (cells) across a wall when scoring it: real walls are thick and scanned
    /// jaggedly (more so after rotating the map), so a wall cell counts as matched when an
    /// occupied cell lies within this distance.
    pub tolerance: i32,
    /// Exponent applied to candidate weights before ADD draws from them: above 1, clear rooms
    /// are proposed (and so added) well before ambiguous rectangles.
    pub sharpness: f64,
}

impl Default for WallConfig {
    fn default() -> Self {
        WallConfig {
            min_segment: 12,
            max_gap: 2,
            max_lines: 40,
            min_wall_weight: 0.35,
            max_candidates: 60_000,
            tolerance: 2,
            sharpness: 3.0,
        }
    }
}

/// The wall detector's settings as a chain's configuration gives them, lengths in metres:
/// [`WallConfig`] in cells of one map comes from them ([`WallSizes::cells`]).
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct WallSizes {
    /// Shortest run of occupied cells that counts as a wall segment, m. 0.6 m: longer than a
    /// door jamb or a table's edge seen by a laser.
    pub min_segment_m: f64,
    /// Largest gap bridged inside a wall segment (scan dropouts), m. 0.1 m.
    pub max_gap_m: f64,
    /// Most wall lines kept per axis, strongest first.
    pub max_lines: usize,
    /// Smallest wall weight `ω_w` a candidate's walls may have.
    pub min_wall_weight: f64,
    /// Most candidates kept, best weights first.
    pub max_candidates: usize,
    /// Tolerance across a wall when scoring it, m. 0.1 m: a wall's thickness and a laser's
    /// noise.
    pub tolerance_m: f64,
    /// Exponent applied to candidate weights before ADD draws from them.
    pub sharpness: f64,
}

impl Default for WallSizes {
    fn default() -> Self {
        let c = WallConfig::default();
        WallSizes {
            min_segment_m: 0.6,
            max_gap_m: 0.1,
            max_lines: c.max_lines,
            min_wall_weight: c.min_wall_weight,
            max_candidates: c.max_candidates,
            tolerance_m: 0.1,
            sharpness: c.sharpness,
        }
    }
}

impl WallSizes {
    /// These settings in cells of `resolution` metres (lengths rounded; a segment at least 2
    /// cells). A resolution that is not a positive number is read as 0.05 m.
    ///
    /// ```
    /// use ksmcmc::vision::walls::{WallConfig, WallSizes};
    /// assert_eq!(WallSizes::default().cells(0.05), WallConfig::default());
    /// assert_eq!(WallSizes::default().cells(0.1).min_segment, 6);
    /// ```
    pub fn cells(&self, resolution: f64) -> WallConfig {
        let r = crate::grid::cell_size_m(resolution);
        let cells = |m: f64| libm::round(m / r).clamp(0.0, 1e6) as i32;
        WallConfig {
            min_segment: cells(self.min_segment_m).max(2),
            max_gap: cells(self.max_gap_m),
            max_lines: self.max_lines,
            min_wall_weight: self.min_wall_weight,
            max_candidates: self.max_candidates,
            tolerance: cells(self.tolerance_m),
            sharpness: self.sharpness,
        }
    }

    /// Checks the settings, naming the field at fault.
    pub fn validate(&self) -> Result<(), InvalidSetting> {
        for (name, v) in
            [("min_segment_m", self.min_segment_m), ("max_gap_m", self.max_gap_m), ("tolerance_m", self.tolerance_m)]
        {
            check((0.0..=100.0).contains(&v), name, v, "metres from 0 to 100")?;
        }
        check((0.0..=1.0).contains(&self.min_wall_weight), "min_wall_weight", self.min_wall_weight, "from 0 to 1")
    }
}

/// A wall line: consecutive rows (or columns) `lo..=hi` holding wall segments.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct WallLine {
    /// First row (column) of the wall.
    pub lo: i32,
    /// Last row (column) of the wall.
    pub hi: i32,
    /// Cells in wall segments on the strongest row (column).
    pub strength: u32,
}

/// Cells of `line` that lie in occupied runs of at least `min` cells, gaps up to `gap` bridged.
fn segment_cells(line: impl Iterator<Item = bool>, min: i32, gap: i32) -> u32 {
    let (mut total, mut run, mut holes, mut since) = (0u32, 0i32, 0i32, 0i32);
    let flush = |run: i32, holes: i32, total: &mut u32| {
        if run - holes >= min {
            *total += (run - holes) as u32;
        }
    };
    for occ in line {
        if occ {
            if run > 0 && since > 0 {
                holes += since;
                run += since;
            }
            run += 1;
            since = 0;
        } else if run > 0 {
            since += 1;
            if since > gap {
                flush(run, holes, &mut total);
                (run, holes, since) = (0, 0, 0);
            }
        }
    }
    flush(run, holes, &mut total);
    total
}

/// Horizontal (`rows = true`) or vertical wall lines of a world-frame map.
pub fn wall_lines(grid: &Grid<Cell>, rows: bool, c: &WallConfig) -> Vec<WallLine> {
    let (n, len) = if rows { (grid.height(), grid.width()) } else { (grid.width(), grid.height()) };
    let strength: Vec<u32> = (0..n)
        .map(|i| {
            let cells = (0..len).map(|j| {
                let (x, y) = if rows { (j, i) } else { (i, j) };
                *grid.at(x, y) == Cell::Occupied
            });
            segment_cells(cells, c.min_segment, c.max_gap)
        })
        .collect();
    let mut lines = Vec::new();
    let mut i = 0;
    while i < n {
        if strength[i] == 0 {
            i += 1;
            continue;
        }
        let lo = i;
        let mut best = 0;
        while i < n && strength[i] > 0 {
            best = best.max(strength[i]);
            i += 1;
        }
        lines.push(WallLine { lo: lo as i32, hi: i as i32 - 1, strength: best });
    }
    // Keep the strongest, then restore positional order.
    crate::sort::sort_by(&mut lines, |a, b| b.strength.cmp(&a.strength).then(a.lo.cmp(&b.lo)));
    lines.truncate(c.max_lines);
    crate::sort::sort_by_key(&mut lines, |l| l.lo);
    lines
}

fn faces(lines: &[WallLine]) -> Vec<i32> {
    let mut v: Vec<i32> = lines.iter().flat_map(|l| [l.lo, l.hi]).collect();
    crate::sort::sort(&mut v);
    v.dedup();
    v
}

/// Unit candidates with their weights, strongest first: `ω_r` of eq. 3.10 (the weakest wall),
/// times `(1 - f)^2` where `f` is the strongest detected wall line crossing the interior, so
/// that rectangles spanning several rooms are proposed less often than the rooms, times the
/// fourth power of the free share of the interior, so that rectangles over unexplored space
/// are proposed less often than rooms.
pub fn candidates(grid: &Grid<Cell>, min_side: i32, c: &WallConfig) -> Vec<(Rect, f64)> {
    candidates_where(grid, &faces_of(grid, c), min_side, c, &|_| true)
}

/// The wall faces the detector builds candidates on: the columns (`.0`) and rows (`.1`) of
/// the sides of the detected wall lines, sorted.
pub fn faces_of(grid: &Grid<Cell>, c: &WallConfig) -> (Vec<i32>, Vec<i32>) {
    (faces(&wall_lines(grid, false, c)), faces(&wall_lines(grid, true, c)))
}

/// [`candidates`] on the faces `faces` ([`faces_of`] of `grid`, which the chain keeps),
/// restricted to the rectangles `keep` accepts, which are the only ones scored: after a map
/// changes in one place, the online chain rescores only the rectangles the change can reach
/// (see `Chain::update_map`).
pub fn candidates_where(
    grid: &Grid<Cell>,
    faces: &(Vec<i32>, Vec<i32>),
    min_side: i32,
    c: &WallConfig,
    keep: &(dyn Fn(Rect) -> bool + Sync),
) -> Vec<(Rect, f64)> {
    // Three map-sized tables, two on the other core.
    let ((occ, free), raw) = crate::threads::join(
        || (AreaCounts::new(&dilate(grid, c.tolerance), Cell::Occupied), AreaCounts::new(grid, Cell::Free)),
        // Walls crossing a candidate are judged on the raw map: dilation would close doors.
        || AreaCounts::new(grid, Cell::Occupied),
    );
    let faces = Faces { occ, free, raw, xs: &faces.0, ys: &faces.1, min_side, c, keep };
    let mut out = faces.all();
    strongest_first(&mut out, c.max_candidates);
    out
}

/// Sorts candidates strongest first and keeps the first `max`. The order is total (no two
/// candidates are the same rectangle), so the list is the same whatever order the left sides
/// were taken in, and whichever sort makes it.
fn strongest_first(out: &mut Vec<(Rect, f64)>, max: usize) {
    let order = |a: &(Rect, f64), b: &(Rect, f64)| {
        b.1.total_cmp(&a.1).then_with(|| (a.0.x, a.0.y, a.0.w, a.0.h).cmp(&(b.0.x, b.0.y, b.0.w, b.0.h)))
    };
    // Natively the strongest `max` are picked first and only they sorted: Cartesium's 321,000
    // candidates, of which 60,000 are kept, took 13 ms to sort whole, and every chain's setup
    // waits for them. The mapper module keeps the one sort it has (code size).
    #[cfg(not(target_arch = "wasm32"))]
    {
        if out.len() > max {
            out.select_nth_unstable_by(max, order);
            out.truncate(max);
        }
        out.sort_unstable_by(order);
    }
    // The standard sort itself: crate::sort's indirect comparisons cost Cartesium's about
    // 15 ms, for 3 kB.
    #[cfg(target_arch = "wasm32")]
    {
        out.sort_by(order);
        out.truncate(max);
    }
}

/// What [`candidates_where`] builds its candidates on: the area counts of the map and the wall
/// faces, each candidate's sides on four of them.
struct Faces<'a> {
    /// Occupied cells of the map dilated by the wall tolerance.
    occ: AreaCounts,
    /// Free cells.
    free: AreaCounts,
    /// Occupied cells of the raw map.
    raw: AreaCounts,
    /// The columns and rows of the wall faces, sorted.
    xs: &'a [i32],
    ys: &'a [i32],
    min_side: i32,
    c: &'a WallConfig,
    keep: &'a (dyn Fn(Rect) -> bool + Sync),
}

/// Wall faces per thread, at the least: a left side's candidates take milliseconds on a large
/// map (Cartesium: 78 faces, 0.2 s), a thread starts in tens of microseconds.
#[cfg(not(target_arch = "wasm32"))]
const FACES_PER_THREAD: usize = 16;

impl Faces<'_> {
    /// Every candidate, left side by left side: natively the left sides dealt round the
    /// machine's cores (at most four; each left side's candidates are independent of the
    /// others'), in WebAssembly on one thread.
    fn all(&self) -> Vec<(Rect, f64)> {
        let n = self.xs.len();
        #[cfg(not(target_arch = "wasm32"))]
        {
            let threads = crate::threads::threads_for(n, FACES_PER_THREAD);
            if threads > 1 {
                return std::thread::scope(|s| {
                    let handles: Vec<_> =
                        (0..threads).map(|k| s.spawn(move || self.with_lefts((k..n).step_by(threads)))).collect();
                    handles
                        .into_iter()
                        .flat_map(|h| h.join().unwrap_or_else(|e| std::panic::resume_unwind(e)))
                        .collect()
                });
            }
        }
        self.with_lefts(0..n)
    }

    /// The candidates whose left side is on the faces `lefts` (indices into `xs`).
    fn with_lefts(&self, lefts: impl Iterator<Item = usize>) -> Vec<(Rect, f64)> {
        let mut out = Vec::new();
        let mut ok_rows = Vec::with_capacity(self.ys.len());
        for a in lefts {
            self.with_left(a, &mut ok_rows, &mut out);
        }
        out
    }

    /// The candidates whose left side is on face `xs[a]`, pushed onto `out` (`ok_rows` is
    /// working memory).
    fn with_left(&self, a: usize, ok_rows: &mut Vec<(usize, f64)>, out: &mut Vec<(Rect, f64)>) {
        let (xs, ys, c) = (&self.xs, &self.ys, self.c);
        let frac = |r: Rect| self.occ.count(r) as f64 / r.area().max(1) as f64;
        let x0 = xs[a];
        // Indices into the faces: the first face more than two cells inside a candidate's left
        // side, and the first at most two cells inside its right side.
        let x_in = xs.partition_point(|&x| x <= x0 + 2);
        let mut x_out = x_in;
        for &x1 in &xs[a + 1..] {
            let w = x1 - x0 + 1;
            if w < self.min_side {
                continue;
            }
            while x_out < xs.len() && xs[x_out] < x1 - 2 {
                x_out += 1;
            }
            // Rows where a horizontal wall spans x0..=x1 well enough (eq. 3.11).
            ok_rows.clear();
            ok_rows.extend(
                (0..ys.len()).map(|i| (i, frac(Rect::new(x0, ys[i], w, 1)))).filter(|&(_, f)| f >= c.min_wall_weight),
            );
            for (b, &(i0, f0)) in ok_rows.iter().enumerate() {
                let y0 = ys[i0];
                // The most raw wall cells along a face row strictly inside, grown as y1 moves
                // down; `y_out` is the first row not yet counted.
                let (mut y_out, mut most_h) = (i0, 0);
                for &(i1, f1) in &ok_rows[b + 1..] {
                    let y1 = ys[i1];
                    let h = y1 - y0 + 1;
                    if h < self.min_side || !(self.keep)(Rect::new(x0, y0, w, h)) {
                        continue;
                    }
                    let fl = frac(Rect::new(x0, y0, 1, h));
                    let fr = frac(Rect::new(x1, y0, 1, h));
                    let weight = f0.min(f1).min(fl).min(fr);
                    if weight >= c.min_wall_weight {
                        // A wall line crossing the interior means the candidate spans two rooms:
                        // keep it (the lines may be spurious) but propose it less often. The
                        // largest count over the area is the largest share: the division is
                        // monotone, so dividing once gives the same bits.
                        while ys[y_out] < y1 - 2 {
                            if ys[y_out] > y0 + 2 {
                                most_h = most_h.max(self.raw.count(Rect::new(x0, ys[y_out], w, 1)));
                            }
                            y_out += 1;
                        }
                        let most_v = xs[x_in..x_out].iter().map(|&x| self.raw.count(Rect::new(x, y0, 1, h))).max();
                        let r = Rect::new(x0, y0, w, h);
                        let score = candidate_score(r, weight, [most_h, most_v.unwrap_or(0)], &self.free, c);
                        if score > 0.0 {
                            out.push((r, score));
                        }
                    }
                }
            }
        }
    }
}

/// The score of candidate `r` whose four walls span it with `weight` (eq. 3.11): lowered by
/// the wall line crossing its interior with the most raw wall cells (`most`: along a row,
/// along a column), and by the share of its interior that is not free.
fn candidate_score(r: Rect, weight: f64, most: [u32; 2], free: &AreaCounts, c: &WallConfig) -> f64 {
    let inner_h = most[0] as f64 / r.w as f64;
    let inner_v = most[1] as f64 / r.h as f64;
    let open = 1.0 - inner_h.max(inner_v);
    // Rooms are mostly free inside; a rectangle over unexplored space is not.
    let inside = Rect::new(r.x + 1, r.y + 1, r.w - 2, r.h - 2);
    let fill = free.count(inside) as f64 / inside.area().max(1) as f64;
    libm::pow(weight * open * open * fill.powi(4), c.sharpness)
}

/// Occupied cells grown by `r` cells in every direction (a square max filter,
/// [`crate::grid::morphology::dilate`]); the other cells keep their class.
pub fn dilate(grid: &Grid<Cell>, r: i32) -> Grid<Cell> {
    if r <= 0 {
        return grid.clone();
    }
    let grown = crate::grid::morphology::dilate(&grid.map(|&c| c == Cell::Occupied), r as usize);
    let mut out = grid.clone();
    for (c, &g) in out.cells_mut().iter_mut().zip(grown.cells()) {
        if g {
            *c = Cell::Occupied;
        }
    }
    out
}

/// The deepest unit wall ring, metres, measured ([`ring_depth`]) or configured
/// (`ChainConfig::wall_thickness_m`): 0.5 m, an old outer wall of brick or stone; a thicker run
/// of occupied cells is furniture against a wall or unexplored space drawn dark. Ten cells at
/// 5 cm, as it was set in cells.
pub const MAX_RING_M: f64 = 0.5;

/// [`MAX_RING_M`] in whole cells of `resolution` metres (at least one).
pub fn max_ring_cells(resolution: f64) -> i32 {
    (crate::grid::whole_cells(MAX_RING_M, resolution) as i32).max(1)
}

/// The depth of unit wall rings that best explains this map's walls: the typical wall
/// thickness, measured on the original map along the two wall directions of its dominant
/// orientation `angle` (radians): for each occupied cell, the shorter of the two runs of
/// occupied cells through it along those axes; the median `d` over cells, clamped to 1 ..=
/// [`MAX_RING_M`] in cells of the map's `resolution` (metres a cell).
///
/// Why the whole thickness: a ring as deep as the wall predicts every cell of an outer wall,
/// and two units sharing an inner wall both lay their rings on it (a shared wall costs no
/// overlap penalty, see the floor plan's posterior). Scanned walls are thin and give 1 or
/// 2; the dissertation's model is 1. Measured on the original map, not the rotated world
/// frame, so that resampling does not double thin walls. On our maps this rule picked the
/// best or nearly the best depth for K(W, M) (see BENCHMARKS.md).
pub fn ring_depth(grid: &Grid<Cell>, angle: f64, resolution: f64) -> i32 {
    depth_bridging(grid, angle, 0, max_ring_cells(resolution))
}

/// [`ring_depth`] of a map whose walls a robot saw from inside the rooms either side of them
/// (a map growing while it explores): a range sensor sees only a wall's two faces, and the
/// cells between them stay unknown. A run of occupied cells here goes on across up to
/// [`MAX_UNSEEN_WALL_CORE_M`] of unknown cells to occupied cells beyond, so a wall seen from both
/// sides (face, unseen core, face) counts as one wall as thick as all three. Walls seen from
/// one side only (outer walls, walls of rooms not yet entered) still count as their face.
///
/// ```
/// use ksmcmc::grid::{Cell, Grid};
/// use ksmcmc::vision::walls::{ring_depth, ring_depth_seen_from_both_sides};
///
/// // Walls along columns: faces at x and x + 2 with an unseen core between, rooms either side.
/// let mut g = Grid::new(60, 40, Cell::Free);
/// for y in 0..40 {
///     for x in [10, 30, 50] {
///         *g.at_mut(x, y) = Cell::Occupied;
///         *g.at_mut(x + 1, y) = Cell::Unknown;
///         *g.at_mut(x + 2, y) = Cell::Occupied;
///     }
/// }
/// assert_eq!(ring_depth(&g, 0.0, 0.05), 1);
/// assert_eq!(ring_depth_seen_from_both_sides(&g, 0.0, 0.05), 3);
/// ```
pub fn ring_depth_seen_from_both_sides(grid: &Grid<Cell>, angle: f64, resolution: f64) -> i32 {
    let core = crate::grid::whole_cells(MAX_UNSEEN_WALL_CORE_M, resolution).max(1.0) as usize;
    depth_bridging(grid, angle, core, max_ring_cells(resolution))
}

/// The widest unseen core between two occupied faces, metres, that
/// [`ring_depth_seen_from_both_sides`] takes for the inside of one wall: 0.4 m, the thickest
/// wall ([`MAX_RING_M`]) less its two faces; eight cells at 5 cm, as it was set in cells.
pub const MAX_UNSEEN_WALL_CORE_M: f64 = 0.4;

/// [`ring_depth`], with runs of occupied cells going on across up to `bridge` unknown cells to
/// an occupied one, clamped to `max` cells (runs are counted up to `max`: the median of the
/// clamped runs is the clamped median).
fn depth_bridging(grid: &Grid<Cell>, angle: f64, bridge: usize, max: i32) -> i32 {
    let max = max.max(1) as usize;
    let (w, h) = (grid.width() as i64, grid.height() as i64);
    let class = |x: f64, y: f64| {
        let (cx, cy) = (libm::floor(x) as i64, libm::floor(y) as i64);
        (cx >= 0 && cy >= 0 && cx < w && cy < h).then(|| *grid.at(cx as usize, cy as usize))
    };
    let occ = |x: f64, y: f64| class(x, y) == Some(Cell::Occupied);
    let (s, c) = (libm::sin(angle), libm::cos(angle));
    let axes = [(c, s), (-s, c)];
    // Unknown cells from step k on, then an occupied one: how many unknown ones (0: none).
    let unseen_core = |x: f64, y: f64, (dx, dy): (f64, f64), sign: f64, k: f64| -> usize {
        let mut j = 0;
        while j < bridge && class(x + sign * (k + j as f64) * dx, y + sign * (k + j as f64) * dy) == Some(Cell::Unknown)
        {
            j += 1;
        }
        let beyond = k + j as f64;
        if j > 0 && occ(x + sign * beyond * dx, y + sign * beyond * dy) {
            j
        } else {
            0
        }
    };
    let run = |x: f64, y: f64, (dx, dy): (f64, f64)| -> usize {
        let mut n = 1;
        for sign in [1.0, -1.0] {
            let mut k = 1.0;
            while n < max {
                if occ(x + sign * k * dx, y + sign * k * dy) {
                    n += 1;
                    k += 1.0;
                    continue;
                }
                let core = unseen_core(x, y, (dx, dy), sign, k);
                if core == 0 {
                    break;
                }
                n += core;
                k += core as f64;
            }
        }
        n
    };
    let total_occ = grid.cells().iter().filter(|&&c| c == Cell::Occupied).count();
    let stride = (total_occ / 20_000).max(1);
    let mut hist = vec![0u64; max + 1];
    let mut k = 0;
    for y in 0..h {
        for x in 0..w {
            if *grid.at(x as usize, y as usize) != Cell::Occupied {
                continue;
            }
            k += 1;
            if k % stride != 0 {
                continue;
            }
            let (fx, fy) = (x as f64 + 0.5, y as f64 + 0.5);
            let d = run(fx, fy, axes[0]).min(run(fx, fy, axes[1]));
            hist[d.min(max)] += 1;
        }
    }
    let total: u64 = hist.iter().sum();
    if total == 0 {
        return 1;
    }
    let mut acc = 0;
    let median = (0..hist.len()).find(|&d| {
        acc += hist[d];
        2 * acc >= total
    });
    (median.unwrap_or(1) as i32).clamp(1, max as i32)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn dilation_grows_by_r() {
        let mut g = Grid::new(9, 7, Cell::Free);
        *g.at_mut(4, 3) = Cell::Occupied;
        let d = dilate(&g, 2);
        for y in 0..7i64 {
            for x in 0..9i64 {
                let inside = (x - 4).abs() <= 2 && (y - 3).abs() <= 2;
                assert_eq!(*d.get(x, y).unwrap() == Cell::Occupied, inside, "({x},{y})");
            }
        }
        assert_eq!(dilate(&g, 0), g);
    }

    #[test]
    fn ring_depth_measures_wall_thickness() {
        for d in 1..=4usize {
            // A room outlined by walls d cells thick.
            let mut g = Grid::new(60, 50, Cell::Free);
            for y in 0..50 {
                for x in 0..60 {
                    if x < d || y < d || x >= 60 - d || y >= 50 - d || (x >= 30 && x < 30 + d) {
                        *g.at_mut(x, y) = Cell::Occupied;
                    }
                }
            }
            assert_eq!(ring_depth(&g, 0.0, 0.05), d as i32);
        }
        assert_eq!(ring_depth(&Grid::new(5, 5, Cell::Free), 0.0, 0.05), 1);
    }

    #[test]
    fn the_thickest_ring_is_half_a_metre_at_any_cell_size() {
        // A room outlined by walls 0.3 m and 0.6 m thick: 0.3 m is measured as it is, 0.6 m
        // is clamped to 0.5 m, in cells of 2.5, 5 and 10 cm.
        for resolution in [0.025, 0.05, 0.1] {
            let ring = |m: f64| {
                let d = libm::round(m / resolution) as usize;
                let (w, h) = (12 * d, 10 * d);
                let mut g = Grid::new(w, h, Cell::Free);
                for y in 0..h {
                    for x in 0..w {
                        if x < d || y < d || x >= w - d || y >= h - d || (x >= w / 2 && x < w / 2 + d) {
                            *g.at_mut(x, y) = Cell::Occupied;
                        }
                    }
                }
                ring_depth(&g, 0.0, resolution) as f64 * resolution
            };
            assert!((ring(0.3) - 0.3).abs() < 1e-9, "{resolution}: {}", ring(0.3));
            assert!((ring(0.6) - 0.5).abs() < 1e-9, "{resolution}: {}", ring(0.6));
        }
    }

    #[test]
    fn segments_bridge_small_gaps_only() {
        let line = |s: &str| s.chars().map(|c| c == '#').collect::<Vec<_>>().into_iter();
        assert_eq!(segment_cells(line("..#####..."), 5, 1), 5);
        assert_eq!(segment_cells(line("..###.##..."), 5, 1), 5);
        assert_eq!(segment_cells(line("..###...##..."), 5, 1), 0);
        assert_eq!(segment_cells(line("####"), 5, 1), 0);
    }

    #[test]
    fn two_rooms_give_their_rectangles() {
        // Two rooms side by side sharing a 2-cell wall: columns 0, 20-21, 40; rows 0 and 39.
        let mut g = Grid::new(41, 40, Cell::Free);
        for y in 0..40 {
            for x in [0, 20, 21, 40] {
                *g.at_mut(x, y) = Cell::Occupied;
            }
        }
        for x in 0..41 {
            *g.at_mut(x, 0) = Cell::Occupied;
            *g.at_mut(x, 39) = Cell::Occupied;
        }
        // A door through the middle wall.
        for y in 18..22 {
            *g.at_mut(20, y) = Cell::Free;
            *g.at_mut(21, y) = Cell::Free;
        }
        let c = candidates(&g, 5, &WallConfig::default());
        let rects: Vec<Rect> = c.iter().map(|x| x.0).collect();
        assert!(rects.contains(&Rect::new(0, 0, 21, 40)), "left room with the wall's left face");
        assert!(rects.contains(&Rect::new(21, 0, 20, 40)), "right room");
        assert!(rects.contains(&Rect::new(0, 0, 41, 40)), "both rooms as one");
        assert!(c.iter().all(|x| x.1 > 0.0 && x.1 <= 1.0));
        // The wall between the rooms crosses the combined rectangle: each room outweighs it.
        let weight = |r: Rect| c.iter().find(|x| x.0 == r).unwrap().1;
        assert!(weight(Rect::new(0, 0, 21, 40)) > 10.0 * weight(Rect::new(0, 0, 41, 40)));
        assert!(weight(Rect::new(21, 0, 20, 40)) > 10.0 * weight(Rect::new(0, 0, 41, 40)));
    }
}
