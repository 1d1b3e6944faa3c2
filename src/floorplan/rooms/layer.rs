//! The room layer's one entry point, [`RoomLayer::explain`]: a world and its map in, rooms and
//! labels out.
//!
//! The dissertation's world is a set of rectangles, and each rectangle is a room. A person
//! draws otherwise: an L-shaped corridor is one corridor, an office cut by desks is one office,
//! and a room that opens onto a corridor over its whole width is still a room of its own.
//! Which units with no wall between them ([`open_pairs`]) are one room is decided here, when
//! the rooms are grouped [`Grouping::Units`]:
//!
//! * with knowledge supervision, by the Markov logic network of
//!   `samples/knowledge/rooms.mln` ([`RoomKnowledge`], or the configuration's `knowledge.room_kb`):
//!   evidence `Open`, `Flush`, `Closed` (the walls part the two units: [`mark_closed`]) and
//!   the unit types ([`super::knowledge::room_evidence`]), query `SameRoom`, pairs joined where
//!   `P(SameRoom) > 0.5`. Closed pairs are joined too and parted again by the walls, whose
//!   line is more exact than the units' edges;
//! * without it, every open pair is joined.
//!
//! [`Grouping::Walls`] is for a building that no wall direction holds most of: the rooms are
//! where the walls part the floor.
//!
//! The grouping then becomes the label image ([`labels_of_groups`], one id per room, split at
//! doorways), and [`rooms_of_labels`] reads the rooms off it: each unit belongs to the room
//! that holds most of its free cells, a room's type is the type covering most of its cells
//! (with knowledge supervision, the indoor rules applied to the room as one space:
//! [`super::types::type_rooms`]), its doors are those whose cells it touches, and it opens to
//! every room it touches along a passable stretch or through a door. Last, the doors within
//! one room that are openings are marked ([`super::openings`]).
//!
//! Nothing here falls back silently: should the rules fail, the error says which step failed,
//! and no room is made up without them.

use super::config::{RoomCells, RoomConfig};
use super::error::RoomError;
use super::knowledge::RoomKnowledge;
use super::pairs::{group_units, join, open_pairs_among, OpenPair};
use super::read::{mark_unexplored_on, rooms_of_labels, unit_rooms};
use super::segments::{labels_of_groups, labels_read};
use super::wall_gaps::{without_clutter, WallReading};
use crate::floorplan::edits::Edits;
use crate::floorplan::frontier::{placeholders, FrontierRules, BUILTIN_FRONTIER_RULES};
use crate::floorplan::knowledge::KnowledgeConfig;
use crate::floorplan::world::World;
use crate::grid::{Cell, Grid};

/// The room layer's settings: its lengths and areas ([`RoomConfig`]) and the rules that group
/// and type the rooms (none: every open pair joins and units keep their own types).
///
/// Build it once from the run's settings ([`RoomLayer::new`]); the command line, `evaluate`,
/// the wasm plan, the wings and the edits all call [`RoomLayer::explain`], so the same
/// settings give the same rooms and types everywhere.
#[derive(Debug, Clone)]
pub struct RoomLayer {
    config: RoomConfig,
    knowledge: Option<RoomKnowledge>,
    /// The rules that weigh the placeholders ([`crate::floorplan::frontier`]); `None` finds none.
    frontier: Option<FrontierRules>,
}

/// The maps the rooms are found on: the classified map in its own frame (`map`, the frame of
/// `labels.pgm`), the same map turned into the world's frame (`world_map`, where the units'
/// walls run along the axes), and its resolution (metres per cell).
#[derive(Debug, Clone, Copy)]
pub struct RoomMaps<'a> {
    /// The classified map in its own frame.
    pub map: &'a Grid<Cell>,
    /// The classified map in the world's frame.
    pub world_map: &'a Grid<Cell>,
    /// Metres per cell.
    pub resolution: f64,
}

/// How units become rooms.
#[derive(Debug, Clone, Copy)]
pub enum Grouping<'a> {
    /// Units with no wall between them are candidates for one room; the room rules decide
    /// (every such pair joins without them), under a person's edits: merged units are
    /// `SameRoom` evidence and always joined, units a split wall separates never are, then the
    /// edits apply to the labels and the rooms.
    Units(&'a Edits),
    /// The rooms are where the walls part the floor, with the wall gaps along the wall
    /// directions of the building's other wings too (radians, as the frame's angle): for a
    /// building that none of its wall directions holds most of ([`crate::floorplan::wings`]),
    /// whose units cut across the walls that run the other ways. Every unit that encloses
    /// space starts in one group, which the doorways and the wall gaps then split.
    Walls(&'a [f64]),
}

impl RoomLayer {
    /// The layer with `config`'s lengths, and the rules of a knowledge configuration when it
    /// is enabled: its `room_kb` (or the built-in room rules) group the units, its indoor
    /// rules type the rooms. Refused if the room rules do not parse or lack `SameRoom`.
    pub fn new(config: RoomConfig, knowledge: &KnowledgeConfig) -> Result<RoomLayer, RoomError> {
        let frontier = FrontierRules::parse(knowledge.frontier_kb.as_deref().unwrap_or(BUILTIN_FRONTIER_RULES))
            .map_err(|e| RoomError::frontier("reading them", e))?;
        let knowledge = match knowledge.enabled {
            true => Some(RoomKnowledge::configured(knowledge).map_err(|e| RoomError::rules("reading them", e))?),
            false => None,
        };
        Ok(RoomLayer { config, knowledge, frontier: Some(frontier) })
    }

    /// The layer with `config`'s lengths and no rules: every open pair of units joins, rooms
    /// take the type of the units covering most of their cells, and no placeholder is found.
    pub fn without_knowledge(config: RoomConfig) -> RoomLayer {
        RoomLayer { config, knowledge: None, frontier: None }
    }

    /// The layer's lengths and areas.
    pub fn config(&self) -> &RoomConfig {
        &self.config
    }

    /// Groups `world`'s units into rooms as `grouping` says, labels the map with one id per
    /// room, fills `world.rooms` (typed, with their doors and neighbours), marks the doors
    /// that are openings within a room and, last, finds the placeholders where seen space meets
    /// unseen space and weighs what lies beyond them ([`crate::floorplan::frontier`]). Returns
    /// the label image (`labels.pgm`).
    ///
    /// ```
    /// use ksmcmc::floorplan::knowledge::KnowledgeConfig;
    /// use ksmcmc::floorplan::rooms::{Grouping, RoomConfig, RoomLayer, RoomMaps};
    /// use ksmcmc::floorplan::{Unit, UnitType, World};
    /// use ksmcmc::grid::{Cell, Grid};
    ///
    /// // Two 40x40 units side by side with no wall between them: one room of 2 x 1,600 cells.
    /// let map = Grid::new(80, 40, Cell::Free);
    /// let mut world = World::empty(80, 40);
    /// for (id, x) in [(1, 0), (2, 40)] {
    ///     world.units.push(Unit::new(id, x, 0, 40, 40, UnitType::Room));
    /// }
    /// let layer = RoomLayer::new(RoomConfig::default(), &KnowledgeConfig::default())?;
    /// let maps = RoomMaps { map: &map, world_map: &map, resolution: 0.05 };
    /// let labels = layer.explain(&mut world, maps, Grouping::Units(&Default::default()))?;
    /// assert_eq!(world.rooms.len(), 1);
    /// assert_eq!(world.rooms[0].units, vec![1, 2]);
    /// assert_eq!(*labels.at(10, 10), *labels.at(70, 10));
    ///
    /// // Two rooms, 3 m square, parted by a wall along row 60 with a 1 m doorway: one unit
    /// // spans both, and grouped by the walls they are two.
    /// let mut map = Grid::new(60, 121, Cell::Free);
    /// for x in (0..20).chain(40..60) {
    ///     *map.at_mut(x, 60) = Cell::Occupied;
    /// }
    /// let mut world = World::empty(60, 121);
    /// world.units = vec![Unit::new(1, 0, 0, 60, 121, UnitType::Room)];
    /// let layer = RoomLayer::without_knowledge(RoomConfig { min_wall_len_m: 0.5, ..RoomConfig::default() });
    /// let maps = RoomMaps { map: &map, world_map: &map, resolution: 0.05 };
    /// let labels = layer.explain(&mut world, maps, Grouping::Walls(&[]))?;
    /// assert_eq!(world.rooms.len(), 2);
    /// assert_ne!(labels.at(30, 10), labels.at(30, 110));
    /// # Ok::<(), ksmcmc::floorplan::rooms::RoomError>(())
    /// ```
    pub fn explain(&self, world: &mut World, maps: RoomMaps, grouping: Grouping) -> Result<Grid<u16>, RoomError> {
        let walls = self.read_walls(world, maps, grouping);
        self.explain_read(world, maps, grouping, &walls)
    }

    /// The first stage of [`RoomLayer::explain`]: the walls of the maps as the layer reads
    /// them for `world`. It asks only where the units lie, never their types, so a caller may
    /// read the walls of a world while the Markov logic engine types it
    /// ([`crate::floorplan::Chain::best_world_with_rooms`] does).
    pub(crate) fn read_walls(&self, world: &World, maps: RoomMaps, grouping: Grouping) -> WallReading {
        let c = &self.config.cells(maps.resolution);
        match grouping {
            Grouping::Units(_) => WallReading::with_world_open(world, maps.map, maps.world_map, c),
            Grouping::Walls(angles) => WallReading::new(world, maps.map, maps.world_map, c, angles),
        }
    }

    /// The rest of [`RoomLayer::explain`], on the walls [`RoomLayer::read_walls`] read for a
    /// world with these units.
    pub(crate) fn explain_read(
        &self,
        world: &mut World,
        maps: RoomMaps,
        grouping: Grouping,
        walls: &WallReading,
    ) -> Result<Grid<u16>, RoomError> {
        let c = &self.config.cells(maps.resolution);
        let kb = self.knowledge.as_ref();
        let labels = match grouping {
            Grouping::Units(edits) => by_units(world, maps, c, kb, edits, walls)?,
            Grouping::Walls(_) => {
                let groups: Vec<u16> = join(world, maps.world_map, []).into_iter().map(|g| u16::from(g > 0)).collect();
                let labels = labels_read(world, &groups, maps.map, maps.world_map, c, walls);
                rooms_of_segments(world, &labels, maps, kb, walls)?;
                labels
            }
        };
        super::openings::mark_openings(world, &walls.open, maps.resolution);
        if let Some(rules) = &self.frontier {
            world.placeholders = placeholders(world, maps.map, &labels, maps.resolution, rules)
                .map_err(|e| RoomError::frontier("weighing the placeholders", e))?;
        }
        Ok(labels)
    }

    /// Marks the doors of a world composed after its rooms were found (the wings' world,
    /// [`crate::floorplan::wings::WingLayout::compose`]) that are openings within one room, on
    /// `map` (the classified map in its own frame) at `resolution` metres per cell.
    pub fn mark_openings(&self, world: &mut World, map: &Grid<Cell>, resolution: f64) {
        let c = self.config.cells(resolution);
        let walls = without_clutter(map, c.min_wall_len, c.wall_piece_thick, c.hole_reach);
        super::openings::mark_openings(world, &walls, resolution);
    }
}

/// The rooms grouped by units ([`Grouping::Units`]) under `edits`.
fn by_units(
    world: &mut World,
    maps: RoomMaps,
    c: &RoomCells,
    knowledge: Option<&RoomKnowledge>,
    edits: &Edits,
    read: &WallReading,
) -> Result<Grid<u16>, RoomError> {
    let RoomMaps { map, world_map, .. } = maps;
    let walls = edits.world_wall_cells(map, &world.frame);
    let apart = |a: usize, b: usize| Edits::separates(&walls, world.units[a].rect(), world.units[b].rect());
    let merged = edits.merged_units(world);
    let mut given: Vec<(usize, usize, bool)> = merged.iter().map(|&(a, b)| (a, b, true)).collect();
    let mut pairs: Vec<OpenPair> = open_pairs_among(world, world_map, c, &read.open_in_world(map, world_map, c));
    mark_closed(world, map, world_map, &mut pairs, c, read);
    given.extend(pairs.iter().filter(|p| apart(p.a, p.b)).map(|p| (p.a, p.b, false)));
    // Where the walls part two units (closed pairs), the splits of the room layer draw the
    // line between them more exactly than the units' edges: closed pairs are joined and
    // parted again by the walls ([`labels_of_groups`]).
    let mut joined: Vec<(usize, usize)> = match knowledge {
        Some(k) => {
            let p = k.same_room_given(world, &pairs, &given).map_err(|e| RoomError::rules("grouping units", e))?;
            let keep = |(q, p): &(&OpenPair, f64)| *p > 0.5 || q.closed && !apart(q.a, q.b);
            pairs.iter().zip(p).filter(keep).map(|(q, _)| (q.a, q.b)).collect()
        }
        None => pairs.iter().filter(|p| !apart(p.a, p.b)).map(|p| (p.a, p.b)).collect(),
    };
    joined.extend(merged);
    let groups = join(world, world_map, joined);
    let mut labels = labels_read(world, &groups, map, world_map, c, read);
    edits.apply_to_labels(&mut labels, map);
    rooms_of_segments(world, &labels, maps, knowledge, read)?;
    edits.apply_to_rooms(&mut world.rooms, &labels);
    Ok(labels)
}

/// Fills in `world.rooms` from the room `labels`: the rooms read off the labels
/// ([`rooms_of_labels`]), typed by the indoor rules when `knowledge` is on
/// ([`super::types::type_rooms`]), rays typed unknown ([`mark_unexplored_on`], on the walls
/// read already).
fn rooms_of_segments(
    world: &mut World,
    labels: &Grid<u16>,
    maps: RoomMaps,
    knowledge: Option<&RoomKnowledge>,
    walls: &WallReading,
) -> Result<(), RoomError> {
    world.rooms = rooms_of_labels(world, labels, maps.resolution);
    if let Some(k) = knowledge {
        super::types::type_rooms(world, labels, maps.resolution, k.types())
            .map_err(|e| RoomError::rules("typing the rooms", e))?;
    }
    mark_unexplored_on(&mut world.rooms, labels, maps.map, &walls.standing, maps.resolution);
    Ok(())
}

/// The segmentation in the map's frame with every open pair of units joined: every free map
/// cell of a room gets the room's id (1..=n), other cells 0. `world_map` is the classified
/// map in the world frame, `map` in the map frame.
pub(crate) fn room_labels(world: &World, map: &Grid<Cell>, world_map: &Grid<Cell>, c: &RoomCells) -> Grid<u16> {
    labels_of_groups(world, &group_units(world, world_map, c), map, world_map, c)
}

/// Marks the open pairs whose units the room layer's geometry parts (`closed`): with every
/// open pair joined, the doorway split and the wall gaps ([`labels_of_groups`]) still leave
/// the two units mostly in different segments (`unit_rooms`). It is evidence for the room
/// rules (`Closed`): on the chain's worlds of the benchmark floors, nine in ten open pairs
/// that geometry does not part lie in one drawn room, and four in five that it parts do not.
pub(crate) fn mark_closed(
    world: &World,
    map: &Grid<Cell>,
    world_map: &Grid<Cell>,
    pairs: &mut [OpenPair],
    c: &RoomCells,
    read: &WallReading,
) {
    if pairs.is_empty() {
        return;
    }
    let groups = join(world, world_map, pairs.iter().map(|p| (p.a, p.b)));
    let labels = labels_read(world, &groups, map, world_map, c, read);
    let segment = unit_rooms(world, world_map, &labels);
    for p in pairs {
        p.closed = segment[p.a] != segment[p.b];
    }
}

#[cfg(test)]
mod tests {
    use super::super::knowledge::room_evidence;
    use super::super::pairs::open_pairs;
    use super::*;
    use crate::floorplan::{Door, Unit, UnitType};

    #[test]
    fn walls_that_run_on_either_side_close_a_room_open_onto_a_corridor() {
        // A room 2.5 m wide (50 cells) open over its whole width onto a corridor above it, the
        // corridor's wall (row 40) running on either side: a person closes the room's front.
        let mut map = Grid::new(200, 100, Cell::Free);
        for x in (0..75).chain(125..200) {
            *map.at_mut(x, 40) = Cell::Occupied;
        }
        for y in 40..100 {
            *map.at_mut(75, y) = Cell::Occupied;
            *map.at_mut(125, y) = Cell::Occupied;
        }
        let mut world = World::empty(200, 100);
        world.units =
            vec![Unit::new(1, 0, 0, 200, 41, UnitType::Corridor), Unit::new(2, 75, 40, 51, 60, UnitType::Room)];
        let c = RoomCells::default();
        let mut pairs = open_pairs(&world, &map, &c);
        assert_eq!(pairs.len(), 1);
        mark_closed(&world, &map, &map, &mut pairs, &c, &WallReading::new(&world, &map, &map, &c, &[]));
        assert!(pairs[0].closed);
        // Without wall gaps nothing parts them.
        let open = RoomCells { max_wall_gap: 0, ..c };
        mark_closed(&world, &map, &map, &mut pairs, &open, &WallReading::new(&world, &map, &map, &open, &[]));
        assert!(!pairs[0].closed);
    }

    /// The layer with settings `c` and rules `knowledge`, grouping by units without edits.
    fn explain_rooms(
        world: &mut World,
        map: &Grid<Cell>,
        world_map: &Grid<Cell>,
        c: &RoomConfig,
        resolution: f64,
        knowledge: Option<&RoomKnowledge>,
    ) -> Result<Grid<u16>, RoomError> {
        let layer = RoomLayer { config: *c, knowledge: knowledge.cloned(), frontier: None };
        layer.explain(world, RoomMaps { map, world_map, resolution }, Grouping::Units(&Edits::default()))
    }

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
        mark_closed(&world, &map, &map, &mut pairs, &cells, &WallReading::new(&world, &map, &map, &cells, &[]));
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
        // Rules without the query are refused when the configuration is checked, and by the
        // layer made of it.
        config.room_kb = Some("Open(unit, unit)\n".into());
        let e = config.validate().unwrap_err();
        assert_eq!(e.field(), "knowledge.room_kb");
        let cause = std::error::Error::source(&e).map(|c| c.to_string()).unwrap_or_default();
        assert!(cause.contains("SameRoom"), "{e}");
        let e = RoomLayer::new(c, &config).unwrap_err().to_string();
        assert!(e.contains("room rules") && e.contains("SameRoom"), "{e}");
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
        let map = crate::floorplan::rooms::segments::tests::walled_room(200, 200);
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
