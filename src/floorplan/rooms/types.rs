//! What the knowledge base believes about each room's type.
//!
//! Markov logic types units: inference gives every unit four marginals, `P(Room)`,
//! `P(Corr)`, `P(Hall)` and `P(Other)` ([`Inferred`]), and the unit's type is the most
//! probable. A room of the room layer is one or more units ([`super::RoomLayer`]). A person
//! types the room as one space, so with knowledge supervision the same rules are applied to
//! the rooms themselves ([`room_marginals`], [`type_rooms`]): a foyer of many small units is a
//! hall, not a room of "other" pieces. Without it (or for a room the rules were not applied
//! to) a room's marginals are the mean of its units' weighted by each unit's interior (its
//! free area inside the walls), so that a small cupboard merged into an office does not
//! count as much as the office.
//!
//! The four predicates of the knowledge base are separate atoms, not one variable with four
//! values: the rules make them exclude each other only softly, so the four numbers need not
//! add up to 1. They are given as inferred, not normalised.

use crate::floorplan::knowledge::{Inferred, Knowledge, KnowledgeConfig};
use crate::floorplan::world::{Room, Unit, UnitType, World};
use crate::grid::Grid;
use serde::Serialize;
use std::collections::BTreeMap;

/// A room's type marginals and its units with their types.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RoomTypes {
    /// The room's id (its value in `labels.pgm`).
    pub id: u32,
    /// The area-weighted mean of its units' marginals; `None` when none of its units was
    /// inferred (a room of unexplained free space has no units).
    pub marginals: Option<TypeMarginals>,
    /// Its units, each with its own type and marginals.
    pub units: Vec<UnitTypes>,
}

/// One unit of a [`RoomTypes`].
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct UnitTypes {
    /// The unit's id.
    pub id: u32,
    /// Its type, as in `world.json`.
    #[serde(rename = "type")]
    pub kind: UnitType,
    /// Its marginals, if inferred.
    pub marginals: Option<TypeMarginals>,
}

/// `P(Room)`, `P(Corr)`, `P(Hall)` and `P(Other)` of a unit or room.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct TypeMarginals {
    /// P(Room).
    pub room: f64,
    /// P(Corr).
    pub corridor: f64,
    /// P(Hall).
    pub hall: f64,
    /// P(Other).
    pub other: f64,
}

impl TypeMarginals {
    fn of(p: [f64; 4]) -> TypeMarginals {
        TypeMarginals { room: p[0], corridor: p[1], hall: p[2], other: p[3] }
    }
}

/// The type marginals of every room of `world` (whose room layer is filled in, as
/// [`crate::floorplan::Chain::best_world_with_rooms`] gives it), in the order of `world.rooms`: those
/// in `rooms` (room ids to the room-level marginals of [`room_marginals`]) where given, else
/// from the inference `inferred` on its units. Its units come with their own marginals.
///
/// ```
/// use ksmcmc::floorplan::knowledge::Inferred;
/// use ksmcmc::floorplan::rooms::room_types;
/// use ksmcmc::floorplan::{Room, Unit, UnitType, World};
///
/// let mut world = World::empty(100, 40);
/// world.wall_thickness = 1;
/// // Unit 1's interior is 58 x 38 cells, unit 2's 38 x 38.
/// world.units.push(Unit::new(1, 0, 0, 60, 40, UnitType::Room));
/// world.units.push(Unit::new(2, 60, 0, 40, 40, UnitType::Other));
/// world.rooms.push(Room { id: 1, kind: UnitType::Room, units: vec![1, 2], area_m2: 10.0, doors: vec![], opens_to: vec![], name: None });
/// let mut inferred = Inferred::default();
/// inferred.types.insert(1, (UnitType::Room, [1.0, 0.0, 0.0, 0.0]));
/// inferred.types.insert(2, (UnitType::Other, [0.0, 0.0, 0.0, 1.0]));
///
/// let rooms = room_types(&world, &inferred, &Default::default());
/// let p = rooms[0].marginals.unwrap();
/// assert!((p.room - 58.0 / 96.0).abs() < 1e-12 && (p.other - 38.0 / 96.0).abs() < 1e-12);
/// assert_eq!(rooms[0].units[1].kind, UnitType::Other);
/// // The room's own marginals, where the rules were applied to it, come first.
/// let own = [(1, [0.9, 0.0, 0.1, 0.0])].into_iter().collect();
/// assert_eq!(room_types(&world, &inferred, &own)[0].marginals.unwrap().room, 0.9);
/// ```
pub fn room_types(world: &World, inferred: &Inferred, rooms: &BTreeMap<u32, [f64; 4]>) -> Vec<RoomTypes> {
    let t = world.wall_thickness.max(0);
    world
        .rooms
        .iter()
        .map(|room| {
            let mut sum = [0.0; 4];
            let mut weight = 0.0;
            let mut units = Vec::new();
            for u in room.units.iter().filter_map(|id| world.units.iter().find(|u| u.id == *id)) {
                let p = inferred.types.get(&u.id).map(|t| t.1);
                if let Some(p) = p {
                    let w = ((u.w - 2 * t).max(1) as f64) * ((u.h - 2 * t).max(1) as f64);
                    for (s, v) in sum.iter_mut().zip(p) {
                        *s += w * v;
                    }
                    weight += w;
                }
                units.push(UnitTypes { id: u.id, kind: u.kind, marginals: p.map(TypeMarginals::of) });
            }
            let marginals = match rooms.get(&room.id) {
                Some(&p) => Some(TypeMarginals::of(p)),
                None => (weight > 0.0).then(|| TypeMarginals::of(sum.map(|s| s / weight))),
            };
            RoomTypes { id: room.id, marginals, units }
        })
        .collect()
}

/// Each room's cells and its length (cells) in the world frame, by room id: the length of
/// the rectangle with the same spread along the room's longer world axis (a run of `L` cells
/// has variance `(L² - 1) / 12`). A room is then a rectangle as long as that and as wide as
/// its area allows. The few cells a room reaches into its doorways through thick walls, or
/// a ragged scanned edge, move its spread far less than its bounding box: office_c's
/// 15 m2 offices, 2.65 m wide, were "narrow" (and so "other") by their box.
fn room_extents(world: &World, labels: &Grid<u16>) -> BTreeMap<u16, (usize, f64)> {
    let rotation = world.frame.rotation();
    // Cells, and the sums of x, y, x² and y² in the world frame (about the room's first cell).
    let mut sums: BTreeMap<u16, (usize, [f64; 2], [f64; 4])> = BTreeMap::new();
    for y in 0..labels.height() {
        for x in 0..labels.width() {
            let l = *labels.at(x, y);
            if l == 0 {
                continue;
            }
            let (wx, wy) = rotation.to_world(x as f64 + 0.5, y as f64 + 0.5);
            let e = sums.entry(l).or_insert((0, [wx, wy], [0.0; 4]));
            let (dx, dy) = (wx - e.1[0], wy - e.1[1]);
            e.0 += 1;
            e.2 = [e.2[0] + dx, e.2[1] + dy, e.2[2] + dx * dx, e.2[3] + dy * dy];
        }
    }
    sums.into_iter()
        .map(|(l, (n, _, s))| {
            let k = n as f64;
            let var = |sum: f64, sq: f64| (sq / k - (sum / k) * (sum / k)).max(0.0);
            let spread = var(s[0], s[2]).max(var(s[1], s[3]));
            (l, (n, libm::sqrt(12.0 * spread + 1.0)))
        })
        .collect()
}

/// The type marginals of each room (by id) from the indoor rules (`config`'s knowledge base)
/// applied to rooms rather than units. A room's geometry evidence (`RoLi`, `CoLi`, `HaLi`,
/// `Small`, `Narrow`: the classifier of Tab. 3.6) is that of a rectangle with the room's
/// spread along its longer world axis and as wide as its area allows; `MulDoor` holds
/// when it opens to two rooms or more (`opens_to`: through doors or openings). Rooms with
/// units are typed, and so are pieces the room layer parted from their units' room (a room
/// with no unit of its own but a type, as the room layer reads rooms off the labels: a small
/// office the walls part from the big unit that spans it is an office, not a piece of a
/// hall). Free space no unit covers (type `unknown`) is not a space the chain has explained,
/// and is not typed. A room of several small units is typed as the one space it is: on
/// Cartesium the open foyers of many units become halls, not rooms made of "other" pieces.
///
/// ```
/// use ksmcmc::floorplan::knowledge::KnowledgeConfig;
/// use ksmcmc::floorplan::rooms::room_marginals;
/// use ksmcmc::floorplan::{Room, UnitType, World};
/// use ksmcmc::grid::Grid;
///
/// // At 5 cm cells: room 1 is 10 x 10 m (a hall by its area), room 2 is 2 x 12 m and opens
/// // to two rooms (a corridor).
/// let mut labels = Grid::new(440, 240, 0u16);
/// for y in 0..200 { for x in 0..200 { *labels.at_mut(x, y) = 1; } }
/// for y in 0..240 { for x in 400..440 { *labels.at_mut(x, y) = 2; } }
/// let world = World::empty(440, 240);
/// let room = |id, opens_to| Room { id, kind: Default::default(), units: vec![id], area_m2: 0.0, doors: vec![], opens_to, name: None };
/// // Room 2 opens to room 1 and to room 3 (beyond the labels here).
/// let rooms = vec![room(1, vec![2]), room(2, vec![1, 3])];
/// let p = room_marginals(&world, &rooms, &labels, 0.05, &KnowledgeConfig::default())?;
/// assert!(p[&1][2] > 0.5, "hall: {:?}", p[&1]);
/// assert!(p[&2][1] > 0.5, "corridor: {:?}", p[&2]);
/// // A room no unit covers (space the chain left unexplained, type unknown) is not typed;
/// // a piece parted from its units' room (no unit of its own, but their type) is.
/// let bare = Room { units: vec![], ..rooms[0].clone() };
/// assert!(room_marginals(&world, &[bare.clone()], &labels, 0.05, &KnowledgeConfig::default())?.is_empty());
/// let piece = Room { kind: UnitType::Room, ..bare };
/// assert!(room_marginals(&world, &[piece], &labels, 0.05, &KnowledgeConfig::default())?[&1][2] > 0.5);
/// # Ok::<(), ksmcmc::mln::MlnError>(())
/// ```
pub fn room_marginals(
    world: &World,
    rooms: &[Room],
    labels: &Grid<u16>,
    resolution: f64,
    config: &KnowledgeConfig,
) -> Result<BTreeMap<u32, [f64; 4]>, crate::mln::MlnError> {
    Ok(infer_rooms(world, rooms, labels, resolution, config)?.into_iter().map(|(id, (_, p))| (id, p)).collect())
}

/// [`room_marginals`] with each room's most probable type ([`Inferred::types`]).
fn infer_rooms(
    world: &World,
    rooms: &[Room],
    labels: &Grid<u16>,
    resolution: f64,
    config: &KnowledgeConfig,
) -> Result<BTreeMap<u32, (UnitType, [f64; 4])>, crate::mln::MlnError> {
    let extents = room_extents(world, labels);
    let mut pseudo = World::empty(1, 1);
    pseudo.wall_thickness = 0;
    let mut x = 0;
    for r in rooms.iter().filter(|r| !r.units.is_empty() || r.kind != UnitType::Unknown) {
        let Some(&(n, long)) = u16::try_from(r.id).ok().and_then(|l| extents.get(&l)) else { continue };
        let h = (long.round() as i32).max(1);
        let w = ((n as f64 / h as f64).round() as i32).clamp(1, h);
        // Far apart: rooms are typed each by its own evidence, with no `Adj` between them.
        pseudo.units.push(Unit::new(r.id, x, 0, w, h, UnitType::Unknown));
        x = x.saturating_add(w.saturating_add(1000));
        for &b in r.opens_to.iter().filter(|&&b| b > r.id) {
            let id = pseudo.doors.len() as u32 + 1;
            pseudo.doors.push(crate::floorplan::world::Door {
                id,
                units: [r.id, b],
                x0: 0,
                y0: 0,
                x1: 0,
                y1: 0,
                opening: false,
            });
        }
    }
    Ok(Knowledge::new(config)?.infer(&pseudo, resolution)?.types)
}

/// Types the rooms (`world.rooms`, read off `labels`) by [`room_marginals`]: each takes its
/// most probable type; a room the rules give no type (free space no unit covers) keeps its
/// own.
pub fn type_rooms(
    world: &mut World,
    labels: &Grid<u16>,
    resolution: f64,
    config: &KnowledgeConfig,
) -> Result<(), crate::mln::MlnError> {
    let types = infer_rooms(world, &world.rooms, labels, resolution, config)?;
    for r in &mut world.rooms {
        match types.get(&r.id) {
            Some(&(kind, _)) if kind != UnitType::Unknown => r.kind = kind,
            _ => {}
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::floorplan::{Room, Unit};

    #[test]
    fn a_room_is_as_long_as_its_spread_not_its_doorway() {
        // A 110 x 53 cell office (room 1) reaching 18 cells into its doorway through a thick
        // wall at its right end; room 2 is a bare 40 x 10 strip.
        let mut labels = Grid::new(200, 100, 0u16);
        for y in 10..63 {
            for x in 10..120 {
                *labels.at_mut(x, y) = 1;
            }
        }
        for y in 30..50 {
            for x in 120..138 {
                *labels.at_mut(x, y) = 1;
            }
        }
        for y in 80..90 {
            for x in 10..50 {
                *labels.at_mut(x, y) = 2;
            }
        }
        let extents = room_extents(&World::empty(200, 100), &labels);
        let (n, long) = extents[&1];
        assert_eq!(n, 110 * 53 + 18 * 20);
        // Its bounding box is 128 long, which would make it 6190 / 128 = 48 cells wide: under
        // 2.5 m at 5 cm cells, narrow as a store. By its spread it is 119 long and 52 wide.
        assert!((110.0..120.0).contains(&long), "{long}");
        assert!(n as f64 / long > 50.0);
        assert!((extents[&2].1 - 40.0).abs() < 1e-9, "{:?}", extents[&2]);
    }

    #[test]
    fn a_room_without_inferred_units_has_no_marginals() {
        let mut world = World::empty(50, 50);
        world.units.push(Unit::new(4, 0, 0, 20, 20, UnitType::Unknown));
        for (id, units) in [(1, vec![]), (2, vec![4])] {
            world.rooms.push(Room {
                id,
                kind: UnitType::Unknown,
                units,
                area_m2: 1.0,
                doors: vec![],
                opens_to: vec![],
                name: None,
            });
        }
        let rooms = room_types(&world, &Inferred::default(), &Default::default());
        assert_eq!(rooms.len(), 2);
        assert!(rooms.iter().all(|r| r.marginals.is_none()));
        assert_eq!(rooms[1].units, vec![UnitTypes { id: 4, kind: UnitType::Unknown, marginals: None }]);
    }

    #[test]
    fn one_unit_rooms_carry_their_units_marginals() {
        let mut world = World::empty(50, 50);
        world.units.push(Unit::new(3, 0, 0, 30, 8, UnitType::Corridor));
        world.rooms.push(Room {
            id: 7,
            kind: UnitType::Corridor,
            units: vec![3],
            area_m2: 1.0,
            doors: vec![],
            opens_to: vec![],
            name: None,
        });
        let mut inferred = Inferred::default();
        inferred.types.insert(3, (UnitType::Corridor, [0.1, 0.8, 0.05, 0.2]));
        let rooms = room_types(&world, &inferred, &Default::default());
        let p = rooms[0].marginals.unwrap();
        assert_eq!([p.room, p.corridor, p.hall, p.other], [0.1, 0.8, 0.05, 0.2]);
        assert_eq!(rooms[0].id, 7);
    }
}
