//! Doors between the units of two wings (issue 13): where a building's wings meet, a passage
//! leads from a unit of one wing into a unit of the other, and a person draws a door there.
//!
//! Each wing's chain explains its own floor, the other wings' free cells unknown to it
//! ([`crate::floorplan::wings`]), so no chain puts a door between two wings: the corridor that runs
//! from one wing into the next would end at a closed wall in the drawings and the 3D model,
//! and the scene graph would fall apart into one piece per wing. [`join_wings`] finds those
//! passages on the map once the wings' units are composed: from each side of a unit it walks
//! outwards, cell by cell in the unit's frame, through the unit's wall and at most a door's
//! gap ([`DoorLimits::max_gap`]) and a wall beyond, over free map cells only, and stops in the
//! interior of a unit of another angle (a walk that meets it within its own unit's wall
//! finds two units that overlap, with nothing to pass through). Where [`DoorLimits::min_len`] such walks side by side
//! reach the same unit, the run is a door: its rectangle lies in the first unit's frame
//! ([`World::door_frame`]), across that unit's wall and on up to the other unit's interior, so
//! that it covers both walls where the passage crosses them.
//!
//! A passage between wings is an opening, so it has no longest door: a corridor that runs on
//! into the next wing opens over its whole width.

use crate::floorplan::state::DoorLimits;
use crate::floorplan::world::{Door, Room, Unit, World};
use crate::geometry::{Frame, Rect};
use crate::grid::{Cell, Grid};
use std::collections::BTreeMap;

/// Adds a door to `world` for the passages of free cells of `map` between units of different
/// angles (module docs): the widest per pair of rooms and pair of angles. Records the rooms
/// a door joins in each other's `opens_to`, and the door in their `doors`. Returns how many
/// doors were added.
///
/// ```
/// use ksmcmc::floorplan::wing_doors::join_wings;
/// use ksmcmc::floorplan::{DoorLimits, Unit, UnitType, World};
/// use ksmcmc::grid::{Cell, Grid};
/// // Two rooms side by side with a free passage through the walls between them; the one on
/// // the right is given an angle of its own (a millionth of a radian: the same cells).
/// let map = Grid::new(100, 60, Cell::Free);
/// let mut world = World::empty(100, 60);
/// world.units = vec![Unit::new(1, 0, 0, 50, 60, UnitType::Room), Unit::new(2, 50, 0, 50, 60, UnitType::Room)];
/// world.units[1].angle = Some(1e-6);
/// assert_eq!(join_wings(&mut world, &map, &DoorLimits::default()), 1);
/// let door = &world.doors[0];
/// assert_eq!(door.units, [1, 2]);
/// world.validate()?;
/// # Ok::<(), ksmcmc::floorplan::world::WorldError>(())
/// ```
pub fn join_wings(world: &mut World, map: &Grid<Cell>, limits: &DoorLimits) -> usize {
    let frames: Vec<Frame> = world.units.iter().map(|u| world.unit_frame(u)).collect();
    let reach = 2 * world.wall_thickness + limits.max_gap;
    let g = reach as f64;
    let boxes: Vec<[f64; 4]> = world
        .units
        .iter()
        .zip(&frames)
        .map(|(u, f)| {
            let [x0, y0, x1, y1] = f.map_box(u.rect());
            [x0 - g, y0 - g, x1 + g, y1 + g]
        })
        .collect();
    // The widest passage per pair of rooms and pair of angles: where two wings' units overlap
    // in a corner room, or a corridor runs on into the next wing, one door joins the two
    // parts, not one per pair of units that touch.
    let room_of = room_index(world);
    let mut widest: BTreeMap<[(usize, u64); 2], Passage> = BTreeMap::new();
    for i in 0..world.units.len() {
        for j in i + 1..world.units.len() {
            if frames[i] == frames[j] || !overlap(&boxes[i], &boxes[j]) {
                continue;
            }
            let side = |a: usize, b: usize| {
                let (ua, ub) = (&world.units[a], &world.units[b]);
                let sides = (0..4).filter_map(|s| opening(world, map, (ua, &frames[a]), (ub, &frames[b]), s, reach));
                sides.map(|(r, len)| (len, r, a, b)).max_by_key(|o| o.0)
            };
            let best = [side(i, j), side(j, i)].into_iter().flatten().max_by_key(|o| o.0);
            let Some((len, r, a, b)) = best.filter(|o| o.0 >= limits.min_len) else { continue };
            let end = |k: usize| (room_of[k].map_or(usize::MAX, |r| r), frames[k].angle.to_bits());
            let key = if end(a) <= end(b) { [end(a), end(b)] } else { [end(b), end(a)] };
            if widest.get(&key).is_none_or(|w| len > w.0) {
                widest.insert(key, (len, r, a, b));
            }
        }
    }
    // In the order of the units' ids (units are listed by id).
    let mut found: Vec<(Rect, usize, usize)> = widest.into_values().map(|(_, r, a, b)| (r, a, b)).collect();
    found.sort_by_key(|&(_, a, b)| (world.units[a].id, world.units[b].id));
    let added = found.len();
    let first_id = world.doors.iter().map(|d| d.id).max().unwrap_or(0) + 1;
    for (id, (r, a, b)) in (first_id..).zip(found) {
        let units = [world.units[a].id, world.units[b].id];
        world.doors.push(Door { id, units, x0: r.x, y0: r.y, x1: r.right() - 1, y1: r.bottom() - 1, opening: false });
        link_rooms(&mut world.rooms, id, room_of[a], room_of[b]);
    }
    added
}

/// A passage found between two units: its width, its rectangle in the first unit's frame and
/// the two units' indices.
type Passage = (i32, Rect, usize, usize);

/// A run of walks side by side: the first and last position along the side, and how deep
/// the deepest walk went.
type Run = (i32, i32, i32);

/// Per unit of `world`, the index in `rooms` of the first room that holds it.
fn room_index(world: &World) -> Vec<Option<usize>> {
    let mut of = vec![None; world.units.len()];
    for (k, r) in world.rooms.iter().enumerate().rev() {
        for &u in &r.units {
            if let Some(i) = world.unit_index(u) {
                of[i] = Some(k);
            }
        }
    }
    of
}

/// The rooms `ra` and `rb` (indices) of a door's two units: each records the door, and the
/// other room in `opens_to` (kept sorted).
fn link_rooms(rooms: &mut [Room], door: u32, ra: Option<usize>, rb: Option<usize>) {
    for r in [ra, rb].into_iter().flatten() {
        if !rooms[r].doors.contains(&door) {
            rooms[r].doors.push(door);
        }
    }
    if let (Some(ra), Some(rb)) = (ra, rb) {
        if ra != rb {
            let (ida, idb) = (rooms[ra].id, rooms[rb].id);
            for (r, other) in [(ra, idb), (rb, ida)] {
                if !rooms[r].opens_to.contains(&other) {
                    rooms[r].opens_to.push(other);
                    rooms[r].opens_to.sort_unstable();
                }
            }
        }
    }
}

fn overlap(a: &[f64; 4], b: &[f64; 4]) -> bool {
    a[0] <= b[2] && b[0] <= a[2] && a[1] <= b[3] && b[1] <= a[3]
}

/// The widest run of walks from side `side` (0 top, 1 bottom, 2 left, 3 right) of unit `a`
/// that reach the interior of unit `b` over free cells within `reach` cells of `a`'s
/// interior (module docs), as a rectangle of `a`'s frame: along the run, from `a`'s first
/// wall cell to the deepest walk's last cell before `b`'s interior, and the run's length.
fn opening(
    world: &World,
    map: &Grid<Cell>,
    a: (&Unit, &Frame),
    b: (&Unit, &Frame),
    side: u8,
    reach: i32,
) -> Option<(Rect, i32)> {
    let t = world.wall_thickness;
    let (r, ra) = (a.0.rect(), a.1.rotation());
    let (inner_b, rb) = (b.0.rect().interior(t)?, b.1.rotation());
    let [ww, wh] = a.1.world_size.map(|v| v as i32);
    // The side's cells along it, the first wall cell off the interior, and the way out.
    let (along, first, (dx, dy)) = match side {
        0 => (r.x + t..r.right() - t, r.y + t - 1, (0, -1)),
        1 => (r.x + t..r.right() - t, r.bottom() - t, (0, 1)),
        2 => (r.y + t..r.bottom() - t, r.x + t - 1, (-1, 0)),
        _ => (r.y + t..r.bottom() - t, r.right() - t, (1, 0)),
    };
    let cell = |p: i32, k: i32| if dx == 0 { (p, first + k * dy) } else { (first + k * dx, p) };
    let walk = |p: i32| -> Option<i32> {
        for k in 0..reach {
            let (x, y) = cell(p, k);
            if x < 0 || y < 0 || x >= ww || y >= wh {
                return None;
            }
            let (mx, my) = ra.to_map(x as f64 + 0.5, y as f64 + 0.5);
            let (cx, cy) = (libm::floor(mx) as i64, libm::floor(my) as i64);
            if map.get(cx, cy) != Some(&Cell::Free) {
                return None;
            }
            let (bx, by) = rb.to_world(mx, my);
            let inside = |v: f64, lo: i32, hi: i32| v >= lo as f64 && v < hi as f64;
            if inside(bx, inner_b.x, inner_b.right()) && inside(by, inner_b.y, inner_b.bottom()) {
                // Inside `a`'s own wall the two units overlap: no passage, no door.
                return (k >= t).then_some(k);
            }
        }
        None
    };
    // The widest run of walks that get through, and how deep the deepest of them goes.
    // Runs as (first, last, deepest walk).
    let (mut best, mut run): (Option<Run>, Option<Run>) = (None, None);
    for p in along.clone().chain(std::iter::once(along.end)) {
        let depth = if p < along.end { walk(p) } else { None };
        run = match (run, depth) {
            (Some((s, _, d)), Some(k)) => Some((s, p, d.max(k))),
            (None, Some(k)) => Some((p, p, k)),
            (Some(done), None) => {
                if best.is_none_or(|b: Run| done.1 - done.0 > b.1 - b.0) {
                    best = Some(done);
                }
                None
            }
            (None, None) => None,
        };
    }
    let (s, e, d) = best?;
    let (c0, c1) = (cell(s, 0), cell(e, d - 1));
    let (x0, x1) = (c0.0.min(c1.0), c0.0.max(c1.0));
    let (y0, y1) = (c0.1.min(c1.1), c0.1.max(c1.1));
    Some((Rect::new(x0, y0, x1 - x0 + 1, y1 - y0 + 1), e - s + 1))
}
