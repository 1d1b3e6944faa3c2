//! The room layer: units grouped into the rooms a person would draw, typed, with their doors
//! and the room graph a robot plans with.
//!
//! The dissertation's world is a set of rectangles, and each rectangle is a room. A person
//! draws otherwise: an L-shaped corridor is one corridor, an office cut by desks is one office,
//! and a room that opens onto a corridor over its whole width is still a room of its own.
//! Which units with no wall between them ([`open_pairs`]) are one room is decided here:
//!
//! * with knowledge supervision, by the Markov logic network of
//!   `samples/knowledge/rooms.mln` ([`RoomKnowledge`], or the configuration's `knowledge.room_kb`):
//!   evidence `Open`, `Flush`, `Closed` (the walls part the two units: [`mark_closed`]) and
//!   the unit types ([`room_evidence`]), query `SameRoom`, pairs joined where
//!   `P(SameRoom) > 0.5`. Closed pairs are joined too and parted again by the walls, whose
//!   line is more exact than the units' edges;
//! * without it, every open pair is joined (the rule of [`super::rooms::group_units`]).
//!
//! The grouping then becomes the label image ([`labels_of_groups`], one id per room, split at
//! doorways), and [`rooms_of_labels`] reads the rooms off it: each unit belongs to the room
//! that holds most of its free cells, a room's type is the type covering most of its cells
//! (with knowledge supervision, the indoor rules applied to the room as one space:
//! [`super::room_types::type_rooms`]),
//! its doors are those whose cells it touches, and it opens to every room it touches along a
//! passable stretch ([`MIN_CONTACT_CELLS`]) or through a door.

use super::edits::Edits;
use super::knowledge::{constant, Fact};
use super::rooms::{join, labels_of_groups, open_pairs, world_cell, OpenPair, RoomCells, RoomConfig};
use super::topology::{touching, MIN_CONTACT_CELLS};
use super::world::{Room, UnitType, World};
use crate::grid::{Cell, Grid};
use crate::mln::{Database, Evidence, GroundConfig, InferenceConfig, Mln, MlnError, Network};
use std::collections::{BTreeMap, BTreeSet};

/// The built-in room rules (`samples/knowledge/rooms.mln`, weights set by hand; the same
/// rules with weights learned from generated floors are `rooms-learned.mln`).
pub const BUILTIN_ROOM_RULES: &str = include_str!("../../samples/knowledge/rooms.mln");

/// The unit-type evidence predicates of the room rules, with the type each stands for.
const TYPES: [(&str, UnitType); 4] = super::knowledge::TYPE_PREDICATES;

/// A knowledge base that decides which open-adjacent units are one room (query `SameRoom`).
#[derive(Debug, Clone)]
pub struct RoomKnowledge {
    mln: Mln,
    /// The indoor rules and geometry classifier that type the rooms
    /// ([`super::room_types::type_rooms`]).
    types: super::knowledge::KnowledgeConfig,
}

impl RoomKnowledge {
    /// The built-in rules.
    pub fn builtin() -> RoomKnowledge {
        RoomKnowledge::parse(BUILTIN_ROOM_RULES).expect("the built-in room rules parse")
    }

    /// The rules of a knowledge configuration: its `room_kb`, or the built-in ones; its
    /// indoor knowledge base and geometry classifier type the rooms.
    pub fn configured(config: &super::knowledge::KnowledgeConfig) -> Result<RoomKnowledge, MlnError> {
        let mut k = RoomKnowledge::parse(config.room_kb.as_deref().unwrap_or(BUILTIN_ROOM_RULES))?;
        k.types = config.clone();
        Ok(k)
    }

    /// Rules from text: they must declare `SameRoom(unit, unit)`; they may use the evidence
    /// predicates `Open`, `Flush`, `Closed`, `Room`, `Corr`, `Hall` and `Other`. The built-in
    /// indoor rules type the rooms.
    pub fn parse(text: &str) -> Result<RoomKnowledge, MlnError> {
        let mln = Mln::parse(text)?;
        if mln.predicate("SameRoom").is_none() {
            return Err(MlnError::config("the room rules must declare the query SameRoom(unit, unit)"));
        }
        Ok(RoomKnowledge { mln, types: Default::default() })
    }

    /// `P(SameRoom)` of every pair in `pairs` (unit indices into `world.units`), in order.
    pub fn same_room(&self, world: &World, pairs: &[OpenPair]) -> Result<Vec<f64>, MlnError> {
        self.same_room_given(world, pairs, &[])
    }

    /// [`RoomKnowledge::same_room`] with `SameRoom` evidence: `given` lists unit index pairs
    /// with their value (a person's merge or split, [`super::edits`]).
    pub fn same_room_given(
        &self,
        world: &World,
        pairs: &[OpenPair],
        given: &[(usize, usize, bool)],
    ) -> Result<Vec<f64>, MlnError> {
        if pairs.is_empty() {
            return Ok(Vec::new());
        }
        let mut db = Database::new();
        let mut closed = Vec::new();
        for pred in TYPES.iter().map(|t| t.0).chain(["Open", "Flush", "Closed"]) {
            if self.mln.predicate(pred).is_some() {
                closed.push(pred.to_string());
            }
        }
        for (pred, args, _) in room_evidence(world, pairs) {
            if self.mln.predicate(pred).is_some() {
                let args: Vec<&str> = args.iter().map(String::as_str).collect();
                db.insert(&self.mln, pred, &args, Evidence::True)?;
            }
        }
        for &(a, b, value) in given {
            let (a, b) = (constant(world.units[a].id), constant(world.units[b].id));
            let v = if value { Evidence::True } else { Evidence::False };
            db.insert(&self.mln, "SameRoom", &[&a, &b], v)?;
            db.insert(&self.mln, "SameRoom", &[&b, &a], v)?;
        }
        let mut ground = GroundConfig::query(&["SameRoom"]);
        ground.closed_world = closed;
        let units: Vec<String> = world.units.iter().map(|u| constant(u.id)).collect();
        if let Some(ty) = self.mln.predicate("SameRoom").and_then(|p| self.mln.argument_types(p).first().cloned()) {
            ground.domains.push((ty.to_string(), units));
        }
        let net = Network::ground(&self.mln, &db, &ground)?;
        let marginals = net.infer_marginals(&InferenceConfig::default())?;
        Ok(pairs
            .iter()
            .map(|p| {
                let (a, b) = (constant(world.units[p.a].id), constant(world.units[p.b].id));
                marginals.get("SameRoom", &[a.as_str(), b.as_str()]).unwrap_or(0.0)
            })
            .collect())
    }
}

/// The evidence the room rules are given about `world` and its open pairs `pairs` (unit
/// indices, [`open_pairs`]), units named by [`constant`]: each typed unit's type predicate
/// (`Room`, `Corr`, `Hall`, `Other`) and `Open` (and `Flush` where the pair is flush) of every
/// pair both ways. Only true facts: the evidence is closed world, so it grows with the units
/// and their open pairs, never with all pairs of units.
///
/// ```
/// use ksmcmc::floorplan::room_layer::room_evidence;
/// use ksmcmc::floorplan::rooms::OpenPair;
/// use ksmcmc::floorplan::{Unit, UnitType, World};
/// let mut world = World::empty(80, 40);
/// for (id, x) in [(1, 0), (2, 40)] {
///     world.units.push(Unit::new(id, x, 0, 40, 40, UnitType::Room));
/// }
/// let facts = room_evidence(&world, &[OpenPair { a: 0, b: 1, flush: true, closed: false }]);
/// let text: Vec<String> = facts.iter().map(|(p, a, _)| format!("{p}({})", a.join(","))).collect();
/// assert_eq!(text, ["Room(U1)", "Room(U2)", "Open(U1,U2)", "Flush(U1,U2)", "Open(U2,U1)", "Flush(U2,U1)"]);
/// ```
pub fn room_evidence(world: &World, pairs: &[OpenPair]) -> Vec<Fact> {
    let mut facts = Vec::new();
    for u in &world.units {
        if let Some((pred, _)) = TYPES.iter().find(|t| t.1 == u.kind) {
            facts.push((*pred, vec![constant(u.id)], true));
        }
    }
    for p in pairs {
        let (a, b) = (constant(world.units[p.a].id), constant(world.units[p.b].id));
        for (x, y) in [(&a, &b), (&b, &a)] {
            facts.push(("Open", vec![x.clone(), y.clone()], true));
            if p.flush {
                facts.push(("Flush", vec![x.clone(), y.clone()], true));
            }
            if p.closed {
                facts.push(("Closed", vec![x.clone(), y.clone()], true));
            }
        }
    }
    facts
}

/// Groups `world`'s units into rooms (by `knowledge` if given, else every open pair), labels
/// the map with one id per room, and fills `world.rooms`. `map` is the classified map in its
/// own frame, `world_map` in the world frame; `resolution` is metres per cell. Returns the
/// label image (`labels.pgm`).
///
/// ```
/// use ksmcmc::floorplan::room_layer::{explain_rooms, RoomKnowledge};
/// use ksmcmc::floorplan::rooms::RoomConfig;
/// use ksmcmc::floorplan::{Unit, UnitType, World};
/// use ksmcmc::grid::{Cell, Grid};
///
/// // Two 40x40 units side by side with no wall between them: one room of 2 x 1,600 cells.
/// let map = Grid::new(80, 40, Cell::Free);
/// let mut world = World::empty(80, 40);
/// for (id, x) in [(1, 0), (2, 40)] {
///     world.units.push(Unit::new(id, x, 0, 40, 40, UnitType::Room));
/// }
/// let labels = explain_rooms(&mut world, &map, &map, &RoomConfig::default(), 0.05, Some(&RoomKnowledge::builtin()))?;
/// assert_eq!(world.rooms.len(), 1);
/// assert_eq!(world.rooms[0].units, vec![1, 2]);
/// assert_eq!(*labels.at(10, 10), *labels.at(70, 10));
/// # Ok::<(), ksmcmc::mln::MlnError>(())
/// ```
pub fn explain_rooms(
    world: &mut World,
    map: &Grid<Cell>,
    world_map: &Grid<Cell>,
    c: &RoomConfig,
    resolution: f64,
    knowledge: Option<&RoomKnowledge>,
) -> Result<Grid<u16>, MlnError> {
    explain_rooms_edited(world, map, world_map, c, resolution, knowledge, &Edits::default())
}

/// [`explain_rooms`] under a person's edits ([`super::edits`]): merged units are `SameRoom`
/// evidence and always joined, units a split wall separates never are, then the edits apply
/// to the labels ([`Edits::apply_to_labels`]) and the rooms.
pub fn explain_rooms_edited(
    world: &mut World,
    map: &Grid<Cell>,
    world_map: &Grid<Cell>,
    c: &RoomConfig,
    resolution: f64,
    knowledge: Option<&RoomKnowledge>,
    edits: &Edits,
) -> Result<Grid<u16>, MlnError> {
    let c = &c.cells(resolution);
    let walls = edits.world_wall_cells(map, &world.frame);
    let apart = |a: usize, b: usize| Edits::separates(&walls, world.units[a].rect(), world.units[b].rect());
    let merged = edits.merged_units(world);
    let mut given: Vec<(usize, usize, bool)> = merged.iter().map(|&(a, b)| (a, b, true)).collect();
    let mut pairs: Vec<OpenPair> = open_pairs(world, world_map, c);
    mark_closed(world, map, world_map, &mut pairs, c);
    given.extend(pairs.iter().filter(|p| apart(p.a, p.b)).map(|p| (p.a, p.b, false)));
    // Where the walls part two units (closed pairs), the splits of the room layer draw the
    // line between them more exactly than the units' edges: closed pairs are joined and
    // parted again by the walls ([`labels_of_groups`]).
    let mut joined: Vec<(usize, usize)> = match knowledge {
        Some(k) => {
            let p = k.same_room_given(world, &pairs, &given)?;
            let keep = |(q, p): &(&OpenPair, f64)| *p > 0.5 || q.closed && !apart(q.a, q.b);
            pairs.iter().zip(p).filter(keep).map(|(q, _)| (q.a, q.b)).collect()
        }
        None => pairs.iter().filter(|p| !apart(p.a, p.b)).map(|p| (p.a, p.b)).collect(),
    };
    joined.extend(merged);
    let groups = join(world, world_map, joined);
    let mut labels = labels_of_groups(world, &groups, map, world_map, c);
    edits.apply_to_labels(&mut labels, map);
    rooms_of_segments(world, &labels, map, resolution, knowledge)?;
    edits.apply_to_rooms(&mut world.rooms, &labels);
    mark_openings(world, map, c, resolution);
    Ok(labels)
}

/// Marks the doors of `world` that are openings within one of its rooms
/// ([`super::openings::mark_openings`]), the walls of `map` (in its own frame) read as the
/// room layer reads them.
fn mark_openings(world: &mut World, map: &Grid<Cell>, c: &RoomCells, resolution: f64) {
    let walls = super::rooms::without_clutter(map, c.min_wall_len);
    super::openings::mark_openings(world, &walls, resolution);
}

/// [`super::openings::mark_openings`] for a world composed after its rooms were found (the wings' world,
/// [`super::wings::WingLayout::compose`]), with the room layer's settings `rooms` on a map of
/// `resolution` metres per cell.
pub fn mark_world_openings(world: &mut World, map: &Grid<Cell>, rooms: &RoomConfig, resolution: f64) {
    mark_openings(world, map, &rooms.cells(resolution), resolution);
}

/// Fills in `world.rooms` from the room `labels`: the rooms read off the labels
/// ([`rooms_of_labels`]), typed by the indoor rules when `knowledge` is on
/// ([`super::room_types::type_rooms`]), rays typed unknown ([`mark_unexplored`]).
fn rooms_of_segments(
    world: &mut World,
    labels: &Grid<u16>,
    map: &Grid<Cell>,
    resolution: f64,
    knowledge: Option<&RoomKnowledge>,
) -> Result<(), MlnError> {
    world.rooms = rooms_of_labels(world, labels, resolution);
    if let Some(k) = knowledge {
        super::room_types::type_rooms(world, labels, resolution, &k.types)?;
    }
    mark_unexplored(&mut world.rooms, labels, map, resolution);
    Ok(())
}

/// The rooms of a building that none of its wall directions holds most of (issue 13,
/// [`super::wings`]), with the wall directions of its other wings `angles` (radians, as the
/// frame's angle). The units of a chain turned one way cut across the walls that run the
/// other ways, so which of them share a room says little of where a person parts the rooms.
/// The rooms are where the walls part the floor: every unit that encloses space starts in
/// one group, which the doorways and the wall gaps of every direction then split
/// ([`super::rooms::labels_of_groups_along`]). The rooms are read off the labels and typed as
/// [`explain_rooms`] does.
///
/// ```
/// use ksmcmc::floorplan::room_layer::explain_rooms_by_walls;
/// use ksmcmc::floorplan::rooms::RoomConfig;
/// use ksmcmc::floorplan::{Unit, UnitType, World};
/// use ksmcmc::grid::{Cell, Grid};
///
/// // Two rooms, 3 m square, parted by a wall along row 60 with a 1 m doorway: one unit
/// // spans both.
/// let mut map = Grid::new(60, 121, Cell::Free);
/// for x in (0..20).chain(40..60) {
///     *map.at_mut(x, 60) = Cell::Occupied;
/// }
/// let mut world = World::empty(60, 121);
/// world.units = vec![Unit::new(1, 0, 0, 60, 121, UnitType::Room)];
/// let c = RoomConfig { min_wall_len_m: 0.5, ..RoomConfig::default() };
/// let labels = explain_rooms_by_walls(&mut world, &map, &map, &c, 0.05, None, &[])?;
/// assert_eq!(world.rooms.len(), 2);
/// assert_ne!(labels.at(30, 10), labels.at(30, 110));
/// # Ok::<(), ksmcmc::mln::MlnError>(())
/// ```
pub fn explain_rooms_by_walls(
    world: &mut World,
    map: &Grid<Cell>,
    world_map: &Grid<Cell>,
    c: &RoomConfig,
    resolution: f64,
    knowledge: Option<&RoomKnowledge>,
    angles: &[f64],
) -> Result<Grid<u16>, MlnError> {
    let c = &c.cells(resolution);
    let groups: Vec<u16> = join(world, world_map, []).into_iter().map(|g| u16::from(g > 0)).collect();
    let labels = super::rooms::labels_of_groups_along(world, &groups, map, world_map, c, angles);
    rooms_of_segments(world, &labels, map, resolution, knowledge)?;
    mark_openings(world, map, c, resolution);
    Ok(labels)
}

/// How far (m) from every wall, object or unseen cell a cell must be for a person (or a
/// robot) to stand there: [`mark_unexplored`].
pub const STANDING_CLEARANCE_M: f64 = 0.2;

/// Types `unknown` the rooms that are mostly rays, not floor: fewer than a third of their
/// free cells lie [`STANDING_CLEARANCE_M`] or more from every non-free cell of `map` (at
/// `resolution` m per cell). A range sensor looking through a window or an open door into
/// space nobody entered leaves a fan of one-cell rays with unseen cells between them; the
/// room layer labels the fan (a segmentation labels every free cell, and the benchmark's
/// truth draws such fans as regions too), but a person draws no room there and cannot say
/// what it is. The dissertation marks the same places as unexplored (Fig. 3.32-d). Rooms of
/// floor, furnished or not, keep far more than a third: on Cartesium 0.39 and over, the fans
/// 0.23 and under. [`RoomConfig::min_room_depth_m`] judges the free regions beyond every unit
/// by their deep cells too, but deeper (6 cells) and by count, to decide whether they are
/// rooms at all; at that depth several rooms of floor on Cartesium (half-seen offices, a
/// junction) keep only 0.23 - 0.30 of their cells, so the two are not one test.
///
/// ```
/// use ksmcmc::floorplan::room_layer::mark_unexplored;
/// use ksmcmc::floorplan::{Room, UnitType};
/// use ksmcmc::grid::{Cell, Grid};
///
/// // Room 1: 2 x 2 m of floor. Room 2: rays, every other column free, unseen between.
/// let mut map = Grid::new(80, 40, Cell::Unknown);
/// let mut labels = Grid::new(80, 40, 0u16);
/// for y in 0..40 {
///     for x in 0..40 { *map.at_mut(x, y) = Cell::Free; *labels.at_mut(x, y) = 1; }
///     for x in (41..80).step_by(2) { *map.at_mut(x, y) = Cell::Free; *labels.at_mut(x, y) = 2; }
/// }
/// let room = |id| Room { id, kind: UnitType::Other, units: vec![], area_m2: 0.0, doors: vec![], opens_to: vec![], name: None };
/// let mut rooms = vec![room(1), room(2)];
/// mark_unexplored(&mut rooms, &labels, &map, 0.05);
/// assert_eq!((rooms[0].kind, rooms[1].kind), (UnitType::Other, UnitType::Unknown));
/// ```
pub fn mark_unexplored(rooms: &mut [Room], labels: &Grid<u16>, map: &Grid<Cell>, resolution: f64) {
    if (labels.width(), labels.height()) != (map.width(), map.height()) || resolution.is_nan() || resolution <= 0.0 {
        return;
    }
    // Chamfer units: 3 per cell.
    let clearance = (3.0 * (STANDING_CLEARANCE_M / resolution).round()).min(u32::MAX as f64) as u32;
    let depth = super::rooms::free_depth(map);
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

/// [`explain_rooms`] with the built-in room rules when `knowledge` is on, and without them
/// otherwise ([`explain_world_rooms_by`]).
pub fn explain_world_rooms(
    world: &mut World,
    map: &Grid<Cell>,
    world_map: &Grid<Cell>,
    c: &RoomConfig,
    resolution: f64,
    knowledge: bool,
    edits: &Edits,
) -> Grid<u16> {
    let kb = knowledge.then(RoomKnowledge::builtin);
    explain_world_rooms_by(world, map, world_map, c, resolution, kb.as_ref(), edits)
}

/// [`explain_rooms_edited`] with the rules `knowledge` (`None`: every open pair joins), and
/// without them should the rules fail (they cannot on a valid world; the rooms are then still
/// found, by the rule without knowledge).
pub fn explain_world_rooms_by(
    world: &mut World,
    map: &Grid<Cell>,
    world_map: &Grid<Cell>,
    c: &RoomConfig,
    resolution: f64,
    knowledge: Option<&RoomKnowledge>,
    edits: &Edits,
) -> Grid<u16> {
    with_rules_or_without(map, knowledge, |kb| explain_rooms_edited(world, map, world_map, c, resolution, kb, edits))
}

/// The labels `explain` finds with the rules `knowledge`, or without them should the rules
/// fail, or none (every cell 0) should that fail too: the fallback of the room layer's
/// infallible entries.
fn with_rules_or_without<E>(
    map: &Grid<Cell>,
    knowledge: Option<&RoomKnowledge>,
    mut explain: impl FnMut(Option<&RoomKnowledge>) -> Result<Grid<u16>, E>,
) -> Grid<u16> {
    explain(knowledge).or_else(|_| explain(None)).unwrap_or_else(|_| Grid::new(map.width(), map.height(), 0))
}

/// [`explain_rooms_by_walls`] with the rules `knowledge`, and without them should the rules
/// fail, as [`explain_world_rooms_by`] does for the rooms the rules group.
pub fn explain_world_rooms_by_walls(
    world: &mut World,
    map: &Grid<Cell>,
    world_map: &Grid<Cell>,
    c: &RoomConfig,
    resolution: f64,
    knowledge: Option<&RoomKnowledge>,
    angles: &[f64],
) -> Grid<u16> {
    with_rules_or_without(map, knowledge, |kb| explain_rooms_by_walls(world, map, world_map, c, resolution, kb, angles))
}

/// Marks the open pairs whose units the room layer's geometry parts (`closed`): with every
/// open pair joined, the doorway split and the wall gaps ([`labels_of_groups`]) still leave
/// the two units mostly in different segments (`unit_rooms`). It is evidence for the room
/// rules (`Closed`): on the chain's worlds of the benchmark floors, nine in ten open pairs
/// that geometry does not part lie in one drawn room, and four in five that it parts do not.
///
/// ```
/// use ksmcmc::floorplan::room_layer::mark_closed;
/// use ksmcmc::floorplan::rooms::{open_pairs, RoomCells};
/// use ksmcmc::floorplan::{Unit, UnitType, World};
/// use ksmcmc::grid::{Cell, Grid};
///
/// // A room 2.5 m wide (50 cells) open over its whole width onto a corridor above it, the
/// // corridor's wall (row 40) running on either side: a person closes the room's front.
/// let mut map = Grid::new(200, 100, Cell::Free);
/// for x in (0..75).chain(125..200) {
///     *map.at_mut(x, 40) = Cell::Occupied;
/// }
/// for y in 40..100 {
///     *map.at_mut(75, y) = Cell::Occupied;
///     *map.at_mut(125, y) = Cell::Occupied;
/// }
/// let mut world = World::empty(200, 100);
/// world.units = vec![
///     Unit::new(1, 0, 0, 200, 41, UnitType::Corridor),
///     Unit::new(2, 75, 40, 51, 60, UnitType::Room),
/// ];
/// let c = RoomCells::default();
/// let mut pairs = open_pairs(&world, &map, &c);
/// assert_eq!(pairs.len(), 1);
/// mark_closed(&world, &map, &map, &mut pairs, &c);
/// assert!(pairs[0].closed);
/// // Without wall gaps nothing parts them.
/// let open = RoomCells { max_wall_gap: 0, ..c };
/// mark_closed(&world, &map, &map, &mut pairs, &open);
/// assert!(!pairs[0].closed);
/// ```
pub fn mark_closed(world: &World, map: &Grid<Cell>, world_map: &Grid<Cell>, pairs: &mut [OpenPair], c: &RoomCells) {
    if pairs.is_empty() {
        return;
    }
    let groups = join(world, world_map, pairs.iter().map(|p| (p.a, p.b)));
    let labels = labels_of_groups(world, &groups, map, world_map, c);
    let segment = unit_rooms(world, world_map, &labels);
    for p in pairs {
        p.closed = segment[p.a] != segment[p.b];
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

/// Index of the first unit whose interior covers each world cell (`usize::MAX` for none).
fn interior_owner(world: &World) -> (Vec<usize>, usize) {
    let [ww, wh] = world.frame.world_size.map(|v| v as usize);
    let mut owner = vec![usize::MAX; ww * wh];
    let t = world.wall_thickness;
    for (k, u) in world.units.iter().enumerate() {
        for y in (u.y + t).max(0)..(u.y + u.h - t).min(wh as i32) {
            for x in (u.x + t).max(0)..(u.x + u.w - t).min(ww as i32) {
                let o = &mut owner[y as usize * ww + x as usize];
                if *o == usize::MAX {
                    *o = k;
                }
            }
        }
    }
    (owner, ww)
}

/// The rooms of a label image (`labels[cell]` = room id, 0 for none): see the module docs.
pub fn rooms_of_labels(world: &World, labels: &Grid<u16>, resolution: f64) -> Vec<Room> {
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
                if k != usize::MAX {
                    *t.units.entry(k).or_default() += 1;
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
    let mut links: BTreeSet<(u32, u32)> = touching(&labels.map(|&l| l as u32), MIN_CONTACT_CELLS).into_iter().collect();
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
    use crate::floorplan::{Door, Unit};

    fn unit(id: u32, x: i32, y: i32, w: i32, h: i32, kind: UnitType) -> Unit {
        Unit::new(id, x, y, w, h, kind)
    }

    /// A 300 x 100 floor: a corridor along the top (rows 0..40), and below it three rooms
    /// (columns 0..100, 100..200, 200..300), each opening onto the corridor over its whole
    /// width. Walls (columns 100 and 200) part the rooms.
    fn rooms_off_a_corridor() -> (Grid<Cell>, World) {
        let mut map = Grid::new(300, 100, Cell::Free);
        for y in 0..100 {
            *map.at_mut(0, y) = Cell::Occupied;
            *map.at_mut(299, y) = Cell::Occupied;
            if y >= 40 {
                *map.at_mut(100, y) = Cell::Occupied;
                *map.at_mut(200, y) = Cell::Occupied;
            }
        }
        for x in 0..300 {
            *map.at_mut(x, 0) = Cell::Occupied;
            *map.at_mut(x, 99) = Cell::Occupied;
        }
        let mut world = World::empty(300, 100);
        world.units = vec![
            unit(1, 0, 0, 300, 41, UnitType::Corridor),
            unit(2, 0, 40, 101, 60, UnitType::Room),
            unit(3, 100, 40, 101, 60, UnitType::Room),
            unit(4, 200, 40, 100, 60, UnitType::Room),
        ];
        (map, world)
    }

    #[test]
    fn rooms_open_onto_a_corridor_are_apart_where_the_walls_show_their_fronts() {
        let (mut map, mut world) = rooms_off_a_corridor();
        let c = RoomConfig { door_half_width_m: 0.0, ..RoomConfig::default() };
        let cells = c.cells(0.05);
        let kb = RoomKnowledge::builtin();
        // Nothing shows the rooms' fronts: the rules join the open pairs, one space.
        let labels = explain_rooms(&mut world, &map, &map, &c, 0.05, Some(&kb)).unwrap();
        assert_eq!(world.rooms.len(), 1, "{:?}", world.rooms);
        assert_eq!(*labels.at(50, 20), *labels.at(50, 70));
        // Wall stubs along a line just inside the rooms (row 44; the units' edges at row 40
        // stay open), 50 cells apart in front of each room: the fronts are closed (`Closed`),
        // the corridor and three rooms, linked corridor-room only.
        for x in (0..25).chain(75..125).chain(175..225).chain(275..300) {
            *map.at_mut(x, 44) = Cell::Occupied;
        }
        let mut pairs = open_pairs(&world, &map, &cells);
        mark_closed(&world, &map, &map, &mut pairs, &cells);
        assert_eq!(
            pairs.iter().map(|p| (p.a, p.b, p.closed)).collect::<Vec<_>>(),
            [(0, 1, true), (0, 2, true), (0, 3, true)]
        );
        let facts = room_evidence(&world, &pairs);
        assert!(facts.contains(&("Closed", vec!["U1".into(), "U3".into()], true)));
        for knowledge in [Some(&kb), None] {
            let labels = explain_rooms(&mut world, &map, &map, &c, 0.05, knowledge).unwrap();
            assert_eq!(world.rooms.len(), 4, "{:?}", world.rooms);
            let at = |x: usize| *labels.at(x, 70) as u32;
            let (corr, left, mid, right) = (*labels.at(50, 20) as u32, at(50), at(150), at(250));
            let room = |id: u32| world.rooms.iter().find(|r| r.id == id).unwrap();
            assert_eq!(room(corr).kind, UnitType::Corridor);
            assert_eq!(room(mid).kind, UnitType::Room);
            assert_eq!(room(corr).units, vec![1]);
            assert_eq!(room(mid).units, vec![3]);
            assert_eq!(room(corr).opens_to, vec![left, mid, right]);
            assert_eq!(room(mid).opens_to, vec![corr], "walls part the rooms");
            world.validate().unwrap();
        }
    }

    #[test]
    fn a_room_cut_by_a_seam_is_one_room_and_doors_belong_to_the_rooms_they_touch() {
        // Two units flush along their whole side (one room), a third behind a wall with a door.
        let mut map = Grid::new(150, 40, Cell::Free);
        for y in 0..40 {
            if !(15..25).contains(&y) {
                *map.at_mut(100, y) = Cell::Occupied;
            }
        }
        let mut world = World::empty(150, 40);
        world.units = vec![
            unit(1, 0, 0, 51, 40, UnitType::Other),
            unit(2, 50, 0, 51, 40, UnitType::Room),
            unit(3, 100, 0, 50, 40, UnitType::Room),
        ];
        world.doors = vec![Door { id: 7, units: [2, 3], x0: 100, y0: 15, x1: 100, y1: 24, opening: false }];
        // The wall's two pieces are 15 cells long, with nothing else in this small map to
        // join them to: walls of 10 cells and more are walls here.
        let c = RoomConfig { door_half_width_m: 0.0, min_wall_len_m: 1.0, ..RoomConfig::default() };
        explain_rooms(&mut world, &map, &map, &c, 0.1, Some(&RoomKnowledge::builtin())).unwrap();
        assert_eq!(world.rooms.len(), 2, "{:?}", world.rooms);
        let (a, b) = (&world.rooms[0], &world.rooms[1]);
        assert_eq!((a.units.clone(), b.units.clone()), (vec![1, 2], vec![3]));
        assert_eq!((a.doors.clone(), b.doors.clone()), (vec![7], vec![7]));
        assert_eq!((a.opens_to.clone(), b.opens_to.clone()), (vec![b.id], vec![a.id]));
        // The room's type is the type covering most of its cells: units 1 and 2 hold 49 and
        // 49 columns of interior, a tie broken towards the earlier type in UnitType order.
        assert_eq!(a.kind, UnitType::Room);
        // Areas: free cells at 0.1 m per cell (the wall column is not free).
        let free_left = 100 * 40 + 10; // the doorway cells join the nearer room
        let total: f64 = world.rooms.iter().map(|r| r.area_m2).sum();
        assert!((total - (150 * 40 - 30) as f64 * 0.01).abs() < 1e-9, "{total}");
        assert!(a.area_m2 >= (free_left - 10) as f64 * 0.01 - 1e-9);
    }

    #[test]
    fn the_configured_room_rules_decide() {
        let (map, mut world) = rooms_off_a_corridor();
        let c = RoomConfig { door_half_width_m: 0.0, ..RoomConfig::default() };
        // Rules that keep every open pair apart: four rooms, where the built-in rules join
        // them (nothing shows the rooms' fronts).
        let mut config = crate::floorplan::knowledge::KnowledgeConfig {
            room_kb: Some("Open(unit, unit)\nSameRoom(unit, unit)\n5 Open(p, q) => !SameRoom(p, q)\n".into()),
            ..Default::default()
        };
        config.validate().unwrap();
        let kb = RoomKnowledge::configured(&config).unwrap();
        explain_rooms(&mut world, &map, &map, &c, 0.05, Some(&kb)).unwrap();
        assert_eq!(world.rooms.len(), 4, "{:?}", world.rooms);
        config.room_kb = None;
        explain_rooms(&mut world, &map, &map, &c, 0.05, Some(&RoomKnowledge::configured(&config).unwrap())).unwrap();
        assert_eq!(world.rooms.len(), 1, "{:?}", world.rooms);
        // Rules without the query are refused when the configuration is checked.
        config.room_kb = Some("Open(unit, unit)\n".into());
        let e = config.validate().unwrap_err();
        assert!(e.contains("room_kb") && e.contains("SameRoom"), "{e}");
    }

    #[test]
    fn room_rules_must_declare_the_query() {
        let e = RoomKnowledge::parse("Open(unit, unit)\n").unwrap_err();
        assert!(e.to_string().contains("SameRoom"), "{e}");
    }

    #[test]
    fn room_areas_are_square_centimetres_without_float_noise() {
        // 26,184 cells of 5 cm: 65.46 m², where the product of floats is 65.46000000000001.
        let mut world = World::empty(200, 131);
        world.units.push(unit(1, 0, 0, 200, 131, UnitType::Room));
        let mut labels = Grid::new(200, 131, 0u16);
        for l in labels.cells_mut().iter_mut().take(26_184) {
            *l = 1;
        }
        let rooms = rooms_of_labels(&world, &labels, 0.05);
        assert_eq!(rooms[0].area_m2.to_string(), "65.46");
    }

    #[test]
    fn a_piece_parted_from_its_units_room_takes_their_type() {
        // One corridor unit over a 100 x 20 strip; the labels part its last 20 columns off
        // as a room of their own (as a wall gap at a junction does). That room has no unit
        // of its own (the unit's home is the larger room) but the corridor's type.
        let mut world = World::empty(100, 20);
        world.units = vec![unit(1, 0, 0, 100, 20, UnitType::Corridor)];
        let labels = Grid::from_vec(100, 20, (0..2000).map(|i| if i % 100 < 80 { 1 } else { 2 }).collect()).unwrap();
        let rooms = rooms_of_labels(&world, &labels, 0.05);
        assert_eq!(
            rooms.iter().map(|r| (r.units.clone(), r.kind)).collect::<Vec<_>>(),
            [(vec![1], UnitType::Corridor), (vec![], UnitType::Corridor)]
        );
        // Free space no unit covers stays of unknown type.
        world.units.clear();
        assert!(rooms_of_labels(&world, &labels, 0.05).iter().all(|r| r.kind == UnitType::Unknown));
    }

    #[test]
    fn a_room_of_small_other_units_is_typed_as_the_one_space_it_is() {
        // A 10 x 10 m foyer at 5 cm cells, walled round, explained by four units of 5 x 5 m
        // typed Other (as fragments with doors come out), with nothing between them.
        let map = crate::floorplan::rooms::tests::walled_room(200, 200);
        let mut world = World::empty(200, 200);
        world.units = vec![
            unit(1, 0, 0, 101, 101, UnitType::Other),
            unit(2, 100, 0, 100, 101, UnitType::Other),
            unit(3, 0, 100, 101, 100, UnitType::Other),
            unit(4, 100, 100, 100, 100, UnitType::Other),
        ];
        let c = RoomConfig::default();
        explain_rooms(&mut world, &map, &map, &c, 0.05, Some(&RoomKnowledge::builtin())).unwrap();
        assert_eq!(world.rooms.len(), 1);
        assert_eq!(world.rooms[0].kind, UnitType::Hall, "typed by its own area, 100 m2");
        // Without the rules the room takes its units' type.
        explain_rooms(&mut world, &map, &map, &c, 0.05, None).unwrap();
        assert_eq!((world.rooms.len(), world.rooms[0].kind), (1, UnitType::Other));
    }
}
