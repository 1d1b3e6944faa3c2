//! Cells between the map's frame and the world's: the room layer labels map cells, while the
//! units and the wall gaps live in the world frame (turned by the walls' angle).

use crate::floorplan::world::World;
use crate::geometry::Rotation;

/// The world-frame cell under map cell `(mx, my)`, if inside a world grid of `size`
/// (width, height); `rotation` is the world frame's ([`crate::geometry::Frame::rotation`]),
/// worked out once for a loop over cells.
pub(crate) fn world_cell(
    world: &World,
    rotation: &Rotation,
    mx: usize,
    my: usize,
    size: (usize, usize),
) -> Option<(usize, usize)> {
    frame_cell(&world.frame, rotation, mx, my, size)
}

/// [`world_cell`] in any `frame` of the map, with its `rotation`.
pub(crate) fn frame_cell(
    frame: &crate::geometry::Frame,
    rotation: &Rotation,
    mx: usize,
    my: usize,
    (ww, wh): (usize, usize),
) -> Option<(usize, usize)> {
    let (wx, wy) = if frame.is_identity() {
        (mx as f64 + 0.5, my as f64 + 0.5)
    } else {
        rotation.to_world(mx as f64 + 0.5, my as f64 + 0.5)
    };
    (wx >= 0.0 && wy >= 0.0 && (wx as usize) < ww && (wy as usize) < wh).then_some((wx as usize, wy as usize))
}
