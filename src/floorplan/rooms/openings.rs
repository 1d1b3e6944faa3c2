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

/// The indices in `world.doors` of the doors whose two units lie in one room.
fn within_rooms(world: &World) -> Vec<usize> {
    let room = world.rooms_of_units();
    let same = |[a, b]: [u32; 2]| room.get(&a).is_some_and(|ra| room.get(&b) == Some(ra));
    (0..world.doors.len()).filter(|&k| same(world.doors[k].units)).collect()
}

/// Marks the doors of `world` that are openings within one room ([`Door::opening`]): their
/// two units lie in one room, and either they meet along a passage at least [`OPENING_MIN_M`]
/// wide that no cell of `walls` crosses, or the door has no jambs: on every line of the door
/// along its width, the floor through it runs on at least [`OPENING_MIN_M`] before a wall
/// ([`jambless`]). `walls` is the map, in its own frame, with the clutter that is no wall
/// removed, as the room layer reads it. Units turned to their own angle (wings) are read in
/// their frame; a door between units of two angles (a passage between wings) is read in its
/// first unit's, by the door line alone. Returns how many doors are openings.
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
        let rot = frame.rotation();
        let blocked = |x: i32, y: i32| {
            let (mx, my) = rot.to_map(x as f64 + 0.5, y as f64 + 0.5);
            let (mx, my) = (libm::floor(mx) as i64, libm::floor(my) as i64);
            walls.get(mx, my).is_some_and(|&c| c == Cell::Occupied)
        };
        let door = world.doors[k].rect();
        let depth = door.w.min(door.h).max(2 * t);
        let wide = frame == world.unit_frame(ub) && passage(ua.rect(), ub.rect(), t, depth, blocked) >= min_cells;
        if wide || jambless(door, min_cells, blocked) {
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

/// Whether door rectangle `door` has no jambs: on each of its lines along its width (rows of
/// a door wider than deep, columns otherwise), the cells that no `blocked` cell parts from the
/// line's middle cell run on for at least `min_cells`.
///
/// A door leaf hangs between jambs, wall on either side of it at most a leaf's width apart (a
/// single leaf is at most [`OPENING_MIN_M`] wide in building codes). Where the floor runs on
/// that far along the door's line with no wall, there is no door frame, however the chain has
/// cut the open floor into rectangles: a thin unit along a wall, a corridor strip in a hall, the
/// tip of a wedge beside a slanted wall. A doorway in a wall always measures its width between
/// the jambs on every line, so it stays a door. Lines whose middle cell is a wall have no run.
fn jambless(door: Rect, min_cells: i32, blocked: impl Fn(i32, i32) -> bool) -> bool {
    let along_x = door.w >= door.h;
    let (lines, span) = if along_x {
        (door.y..door.bottom(), (door.x, door.right()))
    } else {
        (door.x..door.right(), (door.y, door.bottom()))
    };
    let cell = |line: i32, p: i32| if along_x { blocked(p, line) } else { blocked(line, p) };
    let middle = span.0 + (span.1 - span.0) / 2;
    lines.into_iter().all(|line| {
        if cell(line, middle) {
            return false;
        }
        // Out from the middle both ways, stopping at a wall or once the run is long enough.
        let mut run = 1;
        let mut p = middle - 1;
        while run < min_cells && !cell(line, p) {
            run += 1;
            p -= 1;
        }
        let mut p = middle + 1;
        while run < min_cells && !cell(line, p) {
            run += 1;
            p += 1;
        }
        run >= min_cells
    })
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
    fn a_door_without_jambs_is_an_opening_however_short_the_units_shared_side() {
        // Unit 2 is 16 rows (0.8 m) high: the two units face each other along less than
        // 1.2 m, so the passage between them is too short for an opening.
        let short = |gap| {
            let (mut world, map) = two_units(gap);
            world.units[1].h = 16;
            (world, map)
        };
        // No wall between them at all: along the door's line (columns 39 and 40) the floor runs
        // the map's 2 m. No jambs: an opening.
        let (mut world, map) = short(0..40);
        assert_eq!(mark_openings(&mut world, &map, 0.05), 1);
        // A wall with a gap of 6 rows around the door: jambs 0.3 m apart, a door.
        let (mut world, map) = short(9..16);
        assert_eq!(mark_openings(&mut world, &map, 0.05), 0);
        assert_eq!(doors_in_one_room(&world), 1);
        // A gap of 20 rows (1.0 m): still a door leaf's width, a door.
        let (mut world, map) = short(1..21);
        assert_eq!(mark_openings(&mut world, &map, 0.05), 0);
        // A gap of 26 rows (1.3 m): wider than a leaf, an opening.
        let (mut world, map) = short(1..27);
        assert_eq!(mark_openings(&mut world, &map, 0.05), 1);
        // Units at two angles (wings) are read by the door line alone, in the first one's frame.
        let (mut world, map) = short(0..40);
        world.units[1].angle = Some(0.3);
        assert_eq!(mark_openings(&mut world, &map, 0.05), 1);
        let (mut world, map) = short(9..16);
        world.units[1].angle = Some(0.3);
        assert_eq!(mark_openings(&mut world, &map, 0.05), 0);
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
