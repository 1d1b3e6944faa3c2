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

/// Whether units `a` and `b` (rectangles, walls `t` deep) have an open boundary, and whether
/// it is flush: `None` if there is none.
fn open_boundary(a: Rect, b: Rect, t: i32, world_map: &Grid<Cell>, c: &RoomCells) -> Option<bool> {
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
            if total > 0 && (occ as f64) <= c.max_wall_share * total as f64 {
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
            let open = open_boundary(ra, rb, t, walls, c).or_else(|| wide_door(world, a, b, c));
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
