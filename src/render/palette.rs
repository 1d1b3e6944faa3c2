//! The colours of every picture: the papers' wall, door and object colours, and one colour per
//! unit type shared by the map's tints, the scene graph and the legend.

use crate::floorplan::UnitType;

/// Wall cells (each unit's outer ring), drawn opaque: the papers' blue.
pub const WALL_RGBA: [u8; 4] = [0, 0, 255, 255];
/// Door cells, drawn opaque over the walls: the papers' cyan.
pub const DOOR_RGBA: [u8; 4] = [0, 255, 255, 255];
/// Object cells (unknown cells inside units), semi-transparent green so the map shows through.
pub const OBJECT_RGBA: [u8; 4] = [0, 255, 0, 150];
/// Unexplained free areas (the papers' "N"), semi-transparent orange: where the model gave up.
pub const UNEXPLAINED_RGBA: [u8; 4] = [255, 140, 0, 120];
/// Label text: dark red, as the papers print unit types and ids in red.
pub const LABEL_TEXT_RGBA: [u8; 4] = [150, 0, 0, 255];
/// Label background box: light and mostly opaque, so a label reads over black and white alike.
pub const LABEL_BACKGROUND_RGBA: [u8; 4] = [255, 255, 255, 215];
/// Label box outline: dark gray, one pixel wide.
pub const LABEL_OUTLINE_RGBA: [u8; 4] = [40, 40, 40, 255];

/// The colour of a unit type, the one palette of every picture (the map's room tints, the
/// scene graph's nodes, the legend): the Okabe-Ito colours, which stay distinguishable with
/// the common colour-vision deficiencies: room orange, corridor sky blue, hall bluish green,
/// other reddish purple, unknown (not yet typed) gray.
pub fn unit_type_rgb(kind: UnitType) -> [u8; 3] {
    match kind {
        UnitType::Room => [230, 159, 0],
        UnitType::Corridor => [86, 180, 233],
        UnitType::Hall => [0, 158, 115],
        UnitType::Other => [204, 121, 167],
        UnitType::Unknown => [175, 175, 175],
    }
}

/// The light tint a unit's interior gets on the map: its type colour ([`unit_type_rgb`]) at
/// [`ROOM_FILL_STRENGTH`] over white. It is multiplied into the map, so a free (white) cell
/// shows exactly this colour and an occupied (black) cell stays black.
pub fn room_fill_rgb(kind: UnitType) -> [u8; 3] {
    unit_type_rgb(kind).map(|c| 255 - ((255 - c as u32) * ROOM_FILL_STRENGTH / 100) as u8)
}

/// How strongly interiors are tinted, percent: light, so that labels, object cells and the
/// stronger orange of unexplained space stand out against it.
pub const ROOM_FILL_STRENGTH: u32 = 35;
