//! The room labels of a saved world: what a route needs when only `world.json` is at hand.
//!
//! Rooms are regions of the label image, which `ksmcmc floorplan` writes as `labels.pgm`
//! beside `world.json`. Without that file the labels are found again from the map and the
//! world's units and doors, exactly as the run found them ([`crate::floorplan::rooms::RoomLayer`], through [`RoomInput::for_map`]): with the
//! built-in room rules (knowledge supervision, the default) or without. The result is used only if its
//! rooms are the world's own (ids, types, units, doors and the rooms each opens to), so a route
//! never names rooms the world does not have; otherwise the caller is told to pass the run's
//! `labels.pgm`.

use super::RouteError;
use crate::floorplan::export::RoomInput;
use crate::floorplan::rooms::RoomConfig;
use crate::floorplan::world::{Room, World};
use crate::grid::{Grid, OccupancyMap};

/// The room labels of `world` on `map` (see the module docs), with the default
/// [`RoomConfig`] that `ksmcmc floorplan` and the live mapper use. A world without a room
/// layer gets the labels of the built-in room rules.
///
/// ```
/// use ksmcmc::floorplan::route::saved_labels;
/// use ksmcmc::floorplan::{synth, Chain, ChainConfig};
/// use ksmcmc::floorplan::rooms::RoomConfig;
/// let s = synth::generate(&synth::SynthConfig { width: 160, height: 120, ..Default::default() }, 3).unwrap();
/// let mut chain = Chain::new(&s.map, ChainConfig::default(), 1).unwrap();
/// chain.step(300);
/// let (world, labels) = chain.best_world_with_rooms(&RoomConfig::default()).unwrap();
/// assert!(saved_labels(&world, &s.map).unwrap() == labels);
/// ```
pub fn saved_labels(world: &World, map: &OccupancyMap) -> Result<Grid<u16>, RouteError> {
    let bare = World { rooms: Vec::new(), ..world.clone() };
    for knowledge in [true, false] {
        let input = RoomInput::for_map(bare.clone(), map, knowledge, Default::default())
            .map_err(|e| RouteError::Mismatch(e.to_string()))?;
        let (found, labels) = input.explain(&RoomConfig::default()).map_err(|e| RouteError::Mismatch(e.to_string()))?;
        if world.rooms.is_empty() || same_rooms(&found.rooms, &world.rooms) {
            return Ok(labels);
        }
    }
    Err(RouteError::Mismatch(
        "world.json: its rooms are not those its units and doors give on this map with the default room \
         settings (it was made with other settings, or edited): pass the labels.pgm written with it"
            .into(),
    ))
}

/// The same rooms: ids, types, units, doors and links (areas depend on the resolution only).
fn same_rooms(a: &[Room], b: &[Room]) -> bool {
    a.len() == b.len()
        && a.iter().zip(b).all(|(a, b)| {
            a.id == b.id && a.kind == b.kind && a.units == b.units && a.doors == b.doors && a.opens_to == b.opens_to
        })
}
