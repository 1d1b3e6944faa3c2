//! The chain's world state: units and doors over an [`Explanation`], changed by [`Move`]s that
//! can be undone exactly.
//!
//! A proposal is checked first ([`State::is_valid`]), applied, scored, and then either kept or
//! undone. Undo restores the state bit for bit (unit order and ids included), so a rejected
//! proposal leaves no trace and the chain stays deterministic.

use super::explain::Explanation;
use crate::floorplan::world::{Rect, Unit, UnitType};
pub use crate::geometry::{facing, Axis};
use crate::geometry::{AreaCounts, CellCounts};
use crate::grid::{Cell, Grid};
use crate::setting::{check, InvalidSetting};

/// A door between two units, by unit id; its rectangle follows the units' walls.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct DoorSpec {
    /// The left (or upper) unit's id.
    pub lo: u32,
    /// The right (or lower) unit's id.
    pub hi: u32,
    /// Orientation.
    pub axis: Axis,
    /// First row (or column) of the opening.
    pub start: i32,
    /// Last row (or column) of the opening, inclusive.
    pub end: i32,
}

/// Geometry limits for doors in cells of one map: [`DoorSizes`] turned into cells from the
/// map's resolution ([`DoorSizes::cells`]). The chain's state and kernels read these.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DoorLimits {
    /// Shortest door.
    pub min_len: i32,
    /// Longest door.
    pub max_len: i32,
    /// Largest distance between the two walls a door crosses (wall thickness).
    pub max_gap: i32,
}

impl Default for DoorLimits {
    /// [`DoorSizes::default`] on a map of 5 cm cells (the benchmark floors' and the generated
    /// floors' cell), for examples and tests that draw their maps in cells.
    fn default() -> Self {
        DoorSizes::default().cells(0.05)
    }
}

/// The sizes a door may have, metres: the chain's door limits as the configuration gives them
/// (`ChainConfig::doors`), turned into cells once from the map's resolution.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct DoorSizes {
    /// Shortest door, m. 0.5 m: narrower than any door a person walks through (interior door
    /// leaves are 0.6 m and more) with room for a laser's noise at the jambs.
    pub min_m: f64,
    /// Longest door, m. 2.0 m: a double door; a wider passage is open floor.
    pub max_m: f64,
    /// Largest distance between the two walls a door crosses, m. 0.5 m: the thickest interior
    /// walls and the unseen cores of walls seen from both sides.
    pub max_gap_m: f64,
}

impl Default for DoorSizes {
    fn default() -> Self {
        DoorSizes { min_m: 0.5, max_m: 2.0, max_gap_m: 0.5 }
    }
}

impl DoorSizes {
    /// These sizes in cells of `resolution` metres, rounded to whole cells (a door at least one
    /// cell long). A resolution that is not a positive number is read as 0.05 m.
    ///
    /// ```
    /// use ksmcmc::floorplan::{DoorLimits, DoorSizes};
    /// assert_eq!(DoorSizes::default().cells(0.05), DoorLimits { min_len: 10, max_len: 40, max_gap: 10 });
    /// assert_eq!(DoorSizes::default().cells(0.1), DoorLimits { min_len: 5, max_len: 20, max_gap: 5 });
    /// ```
    pub fn cells(&self, resolution: f64) -> DoorLimits {
        let r = crate::grid::cell_size_m(resolution);
        let cells = |m: f64| libm::round(m / r).clamp(0.0, 1e6) as i32;
        DoorLimits {
            min_len: cells(self.min_m).max(1),
            max_len: cells(self.max_m).max(1),
            max_gap: cells(self.max_gap_m),
        }
    }

    /// Checks the sizes: finite, `0 < min_m <= max_m`, and `0 <= max_gap_m <= 5`.
    pub fn validate(&self) -> Result<(), InvalidSetting> {
        check(self.min_m > 0.0 && self.min_m <= self.max_m, "min_m", self.min_m, "metres above 0, at most max_m")?;
        check(self.max_m <= 1e3, "max_m", self.max_m, "metres, at most 1000")?;
        check((0.0..=5.0).contains(&self.max_gap_m), "max_gap_m", self.max_gap_m, "metres from 0 to 5")
    }
}

/// Whether `r` is big enough for a unit: both sides at least `min_side` and longer than two
/// walls `wall` deep, so that a unit has a free interior. Every proposal source (the
/// kernels, the detectors' candidates, the free-space detector) uses this one bound.
pub fn fits_unit(r: Rect, min_side: i32, wall: i32) -> bool {
    let side = min_side.max(2 * wall + 1);
    r.w >= side && r.h >= side
}

/// The rectangle of a door between `lo` and `hi`, or `None` if they no longer face each other
/// over the door's span.
pub fn door_rect(lo: Rect, hi: Rect, d: &DoorSpec, limits: &DoorLimits, t: i32) -> Option<Rect> {
    let (s, e) = facing(lo, hi, d.axis, limits.max_gap, t)?;
    let len = d.end - d.start + 1;
    if d.start < s || d.end > e || len < limits.min_len || len > limits.max_len {
        return None;
    }
    Some(match d.axis {
        Axis::Horizontal => Rect::new(lo.right() - t, d.start, hi.x - lo.right() + 2 * t, len),
        Axis::Vertical => Rect::new(d.start, lo.bottom() - t, len, hi.y - lo.bottom() + 2 * t),
    })
}

/// A proposed change to the world.
#[derive(Debug, Clone, PartialEq)]
pub enum Move {
    /// Add a unit with this rectangle.
    Add(Rect),
    /// Remove the unit at this index.
    Remove(usize),
    /// Replace the unit at `index` by two units.
    Split {
        /// The unit split.
        index: usize,
        /// The part that keeps the unit's slot.
        first: Rect,
        /// The part appended.
        second: Rect,
    },
    /// Replace units `i` and `j` by one unit.
    Merge {
        /// First unit (its slot receives the merged unit).
        i: usize,
        /// Second unit (removed).
        j: usize,
        /// The merged rectangle.
        merged: Rect,
    },
    /// Move walls of one unit (SHRINK or DILATE).
    Reshape {
        /// The unit.
        index: usize,
        /// Its new rectangle.
        rect: Rect,
    },
    /// Re-partition two units (INTERCHANGE).
    Repartition {
        /// First unit.
        i: usize,
        /// Second unit.
        j: usize,
        /// New rectangle of unit `i`.
        a: Rect,
        /// New rectangle of unit `j`.
        b: Rect,
    },
    /// Add a door.
    Allocate(DoorSpec),
    /// Remove the door at this index.
    Delete(usize),
}

/// What is needed to undo an applied move.
#[derive(Debug, Clone)]
pub enum Undo {
    /// Pop the last unit.
    Added,
    /// Put `unit` back at `index`.
    Removed {
        /// Where it was.
        index: usize,
        /// The unit.
        unit: Unit,
    },
    /// Restore units (index, old unit) and truncate to `len` units.
    Replaced {
        /// Old units by slot.
        old: [(usize, Unit); 2],
        /// How many old entries are meaningful.
        count: usize,
        /// Unit count before the move.
        len: usize,
    },
    /// Undo a MERGE of units `i` and `j`.
    Merged {
        /// Slot of the first unit.
        i: usize,
        /// Slot the second unit was removed from.
        j: usize,
        /// The first unit.
        ui: Unit,
        /// The second unit.
        uj: Unit,
    },
    /// Pop the last door.
    Allocated,
    /// Put a door back.
    Deleted {
        /// Where it was.
        index: usize,
        /// The door.
        door: DoorSpec,
    },
}

/// Units, doors and their explanation of the map.
#[derive(Debug, Clone)]
pub struct State {
    /// The incremental likelihood bookkeeping.
    pub explanation: Explanation,
    counts: CellCounts,
    /// The units, in slot order.
    pub units: Vec<Unit>,
    /// The doors.
    pub doors: Vec<DoorSpec>,
    /// Next unit id.
    pub next_id: u32,
    /// Changes whenever unit geometry changes (restored on undo), for caches.
    pub generation: u64,
    generation_counter: u64,
    /// Door geometry limits.
    pub door_limits: DoorLimits,
    /// Depth of every unit's wall ring, cells.
    pub wall: i32,
    width: i32,
    height: i32,
    /// The cells no unit interior may hold (a person's split walls, [`State::forbid`]),
    /// counted as occupied cells; `None` when there are none.
    forbidden: Option<AreaCounts>,
}

impl State {
    /// An empty world over a world-frame classified map.
    pub fn new(map: &Grid<Cell>, door_limits: DoorLimits, wall: i32) -> Self {
        State {
            explanation: Explanation::new(map),
            counts: CellCounts::new(map),
            units: Vec::new(),
            doors: Vec::new(),
            next_id: 1,
            generation: 0,
            generation_counter: 0,
            door_limits,
            wall: wall.max(1),
            width: map.width() as i32,
            height: map.height() as i32,
            forbidden: None,
        }
    }

    /// From now on, no unit's interior (inside its wall ring) may hold any of `cells` (world
    /// frame; those off the grid are ignored): every move that would make such a unit is
    /// invalid ([`State::is_valid`]). An empty list lifts the constraint. Units that already
    /// break it stay until [`State::breaks_forbidden`] finds them and they are removed.
    pub fn forbid(&mut self, cells: &[(i32, i32)]) {
        let mut marked = Grid::new(self.width as usize, self.height as usize, Cell::Free);
        let mut any = false;
        for &(x, y) in cells {
            if x >= 0 && y >= 0 && x < self.width && y < self.height {
                *marked.at_mut(x as usize, y as usize) = Cell::Occupied;
                any = true;
            }
        }
        self.forbidden = any.then(|| AreaCounts::new(&marked, Cell::Occupied));
    }

    /// Whether the interior of a unit with rectangle `r` holds a forbidden cell.
    pub fn breaks_forbidden(&self, r: Rect) -> bool {
        let t = self.wall;
        let inner = Rect { x: r.x + t, y: r.y + t, w: r.w - 2 * t, h: r.h - 2 * t };
        self.forbidden.as_ref().is_some_and(|f| f.count(inner) > 0)
    }

    /// Sets the depth of every unit's wall ring, `wall` cells (at least 1), in a world with no
    /// units: the explanation of an empty world does not depend on it.
    pub fn set_wall(&mut self, wall: i32) {
        debug_assert!(self.units.is_empty() && self.doors.is_empty());
        if self.units.is_empty() && self.doors.is_empty() {
            self.wall = wall.max(1);
        }
    }

    /// Takes a changed world-frame map: the cells listed in `changed` (row-major indices) now
    /// have the classes `map` gives them. The explanation changes only there; the cell counts
    /// are counted again.
    pub fn set_map(&mut self, map: &Grid<Cell>, changed: &[usize]) {
        let cells = map.cells();
        for &i in changed {
            self.explanation.set_map_class(i, cells[i]);
        }
        self.counts = CellCounts::new(map);
    }

    /// Grid width.
    pub fn width(&self) -> i32 {
        self.width
    }

    /// Grid height.
    pub fn height(&self) -> i32 {
        self.height
    }

    /// The map's cell counts, for the detectors.
    pub fn counts(&self) -> &CellCounts {
        &self.counts
    }

    /// Occupied cells inside a rectangle.
    pub fn occupied_in(&self, r: Rect) -> u32 {
        self.counts.occupied_in(r)
    }

    /// Free cells inside a rectangle (see [`CellCounts::free_in`]).
    pub fn free_in(&self, r: Rect) -> u32 {
        self.counts.free_in(r)
    }

    /// Wall weights `ω_w` of eq. 3.11 for the four walls (left, right, top, bottom): the share
    /// of each wall's cells that are occupied in the map (eqs. 3.12 - 3.14).
    pub fn wall_weights(&self, r: Rect) -> [f64; 4] {
        let t = self.wall;
        let walls = [
            Rect::new(r.x, r.y, t, r.h),
            Rect::new(r.right() - t, r.y, t, r.h),
            Rect::new(r.x, r.y, r.w, t),
            Rect::new(r.x, r.bottom() - t, r.w, t),
        ];
        walls.map(|w| self.counts.occupied_in(w) as f64 / w.area().max(1) as f64)
    }

    /// The unit weight `ω_r` of eq. 3.10: its weakest wall.
    pub fn unit_weight(&self, r: Rect) -> f64 {
        self.wall_weights(r).into_iter().fold(f64::INFINITY, f64::min)
    }

    /// Index of the unit with id `id`.
    pub fn index_of(&self, id: u32) -> Option<usize> {
        self.units.iter().position(|u| u.id == id)
    }

    /// Whether a unit has a door.
    pub fn has_door(&self, id: u32) -> bool {
        self.doors.iter().any(|d| d.lo == id || d.hi == id)
    }

    /// The rectangle of a door in the current world.
    pub fn door_rect_of(&self, d: &DoorSpec) -> Option<Rect> {
        let lo = self.units[self.index_of(d.lo)?].rect();
        let hi = self.units[self.index_of(d.hi)?].rect();
        door_rect(lo, hi, d, &self.door_limits, self.wall)
    }

    fn rect_ok(&self, r: Rect, min_side: i32) -> bool {
        fits_unit(r, min_side, self.wall)
            && r.x >= 0
            && r.y >= 0
            && r.right() <= self.width
            && r.bottom() <= self.height
            && !self.breaks_forbidden(r)
    }

    fn duplicate(&self, r: Rect, except: &[usize]) -> bool {
        self.units.iter().enumerate().any(|(k, u)| !except.contains(&k) && u.rect() == r)
    }

    /// Whether applying `m` gives a valid world: units inside the grid, at least `min_side`
    /// cells on each side, no two identical, at most `max_units`, units with doors changed only
    /// in ways that keep every door between facing walls, doors not overlapping.
    pub fn is_valid(&self, m: &Move, min_side: i32, max_units: usize) -> bool {
        match *m {
            Move::Add(r) => self.units.len() < max_units && self.rect_ok(r, min_side) && !self.duplicate(r, &[]),
            Move::Remove(i) => i < self.units.len() && !self.has_door(self.units[i].id),
            Move::Split { index, first, second } => {
                index < self.units.len()
                    && self.units.len() < max_units
                    && !self.has_door(self.units[index].id)
                    && self.rect_ok(first, min_side)
                    && self.rect_ok(second, min_side)
                    && !self.duplicate(first, &[index])
                    && !self.duplicate(second, &[index])
            }
            Move::Merge { i, j, merged } => {
                i != j
                    && i.max(j) < self.units.len()
                    && !self.has_door(self.units[i].id)
                    && !self.has_door(self.units[j].id)
                    && self.rect_ok(merged, min_side)
                    && !self.duplicate(merged, &[i, j])
            }
            Move::Reshape { index, rect } => {
                if index >= self.units.len() || !self.rect_ok(rect, min_side) || self.duplicate(rect, &[index]) {
                    return false;
                }
                let id = self.units[index].id;
                // Every door of this unit must still fit between facing walls.
                self.doors.iter().filter(|d| d.lo == id || d.hi == id).all(|d| {
                    let other = if d.lo == id { d.hi } else { d.lo };
                    let Some(o) = self.index_of(other) else { return false };
                    let (lo, hi) = if d.lo == id { (rect, self.units[o].rect()) } else { (self.units[o].rect(), rect) };
                    door_rect(lo, hi, d, &self.door_limits, self.wall).is_some()
                })
            }
            Move::Repartition { i, j, a, b } => {
                i != j
                    && i.max(j) < self.units.len()
                    && !self.has_door(self.units[i].id)
                    && !self.has_door(self.units[j].id)
                    && self.rect_ok(a, min_side)
                    && self.rect_ok(b, min_side)
                    && a != b
                    && !self.duplicate(a, &[i, j])
                    && !self.duplicate(b, &[i, j])
            }
            Move::Allocate(d) => {
                let Some(r) = self.door_rect_of(&d) else { return false };
                !self.doors.iter().any(|o| self.door_rect_of(o).is_some_and(|or| or.intersection(&r).is_some()))
            }
            Move::Delete(k) => k < self.doors.len(),
        }
    }

    fn new_unit(&mut self, r: Rect) -> Unit {
        let u = Unit::new(self.next_id, r.x, r.y, r.w, r.h, UnitType::Unknown);
        self.next_id += 1;
        u
    }

    fn bump(&mut self) -> u64 {
        let old = self.generation;
        self.generation_counter += 1;
        self.generation = self.generation_counter;
        old
    }

    /// Applies a valid move and returns how to undo it.
    pub fn apply(&mut self, m: &Move) -> (Undo, u64, u32) {
        let undo = self.apply_pending(m);
        self.explanation.write_pending();
        undo
    }

    /// [`State::apply`] with the cells of a unit added or taken out not yet written
    /// ([`Explanation::apply_unit`]): the counts are right, and [`State::undo`] or
    /// [`Explanation::write_pending`] must come next.
    #[inline(never)]
    pub fn apply_pending(&mut self, m: &Move) -> (Undo, u64, u32) {
        let saved = (self.generation, self.next_id);
        let undo = match *m {
            Move::Add(r) => {
                let u = self.new_unit(r);
                self.explanation.apply_unit(r, self.wall, 1);
                self.units.push(u);
                self.bump();
                Undo::Added
            }
            Move::Remove(i) => {
                let u = self.units.swap_remove(i);
                self.explanation.apply_unit(u.rect(), self.wall, -1);
                self.bump();
                Undo::Removed { index: i, unit: u }
            }
            Move::Split { index, first, second } => self.apply_split(index, first, second),
            Move::Merge { i, j, merged } => self.apply_merge(i, j, merged),
            Move::Reshape { index, rect } => self.apply_reshape(index, rect),
            Move::Repartition { i, j, a, b } => self.apply_repartition(i, j, a, b),
            Move::Allocate(d) => {
                let r = self.door_rect_of(&d).expect("checked by is_valid");
                self.explanation.apply_door(r, 1);
                self.doors.push(d);
                Undo::Allocated
            }
            Move::Delete(k) => {
                let d = self.doors.swap_remove(k);
                let r = self.door_rect_of(&d).expect("doors are kept valid");
                self.explanation.apply_door(r, -1);
                Undo::Deleted { index: k, door: d }
            }
        };
        (undo, saved.0, saved.1)
    }

    /// SPLIT: unit `index` becomes `first` (in its slot) and `second` (appended), both new ids.
    #[inline]
    fn apply_split(&mut self, index: usize, first: Rect, second: Rect) -> Undo {
        let len = self.units.len();
        let old = self.units[index];
        self.explanation.replace_units(&[old.rect()], &[first, second], self.wall);
        self.units[index] = self.new_unit(first);
        let s = self.new_unit(second);
        self.units.push(s);
        self.bump();
        Undo::Replaced { old: [(index, old), (index, old)], count: 1, len }
    }

    /// MERGE: units `i` and `j` become one new unit `merged` in slot `i`; slot `j` is removed.
    #[inline]
    fn apply_merge(&mut self, i: usize, j: usize, merged: Rect) -> Undo {
        let (ui, uj) = (self.units[i], self.units[j]);
        self.explanation.replace_units(&[ui.rect(), uj.rect()], &[merged], self.wall);
        self.units[i] = self.new_unit(merged);
        self.units.remove(j);
        self.bump();
        Undo::Merged { i, j, ui, uj }
    }

    /// SHRINK or DILATE: unit `index` takes rectangle `rect`, keeping its id and type; its doors
    /// move with its walls.
    #[inline]
    fn apply_reshape(&mut self, index: usize, rect: Rect) -> Undo {
        let len = self.units.len();
        let old = self.units[index];
        let id = old.id;
        let doors: Vec<usize> =
            (0..self.doors.len()).filter(|&k| self.doors[k].lo == id || self.doors[k].hi == id).collect();
        for &k in &doors {
            let r = self.door_rect_of(&self.doors[k]).expect("valid before the move");
            self.explanation.apply_door(r, -1);
        }
        self.explanation.replace_units(&[old.rect()], &[rect], self.wall);
        self.units[index] = Unit { x: rect.x, y: rect.y, w: rect.w, h: rect.h, ..old };
        for &k in &doors {
            let r = self.door_rect_of(&self.doors[k]).expect("checked by is_valid");
            self.explanation.apply_door(r, 1);
        }
        self.bump();
        Undo::Replaced { old: [(index, old), (index, old)], count: 1, len }
    }

    /// INTERCHANGE: units `i` and `j` take rectangles `a` and `b`, keeping their ids and types.
    #[inline]
    fn apply_repartition(&mut self, i: usize, j: usize, a: Rect, b: Rect) -> Undo {
        let len = self.units.len();
        let (ui, uj) = (self.units[i], self.units[j]);
        self.explanation.replace_units(&[ui.rect(), uj.rect()], &[a, b], self.wall);
        self.units[i] = Unit { x: a.x, y: a.y, w: a.w, h: a.h, ..ui };
        self.units[j] = Unit { x: b.x, y: b.y, w: b.w, h: b.h, ..uj };
        self.bump();
        Undo::Replaced { old: [(i, ui), (j, uj)], count: 2, len }
    }

    /// Reverts a move applied by [`State::apply`].
    pub fn undo(&mut self, undo: Undo, generation: u64, next_id: u32) {
        match undo {
            Undo::Added => {
                let u = self.units.pop().expect("added unit");
                self.explanation.apply_unit(u.rect(), self.wall, -1);
            }
            Undo::Removed { index, unit } => {
                self.explanation.apply_unit(unit.rect(), self.wall, 1);
                self.units.push(unit);
                let last = self.units.len() - 1;
                self.units.swap(index, last);
            }
            Undo::Merged { i, j, ui, uj } => {
                let mi = if i > j { i - 1 } else { i };
                let merged = self.units[mi];
                self.explanation.replace_units(&[merged.rect()], &[ui.rect(), uj.rect()], self.wall);
                self.units.insert(j, uj);
                self.units[i] = ui;
            }
            Undo::Replaced { old, count, len } => {
                // Doors of reshaped units move with them: take their current rectangles out first.
                let ids: Vec<u32> = old[..count].iter().map(|(_, u)| u.id).collect();
                let doors: Vec<usize> = (0..self.doors.len())
                    .filter(|&k| ids.contains(&self.doors[k].lo) || ids.contains(&self.doors[k].hi))
                    .collect();
                for &k in &doors {
                    if let Some(r) = self.door_rect_of(&self.doors[k]) {
                        self.explanation.apply_door(r, -1);
                    }
                }
                // What the move made (appended units, then the changed slots) back to what was.
                let mut made: Vec<Rect> = self.units[len..].iter().map(|u| u.rect()).collect();
                made.extend(old[..count].iter().map(|&(i, _)| self.units[i].rect()));
                let was: Vec<Rect> = old[..count].iter().map(|(_, u)| u.rect()).collect();
                self.explanation.replace_units(&made, &was, self.wall);
                self.units.truncate(len);
                for &(i, u) in &old[..count] {
                    self.units[i] = u;
                }
                for &k in &doors {
                    let r = self.door_rect_of(&self.doors[k]).expect("doors were valid before the move");
                    self.explanation.apply_door(r, 1);
                }
            }
            Undo::Allocated => {
                let d = self.doors.pop().expect("allocated door");
                let r = self.door_rect_of(&d).expect("valid");
                self.explanation.apply_door(r, -1);
            }
            Undo::Deleted { index, door } => {
                let r = self.door_rect_of(&door).expect("valid");
                self.explanation.apply_door(r, 1);
                self.doors.push(door);
                let last = self.doors.len() - 1;
                self.doors.swap(index, last);
            }
        }
        self.explanation.write_pending();
        self.generation = generation;
        self.next_id = next_id;
    }

    /// Rectangles of all units and doors, for a full recomputation.
    pub fn rects(&self) -> (Vec<Rect>, Vec<Rect>) {
        (
            self.units.iter().map(|u| u.rect()).collect(),
            self.doors.iter().filter_map(|d| self.door_rect_of(d)).collect(),
        )
    }
}
