//! From grouped units to the label image: the segmentation a room-segmentation benchmark
//! scores.
//!
//! Every free map cell inside a room's units gets the room's id; free cells outside all units
//! (door openings, corners the units miss, scan rays) join the nearest room by a wavefront
//! through free space, as room-segmentation tools do; free regions beyond every unit's reach
//! become rooms of their own when they are deep enough; then rooms are split at doorways and
//! at wall gaps, small segments join their neighbours, and rooms touch only along passages
//! ([`super::passages`]).

use super::config::RoomCells;
use super::frame::world_cell;
use super::wall_gaps::WallReading;
use crate::floorplan::world::World;

use crate::grid::flood::{labelled_wavefront, neighbours4, Flood, Neighbours};
use crate::grid::{Cell, Grid};
use std::collections::VecDeque;

/// [`room_labels`] for a given grouping of units into rooms (`rooms[i]` is unit `i`'s room,
/// 1-based, 0 for none), as [`join`] makes it: the units' free cells, then a wavefront within
/// reach, then free regions beyond reach (`label_far_regions`), split at doorways and with
/// small segments joined to their neighbours.
pub fn labels_of_groups(
    world: &World,
    rooms: &[u16],
    map: &Grid<Cell>,
    world_map: &Grid<Cell>,
    c: &RoomCells,
) -> Grid<u16> {
    labels_of_groups_along(world, rooms, map, world_map, c, &[])
}

/// [`labels_of_groups`] with the wall gaps of further wall directions closed too (`angles`,
/// [`super::wall_gaps::close_wall_gaps_along`]).
pub fn labels_of_groups_along(
    world: &World,
    rooms: &[u16],
    map: &Grid<Cell>,
    world_map: &Grid<Cell>,
    c: &RoomCells,
    angles: &[f64],
) -> Grid<u16> {
    labels_read(world, rooms, map, world_map, c, &WallReading::new(world, map, world_map, c, angles))
}

/// [`labels_of_groups_along`] on walls read already.
pub(crate) fn labels_read(
    world: &World,
    rooms: &[u16],
    map: &Grid<Cell>,
    world_map: &Grid<Cell>,
    c: &RoomCells,
    walls: &WallReading,
) -> Grid<u16> {
    let owner = room_owner(world, rooms, world_map);
    let (mut labels, queue) = label_unit_cells(world, &owner, world_map.width(), map);
    spread_labels(&mut labels, map, queue, c.max_reach);
    label_far_regions(&mut labels, map, rooms.iter().copied().max().unwrap_or(0), c);
    split_open_at_doorways(&mut labels, &walls.open, c);
    if let Some(closed) = &walls.closed {
        split_at_wall_gaps(&mut labels, closed, c);
    }
    let fragment = split_disconnected(&mut labels, map, c.min_room_cells);
    merge_segments(&mut labels, c.min_segment_cells, &fragment, c.min_room_cells / 4);
    if c.clutter_in_rooms {
        label_clutter(&mut labels, map, &walls.open);
    }
    super::passages::seal_narrow_contacts(&mut labels, &walls.standing, c.passage_depth);
    labels
}

/// Gives each 8-connected part of clutter (cells free in `open`, [`without_clutter`](super::wall_gaps::without_clutter), but not
/// in `map`: furniture, unseen specks) the label of the room around it, when all its
/// 8-neighbours belong to that one room. A part beside two rooms (a chair in a doorway) or
/// beside cells of no room (a wall's stub in its line, the outside) stays unlabelled.
fn label_clutter(labels: &mut Grid<u16>, map: &Grid<Cell>, open: &Grid<Cell>) {
    let (w, h) = (labels.width(), labels.height());
    if w == 0 || h == 0 || (map.width(), map.height()) != (w, h) || (open.width(), open.height()) != (w, h) {
        return;
    }
    let (cells, opened) = (map.cells(), open.cells());
    let clutter = |i: usize| opened[i] == Cell::Free && cells[i] != Cell::Free;
    let mut assign: Vec<(usize, u16)> = Vec::new();
    let mut around: Vec<u16> = Vec::new();
    super::wall_gaps::each_part(w, h, clutter, clutter, |part, _| {
        around.clear();
        for &i in part {
            let (x, y) = (i % w, i / w);
            for ny in y.saturating_sub(1)..=(y + 1).min(h - 1) {
                for nx in x.saturating_sub(1)..=(x + 1).min(w - 1) {
                    let j = ny * w + nx;
                    if !clutter(j) {
                        around.push(labels.cells()[j]);
                    }
                }
            }
        }
        let room = around.first().copied().unwrap_or(0);
        if room != 0 && around.iter().all(|&l| l == room) {
            assign.extend(part.iter().map(|&i| (i, room)));
        }
    });
    let out = labels.cells_mut();
    for (i, room) in assign {
        out[i] = room;
    }
}

/// Gives the 4-connected parts of each segment ids of their own, and returns which new ids
/// are *fragments* (indexed by id). A segment's largest part keeps its role. Its other parts
/// that touch another segment are fragments: pieces the splits cut off from all the
/// segment's cores (the strip of doorway cells along a corridor's wall, left in the
/// corridor's label), which [`merge_segments`] joins to the room each lies in, whatever their
/// size, instead of one scattered segment joined to one of them. Parts that touch no other
/// segment are segments of their own if they have `min_room_cells` or more, or a quarter of
/// that and are walled in (a closet walled off from the rest), and no part of any room
/// otherwise: specks of free space walled in by clutter, and the tips of fans of scan rays
/// ([`part_surroundings`]).
fn split_disconnected(labels: &mut Grid<u16>, map: &Grid<Cell>, min_room_cells: usize) -> Vec<bool> {
    // `part[i]` is cell i's part (1-based, 0 for none); `found[k]` is part k's (label, cells).
    let (part, found) = find_cores(labels, |_| true);
    let around = part_surroundings(labels, map, &part, found.len());
    // Each part: (label, cells, touches another segment), numbered from 0.
    let parts: Vec<(u16, usize, bool)> =
        found.iter().zip(&around).skip(1).map(|(&(l, n), &(t, _))| (l, n, t)).collect();
    let walled_in = |k: usize| around[k + 1].1;
    let max_label = labels.cells().iter().copied().max().unwrap_or(0) as usize;
    let mut biggest = vec![(0usize, usize::MAX); max_label + 1];
    for (k, &(l, n, _)) in parts.iter().enumerate() {
        if n > biggest[l as usize].0 {
            biggest[l as usize] = (n, k);
        }
    }
    let largest = |k: usize| biggest[parts[k].0 as usize].1 == k;
    let lone_room = |k: usize| parts[k].1 >= min_room_cells || (walled_in(k) && parts[k].1 >= min_room_cells / 4);
    let kept = |k: usize| parts[k].2 || lone_room(k);
    let mut id = vec![0u16; parts.len()];
    let mut fragment = vec![false];
    for (cell, &p) in labels.cells_mut().iter_mut().zip(&part) {
        let k = p as usize;
        if k == 0 || !kept(k - 1) {
            *cell = 0;
            continue;
        }
        if id[k - 1] == 0 {
            id[k - 1] = fragment.len().min(u16::MAX as usize - 1) as u16;
            if fragment.len() < u16::MAX as usize - 1 {
                fragment.push(!largest(k - 1) && parts[k - 1].2);
            }
        }
        *cell = id[k - 1];
    }
    fragment
}

/// For each part (`part`: cells to 1-based parts, `n` parts counting the 0th), in one pass
/// over the steps from its cells to the 4-neighbours outside it: whether it touches another
/// segment, and whether it is walled in, at least [`MIN_WALLED_BORDER`] of those steps leading
/// to occupied cells of `map` (always, if `map` is not the labels' size). A closet is walled
/// in. The tip of a fan of scan rays beyond a room's wall, which the room's rectangle overlaps
/// and the splits cut off, is not: unseen cells lie between its rays.
fn part_surroundings(labels: &Grid<u16>, map: &Grid<Cell>, part: &[u32], n: usize) -> Vec<(bool, bool)> {
    let (w, h) = (labels.width(), labels.height());
    let same_size = (map.width(), map.height()) == (w, h);
    // Per part: (touches another segment, steps out of it, steps onto occupied cells).
    let mut border = vec![(false, 0u32, 0u32); n];
    for (i, &l) in labels.cells().iter().enumerate() {
        if l == 0 {
            continue;
        }
        let b = &mut border[part[i] as usize];
        let mut inside = 0;
        for j in neighbours4(i, w, h) {
            let lj = labels.cells()[j];
            inside += u32::from(lj == l);
            b.0 |= lj != 0 && lj != l;
            b.2 += u32::from(lj != l && same_size && map.cells()[j] == Cell::Occupied);
        }
        b.1 += 4 - inside;
    }
    let walled = |all: u32, wall: u32| !same_size || f64::from(wall) >= MIN_WALLED_BORDER * f64::from(all);
    border.into_iter().map(|(touches, all, wall)| (touches, walled(all, wall))).collect()
}

/// The smallest share of a walled-in part's border on occupied cells ([`part_surroundings`]). The
/// closets the splits cut off on the benchmark maps have 46 % or more; the tips of fans of rays
/// cut off on Cartesium 6 - 13 %.
const MIN_WALLED_BORDER: f64 = 1.0 / 3.0;

/// Owner room of every world cell: the room of the first unit covering it (0 for none).
fn room_owner(world: &World, rooms: &[u16], world_map: &Grid<Cell>) -> Vec<u16> {
    let (ww, wh) = (world_map.width(), world_map.height());
    let mut owner = vec![0u16; ww * wh];
    for (u, &room) in world.units.iter().zip(rooms) {
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
    owner
}

/// Labels every free map cell whose world cell has an owner room, and queues those cells.
fn label_unit_cells(world: &World, owner: &[u16], ww: usize, map: &Grid<Cell>) -> (Grid<u16>, VecDeque<u32>) {
    let wh = owner.len() / ww.max(1);
    let rotation = world.frame.rotation();
    let mut labels = Grid::new(map.width(), map.height(), 0u16);
    let mut queue = VecDeque::new();
    for my in 0..map.height() {
        for mx in 0..map.width() {
            if *map.at(mx, my) != Cell::Free {
                continue;
            }
            if let Some((wx, wy)) = world_cell(world, &rotation, mx, my, (ww, wh)) {
                let room = owner[wy * ww + wx];
                if room > 0 {
                    *labels.at_mut(mx, my) = room;
                    // Cell indices, not coordinate pairs: the queue holds most of the map's
                    // free cells at once, and 4 bytes a cell instead of 16 keeps the peak low.
                    queue.push_back((my * map.width() + mx) as u32);
                }
            }
        }
    }
    (labels, queue)
}

/// Wavefront: unlabelled free cells within `max_reach` steps take the label of the nearest
/// labelled one.
fn spread_labels(labels: &mut Grid<u16>, map: &Grid<Cell>, queue: VecDeque<u32>, max_reach: u32) {
    let (w, h) = (map.width(), map.height());
    let free = |j: usize, _| map.cells()[j] == Cell::Free;
    labelled_wavefront(w, h, labels.cells_mut(), queue, free, max_reach);
}

/// Free regions out of every unit's reach become rooms of their own, numbered after `last`,
/// if big and deep enough ([`RoomCells::min_room_cells`], [`RoomCells::min_room_depth`]);
/// the others stay unlabelled.
fn label_far_regions(labels: &mut Grid<u16>, map: &Grid<Cell>, last: u16, c: &RoomCells) {
    let (w, h) = (map.width(), map.height());
    let depth = if c.min_room_depth > 0 { free_depth(map) } else { vec![u32::MAX; w * h] };
    let mut next = last;
    let mut flood = Flood::default();
    let mut region = Vec::new();
    for start in 0..w * h {
        if map.cells()[start] != Cell::Free || labels.cells()[start] != 0 {
            continue;
        }
        // Flood the region with a provisional id, then keep it only if it is a room.
        let id = next.saturating_add(1);
        region.clear();
        let ids = labels.cells_mut();
        let mut enter =
            |j: usize| map.cells()[j] == Cell::Free && ids[j] == 0 && std::mem::replace(&mut ids[j], id) == 0;
        flood.fill(w, h, [start], Neighbours::Four, &mut enter, |i| region.push(i));
        let deep = region.iter().filter(|&&i| depth[i] > 3 * c.min_room_depth).count();
        if region.len() >= c.min_room_cells && deep >= c.min_room_cells / 4 {
            next = id;
        } else {
            // u16::MAX marks "seen, not a room" until the end.
            for &i in &region {
                labels.cells_mut()[i] = u16::MAX;
            }
        }
    }
    for l in labels.cells_mut() {
        if *l == u16::MAX {
            *l = 0;
        }
    }
}

/// Joins every segment smaller than `min_cells` to the neighbouring segment it shares the
/// longest boundary with (4-neighbours), smallest first, then numbers the segments 1..=n in
/// scan order. Segments with no labelled neighbour stay.
#[cfg(test)]
fn merge_small_segments(labels: &mut Grid<u16>, min_cells: usize) {
    merge_segments(labels, min_cells, &[], 0);
}

/// [`merge_small_segments`], joining also the segments `fragment` marks (indexed by label),
/// whatever their size, and unlabelling the segments still under `min_room` cells after the
/// merge. Those touch no other segment: two slivers that only touched each other, left over
/// from the splits ([`split_disconnected`] keeps no lone part that small either), so no room
/// is.
fn merge_segments(labels: &mut Grid<u16>, min_cells: usize, fragment: &[bool], min_room: usize) {
    use std::collections::BTreeMap;
    if min_cells == 0 && min_room == 0 && !fragment.contains(&true) {
        return;
    }
    let n = labels.cells().iter().copied().max().unwrap_or(0) as usize;
    let mut size = vec![0usize; n + 1];
    for &l in labels.cells() {
        size[l as usize] += 1;
    }
    // Contacts both ways round, so that a label's neighbours are one range of the map.
    let mut contact: BTreeMap<(u16, u16), usize> = BTreeMap::new();
    for ((a, b), k) in crate::floorplan::topology::contacts(&labels.map(|&l| l as u32)) {
        contact.insert((a as u16, b as u16), k);
        contact.insert((b as u16, a as u16), k);
    }
    // Where each label went (union by redirection), smallest segments first.
    let mut to: Vec<u16> = (0..=n as u16).collect();
    let find = |to: &[u16], mut l: u16| {
        while to[l as usize] != l {
            l = to[l as usize];
        }
        l
    };
    let mut order: Vec<u16> = (1..=n as u16).filter(|&l| size[l as usize] > 0).collect();
    crate::sort::sort_by_key(&mut order, |&l| (size[l as usize], l));
    for l in order {
        let root = find(&to, l);
        let small = size[l as usize] < min_cells || fragment.get(l as usize).copied().unwrap_or(false);
        if root != l || !small {
            continue;
        }
        let mut best: BTreeMap<u16, usize> = BTreeMap::new();
        for (&(a, b), &k) in contact.range((l, 0)..=(l, u16::MAX)) {
            debug_assert_eq!(a, l);
            let r = find(&to, b);
            if r != l {
                *best.entry(r).or_default() += k;
            }
        }
        if let Some((&target, _)) = best.iter().max_by_key(|&(&r, &k)| (k, std::cmp::Reverse(r))) {
            to[l as usize] = target;
            size[target as usize] += size[l as usize];
            // The merged segment's contacts are its parts' contacts: look them up by part.
            let moved: Vec<((u16, u16), usize)> =
                contact.range((l, 0)..=(l, u16::MAX)).map(|(&k, &v)| (k, v)).collect();
            for ((_, b), k) in moved {
                *contact.entry((target, b)).or_default() += k;
            }
        }
    }
    let mut id = vec![0u16; n + 1];
    let mut next = 0u16;
    for l in labels.cells_mut() {
        if *l == 0 {
            continue;
        }
        let r = find(&to, *l) as usize;
        if size[r] < min_room {
            *l = 0;
            continue;
        }
        if id[r] == 0 {
            next += 1;
            id[r] = next;
        }
        *l = id[r];
    }
}

/// Chamfer 3-4 distance (3 per straight step, 4 per diagonal one) from every cell to the
/// nearest non-free cell; cells beyond the map are not free. Non-free cells are 0.
pub fn free_depth(map: &Grid<Cell>) -> Vec<u32> {
    let (w, h) = (map.width(), map.height());
    let mut dist = vec![0u32; w * h];
    const FAR: u32 = u32::MAX / 2;
    for y in 0..h {
        for x in 0..w {
            dist[y * w + x] = if *map.at(x, y) == Cell::Free { FAR } else { 0 };
        }
    }
    let at = |d: &[u32], x: usize, y: usize, dx: isize, dy: isize| -> u32 {
        let (nx, ny) = (x as isize + dx, y as isize + dy);
        if nx < 0 || ny < 0 || nx >= w as isize || ny >= h as isize {
            0
        } else {
            d[ny as usize * w + nx as usize]
        }
    };
    for y in 0..h {
        for x in 0..w {
            let i = y * w + x;
            if dist[i] == 0 {
                continue;
            }
            let m = (at(&dist, x, y, -1, 0) + 3)
                .min(at(&dist, x, y, 0, -1) + 3)
                .min(at(&dist, x, y, -1, -1) + 4)
                .min(at(&dist, x, y, 1, -1) + 4);
            dist[i] = dist[i].min(m);
        }
    }
    for y in (0..h).rev() {
        for x in (0..w).rev() {
            let i = y * w + x;
            if dist[i] == 0 {
                continue;
            }
            let m = (at(&dist, x, y, 1, 0) + 3)
                .min(at(&dist, x, y, 0, 1) + 3)
                .min(at(&dist, x, y, 1, 1) + 4)
                .min(at(&dist, x, y, -1, 1) + 4);
            dist[i] = dist[i].min(m);
        }
    }
    dist
}

/// Splits rooms at doorways, as morphological and Voronoi room segmentation do (Bormann et
/// al. 2016): a rectangle explains a room's walls, but where the walls are not rectangular (or
/// stop short) one unit, or a group of units, can reach through doors into the rooms behind.
///
/// A room's *cores* are its free cells farther than `door_half_width` from every wall or
/// unknown cell (a chamfer distance; clutter such as chairs counts as free,
/// [`RoomCells::min_wall_len`]), split into 4-connected parts; a doorway narrower than twice that
/// leaves no core cells, so rooms joined by doors have separate cores while a room narrowed
/// only a little keeps one. A room with two or more cores of `min_core_cells` or more is
/// divided among them: each of its cells joins the core nearest to it through the room
/// (wavefront), and cells no core reaches keep the room's label. Rooms are then numbered
/// 1..=n in scan order. `open` is the map with its clutter drawn free ([`without_clutter`](super::wall_gaps::without_clutter)).
fn split_open_at_doorways(labels: &mut Grid<u16>, open: &Grid<Cell>, c: &RoomCells) {
    let (w, h) = (labels.width(), labels.height());
    if c.door_half_width == 0 || w == 0 || h == 0 || (open.width(), open.height()) != (w, h) {
        return;
    }
    let dist = free_depth(open);
    let core_min = c.door_half_width.saturating_mul(3);
    let (seed, cores) = find_cores(labels, |i| dist[i] > core_min);
    divide_among_cores(labels, &seed, &cores, c.min_core_cells);
}

/// Splits rooms along the wall gaps of `closed` (the map with every gap drawn as a wall,
/// [`super::wall_gaps::close_wall_gaps_along`]): a room whose free cells, gaps left out, fall into
/// two or more 4-connected parts of `min_core_cells` or more is divided among those parts
/// as [`split_open_at_doorways`] divides a room among its cores. A gap that closes nothing (two
/// desks in a row, a notch) leaves one part and changes nothing.
pub fn split_at_wall_gaps(labels: &mut Grid<u16>, closed: &Grid<Cell>, c: &RoomCells) {
    let (w, h) = (labels.width(), labels.height());
    if w == 0 || h == 0 || (closed.width(), closed.height()) != (w, h) {
        return;
    }
    let (seed, cores) = find_cores(labels, |i| closed.cells()[i] == Cell::Free);
    divide_among_cores(labels, &seed, &cores, c.min_core_cells);
}

/// Cores: the 4-connected parts of labelled cells with `is_core` and one label. Returns each
/// cell's core number (0 for none) and each core's (label, cells), index 0 standing for none.
fn find_cores(labels: &Grid<u16>, is_core: impl Fn(usize) -> bool) -> (Vec<u32>, Vec<(u16, usize)>) {
    let (w, h) = (labels.width(), labels.height());
    let mut seed = vec![0u32; w * h];
    let mut cores: Vec<(u16, usize)> = vec![(0, 0)];
    let mut flood = Flood::default();
    for start in 0..w * h {
        let l = labels.cells()[start];
        if l == 0 || seed[start] != 0 || !is_core(start) {
            continue;
        }
        let id = cores.len() as u32;
        let mut n = 0usize;
        let mut enter =
            |j: usize| seed[j] == 0 && labels.cells()[j] == l && is_core(j) && std::mem::replace(&mut seed[j], id) == 0;
        flood.fill(w, h, [start], Neighbours::Four, &mut enter, |_| n += 1);
        cores.push((l, n));
    }
    (seed, cores)
}

/// Divides every room with two or more cores of `min_core_cells` or more among them: each of
/// its cells joins the core nearest to it through the room (wavefront), cells no core reaches
/// keep the room's label, and small cores are forgotten. Rooms are then numbered 1..=n in
/// scan order (unchanged when no room is divided).
fn divide_among_cores(labels: &mut Grid<u16>, seed: &[u32], cores: &[(u16, usize)], min_core_cells: usize) {
    let (w, h) = (labels.width(), labels.height());
    let max_label = labels.cells().iter().copied().max().unwrap_or(0) as usize;
    let mut big = vec![0usize; max_label + 1];
    for &(l, n) in &cores[1..] {
        if n >= min_core_cells {
            big[l as usize] += 1;
        }
    }
    if big.iter().all(|&k| k < 2) {
        return;
    }
    let mut owner = vec![0u32; w * h];
    let mut queue = VecDeque::new();
    for i in 0..w * h {
        let s = seed[i] as usize;
        if s != 0 {
            let (l, n) = cores[s];
            if big[l as usize] >= 2 && n >= min_core_cells {
                owner[i] = s as u32;
                queue.push_back(i as u32);
            }
        }
    }
    // Each cell of a divided room joins the core nearest to it through the room.
    let same_room = |j: usize, o: u32| labels.cells()[j] == cores[o as usize].0;
    labelled_wavefront(w, h, &mut owner, queue, same_room, u32::MAX);
    // Renumber: a split room's parts by core, other rooms by label, in scan order.
    let mut id_of_core = vec![0u16; cores.len()];
    let mut id_of_label = vec![0u16; max_label + 1];
    let mut next = 0u16;
    for i in 0..w * h {
        let l = labels.cells()[i];
        if l == 0 {
            continue;
        }
        let slot = if owner[i] != 0 { &mut id_of_core[owner[i] as usize] } else { &mut id_of_label[l as usize] };
        if *slot == 0 {
            next = next.saturating_add(1).min(u16::MAX - 1);
            *slot = next;
        }
        labels.cells_mut()[i] = *slot;
    }
}

#[cfg(test)]
pub(crate) mod tests {
    use super::super::layer::room_labels;
    use super::super::pairs::{group_units, open_pairs, OpenPair};
    use super::*;
    use crate::floorplan::{Unit, UnitType};

    fn unit(id: u32, x: i32, y: i32, w: i32, h: i32) -> Unit {
        Unit::new(id, x, y, w, h, UnitType::Unknown)
    }

    /// A map all wall: every lone part is walled in.
    fn walls(w: usize, h: usize) -> Grid<Cell> {
        Grid::new(w, h, Cell::Occupied)
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
        let rooms = group_units(&world, &map, &RoomCells::default());
        assert_eq!(rooms, vec![1, 1, 2]);
        let labels = room_labels(&world, &map, &map, &RoomCells::default());
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
        // Rooms here are smaller than the smallest segment kept alone: no merging.
        let c = RoomCells { min_segment_cells: 0, ..RoomCells::default() };
        let labels = room_labels(&world, &map, &map, &c);
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
        let c = RoomCells { min_segment_cells: 0, ..RoomCells::default() };
        let labels = room_labels(&world, &map, &map, &c);
        assert_eq!(*labels.at(22, 10), 1, "nearer to the left unit");
        assert_eq!(*labels.at(27, 10), 2, "nearer to the right unit");
        assert_eq!(*labels.at(25, 0), 0, "an isolated free cell is no room");
        assert_eq!(*labels.at(0, 0), 0, "unknown cells are not labelled");
    }

    #[test]
    fn a_door_as_wide_as_the_shared_wall_is_an_opening() {
        // Two 41x40 units sharing the wall at column 40, which the map has only at its ends
        // (rows 0..3 and 37..40, stubs of the outer walls): the chain explains the gap with a
        // 34-cell door.
        let mut map = Grid::new(81, 40, Cell::Free);
        for y in (0..3).chain(37..40) {
            *map.at_mut(40, y) = Cell::Occupied;
        }
        for x in 0..81 {
            *map.at_mut(x, 0) = Cell::Occupied;
            *map.at_mut(x, 39) = Cell::Occupied;
        }
        let mut world = World::empty(81, 40);
        world.units = vec![unit(1, 0, 0, 41, 40), unit(2, 40, 0, 41, 40)];
        world.doors =
            vec![crate::floorplan::Door { id: 1, units: [1, 2], x0: 40, y0: 3, x1: 40, y1: 36, opening: false }];
        let c = RoomCells::default();
        assert_eq!(open_pairs(&world, &map, &c), vec![OpenPair { a: 0, b: 1, flush: true, closed: false }]);
        // Not when wide doors are doors (the wall band is 15 % occupied: no opening by itself).
        let doors = RoomCells { wide_door_share: 2.0, ..c };
        assert!(open_pairs(&world, &map, &doors).is_empty());
        // A narrow door stays a door.
        world.doors[0].y1 = 12;
        assert!(open_pairs(&world, &map, &c).is_empty());
    }

    #[test]
    fn a_wide_door_through_a_thick_wall_is_an_opening_too() {
        // Walls 3 cells deep; the two units' walls are 8 cells apart (a door may cross up to
        // 10), and a door 8 cells deep spans the whole stretch they face each other along: a
        // corridor the chain cut in two where a thick wall's ends narrow it.
        let mut map = Grid::new(90, 40, Cell::Free);
        for x in 0..90 {
            for y in (0..3).chain(37..40) {
                *map.at_mut(x, y) = Cell::Occupied;
            }
        }
        for x in 41..49 {
            for y in (3..5).chain(35..37) {
                *map.at_mut(x, y) = Cell::Occupied;
            }
        }
        let mut world = World::empty(90, 40);
        world.wall_thickness = 3;
        world.units = vec![unit(1, 0, 0, 41, 40), unit(2, 49, 0, 41, 40)];
        world.doors =
            vec![crate::floorplan::Door { id: 1, units: [1, 2], x0: 38, y0: 3, x1: 51, y1: 36, opening: false }];
        let c = RoomCells::default();
        assert_eq!(open_pairs(&world, &map, &c), vec![OpenPair { a: 0, b: 1, flush: true, closed: false }]);
        // A narrow door through the same wall stays a door.
        world.doors[0].y1 = 14;
        assert!(open_pairs(&world, &map, &c).is_empty());
    }

    #[test]
    fn small_segments_join_the_neighbour_they_share_most_boundary_with() {
        // Segments 1 (40x40), 2 (60x45) and a sliver 3 (40x5) below 1, numbered in scan
        // order; the sliver touches 1 along 40 cells and 2 along 5.
        let mut labels = Grid::new(100, 45, 0u16);
        for y in 0..45 {
            for x in 0..100 {
                *labels.at_mut(x, y) = if y >= 40 && x < 40 {
                    3
                } else if x < 40 {
                    1
                } else {
                    2
                };
            }
        }
        let mut merged = labels.clone();
        merge_small_segments(&mut merged, 1000);
        assert_eq!(*merged.at(10, 42), *merged.at(10, 10), "the sliver joins segment 1");
        assert_ne!(*merged.at(10, 10), *merged.at(70, 10));
        assert_eq!(merged.cells().iter().copied().max(), Some(2), "renumbered 1..=n");
        // Below the limit nothing moves; a limit of 0 turns merging off.
        let mut same = labels.clone();
        merge_small_segments(&mut same, 200);
        assert!(same == labels, "a 200-cell sliver is not below 200");
        merge_small_segments(&mut same, 0);
        assert!(same == labels, "0 turns merging off");
    }

    #[test]
    fn scan_ray_fans_beyond_every_unit_are_not_rooms() {
        // A unit on the left; far to the right, a fan of thin free rays (2 cells wide, 5 apart)
        // of 1,200 cells, and below it a deep free square of 40x40: only the square is a room.
        let mut map = Grid::new(200, 100, Cell::Unknown);
        for y in 0..100 {
            for x in 0..30 {
                *map.at_mut(x, y) = Cell::Free;
            }
        }
        for ray in 0..6 {
            for x in 100..200 {
                for dy in 0..2 {
                    *map.at_mut(x, 5 + ray * 5 + dy) = Cell::Free;
                }
            }
            *map.at_mut(100, 5 + ray * 5 + 2) = Cell::Free; // joined at their source
            *map.at_mut(100, 5 + ray * 5 + 3) = Cell::Free;
            *map.at_mut(100, 5 + ray * 5 + 4) = Cell::Free;
        }
        for y in 55..95 {
            for x in 120..160 {
                *map.at_mut(x, y) = Cell::Free;
            }
        }
        let mut world = World::empty(200, 100);
        world.units = vec![unit(1, 0, 0, 30, 100)];
        let labels = room_labels(&world, &map, &map, &RoomCells::default());
        assert_eq!(*labels.at(150, 5), 0, "a fan is no room");
        assert!(*labels.at(140, 75) > 0, "a deep region is");
        let keep = RoomCells { min_room_depth: 0, ..RoomCells::default() };
        assert!(*room_labels(&world, &map, &map, &keep).at(150, 5) > 0, "without the depth test it is");
    }

    /// A corridor above two rooms, joined to them by doors narrower than a room core allows.
    fn corridor_with_two_rooms() -> Grid<Cell> {
        let mut map = Grid::new(200, 120, Cell::Free);
        for x in 0..200 {
            *map.at_mut(x, 0) = Cell::Occupied;
            *map.at_mut(x, 119) = Cell::Occupied;
            if !(30..46).contains(&x) && !(130..146).contains(&x) {
                *map.at_mut(x, 40) = Cell::Occupied;
            }
        }
        for y in 0..120 {
            *map.at_mut(0, y) = Cell::Occupied;
            *map.at_mut(199, y) = Cell::Occupied;
            if y > 40 {
                *map.at_mut(100, y) = Cell::Occupied;
            }
        }
        map
    }

    #[test]
    fn doorways_split_a_unit_that_reaches_through_them() {
        // One unit over the whole floor, as the chain leaves it where rooms are not rectangles.
        let map = corridor_with_two_rooms();
        let mut world = World::empty(200, 120);
        world.units = vec![unit(1, 0, 0, 200, 120)];
        let labels = room_labels(&world, &map, &map, &RoomCells::default());
        let (corridor, left, right) = (*labels.at(50, 20), *labels.at(50, 80), *labels.at(150, 80));
        assert!(corridor > 0 && left > 0 && right > 0);
        assert!(corridor != left && corridor != right && left != right, "{corridor} {left} {right}");
        assert_eq!(*labels.at(5, 35), corridor);
        assert_eq!(*labels.at(95, 115), left);
        assert_eq!(*labels.at(105, 45), right);
        assert_eq!(labels.cells().iter().copied().max(), Some(3), "rooms are numbered 1..=n");
        // Without the split (and without closing wall gaps, which close these doorways too)
        // it is one room.
        let off = RoomCells { door_half_width: 0, max_wall_gap: 0, ..RoomCells::default() };
        let labels = room_labels(&world, &map, &map, &off);
        assert_eq!(*labels.at(50, 20), *labels.at(150, 80));
    }

    #[test]
    fn a_nook_behind_furniture_stays_with_its_room() {
        // A 160 x 80 room; a cupboard leaves a 40 x 40 nook open through a 10-cell gap. The
        // nook has a core, smaller than a room's.
        let mut map = Grid::new(160, 80, Cell::Free);
        for x in 0..160 {
            *map.at_mut(x, 0) = Cell::Occupied;
            *map.at_mut(x, 79) = Cell::Occupied;
        }
        for y in 0..80 {
            *map.at_mut(0, y) = Cell::Occupied;
            *map.at_mut(159, y) = Cell::Occupied;
        }
        for y in 1..79 {
            if !(50..60).contains(&y) {
                *map.at_mut(115, y) = Cell::Occupied;
            }
        }
        for x in 115..159 {
            *map.at_mut(x, 40) = Cell::Occupied;
        }
        let mut world = World::empty(160, 80);
        world.units = vec![unit(1, 0, 0, 160, 80)];
        // Wall gaps off: the doorway split alone (closing the 10-cell gap between the two
        // wall-thin pieces of cupboard, as the default does, makes the 2 m nook a room).
        let doorways = RoomCells { max_wall_gap: 0, ..RoomCells::default() };
        let labels = room_labels(&world, &map, &map, &doorways);
        assert_eq!(*labels.at(50, 40), *labels.at(137, 60), "the nook is part of the room");
        let labels = room_labels(&world, &map, &map, &RoomCells::default());
        assert_ne!(*labels.at(50, 40), *labels.at(137, 60), "closed, the nook is a room");
        // With small cores allowed, the same nook is a room of its own: the test can fail.
        let small = RoomCells { min_core_cells: 50, ..doorways };
        let labels = room_labels(&world, &map, &map, &small);
        assert_ne!(*labels.at(50, 40), *labels.at(137, 60));
    }

    /// A 200 x 120 room walled all round.
    /// A `w` x `h` map of free cells with a one-cell wall round it.
    pub(crate) fn walled_room(w: usize, h: usize) -> Grid<Cell> {
        let mut map = Grid::new(w, h, Cell::Free);
        for x in 0..w {
            *map.at_mut(x, 0) = Cell::Occupied;
            *map.at_mut(x, h - 1) = Cell::Occupied;
        }
        for y in 0..h {
            *map.at_mut(0, y) = Cell::Occupied;
            *map.at_mut(w - 1, y) = Cell::Occupied;
        }
        map
    }

    #[test]
    fn a_table_ringed_by_chairs_is_no_room() {
        // A drawn meeting table: 2 x 2 chairs every 6 cells round a 100 x 70 free area in the
        // middle of a 300 x 200 room. The gaps between the chairs are far narrower than a
        // door, so if chairs were walls the table would be a room behind doorways.
        let mut map = walled_room(300, 200);
        let (x0, y0, x1, y1) = (100, 65, 200, 135);
        let mut chair = |x: usize, y: usize| {
            for (cx, cy) in [(x, y), (x + 1, y), (x, y + 1), (x + 1, y + 1)] {
                *map.at_mut(cx, cy) = Cell::Occupied;
            }
        };
        for x in (x0..=x1).step_by(6) {
            chair(x, y0);
            chair(x, y1);
        }
        for y in (y0..=y1).step_by(6) {
            chair(x0, y);
            chair(x1, y);
        }
        let mut world = World::empty(300, 200);
        world.units = vec![unit(1, 0, 0, 300, 200)];
        let c = RoomCells::default();
        let labels = room_labels(&world, &map, &map, &c);
        assert!(*labels.at(150, 100) > 0);
        assert_eq!(*labels.at(150, 100), *labels.at(20, 20), "the table's middle is part of the room");
        // Chairs counted as walls (no part too short to be one): the ring parts the room.
        let chairs_are_walls = RoomCells { min_wall_len: 1, ..c };
        let labels = room_labels(&world, &map, &map, &chairs_are_walls);
        assert_ne!(*labels.at(150, 100), *labels.at(20, 20));
    }

    #[test]
    fn furniture_inside_a_room_is_part_of_it_but_a_block_between_two_rooms_is_not() {
        // Two rooms (0..60 and 61..120) parted by a wall at column 60 with a doorway at rows
        // 15..25; a desk (10 x 6) in the middle of the left room, a cupboard (4 x 4) against
        // in the doorway, clear of the wall, in both rooms.
        let mut map = walled_room(121, 40);
        for y in (0..40).filter(|y| !(15..25).contains(y)) {
            *map.at_mut(60, y) = Cell::Occupied;
        }
        let mut block = |x0: usize, y0: usize, w: usize, h: usize| {
            for y in y0..y0 + h {
                for x in x0..x0 + w {
                    *map.at_mut(x, y) = Cell::Occupied;
                }
            }
        };
        block(20, 17, 10, 6);
        block(58, 18, 5, 4);
        let mut world = World::empty(121, 40);
        world.units = vec![unit(1, 0, 0, 61, 40), unit(2, 60, 0, 61, 40)];
        let c = RoomCells { door_half_width: 0, max_wall_gap: 0, ..RoomCells::default() };
        let labels = room_labels(&world, &map, &map, &c);
        let (left, right) = (*labels.at(5, 5), *labels.at(100, 5));
        assert!(left != 0 && right != 0 && left != right, "two rooms: {left}, {right}");
        assert_eq!(*labels.at(25, 20), left, "the desk is in the left room");
        assert_eq!((*labels.at(57, 20), *labels.at(63, 20)), (left, right), "the block touches both rooms");
        assert_eq!(*labels.at(60, 20), 0, "the block in the doorway belongs to no room");
        assert_eq!(*labels.at(60, 5), 0, "walls belong to no room");
        let free_only = room_labels(&world, &map, &map, &RoomCells { clutter_in_rooms: false, ..c });
        assert_eq!(*free_only.at(25, 20), 0, "off, only free cells are labelled");
        let counted = |l: &Grid<u16>| l.cells().iter().filter(|&&v| v == left).count();
        assert_eq!(counted(&labels), counted(&free_only) + 60, "the desk's 60 cells, no more");
    }

    #[test]
    fn slivers_that_only_touch_each_other_are_no_room() {
        // A room (label 1, 30 x 30) and, far from it, two one-cell slivers of labels 2 and 3
        // side by side: each touches another segment, so the part split keeps both and the
        // merge joins them into one segment of two cells, which is then dropped.
        let mut labels = Grid::new(60, 40, 0u16);
        for y in 0..30 {
            for x in 0..30 {
                *labels.at_mut(x, y) = 1;
            }
        }
        *labels.at_mut(50, 35) = 2;
        *labels.at_mut(51, 35) = 3;
        let c = RoomCells::default();
        let fragment = split_disconnected(&mut labels, &walls(60, 40), c.min_room_cells);
        let mut kept = labels.clone();
        merge_segments(&mut kept, c.min_segment_cells, &fragment, 0);
        let seg = *kept.at(50, 35);
        assert!(seg != 0 && seg == *kept.at(51, 35), "merged into one segment of two cells");
        merge_segments(&mut labels, c.min_segment_cells, &fragment, c.min_room_cells / 4);
        assert_eq!((*labels.at(50, 35), *labels.at(51, 35)), (0, 0));
        assert_eq!(*labels.at(10, 10), 1);
        assert_eq!(labels.cells().iter().filter(|&&l| l == 1).count(), 900);
    }

    #[test]
    fn chairs_along_an_open_boundary_are_no_wall() {
        // Two units side by side in one room, with a row of chairs (0.45 m square, 9 x 9
        // cells, 2 apart) down the line between them, clear of the room's walls: over half of
        // the band is occupied, but by no wall. (Pieces a wall's thickness across, 0.1 m
        // apart, would be a glass pane, `wall_gaps::walls`; a chair is deeper than a wall.)
        let mut map = walled_room(90, 40);
        for y in (4..36).filter(|y| (y - 4) % 11 < 9) {
            for x in 41..50 {
                *map.at_mut(x, y) = Cell::Occupied;
            }
        }
        let mut world = World::empty(90, 40);
        world.units = vec![unit(1, 0, 0, 46, 40), unit(2, 45, 0, 45, 40)];
        let c = RoomCells::default();
        assert_eq!(open_pairs(&world, &map, &c), vec![OpenPair { a: 0, b: 1, flush: true, closed: false }]);
        let chairs_are_walls = RoomCells { min_wall_len: 1, ..c };
        assert!(open_pairs(&world, &map, &chairs_are_walls).is_empty());
    }

    #[test]
    fn pieces_cut_off_from_a_segment_join_the_rooms_they_lie_in() {
        // Label 1 is a corridor (rows 0..10) and, cut off from it by a wall (row 10), two
        // strips of cells along the tops of rooms 2 and 3 (row 11): a scattered segment.
        let (w, h) = (60, 40);
        let mut labels = Grid::new(w, h, 0u16);
        for y in 0..h {
            for x in 0..w {
                *labels.at_mut(x, y) = match (x, y) {
                    (_, 10) => 0,
                    (_, 0..=9) => 1,
                    (_, 11) => 1,
                    (0..=29, _) => 2,
                    (30, _) => 0,
                    _ => 3,
                };
            }
        }
        *labels.at_mut(30, 11) = 0;
        let fragment = split_disconnected(&mut labels, &walls(w, h), 400);
        assert_eq!(fragment.iter().filter(|&&f| f).count(), 2, "the two strips");
        merge_segments(&mut labels, 0, &fragment, 0); // fragments only, whatever their size
        assert_eq!(*labels.at(5, 11), *labels.at(5, 20), "the left strip joins the left room");
        assert_eq!(*labels.at(45, 11), *labels.at(45, 20), "the right strip joins the right room");
        assert_ne!(*labels.at(5, 5), *labels.at(5, 11));
        assert_eq!(labels.cells().iter().copied().max(), Some(3));
        // A speck walled in on its own (no other segment beside it) is no room.
        let mut specks = Grid::new(20, 20, 0u16);
        *specks.at_mut(5, 5) = 1;
        *specks.at_mut(15, 15) = 1;
        split_disconnected(&mut specks, &walls(20, 20), 400);
        assert!(specks.cells().iter().all(|&l| l == 0));
        // Two lone parts of 15 x 15 cells (a quarter of `min_room_cells` or more, and less
        // than it): the one walled in is a closet, the one amid unseen cells the tip of a fan
        // of rays, no room.
        let mut lone = Grid::new(60, 30, 0u16);
        let mut map = walls(60, 30);
        for y in 1..16 {
            for x in 1..16 {
                *lone.at_mut(x, y) = 1;
                *lone.at_mut(x + 30, y) = 1;
            }
        }
        for y in 0..30 {
            for x in 25..60 {
                *map.at_mut(x, y) = Cell::Unknown;
            }
        }
        split_disconnected(&mut lone, &map, 400);
        assert_ne!(*lone.at(5, 5), 0, "the closet");
        assert_eq!(*lone.at(35, 5), 0, "the tip of a fan");
    }

    #[test]
    fn cells_a_scan_missed_amid_a_room_part_nothing() {
        // A line of unseen cells, one every 4 rows, across the middle of a 300 x 200 room
        // (speckle in a SLAM map). The gaps between them are far narrower than a door.
        let mut map = walled_room(300, 200);
        for y in (2..198).step_by(4) {
            *map.at_mut(150, y) = Cell::Unknown;
        }
        let mut world = World::empty(300, 200);
        world.units = vec![unit(1, 0, 0, 300, 200)];
        let c = RoomCells::default();
        let labels = room_labels(&world, &map, &map, &c);
        assert_eq!(*labels.at(50, 100), *labels.at(250, 100), "one room");
        // Unseen specks counted as the edge of the map (no part too short to be a wall): the
        // line parts the room.
        let specks_are_walls = RoomCells { min_wall_len: 1, ..c };
        let labels = room_labels(&world, &map, &map, &specks_are_walls);
        assert_ne!(*labels.at(50, 100), *labels.at(250, 100));
    }
}
