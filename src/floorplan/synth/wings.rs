//! Two wings of a building at an angle (issue 13): the map the one-direction world model
//! explains badly, with its truth.
//!
//! Each wing is a building of the same configuration, planned and scanned on its own upright
//! canvas. The map holds the first wing's canvas turned by `rotation_deg` on the left and the
//! second's turned by `rotation_deg + wing_deg` on the right, their bounding boxes side by
//! side. Every map cell takes the canvas cell its centre falls on (nearest cell, as a rotated
//! single building does). A short passage of free cells with walls either side then joins the
//! two free cells of different wings that lie closest together, through both outer walls.
//!
//! The wing's canvas sits at an integer offset in the world frame [`Frame::turned`] gives for
//! its angle on the whole map, so its units are the canvas units moved by that offset, exactly:
//! the first wing's frame is the truth's `frame`, and the second wing's units carry its angle
//! ([`World::unit_frame`](crate::floorplan::World::unit_frame)).

use super::config::{turned_extent, Cells};
use super::scan::Observed;
use crate::geometry::Frame;
use crate::grid::{Cell, Grid};
use std::collections::VecDeque;

/// The map of two wings, before the scan's noise.
pub(super) struct Composed {
    /// The map's cells.
    pub cells: Grid<Cell>,
    /// Unit index + 1 (over both wings, the first wing's units first) on unit interiors.
    pub labels: Grid<u16>,
    /// Each wing's world frame on the map.
    pub frames: [Frame; 2],
    /// Each wing's canvas origin in its frame, cells.
    pub offsets: [(i32, i32); 2],
}

/// Lays the two wings' canvases side by side on the map, turned by `angles`, and joins them;
/// `units` is the first wing's unit count (the second's labels follow on).
pub(super) fn compose(wings: [&Observed; 2], angles: [f64; 2], units: u16, c: &Cells, door: i32) -> Composed {
    let (mw, mh) = c.map_size;
    let (cw, ch) = (c.canvas.0 as f64, c.canvas.1 as f64);
    let canvas = (c.canvas.0 as u32, c.canvas.1 as u32);
    let (first, second) = (turned_extent(canvas, angles[0]), turned_extent(canvas, angles[1]));
    let centres = [(first.0 / 2.0, mh as f64 / 2.0), (first.0 + second.0 / 2.0, mh as f64 / 2.0)];
    let frames = angles.map(|a| Frame::turned(mw, mh, a));
    let offsets = [0, 1].map(|k| {
        let (wx, wy) = frames[k].to_world(centres[k].0, centres[k].1);
        let [ww, wh] = frames[k].world_size;
        let ox = libm::round(wx - cw / 2.0).clamp(0.0, (ww as f64 - cw).max(0.0));
        let oy = libm::round(wy - ch / 2.0).clamp(0.0, (wh as f64 - ch).max(0.0));
        (ox as i32, oy as i32)
    });
    let mut cells = Grid::new(mw as usize, mh as usize, Cell::Unknown);
    let mut labels = Grid::new(mw as usize, mh as usize, 0u16);
    let mut wing_of = Grid::new(mw as usize, mh as usize, u8::MAX);
    let rotations = frames.map(|f| f.rotation());
    for my in 0..mh as usize {
        for mx in 0..mw as usize {
            for k in 0..2 {
                let (wx, wy) = rotations[k].to_world(mx as f64 + 0.5, my as f64 + 0.5);
                let (x, y) =
                    (libm::floor(wx) as i64 - offsets[k].0 as i64, libm::floor(wy) as i64 - offsets[k].1 as i64);
                if x < 0 || y < 0 || x >= c.canvas.0 as i64 || y >= c.canvas.1 as i64 {
                    continue;
                }
                let (x, y) = (x as usize, y as usize);
                *cells.at_mut(mx, my) = *wings[k].cells.at(x, y);
                let l = *wings[k].labels.at(x, y);
                *labels.at_mut(mx, my) = if l > 0 && k == 1 { l + units } else { l };
                *wing_of.at_mut(mx, my) = k as u8;
                break;
            }
        }
    }
    join(&mut cells, &mut labels, &wing_of, door, c.wall);
    Composed { cells, labels, frames, offsets }
}

/// Carves a passage `width` cells wide, with walls `wall` cells deep on either side where the
/// map is unknown, between the closest free cells of the two wings.
fn join(cells: &mut Grid<Cell>, labels: &mut Grid<u16>, wing_of: &Grid<u8>, width: i32, wall: i32) {
    let Some((a, b)) = closest_pair(cells, wing_of) else { return };
    let (w, h) = (cells.width(), cells.height());
    let (ax, ay, bx, by) = ((a % w) as f64, (a / w) as f64, (b % w) as f64, (b / w) as f64);
    let half = width as f64 / 2.0;
    let reach = half + wall as f64;
    let (x0, x1) = (ax.min(bx) - reach - 1.0, ax.max(bx) + reach + 1.0);
    let (y0, y1) = (ay.min(by) - reach - 1.0, ay.max(by) + reach + 1.0);
    for y in (y0.max(0.0) as usize)..=(y1.min(h as f64 - 1.0) as usize) {
        for x in (x0.max(0.0) as usize)..=(x1.min(w as f64 - 1.0) as usize) {
            let d = segment_distance((x as f64, y as f64), (ax, ay), (bx, by));
            if d <= half {
                *cells.at_mut(x, y) = Cell::Free;
                *labels.at_mut(x, y) = 0;
            } else if d <= reach && *cells.at(x, y) == Cell::Unknown {
                *cells.at_mut(x, y) = Cell::Occupied;
            }
        }
    }
}

/// The free cell of the second wing nearest (4-connected steps over any cells) to a free cell
/// of the first, with that cell: `(first, second)` as row-major indices. Ties break by index.
fn closest_pair(cells: &Grid<Cell>, wing_of: &Grid<u8>) -> Option<(usize, usize)> {
    let (w, n) = (cells.width(), cells.cells().len());
    let free = |i: usize, k: u8| cells.cells()[i] == Cell::Free && wing_of.cells()[i] == k;
    let mut source = vec![usize::MAX; n];
    let mut queue = VecDeque::new();
    for i in (0..n).filter(|&i| free(i, 0)) {
        source[i] = i;
        queue.push_back(i);
    }
    while let Some(i) = queue.pop_front() {
        if free(i, 1) {
            return Some((source[i], i));
        }
        let (x, y) = (i % w, i / w);
        let mut visit = |j: usize| {
            if source[j] == usize::MAX {
                source[j] = source[i];
                queue.push_back(j);
            }
        };
        if x > 0 {
            visit(i - 1);
        }
        if x + 1 < w {
            visit(i + 1);
        }
        if y > 0 {
            visit(i - w);
        }
        if i + w < n {
            visit(i + w);
        }
    }
    None
}

/// Distance from `p` to the segment `a`-`b`.
fn segment_distance(p: (f64, f64), a: (f64, f64), b: (f64, f64)) -> f64 {
    let (dx, dy) = (b.0 - a.0, b.1 - a.1);
    let len2 = dx * dx + dy * dy;
    let t = if len2 > 0.0 { (((p.0 - a.0) * dx + (p.1 - a.1) * dy) / len2).clamp(0.0, 1.0) } else { 0.0 };
    let (qx, qy) = (a.0 + t * dx - p.0, a.1 + t * dy - p.1);
    libm::sqrt(qx * qx + qy * qy)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_closest_free_cells_of_two_wings_are_joined() {
        // Two free blocks, the first wing's at columns 2-5, the second's at 14-17.
        let mut cells = Grid::new(20, 12, Cell::Unknown);
        let mut wing = Grid::new(20, 12, u8::MAX);
        for y in 2..10 {
            for x in (2..6).chain(14..18) {
                *cells.at_mut(x, y) = Cell::Free;
                *wing.at_mut(x, y) = u8::from(x >= 14);
            }
        }
        let (a, b) = closest_pair(&cells, &wing).unwrap();
        assert_eq!((a % 20, b % 20), (5, 14));
        let mut labels = Grid::new(20, 12, 1u16);
        join(&mut cells, &mut labels, &wing, 2, 1);
        // The passage is free all the way across, with walls either side.
        let row = a / 20;
        assert!((5..=14).all(|x| *cells.at(x, row) == Cell::Free && *labels.at(x, row) == 0));
        assert!((7..=12).all(|x| *cells.at(x, row + 2) == Cell::Occupied || *cells.at(x, row - 2) == Cell::Occupied));
        assert_eq!(segment_distance((1.0, 1.0), (0.0, 0.0), (2.0, 0.0)), 1.0);
    }
}
