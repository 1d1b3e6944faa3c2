//! Wall gaps: the lines a person draws to close a room where its wall stops short.
//!
//! A room that opens onto a corridor over most of its width has no wall and no door between
//! the two, yet a person drawing the floor plan closes it along the corridor's wall, from one
//! wall stub to the next (the ground truth of the room-segmentation benchmark is drawn so).
//! A rectangle of the chain cannot tell: the unit that explains the corridor's walls may reach
//! into the room, and the room layer then labels room and corridor as one segment.
//!
//! This module finds those gaps. In the world frame, where walls run along the axes, a *gap*
//! is a run of free cells along a row or a column (unseen cells on it too: the tip of a wall
//! a scan missed), at most [`RoomCells::max_wall_gap`] cells long, between two ends of walls
//! of that line, at least one of them a *stub*: a wall lying along the line for
//! [`RoomCells::min_wall_stub`] cells or more and somewhere no deeper across it than a wall (a
//! desk is deep all along). The other end may be a stub or a *corner*, a wall meeting the line
//! from one side anywhere along its short run (a corridor's wall leaving a hall's). Three
//! things a person would not close stay open:
//!
//! * a corridor seen from the tip of a wall pointing at its far wall (that wall runs on
//!   through the line on both sides, or is the jamb of a door in it: no corner);
//! * a corridor passing between the walls of the rooms either side of it (walls cross the
//!   line at both ends of the gap);
//! * gaps onto chairs, the dots of a drawn table and specks: occupied parts less than
//!   [`RoomCells::min_wall_len`] long are no walls (a wall's parts join through the unseen
//!   cells beside them, so a wall a scan saw in pieces is still one wall).
//!
//! The gaps are drawn into a copy of the map as occupied cells ([`close_wall_gaps_along`]), and the
//! room layer splits a room whose cells the gaps part into two or more parts of a room core's
//! size ([`super::segments::split_at_wall_gaps`]); a gap that closes nothing changes nothing.
//! The gaps never reach the chain, its likelihood or K(W,M): they are a reading of the walls,
//! not an observation.

use super::config::RoomCells;
use super::frame::frame_cell;
use crate::floorplan::world::World;
use crate::geometry::Frame;
use crate::grid::flood::{Flood, Neighbours};
use crate::grid::{Cell, Grid};
use std::ops::RangeInclusive;

/// Cells of the world frame (row-major, `world_map`'s size) that close a wall gap. `depth` is
/// the thickest a wall stub may be across its line, in cells (furniture along a line is
/// deeper than a wall).
pub fn wall_gaps(world_map: &Grid<Cell>, c: &RoomCells, depth: usize) -> Vec<bool> {
    let (w, h) = (world_map.width(), world_map.height());
    let mut gaps = vec![false; w * h];
    if c.max_wall_gap == 0 || w == 0 || h == 0 {
        return gaps;
    }
    let cells = world_map.cells();
    let wall = walls(world_map, c.min_wall_len as usize, c.wall_piece_thick as usize, c.hole_reach);
    for y in 0..h {
        let line = Line {
            len: w,
            wall: |x: usize, off: isize| {
                let yy = y as isize + off;
                yy >= 0 && (yy as usize) < h && wall[yy as usize * w + x]
            },
            cell: |x: usize| cells[y * w + x],
            depth,
        };
        line.mark(c, |x| gaps[y * w + x] = true);
    }
    for x in 0..w {
        let line = Line {
            len: h,
            wall: |y: usize, off: isize| {
                let xx = x as isize + off;
                xx >= 0 && (xx as usize) < w && wall[y * w + xx as usize]
            },
            cell: |y: usize| cells[y * w + x],
            depth,
        };
        line.mark(c, |y| gaps[y * w + x] = true);
    }
    gaps
}

/// Which cells are walls: occupied cells of a connected part at least `min_len` cells long or
/// wide, or a piece of wall: a line, straight or bent, no thicker than `piece_thick` cells and
/// at least three times that long ([`line_like`]; 0 turns pieces off). Parts are 8-connected
/// through occupied cells, unknown cells within `hole_reach` cells of one
/// ([`super::config::HOLE_REACH_M`]) and free cells between two pieces of wall as thick as a
/// wall within `hole_reach` along a row or column ([`seen_through`]), so a wall that a scan
/// saw in pieces, with unseen cells in it or seen through as a glass pane, is one part;
/// smaller parts (chairs, the dots of a drawn table, specks amid free space) are no wall a gap
/// could close onto, no jamb of a doorway and no wall between two units (see
/// [`RoomCells::min_wall_len`]).
pub(crate) fn walls(map: &Grid<Cell>, min_len: usize, piece_thick: usize, hole_reach: u32) -> Vec<bool> {
    let (w, h) = (map.width(), map.height());
    let cells = map.cells();
    let mut wall = vec![false; w * h];
    // Unknown cells within the reach of an occupied one: the map grown by it.
    let near = crate::vision::walls::dilate(map, hole_reach.min(i32::MAX as u32) as i32);
    let seen_through = seen_through(map, hole_reach as usize, piece_thick);
    let joins = |j: usize| {
        cells[j] == Cell::Occupied
            || (cells[j] == Cell::Unknown && near.cells()[j] == Cell::Occupied)
            || seen_through[j]
    };
    each_part(
        w,
        h,
        |i| cells[i] == Cell::Occupied,
        joins,
        |part, extent| {
            if extent >= min_len || (piece_thick > 0 && line_like(part, w, extent, piece_thick)) {
                part.iter().filter(|&&i| cells[i] == Cell::Occupied).for_each(|&i| wall[i] = true);
            }
        },
    );
    wall
}

/// Free cells of `map` between two pieces of wall within `reach` cells on either side along
/// their row or along their column: the gaps of a wall a scan saw through (a glass pane,
/// whose rays pass between its reflections), no wider than the reach: a cell of a wider gap
/// lies beyond the reach of the piece on its far side.
/// A piece of wall is an occupied cell whose run of occupied cells across the line is a
/// wall's thickness: from the reach (the hole's 0.1 m, [`super::config::HOLE_REACH_M`], is
/// also the thinnest partition wall: 2 cells at 5 cm, 4 at 2.5 cm, 1 at 10 cm, where a wall
/// is one cell thick) to `thick`. A speck is thinner than a wall at 5 cm and finer cells, the
/// edge of a desk or a shelf running along the line is longer, and neither joins anything.
fn seen_through(map: &Grid<Cell>, reach: usize, thick: usize) -> Vec<bool> {
    let (w, h) = (map.width(), map.height());
    let cells = map.cells();
    let mut out = vec![false; w * h];
    let thinnest = reach.max(1);
    if reach == 0 || thick < thinnest || w == 0 || h == 0 {
        return out;
    }
    let across_rows = pieces(cells, w, h, true, thinnest..=thick);
    let across_columns = pieces(cells, w, h, false, thinnest..=thick);
    let mut line = |at: &dyn Fn(usize) -> usize, len: usize, piece: &[bool]| {
        // Between each two pieces of wall in a row, the free cells within the reach of both.
        let mut last: Option<usize> = None;
        for n in (0..len).filter(|&k| piece[at(k)]) {
            if let Some(l) = last {
                for j in (l + 1).max(n.saturating_sub(reach))..n.min(l + reach + 1) {
                    if cells[at(j)] == Cell::Free {
                        out[at(j)] = true;
                    }
                }
            }
            last = Some(n);
        }
    };
    // Along a row, a piece of wall is thick down its column; along a column, across its row.
    for y in 0..h {
        line(&|k| y * w + k, w, &across_columns);
    }
    for x in 0..w {
        line(&|k| k * w + x, h, &across_rows);
    }
    out
}

/// Per cell, whether it is occupied and the run of occupied cells through it along its row
/// (`along_rows`) or its column is `thick` long (a byte a cell, not the run's length in four).
fn pieces(cells: &[Cell], w: usize, h: usize, along_rows: bool, thick: RangeInclusive<usize>) -> Vec<bool> {
    let mut piece = vec![false; w * h];
    let (lines, len) = if along_rows { (h, w) } else { (w, h) };
    let at = |line: usize, k: usize| if along_rows { line * w + k } else { k * w + line };
    for line in 0..lines {
        let mut k = 0;
        while k < len {
            if cells[at(line, k)] != Cell::Occupied {
                k += 1;
                continue;
            }
            let start = k;
            while k < len && cells[at(line, k)] == Cell::Occupied {
                k += 1;
            }
            if thick.contains(&(k - start)) {
                (start..k).for_each(|j| piece[at(line, j)] = true);
            }
        }
    }
    piece
}

/// Calls `f(part, extent)` for every 8-connected part of the cells of a `w` x `h` grid that
/// `member` holds (cell indices), each part found from a cell `start` holds (`start` implies
/// `member`); `extent` is the longer side of the part's bounding box.
pub(crate) fn each_part(
    w: usize,
    h: usize,
    start: impl Fn(usize) -> bool,
    member: impl Fn(usize) -> bool,
    f: impl FnMut(&[usize], usize),
) {
    each_part_below(w, h, start, member, usize::MAX, f)
}

/// [`each_part`] for the parts whose extent is below `max_extent` only: a larger part is
/// flooded (its cells are marked seen) but its cells are not kept, so the unexplored space
/// around a building (millions of cells) costs no list of them.
pub(crate) fn each_part_below(
    w: usize,
    h: usize,
    start: impl Fn(usize) -> bool,
    member: impl Fn(usize) -> bool,
    max_extent: usize,
    mut f: impl FnMut(&[usize], usize),
) {
    let mut seen = vec![false; w * h];
    let (mut flood, mut part) = (Flood::default(), Vec::new());
    for first in 0..w * h {
        if seen[first] || !start(first) {
            continue;
        }
        part.clear();
        let (mut x0, mut y0, mut x1, mut y1) = (usize::MAX, usize::MAX, 0, 0);
        let mut large = false;
        // `start` implies `member`: the first cell enters as the others do.
        let mut enter = |j: usize| !seen[j] && member(j) && !std::mem::replace(&mut seen[j], true);
        flood.fill(w, h, [first], Neighbours::Eight, &mut enter, |i| {
            let (x, y) = (i % w, i / w);
            (x0, y0, x1, y1) = (x0.min(x), y0.min(y), x1.max(x), y1.max(y));
            if large {
                return;
            }
            large = (x1 - x0 + 1).max(y1 - y0 + 1) >= max_extent;
            if large {
                part = Vec::new();
            } else {
                part.push(i);
            }
        });
        let extent = (x1 - x0 + 1).max(y1 - y0 + 1);
        if extent < max_extent {
            f(&part, extent);
        }
    }
}

/// Whether a part (cell indices of a `w`-wide grid, `extent` its longer side) is a piece of
/// wall: a line, straight or bent, no thicker than `thick` cells (no more cells than its
/// bounding box's two sides times that) and at least three times as long as that. A piece of
/// wall between a door and a corner, or between a door and a glass pane, is; a chair, a desk
/// or a cupboard is a blob (a filled shape whose sides both reach twice `thick` has more
/// cells than the bound).
fn line_like(part: &[usize], w: usize, extent: usize, thick: usize) -> bool {
    let thick = thick.max(1);
    if extent < 3 * thick {
        return false;
    }
    let (mut x0, mut y0, mut x1, mut y1) = (usize::MAX, usize::MAX, 0, 0);
    for &i in part {
        let (x, y) = (i % w, i / w);
        (x0, y0, x1, y1) = (x0.min(x), y0.min(y), x1.max(x), y1.max(y));
    }
    part.len() <= thick * (x1 - x0 + 1 + y1 - y0 + 1)
}

/// One row or column of the world frame: `wall(i, off)` is whether a wall holds the cell at
/// position `i` along the line and `off` cells across it, `cell(i)` the line's own cell at
/// `i`. `depth` is the thickest a wall stub may be across the line.
struct Line<W, F> {
    len: usize,
    wall: W,
    cell: F,
    depth: usize,
}

impl<W: Fn(usize, isize) -> bool, F: Fn(usize) -> Cell> Line<W, F> {
    /// Whether a wall of the line holds position `i`.
    fn band(&self, i: usize) -> bool {
        (self.wall)(i, 0)
    }

    /// Wall cells within `2 * depth` of the line across it at position `i`.
    fn across(&self, i: usize) -> usize {
        let d = 2 * self.depth as isize;
        (-d..=d).filter(|&off| (self.wall)(i, off)).count()
    }

    /// Whether a wall crosses the line at position `i`: wall beyond a stub's depth on both
    /// sides.
    fn crossed(&self, i: usize) -> bool {
        self.side(i, 1) && self.side(i, -1)
    }

    /// Whether a wall leaves the line at position `i` towards `sign` (1 or -1), beyond a
    /// stub's depth.
    fn side(&self, i: usize, sign: isize) -> bool {
        let d = self.depth as isize;
        (d + 1..=2 * d).any(|off| (self.wall)(i, sign * off))
    }

    /// Whether the run `s..e` of the band is a wall stub: long along the line and somewhere
    /// no deeper across it than a wall (a stub meets the wall it sticks out of; a desk is
    /// deep all along).
    fn stub(&self, (s, e): (usize, usize), c: &RoomCells) -> bool {
        e - s >= c.min_wall_stub.max(1) as usize && (s..e).any(|k| self.across(k) <= self.depth)
    }

    /// Whether the run `s..e` is a stub or a corner: a wall meeting the line from one side,
    /// no longer along the line than a stub is deep and reaching across it at least twice
    /// that. Two walls are no corner: one running on through the line (the far wall of a
    /// corridor seen from the tip of a wall pointing at it), and the jamb of a door in a wall
    /// across the line (the wall resumes beyond the tip within a doorway's width, `door`
    /// cells). Closing onto either would cut a corridor.
    fn end(&self, (s, e): (usize, usize), c: &RoomCells, door: usize) -> bool {
        if self.stub((s, e), c) {
            return true;
        }
        let corner = e - s <= self.depth && (s..e).any(|k| self.across(k) >= 2 * self.depth && !self.crossed(k));
        corner && !(s..e).any(|k| self.jamb(k, door))
    }

    /// Whether the wall meeting the line at position `i` (from the side it reaches) resumes
    /// beyond its tip, on the other side, within `door` free cells.
    fn jamb(&self, i: usize, door: usize) -> bool {
        let sign = if self.side(i, 1) { -1 } else { 1 };
        // Past the tip's own cells, then across the opening.
        let mut k = 1;
        while k <= self.depth as isize && (self.wall)(i, sign * k) {
            k += 1;
        }
        let opening = k;
        while k < opening + door as isize {
            if (self.wall)(i, sign * k) {
                return k > opening;
            }
            k += 1;
        }
        false
    }

    /// Whether the cells `gap` between two runs of wall are an opening: nothing occupied on
    /// it and something free. Unseen cells on it (the tip of a wall the scan missed, a speck
    /// in the doorway, a turned wall's anti-aliased edge) say nothing about where a wall
    /// ends, and a person draws the line through them; clutter in the opening keeps it open.
    fn opening(&self, gap: std::ops::Range<usize>) -> bool {
        gap.clone().all(|k| (self.cell)(k) != Cell::Occupied) && gap.into_iter().any(|k| (self.cell)(k) == Cell::Free)
    }

    /// Whether walls cross the line at both ends of the gap between runs `p` and `next`
    /// (within a stub's depth of it): a corridor passing between two walls.
    fn passage(&self, p: (usize, usize), next: (usize, usize)) -> bool {
        let d = self.depth;
        (p.1.saturating_sub(d).max(p.0)..p.1).any(|k| self.crossed(k))
            && (next.0..(next.0 + d).min(next.1)).any(|k| self.crossed(k))
    }

    /// Marks every free run between two ends of walls of the line ([`Line::end`]), at least
    /// one of them a stub, that is short enough to be a gap, unless walls cross the line at
    /// both ends (a corridor passing between the walls of the rooms either side of it).
    fn mark(&self, c: &RoomCells, mut mark: impl FnMut(usize)) {
        let max_gap = c.max_wall_gap as usize;
        let door = 2 * c.door_half_width as usize;
        let mut prev: Option<(usize, usize)> = None;
        let mut i = 0;
        while i < self.len {
            if !self.band(i) {
                i += 1;
                continue;
            }
            let start = i;
            while i < self.len && self.band(i) {
                i += 1;
            }
            if let Some(p) = prev {
                let gap = p.1..start;
                let next = (start, i);
                if gap.len() <= max_gap
                    && self.opening(gap.clone())
                    && ((self.stub(p, c) && self.end(next, c, door)) || (self.end(p, c, door) && self.stub(next, c)))
                    && !self.passage(p, next)
                {
                    gap.for_each(&mut mark);
                }
            }
            prev = Some((start, i));
        }
    }
}

/// The deepest a wall stub may be across its line for walls `t` cells thick: the wall and
/// `noise` cells of drawing noise (anti-aliased edges, a wall a cell off its line:
/// [`RoomCells::stub_noise`]).
pub fn stub_depth(t: i32, noise: u32) -> usize {
    t.max(1) as usize + noise as usize
}

/// The map (in the map frame) with every wall gap ([`wall_gaps`], found in the world frame)
/// drawn as occupied; `None` when there is none, or gaps are off. With the gaps of the walls
/// that run along further directions too:
/// `angles` (radians, in the convention of the frame's angle, [`Frame::turned`]) are the
/// wall directions of a building's other wings ([`crate::floorplan::wings`]). A person closes a room
/// along its wall whichever way the wall runs; a gap is found in a frame turned by its
/// wall's direction, where that wall runs along the rows or columns, and drawn back onto the
/// map. Walls of other directions run along no row of that frame for a stub's length, so a
/// frame closes the gaps of its own walls only.
///
/// [`Frame::turned`]: crate::geometry::Frame::turned
pub fn close_wall_gaps_along(
    world: &World,
    map: &Grid<Cell>,
    world_map: &Grid<Cell>,
    c: &RoomCells,
    angles: &[f64],
) -> Option<Grid<Cell>> {
    let depth = stub_depth(world.wall_thickness, c.stub_noise);
    let mut closed = map.clone();
    let mut any = close_in_frame(&mut closed, map, world_map, &world.frame, &wall_gaps(world_map, c, depth));
    for &angle in angles {
        let (turned, frame) = crate::vision::orientation::to_world_frame(map, angle);
        any |= close_in_frame(&mut closed, map, &turned, &frame, &wall_gaps(&turned, c, depth));
    }
    any.then_some(closed)
}

/// Draws into `closed` (the map frame) every free cell of `map` whose cell in `frame` is a
/// gap of `gaps` (cells of `framed`, the map in that frame); returns whether any gap was.
fn close_in_frame(
    closed: &mut Grid<Cell>,
    map: &Grid<Cell>,
    framed: &Grid<Cell>,
    frame: &Frame,
    gaps: &[bool],
) -> bool {
    if !gaps.contains(&true) {
        return false;
    }
    let (ww, wh) = (framed.width(), framed.height());
    let rotation = frame.rotation();
    for my in 0..map.height() {
        for mx in 0..map.width() {
            if *map.at(mx, my) != Cell::Free {
                continue;
            }
            if let Some((wx, wy)) = frame_cell(frame, &rotation, mx, my, (ww, wh)) {
                if gaps[wy * ww + wx] {
                    *closed.at_mut(mx, my) = Cell::Occupied;
                }
            }
        }
    }
    true
}

/// The walls of one map as the room layer reads them, read once for every grouping of units
/// it labels: grouping by units labels the map twice ([`super::layer::mark_closed`], then the
/// rooms) and asks about open pairs and openings besides, and each reading cost Cartesium
/// about 60 ms.
#[derive(Debug, Clone)]
pub(crate) struct WallReading {
    /// The map with its clutter drawn free ([`without_clutter`]), in the map's frame.
    pub(crate) open: Grid<Cell>,
    /// The map with its wall gaps closed ([`close_wall_gaps_along`]).
    pub(crate) closed: Option<Grid<Cell>>,
    /// The map's free depth with its specks looked past ([`super::read::standing_depth`]),
    /// in the map's frame: where a person stands, and how wide a passage is.
    pub(crate) standing: Vec<u32>,
    /// The world's map with its clutter drawn free, when it was read up front
    /// ([`WallReading::with_world_open`]) and is not the map itself.
    open_world: Option<Grid<Cell>>,
}

impl WallReading {
    /// Reads the walls of `map` (in its own frame) and `world_map` (the same map in the
    /// world's frame), with the wall gaps along `angles` too.
    pub(crate) fn new(world: &World, map: &Grid<Cell>, world_map: &Grid<Cell>, c: &RoomCells, angles: &[f64]) -> Self {
        Self::read(world, map, world_map, c, angles, false)
    }

    /// [`WallReading::new`], and the world's map with its clutter drawn free too
    /// ([`WallReading::open_in_world`]), read beside the rest: grouping by units asks for it.
    pub(crate) fn with_world_open(world: &World, map: &Grid<Cell>, world_map: &Grid<Cell>, c: &RoomCells) -> Self {
        Self::read(world, map, world_map, c, &[], true)
    }

    /// The readings are independent of each other, so they share the machine's cores
    /// ([`crate::threads::join`]); each is what it would be alone.
    fn read(
        world: &World,
        map: &Grid<Cell>,
        world_map: &Grid<Cell>,
        c: &RoomCells,
        angles: &[f64],
        world_open: bool,
    ) -> Self {
        use crate::threads::join;
        let clear = |m: &Grid<Cell>| without_clutter(m, c.min_wall_len, c.wall_piece_thick, c.hole_reach);
        let ((open, open_world), (closed, standing)) = join(
            || join(|| clear(map), || (world_open && world_map != map).then(|| clear(world_map))),
            || {
                join(
                    || close_wall_gaps_along(world, map, world_map, c, angles),
                    || super::read::standing_depth(map, c.speck, c.hole_reach),
                )
            },
        );
        WallReading { open, closed, standing, open_world }
    }

    /// `world_map` (the map these walls were read from, in the world's frame) with its clutter
    /// drawn free: [`WallReading::open`] itself when the world's frame is the map's. Only
    /// grouping by units asks for it, once.
    pub(crate) fn open_in_world<'a>(
        &'a self,
        map: &Grid<Cell>,
        world_map: &Grid<Cell>,
        c: &RoomCells,
    ) -> std::borrow::Cow<'a, Grid<Cell>> {
        if let Some(open) = &self.open_world {
            std::borrow::Cow::Borrowed(open)
        } else if world_map == map {
            std::borrow::Cow::Borrowed(&self.open)
        } else {
            std::borrow::Cow::Owned(without_clutter(world_map, c.min_wall_len, c.wall_piece_thick, c.hole_reach))
        }
    }
}

/// `map` with the occupied parts that are no walls ([`walls`]: shorter
/// than `min_wall_len` cells) and the unseen specks amid free space ([`unknown_specks`])
/// drawn free: chairs, the dots of a drawn table, a bin, cells a scan missed. A doorway
/// is a narrowing between walls; the gaps between the chairs round a table are none, and
/// the free space they ring is part of the room, not a room behind a door.
pub(crate) fn without_clutter(map: &Grid<Cell>, min_wall_len: u32, piece_thick: u32, hole_reach: u32) -> Grid<Cell> {
    let wall = super::wall_gaps::walls(map, min_wall_len as usize, piece_thick as usize, hole_reach);
    let specks = unknown_specks(map, min_wall_len as usize);
    let mut out = map.clone();
    for ((cell, &is_wall), &speck) in out.cells_mut().iter_mut().zip(&wall).zip(&specks) {
        if *cell == Cell::Occupied && !is_wall || speck {
            *cell = Cell::Free;
        }
    }
    out
}

/// Unknown cells of 8-connected unknown parts less than `min_len` cells long and wide that
/// touch free space: the cells a scan missed amid a room (or the unseen holes in a chair),
/// not the unexplored space around the building.
///
/// The parts are found as runs of unknown cells along the rows, joined where runs of
/// neighbouring rows touch (diagonally too) in the crate's one union-find: the unknown space
/// around a building, most of the map, is a few runs a row, where a flood visited each of its
/// cells (6 % of Cartesium's run, read twice). Only the small parts' cells are looked at.
fn unknown_specks(map: &Grid<Cell>, min_len: usize) -> Vec<bool> {
    let (w, h) = (map.width(), map.height());
    let cells = map.cells();
    let mut speck = vec![false; w * h];
    // Runs `(y, x0, x1)`, `x1` exclusive, row by row; `rows[y]` is row y's first run.
    let mut runs: Vec<(usize, usize, usize)> = Vec::new();
    let mut rows = Vec::with_capacity(h + 1);
    for y in 0..h {
        rows.push(runs.len());
        let row = &cells[y * w..(y + 1) * w];
        let mut x = 0;
        while x < w {
            if row[x] != Cell::Unknown {
                x += 1;
                continue;
            }
            let x0 = x;
            while x < w && row[x] == Cell::Unknown {
                x += 1;
            }
            runs.push((y, x0, x));
        }
    }
    rows.push(runs.len());
    let mut parts = crate::union_find::UnionFind::new(runs.len());
    for y in 1..h {
        let (above, here) = (rows[y - 1]..rows[y], rows[y]..rows[y + 1]);
        let mut a = above.start;
        for b in here {
            let (_, bx0, bx1) = runs[b];
            // Runs above that end before this one's diagonal neighbour are done with.
            while a < above.end && runs[a].2 < bx0 {
                a += 1;
            }
            let mut k = a;
            while k < above.end && runs[k].1 <= bx1 {
                parts.union(k, b);
                k += 1;
            }
        }
    }
    // Each part's extent, at its root (its first run).
    let mut boxes: Vec<(usize, usize, usize, usize)> = vec![(usize::MAX, usize::MAX, 0, 0); runs.len()];
    let root: Vec<usize> = (0..runs.len()).map(|r| parts.find(r)).collect();
    for (&(y, x0, x1), &r) in runs.iter().zip(&root) {
        let bx = &mut boxes[r];
        *bx = (bx.0.min(x0), bx.1.min(y), bx.2.max(x1 - 1), bx.3.max(y));
    }
    let small = |r: usize| {
        let (x0, y0, x1, y1) = boxes[r];
        (x1 - x0 + 1).max(y1 - y0 + 1) < min_len
    };
    let by_free = |i: usize| beside_free(map, i);
    let mut touches_free = vec![false; runs.len()];
    for (&(y, x0, x1), &r) in runs.iter().zip(&root) {
        if small(r) && !touches_free[r] {
            touches_free[r] = (y * w + x0..y * w + x1).any(by_free);
        }
    }
    for (&(y, x0, x1), &r) in runs.iter().zip(&root) {
        if small(r) && touches_free[r] {
            speck[y * w + x0..y * w + x1].fill(true);
        }
    }
    speck
}

/// Whether cell `i` of `map` has a free cell among its eight neighbours (or is free itself).
fn beside_free(map: &Grid<Cell>, i: usize) -> bool {
    let (w, h, cells) = (map.width(), map.height(), map.cells());
    let (x, y) = (i % w, i / w);
    (y.saturating_sub(1)..=(y + 1).min(h - 1))
        .any(|ny| (x.saturating_sub(1)..=(x + 1).min(w - 1)).any(|nx| cells[ny * w + nx] == Cell::Free))
}

/// [`unknown_specks`] by flooding each part, as it was: the test holds the runs to it.
#[cfg(test)]
fn unknown_specks_flooded(map: &Grid<Cell>, min_len: usize) -> Vec<bool> {
    let (w, h) = (map.width(), map.height());
    let cells = map.cells();
    let by_free = |i: usize| beside_free(map, i);
    let mut speck = vec![false; w * h];
    let unknown = |i: usize| cells[i] == Cell::Unknown;
    each_part_below(w, h, unknown, unknown, min_len, |part, _| {
        if part.iter().any(|&i| by_free(i)) {
            part.iter().for_each(|&i| speck[i] = true);
        }
    });
    speck
}

#[cfg(test)]
mod tests {
    use super::super::config::RoomConfig;
    use super::super::segments::{labels_of_groups, labels_of_groups_along};
    use super::*;
    use crate::floorplan::{Unit, UnitType};

    /// The runs find the flood's specks: random maps of every mix of classes (parts joined
    /// only diagonally among them), and parts up to the map's size.
    #[test]
    fn specks_by_runs_are_the_flooded_specks() {
        let mut seed = 11u64;
        let mut next = move |n: u64| {
            seed = seed.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            (seed >> 33) % n
        };
        for trial in 0..200 {
            let (w, h) = (1 + next(40) as usize, 1 + next(30) as usize);
            let unknown_share = next(10);
            let mut map = Grid::new(w, h, Cell::Free);
            for c in map.cells_mut() {
                let r = next(10);
                *c = if r < unknown_share {
                    Cell::Unknown
                } else if r < 8 {
                    Cell::Free
                } else {
                    Cell::Occupied
                };
            }
            for min_len in [1, 2, 3, 6, 50] {
                let runs = unknown_specks(&map, min_len);
                assert_eq!(runs, unknown_specks_flooded(&map, min_len), "trial {trial}, {w}x{h}, min_len {min_len}");
            }
        }
    }

    #[test]
    fn a_gap_between_two_stubs_of_one_line_is_closed() {
        // A wall along row 5 with a 4-cell gap between two 10-cell stubs.
        let mut map = Grid::new(24, 11, Cell::Free);
        for x in (0..10).chain(14..24) {
            *map.at_mut(x, 5) = Cell::Occupied;
        }
        let c = RoomCells { max_wall_gap: 6, min_wall_stub: 6, min_wall_len: 8, ..RoomCells::default() };
        let gaps = wall_gaps(&map, &c, 3);
        assert!((10..14).all(|x| gaps[5 * 24 + x]));
        assert_eq!(gaps.iter().filter(|&&g| g).count(), 4);
    }

    fn config(gap: u32, stub: u32) -> RoomCells {
        RoomCells { max_wall_gap: gap, min_wall_stub: stub, min_wall_len: 1, ..RoomCells::default() }
    }

    fn fill(map: &mut Grid<Cell>, xs: std::ops::Range<usize>, ys: std::ops::Range<usize>, cell: Cell) {
        for y in ys {
            for x in xs.clone() {
                *map.at_mut(x, y) = cell;
            }
        }
    }

    fn marked(gaps: &[bool], w: usize) -> Vec<(usize, usize)> {
        (0..gaps.len()).filter(|&i| gaps[i]).map(|i| (i % w, i / w)).collect()
    }

    #[test]
    fn gaps_between_stubs_close_along_rows_and_columns() {
        let mut map = Grid::new(30, 30, Cell::Free);
        fill(&mut map, 0..8, 10..11, Cell::Occupied);
        fill(&mut map, 12..13, 10..30, Cell::Occupied);
        fill(&mut map, 20..21, 0..14, Cell::Occupied);
        fill(&mut map, 20..21, 17..30, Cell::Occupied);
        let got = marked(&wall_gaps(&map, &config(5, 5), 3), 30);
        // Row 10 between the stub 0..8 and the corner of the wall meeting it from below at
        // x = 12; column 20 between y = 14 and 17.
        let want = [(8, 10), (9, 10), (10, 10), (11, 10), (20, 14), (20, 15), (20, 16)];
        assert_eq!(got, want);
        // A stub and a short run that crosses nothing: no wall end there, nothing closes.
        let mut map = Grid::new(30, 5, Cell::Free);
        fill(&mut map, 0..8, 2..3, Cell::Occupied);
        fill(&mut map, 12..16, 2..3, Cell::Occupied);
        assert!(!wall_gaps(&map, &config(5, 5), 3).contains(&true));
    }

    #[test]
    fn walls_crossed_at_right_angles_and_deep_furniture_are_no_stubs() {
        // A room 4 cells wide between two vertical walls: its rows cross the walls (runs of
        // one cell), which are no stubs, so nothing closes.
        let mut map = Grid::new(20, 20, Cell::Free);
        fill(&mut map, 5..6, 0..20, Cell::Occupied);
        fill(&mut map, 10..11, 0..20, Cell::Occupied);
        assert!(!wall_gaps(&map, &config(8, 3), 3).contains(&true));
        // A desk 8 cells deep 3 cells from a wall: deep all along, no stub.
        let mut map = Grid::new(30, 30, Cell::Free);
        fill(&mut map, 0..1, 0..30, Cell::Occupied);
        fill(&mut map, 4..14, 10..18, Cell::Occupied);
        assert!(!wall_gaps(&map, &config(8, 3), 3).contains(&true));
        // A wall stub pointing at a wall that runs on through its line (the far wall of a
        // corridor): no corner, nothing closes.
        let mut map = Grid::new(30, 30, Cell::Free);
        fill(&mut map, 0..1, 0..30, Cell::Occupied);
        fill(&mut map, 4..14, 10..11, Cell::Occupied);
        assert!(!wall_gaps(&map, &config(8, 3), 3).contains(&true));
        // Where that wall meets the line from one side only (a corner), the gap closes.
        fill(&mut map, 0..1, 0..10, Cell::Free);
        assert_eq!(marked(&wall_gaps(&map, &config(8, 3), 3), 30), [(1, 10), (2, 10), (3, 10)]);
        // Parts shorter than `min_wall_len` (chairs, a table's dots) are no walls to close onto.
        let mut map = Grid::new(30, 5, Cell::Free);
        fill(&mut map, 0..10, 2..3, Cell::Occupied);
        fill(&mut map, 14..20, 2..3, Cell::Occupied);
        let c = RoomCells { min_wall_len: 7, ..config(8, 3) };
        assert!(!wall_gaps(&map, &c, 3).contains(&true));
        let c = RoomCells { min_wall_len: 6, ..config(8, 3) };
        assert_eq!(marked(&wall_gaps(&map, &c, 3), 30), [(10, 2), (11, 2), (12, 2), (13, 2)]);
    }

    #[test]
    fn a_corridor_between_room_walls_stays_open_a_door_closes() {
        // A corridor (x = 20..30) between two vertical walls; the rooms either side have walls
        // along row 20 that meet the corridor's walls. The corridor passes between them: the
        // walls cross the row at both ends of the gap, and it stays open.
        let mut map = Grid::new(50, 40, Cell::Free);
        fill(&mut map, 19..20, 0..40, Cell::Occupied);
        fill(&mut map, 30..31, 0..40, Cell::Occupied);
        fill(&mut map, 0..19, 20..21, Cell::Occupied);
        fill(&mut map, 31..50, 20..21, Cell::Occupied);
        assert!(!wall_gaps(&map, &config(15, 5), 3).iter().enumerate().any(|(i, &g)| g && i / 50 == 20));
        // A door in the corridor's right wall (y = 5..9), between two free wall ends, closes.
        fill(&mut map, 30..31, 5..9, Cell::Free);
        let gaps = wall_gaps(&map, &config(15, 5), 3);
        assert!((5..9).all(|y| gaps[y * 50 + 30]));
    }

    #[test]
    fn a_corridor_ending_in_a_hall_closes_along_the_halls_wall() {
        // A hall's wall along column 20 (3 thick, x = 19..22) with the corridor's two walls
        // (rows 10..13 and 30..33) leaving it to the right: the corridor opens onto the hall
        // over rows 13..30. Above the corridor the hall's wall is three cells long before an
        // unseen stretch, so its run at the corridor is a corner whose wall leaves at its first
        // row, not its middle; below, the wall's tip at the gap is unseen.
        let mut map = Grid::new(40, 50, Cell::Free);
        fill(&mut map, 19..22, 0..4, Cell::Occupied);
        fill(&mut map, 19..22, 4..10, Cell::Unknown);
        fill(&mut map, 19..22, 10..13, Cell::Occupied);
        fill(&mut map, 22..40, 10..11, Cell::Occupied);
        fill(&mut map, 19..22, 29..30, Cell::Unknown);
        fill(&mut map, 19..22, 30..50, Cell::Occupied);
        fill(&mut map, 22..40, 30..31, Cell::Occupied);
        let c = RoomCells { door_half_width: 3, ..config(25, 5) };
        let gaps = wall_gaps(&map, &c, 3);
        assert!((13..29).all(|y| gaps[y * 40 + 20]), "{:?}", marked(&gaps, 40));
        // With the tip seen free instead, the run is the same gap of free cells; so with a
        // speck the scan missed amid the opening.
        fill(&mut map, 19..22, 29..30, Cell::Free);
        fill(&mut map, 20..21, 20..21, Cell::Unknown);
        assert!((13..30).all(|y| wall_gaps(&map, &c, 3)[y * 40 + 20]));
        // Clutter in the opening (an occupied cell that is no wall) still keeps it open.
        let c = RoomCells { min_wall_len: 2, ..c };
        fill(&mut map, 20..21, 20..21, Cell::Occupied);
        assert!(!(13..30).any(|y| wall_gaps(&map, &c, 3)[y * 40 + 20]));
    }

    #[test]
    fn a_door_jamb_across_the_line_is_no_corner() {
        // A stub along column 20 (y = 30..50) points up at a horizontal wall (row 10) that
        // ends at x = 21: a corner, so the column closes between them.
        let mut map = Grid::new(60, 60, Cell::Free);
        fill(&mut map, 20..21, 30..50, Cell::Occupied);
        fill(&mut map, 0..22, 10..11, Cell::Occupied);
        let c = RoomCells { door_half_width: 6, ..config(30, 5) };
        let gaps = wall_gaps(&map, &c, 3);
        assert!((11..30).all(|y| gaps[y * 60 + 20]));
        // The same wall resuming 8 cells on (a door 8 cells wide, under 12): a jamb, no corner.
        fill(&mut map, 30..60, 10..11, Cell::Occupied);
        let gaps = wall_gaps(&map, &c, 3);
        assert!(!(11..30).any(|y| gaps[y * 60 + 20]));
        // A wider opening (over twice the door half-width) is no door: the corner is back.
        let c = RoomCells { door_half_width: 3, ..c };
        let gaps = wall_gaps(&map, &c, 3);
        assert!((11..30).all(|y| gaps[y * 60 + 20]));
    }

    #[test]
    fn a_glass_pane_is_a_wall_a_row_of_specks_or_desks_is_not() {
        // A 3-cell thick wall along rows 10..13, 60 cells long, seen through in one column of
        // every three (a glass pane: its rays pass between the reflections): pieces 2 cells
        // long, each shorter than a wall and thinner than three times its thickness.
        let mut map = Grid::new(70, 40, Cell::Free);
        for x in (5..65).filter(|x| x % 3 != 0) {
            fill(&mut map, x..x + 1, 10..13, Cell::Occupied);
        }
        let at = |w: &[bool], x: usize, y: usize| w[y * 70 + x];
        let glass = walls(&map, 40, 4, 2);
        assert!(at(&glass, 7, 11) && at(&glass, 62, 11), "the pane is one wall");
        // Without the reach, nothing joins its pieces.
        assert!(!walls(&map, 40, 4, 0).contains(&true));
        // Seen through in gaps of three cells out of five, wider than a reach of one cell
        // spans, its pieces stay apart.
        let mut wide = Grid::new(70, 40, Cell::Free);
        for x in (5..65).filter(|x| x % 5 >= 3) {
            fill(&mut wide, x..x + 1, 10..13, Cell::Occupied);
        }
        assert!(walls(&wide, 40, 4, 1).iter().all(|&w| !w));
        // At 10 cm a wall is one cell thick and the reach one cell: a pane seen through in
        // every other cell is a wall there.
        let mut thin = Grid::new(70, 40, Cell::Free);
        (5..65).step_by(2).for_each(|x| *thin.at_mut(x, 20) = Cell::Occupied);
        assert!(at(&walls(&thin, 40, 2, 1), 33, 20));
        // Specks two cells apart along a row are no wall: a speck is no wall's thickness.
        let mut specks = Grid::new(70, 40, Cell::Free);
        (5..65).step_by(2).for_each(|x| *specks.at_mut(x, 20) = Cell::Occupied);
        assert!(!walls(&specks, 40, 4, 2).contains(&true));
        // Nor desks side by side: each is 10 cells deep across the row, no wall's thickness.
        let mut desks = Grid::new(70, 40, Cell::Free);
        for x0 in (5..60).step_by(12) {
            fill(&mut desks, x0..x0 + 10, 15..25, Cell::Occupied);
        }
        assert!(!walls(&desks, 40, 4, 2).contains(&true));
    }

    #[test]
    fn a_short_piece_of_wall_is_a_wall_a_chair_is_not() {
        // An L-shaped piece of wall (a 30-cell arm and a 10-cell arm, 3 cells thick) under
        // `min_wall_len` (40), a filled disc of 10 cells across (a chair) and a filled 30 x 12
        // block (a desk); pieces up to 4 cells thick.
        let mut map = Grid::new(100, 60, Cell::Free);
        fill(&mut map, 10..40, 10..13, Cell::Occupied);
        fill(&mut map, 10..13, 13..23, Cell::Occupied);
        for y in 40..50 {
            for x in 10..20 {
                let (dx, dy) = (x as f64 - 14.5, y as f64 - 44.5);
                if dx * dx + dy * dy <= 25.0 {
                    *map.at_mut(x, y) = Cell::Occupied;
                }
            }
        }
        fill(&mut map, 50..80, 40..52, Cell::Occupied);
        let at = |w: &[bool], x: usize, y: usize| w[y * 100 + x];
        let pieces = walls(&map, 40, 4, 2);
        assert!(at(&pieces, 20, 11) && at(&pieces, 11, 20), "the piece of wall");
        assert!(!at(&pieces, 14, 44), "the chair");
        assert!(!at(&pieces, 60, 45), "the desk");
        // Without pieces only parts of `min_wall_len` are walls.
        assert!(!walls(&map, 40, 0, 2).contains(&true));
        // A piece shorter than three times the thickness (11 cells) is none: a speck.
        let mut short = Grid::new(40, 20, Cell::Free);
        fill(&mut short, 5..15, 5..8, Cell::Occupied);
        assert!(!walls(&short, 40, 4, 2).contains(&true));
        fill(&mut short, 15..17, 5..8, Cell::Occupied);
        assert!(walls(&short, 40, 4, 2).contains(&true));
    }

    #[test]
    fn a_wall_seen_in_pieces_is_one_wall() {
        // A corridor's far wall (row 10) with unseen holes beside column 20, the end of its
        // left piece; its middle piece is 8 cells, under `min_wall_len`. Joined through the
        // holes it is one wall running on through column 20, so the stub below does not close
        // onto it (it would cut the corridor).
        let mut map = Grid::new(40, 40, Cell::Free);
        fill(&mut map, 0..40, 10..11, Cell::Occupied);
        fill(&mut map, 21..23, 10..11, Cell::Unknown);
        fill(&mut map, 31..33, 10..11, Cell::Unknown);
        fill(&mut map, 20..21, 25..40, Cell::Occupied);
        let c = RoomCells { min_wall_len: 12, ..config(20, 5) };
        assert!(!wall_gaps(&map, &c, 3).iter().enumerate().any(|(i, &g)| g && i % 40 == 20));
        // Holes wider than twice the reach part the wall: the pieces right of column 20 are
        // too short to be walls, column 20 is a corner, and the stub closes onto it.
        fill(&mut map, 21..27, 10..11, Cell::Unknown);
        fill(&mut map, 31..37, 10..11, Cell::Unknown);
        let gaps = wall_gaps(&map, &c, 3);
        assert!((11..25).all(|y| gaps[y * 40 + 20]));
    }

    #[test]
    fn a_hole_in_a_wall_reaches_as_far_in_metres_at_any_cell_size() {
        // A wall 3 m long with a 0.15 m hole a scan left in its middle, its pieces each under
        // the 2 m of a wall: at 5 cm cells (a 3-cell hole) and at 2.5 cm (6 cells) the hole
        // joins them into one wall; a hole of 0.5 m (a doorway's width) joins nothing.
        let wall_with_hole = |resolution: f64, hole_m: f64| {
            let cells = |m: f64| libm::round(m / resolution) as usize;
            let (len, hole) = (cells(3.0), cells(hole_m));
            let mut map = Grid::new(len + 4, 5, Cell::Free);
            fill(&mut map, 2..len + 2, 2..3, Cell::Occupied);
            let from = 2 + (len - hole) / 2;
            fill(&mut map, from..from + hole, 2..3, Cell::Unknown);
            let c = RoomConfig::default().cells(resolution);
            walls(&map, c.min_wall_len as usize, 0, c.hole_reach).contains(&true)
        };
        for resolution in [0.025, 0.05, 0.1] {
            assert!(wall_with_hole(resolution, 0.15), "at {resolution} m a cell");
            assert!(!wall_with_hole(resolution, 0.5), "at {resolution} m a cell");
        }
    }

    #[test]
    fn long_gaps_and_off_stay_open_unseen_cells_close() {
        let mut map = Grid::new(40, 5, Cell::Free);
        fill(&mut map, 0..10, 2..3, Cell::Occupied);
        fill(&mut map, 20..30, 2..3, Cell::Occupied);
        fill(&mut map, 33..40, 2..3, Cell::Occupied);
        *map.at_mut(31, 2) = Cell::Unknown;
        // 10 cells is over the longest gap; the second gap, with an unseen cell on its line,
        // closes at both lengths (its free cells; the unseen one stays unseen in the map).
        let gaps = wall_gaps(&map, &config(9, 5), 3);
        assert!(!(10..20).any(|x| gaps[2 * 40 + x]));
        assert!((30..33).all(|x| gaps[2 * 40 + x]));
        let gaps = wall_gaps(&map, &config(10, 5), 3);
        assert!((10..20).all(|x| gaps[2 * 40 + x]));
        // A line unseen all along between the two wall ends holds nothing to close.
        *map.at_mut(30, 2) = Cell::Unknown;
        *map.at_mut(32, 2) = Cell::Unknown;
        assert!(!(30..33).any(|x| wall_gaps(&map, &config(10, 5), 3)[2 * 40 + x]));
        assert!(!wall_gaps(&map, &config(0, 5), 3).contains(&true));
    }

    /// The room and corridor of [`an_open_room_front_parts_room_and_corridor`] (walls 3 cells
    /// thick) turned by 30 degrees on a map whose units stay upright (a wing of a building at an angle): the
    /// gap is closed only along its own wall's direction.
    #[test]
    fn gaps_close_along_a_turned_wing() {
        let (w, h) = (120usize, 100usize);
        let mut upright = Grid::new(w, h, Cell::Free);
        fill(&mut upright, 0..40, 39..42, Cell::Occupied);
        fill(&mut upright, 80..w, 39..42, Cell::Occupied);
        let angle = 30f64.to_radians();
        let frame = crate::geometry::Frame::turned(200, 200, angle);
        let [ww, wh] = frame.world_size.map(|v| v as f64);
        // The building in the middle of the turned frame, solid outside.
        let (ox, oy) = ((ww - w as f64) / 2.0, (wh - h as f64) / 2.0);
        let mut map = Grid::new(200, 200, Cell::Occupied);
        for my in 0..200 {
            for mx in 0..200 {
                let (wx, wy) = frame.to_world(mx as f64 + 0.5, my as f64 + 0.5);
                let (x, y) = ((wx - ox).floor(), (wy - oy).floor());
                if x >= 0.0 && y >= 0.0 && (x as usize) < w && (y as usize) < h {
                    *map.at_mut(mx, my) = *upright.at(x as usize, y as usize);
                }
            }
        }
        let at = |x: f64, y: f64| {
            let (mx, my) = frame.to_map(x + ox, y + oy);
            (mx as usize, my as usize)
        };
        let (corridor, room) = (at(60.5, 20.5), at(60.5, 70.5));
        let mut world = World::empty(200, 200);
        world.wall_thickness = 3;
        world.units = vec![Unit::new(1, 0, 0, 200, 200, UnitType::Room)];
        let c = RoomCells { max_wall_gap: 50, min_wall_stub: 6, min_core_cells: 200, ..RoomCells::default() };
        let label = |labels: &Grid<u16>, (x, y): (usize, usize)| *labels.at(x, y);
        let upright_only = labels_of_groups(&world, &[1], &map, &map, &c);
        assert_eq!(label(&upright_only, corridor), label(&upright_only, room), "no upright wall has a gap");
        let turned = labels_of_groups_along(&world, &[1], &map, &map, &c, &[angle]);
        assert_ne!(label(&turned, corridor), 0);
        assert_ne!(label(&turned, corridor), label(&turned, room), "closed along the turned wall");
        // A frame of another direction finds no gap there.
        let other = labels_of_groups_along(&world, &[1], &map, &map, &c, &[-30f64.to_radians()]);
        assert_eq!(label(&other, corridor), label(&other, room));
    }

    /// A corridor along the top and, below it, a room whose front is open between two wall
    /// stubs, one unit over both: the room layer parts them only with gaps closed.
    #[test]
    fn an_open_room_front_parts_room_and_corridor() {
        let (w, h) = (120, 100);
        let mut map = Grid::new(w, h, Cell::Free);
        // Outer walls.
        fill(&mut map, 0..w, 0..1, Cell::Occupied);
        fill(&mut map, 0..w, h - 1..h, Cell::Occupied);
        fill(&mut map, 0..1, 0..h, Cell::Occupied);
        fill(&mut map, w - 1..w, 0..h, Cell::Occupied);
        // The corridor's lower wall at y = 40, open between x = 40 and x = 80.
        fill(&mut map, 0..40, 40..41, Cell::Occupied);
        fill(&mut map, 80..w, 40..41, Cell::Occupied);
        let mut world = World::empty(w as u32, h as u32);
        world.wall_thickness = 1;
        world.units = vec![Unit::new(1, 0, 0, w as i32, h as i32, UnitType::Room)];
        let c = RoomCells { max_wall_gap: 50, min_wall_stub: 6, min_core_cells: 200, ..RoomCells::default() };
        let labels = labels_of_groups(&world, &[1], &map, &map, &c);
        assert_ne!(labels.at(60, 20), labels.at(60, 70), "corridor and room are two segments");
        let open = labels_of_groups(&world, &[1], &map, &map, &RoomCells { max_wall_gap: 0, ..c });
        assert_eq!(open.at(60, 20), open.at(60, 70), "without gaps they are one");
        // 40 cells is over a 30-cell gap: the front stays open.
        let wide = labels_of_groups(&world, &[1], &map, &map, &RoomCells { max_wall_gap: 30, ..c });
        assert_eq!(wide.at(60, 20), wide.at(60, 70));
    }
}
