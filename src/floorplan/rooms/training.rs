//! Training worlds for the room rules: the evidence the room layer gives the rules about a
//! chain's world, with the `SameRoom` answer a person's drawing gives.
//!
//! The room rules (`samples/knowledge/rooms.mln`, [`super::RoomKnowledge`]) decide
//! which units with no wall between them are one room. Their weights can be learned
//! (`ksmcmc mln learn`) only from worlds like those they judge: the chain's, with its seams,
//! slivers and rectangles across slanted rooms, not the synthetic truth, whose units are
//! already the rooms. So a training world is a chain's explained world of a synthetic floor
//! with the floor's truth labels beside it: the evidence is exactly what the room layer feeds
//! the rules ([`room_evidence`] of [`open_pairs`]), and `SameRoom(a, b)` is true for an open
//! pair whose two units lie mostly in the same truth room. A unit lies in the truth room that
//! holds most of its free interior cells; a unit with no free interior cell in any truth room
//! (a sliver over a wall, or over space the truth leaves unlabelled) lies in none, and is one
//! room with no neighbour.

use super::config::RoomConfig;
use super::error::RoomError;
use super::knowledge::room_evidence;
use super::layer::mark_closed;
use super::pairs::open_pairs;
use super::read::unit_rooms;
use super::wall_gaps::WallReading;
use crate::floorplan::knowledge::{constant, Fact};
use crate::floorplan::world::World;
use crate::grid::{Cell, Grid};
use std::collections::BTreeMap;

/// A training world for the room rules.
#[derive(Debug, Clone, PartialEq)]
pub struct RoomTraining {
    /// The evidence (what the room layer gives the rules) and every `SameRoom` atom of the world's units, true
    /// or false; [`crate::floorplan::knowledge::database_text`] writes the true ones (the rest are false
    /// by the closed world of training databases).
    pub facts: Vec<Fact>,
    /// Per unit of the world (in order), the truth room it lies in (its truth label), if any.
    pub truth_rooms: Vec<Option<u16>>,
    /// Open pairs of units.
    pub open_pairs: usize,
    /// Open pairs whose units lie in the same truth room.
    pub same_room: usize,
}

/// The training world of `world`, a chain's typed world (as [`crate::floorplan::Chain::best_world_typed`]
/// gives it), with `world_map` the classified map in the world frame and `truth` the truth
/// labels in the map's frame (per map cell the truth room's id, 0 for none: the
/// `truth_labels.pgm` of `ksmcmc synth`). Refused if the grids are not the sizes the world's
/// frame gives. `rooms` are the room layer's settings, `resolution` the map's metres per cell.
///
/// ```
/// use ksmcmc::floorplan::rooms::{room_training, RoomConfig};
/// use ksmcmc::floorplan::{Unit, UnitType, World};
/// use ksmcmc::grid::{Cell, Grid};
///
/// // One 80x40 truth room explained by two units with no wall between them.
/// let map = Grid::new(80, 40, Cell::Free);
/// let truth = Grid::new(80, 40, 1u16);
/// let mut world = World::empty(80, 40);
/// for (id, x) in [(1, 0), (2, 40)] {
///     world.units.push(Unit::new(id, x, 0, 40, 40, UnitType::Room));
/// }
/// let t = room_training(&world, &map, &map, &truth, &RoomConfig::default(), 0.05)?;
/// assert_eq!((t.open_pairs, t.same_room), (1, 1));
/// assert!(t.facts.contains(&("SameRoom", vec!["U1".to_string(), "U2".to_string()], true)));
/// # Ok::<(), ksmcmc::floorplan::rooms::RoomError>(())
/// ```
pub fn room_training(
    world: &World,
    map: &Grid<Cell>,
    world_map: &Grid<Cell>,
    truth: &Grid<u16>,
    rooms: &RoomConfig,
    resolution: f64,
) -> Result<RoomTraining, RoomError> {
    let c = &rooms.cells(resolution);
    world.require_one_direction("learning which units are one room").map_err(|e| RoomError::training(e.to_string()))?;
    let size = |g: (usize, usize)| [g.0 as u32, g.1 as u32];
    if size((truth.width(), truth.height())) != world.frame.map_size {
        return Err(RoomError::training(format!(
            "the truth labels are {}x{} cells, but the world explains a {}x{} map (frame.map_size): they \
             belong to another map",
            truth.width(),
            truth.height(),
            world.frame.map_size[0],
            world.frame.map_size[1]
        )));
    }
    if size((world_map.width(), world_map.height())) != world.frame.world_size {
        return Err(RoomError::training(format!(
            "the world-frame map is {}x{} cells, but the world's frame.world_size is {}x{}",
            world_map.width(),
            world_map.height(),
            world.frame.world_size[0],
            world.frame.world_size[1]
        )));
    }
    let mut pairs = open_pairs(world, world_map, c);
    mark_closed(world, map, world_map, &mut pairs, c, &WallReading::new(world, map, world_map, c, &[]));
    let truth_rooms = unit_rooms(world, world_map, truth);
    let mut facts = room_evidence(world, &pairs);
    let mut same = BTreeMap::new();
    for p in &pairs {
        if truth_rooms[p.a].is_some() && truth_rooms[p.a] == truth_rooms[p.b] {
            same.insert((p.a, p.b), ());
            same.insert((p.b, p.a), ());
        }
    }
    for (i, a) in world.units.iter().enumerate() {
        for (j, b) in world.units.iter().enumerate().filter(|&(j, _)| j != i) {
            facts.push(("SameRoom", vec![constant(a.id), constant(b.id)], same.contains_key(&(i, j))));
        }
    }
    Ok(RoomTraining { facts, truth_rooms, open_pairs: pairs.len(), same_room: same.len() / 2 })
}

/// Truth labels from a PGM (P2 or P5, 8 or 16 bits, such as `truth_labels.pgm` of
/// `ksmcmc synth`): one gray value per truth room, 0 where there is none. Only which cells
/// share a value matters, so an 8-bit image's scaled values do as well.
///
/// ```
/// use ksmcmc::floorplan::rooms::truth_labels_from_pgm;
/// let labels = truth_labels_from_pgm(b"P2\n2 1\n65535\n0 7\n")?;
/// assert_eq!(labels.cells(), &[0, 7]);
/// assert!(truth_labels_from_pgm(b"P6\n").is_err());
/// # Ok::<(), ksmcmc::floorplan::rooms::RoomError>(())
/// ```
pub fn truth_labels_from_pgm(bytes: &[u8]) -> Result<Grid<u16>, RoomError> {
    crate::grid::pgm::decode(bytes, &Default::default())
        .map(|r| r.gray)
        .map_err(|e| RoomError::training(format!("truth labels: {e} (expected a PGM such as truth_labels.pgm)")))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::floorplan::{Unit, UnitType};

    fn unit(id: u32, x: i32, y: i32, w: i32, h: i32, kind: UnitType) -> Unit {
        Unit::new(id, x, y, w, h, kind)
    }

    /// A 200 x 100 floor: a corridor along the top (rows 0..40, truth room 1), and below it
    /// one office (truth room 2) opening onto it over its whole width, explained by a
    /// corridor unit and two room units that split the office at column 100.
    fn office_off_a_corridor() -> (Grid<Cell>, Grid<u16>, World) {
        let map = Grid::new(200, 100, Cell::Free);
        let cells = (0..100).flat_map(|y| [if y < 40 { 1u16 } else { 2 }; 200]).collect();
        let truth = Grid::from_vec(200, 100, cells).unwrap();
        let mut world = World::empty(200, 100);
        world.units = vec![
            unit(1, 0, 0, 200, 41, UnitType::Corridor),
            unit(2, 0, 40, 101, 60, UnitType::Room),
            unit(3, 100, 40, 100, 60, UnitType::Room),
        ];
        (map, truth, world)
    }

    fn same_room(t: &RoomTraining, a: &str, b: &str) -> bool {
        t.facts.iter().any(|(p, args, v)| *p == "SameRoom" && args == &[a.to_string(), b.to_string()] && *v)
    }

    #[test]
    fn two_units_of_one_truth_room_are_one_room_and_the_corridor_is_apart() {
        let (map, truth, world) = office_off_a_corridor();
        let c = RoomConfig { door_half_width_m: 0.0, ..RoomConfig::default() };
        let t = room_training(&world, &map, &map, &truth, &c, 0.05).unwrap();
        assert_eq!(t.truth_rooms, vec![Some(1), Some(2), Some(2)]);
        assert_eq!(t.open_pairs, 3, "{:?}", t.facts);
        assert_eq!(t.same_room, 1);
        assert!(same_room(&t, "U2", "U3") && same_room(&t, "U3", "U2"));
        assert!(!same_room(&t, "U1", "U2") && !same_room(&t, "U2", "U1"));
        // Every ordered pair of distinct units has its SameRoom atom, true or false.
        assert_eq!(t.facts.iter().filter(|f| f.0 == "SameRoom").count(), 6);
        // The evidence is the room layer's own.
        assert!(t.facts.contains(&("Corr", vec!["U1".into()], true)));
        assert!(t.facts.contains(&("Open", vec!["U1".into(), "U2".into()], true)));
        assert!(t.facts.contains(&("Flush", vec!["U3".into(), "U2".into()], true)));
    }

    #[test]
    fn a_unit_over_no_truth_room_is_alone() {
        let (map, mut truth, world) = office_off_a_corridor();
        for y in 40..100 {
            for x in 100..200 {
                *truth.at_mut(x, y) = 0;
            }
        }
        let c = RoomConfig { door_half_width_m: 0.0, ..RoomConfig::default() };
        let t = room_training(&world, &map, &map, &truth, &c, 0.05).unwrap();
        assert_eq!(t.truth_rooms[2], None);
        assert!(!same_room(&t, "U2", "U3"));
        assert_eq!(t.same_room, 0);
    }

    #[test]
    fn grids_of_another_map_are_refused() {
        let (map, truth, world) = office_off_a_corridor();
        let small = Grid::new(100, 100, 1u16);
        let e = room_training(&world, &map, &map, &small, &RoomConfig::default(), 0.05).unwrap_err();
        assert!(e.to_string().contains("truth labels are 100x100"), "{e}");
        let e = room_training(&world, &map, &Grid::new(20, 20, Cell::Free), &truth, &RoomConfig::default(), 0.05)
            .unwrap_err();
        assert!(e.to_string().contains("world-frame map is 20x20"), "{e}");
    }
}
