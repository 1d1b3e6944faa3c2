//! Doors within one room: openings, and the contradictions left.
//!
//! The chain joins every pair of neighbouring units it keeps apart by a door, also two units
//! that explain one open hall between them. Once the room layer has found the rooms, a door
//! whose two units lie in one room is either an *opening* (the units meet along a passage at
//! least [`OPENING_MIN_M`] wide that no wall crosses: open floor, as a person draws a hall)
//! or a contradiction the plan should not hold (a door, walls either side, inside one room:
//! two rooms merged across their door). Openings are marked on the door ([`Door::opening`]);
//! the rest are counted ([`doors_in_one_room`]), so that the figure a reader of the plan cares
//! about, rooms merged across doors, is measured on every map.
//!
//! [`Door::opening`]: crate::floorplan::world::Door::opening

use crate::floorplan::world::{Rect, World, OPENING_MIN_M};
use crate::geometry::{facing, Axis};
use crate::grid::{Cell, Grid};
use std::collections::HashMap;

/// The room of each unit id, from `world.rooms`.
fn room_of_unit(world: &World) -> HashMap<u32, u32> {
    world.rooms.iter().flat_map(|r| r.units.iter().map(move |&u| (u, r.id))).collect()
}

/// The indices in `world.doors` of the doors whose two units lie in one room.
fn within_rooms(world: &World) -> Vec<usize> {
    let room = room_of_unit(world);
    let same = |[a, b]: [u32; 2]| room.get(&a).is_some_and(|ra| room.get(&b) == Some(ra));
    (0..world.doors.len()).filter(|&k| same(world.doors[k].units)).collect()
}

/// Marks the doors of `world` that are openings within one room ([`Door::opening`]): their
/// two units lie in one room and meet along a passage at least [`OPENING_MIN_M`] wide that no
/// cell of `walls` crosses (`walls`: the map, in its own frame, with the clutter that is no
/// wall removed, as the room layer reads it). Units turned to their own angle (wings) are
/// read in their frame; a door between units of two angles is never an opening. Returns how
/// many doors are openings.
///
/// [`Door::opening`]: crate::floorplan::world::Door::opening
pub(crate) fn mark_openings(world: &mut World, walls: &Grid<Cell>, resolution: f64) -> usize {
    let min_cells = libm::ceil(OPENING_MIN_M / resolution - 1e-9).max(1.0) as i32;
    let t = world.wall_thickness;
    for door in &mut world.doors {
        door.opening = false;
    }
    let mut count = 0;
    for k in within_rooms(world) {
        let [a, b] = world.doors[k].units;
        let unit = |id: u32| world.units.iter().find(|u| u.id == id);
        let (Some(ua), Some(ub)) = (unit(a), unit(b)) else { continue };
        let frame = world.unit_frame(ua);
        if frame != world.unit_frame(ub) {
            continue;
        }
        let rot = frame.rotation();
        let blocked = |x: i32, y: i32| {
            let (mx, my) = rot.to_map(x as f64 + 0.5, y as f64 + 0.5);
            let (mx, my) = (libm::floor(mx) as i64, libm::floor(my) as i64);
            walls.get(mx, my).is_some_and(|&c| c == Cell::Occupied)
        };
        let depth = world.doors[k].rect().w.min(world.doors[k].rect().h).max(2 * t);
        if passage(ua.rect(), ub.rect(), t, depth, blocked) >= min_cells {
            world.doors[k].opening = true;
            count += 1;
        }
    }
    count
}

/// How many doors of `world` join two units of one room and are no opening: rooms merged
/// across a door.
pub fn doors_in_one_room(world: &World) -> usize {
    within_rooms(world).into_iter().filter(|&k| !world.doors[k].opening).count()
}

/// The widest run, in cells, along which rectangles `a` and `b` (wall rings `t` deep, at most
/// `max_gap` cells apart) face each other with no `blocked` cell in the band between them;
/// `i32::MAX` when their interiors overlap.
fn passage(a: Rect, b: Rect, t: i32, max_gap: i32, blocked: impl Fn(i32, i32) -> bool) -> i32 {
    if a.intersection(&b).is_some_and(|i| i.w > 2 * t && i.h > 2 * t) {
        return i32::MAX;
    }
    let mut best = 0;
    for (lo, hi) in [(a, b), (b, a)] {
        for axis in [Axis::Horizontal, Axis::Vertical] {
            let Some((s, e)) = facing(lo, hi, axis, max_gap, t) else { continue };
            let open_at = |p: i32| match axis {
                Axis::Horizontal => (lo.right() - t..hi.x + t).all(|x| !blocked(x, p)),
                Axis::Vertical => (lo.bottom() - t..hi.y + t).all(|y| !blocked(p, y)),
            };
            let mut run = 0;
            for p in s..=e {
                run = if open_at(p) { run + 1 } else { 0 };
                best = best.max(run);
            }
        }
    }
    best
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::floorplan::world::{Door, Room, Unit, UnitType};

    /// Two units side by side, columns 0..40 and 40..80 (their walls on columns 39 and 40),
    /// 40 rows, in one room, with a door between them over rows 10..15; the wall
    /// between them on column 39-40 has a gap over rows `gap`.
    fn two_units(gap: std::ops::Range<usize>) -> (World, Grid<Cell>) {
        let mut map = Grid::new(80, 40, Cell::Free);
        for y in (0..40).filter(|y| !gap.contains(y)) {
            *map.at_mut(39, y) = Cell::Occupied;
            *map.at_mut(40, y) = Cell::Occupied;
        }
        let mut world = World::empty(80, 40);
        world.units = vec![Unit::new(1, 0, 0, 40, 40, UnitType::Room), Unit::new(2, 40, 0, 40, 40, UnitType::Room)];
        world.doors = vec![Door { id: 1, units: [1, 2], x0: 39, y0: 10, x1: 40, y1: 15, opening: false }];
        let room = Room {
            id: 1,
            kind: UnitType::Room,
            units: vec![1, 2],
            area_m2: 8.0,
            doors: vec![],
            opens_to: vec![],
            name: None,
        };
        world.rooms = vec![room];
        (world, map)
    }

    #[test]
    fn a_wide_passage_within_a_room_is_an_opening_and_a_narrow_door_is_counted() {
        // A gap of 30 rows (1.5 m at 5 cm): open floor within the room.
        let (mut world, map) = two_units(5..35);
        assert_eq!(mark_openings(&mut world, &map, 0.05), 1);
        assert!(world.doors[0].opening);
        assert_eq!(doors_in_one_room(&world), 0);
        // A gap of 6 rows (0.3 m): a door, walls either side, inside one room.
        let (mut world, map) = two_units(10..16);
        assert_eq!(mark_openings(&mut world, &map, 0.05), 0);
        assert!(!world.doors[0].opening);
        assert_eq!(doors_in_one_room(&world), 1);
        // The same 6 rows at 25 cm a cell are 1.5 m: an opening.
        assert_eq!(mark_openings(&mut world, &map, 0.25), 1);
        // Units in two rooms: no door is within a room.
        let (mut world, map) = two_units(5..35);
        world.rooms[0].units = vec![1];
        let mut other = world.rooms[0].clone();
        (other.id, other.units) = (2, vec![2]);
        world.rooms.push(other);
        assert_eq!((mark_openings(&mut world, &map, 0.05), doors_in_one_room(&world)), (0, 0));
    }

    #[test]
    fn a_door_written_as_an_opening_reads_back_and_a_plain_door_is_written_as_before() {
        let (mut world, map) = two_units(5..35);
        let plain = serde_json::to_string(&world.doors[0]).unwrap();
        assert!(!plain.contains("opening"), "{plain}");
        mark_openings(&mut world, &map, 0.05);
        let text = serde_json::to_string(&world.doors[0]).unwrap();
        assert!(text.contains("\"opening\":true"), "{text}");
        assert_eq!(serde_json::from_str::<Door>(&text).unwrap(), world.doors[0]);
    }
}
