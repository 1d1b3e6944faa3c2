//! Drawing the scene graph of a world (Fig. 3.8 c/d): units as nodes, doors and shared walls as
//! edges.
//!
//! The layout is the floor plan's own: each node sits at its unit's centre on the map (through
//! the world's [`crate::floorplan::Frame`]), scaled to fit the picture, so the graph drawn
//! beside the map reads like a skeleton of it. Nodes are discs in their unit type's colour
//! ([`unit_type_rgb`]) with the unit's id; a door is a solid dark edge, a shared wall without a
//! door a thin dashed gray one. Units whose centres come close (a small unit inside a large
//! one, two narrow offices side by side) would hide each other's discs, so overlapping nodes
//! are nudged apart, as little as needed ([`separate_nodes`]). The edges are those of
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
/// w.units.push(Unit::new(1, 0, 0, 30, 30, UnitType::Room));
/// w.units.push(Unit::new(2, 29, 0, 31, 30, UnitType::Corridor));
/// w.doors.push(Door { id: 1, units: [1, 2], x0: 29, y0: 10, x1: 29, y1: 20, opening: false });
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
    let mut centres: Vec<(f32, f32)> = world
        .units
        .iter()
        .map(|u| {
            let (cx, cy) = u.rect().center();
            let (mx, my) = if world.frame.is_identity() { (cx, cy) } else { world.frame.to_map(cx, cy) };
            (ox + k * mx as f32, oy + k * my as f32)
        })
        .collect();
    separate_nodes(&mut centres, 2.0 * radius + 2.0, (radius, radius, pw - radius, ph - radius));
    Some(GraphLayout { centres, radius, map_box: [ox, oy, k * mw, k * mh] })
}

/// Nudges points apart until no two are closer than `gap` (or a fixed number of rounds has
/// passed), keeping them inside `bounds` (left, top, right, bottom). Each round pushes every
/// too-close pair apart by half the shortfall each, along the line joining them (coincident
/// points along a direction fixed by their indices), so the result is deterministic and
/// points that were already apart do not move.
pub fn separate_nodes(points: &mut [(f32, f32)], gap: f32, bounds: (f32, f32, f32, f32)) {
    if !(gap.is_finite() && gap > 0.0) || points.iter().any(|p| !(p.0.is_finite() && p.1.is_finite())) {
        return;
    }
    let (x0, y0, x1, y1) = bounds;
    for _ in 0..100 {
        let mut moved = false;
        for i in 0..points.len() {
            for j in i + 1..points.len() {
                let (dx, dy) = (points[j].0 - points[i].0, points[j].1 - points[i].1);
                let d = (dx * dx + dy * dy).sqrt();
                if d >= gap - 0.01 {
                    continue;
                }
                let (ux, uy) = if d > 1e-3 {
                    (dx / d, dy / d)
                } else {
                    let a = j as f32 * 2.399_963; // the golden angle: coincident points fan out
                    (a.cos(), a.sin())
                };
                let push = (gap - d) / 2.0 + 0.01;
                points[i] = (points[i].0 - ux * push, points[i].1 - uy * push);
                points[j] = (points[j].0 + ux * push, points[j].1 + uy * push);
                moved = true;
            }
        }
        for p in points.iter_mut() {
            *p = (p.0.clamp(x0, x1.max(x0)), p.1.clamp(y0, y1.max(y0)));
        }
        if !moved {
            return;
        }
    }
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
        w.units.push(Unit::new(1, 0, 0, 30, 30, UnitType::Room));
        w.units.push(Unit::new(2, 29, 0, 31, 30, UnitType::Corridor));
        w.units.push(Unit::new(3, 59, 0, 31, 30, UnitType::Hall));
        w.doors.push(Door { id: 1, units: [1, 2], x0: 29, y0: 10, x1: 29, y1: 20, opening: false });
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
    fn nodes_sit_at_their_units_and_overlapping_ones_are_nudged_apart() {
        let mut w = world();
        // A small unit inside the room, with almost the same centre, and a twin of the hall.
        w.units.push(Unit::new(4, 13, 13, 5, 5, UnitType::Other));
        w.units.push(Unit::new(5, 59, 0, 31, 30, UnitType::Room));
        let layout = scene_graph_layout(&w, 560, 200).unwrap();
        let c = &layout.centres;
        let r = layout.radius;
        for (i, a) in c.iter().enumerate() {
            for b in &c[i + 1..] {
                let d = ((a.0 - b.0).powi(2) + (a.1 - b.1).powi(2)).sqrt();
                assert!(d >= 2.0 * r + 1.9, "{a:?} and {b:?} overlap (radius {r})");
            }
            assert!(a.0 >= r && a.0 <= 560.0 - r && a.1 >= r && a.1 <= 200.0 - r, "{a:?} inside");
        }
        // The corridor, which overlapped nothing, stays at its unit's centre on the map.
        let [ox, oy, bw, _] = layout.map_box;
        let k = bw / 90.0;
        assert!((c[1].0 - (ox + k * 44.5)).abs() < 0.01 && (c[1].1 - (oy + k * 15.0)).abs() < 0.01, "{:?}", c[1]);
        // The nudged pair stays near where its units are.
        assert!((c[0].0 - c[3].0).abs() < 4.0 * r && c[0].0 < c[1].0);
        assert_eq!(layout, scene_graph_layout(&w, 560, 200).unwrap(), "deterministic");
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
        odd.doors.push(Door { id: 9, units: [7, 8], x0: 0, y0: 0, x1: 0, y1: 0, opening: false });
        render_scene_graph(&odd, 20, 20).unwrap();
        render_scene_graph(&odd, 3, 3).unwrap();
        odd.frame.angle = f64::NAN;
        render_scene_graph(&odd, 30, 30).unwrap();
    }
}
