//! Shortest paths over the cells of a map: the moves a robot makes on a grid.
//!
//! A path steps to any of the 8 neighbours of a cell, onto free cells only, and never cuts a
//! corner: a diagonal step needs both cells beside it (the two 4-neighbours it passes between)
//! to be not occupied, or the robot would brush through the end of a wall. Steps cost
//! [`STRAIGHT`] and [`DIAGONAL`], integers in the ratio 1 : sqrt(2) to within 0.005 %, so that
//! searches compare exact integers, the same natively and in wasm.
//!
//! [`Search`] keeps one distance table of the map's size and reuses it between searches
//! (resetting only the cells a search touched): the route planner runs a few searches per
//! route, each over a room or a handful of rooms, not over the whole map. Distances are `u32`:
//! the longest possible path, every cell of the largest map once, costs under 2^32.
//! The path itself is read back from the distances (each step goes to a neighbour whose
//! distance plus the step's cost is the cell's own), so no parent table is kept.

use crate::grid::{Cell, Grid};
use std::cmp::Reverse;
use std::collections::BinaryHeap;

/// Cost of a step to a 4-neighbour.
pub const STRAIGHT: u32 = 70;
/// Cost of a diagonal step (99/70 = 1.41429, sqrt(2) = 1.41421).
pub const DIAGONAL: u32 = 99;
/// No path (yet).
pub const FAR: u32 = u32::MAX;

/// The 8 moves, straight ones first.
const MOVES: [(i32, i32); 8] = [(1, 0), (-1, 0), (0, 1), (0, -1), (1, 1), (1, -1), (-1, 1), (-1, -1)];

/// The octile distance between cells `a` and `b` of a `w`-wide grid, in step costs: the cost
/// of the shortest path on an empty grid, which no path through walls beats.
pub fn octile(a: usize, b: usize, w: usize) -> u64 {
    let (dx, dy) = ((a % w).abs_diff(b % w) as u64, (a / w).abs_diff(b / w) as u64);
    let (lo, hi) = (dx.min(dy), dx.max(dy));
    lo * DIAGONAL as u64 + (hi - lo) * STRAIGHT as u64
}

/// The cell reached from `i` by move `(dx, dy)`, if the move is allowed on `map`: the target
/// is on the map and free, and a diagonal move cuts no occupied corner.
fn step(map: &Grid<Cell>, i: usize, (dx, dy): (i32, i32)) -> Option<usize> {
    let (w, h) = (map.width() as i64, map.height() as i64);
    let (x, y) = ((i as i64) % w, (i as i64) / w);
    let (nx, ny) = (x + dx as i64, y + dy as i64);
    if nx < 0 || ny < 0 || nx >= w || ny >= h {
        return None;
    }
    let cell = |x: i64, y: i64| *map.at(x as usize, y as usize);
    if cell(nx, ny) != Cell::Free {
        return None;
    }
    if dx != 0 && dy != 0 && (cell(nx, y) == Cell::Occupied || cell(x, ny) == Cell::Occupied) {
        return None;
    }
    Some((ny * w + nx) as usize)
}

fn cost((dx, dy): (i32, i32)) -> u32 {
    if dx != 0 && dy != 0 {
        DIAGONAL
    } else {
        STRAIGHT
    }
}

/// Searches over the free cells of one map (see the module docs).
#[derive(Debug, Clone)]
pub struct Search {
    dist: Vec<u32>,
    touched: Vec<u32>,
    heap: BinaryHeap<Reverse<(u64, u32)>>,
}

impl Search {
    /// A search table for a map of `cells` cells.
    pub fn new(cells: usize) -> Search {
        Search { dist: vec![FAR; cells], touched: Vec::new(), heap: BinaryHeap::new() }
    }

    fn reset(&mut self) {
        for &i in &self.touched {
            self.dist[i as usize] = FAR;
        }
        self.touched.clear();
        self.heap.clear();
    }

    fn relax(&mut self, i: usize, d: u32, priority: u64) {
        if d < self.dist[i] {
            if self.dist[i] == FAR {
                self.touched.push(i as u32);
            }
            self.dist[i] = d;
            self.heap.push(Reverse((priority, i as u32)));
        }
    }

    /// The distance from the last search's source to `i` ([`FAR`] if not reached).
    pub fn dist(&self, i: usize) -> u32 {
        self.dist[i]
    }

    /// Distances from `source` to every cell of `allowed` it reaches (Dijkstra). `source` must
    /// be free and allowed.
    pub fn from(&mut self, map: &Grid<Cell>, allowed: &dyn Fn(usize) -> bool, source: usize) {
        self.reset();
        self.relax(source, 0, 0);
        while let Some(Reverse((d, i))) = self.heap.pop() {
            let i = i as usize;
            if d > self.dist[i] as u64 {
                continue;
            }
            for m in MOVES {
                if let Some(j) = step(map, i, m).filter(|&j| allowed(j)) {
                    let nd = self.dist[i].saturating_add(cost(m));
                    self.relax(j, nd, nd as u64);
                }
            }
        }
    }

    /// The shortest path from `start` to `goal` over the cells of `allowed` (A* with the
    /// octile distance), as its cells from start to goal and its cost; `None` if there is
    /// none. Both ends must be free and allowed.
    pub fn path(
        &mut self,
        map: &Grid<Cell>,
        allowed: &dyn Fn(usize) -> bool,
        start: usize,
        goal: usize,
    ) -> Option<(Vec<usize>, u32)> {
        let w = map.width();
        self.reset();
        self.relax(start, 0, octile(start, goal, w));
        while let Some(Reverse((f, i))) = self.heap.pop() {
            let i = i as usize;
            if i == goal {
                break;
            }
            if f > self.dist[i] as u64 + octile(i, goal, w) {
                continue;
            }
            for m in MOVES {
                if let Some(j) = step(map, i, m).filter(|&j| allowed(j)) {
                    let nd = self.dist[i].saturating_add(cost(m));
                    self.relax(j, nd, nd as u64 + octile(j, goal, w));
                }
            }
        }
        let total = self.dist[goal];
        (total != FAR).then(|| (self.trace_back(map, goal), total))
    }

    /// The cells from the last search's source to `goal`, read back from the distances.
    fn trace_back(&self, map: &Grid<Cell>, goal: usize) -> Vec<usize> {
        let mut path = vec![goal];
        let mut i = goal;
        while self.dist[i] != 0 {
            // A neighbour `j` with dist[j] + cost(j -> i) = dist[i] exists: the cell dist[i]
            // was last lowered from. Moves are symmetric, so j -> i is allowed when i -> j is.
            let Some(j) = MOVES.iter().find_map(|&m| {
                let j = step(map, i, m)?;
                (self.dist[j] != FAR && self.dist[j].checked_add(cost(m)) == Some(self.dist[i])).then_some(j)
            }) else {
                break; // cannot happen: distances come from such steps
            };
            path.push(j);
            i = j;
        }
        path.reverse();
        path
    }
}

/// Whether consecutive cells of `path` (indices into a `w`-wide grid) are 8-neighbours.
pub fn is_connected(path: &[usize], w: usize) -> bool {
    path.windows(2).all(|p| {
        let (dx, dy) = ((p[0] % w).abs_diff(p[1] % w), (p[0] / w).abs_diff(p[1] / w));
        dx <= 1 && dy <= 1 && (dx, dy) != (0, 0)
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A 9 x 5 free map with a wall at column 4, open at row 4 only.
    fn walled() -> Grid<Cell> {
        let mut map = Grid::new(9, 5, Cell::Free);
        for y in 0..4 {
            *map.at_mut(4, y) = Cell::Occupied;
        }
        map
    }

    #[test]
    fn paths_go_round_walls_without_cutting_corners() {
        let map = walled();
        let mut s = Search::new(map.len());
        let all = |_| true;
        let (path, cost) = s.path(&map, &all, 0, 8).unwrap();
        assert_eq!((path[0], *path.last().unwrap()), (0, 8));
        assert!(is_connected(&path, 9));
        assert!(path.iter().all(|&i| map.cells()[i] == Cell::Free));
        // Down to row 4 and back up: no diagonal step past the wall's end at (4, 3).
        assert!(path.contains(&(4 * 9 + 4)), "{path:?}");
        assert!(!path.windows(2).any(|p| p == [3 * 9 + 3, 4 * 9 + 4]), "cut the corner: {path:?}");
        // Dijkstra agrees with A* on the cost.
        s.from(&map, &all, 0);
        assert_eq!(s.dist(8), cost);
        assert_eq!(s.dist(0), 0);
    }

    #[test]
    fn allowed_cells_bound_the_search() {
        let map = walled();
        let mut s = Search::new(map.len());
        // Row 4 forbidden: the two halves are not connected.
        let upper = |i: usize| i / 9 < 4;
        assert!(s.path(&map, &upper, 0, 8).is_none());
        s.from(&map, &upper, 0);
        assert_eq!(s.dist(8), FAR);
        assert_eq!(s.dist(3), 3 * STRAIGHT);
    }

    #[test]
    fn octile_is_the_empty_grid_distance() {
        let map = Grid::new(10, 10, Cell::Free);
        let mut s = Search::new(100);
        s.from(&map, &|_| true, 0);
        for i in 0..100 {
            assert_eq!(s.dist(i) as u64, octile(0, i, 10), "cell {i}");
        }
    }
}
