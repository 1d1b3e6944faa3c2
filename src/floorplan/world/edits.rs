//! A person's corrections of a floor plan, taken as hard evidence.
//!
//! Users of room segmentation ask above all to correct the result: split and merge rooms, name
//! and retype them. In a knowledge-supervised sampler a correction is the strongest knowledge
//! there is, so it does not patch the output: it constrains the chain, which then re-explains
//! everything else around it.
//!
//! Edits are given in map cells (column, row), as JSON (`ksmcmc floorplan --edits EDITS.json`,
//! `Mapper.setEdits` in wasm), a list of:
//!
//! * `{"op": "merge", "at": [[x1, y1], [x2, y2]]}`: the rooms at the two points are one room;
//! * `{"op": "split", "line": [[x1, y1], [x2, y2]]}`: a wall runs there, and the two sides are
//!   different rooms;
//! * `{"op": "type", "at": [x, y], "type": "corridor"}`: the room there has this type
//!   (`room`, `corridor`, `hall` or `other`);
//! * `{"op": "name", "at": [x, y], "name": "Kitchen"}`: the room there has this name.
//!
//! How each one binds:
//!
//! * **split**: the line is taken as a wall, extended at both ends along its direction to the
//!   nearest non-free cell ([`MAX_EXTENSION_CELLS`] at most), so that a line drawn roughly from
//!   wall to wall closes the gap. No unit's interior may hold a wall cell: the chain refuses any
//!   proposal that would (`State::forbid`), so no world that breaks the edit is
//!   proposed or accepted. The room layer gets `SameRoom` false for units the wall separates,
//!   and the room the line is drawn across (the one at its middle) is cut in two along it.
//! * **merge**: the units under the two points get `SameRoom` as evidence, and the rooms at the
//!   two points are joined.
//! * **type**: the unit under the point gets its type as evidence in the Markov logic
//!   inference, which types the units and shapes the prior ([`crate::floorplan::knowledge`]); the room at
//!   the point takes the type.
//! * **name**: the room at the point carries the name (`rooms[].name` in `world.json`).
//!
//! Edits apply in order: a later one wins where two disagree (a merge across an earlier split
//! joins the two sides again).

use crate::floorplan::world::{Room, UnitType, World};
use crate::geometry::{Frame, Rect};
use crate::grid::{Cell, Grid};
use serde::{Deserialize, Serialize};

/// Longest edits text read, bytes.
pub const MAX_EDITS_TEXT: usize = 1 << 20;
/// Most edits in one list.
pub const MAX_EDITS: usize = 10_000;
pub use super::MAX_NAME_CHARS;
/// How far a split line is extended at each end to reach a wall, cells: a line drawn roughly
/// from wall to wall closes the gaps at its ends, one drawn up to an opening stops soon after.
pub const MAX_EXTENSION_CELLS: i64 = 12;
/// How far from an edit's point the room it means is looked for, cells (a click on a wall or
/// on furniture still finds the room beside it).
pub const NEAR_CELLS: i64 = 6;

/// One edit (see the module docs).
#[derive(Debug, Clone, PartialEq, Eq, Serialize)]
#[serde(tag = "op", rename_all = "lowercase")]
pub enum Edit {
    /// The rooms at the two points are one room.
    Merge {
        /// The two points, map cells.
        at: [[i64; 2]; 2],
    },
    /// A wall runs along the line, and its two sides are different rooms.
    Split {
        /// The line's ends, map cells.
        line: [[i64; 2]; 2],
    },
    /// The room at the point has this type.
    Type {
        /// The point, map cells.
        at: [i64; 2],
        /// The type (not `unknown`).
        #[serde(rename = "type")]
        kind: UnitType,
    },
    /// The room at the point has this name.
    Name {
        /// The point, map cells.
        at: [i64; 2],
        /// The name.
        name: String,
    },
}

impl Edit {
    fn op(&self) -> &'static str {
        match self {
            Edit::Merge { .. } => Op::Merge,
            Edit::Split { .. } => Op::Split,
            Edit::Type { .. } => Op::Type,
            Edit::Name { .. } => Op::Name,
        }
        .name()
    }

    /// The edit `raw` reads as, once its op has the fields it needs and no other's.
    fn read(raw: RawEdit) -> Result<Edit, String> {
        let RawEdit { op, at, line, kind, name } = raw;
        let stray = match op {
            Op::Merge | Op::Type | Op::Name => line.is_some().then_some("line"),
            Op::Split => at.is_some().then_some("at"),
        }
        .or_else(|| (kind.is_some() && op != Op::Type).then_some("type"))
        .or_else(|| (name.is_some() && op != Op::Name).then_some("name"));
        if let Some(field) = stray {
            return Err(format!("`{field}` belongs to another op"));
        }
        let missing = |field: &str| format!("missing field `{field}`");
        let point = |v: &serde_json::Value| -> Option<[i64; 2]> {
            match v.as_array()?.as_slice() {
                [x, y] => Some([x.as_i64()?, y.as_i64()?]),
                _ => None,
            }
        };
        let two = |v: &serde_json::Value| -> Option<[[i64; 2]; 2]> {
            match v.as_array()?.as_slice() {
                [a, b] => Some([point(a)?, point(b)?]),
                _ => None,
            }
        };
        let at = at.ok_or_else(|| missing("at"));
        Ok(match op {
            Op::Merge => Edit::Merge { at: two(&at?).ok_or("`at` must be two points, [[x1, y1], [x2, y2]]")? },
            Op::Split => Edit::Split { line: line.ok_or_else(|| missing("line"))? },
            Op::Type => Edit::Type {
                at: point(&at?).ok_or("`at` must be a point, [x, y]")?,
                kind: kind.ok_or_else(|| missing("type"))?,
            },
            Op::Name => Edit::Name {
                at: point(&at?).ok_or("`at` must be a point, [x, y]")?,
                name: name.ok_or_else(|| missing("name"))?,
            },
        })
    }

    fn points(&self) -> Vec<[i64; 2]> {
        match self {
            Edit::Merge { at } => at.to_vec(),
            Edit::Split { line } => line.to_vec(),
            Edit::Type { at, .. } | Edit::Name { at, .. } => vec![*at],
        }
    }
}

/// The ops an edit can have.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "lowercase")]
enum Op {
    Merge,
    Split,
    Type,
    Name,
}

impl Op {
    fn name(self) -> &'static str {
        match self {
            Op::Merge => "merge",
            Op::Split => "split",
            Op::Type => "type",
            Op::Name => "name",
        }
    }
}

/// An edit as its JSON has it: its op and every field any op takes, which [`Edit::read`]
/// then checks against the op. A plain struct rather than serde's internally tagged enum,
/// which reads each object twice through a buffer: that reader was 17 kB of the live
/// mapper's module, whose size the first frame waits for.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawEdit {
    op: Op,
    /// One point, or two for a merge (read by [`Edit::read`]).
    at: Option<serde_json::Value>,
    line: Option<[[i64; 2]; 2]>,
    #[serde(rename = "type")]
    kind: Option<UnitType>,
    name: Option<String>,
}

/// Why edits were refused.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum EditError {
    /// The text is not a JSON list of edits.
    Json(String),
    /// The text or the list is over a cap.
    TooLarge(String),
    /// Edit number `index` (1-based) cannot apply.
    Edit {
        /// 1-based position in the list.
        index: usize,
        /// Its `op`.
        op: &'static str,
        /// What is wrong.
        message: String,
    },
}

impl std::fmt::Display for EditError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            EditError::Json(m) => write!(
                f,
                "edits: {m}; expected a list such as [{{\"op\": \"type\", \"at\": [40, 12], \"type\": \"corridor\"}}]"
            ),
            EditError::TooLarge(m) => write!(f, "edits: {m}"),
            EditError::Edit { index, op, message } => write!(f, "edit {index} ({op}): {message}"),
        }
    }
}

impl std::error::Error for EditError {}

/// A list of edits, checked against a map.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct Edits {
    list: Vec<Edit>,
}

impl Edits {
    /// Reads a JSON list of edits (see the module docs).
    ///
    /// ```
    /// use ksmcmc::floorplan::edits::Edits;
    /// let e = Edits::parse(r#"[{"op": "name", "at": [3, 4], "name": "Kitchen"}]"#)?;
    /// assert_eq!(e.len(), 1);
    /// assert!(Edits::parse(r#"[{"op": "paint"}]"#).unwrap_err().to_string().contains("unknown variant"));
    /// # Ok::<(), ksmcmc::floorplan::edits::EditError>(())
    /// ```
    pub fn parse(text: &str) -> Result<Edits, EditError> {
        if text.len() > MAX_EDITS_TEXT {
            return Err(EditError::TooLarge(format!(
                "the text is {} bytes, over the cap of {MAX_EDITS_TEXT}",
                text.len()
            )));
        }
        let raw: Vec<RawEdit> = serde_json::from_str(text).map_err(|e| EditError::Json(e.to_string()))?;
        if raw.len() > MAX_EDITS {
            return Err(EditError::TooLarge(format!("{} edits, over the cap of {MAX_EDITS}", raw.len())));
        }
        let mut list = Vec::with_capacity(raw.len());
        for (i, r) in raw.into_iter().enumerate() {
            let op = r.op.name();
            list.push(Edit::read(r).map_err(|message| EditError::Edit { index: i + 1, op, message })?);
        }
        let edits = Edits { list };
        edits.check_values()?;
        Ok(edits)
    }

    /// The edits as JSON text, the form [`Edits::parse`] reads.
    pub fn to_json(&self) -> String {
        serde_json::to_string_pretty(&self.list).unwrap_or_else(|_| "[]".into())
    }

    /// The edits in order.
    pub fn list(&self) -> &[Edit] {
        &self.list
    }

    /// Number of edits.
    pub fn len(&self) -> usize {
        self.list.len()
    }

    /// Whether there are none.
    pub fn is_empty(&self) -> bool {
        self.list.is_empty()
    }

    fn fail(&self, index: usize, message: String) -> EditError {
        EditError::Edit { index: index + 1, op: self.list[index].op(), message }
    }

    /// The checks of each edit's values (the list's length is checked as it is read).
    fn check_values(&self) -> Result<(), EditError> {
        for (i, e) in self.list.iter().enumerate() {
            match e {
                Edit::Type { kind: UnitType::Unknown, .. } => {
                    return Err(self.fail(i, "the type must be room, corridor, hall or other".into()));
                }
                Edit::Name { name, .. } if name.trim().is_empty() || name.chars().count() > MAX_NAME_CHARS => {
                    return Err(self.fail(i, format!("a name has 1 to {MAX_NAME_CHARS} characters")));
                }
                Edit::Split { line: [a, b] } if (a[0] - b[0]).abs().max((a[1] - b[1]).abs()) < 2 => {
                    return Err(self.fail(i, "the line must be at least 2 cells long".into()));
                }
                _ => {}
            }
        }
        Ok(())
    }

    /// Checks that every point lies on a `width` x `height` map.
    pub fn check_map(&self, width: usize, height: usize) -> Result<(), EditError> {
        for (i, e) in self.list.iter().enumerate() {
            for p in e.points() {
                if p[0] < 0 || p[1] < 0 || p[0] >= width as i64 || p[1] >= height as i64 {
                    return Err(
                        self.fail(i, format!("the point ({}, {}) is outside the {width} x {height} map", p[0], p[1]))
                    );
                }
            }
        }
        Ok(())
    }

    /// Every split line's ends, extended to the walls of `map` (see the module docs), in map
    /// cells.
    pub fn wall_lines(&self, map: &Grid<Cell>) -> Vec<[[f64; 2]; 2]> {
        self.list
            .iter()
            .filter_map(|e| match e {
                Edit::Split { line: [a, b] } => Some(extend_to_walls(map, *a, *b)),
                _ => None,
            })
            .collect()
    }

    /// The cells of every split wall in the world frame `frame` (for the chain's constraint), from the
    /// lines on `map` (the map in its own frame).
    pub fn world_wall_cells(&self, map: &Grid<Cell>, frame: &Frame) -> Vec<(i32, i32)> {
        let mut cells: Vec<(i32, i32)> =
            self.wall_lines(map).iter().flat_map(|&line| line_world_cells(line, frame)).collect();
        crate::sort::sort(&mut cells);
        cells.dedup();
        cells
    }

    /// Index of the unit of `world` whose interior holds map cell `p`, if any (the first).
    pub fn unit_at(world: &World, p: [i64; 2]) -> Option<usize> {
        let (x, y) = world.frame.to_world(p[0] as f64 + 0.5, p[1] as f64 + 0.5);
        let t = world.wall_thickness;
        world.units.iter().position(|u| {
            (u.x + t) as f64 <= x && x < (u.x + u.w - t) as f64 && (u.y + t) as f64 <= y && y < (u.y + u.h - t) as f64
        })
    }

    /// The type a person gave each unit of `world` (by unit id): for every type edit whose
    /// point lies in a unit, that unit; later edits win. The Markov logic inference takes these
    /// as evidence ([`crate::floorplan::knowledge::edit_facts`]).
    pub fn typed_units(&self, world: &World) -> std::collections::BTreeMap<u32, UnitType> {
        let mut by_unit = std::collections::BTreeMap::new();
        for e in &self.list {
            if let Edit::Type { at, kind } = e {
                if let Some(k) = Edits::unit_at(world, *at) {
                    by_unit.insert(world.units[k].id, *kind);
                }
            }
        }
        by_unit
    }

    /// Pairs of units (indices into `world.units`) that merges join: the units under the two
    /// points of each merge.
    pub fn merged_units(&self, world: &World) -> Vec<(usize, usize)> {
        self.list
            .iter()
            .filter_map(|e| match e {
                Edit::Merge { at: [a, b] } => Some((Edits::unit_at(world, *a)?, Edits::unit_at(world, *b)?)),
                _ => None,
            })
            .filter(|(a, b)| a != b)
            .collect()
    }

    /// Whether a split wall (cells of [`Edits::world_wall_cells`], sorted) runs between units
    /// `a` and `b`: through the band where their walls meet.
    pub fn separates(walls: &[(i32, i32)], a: Rect, b: Rect) -> bool {
        let grow = |r: Rect| Rect { x: r.x - 1, y: r.y - 1, w: r.w + 2, h: r.h + 2 };
        let Some(band) = grow(a).intersection(&grow(b)) else { return false };
        walls.iter().any(|&(x, y)| x >= band.x && x < band.right() && y >= band.y && y < band.bottom())
    }

    /// Applies the edits to a room label image (`labels.pgm`, room id per map cell, 0 for
    /// none), in order: a split gives each part of a room it divides its own id, a merge gives
    /// the room at its second point the id of the room at its first. Rooms are then numbered
    /// 1..=n in scan order. `map` is the map in its own frame.
    pub fn apply_to_labels(&self, labels: &mut Grid<u16>, map: &Grid<Cell>) {
        if self.is_empty() || (labels.width(), labels.height()) != (map.width(), map.height()) {
            return;
        }
        let lines = self.wall_lines(map);
        let mut split = 0;
        for e in &self.list {
            match e {
                Edit::Split { line: [a, b] } => {
                    let [p, q] = lines[split];
                    split += 1;
                    split_room_across(labels, *a, *b, &line_cells(p, q));
                }
                Edit::Merge { at: [a, b] } => {
                    let (la, lb) = (label_near(labels, *a), label_near(labels, *b));
                    if la != 0 && lb != 0 && la != lb {
                        for l in labels.cells_mut() {
                            if *l == lb {
                                *l = la;
                            }
                        }
                    }
                }
                _ => {}
            }
        }
        renumber(labels);
    }

    /// Applies type and name edits to the rooms read off `labels` (their `id` is the label).
    pub fn apply_to_rooms(&self, rooms: &mut [Room], labels: &Grid<u16>) {
        for e in &self.list {
            let (at, kind, name) = match e {
                Edit::Type { at, kind } => (at, Some(*kind), None),
                Edit::Name { at, name } => (at, None, Some(name)),
                _ => continue,
            };
            let l = label_near(labels, *at) as u32;
            if let Some(r) = rooms.iter_mut().find(|r| l != 0 && r.id == l) {
                if let Some(k) = kind {
                    r.kind = k;
                }
                if let Some(n) = name {
                    r.name = Some(n.clone());
                }
            }
        }
    }

    /// Whether `world` (with its room layer) and its labels respect every edit: no unit
    /// interior holds a split wall cell, the two sides of each split wall are different rooms,
    /// the points of each merge are in one room, and the rooms at type and name edits have
    /// that type and name. It assumes no two edits contradict each other (where they do, the
    /// later one wins and the earlier one is reported). For tests, and to check a world file.
    ///
    /// The first edit not respected is the error ([`EditError::Edit`]): its number, its `op`
    /// and what the world does instead.
    pub fn respected_by(&self, world: &World, labels: &Grid<u16>, map: &Grid<Cell>) -> Result<(), EditError> {
        let room_at = |p: [i64; 2]| label_near(labels, p) as u32;
        let room = |p: [i64; 2]| world.rooms.iter().find(|r| r.id == room_at(p));
        for (i, e) in self.list.iter().enumerate() {
            let broken = match e {
                Edit::Merge { at: [a, b] } => (room_at(*a) == 0 || room_at(*a) != room_at(*b))
                    .then(|| format!("the points are in rooms {} and {}", room_at(*a), room_at(*b))),
                Edit::Split { line: [a, b] } => split_broken(world, labels, map, [*a, *b]),
                Edit::Type { at, kind } => match room(*at) {
                    None => Some("no room there".into()),
                    Some(r) => (r.kind != *kind).then(|| format!("room {} is {}", r.id, r.kind.name())),
                },
                Edit::Name { at, name } => match room(*at) {
                    None => Some("no room there".into()),
                    Some(r) => {
                        (r.name.as_deref() != Some(name)).then(|| format!("room {} is named {:?}", r.id, r.name))
                    }
                },
            };
            if let Some(message) = broken {
                return Err(EditError::Edit { index: i + 1, op: e.op(), message });
            }
        }
        Ok(())
    }
}

/// The cells of one split line (in map cells) in the world frame `frame`; cells beyond the
/// range of `i32` are left out.
fn line_world_cells(line: [[f64; 2]; 2], frame: &Frame) -> impl Iterator<Item = (i32, i32)> {
    let to_world = |p: [f64; 2]| {
        let (x, y) = frame.to_world(p[0] + 0.5, p[1] + 0.5);
        [x - 0.5, y - 0.5]
    };
    let in_range = |v: i64| v >= i32::MIN as i64 && v <= i32::MAX as i64;
    line_cells(to_world(line[0]), to_world(line[1]))
        .into_iter()
        .filter(move |&(x, y)| in_range(x) && in_range(y))
        .map(|(x, y)| (x as i32, y as i32))
}

/// How `world` breaks the split edit along `line` (map cells), if it does: a unit whose
/// interior holds a cell of the wall (the line extended to the walls of `map`), or one room on
/// both sides of it.
fn split_broken(world: &World, labels: &Grid<u16>, map: &Grid<Cell>, line: [[i64; 2]; 2]) -> Option<String> {
    let wall: Vec<(i32, i32)> = line_world_cells(extend_to_walls(map, line[0], line[1]), &world.frame).collect();
    let t = world.wall_thickness;
    for u in &world.units {
        let inner = Rect { x: u.x + t, y: u.y + t, w: u.w - 2 * t, h: u.h - 2 * t };
        if wall.iter().any(|&(x, y)| x >= inner.x && x < inner.right() && y >= inner.y && y < inner.bottom()) {
            return Some(format!("unit {} crosses the split wall", u.id));
        }
    }
    match sides(labels, line[0], line[1]) {
        Some((l, r)) if l == r && l != 0 => Some(format!("room {l} lies on both sides")),
        _ => None,
    }
}

/// Keeps room ids stable from one room layer to the next while a person edits: each room of
/// `labels` takes the id of the room of `previous` it overlaps most (largest overlaps first,
/// each old id used once), the others take ids above every id in use. `labels` and `rooms`
/// (ids and `opens_to`) are renumbered to match; rooms are sorted by id. Without this the ids
/// are numbered in scan order, as `ksmcmc floorplan` writes them, and one room found above
/// another renumbers everything below it.
///
/// ```
/// use ksmcmc::floorplan::edits::carry_ids;
/// use ksmcmc::grid::Grid;
/// let previous = Grid::from_vec(4, 1, vec![7, 7, 3, 3]).unwrap();
/// // Room 1 lies where room 7 was; room 2 on the old room 3; room 3 is new.
/// let mut labels = Grid::from_vec(4, 1, vec![1, 1, 2, 3]).unwrap();
/// carry_ids(&previous, &mut labels, &mut []);
/// assert_eq!(labels.cells(), &[7, 7, 3, 8]);
/// ```
pub fn carry_ids(previous: &Grid<u16>, labels: &mut Grid<u16>, rooms: &mut [Room]) {
    if (previous.width(), previous.height()) != (labels.width(), labels.height()) {
        return;
    }
    let mut overlap: std::collections::HashMap<(u16, u16), u64> = std::collections::HashMap::new();
    for (&p, &l) in previous.cells().iter().zip(labels.cells()) {
        if p != 0 && l != 0 {
            *overlap.entry((l, p)).or_insert(0) += 1;
        }
    }
    let mut pairs: Vec<((u16, u16), u64)> = overlap.into_iter().collect();
    crate::sort::sort_by(&mut pairs, |a, b| b.1.cmp(&a.1).then(a.0.cmp(&b.0)));
    let n = labels.cells().iter().copied().max().unwrap_or(0) as usize;
    let mut new_id = vec![0u16; n + 1];
    let mut used = std::collections::HashSet::new();
    for ((l, p), _) in pairs {
        if new_id[l as usize] == 0 && used.insert(p) {
            new_id[l as usize] = p;
        }
    }
    let mut next = previous.cells().iter().copied().max().unwrap_or(0).max(new_id.iter().copied().max().unwrap_or(0));
    let mut seen = vec![false; n + 1];
    for &l in labels.cells() {
        if l != 0 && !seen[l as usize] {
            seen[l as usize] = true;
            if new_id[l as usize] == 0 {
                next = next.saturating_add(1);
                new_id[l as usize] = next;
            }
        }
    }
    for l in labels.cells_mut() {
        *l = new_id[*l as usize];
    }
    let id = |v: u32| new_id.get(v as usize).map_or(v, |&n| n as u32);
    for r in rooms.iter_mut() {
        r.id = id(r.id);
        r.opens_to = r.opens_to.iter().map(|&o| id(o)).collect();
        crate::sort::sort(&mut r.opens_to);
    }
    crate::sort::sort_by_key(rooms, |r| r.id);
}

/// The labels on either side of the middle of the split line from `a` to `b` (as the person
/// drew it: the room [`split_room_across`] divides), three cells off it (0 for none).
fn sides(labels: &Grid<u16>, a: [i64; 2], b: [i64; 2]) -> Option<(u16, u16)> {
    let (dx, dy) = ((b[0] - a[0]) as f64, (b[1] - a[1]) as f64);
    let len = (dx * dx + dy * dy).sqrt();
    if len == 0.0 {
        return None;
    }
    let (mx, my) = ((a[0] + b[0]) / 2, (a[1] + b[1]) / 2);
    let (nx, ny) = (-dy / len, dx / len);
    let at = |s: f64| [mx + libm::round(s * nx) as i64, my + libm::round(s * ny) as i64];
    Some((label_near(labels, at(3.0)), label_near(labels, at(-3.0))))
}

/// The split line from `a` to `b` with each end moved along the line, away from the other,
/// over free cells until the next cell is not free (at most [`MAX_EXTENSION_CELLS`]).
fn extend_to_walls(map: &Grid<Cell>, a: [i64; 2], b: [i64; 2]) -> [[f64; 2]; 2] {
    let (a, b) = ([a[0] as f64, a[1] as f64], [b[0] as f64, b[1] as f64]);
    let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
    let len = (dx * dx + dy * dy).sqrt().max(1e-9);
    let (ux, uy) = (dx / len, dy / len);
    let free = |p: [f64; 2]| {
        let (x, y) = (libm::round(p[0]), libm::round(p[1]));
        x >= 0.0
            && y >= 0.0
            && (x as usize) < map.width()
            && (y as usize) < map.height()
            && *map.at(x as usize, y as usize) == Cell::Free
    };
    let extend = |from: [f64; 2], sx: f64, sy: f64| {
        let mut p = from;
        for _ in 0..MAX_EXTENSION_CELLS {
            let next = [p[0] + sx, p[1] + sy];
            if !free(next) {
                return next;
            }
            p = next;
        }
        p
    };
    let start = if free(a) { extend(a, -ux, -uy) } else { a };
    let end = if free(b) { extend(b, ux, uy) } else { b };
    [start, end]
}

/// The cells of the segment from `a` to `b` (cell coordinates), 4-connected: every cell the
/// segment passes through, with a step in x and in y where it crosses a corner, so that no
/// flood fill slips through it diagonally.
///
/// ```
/// use ksmcmc::floorplan::edits::line_cells;
/// assert_eq!(line_cells([0.0, 0.0], [2.0, 0.0]), vec![(0, 0), (1, 0), (2, 0)]);
/// assert_eq!(line_cells([0.0, 0.0], [1.0, 1.0]).len(), 3);
/// ```
pub fn line_cells(a: [f64; 2], b: [f64; 2]) -> Vec<(i64, i64)> {
    let (mut x, mut y) = (libm::round(a[0]) as i64, libm::round(a[1]) as i64);
    let (x1, y1) = (libm::round(b[0]) as i64, libm::round(b[1]) as i64);
    let (dx, dy) = ((x1 - x).abs(), (y1 - y).abs());
    let (sx, sy) = ((x1 - x).signum(), (y1 - y).signum());
    let mut cells = Vec::with_capacity((dx + dy + 1).min(1 << 20) as usize);
    cells.push((x, y));
    // Walk the grid: step in x or y, whichever the line crosses first.
    let (mut ix, mut iy) = (0i64, 0i64);
    while (ix < dx || iy < dy) && cells.len() < 1 << 20 {
        if (1 + 2 * ix) * dy < (1 + 2 * iy) * dx {
            x += sx;
            ix += 1;
        } else {
            y += sy;
            iy += 1;
        }
        cells.push((x, y));
    }
    cells
}

/// The label at map cell `p`, or if that is 0 the nearest nonzero label within [`NEAR_CELLS`]
/// (by rings of growing Chebyshev distance, scan order within a ring); 0 if none.
pub fn label_near(labels: &Grid<u16>, p: [i64; 2]) -> u16 {
    let (w, h) = (labels.width() as i64, labels.height() as i64);
    for r in 0..=NEAR_CELLS {
        for y in p[1] - r..=p[1] + r {
            for x in p[0] - r..=p[0] + r {
                let ring = (x - p[0]).abs() == r || (y - p[1]).abs() == r;
                if ring && x >= 0 && y >= 0 && x < w && y < h {
                    let l = *labels.at(x as usize, y as usize);
                    if l != 0 {
                        return l;
                    }
                }
            }
        }
    }
    0
}

/// Divides the room at the middle of the line from `a` to `b` (the room a person drew the
/// line across) along the line; only that room, so that a line drawn up to an opening does not
/// cut the room beyond it. The room's cells on the `wall` become unlabelled. If the wall then
/// parts the room, each part is a room; if the room still holds together around the wall's
/// ends, its cells on one side of the line take a new id.
fn split_room_across(labels: &mut Grid<u16>, a: [i64; 2], b: [i64; 2], wall: &[(i64, i64)]) {
    let l = label_near(labels, [(a[0] + b[0]) / 2, (a[1] + b[1]) / 2]);
    if l == 0 {
        return;
    }
    let (w, h) = (labels.width(), labels.height());
    for &(x, y) in wall {
        if x >= 0 && y >= 0 && (x as usize) < w && (y as usize) < h && *labels.at(x as usize, y as usize) == l {
            *labels.at_mut(x as usize, y as usize) = 0;
        }
    }
    let mut next = labels.cells().iter().copied().max().unwrap_or(0);
    let on_wall: std::collections::HashSet<(i64, i64)> = wall.iter().copied().collect();
    let touches = |i: &usize| {
        let (x, y) = ((i % w) as i64, (i / w) as i64);
        [(x - 1, y), (x + 1, y), (x, y - 1), (x, y + 1)].iter().any(|c| on_wall.contains(c))
    };
    // Parts the wall parts (a room already in pieces elsewhere keeps those pieces).
    let mut parts: Vec<Vec<usize>> = parts_of(labels, l).into_iter().filter(|p| p.iter().any(touches)).collect();
    if parts.len() >= 2 {
        crate::sort::sort_by_key(&mut parts, |p| std::cmp::Reverse(p.len()));
        for part in &parts[1..] {
            next = next.saturating_add(1);
            for &i in part {
                labels.cells_mut()[i] = next;
            }
        }
        return;
    }
    next = next.saturating_add(1);
    let (dx, dy) = ((b[0] - a[0]) as f64, (b[1] - a[1]) as f64);
    for (i, v) in labels.cells_mut().iter_mut().enumerate() {
        let (x, y) = ((i % w) as f64 - a[0] as f64, (i / w) as f64 - a[1] as f64);
        if *v == l && dx * y - dy * x > 0.0 {
            *v = next;
        }
    }
}

/// The 4-connected parts of the cells labelled `l`, as cell indices.
fn parts_of(labels: &Grid<u16>, l: u16) -> Vec<Vec<usize>> {
    use crate::grid::flood::{Flood, Neighbours};
    let (w, h) = (labels.width(), labels.height());
    let cells = labels.cells();
    let mut seen = vec![false; w * h];
    let mut flood = Flood::default();
    let mut parts = Vec::new();
    for start in 0..w * h {
        if seen[start] || cells[start] != l {
            continue;
        }
        let mut part = Vec::new();
        let enter = |j: usize| cells[j] == l && !std::mem::replace(&mut seen[j], true);
        flood.fill(w, h, [start], Neighbours::Four, enter, |i| part.push(i));
        parts.push(part);
    }
    parts
}

/// Numbers the labels 1..=n in scan order of their first cell.
fn renumber(labels: &mut Grid<u16>) {
    let mut map = std::collections::HashMap::new();
    let mut next = 0u16;
    for l in labels.cells_mut() {
        if *l != 0 {
            *l = *map.entry(*l).or_insert_with(|| {
                next = next.saturating_add(1);
                next
            });
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_form_parses_and_writes_back() {
        let text = r#"[{"op": "merge", "at": [[1, 2], [3, 4]]}, {"op": "split", "line": [[0, 5], [9, 5]]},
            {"op": "type", "at": [2, 2], "type": "corridor"}, {"op": "name", "at": [2, 3], "name": "Kitchen"}]"#;
        let e = Edits::parse(text).unwrap();
        assert_eq!(e.len(), 4);
        assert_eq!(Edits::parse(&e.to_json()).unwrap(), e);
        assert_eq!(e.list()[2], Edit::Type { at: [2, 2], kind: UnitType::Corridor });
    }

    #[test]
    fn bad_edits_say_which_and_why() {
        let err = |t: &str| Edits::parse(t).unwrap_err().to_string();
        assert!(err("{}").contains("expected a list"), "{}", err("{}"));
        assert!(
            err(r#"[{"op": "type", "at": [1, 1], "type": "unknown"}]"#).starts_with("edit 1 (type): the type must be")
        );
        assert!(err(r#"[{"op": "type", "at": [1, 1], "type": "kitchen"}]"#).contains("unknown variant"));
        assert!(err(r#"[{"op": "name", "at": [1, 1], "name": " "}]"#).contains("1 to 200 characters"));
        assert!(err(r#"[{"op": "split", "line": [[1, 1], [2, 2]]}]"#).contains("at least 2 cells"));
        assert_eq!(
            err(r#"[{"op": "merge", "at": [[1, 1]]}]"#),
            "edit 1 (merge): `at` must be two points, [[x1, y1], [x2, y2]]"
        );
        assert_eq!(
            err(r#"[{"op": "type", "at": [[1, 1], [2, 2]], "type": "hall"}]"#),
            "edit 1 (type): `at` must be a point, [x, y]"
        );
        assert!(err(r#"[{"op": "split", "line": [[1, 1]]}]"#).contains("invalid length 1"));
        assert!(err(r#"[{"op": "merge", "at": [[1, 1], [2, 2]], "extra": 1}]"#).contains("unknown field `extra`"));
        assert!(err(r#"[{"op": "paint", "at": [1, 1]}]"#).contains("unknown variant `paint`"));
        assert_eq!(err(r#"[{"op": "name", "at": [1, 1]}]"#), "edit 1 (name): missing field `name`");
        assert_eq!(err(r#"[{"at": [1, 1], "name": "a"}]"#).split(" at line").next(), Some("edits: missing field `op`"));
        assert_eq!(
            err(r#"[{"op": "name", "at": [1, 1], "name": "a"}, {"op": "merge", "at": [[1, 1], [2, 2]], "name": "b"}]"#),
            "edit 2 (merge): `name` belongs to another op"
        );
        assert_eq!(
            err(r#"[{"op": "split", "at": [1, 1], "line": [[1, 1], [5, 1]]}]"#),
            "edit 1 (split): `at` belongs to another op"
        );
        let many = format!("[{}]", vec![r#"{"op": "name", "at": [1, 1], "name": "a"}"#; MAX_EDITS + 1].join(","));
        assert!(err(&many).contains("over the cap of 10000"));
        let e =
            Edits::parse(r#"[{"op": "name", "at": [1, 1], "name": "a"}, {"op": "merge", "at": [[1, 1], [40, 2]]}]"#)
                .unwrap();
        assert_eq!(
            e.check_map(40, 30).unwrap_err().to_string(),
            "edit 2 (merge): the point (40, 2) is outside the 40 x 30 map"
        );
        assert!(e.check_map(41, 30).is_ok());
    }

    #[test]
    fn lines_are_4_connected_and_end_where_they_should() {
        for (a, b) in
            [([0.0, 0.0], [7.0, 3.0]), ([5.0, 9.0], [0.0, 0.0]), ([2.0, 2.0], [2.0, -4.0]), ([0.0, 0.0], [4.0, 4.0])]
        {
            let cells = line_cells(a, b);
            assert_eq!(cells[0], (a[0] as i64, a[1] as i64));
            assert_eq!(*cells.last().unwrap(), (b[0] as i64, b[1] as i64));
            for p in cells.windows(2) {
                assert_eq!((p[0].0 - p[1].0).abs() + (p[0].1 - p[1].1).abs(), 1, "{a:?} {b:?}: {p:?}");
            }
        }
    }

    #[test]
    fn a_split_line_reaches_the_walls_and_divides_the_room() {
        // A 20x10 room walled all round; the user's line stops short of both walls.
        let mut map = Grid::new(22, 12, Cell::Occupied);
        for y in 1..11 {
            for x in 1..21 {
                *map.at_mut(x, y) = Cell::Free;
            }
        }
        let e = Edits::parse(r#"[{"op": "split", "line": [[10, 3], [10, 8]]}]"#).unwrap();
        // From wall to wall: each end moved onto the first wall cell past it.
        assert_eq!(e.wall_lines(&map), vec![[[10.0, 0.0], [10.0, 11.0]]]);
        let mut labels = Grid::new(22, 12, 0u16);
        for y in 1..11 {
            for x in 1..21 {
                *labels.at_mut(x, y) = 1;
            }
        }
        e.apply_to_labels(&mut labels, &map);
        assert_eq!((*labels.at(5, 5), *labels.at(15, 5), *labels.at(10, 5)), (1, 2, 0));
        assert_eq!(sides(&labels, [10, 3], [10, 8]), Some((1, 2)));
        let merged = Edits::parse(r#"[{"op": "merge", "at": [[15, 5], [2, 2]]}]"#).unwrap();
        merged.apply_to_labels(&mut labels, &map);
        assert_eq!((*labels.at(5, 5), *labels.at(15, 5)), (1, 1));
    }

    #[test]
    fn a_world_that_breaks_an_edit_is_told_which_and_how() {
        // A 20x10 room walled all round, one unit filling it, one room: a split across it and
        // a type edit for its corridor.
        let mut map = Grid::new(22, 12, Cell::Occupied);
        let mut labels = Grid::new(22, 12, 0u16);
        for y in 1..11 {
            for x in 1..21 {
                *map.at_mut(x, y) = Cell::Free;
                *labels.at_mut(x, y) = 1;
            }
        }
        let mut world = World::empty(22, 12);
        world.units.push(crate::floorplan::world::Unit::new(7, 0, 0, 22, 12, UnitType::Room));
        world.rooms.push(Room {
            id: 1,
            kind: UnitType::Room,
            units: vec![7],
            area_m2: 0.5,
            doors: Vec::new(),
            opens_to: Vec::new(),
            name: None,
        });
        let e = Edits::parse(
            r#"[{"op": "type", "at": [5, 5], "type": "room"}, {"op": "split", "line": [[10, 3], [10, 8]]}]"#,
        )
        .unwrap();
        let err = e.respected_by(&world, &labels, &map).unwrap_err();
        assert_eq!(err, EditError::Edit { index: 2, op: "split", message: "unit 7 crosses the split wall".into() });
        // Without the unit, the one room on both sides is what breaks it.
        world.units.clear();
        let err = e.respected_by(&world, &labels, &map).unwrap_err();
        assert_eq!(err.to_string(), "edit 2 (split): room 1 lies on both sides");
        // Labels split along the wall respect it; a corridor asked for where a room is does not.
        e.apply_to_labels(&mut labels, &map);
        world.rooms.push(Room { id: 2, ..world.rooms[0].clone() });
        assert_eq!(e.respected_by(&world, &labels, &map), Ok(()));
        let corridor = Edits::parse(r#"[{"op": "type", "at": [15, 5], "type": "corridor"}]"#).unwrap();
        assert_eq!(
            corridor.respected_by(&world, &labels, &map).unwrap_err().to_string(),
            "edit 1 (type): room 2 is room"
        );
    }

    #[test]
    fn the_label_near_a_wall_click_is_the_room_beside_it() {
        let mut labels = Grid::new(10, 10, 0u16);
        *labels.at_mut(7, 3) = 4;
        assert_eq!(label_near(&labels, [7, 3]), 4);
        assert_eq!(label_near(&labels, [5, 5]), 4);
        assert_eq!(label_near(&labels, [1, 9]), 4, "within {NEAR_CELLS} cells");
        assert_eq!(label_near(&labels, [0, 9]), 0, "beyond {NEAR_CELLS} cells");
        let far = Grid::new(30, 30, 0u16);
        assert_eq!(label_near(&far, [0, 0]), 0);
    }
}
