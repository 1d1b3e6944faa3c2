//! Possible objects (furniture) on an occupancy map: the cells the floor plan's semantic sensor
//! model (eq. 3.37) may forgive inside rooms, told apart from the building's walls and from the
//! unexplored space around it. A detector over the grid: it knows cells, not units.

use crate::geometry::{AreaCounts, Rect};
use crate::grid::flood::{Flood, Neighbours};
use crate::grid::{Cell, Grid};

/// The map cells the semantic sensor model may read as objects (furniture), counted by
/// rectangle in O(1).
///
/// The dissertation's semantic sensor model (eq. 3.37, Fig. 3.31) forgives non-free cells
/// inside rooms, halls and other units because they may be objects. Forgiving *every* such
/// cell also forgives the building itself: a unit then grows across a wall it should stop at,
/// or out into the unexplored space around the building, and buys the swallowed cells at the
/// object rate. So only cells that can be objects are forgiven (a departure from the letter of
/// eq. 3.37, which leaves "object" undefined):
///
/// * an occupied cell is part of an object unless it lies on a straight line of occupied cells
///   (along its row or its column, across doorways of up to half `max_object_m` between
///   stretches of at least 0.15 of it) at least
///   `max_object_m` long, or belongs to a connected group of occupied cells that spans that
///   much or touches such a line: walls are long lines broken by doors and joined into one
///   network, furniture outlines are small and stand apart (furniture pushed against a wall
///   joins the wall and is not forgiven, the price of never forgiving a wall);
/// * an unknown cell is part of an object unless it is connected through unknown cells to the
///   edge of the map: furniture shadows are enclosed by what the robot saw, the space outside
///   the building is not.
#[derive(Debug, Clone)]
pub struct ObjectCells {
    occupied: Option<AreaCounts>,
    unknown: Option<AreaCounts>,
}

impl ObjectCells {
    /// Finds the possible object cells of `map` (`resolution` metres per cell).
    pub fn new(map: &Grid<Cell>, resolution: f64, max_object_m: f64) -> ObjectCells {
        Self::counting(map, resolution, max_object_m, [true, true])
    }

    /// As [`ObjectCells::new`], counting only the classes asked for (`[occupied, unknown]`):
    /// the other counts are 0. A count table takes 4 bytes a cell, and the chain needs none
    /// for a class its sensor model does not forgive.
    pub fn counting(map: &Grid<Cell>, resolution: f64, max_object_m: f64, classes: [bool; 2]) -> ObjectCells {
        let lengths = Lengths::new(resolution, max_object_m);
        let mut flood = Flood::default();
        let mut structure = wall_lines(map, &lengths);
        join_wall_network(map, lengths.run, &mut structure, &mut flood);
        let outside = outside(map, &mut flood);
        let mut object = map.clone();
        for (i, c) in object.cells_mut().iter_mut().enumerate() {
            if (*c == Cell::Occupied && structure[i]) || (*c == Cell::Unknown && outside[i]) {
                *c = Cell::Free;
            }
        }
        ObjectCells {
            occupied: classes[0].then(|| AreaCounts::new(&object, Cell::Occupied)),
            unknown: classes[1].then(|| AreaCounts::new(&object, Cell::Unknown)),
        }
    }

    /// Occupied cells in `r` that may be objects.
    pub fn occupied_in(&self, r: Rect) -> u32 {
        self.occupied.as_ref().map_or(0, |c| c.count(r))
    }

    /// Unknown cells in `r` that may be objects.
    pub fn unknown_in(&self, r: Rect) -> u32 {
        self.unknown.as_ref().map_or(0, |c| c.count(r))
    }
}

/// The lengths, in cells, that tell walls from objects.
struct Lengths {
    /// `max_object_m`: a line (or a connected group) this long is structure.
    run: usize,
    /// A doorway: free cells between two stretches of the same wall line, up to half of it.
    doorway: usize,
    /// Wall stretches between doors are at least 0.15 `max_object_m` long (0.3 m); shorter
    /// pieces (a wall crossed edgeways, a chair) never join a line.
    stretch: usize,
}

impl Lengths {
    fn new(resolution: f64, max_object_m: f64) -> Self {
        Lengths {
            run: ((max_object_m / resolution).ceil() as usize).max(2),
            doorway: ((0.5 * max_object_m / resolution).ceil() as usize).max(1),
            stretch: ((0.15 * max_object_m / resolution).ceil() as usize).max(2),
        }
    }
}

/// Occupied cells on long row or column runs are structure, not objects. A run may pass
/// doorways (up to `doorway` free cells with occupied cells on both sides): a corridor wall is
/// one line broken by doors, and its stretches between doors may each be short.
fn wall_lines(map: &Grid<Cell>, lengths: &Lengths) -> Vec<bool> {
    let (w, h) = (map.width(), map.height());
    let mut structure = vec![false; w * h];
    for y in 0..h {
        mark_line(map, lengths, w, &|x| y * w + x, &mut structure);
    }
    for x in 0..w {
        mark_line(map, lengths, h, &|y| y * w + x, &mut structure);
    }
    structure
}

/// Marks the structure on one line of `len` cells, cell `i` of the line being map cell `at(i)`.
fn mark_line(map: &Grid<Cell>, lengths: &Lengths, len: usize, at: &dyn Fn(usize) -> usize, structure: &mut [bool]) {
    let class = |i: usize| map.cells()[at(i)];
    // Occupied stretches along the line, as [start, end).
    let mut stretches: Vec<(usize, usize)> = Vec::new();
    let mut i = 0;
    while i < len {
        if class(i) == Cell::Occupied {
            let s0 = i;
            while i < len && class(i) == Cell::Occupied {
                i += 1;
            }
            stretches.push((s0, i));
        } else {
            i += 1;
        }
    }
    let mut k = 0;
    while k < stretches.len() {
        // Chain long stretches across doorways: short gaps of free cells only.
        let mut last = k;
        while last + 1 < stretches.len() {
            let (a, b) = (stretches[last], stretches[last + 1]);
            let gap = b.0 - a.1;
            let joinable = a.1 - a.0 >= lengths.stretch
                && b.1 - b.0 >= lengths.stretch
                && gap <= lengths.doorway
                && (a.1..b.0).all(|j| class(j) == Cell::Free);
            if !joinable {
                break;
            }
            last += 1;
        }
        if stretches[last].1 - stretches[k].0 >= lengths.run {
            for &(s0, s1) in &stretches[k..=last] {
                for j in s0..s1 {
                    structure[at(j)] = true;
                }
            }
        }
        k = last + 1;
    }
}

/// Occupied components (8-connected) spanning `run` cells or more are structure too: a wall
/// stretch between two doors is short, but it hangs on the building's wall network. So is a
/// piece that touches a wall line.
fn join_wall_network(map: &Grid<Cell>, run: usize, structure: &mut [bool], flood: &mut Flood) {
    let (w, h) = (map.width(), map.height());
    let occupied = |i: usize| map.cells()[i] == Cell::Occupied;
    let mut seen = vec![false; w * h];
    let mut component: Vec<usize> = Vec::new();
    for start in 0..w * h {
        if seen[start] || !occupied(start) {
            continue;
        }
        component.clear();
        let (mut x0, mut y0, mut x1, mut y1) = (w, h, 0, 0);
        let enter = |j: usize| occupied(j) && !std::mem::replace(&mut seen[j], true);
        flood.fill(w, h, [start], Neighbours::Eight, enter, |i| {
            component.push(i);
            let (x, y) = (i % w, i / w);
            (x0, y0, x1, y1) = (x0.min(x), y0.min(y), x1.max(x), y1.max(y));
        });
        if x1 - x0 + 1 >= run || y1 - y0 + 1 >= run || component.iter().any(|&i| structure[i]) {
            for &i in &component {
                structure[i] = true;
            }
        }
    }
}

/// Unknown cells reachable from the map's edge through unknown cells: the outside of the
/// building, not furniture shadows (which what the robot saw encloses).
fn outside(map: &Grid<Cell>, flood: &mut Flood) -> Vec<bool> {
    let (w, h) = (map.width(), map.height());
    let mut outside = vec![false; w * h];
    let border = (0..w).flat_map(|x| [x, (h - 1) * w + x]).chain((0..h).flat_map(|y| [y * w, y * w + w - 1]));
    let enter = |i: usize| map.cells()[i] == Cell::Unknown && !std::mem::replace(&mut outside[i], true);
    flood.fill(w, h, border, Neighbours::Four, enter, |_| {});
    outside
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn object_cells_are_small_enclosed_things_not_walls_or_the_outside() {
        // 100 x 60 at 5 cm: a closed room (walls 2 cells), a 10 x 6 cell desk outline inside
        // with an unknown inside, a broken 30-cell wall stub hanging on the outer wall.
        let mut g = Grid::new(100, 60, Cell::Unknown);
        for y in 10..50 {
            for x in 10..90 {
                let wall = !(12..88).contains(&x) || !(12..48).contains(&y);
                *g.at_mut(x, y) = if wall { Cell::Occupied } else { Cell::Free };
            }
        }
        for y in 20..26 {
            for x in 40..50 {
                let edge = x == 40 || x == 49 || y == 20 || y == 25;
                *g.at_mut(x, y) = if edge { Cell::Occupied } else { Cell::Unknown };
            }
        }
        for x in 12..42 {
            *g.at_mut(x, 35) = Cell::Occupied;
        }
        let o = ObjectCells::new(&g, 0.05, 2.0);
        assert_eq!(o.occupied_in(Rect::new(0, 0, 100, 60)), 28, "only the desk outline");
        assert_eq!(o.unknown_in(Rect::new(0, 0, 100, 60)), 32, "only the desk's inside");
        assert_eq!(o.unknown_in(Rect::new(0, 0, 100, 10)), 0);
    }

    #[test]
    fn a_wall_broken_by_doorways_is_structure_short_pieces_are_objects() {
        // 120 x 40 at 5 cm, all free: a wall line (2 cells thick) at rows 20-21 whose pieces
        // between 16-cell (0.8 m) doorways are 14 cells (0.7 m), each far below 2 m.
        let mut g = Grid::new(120, 40, Cell::Free);
        for x in 0..120 {
            if x % 30 < 14 {
                for y in 20..22 {
                    *g.at_mut(x, y) = Cell::Occupied;
                }
            }
        }
        // Chairs along row 5: 5-cell pieces 3 cells apart (below the 0.3 m a wall piece has).
        for x in [10, 18, 26, 34, 42, 50] {
            for dx in 0..5 {
                *g.at_mut(x + dx, 5) = Cell::Occupied;
            }
        }
        let o = ObjectCells::new(&g, 0.05, 2.0);
        assert_eq!(o.occupied_in(Rect::new(0, 18, 120, 6)), 0, "the broken wall is one line");
        assert_eq!(o.occupied_in(Rect::new(0, 0, 120, 10)), 30, "the chairs stay objects");
        // The same wall with doorways wider than 1 m (half of 2 m) falls apart into objects.
        let mut wide = Grid::new(120, 40, Cell::Free);
        for x in (0..120).filter(|x| x % 40 < 14) {
            for y in 20..22 {
                *wide.at_mut(x, y) = Cell::Occupied;
            }
        }
        let o = ObjectCells::new(&wide, 0.05, 2.0);
        assert_eq!(o.occupied_in(Rect::new(0, 18, 120, 6)), 3 * 14 * 2);
    }
}
