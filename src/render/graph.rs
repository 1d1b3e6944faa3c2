//! Drawing the scene graph of a world (Fig. 3.8 c/d): units as nodes, doors and shared walls as
//! edges.
//!
//! The layout is the floor plan's own: each node sits at its unit's centre on the map (through
//! the world's [`crate::floorplan::Frame`]), scaled to fit the picture, so the graph drawn
//! beside the map reads like a skeleton of it. Nodes are discs in their unit type's colour
//! ([`unit_type_rgb`]) with the unit's id; a door is a solid dark edge, a shared wall without a
//! door a thin dashed gray one. The edges are those of
//! [`crate::floorplan::graph::scene_graph`], so the picture and `graph.json` always agree.

use super::{font, unit_type_rgb, RenderError, MAX_PIXELS};
use crate::floorplan::graph::{scene_graph, Link};
use crate::floorplan::World;
use tiny_skia::{Color, FillRule, Paint, PathBuilder, Pixmap, Stroke, StrokeDash, Transform};

/// The picture's background: white.
pub const GRAPH_BACKGROUND_RGBA: [u8; 4] = [255, 255, 255, 255];
/// Door edges: solid, near black.
pub const GRAPH_DOOR_RGBA: [u8; 4] = [40, 40, 40, 255];
/// Adjacency edges (a shared wall without a door): dashed, mid gray.
pub const GRAPH_ADJACENT_RGBA: [u8; 4] = [120, 120, 120, 255];
/// The outline of the map's extent, so that the layout has a frame of reference.
pub const GRAPH_FRAME_RGBA: [u8; 4] = [225, 225, 225, 255];

/// The radius of a node, in pixels, on a `width` x `height` picture.
pub fn graph_node_radius(width: u32, height: u32) -> f32 {
    (width.min(height) as f32 / 28.0).clamp(5.0, 14.0)
}

/// Draws the scene graph of `world` on a new `width` x `height` picture.
///
/// Refuses a picture with no pixels or more than [`MAX_PIXELS`]; draws any world, checked or
/// not, without panicking (units outside the map are drawn where they lie, clipped).
///
/// ```
/// use ksmcmc::floorplan::{Door, Unit, UnitType, World};
/// use ksmcmc::render::{render_scene_graph, unit_type_rgb};
///
/// let mut w = World::empty(60, 30);
/// w.units.push(Unit { id: 1, x: 0, y: 0, w: 30, h: 30, kind: UnitType::Room });
/// w.units.push(Unit { id: 2, x: 29, y: 0, w: 31, h: 30, kind: UnitType::Corridor });
/// w.doors.push(Door { id: 1, units: [1, 2], x0: 29, y0: 10, x1: 29, y1: 20 });
/// let picture = render_scene_graph(&w, 240, 120).unwrap();
/// // The room's node is a disc in the room colour at the room's centre.
/// let layout = ksmcmc::render::scene_graph_layout(&w, 240, 120).unwrap();
/// let (x, y) = layout.centres[0];
/// let p = picture.pixel((x - layout.radius / 2.0) as u32, y as u32).unwrap();
/// assert_eq!([p.red(), p.green(), p.blue()], unit_type_rgb(UnitType::Room));
/// ```
pub fn render_scene_graph(world: &World, width: u32, height: u32) -> Result<Pixmap, RenderError> {
    let (w, h) = (width as usize, height as usize);
    if width == 0 || height == 0 {
        return Err(RenderError::Empty { width: w, height: h });
    }
    if width as u64 * height as u64 > MAX_PIXELS {
        return Err(RenderError::TooLarge { width: w, height: h, scale: 1, max_scale: 0 });
    }
    let mut pixmap =
        Pixmap::new(width, height).ok_or(RenderError::TooLarge { width: w, height: h, scale: 1, max_scale: 0 })?;
    draw_scene_graph(&mut pixmap, world);
    Ok(pixmap)
}

/// Where the nodes of `world`'s scene graph go on a `width` x `height` picture: each unit's
/// centre on the map, scaled to fit with a margin (in `world.units` order), and the node radius.
/// `None` when nothing fits (a picture smaller than a node, or a frame with a non-finite angle).
pub fn scene_graph_layout(world: &World, width: u32, height: u32) -> Option<GraphLayout> {
    let (pw, ph) = (width as f32, height as f32);
    let radius = graph_node_radius(width, height);
    let [mw, mh] = world.frame.map_size.map(|v| v.max(1) as f32);
    let margin = radius + 3.0;
    let k = ((pw - 2.0 * margin) / mw).min((ph - 2.0 * margin) / mh);
    if !(k.is_finite() && k > 0.0 && world.frame.angle.is_finite()) {
        return None;
    }
    let (ox, oy) = ((pw - k * mw) / 2.0, (ph - k * mh) / 2.0);
    let centres = world
        .units
        .iter()
        .map(|u| {
            let (cx, cy) = u.rect().center();
            let (mx, my) = if world.frame.is_identity() { (cx, cy) } else { world.frame.to_map(cx, cy) };
            (ox + k * mx as f32, oy + k * my as f32)
        })
        .collect();
    Some(GraphLayout { centres, radius, map_box: [ox, oy, k * mw, k * mh] })
}

/// The geometry of a drawn scene graph, from [`scene_graph_layout`].
#[derive(Debug, Clone, PartialEq)]
pub struct GraphLayout {
    /// Node centres in pixels, one per unit in `world.units` order.
    pub centres: Vec<(f32, f32)>,
    /// Node radius in pixels.
    pub radius: f32,
    /// The map's extent on the picture: left, top, width, height in pixels.
    pub map_box: [f32; 4],
}

/// Draws the scene graph of `world` over the whole pixmap (background included).
pub fn draw_scene_graph(pixmap: &mut Pixmap, world: &World) {
    let [r, g, b, a] = GRAPH_BACKGROUND_RGBA;
    pixmap.fill(Color::from_rgba8(r, g, b, a));
    let Some(layout) = scene_graph_layout(world, pixmap.width(), pixmap.height()) else { return };
    let radius = layout.radius;
    let centre = &layout.centres;
    let [ox, oy, bw, bh] = layout.map_box;
    // The map's extent.
    if let Some(rect) = tiny_skia::Rect::from_xywh(ox, oy, bw, bh) {
        let path = PathBuilder::from_rect(rect);
        stroke(pixmap, &path, GRAPH_FRAME_RGBA, 1.0, None);
    }

    // The scene graph's geometry works in i32: leave the edges out for a world whose numbers
    // could overflow it (no world that `World::validate` accepts comes near).
    const LIMIT: i32 = 1 << 28;
    let sane = (0..=1000).contains(&world.wall_thickness)
        && world.units.iter().all(|u| [u.x, u.y, u.w, u.h].iter().all(|v| (-LIMIT..=LIMIT).contains(v)));
    let graph = if sane { scene_graph(world) } else { Default::default() };
    // Node index in `world.units` by node index in the graph: scene_graph adds them in order.
    for e in graph.edge_indices() {
        let Some((a, b)) = graph.edge_endpoints(e) else { continue };
        let (Some(&p), Some(&q)) = (centre.get(a.index()), centre.get(b.index())) else { continue };
        let mut pb = PathBuilder::new();
        pb.move_to(p.0, p.1);
        pb.line_to(q.0, q.1);
        let Some(path) = pb.finish() else { continue };
        match graph[e] {
            Link::Door(_) => stroke(pixmap, &path, GRAPH_DOOR_RGBA, (radius / 4.0).max(2.0), None),
            Link::Adjacent => {
                let dash = StrokeDash::new(vec![5.0, 4.0], 0.0);
                stroke(pixmap, &path, GRAPH_ADJACENT_RGBA, 1.25, dash)
            }
        }
    }
    let factor = if radius >= 12.0 { 2 } else { 1 };
    for (unit, &(x, y)) in world.units.iter().zip(centre) {
        let Some(circle) = PathBuilder::from_circle(x, y, radius) else { continue };
        let [r, g, b] = unit_type_rgb(unit.kind);
        let mut paint = Paint::default();
        paint.set_color(Color::from_rgba8(r, g, b, 255));
        pixmap.fill_path(&circle, &paint, FillRule::Winding, Transform::identity(), None);
        stroke(pixmap, &circle, [30, 30, 30, 255], 1.5, None);
        let text = unit.id.to_string();
        let (tw, th) = font::text_size(&text, factor);
        let (tx, ty) = ((x - tw as f32 / 2.0).round(), (y - (font::CAP_HEIGHT * factor) as f32 / 2.0).round());
        if tx.abs() < 1e6 && ty.abs() < 1e6 && th > 0 {
            font::draw_text(pixmap, tx as i32, ty as i32, &text, factor, [0, 0, 0, 255]);
        }
    }
}

/// Strokes a path, anti-aliased.
fn stroke(pixmap: &mut Pixmap, path: &tiny_skia::Path, rgba: [u8; 4], width: f32, dash: Option<StrokeDash>) {
    let mut paint = Paint::default();
    paint.set_color(Color::from_rgba8(rgba[0], rgba[1], rgba[2], rgba[3]));
    paint.anti_alias = true;
    let stroke = Stroke { width, dash, ..Stroke::default() };
    pixmap.stroke_path(path, &paint, &stroke, Transform::identity(), None);
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::floorplan::{Door, Unit, UnitType};

    fn world() -> World {
        let mut w = World::empty(90, 30);
        w.units.push(Unit { id: 1, x: 0, y: 0, w: 30, h: 30, kind: UnitType::Room });
        w.units.push(Unit { id: 2, x: 29, y: 0, w: 31, h: 30, kind: UnitType::Corridor });
        w.units.push(Unit { id: 3, x: 59, y: 0, w: 31, h: 30, kind: UnitType::Hall });
        w.doors.push(Door { id: 1, units: [1, 2], x0: 29, y0: 10, x1: 29, y1: 20 });
        w
    }

    fn dark(p: &Pixmap, x: u32, y: u32) -> bool {
        let c = p.pixel(x, y).unwrap();
        (c.red() as u32 + c.green() as u32 + c.blue() as u32) < 3 * 150
    }

    #[test]
    fn doors_are_solid_and_walls_dashed() {
        let p = render_scene_graph(&world(), 560, 200).unwrap();
        let layout = scene_graph_layout(&world(), 560, 200).unwrap();
        let r = layout.radius;
        let [(room, y), (corridor, _), (hall, _)] = [layout.centres[0], layout.centres[1], layout.centres[2]];
        let y = y as u32;
        let c = p.pixel((corridor - 6.0) as u32, y).unwrap();
        assert_eq!([c.red(), c.green(), c.blue()], unit_type_rgb(UnitType::Corridor));
        let c = p.pixel((hall + 6.0) as u32, y).unwrap();
        assert_eq!([c.red(), c.green(), c.blue()], unit_type_rgb(UnitType::Hall));
        // The door edge (room - corridor) is dark along its whole length.
        for x in (room + r + 2.0) as u32..(corridor - r - 2.0) as u32 {
            assert!(dark(&p, x, y), "door edge at x = {x}");
        }
        // The wall edge (corridor - hall) has gaps.
        let along: Vec<bool> = ((corridor + r + 2.0) as u32..(hall - r - 2.0) as u32)
            .map(|x| p.pixel(x, y).unwrap().green() < 200)
            .collect();
        assert!(along.iter().any(|&d| d) && along.iter().any(|&d| !d), "dashed: {along:?}");
    }

    #[test]
    fn bad_sizes_are_errors_and_odd_worlds_draw() {
        assert!(render_scene_graph(&world(), 0, 10).is_err());
        assert!(render_scene_graph(&world(), 100_000, 100_000).is_err());
        let p = render_scene_graph(&World::empty(10, 10), 50, 50).unwrap();
        assert!(p.pixels().iter().all(|c| c.red() > 200), "an empty world is a blank frame");
        let mut odd = world();
        odd.units[0].x = i32::MIN;
        odd.frame.angle = 0.5;
        odd.doors.push(Door { id: 9, units: [7, 8], x0: 0, y0: 0, x1: 0, y1: 0 });
        render_scene_graph(&odd, 20, 20).unwrap();
        render_scene_graph(&odd, 3, 3).unwrap();
        odd.frame.angle = f64::NAN;
        render_scene_graph(&odd, 30, 30).unwrap();
    }
}
