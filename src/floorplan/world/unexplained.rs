//! Unexplained free areas: the "N" of the papers.
//!
//! The dissertation's world leaves some free space outside every unit (section 3.4: areas "too
//! small to be recognized" as units, Tab. 3.7's discussion of partly explored space). They are
//! part of the explanation, not noise to hide: a floor-plan tool wants to know where the model
//! gave up, and a large one is a hint that a room was missed. This module finds them in the
//! world frame: 4-connected components of free map cells covered by no unit rectangle (wall
//! ring included) and no door, listed as row runs so that a reader can redraw them exactly.

use crate::floorplan::world::{Rect, UnexplainedArea};
use crate::grid::flood::{Flood, Neighbours};
use crate::grid::{Cell, Grid};

/// Components smaller than this many cells are not listed: single free cells and specks
/// outside the building are scan noise, not areas (a 3x3 block is the smallest listed shape
/// that is not a line of noise).
pub const MIN_UNEXPLAINED_CELLS: usize = 9;

/// The unexplained free areas of `world_map` (classified cells in the world frame) given the
/// units' rectangles and the doors' rectangles, ordered by their first cell (row by row) and
/// numbered from 1. Components of fewer than `min_cells` cells are skipped.
///
/// ```
/// use ksmcmc::floorplan::unexplained::unexplained_areas;
/// use ksmcmc::floorplan::Rect;
/// use ksmcmc::grid::{Cell, Grid};
///
/// let mut map = Grid::new(12, 6, Cell::Free);
/// // One unit explains the left half; the right half (6x6 = 36 cells) is unexplained.
/// let areas = unexplained_areas(&map, &[Rect::new(0, 0, 6, 6)], &[], 9);
/// assert_eq!(areas.len(), 1);
/// assert_eq!(areas[0].cells, 36);
/// assert_eq!((areas[0].x0, areas[0].y0, areas[0].x1, areas[0].y1), (6, 0, 11, 5));
/// assert_eq!(areas[0].runs[0], [0, 6, 11]); // row 0, columns 6..=11
/// ```
pub fn unexplained_areas(
    world_map: &Grid<Cell>,
    units: &[Rect],
    doors: &[Rect],
    min_cells: usize,
) -> Vec<UnexplainedArea> {
    let (w, h) = (world_map.width(), world_map.height());
    if w == 0 || h == 0 {
        return Vec::new();
    }
    // open[i]: a free cell that nothing explains. Rectangles are clipped to the grid.
    let mut open: Vec<bool> = world_map.cells().iter().map(|&c| c == Cell::Free).collect();
    for r in units.iter().chain(doors) {
        let (x0, y0) = (r.x.max(0) as usize, r.y.max(0) as usize);
        let (x1, y1) = (r.right().clamp(0, w as i32) as usize, r.bottom().clamp(0, h as i32) as usize);
        for y in y0..y1 {
            open[y * w + x0.min(x1)..y * w + x1].fill(false);
        }
    }

    let mut areas = Vec::new();
    let mut flood = Flood::default();
    let mut members = Vec::new();
    for start in 0..w * h {
        if !open[start] {
            continue;
        }
        members.clear();
        let enter = |j: usize| std::mem::replace(&mut open[j], false);
        flood.fill(w, h, [start], Neighbours::Four, enter, |i| members.push(i));
        if members.len() < min_cells {
            continue;
        }
        // The standard sort: an area can hold most of a large map's cells (crate::sort's
        // indirect comparisons made the setup on Cartesium a fifth slower).
        members.sort_unstable();
        areas.push(area_of(&members, w, areas.len() as u32 + 1));
    }
    areas
}

/// The area record of a component given its cell indices in row-major order.
fn area_of(members: &[usize], w: usize, id: u32) -> UnexplainedArea {
    let mut runs: Vec<[i32; 3]> = Vec::new();
    let (mut x0, mut y0, mut x1, mut y1) = (i32::MAX, i32::MAX, i32::MIN, i32::MIN);
    for &i in members {
        let (x, y) = ((i % w) as i32, (i / w) as i32);
        (x0, y0, x1, y1) = (x0.min(x), y0.min(y), x1.max(x), y1.max(y));
        match runs.last_mut() {
            Some(run) if run[0] == y && run[2] + 1 == x => run[2] = x,
            _ => runs.push([y, x, x]),
        }
    }
    UnexplainedArea { id, cells: members.len() as u32, x0, y0, x1, y1, runs }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn map_from(rows: &[&str]) -> Grid<Cell> {
        let mut g = Grid::new(rows[0].len(), rows.len(), Cell::Unknown);
        for (y, row) in rows.iter().enumerate() {
            for (x, c) in row.bytes().enumerate() {
                *g.at_mut(x, y) = match c {
                    b'.' => Cell::Free,
                    b'#' => Cell::Occupied,
                    _ => Cell::Unknown,
                };
            }
        }
        g
    }

    #[test]
    fn components_are_separated_by_walls_and_counted_exactly() {
        let map = map_from(&[
            "....#...", //
            "....#...", "....#...", "#####...", "?????..?",
        ]);
        let areas = unexplained_areas(&map, &[], &[], 1);
        assert_eq!(areas.len(), 2);
        assert_eq!(areas[0].cells, 12);
        assert_eq!((areas[0].x0, areas[0].y0, areas[0].x1, areas[0].y1), (0, 0, 3, 2));
        assert_eq!(areas[1].cells, 3 * 4 + 2);
        assert_eq!(areas[1].runs.last(), Some(&[4, 5, 6]));
        // Every run is inside the bounding box and the runs add up to the count.
        for a in &areas {
            let sum: i32 = a.runs.iter().map(|r| r[2] - r[1] + 1).sum();
            assert_eq!(sum as u32, a.cells);
        }
        assert_eq!(areas.iter().map(|a| a.id).collect::<Vec<_>>(), vec![1, 2]);
    }

    #[test]
    fn units_doors_and_small_specks_explain_or_hide_cells() {
        let map = map_from(&[
            "......", //
            "......", "......", "......",
        ]);
        // A unit over columns 0..4 and a door over column 4 leave column 5 (4 cells).
        let areas = unexplained_areas(&map, &[Rect::new(0, 0, 4, 4)], &[Rect::new(4, 0, 1, 4)], 1);
        assert_eq!(areas.len(), 1);
        assert_eq!(areas[0].cells, 4);
        assert_eq!(areas[0].runs, vec![[0, 5, 5], [1, 5, 5], [2, 5, 5], [3, 5, 5]]);
        // Below the size floor, nothing is listed.
        assert!(unexplained_areas(&map, &[Rect::new(0, 0, 4, 4)], &[Rect::new(4, 0, 1, 4)], 5).is_empty());
        // Rectangles reaching past the grid are clipped, not a panic.
        assert!(unexplained_areas(&map, &[Rect::new(-5, -5, 100, 100)], &[], 1).is_empty());
    }
}
