//! **The world folder** owns the world and what is read off a world alone: a person's
//! [`edits`], K(W,M) and the other [`metrics`], contacts between regions ([`topology`]) and the
//! free space no unit explains ([`unexplained`]). It imports only the geometry and the grid;
//! everything else in the floor plan imports it.
//!
//! The semantic world `W = {U, T, R}` (section 3.4): units, their types, doors, object cells.
//!
//! A [`Unit`] is an axis-aligned rectangle of cells in the *world frame*; its outermost ring of
//! cells is its four walls and the inside is its free space (eq. 3.8). Maps whose walls are not
//! parallel to the image axes are explained in a rotated world frame, described by [`Frame`], so
//! that units stay upright rectangles there.
//!
//! # `world.json`
//!
//! A world serialises to JSON as below (field order as written; unknown fields are refused so
//! that typos are caught). Coordinates are cells in the world frame, `x` right, `y` down.
//!
//! ```json
//! {
//!   "format": "ksmcmc-world/1",
//!   "frame": { "angle": 0.0, "world_size": [120, 80], "map_size": [120, 80] },
//!   "wall_thickness": 2,
//!   "units": [ { "id": 1, "x": 10, "y": 10, "w": 30, "h": 20, "type": "room" } ],
//!   "doors": [ { "id": 1, "units": [1, 2], "x0": 39, "y0": 14, "x1": 39, "y1": 18 } ],
//!   "object_cells": [[12, 14], [12, 15]],
//!   "rooms": [ { "id": 1, "type": "room", "units": [1], "area_m2": 12.5, "doors": [1],
//!                "opens_to": [2] } ],
//!   "unexplained": [ { "id": 1, "cells": 14, "x0": 50, "y0": 3, "x1": 55, "y1": 5,
//!                      "runs": [[3, 50, 55], [4, 50, 55], [5, 54, 55]] } ]
//! }
//! ```
//!
//! * `frame.angle`: radians; a world point `p` lies at map point
//!   `c_map + R(angle) (p - c_world)`, where the `c` are the centres of the two grids.
//! * `wall_thickness`: how many cells deep each unit's wall ring is (1 in the dissertation's
//!   model; optional, default 1).
//! * `units[].type`: `room`, `corridor`, `hall`, `other` or `unknown` (not yet typed).
//! * `units[].angle`: optional, radians in the convention of `frame.angle`: a unit that follows
//!   another wall direction than the frame (a wing at an angle, [`super::wings`]) lies in the
//!   frame [`Frame::turned`] gives for its angle on the same map ([`World::unit_frame`]).
//! * `doors[]`: the rectangle of cells from `(x0, y0)` to `(x1, y1)` inclusive, through the wall
//!   between the two units named by id (a straight run of cells where they share a thin wall),
//!   in the first unit's frame. A door between units of two angles (where two wings meet,
//!   [`super::wing_doors`]) crosses the first unit's wall and the second's, up to the second's
//!   interior. `"opening": true` (absent otherwise) marks a door whose two units the room
//!   layer found in one room, meeting along a passage at least 1.2 m wide: open floor within
//!   the room, not a door between rooms ([`super::rooms::doors_in_one_room`]).
//! * `object_cells`: unknown map cells inside units (furniture), optional.
//! * `rooms`: the room layer, optional (written by `ksmcmc floorplan`): what a person would
//!   call one space, one or more units each. `id` is the room's value in `labels.pgm`; `type`
//!   is `room`, `corridor`, `hall` or `other`; `units` and `doors` name units and doors by id;
//!   `area_m2` is the room's free floor area; `opens_to` names the rooms it connects to
//!   (through a door or an open boundary). See [`rooms`](super::rooms).
//! * `unexplained`: areas of free map cells that no unit or door covers (the papers' "N"),
//!   optional: each a 4-connected component with its cell count, bounding box `(x0, y0)` to
//!   `(x1, y1)` inclusive, and its cells as row runs `[y, x_first, x_last]`, top to bottom.
//!   The chain lists components of at least
//!   [`MIN_UNEXPLAINED_CELLS`](self::unexplained::MIN_UNEXPLAINED_CELLS) cells.
//!
//! # Limits
//!
//! A `world.json` may come from anyone (the pages read uploaded files), so reading one is
//! bounded before anything is allocated for it: the text is at most [`MAX_WORLD_JSON_BYTES`],
//! and each list is refused as soon as it grows past its cap while being parsed, with an error
//! naming the list and the cap. [`World::validate`] checks the same caps for worlds built in
//! code.
//!
//! | what | cap |
//! |---|---|
//! | text of `world.json` | [`MAX_WORLD_JSON_BYTES`] (64 MiB) |
//! | `units` | [`MAX_UNITS`] (10 000) |
//! | `doors` | [`MAX_DOORS`] (40 000) |
//! | `object_cells` | [`MAX_OBJECT_CELLS`] (2^20) |
//! | `rooms`, and the ids each room lists | [`MAX_ROOMS`] (100 000) |
//! | `unexplained` areas | [`MAX_UNEXPLAINED`] (100 000) |
//! | `runs` of one unexplained area | [`MAX_RUNS`] (2^20) |
//! | `placeholders` | [`MAX_PLACEHOLDERS`] (100 000) |
//! | cells of `frame.world_size` | [`MAX_WORLD_CELLS`] (2^26), and each side at most [`WORLD_FRAME_SLACK`] (4) times what the map turned into the world frame needs |
//!
//! The largest maps ([`DEFAULT_MAX_CELLS`](crate::grid::DEFAULT_MAX_CELLS), 2^25 cells) are
//! explained with a few thousand units at most; the caps leave a wide margin while keeping a
//! hostile file from asking for gigabytes (or, in wasm32, from overflowing sizes).

pub mod edits;
pub mod metrics;
pub mod topology;
pub mod unexplained;

pub use crate::geometry::{Frame, Rect};

/// Longest room name, characters (a person's name for a room, [`edits`]).
pub const MAX_NAME_CHARS: usize = 200;
use serde::{Deserialize, Deserializer, Serialize};

/// The format tag written into every `world.json`.
pub const WORLD_FORMAT: &str = "ksmcmc-world/1";

/// Longest `world.json` text read, bytes (64 MiB). The largest sample is under 300 KB.
pub const MAX_WORLD_JSON_BYTES: usize = 64 << 20;
/// Most units in a world.
pub const MAX_UNITS: usize = 10_000;
/// Most doors in a world.
pub const MAX_DOORS: usize = 40_000;
/// Most object cells in a world.
pub const MAX_OBJECT_CELLS: usize = 1 << 20;
/// Most rooms in a world's room layer, and most ids one room may list.
pub const MAX_ROOMS: usize = 100_000;
/// Most unexplained areas in a world.
pub const MAX_UNEXPLAINED: usize = 100_000;
/// Most row runs in one unexplained area.
pub const MAX_RUNS: usize = 1 << 20;
/// Most placeholders in a world.
pub const MAX_PLACEHOLDERS: usize = 100_000;
/// Most cells in the world frame (`frame.world_size`): twice the largest map
/// ([`DEFAULT_MAX_CELLS`](crate::grid::DEFAULT_MAX_CELLS)), what a square map turned by 45
/// degrees needs.
pub const MAX_WORLD_CELLS: u64 = 1 << 26;
/// How many times wider and higher than the map turned into the world frame needs (plus a
/// cell of rounding a side) `frame.world_size` may be.
pub const WORLD_FRAME_SLACK: f64 = 4.0;

/// The semantic type of a unit (the query predicates of Tab. 3.3).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize, Default)]
#[serde(rename_all = "lowercase")]
pub enum UnitType {
    /// An office, lab or other enclosed room.
    Room,
    /// A long, narrow unit connecting others.
    Corridor,
    /// A large open area.
    Hall,
    /// Anything else (stairwells, shafts, small storage).
    Other,
    /// Not typed yet (before knowledge processing).
    #[default]
    Unknown,
}

impl UnitType {
    /// All types, in a fixed order.
    pub const ALL: [UnitType; 5] =
        [UnitType::Room, UnitType::Corridor, UnitType::Hall, UnitType::Other, UnitType::Unknown];

    /// The lowercase name used in JSON and labels.
    pub fn name(self) -> &'static str {
        match self {
            UnitType::Room => "room",
            UnitType::Corridor => "corridor",
            UnitType::Hall => "hall",
            UnitType::Other => "other",
            UnitType::Unknown => "unknown",
        }
    }
}

/// One unit: a rectangle enclosed by four walls, with a type.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Unit {
    /// Identifier, unique within the world, 1-based in exported files.
    pub id: u32,
    /// Leftmost column.
    pub x: i32,
    /// Top row.
    pub y: i32,
    /// Width in cells (at least 3: two walls and free space).
    pub w: i32,
    /// Height in cells.
    pub h: i32,
    /// The unit's type.
    #[serde(rename = "type", default)]
    pub kind: UnitType,
    /// The unit's own angle, radians, in the convention of `frame.angle`, for a unit that
    /// follows another wall direction than the world frame (a wing of the building at an
    /// angle, issue 13). Its rectangle then lies in the frame [`Frame::turned`] gives for that
    /// angle on the same map ([`World::unit_frame`]). `None` (the field left out): the world
    /// frame's angle.
    #[serde(default, skip_serializing_if = "Option::is_none", deserialize_with = "crate::json::exact_opt")]
    pub angle: Option<f64>,
}

impl Unit {
    /// The unit's rectangle, in its own frame ([`World::unit_frame`]).
    pub fn rect(&self) -> Rect {
        Rect::new(self.x, self.y, self.w, self.h)
    }

    /// A unit at the world frame's angle.
    ///
    /// ```
    /// use ksmcmc::floorplan::{Unit, UnitType};
    /// let u = Unit::new(3, 10, 20, 40, 30, UnitType::Corridor);
    /// assert_eq!((u.id, u.rect().area(), u.angle), (3, 1200, None));
    /// ```
    pub fn new(id: u32, x: i32, y: i32, w: i32, h: i32, kind: UnitType) -> Unit {
        Unit { id, x, y, w, h, kind, angle: None }
    }
}

/// A door: a rectangle of cells through the wall(s) between two units, from one unit's wall to
/// the other's, predicted free. For units sharing a one-cell wall it is a straight run of cells.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Door {
    /// Identifier, unique within the world.
    pub id: u32,
    /// Ids of the two units it joins.
    pub units: [u32; 2],
    /// First cell, column.
    pub x0: i32,
    /// First cell, row.
    pub y0: i32,
    /// Last cell (inclusive), column.
    pub x1: i32,
    /// Last cell (inclusive), row.
    pub y1: i32,
    /// Whether the room layer found the two units in one room with a passage between them at
    /// least [`OPENING_MIN_M`] wide: an opening within a room (where two units of a hall meet),
    /// not a door between rooms. Written to world.json only when true.
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub opening: bool,
}

/// The narrowest passage between two units of one room that makes the door between them an
/// opening ([`Door::opening`]), m: 1.2 m, the widest single door leaf building codes provide
/// for (an accessible door); a wider passage inside one room is open floor, not a door.
pub const OPENING_MIN_M: f64 = 1.2;

impl Door {
    /// The door's width along the wall, in cells (the longer side of its rectangle).
    pub fn len(&self) -> i32 {
        (self.x1 - self.x0).abs().max((self.y1 - self.y0).abs()) + 1
    }

    /// The door's rectangle.
    pub fn rect(&self) -> Rect {
        let (x0, x1) = (self.x0.min(self.x1), self.x0.max(self.x1));
        let (y0, y1) = (self.y0.min(self.y1), self.y0.max(self.y1));
        Rect::new(x0, y0, x1 - x0 + 1, y1 - y0 + 1)
    }

    /// Doors always hold at least one cell.
    pub fn is_empty(&self) -> bool {
        false
    }

    /// The door's cells, row by row.
    pub fn cells(&self) -> impl Iterator<Item = (i32, i32)> + '_ {
        let r = self.rect();
        (r.y..r.bottom()).flat_map(move |y| (r.x..r.right()).map(move |x| (x, y)))
    }
}

/// A semantic world: the explanation of one map.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct World {
    /// Always [`WORLD_FORMAT`].
    pub format: String,
    /// How the world frame sits on the map.
    pub frame: Frame,
    /// Depth of each unit's wall ring, in cells (1 in the dissertation's model).
    #[serde(default = "one", skip_serializing_if = "is_one")]
    pub wall_thickness: i32,
    /// The units.
    #[serde(deserialize_with = "caps::units")]
    pub units: Vec<Unit>,
    /// The doors.
    #[serde(default, deserialize_with = "caps::doors")]
    pub doors: Vec<Door>,
    /// Unknown map cells inside units (furniture and clutter), world frame.
    #[serde(default, deserialize_with = "caps::object_cells")]
    pub object_cells: Vec<[i32; 2]>,
    /// The room layer: units grouped into the spaces a person would draw (optional).
    #[serde(default, skip_serializing_if = "Vec::is_empty", deserialize_with = "caps::rooms")]
    pub rooms: Vec<Room>,
    /// Free areas no unit explains (the papers' "N"), world frame.
    #[serde(default, skip_serializing_if = "Vec::is_empty", deserialize_with = "caps::unexplained")]
    pub unexplained: Vec<UnexplainedArea>,
    /// Where seen free space meets unseen space, and what lies beyond it
    /// ([`crate::floorplan::frontier`]), map frame.
    #[serde(default, skip_serializing_if = "Vec::is_empty", deserialize_with = "caps::placeholders")]
    pub placeholders: Vec<Placeholder>,
}

/// A room: what a person would call one space (an office, an L-shaped corridor, a hall cut by
/// desks), made of one or more units. Rooms are what `labels.pgm` numbers and what a robot
/// plans with: [`Room::opens_to`] is the room graph.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Room {
    /// Identifier, the room's value in the label image (1-based).
    pub id: u32,
    /// The room's type.
    #[serde(rename = "type", default)]
    pub kind: UnitType,
    /// Ids of its units (may be empty: free space the chain left unexplained can be a room).
    #[serde(deserialize_with = "caps::ids")]
    pub units: Vec<u32>,
    /// Free floor area, square metres. Read exactly (`crate::json`): a world's JSON reads
    /// back to the same text.
    #[serde(deserialize_with = "crate::json::exact")]
    pub area_m2: f64,
    /// Ids of the doors on its boundary or inside it.
    #[serde(deserialize_with = "caps::ids")]
    pub doors: Vec<u32>,
    /// Ids of the rooms it connects to, through a door or an open boundary.
    #[serde(deserialize_with = "caps::ids")]
    pub opens_to: Vec<u32>,
    /// The name a person gave it ([`self::edits`]), if any.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub name: Option<String>,
}

/// A connected area of free cells that no unit or door covers (the papers' "N"): free space
/// too small or too irregular to be a unit, or a room the chain has not found.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct UnexplainedArea {
    /// Identifier, unique within the world's unexplained areas.
    pub id: u32,
    /// Number of cells.
    pub cells: u32,
    /// Bounding box: first column.
    pub x0: i32,
    /// Bounding box: first row.
    pub y0: i32,
    /// Bounding box: last column (inclusive).
    pub x1: i32,
    /// Bounding box: last row (inclusive).
    pub y1: i32,
    /// The cells as row runs `[y, x_first, x_last]` (inclusive), top to bottom, left to right.
    #[serde(deserialize_with = "caps::runs")]
    pub runs: Vec<[i32; 3]>,
}

/// A placeholder (the CogX report on gaps in spatial knowledge, annexes 2.1 and 2.3): a
/// stretch of frontier, where free space the robot has seen meets space it has not, and what
/// going through it probably leads to ([`crate::floorplan::frontier`]).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Placeholder {
    /// Identifier, unique within the world's placeholders (1-based).
    pub id: u32,
    /// A free cell on the frontier, map column (as edits give cells).
    pub x: i32,
    /// The same cell's map row.
    pub y: i32,
    /// The frontier's width, metres (to the centimetre).
    #[serde(deserialize_with = "crate::json::exact")]
    pub width_m: f64,
    /// The id of the room it opens from (0: free space no room holds).
    pub room: u32,
    /// The probability that going through it leads to a room not yet in the map.
    #[serde(deserialize_with = "crate::json::exact")]
    pub p_new_room: f64,
    /// The probability of each type for the space it leads to, given that a room, corridor,
    /// hall or other space lies beyond (they sum to 1).
    pub types: TypeProbabilities,
}

/// A probability per room type (they sum to 1).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TypeProbabilities {
    /// An office, lab or other enclosed room.
    #[serde(deserialize_with = "crate::json::exact")]
    pub room: f64,
    /// A corridor.
    #[serde(deserialize_with = "crate::json::exact")]
    pub corridor: f64,
    /// A hall.
    #[serde(deserialize_with = "crate::json::exact")]
    pub hall: f64,
    /// Anything else (stairwells, shafts, small storage).
    #[serde(deserialize_with = "crate::json::exact")]
    pub other: f64,
}

impl TypeProbabilities {
    /// The four probabilities in the order room, corridor, hall, other.
    pub fn as_array(&self) -> [f64; 4] {
        [self.room, self.corridor, self.hall, self.other]
    }
}

/// Lists that stop growing at their cap while `world.json` is parsed (see the module's
/// Limits), so that a hostile file is refused before it is held in memory.
mod caps {
    use super::*;
    use serde::de::{Error, SeqAccess, Visitor};

    struct Capped<T> {
        max: usize,
        what: &'static str,
        _item: std::marker::PhantomData<T>,
    }

    impl<'de, T: Deserialize<'de>> Visitor<'de> for Capped<T> {
        type Value = Vec<T>;

        fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
            write!(f, "a list of at most {} {}", self.max, self.what)
        }

        fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Vec<T>, A::Error> {
            let mut out = Vec::with_capacity(seq.size_hint().unwrap_or(0).min(1024));
            while let Some(item) = seq.next_element()? {
                if out.len() == self.max {
                    return Err(A::Error::custom(format!(
                        "too many {what}: over the cap of {max} (ksmcmc::floorplan::world, Limits); the file is \
                         damaged or not a ksmcmc world. Refused",
                        max = self.max,
                        what = self.what
                    )));
                }
                out.push(item);
            }
            Ok(out)
        }
    }

    fn capped<'de, D: Deserializer<'de>, T: Deserialize<'de>>(
        d: D,
        max: usize,
        what: &'static str,
    ) -> Result<Vec<T>, D::Error> {
        d.deserialize_seq(Capped { max, what, _item: std::marker::PhantomData })
    }

    pub fn units<'de, D: Deserializer<'de>>(d: D) -> Result<Vec<Unit>, D::Error> {
        capped(d, MAX_UNITS, "units")
    }

    pub fn doors<'de, D: Deserializer<'de>>(d: D) -> Result<Vec<Door>, D::Error> {
        capped(d, MAX_DOORS, "doors")
    }

    pub fn object_cells<'de, D: Deserializer<'de>>(d: D) -> Result<Vec<[i32; 2]>, D::Error> {
        capped(d, MAX_OBJECT_CELLS, "object cells")
    }

    pub fn rooms<'de, D: Deserializer<'de>>(d: D) -> Result<Vec<Room>, D::Error> {
        capped(d, MAX_ROOMS, "rooms")
    }

    pub fn ids<'de, D: Deserializer<'de>>(d: D) -> Result<Vec<u32>, D::Error> {
        capped(d, MAX_ROOMS, "ids in one room's list")
    }

    pub fn unexplained<'de, D: Deserializer<'de>>(d: D) -> Result<Vec<UnexplainedArea>, D::Error> {
        capped(d, MAX_UNEXPLAINED, "unexplained areas")
    }

    pub fn placeholders<'de, D: Deserializer<'de>>(d: D) -> Result<Vec<Placeholder>, D::Error> {
        capped(d, MAX_PLACEHOLDERS, "placeholders")
    }

    pub fn runs<'de, D: Deserializer<'de>>(d: D) -> Result<Vec<[i32; 3]>, D::Error> {
        capped(d, MAX_RUNS, "runs in one unexplained area")
    }
}

fn one() -> i32 {
    1
}

fn is_one(t: &i32) -> bool {
    *t == 1
}

/// The units and doors of a world that lie in one frame ([`World::frame_groups`]).
#[derive(Debug, Clone, PartialEq)]
pub struct FrameGroup {
    /// The frame.
    pub frame: Frame,
    /// Indices into the world's `units`.
    pub units: Vec<usize>,
    /// Indices into the world's `doors`.
    pub doors: Vec<usize>,
}

impl FrameGroup {
    /// Per unit of a world of `units` units, the index in `groups` (its
    /// [`World::frame_groups`]) of the group the unit lies in, `usize::MAX` for none.
    pub fn of_units(groups: &[FrameGroup], units: usize) -> Vec<usize> {
        let mut group_of = vec![usize::MAX; units];
        for (k, g) in groups.iter().enumerate() {
            g.units.iter().for_each(|&i| group_of[i] = k);
        }
        group_of
    }
}

/// Why a `world.json` was refused.
#[derive(Debug, Clone, PartialEq)]
pub struct WorldError {
    message: String,
}

impl WorldError {
    /// The error with `message`, which says what was refused and how to put it right.
    pub(crate) fn new(message: impl Into<String>) -> WorldError {
        WorldError { message: message.into() }
    }
}

impl std::fmt::Display for WorldError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.message)
    }
}

impl std::error::Error for WorldError {}

impl World {
    /// An empty world on a map of the given size, upright.
    pub fn empty(width: u32, height: u32) -> Self {
        World {
            format: WORLD_FORMAT.to_string(),
            frame: Frame::identity(width, height),
            wall_thickness: 1,
            units: Vec::new(),
            doors: Vec::new(),
            object_cells: Vec::new(),
            rooms: Vec::new(),
            unexplained: Vec::new(),
            placeholders: Vec::new(),
        }
    }

    /// The unit with the given id.
    pub fn unit(&self, id: u32) -> Option<&Unit> {
        self.units.iter().find(|u| u.id == id)
    }

    /// The room of each unit, by unit id: the first room in `rooms` that lists it. The room
    /// layer gives each unit one room; units no room lists are absent.
    ///
    /// ```
    /// use ksmcmc::floorplan::{Room, UnitType, World};
    /// let mut w = World::empty(100, 60);
    /// let (doors, opens_to, name) = (vec![], vec![], None);
    /// w.rooms = vec![Room { id: 7, kind: UnitType::Room, units: vec![1, 2], area_m2: 12.0, doors, opens_to, name }];
    /// let rooms = w.rooms_of_units();
    /// assert_eq!((rooms.get(&2), rooms.get(&3)), (Some(&7), None));
    /// ```
    pub fn rooms_of_units(&self) -> std::collections::HashMap<u32, u32> {
        let mut out = std::collections::HashMap::new();
        for r in &self.rooms {
            for &u in &r.units {
                out.entry(u).or_insert(r.id);
            }
        }
        out
    }

    /// The frame `unit`'s rectangle lies in: the world frame, or, for a unit with an angle of
    /// its own (issue 13), the frame [`Frame::turned`] gives for that angle on the same map.
    ///
    /// ```
    /// use ksmcmc::floorplan::{Unit, UnitType, World};
    /// let w = World::empty(100, 60);
    /// let upright = Unit::new(1, 0, 0, 10, 10, UnitType::Room);
    /// assert_eq!(w.unit_frame(&upright), w.frame);
    /// let turned = Unit { angle: Some(0.5), ..upright };
    /// let f = w.unit_frame(&turned);
    /// assert_eq!((f.angle, f.map_size), (0.5, [100, 60]));
    /// assert!(f.world_size[0] > 100 && f.world_size[1] > 60);
    /// ```
    #[inline(never)] // one copy in the size-budgeted mapper module, not one per caller
    pub fn unit_frame(&self, unit: &Unit) -> Frame {
        match unit.angle {
            Some(a) if a != self.frame.angle => Frame::turned(self.frame.map_size[0], self.frame.map_size[1], a),
            _ => self.frame,
        }
    }

    /// The frames the units lie in, the world frame first, each with the indices of its units
    /// and of its doors (a door lies in its first unit's frame, the world frame if that unit
    /// does not exist), found in one pass over each list: what drawing and rasterising a world
    /// of units at several angles works through frame by frame. Units whose angle is not a
    /// finite number belong to no frame.
    pub fn frame_groups(&self) -> Vec<FrameGroup> {
        // Plain vectors and linear searches over the (few) frames, no maps: this runs in the
        // size-budgeted mapper module.
        let mut groups = vec![FrameGroup { frame: self.frame, units: Vec::new(), doors: Vec::new() }];
        let mut group_of = vec![usize::MAX; self.units.len()];
        let mut last = 0;
        for (i, u) in self.units.iter().enumerate() {
            let frame = self.unit_frame(u);
            if !frame.angle.is_finite() {
                continue;
            }
            if groups[last].frame != frame {
                last = groups.iter().position(|g| g.frame == frame).unwrap_or_else(|| {
                    groups.push(FrameGroup { frame, units: Vec::new(), doors: Vec::new() });
                    groups.len() - 1
                });
            }
            groups[last].units.push(i);
            group_of[i] = last;
        }
        for (i, d) in self.doors.iter().enumerate() {
            match self.unit_index(d.units[0]) {
                Some(u) if group_of[u] != usize::MAX => groups[group_of[u]].doors.push(i),
                Some(_) => {}
                None => groups[0].doors.push(i),
            }
        }
        groups
    }

    /// The index in `units` of the unit with this id: at once where ids follow the order
    /// (as every world this crate writes has them), else by a search.
    pub(crate) fn unit_index(&self, id: u32) -> Option<usize> {
        let at = (id as usize).wrapping_sub(1);
        match self.units.get(at) {
            Some(u) if u.id == id => Some(at),
            _ => self.units.iter().position(|u| u.id == id),
        }
    }

    /// The frame a door's cells lie in: its first unit's (the other's too, but for a door
    /// between two wings, [`super::wing_doors`]).
    pub fn door_frame(&self, door: &Door) -> Frame {
        self.unit(door.units[0]).map_or(self.frame, |u| self.unit_frame(u))
    }

    /// Whether every unit lies in the world frame (none has an angle of its own).
    pub fn is_one_direction(&self) -> bool {
        self.units.iter().all(|u| self.unit_frame(u) == self.frame)
    }

    /// An error for the tools that draw or plan on the world frame alone when a unit has an
    /// angle of its own: `what` names the tool.
    pub fn require_one_direction(&self, what: &str) -> Result<(), WorldError> {
        match self.units.iter().find(|u| self.unit_frame(u) != self.frame) {
            Some(u) => Err(WorldError::new(format!(
                "world.json: unit {} has an angle of its own ({} rad, the frame's is {}); {what} handles \
                 units in the world frame only so far (issue 13)",
                u.id,
                u.angle.unwrap_or_default(),
                self.frame.angle
            ))),
            None => Ok(()),
        }
    }

    /// Pretty JSON text.
    pub fn to_json(&self) -> String {
        serde_json::to_string_pretty(self).expect("a world always serialises")
    }

    /// Parses and validates `world.json` text.
    ///
    /// ```
    /// use ksmcmc::floorplan::World;
    /// let mut w = World::empty(20, 10);
    /// w.units.push(ksmcmc::floorplan::Unit::new(1, 0, 0, 5, 5, Default::default()));
    /// let back = World::from_json(&w.to_json()).unwrap();
    /// assert_eq!(back, w);
    /// assert!(World::from_json("{").is_err());
    /// ```
    pub fn from_json(text: &str) -> Result<World, WorldError> {
        if text.len() > MAX_WORLD_JSON_BYTES {
            return Err(WorldError::new(format!(
                "world.json: the text is {} bytes, over the limit of {MAX_WORLD_JSON_BYTES} bytes \
                 (MAX_WORLD_JSON_BYTES); a world of this size is damaged or not a ksmcmc world",
                text.len()
            )));
        }
        let w: World = serde_json::from_str(text).map_err(|e| WorldError::new(format!("world.json: {e}")))?;
        w.validate()?;
        Ok(w)
    }

    /// Checks that this world belongs to a `map_width` x `map_height` map: its frame was made
    /// for a map of that size, and every unit lands at least partly on the map (checked on
    /// the bounding box of its corners). [`World::validate`] keeps units inside the world
    /// frame; in a rotated or larger frame a unit can still miss the map entirely.
    ///
    /// ```
    /// use ksmcmc::floorplan::{Unit, World};
    /// let mut w = World::empty(64, 40);
    /// assert!(w.fits(64, 40).is_ok());
    /// let e = w.fits(100, 100).unwrap_err().to_string();
    /// assert!(e.contains("explains a 64x40 map, but the map is 100x100"), "{e}");
    /// w.frame.world_size = [200, 40];
    /// w.units.push(Unit::new(7, 190, 0, 10, 10, Default::default())); // frames share their centre
    /// let e = w.fits(64, 40).unwrap_err().to_string();
    /// assert!(e.contains("unit 7 (10x10 at 190,0) lies entirely outside the 64x40 map"), "{e}");
    /// ```
    pub fn fits(&self, map_width: usize, map_height: usize) -> Result<(), WorldError> {
        let [fw, fh] = self.frame.map_size;
        if [fw as usize, fh as usize] != [map_width, map_height] {
            return Err(WorldError::new(format!(
                "world.json: this world explains a {fw}x{fh} map, but the map is {map_width}x{map_height} \
                 cells (see frame.map_size): it was made for a different map (or the map was cropped or \
                 resized since)"
            )));
        }
        match self.units.iter().find(|u| !self.touches_map(u, map_width, map_height)) {
            Some(u) => Err(WorldError::new(format!(
                "world.json: unit {} ({}x{} at {},{}) lies entirely outside the {map_width}x{map_height} map",
                u.id, u.w, u.h, u.x, u.y
            ))),
            None => Ok(()),
        }
    }

    /// Whether any part of `unit` lands on the map (checked on the bounding box of its corners).
    fn touches_map(&self, unit: &Unit, w: usize, h: usize) -> bool {
        let [min_x, min_y, max_x, max_y] = self.unit_frame(unit).map_box(unit.rect());
        max_x > 0.0 && max_y > 0.0 && min_x < w as f64 && min_y < h as f64
    }

    /// Checks the format tag, frame, unit geometry and door references.
    pub fn validate(&self) -> Result<(), WorldError> {
        let bad = |m: String| Err(WorldError::new(m));
        if self.format != WORLD_FORMAT {
            return bad(format!("world.json: format is {:?}, expected {WORLD_FORMAT:?}", self.format));
        }
        let f = &self.frame;
        if !f.angle.is_finite() || f.world_size.contains(&0) || f.map_size.contains(&0) {
            return bad("world.json: the frame needs a finite angle and non-zero sizes".into());
        }
        if !(1..=20).contains(&self.wall_thickness) {
            return bad(format!("world.json: wall_thickness {} is not between 1 and 20", self.wall_thickness));
        }
        self.validate_sizes()?;
        let [ww, wh] = [f.world_size[0] as i64, f.world_size[1] as i64];
        let mut ids = std::collections::HashSet::new();
        for u in &self.units {
            if !ids.insert(u.id) {
                return bad(format!("world.json: unit id {} appears twice", u.id));
            }
            if u.w < 1 || u.h < 1 {
                return bad(format!("world.json: unit {} has size {}x{}", u.id, u.w, u.h));
            }
            if u.angle.is_some_and(|a| !(a.is_finite() && a.abs() <= std::f64::consts::TAU)) {
                return bad(format!("world.json: unit {} has an angle that is not between -2π and 2π", u.id));
            }
            let [ww, wh] = self.unit_frame(u).world_size.map(i64::from);
            let (x0, y0) = (u.x as i64, u.y as i64);
            if x0 < 0 || y0 < 0 || x0 + u.w as i64 > ww || y0 + u.h as i64 > wh {
                return bad(format!(
                    "world.json: unit {} ({}x{} at {},{}) lies outside the {}x{} world",
                    u.id, u.w, u.h, u.x, u.y, ww, wh
                ));
            }
        }
        for d in &self.doors {
            for id in d.units {
                if !ids.contains(&id) {
                    return bad(format!("world.json: door {} names unit {id}, which does not exist", d.id));
                }
            }
            let [ww, wh] = self.door_frame(d).world_size.map(i64::from);
            for (x, y) in [(d.x0, d.y0), (d.x1, d.y1)] {
                if x < 0 || y < 0 || x as i64 >= ww || y as i64 >= wh {
                    return bad(format!("world.json: door {} has a cell ({x},{y}) outside the world", d.id));
                }
            }
        }
        for c in &self.object_cells {
            if c[0] < 0 || c[1] < 0 || c[0] as i64 >= ww || c[1] as i64 >= wh {
                return bad(format!("world.json: object cell ({},{}) lies outside the world", c[0], c[1]));
            }
        }
        self.validate_rooms(&ids)?;
        self.validate_placeholders()?;
        for a in &self.unexplained {
            let mut sum = 0u64;
            for r in &a.runs {
                let [y, x0, x1] = *r;
                if y < a.y0 || y > a.y1 || x0 > x1 || x0 < a.x0 || x1 > a.x1 {
                    return bad(format!(
                        "world.json: unexplained area {} has a run [{y}, {x0}, {x1}] outside its box or reversed",
                        a.id
                    ));
                }
                sum += (x1 - x0 + 1) as u64;
            }
            if a.x0 < 0 || a.y0 < 0 || a.x1 as i64 >= ww || a.y1 as i64 >= wh {
                return bad(format!("world.json: unexplained area {} lies outside the world", a.id));
            }
            if sum != a.cells as u64 {
                return bad(format!(
                    "world.json: unexplained area {} says {} cells but its runs hold {sum}",
                    a.id, a.cells
                ));
            }
        }
        Ok(())
    }

    /// The caps of the module's Limits, and a world frame no larger than the map needs.
    fn validate_sizes(&self) -> Result<(), WorldError> {
        let counts = [
            (self.units.len(), MAX_UNITS, "units"),
            (self.doors.len(), MAX_DOORS, "doors"),
            (self.object_cells.len(), MAX_OBJECT_CELLS, "object cells"),
            (self.rooms.len(), MAX_ROOMS, "rooms"),
            (self.unexplained.len(), MAX_UNEXPLAINED, "unexplained areas"),
            (self.placeholders.len(), MAX_PLACEHOLDERS, "placeholders"),
        ];
        for (n, max, what) in counts {
            if n > max {
                return Err(WorldError::new(format!("world.json: {n} {what}, over the limit of {max} {what}")));
            }
        }
        let f = &self.frame;
        let [ww, wh] = f.world_size;
        let cells = ww as u64 * wh as u64;
        if cells > MAX_WORLD_CELLS {
            return Err(WorldError::new(format!(
                "world.json: frame.world_size {ww}x{wh} is {cells} cells, over the limit of {MAX_WORLD_CELLS} \
                 (MAX_WORLD_CELLS)"
            )));
        }
        // The world frame holds the map turned by `angle` (its bounding box); a larger frame
        // is allowed, but not more than WORLD_FRAME_SLACK times as wide or high.
        let [mw, mh] = f.map_size.map(f64::from);
        let (s, c) = (libm::fabs(libm::sin(f.angle)), libm::fabs(libm::cos(f.angle)));
        let need = [libm::ceil(mw * c + mh * s), libm::ceil(mw * s + mh * c)].map(|v| WORLD_FRAME_SLACK * (v + 2.0));
        if ww as f64 > need[0] || wh as f64 > need[1] {
            return Err(WorldError::new(format!(
                "world.json: frame.world_size {ww}x{wh} is far larger than the {}x{} map (frame.map_size) \
                 turned by frame.angle {} needs (at most {}x{}); the frame is damaged",
                f.map_size[0], f.map_size[1], f.angle, need[0], need[1]
            )));
        }
        for r in &self.rooms {
            if r.units.len().max(r.doors.len()).max(r.opens_to.len()) > MAX_ROOMS {
                return Err(WorldError::new(format!("world.json: room {} lists over {MAX_ROOMS} ids", r.id)));
            }
        }
        match self.unexplained.iter().find(|a| a.runs.len() > MAX_RUNS) {
            Some(a) => Err(WorldError::new(format!("world.json: unexplained area {} has over {MAX_RUNS} runs", a.id))),
            None => Ok(()),
        }
    }

    /// Placeholders on the map, opening from a room that exists (or none), with probabilities.
    fn validate_placeholders(&self) -> Result<(), WorldError> {
        let bad = |m: String| Err(WorldError::new(format!("world.json: placeholder {m}")));
        let [mw, mh] = self.frame.map_size.map(i64::from);
        for p in &self.placeholders {
            let id = p.id;
            if p.x < 0 || p.y < 0 || p.x as i64 >= mw || p.y as i64 >= mh {
                return bad(format!("{id}: cell ({},{}) lies outside the {mw}x{mh} map", p.x, p.y));
            }
            if p.room != 0 && !self.rooms.iter().any(|r| r.id == p.room) {
                return bad(format!("{id}: opens from room {}, which does not exist", p.room));
            }
            if !(p.width_m.is_finite() && p.width_m >= 0.0) {
                return bad(format!("{id}: width_m {} is not a length", p.width_m));
            }
            let types = p.types.as_array();
            let probability = |v: f64| (0.0..=1.0).contains(&v);
            if !probability(p.p_new_room) || !types.into_iter().all(probability) {
                return bad(format!("{id}: a probability lies outside [0, 1]"));
            }
            if (types.iter().sum::<f64>() - 1.0).abs() > 0.01 {
                return bad(format!("{id}: the type probabilities sum to {}, not 1", types.iter().sum::<f64>()));
            }
        }
        Ok(())
    }

    /// Room ids unique and non-zero; the units, doors and rooms each room names exist.
    fn validate_rooms(&self, unit_ids: &std::collections::HashSet<u32>) -> Result<(), WorldError> {
        let bad = |m: String| Err(WorldError::new(format!("world.json: {m}")));
        let room_ids: std::collections::HashSet<u32> = self.rooms.iter().map(|r| r.id).collect();
        let door_ids: std::collections::HashSet<u32> = self.doors.iter().map(|d| d.id).collect();
        if room_ids.len() != self.rooms.len() || room_ids.contains(&0) {
            return bad("room ids must be distinct and non-zero".into());
        }
        for r in &self.rooms {
            if !(r.area_m2.is_finite() && r.area_m2 >= 0.0) {
                return bad(format!("room {} has area {}", r.id, r.area_m2));
            }
            if let Some(u) = r.units.iter().find(|u| !unit_ids.contains(u)) {
                return bad(format!("room {} names unit {u}, which does not exist", r.id));
            }
            if let Some(d) = r.doors.iter().find(|d| !door_ids.contains(d)) {
                return bad(format!("room {} names door {d}, which does not exist", r.id));
            }
            if let Some(o) = r.opens_to.iter().find(|o| !room_ids.contains(o)) {
                return bad(format!("room {} opens to room {o}, which does not exist", r.id));
            }
            if r.name.as_ref().is_some_and(|n| n.chars().count() > MAX_NAME_CHARS) {
                return bad(format!("room {} has a name over {} characters", r.id, MAX_NAME_CHARS));
            }
        }
        Ok(())
    }
}
