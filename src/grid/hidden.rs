//! Occupied cells no sensor could have seen.
//!
//! A range sensor sees the faces of walls, not their inside. Some maps are drawn with
//! everything outside the building filled in as occupied (the floor plans of Bormann et al.);
//! taken at face value that solid mass is a huge "explained by walls" region the chain fills
//! with units of no use, and it makes walls look as thick as the mass. Occupied cells farther
//! from every free cell than any wall is thick are therefore treated as unknown, like the
//! unexplored space they are.

use super::flood::wavefront;
use super::{Cell, Grid};

/// How deep into occupied space, in metres, a wall face reaches: thicker than the walls of
/// ordinary buildings (about 0.3 - 0.5 m), so real walls keep all their cells.
pub const WALL_DEPTH_M: f64 = 0.6;

/// `grid` with every occupied cell more than `depth` cells (4-connected steps through
/// occupied cells) from the nearest free cell turned unknown. Occupied cells that no free cell
/// reaches through occupied cells are left alone: they are walls seen from unexplored space
/// (or scan noise there), evidence the chain should keep. So are occupied cells within `depth`
/// of unknown space: a thick band between free and unexplored space may be a wall seen from
/// both sides; only the inside of a mass enclosed by occupied cells is surely unseen.
pub fn hide_interior(grid: &Grid<Cell>, depth: u32) -> Grid<Cell> {
    let from_free = occupied_distance(grid, Cell::Free, u32::MAX - 1);
    if from_free.iter().all(|&d| d == u32::MAX) {
        return grid.clone();
    }
    let from_unknown = occupied_distance(grid, Cell::Unknown, depth);
    let mut out = grid.clone();
    for (i, c) in out.cells_mut().iter_mut().enumerate() {
        let d = from_free[i];
        if *c == Cell::Occupied && d > depth && d != u32::MAX && from_unknown[i] > depth {
            *c = Cell::Unknown;
        }
    }
    out
}

/// Steps (4-connected, through occupied cells) from the nearest `source` cell to every
/// occupied cell, counted up to `depth + 1` (cells farther away are left at `u32::MAX`, like
/// cells no source cell reaches).
fn occupied_distance(grid: &Grid<Cell>, source: Cell, depth: u32) -> Vec<u32> {
    let (w, h) = (grid.width(), grid.height());
    let cells = grid.cells();
    let neighbours = |i: usize| {
        let (x, y) = (i % w, i / w);
        [(x.wrapping_sub(1), y), (x + 1, y), (x, y.wrapping_sub(1)), (x, y + 1)]
            .into_iter()
            .filter(move |&(nx, ny)| nx < w && ny < h)
            .map(move |(nx, ny)| ny * w + nx)
    };
    let mut dist = vec![u32::MAX; w * h];
    // Only the source cells that touch an occupied cell start the wavefront: the others reach
    // nothing, and queueing every free cell of a large map took 13 MB.
    let mut seeds = Vec::new();
    for (i, &c) in cells.iter().enumerate() {
        if c == source {
            dist[i] = 0;
            if neighbours(i).any(|j| cells[j] == Cell::Occupied) {
                seeds.push(i);
            }
        }
    }
    wavefront(w, h, &mut dist, seeds, |j| cells[j] == Cell::Occupied, depth);
    dist
}

/// [`WALL_DEPTH_M`] in cells of a map with `resolution` metres per cell (at least 2).
pub fn depth_cells(resolution: f64) -> u32 {
    if resolution.is_finite() && resolution > 0.0 {
        (libm::ceil(WALL_DEPTH_M / resolution) as u32).max(2)
    } else {
        2
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_inside_of_a_solid_mass_becomes_unknown() {
        // A free room in a solid occupied block; a 2-cell wall splits the room.
        let mut g = Grid::new(60, 40, Cell::Occupied);
        for y in 15..25 {
            for x in 15..45 {
                *g.at_mut(x, y) = Cell::Free;
            }
        }
        for y in 15..25 {
            *g.at_mut(29, y) = Cell::Occupied;
            *g.at_mut(30, y) = Cell::Occupied;
        }
        let out = hide_interior(&g, 4);
        assert_eq!(*out.at(14, 20), Cell::Occupied, "a wall face stays");
        assert_eq!(*out.at(11, 20), Cell::Occupied, "four cells deep stays");
        assert_eq!(*out.at(10, 20), Cell::Unknown, "five cells deep is hidden");
        assert_eq!(*out.at(0, 0), Cell::Unknown);
        assert_eq!(*out.at(29, 20), Cell::Occupied, "an inner wall stays");
        assert_eq!(*out.at(20, 20), Cell::Free);
        // A thick blob in unknown space, touching no free cell, is kept.
        let mut g = Grid::new(40, 40, Cell::Unknown);
        for y in 0..30 {
            for x in 0..30 {
                *g.at_mut(x, y) = Cell::Occupied;
            }
        }
        *g.at_mut(39, 39) = Cell::Free;
        assert_eq!(hide_interior(&g, 2), g);
    }

    #[test]
    fn maps_without_free_space_are_left_alone() {
        let g = Grid::new(10, 10, Cell::Occupied);
        assert_eq!(hide_interior(&g, 2), g);
    }

    #[test]
    fn depth_in_cells_follows_the_resolution() {
        assert_eq!(depth_cells(0.05), 12);
        assert_eq!(depth_cells(0.5), 2);
        assert_eq!(depth_cells(f64::NAN), 2);
    }
}
