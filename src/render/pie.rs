//! Placeholders drawn as small pies, as the CogX report's Fig. 1 draws them: one sector per
//! type of space that may lie beyond, its angle that type's probability, in the type's room
//! colour; a dark rim where a new room is more likely than not
//! ([`crate::floorplan::frontier`]).

use super::palette::{room_fill_rgb, LABEL_OUTLINE_RGBA};
use crate::floorplan::world::Placeholder;
use crate::floorplan::{UnitType, World};
use tiny_skia::{Color, FillRule, Paint, PathBuilder, Pixmap, Stroke, Transform};

/// The types of the sectors, in the order of [`crate::floorplan::world::TypeProbabilities::as_array`].
pub const SECTOR_TYPES: [UnitType; 4] = [UnitType::Room, UnitType::Corridor, UnitType::Hall, UnitType::Other];

/// Radius of a pie, map cells: 8 (0.4 m at 5 cm a cell, a robot's footprint).
pub const PIE_RADIUS_CELLS: f64 = 8.0;

/// Smallest pie radius in pixels, so that a coarse drawing still shows it.
const MIN_RADIUS_PX: f64 = 6.0;

/// A placeholder is drawn with a rim where `P(NewRoom)` is at least this.
pub const NEW_ROOM_RIM: f64 = 0.5;

/// The sectors of a pie centred on `(cx, cy)` with radius `r`: per type with a probability
/// of at least 0.5 %, its type and its outline (the centre, then points along the arc no more
/// than 10 degrees apart), clockwise from twelve o'clock.
pub fn sectors(cx: f64, cy: f64, r: f64, p: &Placeholder) -> Vec<(UnitType, Vec<(f64, f64)>)> {
    let mut out = Vec::new();
    let mut start = -std::f64::consts::FRAC_PI_2;
    for (kind, f) in SECTOR_TYPES.into_iter().zip(p.types.as_array()) {
        let sweep = std::f64::consts::TAU * f.clamp(0.0, 1.0);
        if f >= 0.005 {
            let steps = (sweep / 10f64.to_radians()).ceil().max(1.0) as usize;
            let mut ring = vec![(cx, cy)];
            for k in 0..=steps {
                let a = start + sweep * k as f64 / steps as f64;
                ring.push((cx + r * libm::cos(a), cy + r * libm::sin(a)));
            }
            out.push((kind, ring));
        }
        start += sweep;
    }
    out
}

/// Draws `world`'s placeholders over a map drawn at `scale` pixels per cell.
pub fn draw_placeholders(pixmap: &mut Pixmap, world: &World, scale: u32) {
    let s = f64::from(scale.max(1));
    let r = (PIE_RADIUS_CELLS * s).max(MIN_RADIUS_PX);
    for p in &world.placeholders {
        let (cx, cy) = ((f64::from(p.x) + 0.5) * s, (f64::from(p.y) + 0.5) * s);
        for (kind, ring) in sectors(cx, cy, r, p) {
            let [red, green, blue] = room_fill_rgb(kind);
            if let Some(path) = polygon(&ring) {
                pixmap.fill_path(
                    &path,
                    &paint([red, green, blue, 255]),
                    FillRule::Winding,
                    Transform::identity(),
                    None,
                );
            }
        }
        let mut pb = PathBuilder::new();
        pb.push_circle(cx as f32, cy as f32, r as f32);
        if let Some(circle) = pb.finish() {
            let (width, rgba) = match p.p_new_room >= NEW_ROOM_RIM {
                true => ((0.25 * r).max(2.0), LABEL_OUTLINE_RGBA),
                false => (1.0, [120, 120, 120, 255]),
            };
            let stroke = Stroke { width: width as f32, ..Stroke::default() };
            pixmap.stroke_path(&circle, &paint(rgba), &stroke, Transform::identity(), None);
        }
    }
}

/// A closed polygon through `points`.
fn polygon(points: &[(f64, f64)]) -> Option<tiny_skia::Path> {
    let mut pb = PathBuilder::new();
    let (x0, y0) = *points.first()?;
    pb.move_to(x0 as f32, y0 as f32);
    for &(x, y) in &points[1..] {
        pb.line_to(x as f32, y as f32);
    }
    pb.close();
    pb.finish()
}

fn paint(rgba: [u8; 4]) -> Paint<'static> {
    let mut p = Paint::default();
    p.set_color(Color::from_rgba8(rgba[0], rgba[1], rgba[2], rgba[3]));
    p.anti_alias = true;
    p
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::floorplan::world::TypeProbabilities;

    fn placeholder(types: [f64; 4], p_new_room: f64) -> Placeholder {
        let [room, corridor, hall, other] = types;
        let types = TypeProbabilities { room, corridor, hall, other };
        Placeholder { id: 1, x: 20, y: 20, width_m: 1.0, room: 0, p_new_room, types }
    }

    #[test]
    fn sectors_sweep_their_share_of_the_circle() {
        let s = sectors(0.0, 0.0, 10.0, &placeholder([0.5, 0.25, 0.0, 0.25], 0.5));
        let kinds: Vec<UnitType> = s.iter().map(|t| t.0).collect();
        assert_eq!(kinds, [UnitType::Room, UnitType::Corridor, UnitType::Other]);
        // The room half runs from twelve o'clock clockwise (y down) to six o'clock.
        let room = &s[0].1;
        let (first, last) = (room[1], room[room.len() - 1]);
        assert!(first.0.abs() < 1e-9 && (first.1 + 10.0).abs() < 1e-9, "{first:?}");
        assert!(last.0.abs() < 1e-9 && (last.1 - 10.0).abs() < 1e-9, "{last:?}");
    }

    #[test]
    fn the_legend_names_the_rim_only_when_a_pie_has_it() {
        let mut world = World::empty(40, 40);
        world.placeholders = vec![placeholder([1.0, 0.0, 0.0, 0.0], 0.3)];
        let has = |w: &World| super::super::legend_entries(w).iter().any(|e| e.0 == "new room likely");
        assert!(!has(&world));
        world.placeholders[0].p_new_room = 0.5;
        assert!(has(&world));
    }

    #[test]
    fn a_likely_new_room_gets_a_dark_rim() {
        let mut world = World::empty(40, 40);
        world.placeholders = vec![placeholder([1.0, 0.0, 0.0, 0.0], 0.9)];
        let mut pixmap = Pixmap::new(80, 80).unwrap();
        draw_placeholders(&mut pixmap, &world, 2);
        // Centre (41, 41) px, radius 16: the centre is room-coloured, the rim dark.
        let at = |x: u32, y: u32| pixmap.pixel(x, y).unwrap().demultiply();
        let [r, g, b] = room_fill_rgb(UnitType::Room);
        let c = at(41, 41);
        assert_eq!([c.red(), c.green(), c.blue()], [r, g, b]);
        let rim = at(41 + 16, 41);
        assert!(rim.red() < 100 && rim.green() < 100, "{rim:?}");
        world.placeholders[0].p_new_room = 0.1;
        let mut pale = Pixmap::new(80, 80).unwrap();
        draw_placeholders(&mut pale, &world, 2);
        assert!(pale.pixel(41 + 19, 41).unwrap().alpha() == 0, "a thin rim only");
    }
}
