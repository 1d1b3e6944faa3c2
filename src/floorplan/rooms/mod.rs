//! The room layer: the chain's units grouped into the rooms a person would draw, typed, with
//! their doors, the rooms they open onto, and the label image a room-segmentation benchmark
//! scores.
//!
//! One entry point, one settings struct, one error type: [`RoomLayer::explain`] takes a
//! world and its map ([`RoomMaps`]) and fills in the world's rooms and returns their labels,
//! grouping by units or by walls ([`Grouping`]); [`RoomLayer`] holds the settings (lengths in
//! metres, [`RoomConfig`], and the rules, [`RoomKnowledge`]); every failure is a
//! [`RoomError`]. The command line, `evaluate`, the wasm plan, the wings and the edits all
//! come through it.
//!
//! Its stages are private modules, each owning its numbers:
//!
//! * `config`: the settings in metres and their physical reasons, turned into cells once;
//! * `pairs`: which units touch along an open boundary, and the one union-find that joins them;
//! * `segments`: the label image: units' cells, a wavefront through free space, free regions
//!   beyond every unit, splits at doorways and wall gaps, small segments joined;
//! * `wall_gaps`: where a person closes a room whose wall stops short;
//! * `passages`: rooms touch only where a person can pass, not through the holes of a wall;
//! * `knowledge`: the room rules (`SameRoom`) and the evidence they are given;
//! * `frame`: cells between the map's frame and the world's;
//! * `layer`: the entry point, the grouping and the order of the stages;
//! * `read`: the rooms read off the labels (units, type, doors, neighbours, rays unexplored);
//! * `types`: the indoor rules applied to each room as one space;
//! * `openings`: doors inside one room, openings or contradictions;
//! * `training`: the rules' training worlds from generated floors and their truth.
//!
//! The room layer imports the world, the edits and the knowledge configuration of the floor
//! plan, the frontier stage that ends it ([`crate::floorplan::frontier`]), the grid and the
//! Markov logic engine; nothing of the chain, the wings, the exports or rendering. Those
//! import it.

mod config;
mod error;
mod frame;
mod knowledge;
mod layer;
mod openings;
mod pairs;
mod passages;
mod read;
mod segments;
mod training;
mod types;
mod wall_gaps;

pub use config::{RoomConfig, MAX_ROOM_CONFIG_JSON_BYTES, MAX_ROOM_LENGTH_M};
pub use error::RoomError;
pub use knowledge::{RoomKnowledge, BUILTIN_ROOM_RULES};
pub use layer::{Grouping, RoomLayer, RoomMaps};
pub use openings::doors_in_one_room;
pub use passages::MIN_PASSAGE_M;
pub use read::{SPECK_M, STANDING_CLEARANCE_M};
pub use training::{room_training, truth_labels_from_pgm, RoomTraining};
pub use types::{room_marginals, room_types, RoomTypes, TypeMarginals, UnitTypes};

pub(crate) use layer::room_labels;
pub(crate) use read::map_cell;
