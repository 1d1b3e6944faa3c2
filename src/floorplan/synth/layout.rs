//! The building layout: unit interiors separated by walls, and the doors between them.
//!
//! The layout is drawn in a canonical orientation, the building's long axis along `x`, and
//! transposed at the end when the canvas is taller than wide. From the outside in:
//!
//! * the building is the canvas less the margin; its outer wall is `wall` cells thick;
//! * halls, if any, are end columns spanning the building's depth;
//! * between them, bands across the depth: room rows and corridors, in the pattern
//!   room-corridor-room (one corridor), corridor-room (a shallow building) or
//!   room-corridor-room-room-corridor-room (two corridors);
//! * with two corridors and no hall, a connecting corridor cuts through the two middle rows;
//! * each row segment is split into rooms and "other" units side by side.
//!
//! Every pair of units is separated by exactly `wall` cells, so neighbours share one wall and
//! the interiors tile the building. Doors are then chosen on that adjacency: every room and
//! "other" unit opens onto a corridor it touches (or a hall), corridors and halls are joined
//! until the door graph is connected, and further neighbours get a door by chance.

use super::config::{Cells, Span, DOOR_CLEARANCE};
use super::SynthError;
use crate::floorplan::{Door, Rect, UnitType};
use crate::mcmc::Rng;
use crate::union_find::UnionFind;

/// One unit of the layout: its free interior and its type.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Space {
    /// The free interior (walls excluded).
    pub inner: Rect,
    /// The unit's type.
    pub kind: UnitType,
}

/// A door opening through the wall between spaces `a` (left of or above the wall) and `b`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) struct Opening {
    /// The space on the left of / above the wall.
    pub a: usize,
    /// The space on the right of / below the wall.
    pub b: usize,
    /// Whether the wall runs vertically (`a` left of `b`); otherwise `a` is above `b`.
    pub vertical: bool,
    /// The first wall cell across the wall: one past `a`'s interior.
    pub wall: i32,
    /// The first cell of the opening along the wall.
    pub along: i32,
    /// The opening's length along the wall, cells.
    pub len: i32,
}

impl Opening {
    /// The free cells through the wall.
    pub fn rect(&self, wall: i32) -> Rect {
        if self.vertical {
            Rect::new(self.wall, self.along, wall, self.len)
        } else {
            Rect::new(self.along, self.wall, self.len, wall)
        }
    }

    /// The door as written to `world.json`: the run of opening cells on the wall's centre
    /// line (`(wall - 1) / 2` cells past `a`'s border ring), units `[a + 1, b + 1]`.
    pub fn door(&self, id: u32, wall: i32) -> Door {
        let c = self.wall + (wall - 1) / 2;
        let end = self.along + self.len - 1;
        let (x0, y0, x1, y1) = if self.vertical { (c, self.along, c, end) } else { (self.along, c, end, c) };
        Door { id, units: [self.a as u32 + 1, self.b as u32 + 1], x0, y0, x1, y1, opening: false }
    }

    /// The other space of the opening.
    pub fn other(&self, s: usize) -> usize {
        if self.a == s {
            self.b
        } else {
            self.a
        }
    }
}

/// A complete layout in the world frame.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct Plan {
    /// The building's outer boundary (outer face of the outer wall).
    pub building: Rect,
    /// The units.
    pub spaces: Vec<Space>,
    /// The doors.
    pub openings: Vec<Opening>,
}

fn transpose(r: Rect) -> Rect {
    Rect::new(r.y, r.x, r.h, r.w)
}

impl Plan {
    fn transposed(self) -> Plan {
        Plan {
            building: transpose(self.building),
            spaces: self.spaces.into_iter().map(|s| Space { inner: transpose(s.inner), kind: s.kind }).collect(),
            openings: self.openings.into_iter().map(|o| Opening { vertical: !o.vertical, ..o }).collect(),
        }
    }
}

/// How many times a layout is redrawn when a random choice made it impossible.
const ATTEMPTS: u32 = 16;

/// Draws a layout for the canvas; retries a few times when random sizes made it fail.
pub(super) fn plan(c: &Cells, extra_doors: f64, rng: &mut Rng) -> Result<Plan, SynthError> {
    let mut last = None;
    for _ in 0..ATTEMPTS {
        match attempt(c, extra_doors, rng) {
            Ok(p) => return Ok(p),
            Err(Failure::Fatal(e)) => return Err(e),
            Err(Failure::Unlucky(e)) => last = Some(e),
        }
    }
    Err(last.expect("at least one attempt"))
}

enum Failure {
    /// The configuration can never work.
    Fatal(SynthError),
    /// These random draws did not work; others may.
    Unlucky(SynthError),
}

fn fatal(m: String) -> Failure {
    Failure::Fatal(SynthError::new(format!("synth config: {m}")))
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Band {
    Rooms,
    Corridor,
}

/// A stretch of a room row to split into rooms and "other" units: columns `x0..x1`.
#[derive(Debug, Clone)]
struct Segment {
    row: Rect,
    x0: i32,
    x1: i32,
    /// Widths of the "other" units placed here.
    others: Vec<i32>,
}

impl Segment {
    fn new(row: Rect, x0: i32, x1: i32) -> Self {
        Segment { row, x0, x1, others: Vec::new() }
    }

    /// Length left for rooms after the "other" units and their walls.
    fn rest(&self, wall: i32) -> i32 {
        self.x1 - self.x0 - self.others.iter().map(|w| w + wall).sum::<i32>()
    }

    /// The fewest and most rooms that fill the rest, widths within `room` (the fewest may
    /// need rooms wider than `room.hi` when no count fits exactly).
    fn counts(&self, wall: i32, room: Span) -> (i32, i32) {
        let rest = self.rest(wall) + wall;
        let most = rest / (room.lo + wall);
        let fewest = ((rest + room.hi + wall - 1) / (room.hi + wall)).max(1).min(most);
        (fewest, most)
    }
}

/// One try at a layout: bands across the depth (rows of rooms and corridors), halls at the
/// ends, a connector between two corridors, "other" units, then the rooms, and doors.
fn attempt(c: &Cells, extra_doors: f64, rng: &mut Rng) -> Result<Plan, Failure> {
    let portrait = c.canvas.1 > c.canvas.0;
    let (cw, ch) = if portrait { (c.canvas.1, c.canvas.0) } else { c.canvas };
    let t = c.wall;
    let building = Rect::new(c.margin, c.margin, cw - 2 * c.margin, ch - 2 * c.margin);
    let inner = Rect::new(building.x + t, building.y + t, building.w - 2 * t, building.h - 2 * t);
    let (long_side, short_side) = if portrait { ("height", "width") } else { ("width", "height") };
    let mut spaces = Vec::new();

    let (pattern, corridors) = band_pattern(c, inner, ch, short_side, rng)?;
    let (corridor_widths, depths) = band_sizes(c, inner, &pattern, rng);
    let (halls, xa, xb) = place_halls(c, inner, cw, long_side, rng)?;
    let room_rows = lay_bands(c, inner, (xa, xb), &pattern, &corridor_widths, &depths, &mut spaces);
    let mut segments = row_segments(c, &room_rows, corridors, (xa, xb), &mut spaces, rng);
    for h in halls {
        spaces.push(Space { inner: h, kind: UnitType::Hall });
    }
    place_others(c, &mut segments, rng)?;
    let counts = room_counts(c, &segments, rng)?;
    fill_segments(c, &segments, &counts, &mut spaces, rng);

    let openings = doors(&spaces, c, extra_doors, rng)?;
    let plan = Plan { building, spaces, openings };
    Ok(if portrait { plan.transposed() } else { plan })
}

/// The bands across the depth, and the number of corridors.
fn band_pattern(c: &Cells, inner: Rect, ch: i32, short_side: &str, rng: &mut Rng) -> Result<(Vec<Band>, u32), Failure> {
    let t = c.wall;
    let need = |rows: i32, corridors: i32| rows * c.depth.lo + corridors * c.corridor.lo + (rows + corridors - 1) * t;
    let depth_needed = |n: i32| n + 2 * t + 2 * c.margin;
    let corridors = match c.corridors {
        Some(n) => n,
        None => {
            let mid = (c.corridor.lo + c.corridor.hi) / 2;
            let one_row = (inner.h - mid - 2 * t) / 2;
            if need(4, 2) <= inner.h && one_row > c.depth.hi {
                2
            } else {
                1
            }
        }
    };
    let pattern: Vec<Band> = if corridors == 2 {
        if need(4, 2) > inner.h {
            return Err(fatal(format!(
                "the canvas {short_side} {} is too small for two corridors with rooms on both sides; accepted: at least {} cells",
                ch,
                depth_needed(need(4, 2))
            )));
        }
        use Band::*;
        vec![Rooms, Corridor, Rooms, Rooms, Corridor, Rooms]
    } else if need(2, 1) <= inner.h {
        vec![Band::Rooms, Band::Corridor, Band::Rooms]
    } else if need(1, 1) <= inner.h {
        if rng.chance(0.5) {
            vec![Band::Rooms, Band::Corridor]
        } else {
            vec![Band::Corridor, Band::Rooms]
        }
    } else {
        return Err(fatal(format!(
            "the canvas {short_side} {} is too small for a corridor and a row of rooms; accepted: at least {} cells",
            ch,
            depth_needed(need(1, 1))
        )));
    };
    Ok((pattern, corridors))
}

/// Corridor widths, and each room row's depth beyond the least.
fn band_sizes(c: &Cells, inner: Rect, pattern: &[Band], rng: &mut Rng) -> (Vec<i32>, Vec<i32>) {
    let t = c.wall;
    let rows = pattern.iter().filter(|b| **b == Band::Rooms).count() as i32;
    let n_corridors = pattern.len() as i32 - rows;
    let mut budget = inner.h - (pattern.len() as i32 - 1) * t - rows * c.depth.lo;
    let mut corridor_widths = Vec::new();
    for k in 0..n_corridors {
        let rest = (n_corridors - k - 1) * c.corridor.lo;
        let w = rng.between(c.corridor.lo, c.corridor.hi.min(budget - rest));
        budget -= w;
        corridor_widths.push(w);
    }
    let depths = share(rng, rows as usize, budget, i32::MAX);
    (corridor_widths, depths)
}

/// Halls at the ends, leaving room for at least one room along the corridors; with the columns
/// `xa..xb` left between them.
fn place_halls(
    c: &Cells,
    inner: Rect,
    cw: i32,
    long_side: &str,
    rng: &mut Rng,
) -> Result<(Vec<Rect>, i32, i32), Failure> {
    let t = c.wall;
    let hall_room = (inner.w - c.room.lo - c.halls as i32 * t) / (c.halls.max(1) as i32);
    if c.halls > 0 && hall_room < c.hall.lo {
        return Err(fatal(format!(
            "the canvas {long_side} {} is too small for {} hall(s) of at least {} cells and a room; accepted: at least {} cells",
            cw,
            c.halls,
            c.hall.lo,
            cw + (c.hall.lo - hall_room) * c.halls as i32
        )));
    }
    let (mut xa, mut xb) = (inner.x, inner.right());
    let mut halls = Vec::new();
    for k in 0..c.halls {
        let w = rng.between(c.hall.lo, c.hall.hi.min(hall_room));
        if k == 0 {
            halls.push(Rect::new(xa, inner.y, w, inner.h));
            xa += w + t;
        } else {
            halls.push(Rect::new(xb - w, inner.y, w, inner.h));
            xb -= w + t;
        }
    }
    if xb - xa < c.room.lo {
        return Err(fatal(format!(
            "the canvas {long_side} {} is too small for a room along the corridor; accepted: at least {} cells",
            cw,
            cw + c.room.lo - (xb - xa)
        )));
    }
    Ok((halls, xa, xb))
}

/// Lays the bands out top to bottom over columns `xa..xb`: corridors become spaces, room rows
/// are returned.
fn lay_bands(
    c: &Cells,
    inner: Rect,
    (xa, xb): (i32, i32),
    pattern: &[Band],
    corridor_widths: &[i32],
    depths: &[i32],
    spaces: &mut Vec<Space>,
) -> Vec<Rect> {
    let t = c.wall;
    let (mut y, mut ci, mut ri) = (inner.y, 0, 0);
    let mut room_rows = Vec::new();
    for band in pattern {
        let h = match band {
            Band::Corridor => corridor_widths[ci],
            Band::Rooms => c.depth.lo + depths[ri],
        };
        let r = Rect::new(xa, y, xb - xa, h);
        match band {
            Band::Corridor => {
                spaces.push(Space { inner: r, kind: UnitType::Corridor });
                ci += 1;
            }
            Band::Rooms => {
                room_rows.push(r);
                ri += 1;
            }
        }
        y += h + t;
    }
    debug_assert_eq!(y - t, inner.bottom());
    room_rows
}

/// Row segments; with two corridors and no hall, a connector (a corridor space) cuts the
/// middle rows.
fn row_segments(
    c: &Cells,
    room_rows: &[Rect],
    corridors: u32,
    (xa, xb): (i32, i32),
    spaces: &mut Vec<Space>,
    rng: &mut Rng,
) -> Vec<Segment> {
    let t = c.wall;
    let mut segments: Vec<Segment> = Vec::new();
    let whole = |row: Rect| Segment::new(row, row.x, row.right());
    if corridors == 2 && c.halls == 0 {
        let len = xb - xa;
        let mut w = rng.between(c.corridor.lo, c.corridor.hi);
        let side = c.room.lo + t;
        let cx = if len >= 2 * side + w {
            rng.between(xa + side, xb - side - w)
        } else if len >= side + w {
            xa
        } else {
            w = len;
            xa
        };
        let (upper, lower) = (room_rows[1], room_rows[2]);
        let conn = Rect::new(cx, upper.y, w, lower.bottom() - upper.y);
        spaces.push(Space { inner: conn, kind: UnitType::Corridor });
        for (i, row) in room_rows.iter().enumerate() {
            if i == 1 || i == 2 {
                for (x0, x1) in [(xa, cx - t), (cx + w + t, xb)] {
                    if x1 > x0 {
                        segments.push(Segment::new(*row, x0, x1));
                    }
                }
            } else {
                segments.push(whole(*row));
            }
        }
    } else {
        segments.extend(room_rows.iter().map(|r| whole(*r)));
    }
    segments
}

/// "Other" units go to segments that keep room for a room beside them.
fn place_others(c: &Cells, segments: &mut [Segment], rng: &mut Rng) -> Result<(), Failure> {
    let t = c.wall;
    for placed in 0..c.others {
        let w = rng.between(c.other.lo, c.other.hi);
        let fits: Vec<usize> = (0..segments.len()).filter(|&i| segments[i].rest(t) - (w + t) >= c.room.lo).collect();
        if fits.is_empty() {
            return Err(Failure::Unlucky(SynthError::new(format!(
                "synth config: others: {} small units do not fit beside the rooms (this building held {placed}); \
                 accepted: fewer others or a larger canvas",
                c.others
            ))));
        }
        segments[fits[rng.index(fits.len())]].others.push(w);
    }
    Ok(())
}

/// How many rooms each segment gets: drawn per segment, then nudged into the accepted range.
fn room_counts(c: &Cells, segments: &[Segment], rng: &mut Rng) -> Result<Vec<i32>, Failure> {
    let t = c.wall;
    let bounds: Vec<(i32, i32)> = segments.iter().map(|s| s.counts(t, c.room)).collect();
    let (fewest, most) = bounds.iter().fold((0i64, 0i64), |(a, b), (lo, hi)| (a + *lo as i64, b + *hi as i64));
    let (lo, hi) = (fewest.max(c.rooms[0] as i64), most.min(c.rooms[1] as i64));
    if lo > hi {
        return Err(Failure::Unlucky(SynthError::new(format!(
            "synth config: rooms is [{}, {}]; this building holds {fewest} to {most} rooms \
             (change rooms, room_width or the canvas)",
            c.rooms[0], c.rooms[1]
        ))));
    }
    let mut counts: Vec<i32> = bounds.iter().map(|&(a, b)| rng.between(a, b)).collect();
    let mut total: i64 = counts.iter().map(|&k| k as i64).sum();
    while total < lo || total > hi {
        let grow = total < lo;
        let can: Vec<usize> = (0..counts.len())
            .filter(|&i| if grow { counts[i] < bounds[i].1 } else { counts[i] > bounds[i].0 })
            .collect();
        let i = can[rng.index(can.len())];
        counts[i] += if grow { 1 } else { -1 };
        total += if grow { 1 } else { -1 };
    }
    Ok(counts)
}

/// Splits each segment into its rooms and "other" units, left to right.
fn fill_segments(c: &Cells, segments: &[Segment], counts: &[i32], spaces: &mut Vec<Space>, rng: &mut Rng) {
    let t = c.wall;
    for (seg, &k) in segments.iter().zip(counts) {
        let extra = seg.rest(t) - (k - 1) * t - k * c.room.lo;
        let widths = share(rng, k as usize, extra, c.room.hi - c.room.lo);
        let mut seq: Vec<(UnitType, i32)> = widths.iter().map(|w| (UnitType::Room, c.room.lo + w)).collect();
        for &w in &seg.others {
            let at = rng.index(seq.len() + 1);
            seq.insert(at, (UnitType::Other, w));
        }
        let mut x = seg.x0;
        for (kind, w) in seq {
            spaces.push(Space { inner: Rect::new(x, seg.row.y, w, seg.row.h), kind });
            x += w + t;
        }
        debug_assert_eq!(x - t, seg.x1);
    }
}

/// Two spaces that share a wall long enough for a door: `a` left of / above `b`, their
/// interiors overlapping along the wall on `lo..hi`.
#[derive(Debug, Clone, Copy)]
struct Contact {
    a: usize,
    b: usize,
    vertical: bool,
    wall: i32,
    lo: i32,
    hi: i32,
}

fn contact(spaces: &[Space], i: usize, j: usize, wall: i32) -> Option<Contact> {
    let (p, q) = (spaces[i].inner, spaces[j].inner);
    let overlap = |a0: i32, a1: i32, b0: i32, b1: i32| (a0.max(b0), a1.min(b1));
    for (a, b, p, q) in [(i, j, p, q), (j, i, q, p)] {
        if p.right() + wall == q.x {
            let (lo, hi) = overlap(p.y, p.bottom(), q.y, q.bottom());
            return (hi > lo).then_some(Contact { a, b, vertical: true, wall: p.right(), lo, hi });
        }
        if p.bottom() + wall == q.y {
            let (lo, hi) = overlap(p.x, p.right(), q.x, q.right());
            return (hi > lo).then_some(Contact { a, b, vertical: false, wall: p.bottom(), lo, hi });
        }
    }
    None
}

fn is_hub(kind: UnitType) -> bool {
    matches!(kind, UnitType::Corridor | UnitType::Hall)
}

/// Chooses the doors: each room and "other" unit onto a corridor (else a hall) it touches, hubs
/// joined until everything is connected, other neighbours by chance.
fn doors(spaces: &[Space], c: &Cells, extra_doors: f64, rng: &mut Rng) -> Result<Vec<Opening>, Failure> {
    let n = spaces.len();
    let mut contacts = Vec::new();
    for i in 0..n {
        for j in i + 1..n {
            if let Some(k) = contact(spaces, i, j, c.wall) {
                if k.hi - k.lo >= c.door.lo + 2 * DOOR_CLEARANCE {
                    contacts.push(k);
                }
            }
        }
    }
    let mut chosen = vec![false; contacts.len()];
    for (u, s) in spaces.iter().enumerate() {
        if is_hub(s.kind) {
            continue;
        }
        for hub in [UnitType::Corridor, UnitType::Hall] {
            let best = (0..contacts.len())
                .filter(|&k| {
                    let ct = &contacts[k];
                    (ct.a == u || ct.b == u) && spaces[if ct.a == u { ct.b } else { ct.a }].kind == hub
                })
                .max_by_key(|&k| (contacts[k].hi - contacts[k].lo, std::cmp::Reverse(k)));
            if let Some(k) = best {
                chosen[k] = true;
                break;
            }
        }
    }
    // Join the components, hubs first.
    let mut sets = UnionFind::new(n);
    for (k, ct) in contacts.iter().enumerate() {
        if chosen[k] {
            sets.union(ct.a, ct.b);
        }
    }
    let hubs_first = |k: &usize| !(is_hub(spaces[contacts[*k].a].kind) && is_hub(spaces[contacts[*k].b].kind));
    let mut order: Vec<usize> = (0..contacts.len()).collect();
    order.sort_by_key(|k| (hubs_first(k), *k));
    for k in order {
        if sets.union(contacts[k].a, contacts[k].b) {
            chosen[k] = true;
        }
    }
    if (1..n).any(|i| !sets.same(0, i)) {
        return Err(Failure::Fatal(SynthError::new(
            "synth: internal error: the layout is not connected (a bug: please report the config and seed)",
        )));
    }
    for ch in chosen.iter_mut() {
        let extra = rng.chance(extra_doors);
        *ch |= extra;
    }
    let mut openings = Vec::new();
    for (ct, _) in contacts.iter().zip(&chosen).filter(|(_, &ch)| ch) {
        let room = ct.hi - ct.lo - 2 * DOOR_CLEARANCE;
        // An open arch between two hubs; the draw is skipped when arches are off, so that
        // configs without them keep their bytes.
        let arch =
            c.open_hubs > 0.0 && is_hub(spaces[ct.a].kind) && is_hub(spaces[ct.b].kind) && rng.chance(c.open_hubs);
        let len = if arch { room } else { rng.between(c.door.lo, c.door.hi).min(room) };
        let along = rng.between(ct.lo + DOOR_CLEARANCE, ct.hi - DOOR_CLEARANCE - len);
        openings.push(Opening { a: ct.a, b: ct.b, vertical: ct.vertical, wall: ct.wall, along, len });
    }
    Ok(openings)
}

/// Shares `total` extra cells among `n` parts in random chunks, each part taking at most `cap`
/// until all are full; then the rest is spread evenly.
fn share(rng: &mut Rng, n: usize, total: i32, cap: i32) -> Vec<i32> {
    let mut add = vec![0; n];
    if n == 0 || total <= 0 {
        return add;
    }
    let chunk = (total / (4 * n as i32)).max(1);
    let mut left = total;
    while left > 0 {
        let open: Vec<usize> = (0..n).filter(|&i| add[i] < cap).collect();
        if open.is_empty() {
            let (each, extra) = (left / n as i32, left % n as i32);
            for (i, a) in add.iter_mut().enumerate() {
                *a += each + i32::from((i as i32) < extra);
            }
            break;
        }
        let i = open[rng.index(open.len())];
        let g = chunk.min(left).min(cap - add[i]);
        add[i] += g;
        left -= g;
    }
    add
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn share_gives_everything_and_respects_caps() {
        let mut rng = Rng::seed(1);
        for (n, total, cap) in [(1, 10, 100), (5, 37, 10), (4, 100, 10), (3, 0, 5), (7, 1000, i32::MAX)] {
            let add = share(&mut rng, n, total, cap);
            assert_eq!(add.len(), n);
            assert_eq!(add.iter().sum::<i32>(), total);
            if total as i64 <= cap as i64 * n as i64 {
                assert!(add.iter().all(|&a| (0..=cap).contains(&a)), "{add:?}");
            } else {
                // Past every cap, the rest is spread evenly.
                let (lo, hi) = (add.iter().min().unwrap(), add.iter().max().unwrap());
                assert!(hi - lo <= 1, "{add:?}");
            }
        }
    }

    #[test]
    fn segment_counts_bracket_the_possible_room_numbers() {
        let row = Rect::new(0, 0, 0, 50);
        let room = Span { lo: 60, hi: 120 };
        // 400 cells with 3-cell walls: at least 4 rooms of at most 120, at most 6 of at least 60.
        assert_eq!(Segment::new(row, 0, 400).counts(3, room), (4, 6));
        assert_eq!(Segment::new(row, 0, 120).counts(3, room), (1, 1));
        // 121 cells: no count fits exactly, so one room is widened.
        assert_eq!(Segment::new(row, 0, 121).counts(3, room), (1, 1));
        let mut s = Segment::new(row, 0, 200);
        s.others.push(40);
        assert_eq!(s.rest(3), 157);
    }

    #[test]
    fn door_run_sits_on_the_wall_centre_line() {
        let o = Opening { a: 0, b: 1, vertical: true, wall: 10, along: 5, len: 4 };
        assert_eq!(o.rect(3), Rect::new(10, 5, 3, 4));
        let d = o.door(7, 3);
        assert_eq!((d.id, d.units, d.x0, d.y0, d.x1, d.y1), (7, [1, 2], 11, 5, 11, 8));
        let h = Opening { vertical: false, ..o }.door(1, 1);
        assert_eq!((h.x0, h.y0, h.x1, h.y1), (5, 10, 8, 10));
    }
}
