//! The frontier of a map in stretches, and what lies behind each.
//!
//! Unseen space is unknown space at least [`MIN_UNSEEN_M`] across (a morphological opening
//! takes away the streaks rays leave between them at long range) in regions of at least
//! [`MIN_BEHIND_M2`] (the pinholes between rays and the shadows of furniture go too). A frontier
//! cell is a free cell with an unknown cell beside it (left, right, above or below), near
//! unseen space (within the opening's radius and a cell). Frontier cells that touch, diagonals included, are one frontier; a frontier longer
//! than [`MAX_STRETCH_M`] is cut along its longer side into equal stretches, since one so long
//! may open onto more than one space. A stretch narrower than [`MIN_WIDTH_M`] is noise, and one
//! with less than [`MIN_BEHIND_M2`] of unseen floor behind it within reach is not a way on:
//! neither is a placeholder.
//!
//! What lies behind a stretch is read by a wavefront through unknown cells from the unknown
//! cells beside it, up to [`BEHIND_M`] away: its area, whether it ends before that distance
//! (seen walls close it in: a pocket), and how much of it lies within the bounding box of the
//! map's occupied cells (the building as far as it was seen). Every length is in metres,
//! turned into cells with the map's resolution.

use crate::floorplan::world::{Door, World};
use crate::grid::flood::{neighbours4, wavefront_listed, Flood, Neighbours};
use crate::grid::morphology::{dilate, erode};
use crate::grid::{Cell, Grid};

/// Narrowest frontier that is a placeholder, m: 0.5 m, about the narrowest gap a person or a
/// service robot's base passes through; narrower stretches are single cells of scan noise.
pub const MIN_WIDTH_M: f64 = 0.5;
/// Longest stretch, m: 4 m, about the side of an office; a longer frontier is cut into equal
/// stretches, as it may open onto more than one space.
pub const MAX_STRETCH_M: f64 = 4.0;
/// How far behind a stretch the unseen space is measured, m: 5 m, the depth of a large office
/// (a room deeper than that is open floor to a robot standing at its door).
pub const BEHIND_M: f64 = 5.0;
/// Least unseen floor behind a placeholder, m²: 2 m², about the smallest room a person walks
/// into (a 1.4 m x 1.4 m washroom); less is the shadow of a desk or a cabinet.
pub const MIN_BEHIND_M2: f64 = 2.0;
/// Narrowest unseen space, m: 0.2 m. Rays fanning out from a scanner leave streaks of unknown
/// cells between them at long range, a cell or two wide; the narrowest way a person passes
/// (0.5 m) is far wider.
pub const MIN_UNSEEN_M: f64 = 0.2;
/// A door of the plan this close to a stretch stands in it, m: 1 m, a door leaf's width.
pub const AT_DOOR_M: f64 = 1.0;

/// A stretch of frontier, in the map's frame.
#[derive(Debug, Clone, PartialEq)]
pub struct Stretch {
    /// Its free cells, as map indices (`y * width + x`), in increasing order.
    pub cells: Vec<usize>,
    /// The cell of the stretch nearest to its centroid, `(column, row)`.
    pub at: (usize, usize),
    /// Width, m: the diagonal of its cells' bounding box.
    pub width_m: f64,
    /// Unseen floor behind it within [`BEHIND_M`], m².
    pub behind_m2: f64,
    /// Whether the unseen space behind it ends before [`BEHIND_M`].
    pub pocket: bool,
    /// Share of the unseen space behind it within the bounding box of the map's occupied cells.
    pub inside: f64,
    /// The room it opens from: the room label most of its cells carry (0: none).
    pub room: u32,
    /// Whether a door of the plan lies within [`AT_DOOR_M`] of it.
    pub at_door: bool,
    /// Whether both its ends, along the longer side of its bounding box, touch occupied cells
    /// (within [`JAMB_M`]): it spans a gap between walls, as a doorway does.
    pub jambs: bool,
    /// Share of the unseen space behind it inside the plan's units (their interiors, within
    /// their wall rings): the plan has explained it as part of a space it holds.
    pub planned: f64,
    /// Share of the unseen space behind it inside the interiors of the units of the room it
    /// opens from: that room's own unseen part (a cell under units of two rooms counts).
    pub own: f64,
    /// How many placeholders of the map open from the same room, this one included (0 when
    /// it opens from no room): a room seen whole has none, one the robot has only glimpsed
    /// has a frontier on every side it has not seen past.
    pub ways: usize,
}

/// An end of a stretch this close to an occupied cell stands at a wall, m: 0.15 m, a wall's
/// half thickness with the scan's blur.
pub const JAMB_M: f64 = 0.15;

/// The stretches of `map`'s frontier (module docs) that are placeholders, ordered by `at`,
/// row by row. `labels` numbers the free cells with their rooms, `world` gives the doors.
pub fn stretches(world: &World, map: &Grid<Cell>, labels: &Grid<u16>, resolution: f64) -> Vec<Stretch> {
    let (w, h) = (map.width(), map.height());
    let cells = map.cells();
    // Beside an unknown cell, and near unseen space (the streaks between rays may lie between).
    let unseen = unseen_space(map, resolution);
    let near = dilate(&Grid::from_vec(w, h, unseen).expect("map size"), unseen_radius(resolution) + 1);
    let near = near.cells();
    let unknown = |j: usize| cells[j] == Cell::Unknown;
    let frontier: Vec<bool> =
        (0..w * h).map(|i| cells[i] == Cell::Free && near[i] && neighbours4(i, w, h).any(unknown)).collect();
    let cover = unit_rooms(world, w, h);
    let around = Around { map, labels, resolution, building: occupied_box(map), doors: door_centres(world), cover };
    let mut out = Vec::new();
    let mut waves = Waves::new(w, h);
    let mut taken = vec![false; w * h];
    let mut flood = Flood::default();
    for start in 0..w * h {
        if !frontier[start] || taken[start] {
            continue;
        }
        let mut component = Vec::new();
        let mut enter = |j: usize| frontier[j] && !std::mem::replace(&mut taken[j], true);
        flood.fill(w, h, [start], Neighbours::Eight, &mut enter, |i| component.push(i));
        for piece in cut(component, w, resolution) {
            // Too narrow to be a way on: no need to look behind it.
            let bbox = bounds(&piece, w);
            let width_m = diagonal_m(bbox, resolution);
            if width_m < MIN_WIDTH_M {
                continue;
            }
            let s = describe(piece, bbox, width_m, &around, &mut waves);
            if s.behind_m2 >= MIN_BEHIND_M2 {
                out.push(s);
            }
        }
    }
    out.sort_by_key(|s| (s.at.1, s.at.0));
    let mut ways = std::collections::BTreeMap::<u32, usize>::new();
    for s in out.iter().filter(|s| s.room > 0) {
        *ways.entry(s.room).or_default() += 1;
    }
    for s in &mut out {
        s.ways = ways.get(&s.room).copied().unwrap_or(0);
    }
    out
}

/// Per map cell, whether it is unseen space: an unknown cell of a region of unknown cells at
/// least [`MIN_UNSEEN_M`] across everywhere (a morphological opening: the streaks rays leave
/// between them at long range go), in a 4-connected region of such cells of at least
/// [`MIN_BEHIND_M2`] (the pinholes between rays and the shadows of furniture go).
fn unseen_space(map: &Grid<Cell>, resolution: f64) -> Vec<bool> {
    let (w, h) = (map.width(), map.height());
    let least = libm::ceil(MIN_BEHIND_M2 / (resolution * resolution)) as usize;
    let r = unseen_radius(resolution);
    let unknown = Grid::from_vec(w, h, map.cells().iter().map(|&c| c == Cell::Unknown).collect()).expect("map size");
    let opened = dilate(&erode(&unknown, r), r);
    let opened = opened.cells();
    let mut unseen = vec![false; w * h];
    let mut taken = vec![false; w * h];
    let mut flood = Flood::default();
    let mut region = Vec::new();
    for start in 0..w * h {
        if taken[start] || !opened[start] {
            continue;
        }
        region.clear();
        let mut enter = |j: usize| opened[j] && !std::mem::replace(&mut taken[j], true);
        flood.fill(w, h, [start], Neighbours::Four, &mut enter, |i| region.push(i));
        if region.len() >= least {
            region.iter().for_each(|&i| unseen[i] = true);
        }
    }
    unseen
}

/// `[x0, y0, x1, y1]` (inclusive) of the map's occupied cells; `None` if it has none.
fn occupied_box(map: &Grid<Cell>) -> Option<[usize; 4]> {
    let w = map.width();
    let mut b: Option<[usize; 4]> = None;
    for (i, _) in map.cells().iter().enumerate().filter(|(_, &c)| c == Cell::Occupied) {
        let (x, y) = (i % w, i / w);
        b = Some(match b {
            None => [x, y, x, y],
            Some([x0, y0, x1, y1]) => [x0.min(x), y0.min(y), x1.max(x), y1.max(y)],
        });
    }
    b
}

/// The centre of each door that is not an opening within a room, in map coordinates.
fn door_centres(world: &World) -> Vec<(f64, f64)> {
    world.doors.iter().filter(|d| !d.opening).map(|d| door_centre(world, d)).collect()
}

/// The centre of `world`'s door `d` in map coordinates: its rectangle's centre
/// ([`crate::geometry::Rect::center`]) taken from the door's frame to the map.
pub(crate) fn door_centre(world: &World, d: &Door) -> (f64, f64) {
    let (cx, cy) = d.rect().center();
    world.door_frame(d).to_map(cx, cy)
}

/// `component` (map indices) cut along the longer side of its bounding box into equal pieces
/// no longer than [`MAX_STRETCH_M`], each sorted.
fn cut(mut component: Vec<usize>, w: usize, resolution: f64) -> Vec<Vec<usize>> {
    component.sort_unstable();
    let [x0, y0, x1, y1] = bounds(&component, w);
    let along_x = x1 - x0 >= y1 - y0;
    let (lo, len) = if along_x { (x0, x1 - x0 + 1) } else { (y0, y1 - y0 + 1) };
    let pieces = (libm::ceil(len as f64 * resolution / MAX_STRETCH_M) as usize).max(1);
    let mut out = vec![Vec::new(); pieces];
    for i in component {
        let v = if along_x { i % w } else { i / w };
        out[((v - lo) * pieces / len).min(pieces - 1)].push(i);
    }
    out.retain(|p| !p.is_empty());
    out
}

/// `[x0, y0, x1, y1]` (inclusive) of non-empty `cells` (map indices of a grid `w` wide).
fn bounds(cells: &[usize], w: usize) -> [usize; 4] {
    cells.iter().fold([usize::MAX, usize::MAX, 0, 0], |[x0, y0, x1, y1], &i| {
        [x0.min(i % w), y0.min(i / w), x1.max(i % w), y1.max(i / w)]
    })
}

/// The stretch of `cells` (module docs).
/// What a stretch is described against: the map, the room labels, the
/// resolution, the building's seen extent and the plan's doors (map coordinates).
struct Around<'a> {
    map: &'a Grid<Cell>,
    labels: &'a Grid<u16>,
    resolution: f64,
    building: Option<[usize; 4]>,
    doors: Vec<(f64, f64)>,
    /// Per map cell, the room whose units' interiors cover it ([`unit_rooms`]).
    cover: Vec<u32>,
}

/// A stretch's width: the diagonal of its cells' bounding box `[x0, y0, x1, y1]` (inclusive,
/// [`bounds`]), m.
fn diagonal_m([x0, y0, x1, y1]: [usize; 4], resolution: f64) -> f64 {
    libm::hypot((x1 - x0 + 1) as f64, (y1 - y0 + 1) as f64) * resolution
}

/// The stretch of `cells`, whose bounding box ([`bounds`]) and width ([`diagonal_m`]) the
/// caller has worked out already.
fn describe(cells: Vec<usize>, [x0, y0, x1, y1]: [usize; 4], width_m: f64, a: &Around, waves: &mut Waves) -> Stretch {
    let (map, resolution) = (a.map, a.resolution);
    let w = map.width();
    let n = cells.len() as f64;
    let (mx, my) = cells.iter().fold((0.0, 0.0), |(sx, sy), &i| (sx + (i % w) as f64 / n, sy + (i / w) as f64 / n));
    let d2 = |i: &usize| ((i % w) as f64 - mx).powi(2) + ((i / w) as f64 - my).powi(2);
    let centre = *cells.iter().min_by(|a, b| d2(a).total_cmp(&d2(b))).expect("a stretch has cells");
    let reach = AT_DOOR_M / resolution;
    let at_door = a.doors.iter().any(|&(dx, dy)| {
        cells.iter().any(|&i| libm::hypot((i % w) as f64 + 0.5 - dx, (i / w) as f64 + 0.5 - dy) <= reach)
    });
    let room = room_of(&cells, a.labels);
    let Behind { area_m2: behind_m2, pocket, inside, planned, own } = behind(&cells, a, waves, room);
    let jambs = jambs(&cells, map, [x0, y0, x1, y1], resolution);
    Stretch {
        ways: 0,
        jambs,
        planned,
        own,
        room,
        at: (centre % w, centre / w),
        width_m,
        behind_m2,
        pocket,
        inside,
        at_door,
        cells,
    }
}

/// Whether both ends of `cells` (the cells at either end of the longer side of their bounding
/// box `[x0, y0, x1, y1]`) have an occupied cell within [`JAMB_M`].
fn jambs(cells: &[usize], map: &Grid<Cell>, [x0, y0, x1, y1]: [usize; 4], resolution: f64) -> bool {
    let w = map.width();
    let along_x = x1 - x0 >= y1 - y0;
    let key = |i: usize| if along_x { i % w } else { i / w };
    let (lo, hi) = if along_x { (x0, x1) } else { (y0, y1) };
    let r = libm::ceil(JAMB_M / resolution).max(1.0) as usize;
    let walled = |i: usize| {
        let (x, y) = (i % w, i / w);
        (y.saturating_sub(r)..=(y + r).min(map.height() - 1))
            .any(|yy| (x.saturating_sub(r)..=(x + r).min(w - 1)).any(|xx| *map.at(xx, yy) == Cell::Occupied))
    };
    let end = |v: usize| cells.iter().any(|&i| key(i) == v && walled(i));
    end(lo) && end(hi)
}

/// [`unit_rooms`]: no unit's interior covers the cell.
const NO_UNIT: u32 = 0;
/// [`unit_rooms`]: units of two rooms cover the cell.
const SHARED: u32 = u32::MAX;
/// [`unit_rooms`]: a unit no room holds covers the cell.
const ROOMLESS: u32 = u32::MAX - 1;

/// Per cell of the `w` x `h` map, the id of the room whose units' interiors (within their
/// wall rings, [`World::wall_thickness`]) cover it: [`NO_UNIT`] if none, [`SHARED`] if units
/// of two rooms do, [`ROOMLESS`] if a unit no room holds does. Each unit is visited once, over
/// its box on the map, so the cost is the units' area, not the cells times the units.
fn unit_rooms(world: &World, w: usize, h: usize) -> Vec<u32> {
    let mut out = vec![NO_UNIT; w * h];
    let rooms = world.rooms_of_units();
    let room_of = |id: u32| rooms.get(&id).copied().unwrap_or(ROOMLESS);
    for u in &world.units {
        let Some(r) = u.rect().interior(world.wall_thickness) else { continue };
        let room = room_of(u.id);
        for (x, y) in world.unit_frame(u).map_cells(r, w, h) {
            let c = &mut out[y * w + x];
            *c = if *c == NO_UNIT || *c == room { room } else { SHARED };
        }
    }
    out
}

/// The radius, in cells, of the square that opens unknown space into unseen space: half of
/// [`MIN_UNSEEN_M`], at least a cell.
fn unseen_radius(resolution: f64) -> usize {
    (libm::round(MIN_UNSEEN_M / resolution / 2.0) as usize).max(1)
}

/// The room label most of `cells` carry (ties to the smaller id), 0 if none carries one.
fn room_of(cells: &[usize], labels: &Grid<u16>) -> u32 {
    let mut counts = std::collections::BTreeMap::<u16, usize>::new();
    for &i in cells {
        let l = labels.cells()[i];
        if l > 0 {
            *counts.entry(l).or_default() += 1;
        }
    }
    counts.into_iter().max_by(|a, b| a.1.cmp(&b.1).then(b.0.cmp(&a.0))).map_or(0, |(l, _)| u32::from(l))
}

/// What lies behind a stretch ([`behind`]).
struct Behind {
    area_m2: f64,
    pocket: bool,
    inside: f64,
    planned: f64,
    own: f64,
}

/// The unseen space behind `cells`: its area within [`BEHIND_M`] (m²), whether it ends before
/// that distance, and the shares of it inside the building's seen extent, under the plan's
/// units and inside the units of room `room`.
fn behind(cells: &[usize], a: &Around, waves: &mut Waves, room: u32) -> Behind {
    let (map, resolution) = (a.map, a.resolution);
    let (w, h) = (map.width(), map.height());
    let limit = libm::ceil(BEHIND_M / resolution) as u32;
    let reached = waves.behind(cells, limit, |j| map.cells()[j] == Cell::Unknown);
    let (mut area, mut within, mut planned, mut own, mut open) = (0usize, 0usize, 0usize, 0usize, false);
    for (j, d) in reached {
        if d > limit {
            open = true;
            continue;
        }
        area += 1;
        let (x, y) = (j % w, j / w);
        // Unseen space on the map's edge goes on beyond it.
        open |= x == 0 || y == 0 || x == w - 1 || y == h - 1;
        if a.building.is_some_and(|[bx0, by0, bx1, by1]| (bx0..=bx1).contains(&x) && (by0..=by1).contains(&y)) {
            within += 1;
        }
        let under = a.cover[j];
        planned += usize::from(under != NO_UNIT);
        own += usize::from(under == SHARED || (under == room && room != NO_UNIT));
    }
    let share = |k: usize| if area == 0 { 0.0 } else { k as f64 / area as f64 };
    Behind {
        area_m2: area as f64 * resolution * resolution,
        pocket: !open,
        inside: share(within),
        planned: share(planned),
        own: share(own),
    }
}

/// Wavefronts behind the stretches of one `w` x `h` map, one after another
/// ([`Waves::behind`]). Their distances live in one buffer the size of the map, which each
/// wavefront leaves as it found it, so a wavefront costs the cells it reaches: most stretches
/// have little unseen space behind them, and a window of the map around each, cleared and
/// read back whole, was most of the frontier's time.
pub(crate) struct Waves {
    w: usize,
    h: usize,
    dist: Vec<u32>,
}

impl Waves {
    /// Wavefronts on a `w` x `h` map.
    pub(crate) fn new(w: usize, h: usize) -> Waves {
        Waves { w, h, dist: vec![u32::MAX; w * h] }
    }

    /// A wavefront ([`crate::grid::flood::wavefront`]) from the cells beside `cells` (map
    /// indices) that `enter` admits, through cells it admits, up to `limit` steps: each cell
    /// reached as `(map index, steps)` in the order reached, those at `limit + 1` reached but
    /// not grown from.
    pub(crate) fn behind(&mut self, cells: &[usize], limit: u32, enter: impl Fn(usize) -> bool) -> Vec<(usize, u32)> {
        let (w, h, dist) = (self.w, self.h, &mut self.dist);
        let mut reached = Vec::new();
        for &i in cells {
            for j in neighbours4(i, w, h) {
                if dist[j] == u32::MAX && enter(j) {
                    dist[j] = 1;
                    reached.push(j);
                }
            }
        }
        wavefront_listed(w, h, dist, &mut reached, enter, limit);
        let out = reached.iter().map(|&j| (j, dist[j])).collect();
        for j in reached {
            dist[j] = u32::MAX;
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A `w` x `h` map, walls round its edge, free left of column `split`, unknown right of it.
    fn half_seen(w: usize, h: usize, split: usize) -> Grid<Cell> {
        let mut map = Grid::new(w, h, Cell::Unknown);
        for y in 0..h {
            for x in 0..w {
                let wall = x == 0 || y == 0 || x == w - 1 || y == h - 1;
                *map.at_mut(x, y) = if wall {
                    Cell::Occupied
                } else if x < split {
                    Cell::Free
                } else {
                    Cell::Unknown
                };
            }
        }
        map
    }

    #[test]
    fn waves_reach_what_the_grid_s_wavefront_reaches_and_leave_no_trace() {
        use crate::grid::flood::wavefront;
        let mut rng = crate::mcmc::Rng::seed(11);
        let (w, h) = (41, 29);
        let mut waves = Waves::new(w, h);
        for round in 0..20 {
            let open: Vec<bool> = (0..w * h).map(|_| rng.chance(0.7)).collect();
            let x0 = rng.below(w as u32 - 6) as usize;
            let y = rng.below(h as u32) as usize;
            let cells: Vec<usize> = (x0..x0 + 5).map(|x| y * w + x).collect();
            let limit = [1, 3, 8, 40][round % 4];
            let mut got = waves.behind(&cells, limit, |j| open[j]);
            got.sort_unstable();
            // The same by `wavefront` over the whole grid, seeded beside the cells.
            let mut dist = vec![u32::MAX; w * h];
            let mut seeds = Vec::new();
            for &i in &cells {
                for j in neighbours4(i, w, h) {
                    if open[j] && dist[j] == u32::MAX {
                        dist[j] = 1;
                        seeds.push(j);
                    }
                }
            }
            wavefront(w, h, &mut dist, seeds, |j| open[j], limit);
            let want: Vec<(usize, u32)> = (0..w * h).filter(|&j| dist[j] != u32::MAX).map(|j| (j, dist[j])).collect();
            assert_eq!(got, want, "round {round}");
            assert!(waves.dist.iter().all(|&d| d == u32::MAX), "round {round}: the buffer is left clear");
        }
    }

    #[test]
    fn a_room_seen_in_half_has_one_stretch_closed_by_its_walls() {
        // 6 m x 3 m at 0.05 m: the unseen half is 58 x 59 cells behind a 58-cell frontier.
        let map = half_seen(120, 60, 60);
        let s = stretches(&World::empty(120, 60), &map, &Grid::new(120, 60, 0), 0.05);
        assert_eq!(s.len(), 1);
        assert_eq!(s[0].cells.len(), 58);
        assert_eq!(s[0].at.0, 59);
        assert!((s[0].behind_m2 - 59.0 * 58.0 * 0.0025).abs() < 1e-9, "{}", s[0].behind_m2);
        assert!(s[0].pocket && s[0].inside == 1.0 && !s[0].at_door && s[0].room == 0);
        assert!(s[0].jambs, "the frontier spans the room from wall to wall");
    }

    #[test]
    fn a_long_frontier_is_cut_and_lengths_are_metres() {
        // The same room 12 m high: a 11.9 m frontier in three stretches of about 4 m; at 0.1 m a
        // cell the same room in a quarter of the cells gives the same stretches in metres.
        for (res, k) in [(0.05, 1), (0.1, 2)] {
            let map = half_seen(120 / k, 240 / k, 60 / k);
            let s =
                stretches(&World::empty(120 / k as u32, 240 / k as u32), &map, &Grid::new(120 / k, 240 / k, 0), res);
            assert_eq!(s.len(), 3, "at {res} m");
            for p in &s {
                assert!((3.5..=4.1).contains(&p.width_m), "{} at {res}", p.width_m);
            }
        }
    }

    #[test]
    fn each_stretch_counts_the_placeholders_of_its_room() {
        // The 12 m high room's three stretches open from room 1 if the seen half is labelled:
        // each counts three ways; unlabelled, none.
        let map = half_seen(120, 240, 60);
        let labels = map.map(|&c| u16::from(c == Cell::Free));
        let s = stretches(&World::empty(120, 240), &map, &labels, 0.05);
        assert_eq!(s.iter().map(|p| (p.room, p.ways)).collect::<Vec<_>>(), [(1, 3); 3]);
        let none = stretches(&World::empty(120, 240), &map, &Grid::new(120, 240, 0), 0.05);
        assert!(none.iter().all(|p| p.room == 0 && p.ways == 0) && none.len() == 3);
    }

    #[test]
    fn furniture_shadows_and_specks_are_no_placeholders() {
        // A seen room with a 1 m x 1 m unknown blob (a desk's shadow) and one unknown cell.
        let mut map = half_seen(120, 60, 120);
        for y in 20..40 {
            for x in 30..50 {
                *map.at_mut(x, y) = Cell::Unknown;
            }
        }
        *map.at_mut(90, 30) = Cell::Unknown;
        assert!(stretches(&World::empty(120, 60), &map, &Grid::new(120, 60, 0), 0.05).is_empty());
    }

    #[test]
    fn streaks_between_rays_are_no_frontier() {
        // A seen room crossed by one-cell diagonal streaks of unknown cells that reach its unseen
        // right half: only the frontier along the unseen half is a placeholder.
        let mut map = half_seen(120, 60, 60);
        for k in 0..40 {
            for d in [0, 9, 18] {
                *map.at_mut(20 + k, 5 + (k + d) % 50) = Cell::Unknown;
            }
        }
        let s = stretches(&World::empty(120, 60), &map, &Grid::new(120, 60, 0), 0.05);
        assert_eq!(s.len(), 1, "{:?}", s.iter().map(|p| p.at).collect::<Vec<_>>());
        assert!(s[0].at.0 >= 55, "{:?}", s[0].at);
    }

    #[test]
    fn unseen_space_inside_the_plan_s_units_is_planned_and_the_own_room_s() {
        // The half-seen room, once with no units, once with a unit over the whole room (its
        // interior inside a 1-cell ring) held by room 1, once with that unit in room 2 while the
        // frontier's cells carry room 1's label.
        use crate::floorplan::world::{Room, Unit, UnitType};
        let map = half_seen(120, 60, 60);
        let with_unit = |room_of_unit: u32| {
            let mut world = World::empty(120, 60);
            world.units.push(Unit::new(1, 0, 0, 120, 60, UnitType::Room));
            let room = Room {
                id: room_of_unit,
                kind: UnitType::Room,
                units: vec![1],
                area_m2: 18.0,
                doors: vec![],
                opens_to: vec![],
                name: None,
            };
            world.rooms.push(room);
            world
        };
        let labels = Grid::new(120, 60, 1u16);
        let none = stretches(&World::empty(120, 60), &map, &labels, 0.05);
        assert_eq!((none[0].planned, none[0].own), (0.0, 0.0));
        // Every unseen cell behind lies inside the unit's interior (columns 60 - 118, rows 1 - 58).
        let own = stretches(&with_unit(1), &map, &labels, 0.05);
        assert_eq!((own[0].room, own[0].planned, own[0].own), (1, 1.0, 1.0));
        let other = stretches(&with_unit(2), &map, &labels, 0.05);
        assert_eq!((other[0].planned, other[0].own), (1.0, 0.0));
    }

    #[test]
    fn space_that_runs_on_past_five_metres_is_no_pocket() {
        // Free left of column 20, unknown from there on for 9 m: the wavefront passes 5 m.
        let map = half_seen(200, 60, 20);
        let s = stretches(&World::empty(200, 60), &map, &Grid::new(200, 60, 0), 0.05);
        assert_eq!(s.len(), 1);
        assert!(!s[0].pocket);
        assert!((s[0].behind_m2 - 58.0 * 100.0 * 0.0025).abs() < 0.05, "{}", s[0].behind_m2);
    }
}
