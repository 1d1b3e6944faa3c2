//! The rooms read off the label image: each unit belongs to the room that holds most of its
//! free cells, a room's type is the type covering most of its cells, its doors are those whose
//! cells it touches, it opens to every room it touches along a passable stretch
//! ([`MIN_PASSAGE_M`](super::MIN_PASSAGE_M)) or through a door, and rooms that are mostly
//! rays are unexplored.

use super::frame::world_cell;
use crate::floorplan::topology::touching;
use crate::floorplan::world::{Room, UnitType, World};
use crate::grid::{Cell, Grid};
use std::collections::{BTreeMap, BTreeSet};

/// How far (m) from every wall, object or unseen cell a cell must be for a person (or a
/// robot) to stand there: the room layer types `unknown` the rooms where too few cells are.
pub const STANDING_CLEARANCE_M: f64 = 0.2;

/// The largest speck (m, its longer side) the standing test looks past: a scan's miss, a
/// cable, a table leg, which a person stands beside. Without it the test would depend on the
/// resolution: a SLAM map's speckle is so many specks per cell, so at 0.025 m four times as
/// many per square metre as at 0.05 m, and no cell of a room lay 0.2 m from every speck.
pub const SPECK_M: f64 = 0.1;

/// [`mark_unexplored_on`] working out the map's [`standing_depth`] itself.
#[cfg(test)]
pub(crate) fn mark_unexplored(rooms: &mut [Room], labels: &Grid<u16>, map: &Grid<Cell>, resolution: f64) {
    if (labels.width(), labels.height()) != (map.width(), map.height()) || resolution.is_nan() || resolution <= 0.0 {
        return;
    }
    let c = super::config::RoomConfig::default().cells(resolution);
    mark_unexplored_on(rooms, labels, map, &standing_depth(map, c.speck, c.hole_reach), resolution);
}

/// The longest part, in cells, that is a speck at `resolution` m per cell: [`SPECK_M`] in
/// whole cells, one more than fits.
pub(crate) fn speck_cells(resolution: f64) -> u32 {
    (SPECK_M / resolution).floor().min(u32::MAX as f64) as u32 + 1
}

/// The free depth of `map` (a chamfer distance, [`super::segments::free_depth`]) with its
/// specks of [`SPECK_M`] or less drawn free ([`super::wall_gaps::without_clutter`] with parts
/// shorter than `speck` cells, [`speck_cells`]): how far a person standing on each cell is
/// from what they would not stand beside.
pub(crate) fn standing_depth(map: &Grid<Cell>, speck: u32, hole_reach: u32) -> Vec<u32> {
    super::segments::free_depth(&super::wall_gaps::without_clutter(map, speck, 0, hole_reach))
}

/// Types `unknown` the rooms that are mostly rays, not floor: fewer than a third of their
/// free cells lie [`STANDING_CLEARANCE_M`] or more from every non-free cell of `map` (at
/// `resolution` m per cell, `depth` its [`standing_depth`]), specks of [`SPECK_M`] or less looked past. A range sensor looking through a window or an open door into
/// space nobody entered leaves a fan of one-cell rays with unseen cells between them; the
/// room layer labels the fan (a segmentation labels every free cell, and the benchmark's
/// truth draws such fans as regions too), but a person draws no room there and cannot say
/// what it is. The dissertation marks the same places as unexplored (Fig. 3.32-d). Rooms of
/// floor, furnished or not, keep far more than a third: on Cartesium 0.39 and over, the fans
/// 0.23 and under. [`RoomConfig::min_room_depth_m`] judges the free regions beyond every unit
/// by their deep cells too, but deeper (6 cells) and by count, to decide whether they are
/// rooms at all; at that depth several rooms of floor on Cartesium (half-seen offices, a
/// junction) keep only 0.23 - 0.30 of their cells, so the two are not one test.
pub(crate) fn mark_unexplored_on(
    rooms: &mut [Room],
    labels: &Grid<u16>,
    map: &Grid<Cell>,
    depth: &[u32],
    resolution: f64,
) {
    if (labels.width(), labels.height()) != (map.width(), map.height())
        || depth.len() != map.cells().len()
        || resolution.is_nan()
        || resolution <= 0.0
    {
        return;
    }
    // Chamfer units: 3 per cell.
    let clearance = (3.0 * (STANDING_CLEARANCE_M / resolution).round()).min(u32::MAX as f64) as u32;
    let mut counts = vec![(0u64, 0u64); usize::from(u16::MAX) + 1];
    for (i, (&l, c)) in labels.cells().iter().zip(map.cells()).enumerate() {
        if l != 0 && *c == Cell::Free {
            let e = &mut counts[usize::from(l)];
            e.0 += 1;
            e.1 += u64::from(depth[i] >= clearance);
        }
    }
    for r in rooms.iter_mut() {
        let Some(&(free, standing)) = usize::try_from(r.id).ok().and_then(|i| counts.get(i)) else { continue };
        if free > 0 && 3 * standing < free {
            r.kind = UnitType::Unknown;
        }
    }
}

/// Per unit of `world`, the label of `labels` (in the map's frame) holding most of its free
/// interior cells (ties: the smaller label), `None` if none does.
pub(crate) fn unit_rooms(world: &World, world_map: &Grid<Cell>, labels: &Grid<u16>) -> Vec<Option<u16>> {
    let t = world.wall_thickness;
    let (w, h) = (labels.width(), labels.height());
    let (ww, wh) = (world_map.width() as i32, world_map.height() as i32);
    world
        .units
        .iter()
        .map(|u| {
            let mut votes: BTreeMap<u16, u64> = BTreeMap::new();
            for y in (u.y + t).max(0)..(u.y + u.h - t).min(wh) {
                for x in (u.x + t).max(0)..(u.x + u.w - t).min(ww) {
                    if *world_map.at(x as usize, y as usize) != Cell::Free {
                        continue;
                    }
                    let Some((mx, my)) = map_cell(world, x, y, w, h) else { continue };
                    let label = *labels.at(mx, my);
                    if label != 0 {
                        *votes.entry(label).or_default() += 1;
                    }
                }
            }
            votes.into_iter().max_by_key(|&(label, n)| (n, std::cmp::Reverse(label))).map(|(label, _)| label)
        })
        .collect()
}

/// Per-room tallies gathered in one pass over the labelled cells.
#[derive(Default)]
struct Tally {
    cells: u64,
    /// Cells of each unit (by index) in this room.
    units: BTreeMap<usize, u64>,
}

/// The map cell under world cell `(x, y)` (its centre), if inside the map.
pub(crate) fn map_cell(world: &World, x: i32, y: i32, w: usize, h: usize) -> Option<(usize, usize)> {
    let (mx, my) = if world.frame.is_identity() {
        (x as f64 + 0.5, y as f64 + 0.5)
    } else {
        world.frame.to_map(x as f64 + 0.5, y as f64 + 0.5)
    };
    (mx >= 0.0 && my >= 0.0 && (mx as usize) < w && (my as usize) < h).then_some((mx as usize, my as usize))
}

/// Index of the first unit whose interior covers each world cell (`u32::MAX` for none): four
/// bytes a cell, not eight, as this is the room layer's largest table.
fn interior_owner(world: &World) -> (Vec<u32>, usize) {
    let [ww, wh] = world.frame.world_size.map(|v| v as usize);
    let mut owner = vec![u32::MAX; ww * wh];
    let t = world.wall_thickness;
    for (k, u) in world.units.iter().enumerate() {
        for y in (u.y + t).max(0)..(u.y + u.h - t).min(wh as i32) {
            for x in (u.x + t).max(0)..(u.x + u.w - t).min(ww as i32) {
                let o = &mut owner[y as usize * ww + x as usize];
                if *o == u32::MAX {
                    *o = k as u32;
                }
            }
        }
    }
    (owner, ww)
}

/// The rooms of a label image (`labels[cell]` = room id, 0 for none): see the module docs.
pub(crate) fn rooms_of_labels(world: &World, labels: &Grid<u16>, resolution: f64) -> Vec<Room> {
    let (w, h) = (labels.width(), labels.height());
    let (owner, ww) = interior_owner(world);
    let mut tally: BTreeMap<u16, Tally> = BTreeMap::new();
    let rotation = world.frame.rotation();
    let size = (world.frame.world_size[0] as usize, world.frame.world_size[1] as usize);
    for my in 0..h {
        for mx in 0..w {
            let l = *labels.at(mx, my);
            if l == 0 {
                continue;
            }
            let t = tally.entry(l).or_default();
            t.cells += 1;
            if let Some((x, y)) = world_cell(world, &rotation, mx, my, size) {
                let k = owner[y * ww + x];
                if k != u32::MAX {
                    *t.units.entry(k as usize).or_default() += 1;
                }
            }
        }
    }
    // Each unit belongs to the room holding most of its cells.
    let mut home: BTreeMap<usize, (u64, u16)> = BTreeMap::new();
    for (&l, t) in &tally {
        for (&k, &n) in &t.units {
            let e = home.entry(k).or_insert((0, l));
            if n > e.0 {
                *e = (n, l);
            }
        }
    }
    let door_rooms = door_rooms(world, labels);
    // Touching along a passage's width, at any resolution.
    let min_contact = super::passages::passage_cells(resolution);
    let mut links: BTreeSet<(u32, u32)> = touching(&labels.map(|&l| l as u32), min_contact).into_iter().collect();
    for rooms in door_rooms.values() {
        for (i, &a) in rooms.iter().enumerate() {
            for &b in &rooms[i + 1..] {
                links.insert((a.min(b) as u32, a.max(b) as u32));
            }
        }
    }
    tally
        .iter()
        .map(|(&l, t)| {
            let units: Vec<usize> = home.iter().filter(|(_, &(_, r))| r == l).map(|(&k, _)| k).collect();
            Room {
                id: l as u32,
                kind: room_type(world, t, &units),
                units: units.iter().map(|&k| world.units[k].id).collect(),
                // To a square centimetre: the cells' area, without float noise (65.46, not
                // 65.46000000000001), exact for 5 cm cells (25 cm² each).
                area_m2: libm::round(t.cells as f64 * resolution * resolution * 1e4) / 1e4,
                doors: door_rooms.iter().filter(|(_, r)| r.contains(&l)).map(|(&d, _)| d).collect(),
                opens_to: links
                    .iter()
                    .filter_map(|&(a, b)| {
                        if a == l as u32 {
                            Some(b)
                        } else if b == l as u32 {
                            Some(a)
                        } else {
                            None
                        }
                    })
                    .collect(),
                name: None,
            }
        })
        .collect()
}

/// A room's type: the type of the units covering most of its cells among its own units. A
/// room with no typed unit of its own (a piece the walls part from the room whose unit
/// covers it: a corridor's end beyond a junction) takes the type of the units covering most
/// of its cells; `Unknown` when no typed unit covers it (free space the chain left
/// unexplained).
fn room_type(world: &World, t: &Tally, units: &[usize]) -> UnitType {
    let own = vote_type(world, t, units.iter().copied());
    if own != UnitType::Unknown {
        return own;
    }
    vote_type(world, t, t.units.keys().copied())
}

/// The type of the units among `units` covering most of the room's cells (`t`), ignoring
/// untyped units; `Unknown` when none is typed.
fn vote_type(world: &World, t: &Tally, units: impl Iterator<Item = usize>) -> UnitType {
    let mut votes: BTreeMap<UnitType, u64> = BTreeMap::new();
    for k in units {
        let kind = world.units[k].kind;
        if kind != UnitType::Unknown {
            *votes.entry(kind).or_default() += t.units.get(&k).copied().unwrap_or(0);
        }
    }
    votes.into_iter().max_by_key(|&(kind, n)| (n, std::cmp::Reverse(kind))).map_or(UnitType::Unknown, |(k, _)| k)
}

/// The rooms each door touches: labels on or next to (8-neighbours) its cells.
fn door_rooms(world: &World, labels: &Grid<u16>) -> BTreeMap<u32, Vec<u16>> {
    let (w, h) = (labels.width(), labels.height());
    let mut out = BTreeMap::new();
    for d in &world.doors {
        let mut rooms = BTreeSet::new();
        for (x, y) in d.cells() {
            let Some((mx, my)) = map_cell(world, x, y, w, h) else { continue };
            for ny in my.saturating_sub(1)..(my + 2).min(h) {
                for nx in mx.saturating_sub(1)..(mx + 2).min(w) {
                    let l = *labels.at(nx, ny);
                    if l != 0 {
                        rooms.insert(l);
                    }
                }
            }
        }
        out.insert(d.id, rooms.into_iter().collect());
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rooms_open_onto_each_other_along_half_a_metre_at_any_resolution() {
        // Two rooms, labels 1 and 2, side by side in a 40 x 20 grid, touching along 12 rows
        // (rows 4..16) and parted by unlabelled cells elsewhere: 0.6 m at 5 cm cells, which
        // opens one onto the other, 0.3 m at 2.5 cm, which does not.
        let mut labels = Grid::new(40, 20, 0u16);
        for y in 0..20 {
            for x in 0..40 {
                let open = (4..16).contains(&y);
                *labels.at_mut(x, y) = match x {
                    20 if !open => 0,
                    x if x < 20 => 1,
                    _ => 2,
                };
            }
        }
        let world = World::empty(40, 20);
        let opens = |resolution: f64| {
            rooms_of_labels(&world, &labels, resolution).iter().map(|r| r.opens_to.clone()).collect::<Vec<_>>()
        };
        assert_eq!(opens(0.05), [vec![2], vec![1]]);
        assert_eq!(opens(0.025), [Vec::<u32>::new(), vec![]]);
    }

    #[test]
    fn rooms_of_rays_are_unexplored_rooms_of_floor_are_not() {
        // Room 1: 2 x 2 m of floor. Room 2: rays, every other column free, unseen between.
        let mut map = Grid::new(80, 40, Cell::Unknown);
        let mut labels = Grid::new(80, 40, 0u16);
        for y in 0..40 {
            for x in 0..40 {
                *map.at_mut(x, y) = Cell::Free;
                *labels.at_mut(x, y) = 1;
            }
            for x in (41..80).step_by(2) {
                *map.at_mut(x, y) = Cell::Free;
                *labels.at_mut(x, y) = 2;
            }
        }
        let room = |id| Room {
            id,
            kind: UnitType::Other,
            units: vec![],
            area_m2: 0.0,
            doors: vec![],
            opens_to: vec![],
            name: None,
        };
        let mut rooms = vec![room(1), room(2)];
        mark_unexplored(&mut rooms, &labels, &map, 0.05);
        assert_eq!((rooms[0].kind, rooms[1].kind), (UnitType::Other, UnitType::Unknown));
    }

    #[test]
    fn specks_do_not_make_a_fine_map_s_room_unexplored() {
        // 3 x 3 m of floor at 2.5 cm cells with a speck (one cell, occupied or unseen) in
        // every 8 x 8 block: no cell is 0.2 m from every speck, but the room is floor.
        let (w, h) = (120, 120);
        let mut map = Grid::new(w, h, Cell::Free);
        for y in (3..h).step_by(8) {
            for x in (5..w).step_by(8) {
                *map.at_mut(x, y) = if (x + y) % 16 == 0 { Cell::Occupied } else { Cell::Unknown };
            }
        }
        let labels = Grid::new(w, h, 1u16);
        let room = Room {
            id: 1,
            kind: UnitType::Room,
            units: vec![],
            area_m2: 0.0,
            doors: vec![],
            opens_to: vec![],
            name: None,
        };
        let mut rooms = vec![room.clone()];
        mark_unexplored(&mut rooms, &labels, &map, 0.025);
        assert_eq!(rooms[0].kind, UnitType::Room);
        // Blocks of 4 x 4 cells (10 cm) are still specks; blocks of 5 x 5 are furniture, and
        // a room full of them is no floor to stand on.
        for (size, kind) in [(4, UnitType::Room), (5, UnitType::Unknown)] {
            let mut blocks = Grid::new(w, h, Cell::Free);
            for y in (0..h - size).step_by(8) {
                for x in (0..w - size).step_by(8) {
                    for (dx, dy) in (0..size).flat_map(|a| (0..size).map(move |b| (a, b))) {
                        *blocks.at_mut(x + dx, y + dy) = Cell::Occupied;
                    }
                }
            }
            let mut rooms = vec![room.clone()];
            mark_unexplored(&mut rooms, &labels, &blocks, 0.025);
            assert_eq!(rooms[0].kind, kind, "blocks of {size} cells");
        }
    }
}
