//! What a robot with a 2D laser would have mapped of a layout.
//!
//! The truth is rasterised in the world frame, then degraded the way SLAM maps are:
//!
//! * explored units read free, units the robot never entered read unknown, except for a fan
//!   of free cells seen through a door from the explored side ("peeking");
//! * a wall cell reads occupied only when it is within `wall` cells of observed free space (a
//!   laser sees the faces of walls from where the robot was); outside the building is unknown;
//! * walls have gaps (glass, dark surfaces), runs of unknown across their whole thickness;
//! * furniture blobs in rooms and halls, their outline partly occupied, their inside unknown;
//! * finally, in the map frame, ragged wall faces (free cells beside occupied ones read occupied
//!   now and then) and speckle: free cells flipping to occupied or unknown.
//!
//! The map is sampled from the world frame per map cell: each map cell centre is taken into
//! the world frame with the inverse of [`Frame::to_map`](crate::floorplan::Frame::to_map) and
//! the world cell under it is read (nearest neighbour), so rotated walls stay solid.

use super::config::Cells;
use super::layout::{Opening, Plan, Space};
use crate::floorplan::{Rect, UnitType};
use crate::grid::morphology::dilate;
use crate::grid::{Cell, Grid};
use crate::mcmc::Rng;

/// The noise settings, all probabilities or fractions.
#[derive(Debug, Clone, Copy)]
pub(super) struct Noise {
    pub speckle_occupied: f64,
    pub speckle_unknown: f64,
    pub wall_roughness: f64,
    /// Chance per wall cell that a gap starts there (gaps per [`GAP_STEP_M`] of wall, scaled
    /// to the cell).
    pub wall_gaps: f64,
    pub clutter: f64,
    pub peek: f64,
    /// Chance per wall cell that a glass pane starts there (panes per metre times metres per
    /// cell).
    pub glass: f64,
    /// Metres per cell, for the panes' and rays' lengths.
    pub resolution: f64,
}

impl Noise {
    /// `m` metres in whole cells of this map, at least one.
    fn cells(&self, m: f64) -> i32 {
        (libm::round(m / self.resolution) as i32).max(1)
    }
}

/// The length of wall per draw of [`SynthConfig::wall_gaps`](super::SynthConfig): the
/// generator's gap rate was set as a chance per cell at 5 cm, so it is a chance per 5 cm of
/// wall at every resolution, and a building has as many gaps per metre at 2.5 or 10 cm.
pub(super) const GAP_STEP_M: f64 = 0.05;

/// A wall gap's length, shortest and longest: a strip of dark paint or a narrow window, 0.1 to
/// 0.4 m, whatever the cell.
const GAP_LEN_M: (f64, f64) = (0.1, 0.4);

/// The width of wall a ray through a glass pane frees ([`glaze`]): a laser's beams are spaced
/// about 5 cm apart at a few metres, so one draw decides a 5 cm column of the pane, however
/// many cells that is. At cells coarser than that, a cell reads free only where every one of
/// its columns' rays passed: a beam that ends in a cell marks it occupied, and a mapper weighs
/// a hit above a pass.
const PANE_COLUMN_M: f64 = 0.05;

/// A world-frame observation.
pub(super) struct Observed {
    /// What the map shows, world frame.
    pub cells: Grid<Cell>,
    /// Unit index + 1 on unit interiors, 0 elsewhere, world frame.
    pub labels: Grid<u16>,
    /// Furniture cells, world frame, row by row.
    pub objects: Vec<[i32; 2]>,
}

const OUTSIDE: u8 = 0;
const WALL: u8 = 1;
const INTERIOR: u8 = 2;
const OPENING: u8 = 3;

fn fill<T: Copy>(g: &mut Grid<T>, r: Rect, v: T) {
    for y in r.y..r.bottom() {
        for x in r.x..r.right() {
            *g.at_mut(x as usize, y as usize) = v;
        }
    }
}

/// Rasterises the plan in the world frame and degrades it as a scan would.
pub(super) fn observe(plan: &Plan, explored: &[bool], c: &Cells, noise: &Noise, rng: &mut Rng) -> Observed {
    let (w, h) = (c.canvas.0 as usize, c.canvas.1 as usize);
    let t = c.wall;
    let (kind, labels) = rasterise(plan, w, h, t);
    let mut cells = seen_free(plan, explored, noise, (w, h), t, rng);
    mark_seen_walls(&mut cells, &kind, t);
    if noise.wall_gaps > 0.0 {
        cut_wall_gaps(&mut cells, &kind, plan, noise, t, rng);
    }
    if noise.glass > 0.0 {
        glaze(&mut cells, &kind, &labels, plan, explored, noise, t, rng);
    }

    // Furniture in explored rooms and halls.
    let mut object = Grid::new(w, h, false);
    if noise.clutter > 0.0 {
        for (u, s) in plan.spaces.iter().enumerate() {
            if explored[u] && matches!(s.kind, UnitType::Room | UnitType::Hall) {
                let keep_out: Vec<Rect> =
                    plan.openings.iter().filter(|o| o.a == u || o.b == u).map(|o| door_zone(o, u, t)).collect();
                furnish(&mut cells, &mut object, s.inner, &keep_out, noise.clutter, c.resolution, rng);
            }
        }
    }
    let mut objects = Vec::new();
    for y in 0..h {
        for x in 0..w {
            if *object.at(x, y) {
                objects.push([x as i32, y as i32]);
            }
        }
    }
    Observed { cells, labels, objects }
}

/// The truth, `w` x `h` cells: what each cell is (outside, wall, interior, opening) and the
/// space it belongs to (index + 1 on interiors, 0 elsewhere).
fn rasterise(plan: &Plan, w: usize, h: usize, t: i32) -> (Grid<u8>, Grid<u16>) {
    let mut kind = Grid::new(w, h, OUTSIDE);
    let mut labels = Grid::new(w, h, 0u16);
    fill(&mut kind, plan.building, WALL);
    for (i, s) in plan.spaces.iter().enumerate() {
        fill(&mut kind, s.inner, INTERIOR);
        fill(&mut labels, s.inner, i as u16 + 1);
    }
    for o in &plan.openings {
        fill(&mut kind, o.rect(t), OPENING);
    }
    (kind, labels)
}

/// Free space the robot saw, everything else unknown: explored interiors, openings next to
/// them, and peeks through doors into unexplored spaces (each with chance `noise.peek`).
fn seen_free(
    plan: &Plan,
    explored: &[bool],
    noise: &Noise,
    (w, h): (usize, usize),
    t: i32,
    rng: &mut Rng,
) -> Grid<Cell> {
    let mut cells = Grid::new(w, h, Cell::Unknown);
    for (s, _) in plan.spaces.iter().zip(explored).filter(|(_, &e)| e) {
        fill(&mut cells, s.inner, Cell::Free);
    }
    for o in &plan.openings {
        if explored[o.a] || explored[o.b] {
            fill(&mut cells, o.rect(t), Cell::Free);
        }
    }
    for (u, s) in plan.spaces.iter().enumerate() {
        if explored[u] {
            continue;
        }
        for o in plan.openings.iter().filter(|o| o.a == u || o.b == u) {
            let v = o.other(u);
            if explored[v] && rng.chance(noise.peek) {
                peek(&mut cells, o, s, &plan.spaces[v], v == o.a, t);
            }
        }
    }
    cells
}

/// Walls read occupied where they are within `t` cells of seen free space: a laser sees the
/// faces of walls from where the robot was.
fn mark_seen_walls(cells: &mut Grid<Cell>, kind: &Grid<u8>, t: i32) {
    let free = cells.map(|c| *c == Cell::Free);
    let seen = dilate(&free, t as usize);
    for ((cell, k), s) in cells.cells_mut().iter_mut().zip(kind.cells()).zip(seen.cells()) {
        if *k == WALL && *s {
            *cell = Cell::Occupied;
        }
    }
}

/// The four sides of a unit's interior `r` as (first wall cell, step along, step across
/// outwards, length).
type Side = ((i32, i32), (i32, i32), (i32, i32), i32);

fn sides(r: Rect) -> [Side; 4] {
    [
        ((r.x, r.y - 1), (1, 0), (0, -1), r.w),
        ((r.x, r.bottom()), (1, 0), (0, 1), r.w),
        ((r.x - 1, r.y), (0, 1), (-1, 0), r.h),
        ((r.right(), r.y), (0, 1), (1, 0), r.h),
    ]
}

/// Glass panes in the walls of explored units ([`SynthConfig::glass`](super::SynthConfig)):
/// a pane is 1 to 3 m of wall; across it, each wall column ([`PANE_COLUMN_M`]) a ray
/// crossed (one in two: glass reflects the rays that meet it head-on and lets the slanting
/// ones through) reads free. Where the pane is in the outer wall, each such ray runs on from
/// the unit's centre through the column into the outside for 1 to 4 m, reading free, and half
/// of them end on an occupied cell. A pane whose far side is an unexplored unit stays as it was: the robot never
/// looked through it from there, and its rays would reveal a room the truth calls unseen.
#[allow(clippy::too_many_arguments)]
fn glaze(
    cells: &mut Grid<Cell>,
    kind: &Grid<u8>,
    labels: &Grid<u16>,
    plan: &Plan,
    explored: &[bool],
    noise: &Noise,
    t: i32,
    rng: &mut Rng,
) {
    let (pane, reach) = ((noise.cells(1.0), noise.cells(3.0)), (noise.cells(1.0), noise.cells(4.0)));
    // Cells per column of the pane (fine cells), or the chance a coarse cell is crossed by
    // every one of its columns' rays, each crossing with chance one half.
    let per_column = noise.cells(PANE_COLUMN_M);
    let crossed = libm::pow(0.5, (noise.resolution / PANE_COLUMN_M).max(1.0));
    for (s, _) in plan.spaces.iter().zip(explored).filter(|(_, &e)| e) {
        let r = s.inner;
        let centre = (r.x as f64 + r.w as f64 / 2.0, r.y as f64 + r.h as f64 / 2.0);
        for ((x0, y0), (dx, dy), (ox, oy), len) in sides(r) {
            let mut i = 0;
            while i < len {
                if !rng.chance(noise.glass) {
                    i += 1;
                    continue;
                }
                let n = rng.between(pane.0, pane.1);
                let mut column: Option<(i32, bool)> = None;
                for j in i..(i + n).min(len) {
                    let (x, y) = (x0 + dx * j, y0 + dy * j);
                    let beyond = (x + ox * t, y + oy * t);
                    let outer = match kind.get(beyond.0 as i64, beyond.1 as i64) {
                        None | Some(&OUTSIDE) => true,
                        Some(&INTERIOR) => {
                            let l = *labels.at(beyond.0 as usize, beyond.1 as usize);
                            if !explored[l as usize - 1] {
                                continue;
                            }
                            false
                        }
                        Some(_) => continue,
                    };
                    // Drawn where a cell of the column is first reached, so a pane at 5 cm
                    // draws once per cell as it always did.
                    let c = (j - i) / per_column;
                    let crossed_here = match column {
                        Some((at, was)) if at == c => was,
                        _ => {
                            let was = rng.chance(crossed);
                            column = Some((c, was));
                            was
                        }
                    };
                    if !crossed_here {
                        continue;
                    }
                    for k in 0..t {
                        let (wx, wy) = (x + ox * k, y + oy * k);
                        if kind.get(wx as i64, wy as i64) == Some(&WALL) {
                            *cells.at_mut(wx as usize, wy as usize) = Cell::Free;
                        }
                    }
                    if outer {
                        let length = rng.between(reach.0, reach.1) as f64;
                        let ends_on_something = rng.chance(0.5);
                        ray_outside(cells, kind, centre, beyond, length, ends_on_something);
                    }
                }
                i += n;
            }
        }
    }
}

/// A ray from `centre` through cell `from` (just outside the wall), marking the outside
/// cells it crosses free for `length` cells past `from`; the last one occupied when
/// `ends_on_something`. It stops at the canvas edge or at anything that is not outside.
fn ray_outside(
    cells: &mut Grid<Cell>,
    kind: &Grid<u8>,
    centre: (f64, f64),
    from: (i32, i32),
    length: f64,
    ends_on_something: bool,
) {
    let (fx, fy) = (from.0 as f64 + 0.5, from.1 as f64 + 0.5);
    let (vx, vy) = (fx - centre.0, fy - centre.1);
    let norm = libm::sqrt(vx * vx + vy * vy).max(1e-9);
    let (ux, uy) = (vx / norm, vy / norm);
    let mut last = None;
    let mut d = 0.0;
    while d <= length {
        let (x, y) = (libm::floor(fx + ux * d) as i64, libm::floor(fy + uy * d) as i64);
        if kind.get(x, y) != Some(&OUTSIDE) {
            break;
        }
        *cells.at_mut(x as usize, y as usize) = Cell::Free;
        last = Some((x as usize, y as usize));
        d += 0.5;
    }
    if let (Some((x, y)), true) = (last, ends_on_something) {
        *cells.at_mut(x, y) = Cell::Occupied;
    }
}

/// Gaps (glass, dark surfaces): runs of [`GAP_LEN_M`] along each unit side, starting at each
/// cell with chance `noise.wall_gaps`, read unknown across the whole wall.
fn cut_wall_gaps(cells: &mut Grid<Cell>, kind: &Grid<u8>, plan: &Plan, noise: &Noise, t: i32, rng: &mut Rng) {
    let (rate, gap) = (noise.wall_gaps, (noise.cells(GAP_LEN_M.0), noise.cells(GAP_LEN_M.1)));
    for s in &plan.spaces {
        for ((x0, y0), (dx, dy), (ox, oy), len) in sides(s.inner) {
            let mut i = 0;
            while i < len {
                if !rng.chance(rate) {
                    i += 1;
                    continue;
                }
                let g = rng.between(gap.0, gap.1);
                for j in i..(i + g).min(len) {
                    for k in 0..t {
                        let (x, y) = (x0 + dx * j + ox * k, y0 + dy * j + oy * k);
                        if kind.get(x as i64, y as i64) == Some(&WALL) {
                            *cells.at_mut(x as usize, y as usize) = Cell::Unknown;
                        }
                    }
                }
                i += g;
            }
        }
    }
}

/// Marks free the cells of unexplored space `s` visible from inside `v` (the opening's `a` side
/// when `v_is_a`) through opening `o`.
fn peek(cells: &mut Grid<Cell>, o: &Opening, s: &Space, v: &Space, v_is_a: bool, t: i32) {
    // Work in (along, across) coordinates of the wall.
    let flip = |r: Rect| {
        if o.vertical {
            (r.y, r.bottom(), r.x, r.right())
        } else {
            (r.x, r.right(), r.y, r.bottom())
        }
    };
    let (_, _, v0, v1) = flip(v.inner);
    let (s_al0, s_al1, s_ac0, s_ac1) = flip(s.inner);
    let (faces, len) = ([o.wall as f64, (o.wall + t) as f64], o.len as f64);
    // The robot stood about a door's width back from the opening, on `v`'s side.
    let depth = (o.len as f64).min((v1 - v0) as f64 - 1.0).max(0.5);
    let view_across = if v_is_a { o.wall as f64 - depth } else { (o.wall + t) as f64 + depth };
    let view_along = o.along as f64 + len / 2.0;
    let (lo, hi) = (o.along as f64, o.along as f64 + len);
    for ac in s_ac0..s_ac1 {
        let pc = ac as f64 + 0.5;
        for al in s_al0..s_al1 {
            let pa = al as f64 + 0.5;
            let through = faces.iter().all(|&f| {
                let at = view_along + (pa - view_along) * (f - view_across) / (pc - view_across);
                at >= lo && at <= hi
            });
            if through {
                let (x, y) = if o.vertical { (ac, al) } else { (al, ac) };
                *cells.at_mut(x as usize, y as usize) = Cell::Free;
            }
        }
    }
}

/// The area in front of a door on space `u`'s side, kept clear of furniture.
fn door_zone(o: &Opening, u: usize, t: i32) -> Rect {
    let depth = o.len;
    let across = if u == o.a { o.wall - depth } else { o.wall + t };
    if o.vertical {
        Rect::new(across, o.along - 2, depth, o.len + 4)
    } else {
        Rect::new(o.along - 2, across, o.len + 4, depth)
    }
}

/// Places furniture blobs in `room` until `fraction` of it is covered (or space runs out).
fn furnish(
    cells: &mut Grid<Cell>,
    object: &mut Grid<bool>,
    room: Rect,
    keep_out: &[Rect],
    fraction: f64,
    resolution: f64,
    rng: &mut Rng,
) {
    let target = libm::round(fraction * room.area() as f64) as i64;
    let size = |m: f64| (libm::round(m / resolution) as i32).max(2);
    let (smin, smax) = (size(0.3), size(1.6));
    let mut placed: Vec<Rect> = Vec::new();
    let mut covered = 0i64;
    let mut attempts = 0;
    while covered < target && attempts < 400 {
        attempts += 1;
        let mut bw = rng.between(smin, smax).min(room.w - 2);
        let mut bh = rng.between(smin, smax).min(room.h - 2);
        // Near the target, smaller pieces: overshoot by a quarter at most.
        let budget = ((target - covered) * 5 / 4).max((smin * smin) as i64) as i32;
        if bw * bh > budget {
            bh = (budget / bw).max(smin).min(bh);
            bw = (budget / bh).max(smin).min(bw);
        }
        if bw < 2 || bh < 2 {
            return;
        }
        // Most furniture stands against a wall.
        let (x, y) = if rng.chance(0.6) {
            match rng.index(4) {
                0 => (rng.between(room.x, room.right() - bw), room.y),
                1 => (rng.between(room.x, room.right() - bw), room.bottom() - bh),
                2 => (room.x, rng.between(room.y, room.bottom() - bh)),
                _ => (room.right() - bw, rng.between(room.y, room.bottom() - bh)),
            }
        } else {
            (rng.between(room.x + 1, room.right() - bw - 1), rng.between(room.y + 1, room.bottom() - bh - 1))
        };
        let r = Rect::new(x, y, bw, bh);
        let grown = Rect::new(x - 3, y - 3, bw + 6, bh + 6);
        if keep_out.iter().any(|k| k.intersection(&r).is_some())
            || placed.iter().any(|p| p.intersection(&grown).is_some())
        {
            continue;
        }
        placed.push(r);
        let round = rng.chance(0.4);
        let (cx, cy, rx, ry) =
            (x as f64 + bw as f64 / 2.0, y as f64 + bh as f64 / 2.0, bw as f64 / 2.0, bh as f64 / 2.0);
        let inside = |px: i32, py: i32| {
            if !r.contains(px, py) {
                return false;
            }
            if !round {
                return true;
            }
            let (dx, dy) = ((px as f64 + 0.5 - cx) / rx, (py as f64 + 0.5 - cy) / ry);
            dx * dx + dy * dy <= 1.0
        };
        for py in r.y..r.bottom() {
            for px in r.x..r.right() {
                if !inside(px, py) {
                    continue;
                }
                let edge = !(inside(px - 1, py) && inside(px + 1, py) && inside(px, py - 1) && inside(px, py + 1));
                // The laser sees part of the outline; the inside stays unknown.
                let seen = edge && rng.uniform() < 0.7;
                *cells.at_mut(px as usize, py as usize) = if seen { Cell::Occupied } else { Cell::Unknown };
                *object.at_mut(px as usize, py as usize) = true;
                covered += 1;
            }
        }
    }
}

/// Samples the world-frame observation into the map frame and adds speckle.
pub(super) fn to_map(obs: &Observed, c: &Cells, noise: &Noise, rng: &mut Rng) -> (Grid<Cell>, Grid<u16>) {
    let (ww, wh) = (c.canvas.0 as usize, c.canvas.1 as usize);
    let (mw, mh) = (c.map_size.0 as usize, c.map_size.1 as usize);
    let (s, co) = (libm::sin(c.angle), libm::cos(c.angle));
    let mut cells = Vec::with_capacity(mw * mh);
    let mut labels = Vec::with_capacity(mw * mh);
    for my in 0..mh {
        for mx in 0..mw {
            // Frame::to_world of the cell centre, written out to keep sin and cos out of the loop.
            let (dx, dy) = (mx as f64 + 0.5 - mw as f64 / 2.0, my as f64 + 0.5 - mh as f64 / 2.0);
            let wx = libm::floor(ww as f64 / 2.0 + co * dx + s * dy);
            let wy = libm::floor(wh as f64 / 2.0 - s * dx + co * dy);
            if wx >= 0.0 && wy >= 0.0 && wx < ww as f64 && wy < wh as f64 {
                let (x, y) = (wx as usize, wy as usize);
                cells.push(*obs.cells.at(x, y));
                labels.push(*obs.labels.at(x, y));
            } else {
                cells.push(Cell::Unknown);
                labels.push(0);
            }
        }
    }
    degrade(&mut cells, mw, mh, noise, rng);
    (Grid::from_vec(mw, mh, cells).expect("map size"), Grid::from_vec(mw, mh, labels).expect("map size"))
}

/// What a scan does to the map's cells (`mw` x `mh`, row by row): ragged wall faces and
/// speckle on free cells.
pub(super) fn degrade(cells: &mut [Cell], mw: usize, mh: usize, noise: &Noise, rng: &mut Rng) {
    if noise.wall_roughness > 0.0 {
        let sharp = cells.to_vec();
        let occupied = |x: usize, y: usize| sharp[y * mw + x] == Cell::Occupied;
        for y in 0..mh {
            for x in 0..mw {
                if sharp[y * mw + x] != Cell::Free {
                    continue;
                }
                let beside = (x > 0 && occupied(x - 1, y))
                    || (x + 1 < mw && occupied(x + 1, y))
                    || (y > 0 && occupied(x, y - 1))
                    || (y + 1 < mh && occupied(x, y + 1));
                if beside && rng.chance(noise.wall_roughness) {
                    cells[y * mw + x] = Cell::Occupied;
                }
            }
        }
    }
    let (po, pu) = (noise.speckle_occupied, noise.speckle_unknown);
    if po + pu > 0.0 {
        for cell in cells.iter_mut().filter(|c| **c == Cell::Free) {
            let d = rng.uniform();
            if d < po {
                *cell = Cell::Occupied;
            } else if d < po + pu {
                *cell = Cell::Unknown;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn door_zone_lies_in_front_of_the_door() {
        let o = Opening { a: 0, b: 1, vertical: false, wall: 20, along: 30, len: 16 };
        // Above the wall for a, below it (past the 3-cell wall) for b.
        assert_eq!(door_zone(&o, 0, 3), Rect::new(28, 4, 20, 16));
        assert_eq!(door_zone(&o, 1, 3), Rect::new(28, 23, 20, 16));
    }
}
