//! Which units touch along an open boundary, and the rooms they make when joined.
//!
//! A unit is a rectangle; a real room may be L-shaped or cut by furniture into several units.
//! Going beyond the dissertation, units that touch along an *open* boundary (no wall cells in
//! the band between them; chairs and other clutter are no walls) are candidates for one room
//! ([`open_pairs`]); the room rules decide which are ([`super::layer`]), and [`join`] numbers
//! the rooms the joined pairs make.

use super::config::RoomCells;
use super::wall_gaps::without_clutter;
use crate::floorplan::world::{Rect, World};
use crate::geometry::{facing, Axis};
use crate::grid::{Cell, Grid};
use crate::union_find::UnionFind;

/// Whether a unit encloses space: at least half of its interior (inside the wall ring) is free
/// in the map. Units lying on thick walls or over unexplored space are not rooms.
pub fn encloses_space(u: &crate::floorplan::world::Unit, t: i32, world_map: &Grid<Cell>) -> bool {
    let (mut free, mut total) = (0u64, 0u64);
    for y in (u.y + t).max(0)..(u.y + u.h - t).min(world_map.height() as i32) {
        for x in (u.x + t).max(0)..(u.x + u.w - t).min(world_map.width() as i32) {
            total += 1;
            free += (*world_map.at(x as usize, y as usize) == Cell::Free) as u64;
        }
    }
    total > 0 && 2 * free >= total
}

/// Two units with an open boundary between them (no wall in the band between their facing
/// walls, or overlapping interiors): candidates for one room.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct OpenPair {
    /// Index of the first unit in `world.units`.
    pub a: usize,
    /// Index of the second unit (`a < b`).
    pub b: usize,
    /// Whether the open boundary spans most ([`FLUSH_SHARE`]) of both units' facing sides: one
    /// space cut in two by a unit seam, rather than a room opening off the side of a longer
    /// corridor or hall.
    pub flush: bool,
    /// Whether the room layer's geometry parts the two units even when they are joined: a
    /// wall gap or a doorway lies between them ([`super::layer::mark_closed`]; false
    /// until marked).
    pub closed: bool,
}

/// The share of both facing sides an open boundary must span to be [`OpenPair::flush`].
pub const FLUSH_SHARE: f64 = 0.5;

/// Occupied and total cells of `r` in `map` (clipped to the map).
fn occupied(map: &Grid<Cell>, r: Rect) -> (i64, i64) {
    let (mut occ, mut total) = (0, 0);
    for y in r.y.max(0)..r.bottom().min(map.height() as i32) {
        for x in r.x.max(0)..r.right().min(map.width() as i32) {
            total += 1;
            occ += (*map.at(x as usize, y as usize) == Cell::Occupied) as i64;
        }
    }
    (occ, total)
}

/// Whether the stretch `s..=e` along which `lo` and `hi` face each other (across `axis`, walls
/// `t` deep) spans at least [`FLUSH_SHARE`] of both units' facing sides ([`OpenPair::flush`]).
fn is_flush(lo: Rect, hi: Rect, axis: Axis, (s, e): (i32, i32), t: i32) -> bool {
    let side = |r: Rect| match axis {
        Axis::Horizontal => r.h,
        Axis::Vertical => r.w,
    };
    let span = (e - s + 1) as f64;
    let share = |r: Rect| span / (side(r) - 2 * t).max(1) as f64;
    share(lo).min(share(hi)) >= FLUSH_SHARE
}

/// Whether a seen wall parts `lo` and `hi` just inside one of them, though the band between
/// their rings is free: a line along their boundary, within [`RoomCells::edge_stray`] past
/// either ring (and inside the units), that is wall over at least half the stretch `s..=e`
/// and whose openings are all narrower than an open boundary ([`RoomCells::min_open_len`]):
/// doors and wall gaps in a wall the chain drew one unit's ring across. Read on the map as
/// seen (`map`), where the pieces of wall beside a door and the dots of a glass pane are, and
/// counting only cells a wall's thickness deep across the line ([`wall_thick_at`]): a row of
/// chairs along an open boundary is deeper.
fn walled_inside(map: &Grid<Cell>, lo: Rect, hi: Rect, axis: Axis, (s, e): (i32, i32), t: i32, c: &RoomCells) -> bool {
    let reach = c.edge_stray as i32;
    let (from, to) = match axis {
        Axis::Horizontal => ((lo.right() - t - reach).max(lo.x + t), (hi.x + t + reach).min(hi.right() - t)),
        Axis::Vertical => ((lo.bottom() - t - reach).max(lo.y + t), (hi.y + t + reach).min(hi.bottom() - t)),
    };
    let (w, h) = (map.width() as i32, map.height() as i32);
    let (lines, along) = match axis {
        Axis::Horizontal => (w, h),
        Axis::Vertical => (h, w),
    };
    let (s, e) = (s.max(0), e.min(along - 1));
    let len = e - s + 1;
    if len <= 0 {
        return false;
    }
    (from.max(0)..to.min(lines)).any(|line| {
        let (mut occ, mut run, mut longest) = (0, 0, 0);
        for k in s..=e {
            let (x, y) = match axis {
                Axis::Horizontal => (line, k),
                Axis::Vertical => (k, line),
            };
            if wall_thick_at(map, (x, y), axis, c.wall_piece_thick) {
                occ += 1;
                run = 0;
            } else {
                run += 1;
                longest = longest.max(run);
            }
        }
        2 * occ >= len && longest < c.min_open_len
    })
}

/// Whether `(x, y)` is occupied by a run across the line (along `axis`: down its column when
/// the units face each other across a row) no deeper than `thick` ([`RoomCells::wall_piece_thick`]):
/// a wall or a glass pane's piece, not a chair or a desk (deeper than a wall is thick).
fn wall_thick_at(map: &Grid<Cell>, (x, y): (i32, i32), axis: Axis, thick: u32) -> bool {
    let occupied = |k: i32| {
        let (x, y) = match axis {
            Axis::Horizontal => (k, y),
            Axis::Vertical => (x, k),
        };
        map.get(x as i64, y as i64) == Some(&Cell::Occupied)
    };
    let at = match axis {
        Axis::Horizontal => x,
        Axis::Vertical => y,
    };
    if !occupied(at) {
        return false;
    }
    let limit = thick as i32;
    let before = (1..=limit).take_while(|&d| occupied(at - d)).count() as i32;
    let after = (1..=limit).take_while(|&d| occupied(at + d)).count() as i32;
    before + after < limit
}

/// Whether units `a` and `b` (rectangles, walls `t` deep) have an open boundary in
/// `world_map` (its walls: clutter drawn free), and whether it is flush: `None` if there is
/// none. `seen` is the classified map itself, for [`walled_inside`]: a wall between a door and
/// a glass pane may be too short to be read as one, and the pane a dotted line.
fn open_boundary(
    a: Rect,
    b: Rect,
    t: i32,
    (world_map, seen): (&Grid<Cell>, &Grid<Cell>),
    c: &RoomCells,
) -> Option<bool> {
    let mut found: Option<bool> = None;
    for (lo, hi) in [(a, b), (b, a)] {
        for axis in [Axis::Horizontal, Axis::Vertical] {
            let Some((s, e)) = facing(lo, hi, axis, t, t) else { continue };
            if e - s + 1 < c.min_open_len {
                continue;
            }
            let band = match axis {
                Axis::Horizontal => Rect::new(lo.right() - t, s, hi.x - lo.right() + 2 * t, e - s + 1),
                Axis::Vertical => Rect::new(s, lo.bottom() - t, e - s + 1, hi.y - lo.bottom() + 2 * t),
            };
            let (occ, total) = occupied(world_map, band);
            if total > 0
                && (occ as f64) <= c.max_wall_share * total as f64
                && !walled_inside(seen, lo, hi, axis, (s, e), t, c)
            {
                found = Some(found.unwrap_or(false) || is_flush(lo, hi, axis, (s, e), t));
            }
        }
    }
    // Units overlapping by more than their walls are parts of one space.
    if let Some(inter) = a.intersection(&b) {
        if inter.w > 2 * t && inter.h > 2 * t {
            let (occ, total) = occupied(world_map, inter);
            if (occ as f64) <= c.max_wall_share * total as f64 {
                found = Some(true);
            }
        }
    }
    found
}

/// Whether units `a` and `b` (indices) are joined by a door nearly as wide as the stretch they
/// face each other along ([`RoomCells::wide_door_share`]), and whether that stretch is flush
/// (as in [`OpenPair::flush`]); `None` if not.
fn wide_door(world: &World, a: usize, b: usize, c: &RoomCells) -> Option<bool> {
    let t = world.wall_thickness;
    let (ua, ub) = (&world.units[a], &world.units[b]);
    let (door, across) = world
        .doors
        .iter()
        .filter(|d| d.units.contains(&ua.id) && d.units.contains(&ub.id))
        .map(|d| (d.len(), d.rect().w.min(d.rect().h)))
        .max()?;
    for (lo, hi) in [(ua.rect(), ub.rect()), (ub.rect(), ua.rect())] {
        for axis in [Axis::Horizontal, Axis::Vertical] {
            // Facing across the door: the walls as far apart as the door is deep.
            let Some((s, e)) = facing(lo, hi, axis, across.max(2 * t), t) else { continue };
            if (door as f64) >= c.wide_door_share * (e - s + 1) as f64 {
                return Some(is_flush(lo, hi, axis, (s, e), t));
            }
        }
    }
    None
}

/// Every pair of space-enclosing units ([`encloses_space`]) with an open boundary, or joined
/// by a door as wide as their shared stretch ([`RoomCells::wide_door_share`]).
pub fn open_pairs(world: &World, world_map: &Grid<Cell>, c: &RoomCells) -> Vec<OpenPair> {
    open_pairs_among(world, world_map, c, &without_clutter(world_map, c.min_wall_len, c.wall_piece_thick, c.hole_reach))
}

/// [`open_pairs`] with `world_map`'s walls read already (`walls`, [`without_clutter`]).
pub(crate) fn open_pairs_among(
    world: &World,
    world_map: &Grid<Cell>,
    c: &RoomCells,
    walls: &Grid<Cell>,
) -> Vec<OpenPair> {
    let t = world.wall_thickness;
    let space: Vec<bool> = world.units.iter().map(|u| encloses_space(u, t, world_map)).collect();
    let mut pairs = Vec::new();
    for a in 0..world.units.len() {
        for b in a + 1..world.units.len() {
            if !space[a] || !space[b] {
                continue;
            }
            let (ra, rb) = (world.units[a].rect(), world.units[b].rect());
            let open = open_boundary(ra, rb, t, (walls, world_map), c).or_else(|| wide_door(world, a, b, c));
            if let Some(flush) = open {
                pairs.push(OpenPair { a, b, flush, closed: false });
            }
        }
    }
    pairs
}

/// Room id (1-based) of every unit, by unit index; 0 for units that enclose no space
/// ([`encloses_space`]). Units with an open boundary ([`open_pairs`]) are one room: the rule
/// without knowledge supervision ([`super::layer`] lets the knowledge base decide).
pub fn group_units(world: &World, world_map: &Grid<Cell>, c: &RoomCells) -> Vec<u16> {
    let pairs = open_pairs(world, world_map, c);
    join(world, world_map, pairs.iter().map(|p| (p.a, p.b)))
}

/// Room ids (1-based, numbered by first unit) when the given pairs of unit indices are joined;
/// units that enclose no space get 0.
pub fn join(world: &World, world_map: &Grid<Cell>, pairs: impl IntoIterator<Item = (usize, usize)>) -> Vec<u16> {
    let n = world.units.len();
    let space: Vec<bool> = world.units.iter().map(|u| encloses_space(u, world.wall_thickness, world_map)).collect();
    let mut sets = UnionFind::new(n);
    for (i, j) in pairs {
        if i < n && j < n && space[i] && space[j] {
            sets.union(i, j);
        }
    }
    let mut id_of_root = vec![0u16; n];
    let mut next = 0u16;
    (0..n)
        .map(|i| {
            if !space[i] {
                return 0;
            }
            let r = sets.find(i);
            if id_of_root[r] == 0 {
                next = next.saturating_add(1);
                id_of_root[r] = next;
            }
            id_of_root[r]
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::floorplan::{Unit, UnitType};

    /// An office above a corridor, parted by a wall at rows 40 - 42 with a doorway `door`
    /// cells wide at columns 40 on, and the chain's two units: the office's ends at row 35, in
    /// the free space above the wall, and the corridor's starts there too, its ring over the
    /// office's and the seen wall 5 cells (0.25 m) inside it.
    fn office_over_corridor(door: usize) -> (World, Grid<Cell>) {
        let mut map = Grid::new(100, 80, Cell::Free);
        for y in 40..43 {
            for x in (0..40).chain(40 + door..100) {
                *map.at_mut(x, y) = Cell::Occupied;
            }
        }
        let mut world = World::empty(100, 80);
        world.wall_thickness = 3;
        world.units =
            vec![Unit::new(1, 0, 0, 100, 35, UnitType::Room), Unit::new(2, 0, 32, 100, 48, UnitType::Corridor)];
        (world, map)
    }

    #[test]
    fn a_seen_wall_just_inside_a_unit_parts_it_from_its_neighbour() {
        let c = RoomCells::default();
        // A 1 m door (20 cells, under the 1.5 m of an open boundary): the wall parts them.
        let (world, map) = office_over_corridor(20);
        assert!(open_pairs(&world, &map, &c).is_empty());
        // A 2 m gap is an opening: the boundary is open.
        let (world, map) = office_over_corridor(40);
        assert_eq!(open_pairs(&world, &map, &c), vec![OpenPair { a: 0, b: 1, flush: true, closed: false }]);
        // A wall deeper inside a unit than it may stray (here 4 cells, 0.2 m) is not looked for.
        let near = RoomCells { edge_stray: 4, ..c };
        let (world, map) = office_over_corridor(20);
        assert_eq!(open_pairs(&world, &map, &near).len(), 1);
    }
}
