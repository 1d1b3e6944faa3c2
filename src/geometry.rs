//! Plane geometry on the cell grid, shared by the detectors ([`crate::vision`]) and the floor
//! plan ([`crate::floorplan`]): axis-aligned [`Rect`]s of cells, the [`Frame`] that rotates a
//! map into the world frame, the [`Axis`] a door crosses, and [`AreaCounts`] / [`CellCounts`],
//! which count cells of a class inside any rectangle in O(1).
//!
//! It is a leaf: it knows grids and cells and nothing of units, chains or detectors, so that
//! `vision` and `floorplan` can both build on it without importing each other.
//!
//! ```
//! use ksmcmc::geometry::{AreaCounts, Rect};
//! use ksmcmc::grid::{Cell, Grid};
//!
//! let mut g = Grid::new(4, 3, Cell::Free);
//! *g.at_mut(1, 1) = Cell::Occupied;
//! let occupied = AreaCounts::new(&g, Cell::Occupied);
//! assert_eq!(occupied.count(Rect::new(0, 0, 2, 2)), 1);
//! assert_eq!(occupied.count(Rect::new(2, 0, 2, 3)), 0);
//! ```

use crate::grid::{Cell, Grid};
use serde::{Deserialize, Serialize};

/// An axis-aligned rectangle of cells: columns `x .. x + w`, rows `y .. y + h`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub struct Rect {
    /// Leftmost column.
    pub x: i32,
    /// Top row.
    pub y: i32,
    /// Width in cells.
    pub w: i32,
    /// Height in cells.
    pub h: i32,
}

impl Rect {
    /// A rectangle from its top-left cell and size.
    pub fn new(x: i32, y: i32, w: i32, h: i32) -> Self {
        Rect { x, y, w, h }
    }

    /// One past the rightmost column.
    pub fn right(&self) -> i32 {
        self.x + self.w
    }

    /// One past the bottom row.
    pub fn bottom(&self) -> i32 {
        self.y + self.h
    }

    /// Number of cells covered.
    pub fn area(&self) -> i64 {
        self.w.max(0) as i64 * self.h.max(0) as i64
    }

    /// The rectangle inside a wall ring `t` cells deep, if anything is left of it.
    pub fn interior(&self, t: i32) -> Option<Rect> {
        (self.w > 2 * t && self.h > 2 * t).then(|| Rect::new(self.x + t, self.y + t, self.w - 2 * t, self.h - 2 * t))
    }

    /// Whether cell `(x, y)` is inside.
    pub fn contains(&self, x: i32, y: i32) -> bool {
        x >= self.x && x < self.right() && y >= self.y && y < self.bottom()
    }

    /// Whether cell `(x, y)` is on the outer ring (a wall cell, eq. 3.8's `S_w`).
    pub fn on_border(&self, x: i32, y: i32) -> bool {
        self.in_ring(x, y, 1)
    }

    /// Whether cell `(x, y)` lies within `t` cells of the rectangle's edge: the walls of a unit
    /// whose walls are `t` cells thick.
    pub fn in_ring(&self, x: i32, y: i32, t: i32) -> bool {
        self.contains(x, y) && (x < self.x + t || y < self.y + t || x >= self.right() - t || y >= self.bottom() - t)
    }

    /// The centre in cell coordinates (cell centres at `+0.5`).
    pub fn center(&self) -> (f64, f64) {
        (self.x as f64 + self.w as f64 / 2.0, self.y as f64 + self.h as f64 / 2.0)
    }

    /// The overlap of two rectangles, if any.
    pub fn intersection(&self, o: &Rect) -> Option<Rect> {
        let x0 = self.x.max(o.x);
        let y0 = self.y.max(o.y);
        let x1 = self.right().min(o.right());
        let y1 = self.bottom().min(o.bottom());
        (x0 < x1 && y0 < y1).then(|| Rect::new(x0, y0, x1 - x0, y1 - y0))
    }
}

/// How the world frame sits on the map.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Frame {
    /// Rotation from the world frame to the map, radians, counter-clockwise in image terms
    /// (x right, y down). Read exactly (`crate::json`): a world's JSON reads back to the
    /// same text, and its rooms are found on the map turned by it.
    #[serde(deserialize_with = "crate::json::exact")]
    pub angle: f64,
    /// Width and height of the world-frame grid, cells.
    pub world_size: [u32; 2],
    /// Width and height of the map, cells.
    pub map_size: [u32; 2],
}

impl Frame {
    /// The identity frame for a map of the given size.
    pub fn identity(width: u32, height: u32) -> Self {
        Frame { angle: 0.0, world_size: [width, height], map_size: [width, height] }
    }

    /// Whether world cells are map cells.
    pub fn is_identity(&self) -> bool {
        self.angle == 0.0 && self.world_size == self.map_size
    }

    /// The frame of a map of `width` x `height` cells turned by `angle`: the world grid is the
    /// smallest that holds the whole turned map.
    ///
    /// ```
    /// use ksmcmc::geometry::Frame;
    /// // A 100 x 10 map turned by 30 degrees: 100 cos 30 + 10 sin 30 = 91.6 and
    /// // 100 sin 30 + 10 cos 30 = 58.7 cells.
    /// let f = Frame::turned(100, 10, 30f64.to_radians());
    /// assert_eq!(f.world_size, [92, 59]);
    /// assert_eq!(Frame::turned(100, 10, 0.0), Frame::identity(100, 10));
    /// ```
    pub fn turned(width: u32, height: u32, angle: f64) -> Frame {
        if angle == 0.0 {
            return Frame::identity(width, height);
        }
        let (w, h) = (width as f64, height as f64);
        let (s, c) = (libm::fabs(libm::sin(angle)), libm::fabs(libm::cos(angle)));
        let ww = libm::ceil(w * c + h * s) as u32;
        let wh = libm::ceil(w * s + h * c) as u32;
        Frame { angle, world_size: [ww, wh], map_size: [width, height] }
    }

    /// Maps a world-frame point (cell units, continuous) to map coordinates.
    pub fn to_map(&self, x: f64, y: f64) -> (f64, f64) {
        self.rotation().to_map(x, y)
    }

    /// Maps a map point to the world frame (the inverse of [`Frame::to_map`]).
    pub fn to_world(&self, x: f64, y: f64) -> (f64, f64) {
        self.rotation().to_world(x, y)
    }

    /// The bounding box `[x0, y0, x1, y1]` on the map of rectangle `r` of this frame, from its
    /// corners.
    pub fn map_box(&self, r: Rect) -> [f64; 4] {
        let rot = self.rotation();
        let corners = [(r.x, r.y), (r.right(), r.y), (r.x, r.bottom()), (r.right(), r.bottom())]
            .map(|(x, y)| rot.to_map(x as f64, y as f64));
        let min = |v: [f64; 4]| v.iter().copied().fold(f64::INFINITY, f64::min);
        let max = |v: [f64; 4]| v.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        let (xs, ys) = (corners.map(|c| c.0), corners.map(|c| c.1));
        [min(xs), min(ys), max(xs), max(ys)]
    }

    /// The cells `(x, y)` of a `w` x `h` map whose centres fall, in this frame, on rectangle
    /// `r`, row by row: every cell of its box on the map ([`Frame::map_box`], with a cell to
    /// spare on the far side) is checked, so a turned frame misses none. The rotation is worked
    /// out once for all of them.
    ///
    /// ```
    /// use ksmcmc::geometry::{Frame, Rect};
    /// let upright = Frame::identity(10, 10);
    /// let cells: Vec<_> = upright.map_cells(Rect::new(8, 1, 4, 2), 10, 10).collect();
    /// assert_eq!(cells, [(8, 1), (9, 1), (8, 2), (9, 2)]);
    /// ```
    pub fn map_cells(&self, r: Rect, w: usize, h: usize) -> impl Iterator<Item = (usize, usize)> {
        let rot = self.rotation();
        let [min_x, min_y, max_x, max_y] = self.map_box(r);
        let lo = |v: f64, n: usize| (libm::floor(v).max(0.0) as usize).min(n);
        let hi = |v: f64, n: usize| (libm::ceil(v).max(0.0) as usize + 1).min(n);
        let (x0, x1) = (lo(min_x, w), hi(max_x, w));
        (lo(min_y, h)..hi(max_y, h)).flat_map(move |y| (x0..x1).map(move |x| (x, y))).filter(move |&(x, y)| {
            let (wx, wy) = rot.to_world(x as f64 + 0.5, y as f64 + 0.5);
            r.contains(libm::floor(wx) as i32, libm::floor(wy) as i32)
        })
    }

    /// The frame's rotation with its sine and cosine worked out once, for loops over cells.
    pub fn rotation(&self) -> Rotation {
        Rotation {
            s: libm::sin(self.angle),
            c: libm::cos(self.angle),
            world_half: (self.world_size[0] as f64 / 2.0, self.world_size[1] as f64 / 2.0),
            map_half: (self.map_size[0] as f64 / 2.0, self.map_size[1] as f64 / 2.0),
        }
    }
}

/// A [`Frame`]'s rotation about the centres of the world grid and the map.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Rotation {
    s: f64,
    c: f64,
    world_half: (f64, f64),
    map_half: (f64, f64),
}

impl Rotation {
    /// [`Frame::to_map`].
    #[inline]
    pub fn to_map(&self, x: f64, y: f64) -> (f64, f64) {
        let (s, c) = (self.s, self.c);
        let (wx, wy) = (x - self.world_half.0, y - self.world_half.1);
        (self.map_half.0 + c * wx - s * wy, self.map_half.1 + s * wx + c * wy)
    }

    /// [`Frame::to_world`].
    #[inline]
    pub fn to_world(&self, x: f64, y: f64) -> (f64, f64) {
        let (s, c) = (self.s, self.c);
        let (mx, my) = (x - self.map_half.0, y - self.map_half.1);
        (self.world_half.0 + c * mx + s * my, self.world_half.1 - s * mx + c * my)
    }
}

/// Which way a door crosses the wall(s) between its two units.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Axis {
    /// `lo` lies left of `hi`; the door crosses vertical walls and spans rows.
    Horizontal,
    /// `lo` lies above `hi`; the door crosses horizontal walls and spans columns.
    Vertical,
}

/// Summed-area table of one cell class: the count inside any rectangle in O(1).
#[derive(Debug, Clone)]
pub struct AreaCounts {
    width: usize,
    // Kept beside `sums` rather than divided out of its length: `count` runs millions of
    // times a chain, and an integer division was a tenth of its cost.
    height: usize,
    sums: Vec<u32>,
}

impl AreaCounts {
    /// Counts cells of class `class` in `map`.
    pub fn new(map: &Grid<Cell>, class: Cell) -> Self {
        let (w, h) = (map.width(), map.height());
        let mut sums = vec![0u32; (w + 1) * (h + 1)];
        for y in 0..h {
            let mut row = 0u32;
            for x in 0..w {
                row += (*map.at(x, y) == class) as u32;
                sums[(y + 1) * (w + 1) + x + 1] = sums[y * (w + 1) + x + 1] + row;
            }
        }
        AreaCounts { width: w, height: h, sums }
    }

    /// Number of counted cells in `r` (clipped to the map).
    #[inline]
    pub fn count(&self, r: Rect) -> u32 {
        let h = self.height;
        let x0 = r.x.clamp(0, self.width as i32) as usize;
        let x1 = r.right().clamp(0, self.width as i32) as usize;
        let y0 = r.y.clamp(0, h as i32) as usize;
        let y1 = r.bottom().clamp(0, h as i32) as usize;
        if x0 >= x1 || y0 >= y1 {
            return 0;
        }
        let s = |x: usize, y: usize| self.sums[y * (self.width + 1) + x];
        s(x1, y1) + s(x0, y0) - s(x0, y1) - s(x1, y0)
    }
}

/// The cell counts the detectors ask about a rectangle: occupied, unknown and free cells of one
/// classified map, from two summed-area tables (free cells are the rest: a third table would
/// cost 4 bytes a cell for nothing).
#[derive(Debug, Clone)]
pub struct CellCounts {
    occupied: AreaCounts,
    unknown: AreaCounts,
    width: i32,
    height: i32,
}

impl CellCounts {
    /// Counts the classes of `map`.
    pub fn new(map: &Grid<Cell>) -> Self {
        CellCounts {
            occupied: AreaCounts::new(map, Cell::Occupied),
            unknown: AreaCounts::new(map, Cell::Unknown),
            width: map.width() as i32,
            height: map.height() as i32,
        }
    }

    /// Occupied cells inside a rectangle (clipped to the map).
    #[inline]
    pub fn occupied_in(&self, r: Rect) -> u32 {
        self.occupied.count(r)
    }

    /// Unknown cells inside a rectangle (clipped to the map).
    #[inline]
    pub fn unknown_in(&self, r: Rect) -> u32 {
        self.unknown.count(r)
    }

    /// Free cells inside a rectangle: its cells on the map that are neither occupied nor
    /// unknown.
    #[inline]
    pub fn free_in(&self, r: Rect) -> u32 {
        let w = (r.right().min(self.width) - r.x.max(0)).max(0);
        let h = (r.bottom().min(self.height) - r.y.max(0)).max(0);
        (w * h) as u32 - self.occupied.count(r) - self.unknown.count(r)
    }
}

/// The interior range two facing units share along their walls, if they face each other:
/// `hi` lies beyond `lo` (their wall rings of depth `t` may overlap, their rectangles may be
/// up to `max_gap` cells apart), and their interiors overlap along the walls.
pub fn facing(lo: Rect, hi: Rect, axis: Axis, max_gap: i32, t: i32) -> Option<(i32, i32)> {
    // In i64: unchecked worlds (a world.json from anywhere) may hold extreme coordinates.
    let end = |a: i32, len: i32| a as i64 + len as i64;
    let (gap, a0, a1, b0, b1) = match axis {
        Axis::Horizontal => (hi.x as i64 - end(lo.x, lo.w), lo.y as i64, end(lo.y, lo.h), hi.y as i64, end(hi.y, hi.h)),
        Axis::Vertical => (hi.y as i64 - end(lo.y, lo.h), lo.x as i64, end(lo.x, lo.w), hi.x as i64, end(hi.x, hi.w)),
    };
    let t = t as i64;
    if gap < -t || gap > max_gap as i64 {
        return None;
    }
    // Interior rows (or columns) of both: exclude each unit's corner walls.
    let s = (a0 + t).max(b0 + t);
    let e = (a1 - 1 - t).min(b1 - 1 - t);
    (s <= e && s >= i32::MIN as i64 && e <= i32::MAX as i64).then_some((s as i32, e as i32))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// 12 x 9, free but for an occupied top row and an unknown bottom row.
    fn map() -> Grid<Cell> {
        let mut g = Grid::new(12, 9, Cell::Free);
        for x in 0..12 {
            *g.at_mut(x, 0) = Cell::Occupied;
            *g.at_mut(x, 8) = Cell::Unknown;
        }
        g
    }

    #[test]
    fn area_counts_clip_to_the_map() {
        let m = map();
        let occ = AreaCounts::new(&m, Cell::Occupied);
        assert_eq!(occ.count(Rect::new(0, 0, 12, 9)), 12);
        assert_eq!(occ.count(Rect::new(3, 0, 4, 1)), 4);
        assert_eq!(occ.count(Rect::new(3, 1, 4, 7)), 0);
        assert_eq!(occ.count(Rect::new(-5, -5, 100, 100)), 12);
        let free = AreaCounts::new(&m, Cell::Free);
        assert_eq!(free.count(Rect::new(2, 2, 3, 3)), 9);
    }

    #[test]
    fn cell_counts_free_is_the_rest() {
        let c = CellCounts::new(&map());
        let all = Rect::new(-3, -3, 30, 30);
        assert_eq!((c.occupied_in(all), c.unknown_in(all), c.free_in(all)), (12, 12, 12 * 7));
        assert_eq!(c.free_in(Rect::new(10, 7, 5, 5)), 2);
    }
}
