//! What the knowledge base believes about each room's type: its units' type marginals,
//! averaged over the room.
//!
//! Markov logic types units, not rooms: inference gives every unit four marginals,
//! `P(Room)`, `P(Corr)`, `P(Hall)` and `P(Other)` ([`Inferred`]), and the unit's type is the
//! most probable. A room of the room layer is one or more units ([`super::room_layer`]), and
//! its type is the type covering most of its cells. A reader who hovers a room wants to know
//! how sure that type is; this module answers with the room's marginals as the mean of its
//! units' marginals weighted by each unit's interior (its free area inside the walls), the
//! same weighting that makes the room's type, so that a small cupboard merged into an office
//! does not count as much as the office.
//!
//! The four predicates of the knowledge base are separate atoms, not one variable with four
//! values: the rules make them exclude each other only softly, so the four numbers need not
//! add up to 1. They are given as inferred, not normalised.

use super::knowledge::Inferred;
use super::world::{UnitType, World};
use serde::Serialize;

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
/// [`super::Chain::best_world_with_rooms`] gives it) from the inference `inferred` on the same
/// units, in the order of `world.rooms`.
///
/// ```
/// use ksmcmc::floorplan::knowledge::Inferred;
/// use ksmcmc::floorplan::room_types::room_types;
/// use ksmcmc::floorplan::{Room, Unit, UnitType, World};
///
/// let mut world = World::empty(100, 40);
/// world.wall_thickness = 1;
/// // Unit 1's interior is 58 x 38 cells, unit 2's 38 x 38.
/// world.units.push(Unit { id: 1, x: 0, y: 0, w: 60, h: 40, kind: UnitType::Room });
/// world.units.push(Unit { id: 2, x: 60, y: 0, w: 40, h: 40, kind: UnitType::Other });
/// world.rooms.push(Room { id: 1, kind: UnitType::Room, units: vec![1, 2], area_m2: 10.0, doors: vec![], opens_to: vec![], name: None });
/// let mut inferred = Inferred::default();
/// inferred.types.insert(1, (UnitType::Room, [1.0, 0.0, 0.0, 0.0]));
/// inferred.types.insert(2, (UnitType::Other, [0.0, 0.0, 0.0, 1.0]));
///
/// let rooms = room_types(&world, &inferred);
/// let p = rooms[0].marginals.unwrap();
/// assert!((p.room - 58.0 / 96.0).abs() < 1e-12 && (p.other - 38.0 / 96.0).abs() < 1e-12);
/// assert_eq!(rooms[0].units[1].kind, UnitType::Other);
/// ```
pub fn room_types(world: &World, inferred: &Inferred) -> Vec<RoomTypes> {
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
            let marginals = (weight > 0.0).then(|| TypeMarginals::of(sum.map(|s| s / weight)));
            RoomTypes { id: room.id, marginals, units }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::floorplan::{Room, Unit};

    #[test]
    fn a_room_without_inferred_units_has_no_marginals() {
        let mut world = World::empty(50, 50);
        world.units.push(Unit { id: 4, x: 0, y: 0, w: 20, h: 20, kind: UnitType::Unknown });
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
        let rooms = room_types(&world, &Inferred::default());
        assert_eq!(rooms.len(), 2);
        assert!(rooms.iter().all(|r| r.marginals.is_none()));
        assert_eq!(rooms[1].units, vec![UnitTypes { id: 4, kind: UnitType::Unknown, marginals: None }]);
    }

    #[test]
    fn one_unit_rooms_carry_their_units_marginals() {
        let mut world = World::empty(50, 50);
        world.units.push(Unit { id: 3, x: 0, y: 0, w: 30, h: 8, kind: UnitType::Corridor });
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
        let rooms = room_types(&world, &inferred);
        let p = rooms[0].marginals.unwrap();
        assert_eq!([p.room, p.corridor, p.hall, p.other], [0.1, 0.8, 0.05, 0.2]);
        assert_eq!(rooms[0].id, 7);
    }
}
