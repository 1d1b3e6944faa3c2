//! From units to rooms: the segmentation a room-segmentation benchmark scores.
//!
//! A unit is a rectangle; a real room may be L-shaped or cut by furniture into several units.
//! Going beyond the dissertation, units that touch along an *open* boundary (no wall cells in
//! the band between them) are one room. Every free map cell inside a room's units gets the
//! room's id; free cells outside all units (door openings, corners the units miss, scan rays)
//! join the nearest room by a wavefront through free space, as room-segmentation tools do.

use super::state::{facing, Axis};
use super::world::{Rect, World};
use crate::grid::{Cell, Grid};
use std::collections::VecDeque;

/// Parameters of the room grouping.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct RoomConfig {
    /// Largest share of occupied cells in the band between two units for their boundary to
    /// count as open.
    pub max_wall_share: f64,
    /// Shortest open boundary, in cells, that joins two units (shorter ones are doors).
    pub min_open_len: i32,
    /// How far (cells, through free space) the wavefront carries a room's label beyond its
    /// units. Free regions farther from every unit are rooms of their own, numbered after
    /// the units' rooms: a room the chain left unexplained is still a room, not an annex of
    /// its neighbour through the door.
    pub max_reach: u32,
    /// Smallest free region (cells) beyond every unit's reach that counts as a room; smaller
    /// ones (specks, scan rays) are not part of any room.
    pub min_room_cells: usize,
}

impl Default for RoomConfig {
    fn default() -> Self {
        RoomConfig { max_wall_share: 0.05, min_open_len: 30, max_reach: 20, min_room_cells: 400 }
    }
}

/// Whether a unit encloses space: at least half of its interior (inside the wall ring) is free
/// in the map. Units lying on thick walls or over unexplored space are not rooms.
pub fn encloses_space(u: &super::world::Unit, t: i32, world_map: &Grid<Cell>) -> bool {
    let (mut free, mut total) = (0u64, 0u64);
    for y in (u.y + t).max(0)..(u.y + u.h - t).min(world_map.height() as i32) {
        for x in (u.x + t).max(0)..(u.x + u.w - t).min(world_map.width() as i32) {
            total += 1;
            free += (*world_map.at(x as usize, y as usize) == Cell::Free) as u64;
        }
    }
    total > 0 && 2 * free >= total
}

/// Room id (1-based) of every unit, by unit index; 0 for units that enclose no space
/// ([`encloses_space`]).
pub fn group_units(world: &World, world_map: &Grid<Cell>, c: &RoomConfig) -> Vec<u16> {
    let n = world.units.len();
    let space: Vec<bool> = world.units.iter().map(|u| encloses_space(u, world.wall_thickness, world_map)).collect();
    let mut parent: Vec<usize> = (0..n).collect();
    fn find(p: &mut [usize], mut i: usize) -> usize {
        while p[i] != i {
            p[i] = p[p[i]];
            i = p[i];
        }
        i
    }
    let t = world.wall_thickness;
    let occupied = |r: Rect| -> (i64, i64) {
        let mut occ = 0;
        let mut total = 0;
        for y in r.y.max(0)..r.bottom().min(world_map.height() as i32) {
            for x in r.x.max(0)..r.right().min(world_map.width() as i32) {
                total += 1;
                occ += (*world_map.at(x as usize, y as usize) == Cell::Occupied) as i64;
            }
        }
        (occ, total)
    };
    for i in 0..n {
        for j in 0..n {
            if i == j || !space[i] || !space[j] {
                continue;
            }
            let (a, b) = (world.units[i].rect(), world.units[j].rect());
            let mut open = false;
            for axis in [Axis::Horizontal, Axis::Vertical] {
                let Some((s, e)) = facing(a, b, axis, t, t) else { continue };
                if e - s + 1 < c.min_open_len {
                    continue;
                }
                let band = match axis {
                    Axis::Horizontal => Rect::new(a.right() - t, s, b.x - a.right() + 2 * t, e - s + 1),
                    Axis::Vertical => Rect::new(s, a.bottom() - t, e - s + 1, b.y - a.bottom() + 2 * t),
                };
                let (occ, total) = occupied(band);
                open |= total > 0 && (occ as f64) <= c.max_wall_share * total as f64;
            }
            // Units overlapping by more than their walls are parts of one space.
            if let Some(inter) = a.intersection(&b) {
                if inter.w > 2 * t && inter.h > 2 * t {
                    let (occ, total) = occupied(inter);
                    open |= (occ as f64) <= c.max_wall_share * total as f64;
                }
            }
            if open {
                let (ri, rj) = (find(&mut parent, i), find(&mut parent, j));
                if ri != rj {
                    parent[ri.max(rj)] = ri.min(rj);
                }
            }
        }
    }
    // Number rooms by their first unit.
    let mut id_of_root = vec![0u16; n];
    let mut next = 0u16;
    (0..n)
        .map(|i| {
            if !space[i] {
                return 0;
            }
            let r = find(&mut parent, i);
            if id_of_root[r] == 0 {
                next += 1;
                id_of_root[r] = next;
            }
            id_of_root[r]
        })
        .collect()
}

/// The segmentation in the map's frame: every free map cell of a room gets the room's id
/// (1..=n), other cells 0. `world_map` is the classified map in the world frame, `map` in the
/// map frame.
pub fn room_labels(world: &World, map: &Grid<Cell>, world_map: &Grid<Cell>, c: &RoomConfig) -> Grid<u16> {
    let rooms = group_units(world, world_map, c);
    let (ww, wh) = (world_map.width(), world_map.height());
    // Owner room of every world cell: the first unit covering it.
    let mut owner = vec![0u16; ww * wh];
    for (u, &room) in world.units.iter().zip(&rooms) {
        if room == 0 {
            continue;
        }
        let r = u.rect();
        for y in r.y.max(0)..r.bottom().min(wh as i32) {
            for x in r.x.max(0)..r.right().min(ww as i32) {
                let o = &mut owner[y as usize * ww + x as usize];
                if *o == 0 {
                    *o = room;
                }
            }
        }
    }
    let mut labels = Grid::new(map.width(), map.height(), 0u16);
    let mut queue = VecDeque::new();
    for my in 0..map.height() {
        for mx in 0..map.width() {
            if *map.at(mx, my) != Cell::Free {
                continue;
            }
            let (wx, wy) = if world.frame.is_identity() {
                (mx as f64 + 0.5, my as f64 + 0.5)
            } else {
                world.frame.to_world(mx as f64 + 0.5, my as f64 + 0.5)
            };
            if wx >= 0.0 && wy >= 0.0 && (wx as usize) < ww && (wy as usize) < wh {
                let room = owner[wy as usize * ww + wx as usize];
                if room > 0 {
                    *labels.at_mut(mx, my) = room;
                    queue.push_back((mx, my));
                }
            }
        }
    }
    // Wavefront: unlabelled free cells within reach take the label of the nearest labelled one.
    let (w, h) = (map.width(), map.height());
    let mut dist = vec![0u32; w * h];
    while let Some((x, y)) = queue.pop_front() {
        let l = *labels.at(x, y);
        let d = dist[y * w + x];
        if d >= c.max_reach {
            continue;
        }
        for (nx, ny) in [(x.wrapping_sub(1), y), (x + 1, y), (x, y.wrapping_sub(1)), (x, y + 1)] {
            if nx < w && ny < h && *map.at(nx, ny) == Cell::Free && *labels.at(nx, ny) == 0 {
                *labels.at_mut(nx, ny) = l;
                dist[ny * w + nx] = d + 1;
                queue.push_back((nx, ny));
            }
        }
    }
    // Free regions out of every unit's reach: rooms of their own.
    let mut next = rooms.iter().copied().max().unwrap_or(0);
    let mut stack = Vec::new();
    for start in 0..w * h {
        let (sx, sy) = (start % w, start / w);
        if *map.at(sx, sy) != Cell::Free || *labels.at(sx, sy) != 0 {
            continue;
        }
        // Flood the region with a provisional id, then keep it only if it is big enough.
        let id = next.saturating_add(1);
        let mut region = vec![(sx, sy)];
        *labels.at_mut(sx, sy) = id;
        stack.push((sx, sy));
        while let Some((x, y)) = stack.pop() {
            for (nx, ny) in [(x.wrapping_sub(1), y), (x + 1, y), (x, y.wrapping_sub(1)), (x, y + 1)] {
                if nx < w && ny < h && *map.at(nx, ny) == Cell::Free && *labels.at(nx, ny) == 0 {
                    *labels.at_mut(nx, ny) = id;
                    stack.push((nx, ny));
                    region.push((nx, ny));
                }
            }
        }
        if region.len() >= c.min_room_cells {
            next = id;
        } else {
            // u16::MAX marks "seen, not a room" until the end.
            for (x, y) in region {
                *labels.at_mut(x, y) = u16::MAX;
            }
        }
    }
    for l in labels.cells_mut() {
        if *l == u16::MAX {
            *l = 0;
        }
    }
    labels
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::floorplan::{Unit, UnitType};

    fn unit(id: u32, x: i32, y: i32, w: i32, h: i32) -> Unit {
        Unit { id, x, y, w, h, kind: UnitType::Unknown }
    }

    #[test]
    fn open_boundaries_join_walls_separate() {
        // Two units side by side with no wall between them, a third behind a wall.
        let mut map = Grid::new(90, 40, Cell::Free);
        for y in 0..40 {
            *map.at_mut(60, y) = Cell::Occupied;
        }
        let mut world = World::empty(90, 40);
        world.units = vec![unit(1, 0, 0, 31, 40), unit(2, 30, 0, 31, 40), unit(3, 60, 0, 30, 40)];
        let rooms = group_units(&world, &map, &RoomConfig::default());
        assert_eq!(rooms, vec![1, 1, 2]);
        let labels = room_labels(&world, &map, &map, &RoomConfig::default());
        assert_eq!(*labels.at(5, 5), 1);
        assert_eq!(*labels.at(45, 5), 1);
        assert_eq!(*labels.at(75, 5), 2);
        assert_eq!(*labels.at(60, 5), 0, "walls are not labelled");
    }

    #[test]
    fn far_free_space_is_a_room_of_its_own() {
        // One unit on the left; a free region 60 cells away behind a doorway.
        let mut map = Grid::new(120, 20, Cell::Free);
        for y in 0..20 {
            if !(8..12).contains(&y) {
                *map.at_mut(40, y) = Cell::Occupied;
            }
        }
        let mut world = World::empty(120, 20);
        world.units = vec![unit(1, 0, 0, 20, 20)];
        let labels = room_labels(&world, &map, &map, &RoomConfig::default());
        assert_eq!(*labels.at(5, 5), 1);
        assert_eq!(*labels.at(25, 5), 1, "within reach of the unit");
        assert_eq!(*labels.at(100, 5), 2, "beyond reach: a room of its own");
    }

    #[test]
    fn wavefront_fills_free_cells_outside_units() {
        let mut map = Grid::new(50, 20, Cell::Unknown);
        for y in 2..18 {
            for x in 2..48 {
                *map.at_mut(x, y) = Cell::Free;
            }
        }
        let mut world = World::empty(50, 20);
        world.units = vec![unit(1, 0, 0, 20, 20), unit(2, 30, 0, 20, 20)];
        *map.at_mut(25, 0) = Cell::Free; // isolated: unreachable
        let labels = room_labels(&world, &map, &map, &RoomConfig::default());
        assert_eq!(*labels.at(22, 10), 1, "nearer to the left unit");
        assert_eq!(*labels.at(27, 10), 2, "nearer to the right unit");
        assert_eq!(*labels.at(25, 0), 0, "an isolated free cell is no room");
        assert_eq!(*labels.at(0, 0), 0, "unknown cells are not labelled");
    }
}
