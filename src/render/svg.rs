//! `world.svg`: the floor plan as a vector drawing, to scale to any size, print, or open in a
//! drawing program.
//!
//! The drawing is in map cells (`viewBox="0 0 W H"`, one unit per cell, y down), so that it
//! lies exactly over the map and over `overlay.png`, with `data-resolution` giving metres per
//! cell. It has four layers (`<g>` groups, which Inkscape also shows as layers), five where the
//! map has frontiers, bottom to top:
//!
//! * `rooms`: one `<path>` per room with `data-room` (its id, as in `labels.pgm`) and
//!   `data-type` (`room`, `corridor`, `hall`, `other` or `unknown`), filled with the room tint
//!   of the PNG pictures ([`room_fill_rgb`]); its outline is the room's shape of
//!   [`crate::floorplan::shapes`] (walls' centre lines, holes and separate parts included);
//! * `walls`: every unit's wall ring, in the PNG's wall blue;
//! * `doors`: one `<path>` per door with `data-door`, the door's cells, in the PNG's door cyan;
//! * `placeholders` (only where the world has them): one `<g>` per placeholder with
//!   `data-placeholder` (its id), `data-opens-from` (the room it opens from, 0 for none) and
//!   `data-p-new-room`, a `<title>` with its figures, a `<path>` per type beyond with
//!   `data-beyond` (a pie, as `overlay.png` draws it) and a rim;
//! * `labels`: one `<text>` per room with `data-label` (the room's id; its name if it has one,
//!   else "room 3", shortened to "3" where it does not fit) at the room's anchor, turned with the world frame so that it
//!   runs along the room.
//!
//! Only the room shapes carry `data-room` and `data-type`, so that `[data-room]` selects one
//! element per room.

use super::labels::label_texts;
use super::palette::{room_fill_rgb, DOOR_RGBA, LABEL_OUTLINE_RGBA, LABEL_TEXT_RGBA, WALL_RGBA};
use crate::floorplan::shapes::{floor_shapes, frame_to_map, FloorShapes, MapPoint, RoomShape, ShapeError};
use crate::floorplan::{Frame, World};
use crate::grid::Grid;
use std::fmt::Write as _;

/// `world.svg` of `world` (with its room layer), with `labels` its room labels (`labels.pgm`)
/// and `resolution` the map's metres per cell.
///
/// ```
/// use ksmcmc::floorplan::{Room, Unit, UnitType, World};
/// use ksmcmc::grid::Grid;
/// use ksmcmc::render::svg::world_svg;
///
/// let mut world = World::empty(30, 20);
/// world.units.push(Unit::new(1, 0, 0, 30, 20, UnitType::Hall));
/// world.rooms.push(Room { id: 1, kind: UnitType::Hall, units: vec![1], area_m2: 1.3, doors: vec![], opens_to: vec![], name: None });
/// let svg = world_svg(&world, &Grid::new(30, 20, 1), 0.05)?;
/// assert!(svg.contains(r#"viewBox="0 0 30 20""#));
/// assert!(svg.contains(r##"<path data-room="1" data-type="hall" fill="#a6dece" d="M0.5 0.5L0.5 19.5L29.5 19.5L29.5 0.5Z"/>"##));
/// # Ok::<(), ksmcmc::floorplan::shapes::ShapeError>(())
/// ```
pub fn world_svg(world: &World, labels: &Grid<u16>, resolution: f64) -> Result<String, ShapeError> {
    Ok(svg(&floor_shapes(world, labels)?, world, resolution))
}

/// `world.svg` of shapes made by [`floor_shapes`] from `world`.
pub fn svg(shapes: &FloorShapes, world: &World, resolution: f64) -> String {
    let [w, h] = shapes.map_size;
    let mut s = String::new();
    let _ = writeln!(s, r#"<?xml version="1.0" encoding="UTF-8"?>"#);
    let _ = writeln!(
        s,
        r#"<svg xmlns="http://www.w3.org/2000/svg" xmlns:inkscape="http://www.inkscape.org/namespaces/inkscape" width="{w}" height="{h}" viewBox="0 0 {w} {h}" data-resolution="{}">"#,
        num(resolution)
    );
    let _ = writeln!(s, "<title>Floor plan</title>");
    let _ = writeln!(
        s,
        "<desc>Made by ksmcmc: rooms {}, doors {}; one unit is one map cell of {} m.</desc>",
        shapes.rooms.len(),
        shapes.doors.len(),
        num(resolution)
    );
    rooms(&mut s, shapes);
    walls(&mut s, world);
    doors(&mut s, world);
    placeholders(&mut s, world);
    room_labels(&mut s, shapes);
    s.push_str("</svg>\n");
    s
}

/// Opens a layer.
fn layer(s: &mut String, id: &str, label: &str, attributes: &str) {
    let _ = writeln!(s, r#"<g id="{id}" inkscape:groupmode="layer" inkscape:label="{label}"{attributes}>"#);
}

fn rooms(s: &mut String, shapes: &FloorShapes) {
    layer(s, "rooms", "Rooms", r#" fill-rule="evenodd" stroke="none""#);
    for r in &shapes.rooms {
        let mut d = String::new();
        for p in &r.polygons {
            for ring in std::iter::once(&p.exterior).chain(&p.holes) {
                path_ring(&mut d, ring);
            }
        }
        let [red, green, blue] = room_fill_rgb(r.kind);
        let _ = writeln!(
            s,
            r##"<path data-room="{}" data-type="{}" fill="#{red:02x}{green:02x}{blue:02x}" d="{d}"/>"##,
            r.id,
            r.kind.name()
        );
    }
    s.push_str("</g>\n");
}

fn walls(s: &mut String, world: &World) {
    layer(s, "walls", "Walls", &format!(r#" fill="{}" stroke="none""#, hex(WALL_RGBA)));
    let t = world.wall_thickness.max(1) as f64;
    let mut d = String::new();
    for u in world.units.iter().filter(|u| u.w >= 1 && u.h >= 1) {
        let frame = world.unit_frame(u);
        let (x0, y0, x1, y1) = (u.x as f64, u.y as f64, (u.x + u.w) as f64, (u.y + u.h) as f64);
        let (tx, ty) = (t.min(x1 - x0), t.min(y1 - y0));
        for r in [(x0, y0, x1, y0 + ty), (x0, y1 - ty, x1, y1), (x0, y0, x0 + tx, y1), (x1 - tx, y0, x1, y1)] {
            path_rect(&mut d, &frame, r);
        }
    }
    if !d.is_empty() {
        let _ = writeln!(s, r#"<path d="{d}"/>"#);
    }
    s.push_str("</g>\n");
}

fn doors(s: &mut String, world: &World) {
    layer(s, "doors", "Doors", &format!(r#" fill="{}" stroke="none""#, hex(DOOR_RGBA)));
    for door in &world.doors {
        let r = door.rect();
        let mut d = String::new();
        path_rect(&mut d, &world.door_frame(door), (r.x as f64, r.y as f64, r.right() as f64, r.bottom() as f64));
        let _ = writeln!(s, r#"<path data-door="{}" d="{d}"/>"#, door.id);
    }
    s.push_str("</g>\n");
}

/// The placeholders as pies (`render::pie`), each with its figures in `data-` attributes and a
/// title a reader sees on hovering.
fn placeholders(s: &mut String, world: &World) {
    if world.placeholders.is_empty() {
        return;
    }
    layer(s, "placeholders", "Placeholders", r#" stroke-linejoin="round""#);
    let r = super::pie::PIE_RADIUS_CELLS;
    for p in &world.placeholders {
        let (cx, cy) = (f64::from(p.x) + 0.5, f64::from(p.y) + 0.5);
        let t = p.types;
        let title = format!(
            "placeholder {}: {:.0} % a new room; beyond: room {:.0} %, corridor {:.0} %, hall {:.0} %, other {:.0} %; {} m wide",
            p.id,
            100.0 * p.p_new_room,
            100.0 * t.room,
            100.0 * t.corridor,
            100.0 * t.hall,
            100.0 * t.other,
            num(p.width_m)
        );
        let _ = writeln!(
            s,
            r#"<g data-placeholder="{}" data-opens-from="{}" data-p-new-room="{}"><title>{title}</title>"#,
            p.id,
            p.room,
            num(p.p_new_room)
        );
        for (kind, ring) in super::pie::sectors(cx, cy, r, p) {
            let mut d = String::new();
            path_ring(&mut d, &ring);
            let [red, green, blue] = room_fill_rgb(kind);
            let _ = writeln!(
                s,
                r##"<path data-beyond="{}" fill="#{red:02x}{green:02x}{blue:02x}" d="{d}"/>"##,
                kind.name()
            );
        }
        let rim = match p.p_new_room >= super::pie::NEW_ROOM_RIM {
            true => format!(r#"stroke="{}" stroke-width="{}""#, hex(LABEL_OUTLINE_RGBA), num(0.25 * r)),
            false => r##"stroke="#787878" stroke-width="0.5""##.to_string(),
        };
        let _ = writeln!(s, r#"<circle cx="{}" cy="{}" r="{}" fill="none" {rim}/></g>"#, num(cx), num(cy), num(r));
    }
    s.push_str("</g>\n");
}

fn room_labels(s: &mut String, shapes: &FloorShapes) {
    let attributes = format!(
        r#" fill="{}" font-family="sans-serif" text-anchor="middle" dominant-baseline="central""#,
        hex(LABEL_TEXT_RGBA)
    );
    layer(s, "labels", "Labels", &attributes);
    for r in shapes.rooms.iter().filter(|r| !r.polygons.is_empty()) {
        // Along the frame the room was drawn in, never upside down.
        let mut deg = r.angle.to_degrees() % 180.0;
        if deg > 90.0 {
            deg -= 180.0;
        } else if deg <= -90.0 {
            deg += 180.0;
        }
        let (text, size) = label_fit(r);
        let (x, y) = (num(r.anchor.0), num(r.anchor.1));
        let turn = if deg == 0.0 { String::new() } else { format!(r#" transform="rotate({} {x} {y})""#, num(deg)) };
        let text = escape(&text);
        let _ =
            writeln!(s, r#"<text data-label="{}" x="{x}" y="{y}" font-size="{}"{turn}>{text}</text>"#, r.id, num(size));
    }
    s.push_str("</g>\n");
}

/// Largest label font size, cells.
const MAX_FONT: f64 = 24.0;
/// Smallest font size a shortened label is preferred at, cells.
const MIN_FONT: f64 = 8.0;

/// The room's label text and font size (cells): the longest text that fits its room at
/// [`MIN_FONT`] or more, else its shortest.
fn label_fit(r: &RoomShape) -> (String, f64) {
    let (w, h) = r.label_room;
    let mut texts = label_texts(r.kind, r.id);
    if let Some(name) = &r.name {
        texts.insert(0, name.clone());
    }
    // A sans-serif character is about 0.6 em wide; keep a margin inside the room.
    let size = |t: &str| (0.9 * w / (0.6 * t.chars().count().max(1) as f64)).min(0.5 * h).min(MAX_FONT);
    let fits = texts.iter().find(|t| size(t) >= MIN_FONT).or(texts.last()).cloned().unwrap_or_default();
    let font = size(&fits).max(1.0);
    (fits, font)
}

/// Appends a closed ring as path data.
fn path_ring(d: &mut String, ring: &[MapPoint]) {
    for (k, &(x, y)) in ring.iter().enumerate() {
        let _ = write!(d, "{}{} {}", if k == 0 { "M" } else { "L" }, num(x), num(y));
    }
    if !ring.is_empty() {
        d.push('Z');
    }
}

/// Appends a rectangle `(x0, y0, x1, y1)` (cells) of `frame` as a closed path on the map.
fn path_rect(d: &mut String, frame: &Frame, (x0, y0, x1, y1): (f64, f64, f64, f64)) {
    let corners = [(x0, y0), (x0, y1), (x1, y1), (x1, y0)].map(|(x, y)| frame_to_map(frame, x, y));
    path_ring(d, &corners);
}

/// `text` with XML's special characters as entities (room names come from people).
fn escape(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for c in text.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&apos;"),
            c if (c as u32) < 0x20 => out.push(' '),
            c => out.push(c),
        }
    }
    out
}

/// `#rrggbb` of an RGBA colour.
fn hex([r, g, b, _]: [u8; 4]) -> String {
    format!("#{r:02x}{g:02x}{b:02x}")
}

/// A number with at most three decimals, without trailing zeros or a negative zero.
fn num(v: f64) -> String {
    let s = format!("{v:.3}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    if s == "-0" {
        "0".to_string()
    } else {
        s.to_string()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::floorplan::{Door, Room, Unit, UnitType};

    #[test]
    fn numbers_are_short() {
        assert_eq!([num(1.0), num(0.5), num(-0.0001), num(2.0 / 3.0), num(1e3)], ["1", "0.5", "0", "0.667", "1000"]);
    }

    #[test]
    fn layers_hold_rooms_walls_doors_and_labels() {
        let mut world = World::empty(40, 20);
        world.units = vec![Unit::new(1, 0, 0, 21, 20, UnitType::Room), Unit::new(2, 20, 0, 20, 20, UnitType::Corridor)];
        world.doors = vec![Door { id: 9, units: [1, 2], x0: 20, y0: 5, x1: 20, y1: 10, opening: false }];
        world.rooms = vec![
            Room {
                id: 1,
                kind: UnitType::Room,
                units: vec![1],
                area_m2: 1.0,
                doors: vec![9],
                opens_to: vec![2],
                name: None,
            },
            Room {
                id: 2,
                kind: UnitType::Corridor,
                units: vec![2],
                area_m2: 1.0,
                doors: vec![9],
                opens_to: vec![1],
                name: None,
            },
        ];
        let svg = world_svg(&world, &Grid::new(40, 20, 0), 0.05).unwrap();
        let order: Vec<usize> = ["id=\"rooms\"", "id=\"walls\"", "id=\"doors\"", "id=\"labels\""]
            .iter()
            .map(|l| svg.find(l).unwrap_or_else(|| panic!("{l} missing:\n{svg}")))
            .collect();
        assert!(order.windows(2).all(|w| w[0] < w[1]), "{order:?}");
        assert_eq!(svg.matches("<path data-room=").count(), 2);
        assert!(
            svg.contains(
                r##"data-room="2" data-type="corridor" fill="#c4e5f8" d="M20.5 0.5L20.5 19.5L39.5 19.5L39.5 0.5Z""##
            ),
            "{svg}"
        );
        assert!(svg.contains(r#"<path data-door="9" d="M20 5L20 11L21 11L21 5Z"/>"#), "{svg}");
        // Room 1's floor is 20 x 19 cells: "room 1" fits at 0.9 * 20 / (0.6 * 6) = 5 cells,
        // below MIN_FONT; "1" fits at 9.5 (half the height).
        assert!(svg.contains(r#"<text data-label="1" x="10.5" y="10" font-size="9.5">1</text>"#), "{svg}");
        assert_eq!(svg.matches("<text ").count(), 2);
        assert!(svg.ends_with("</svg>\n"));
    }

    #[test]
    fn a_named_room_is_labelled_with_its_name_escaped() {
        let mut world = World::empty(100, 40);
        world.units = vec![Unit::new(1, 0, 0, 100, 40, UnitType::Hall)];
        world.rooms = vec![Room {
            id: 1,
            kind: UnitType::Hall,
            units: vec![1],
            area_m2: 1.0,
            doors: vec![],
            opens_to: vec![],
            name: Some("Lab <&>".into()),
        }];
        let svg = world_svg(&world, &Grid::new(100, 40, 0), 0.05).unwrap();
        // 99 x 39 cells: the 7 characters fit at min(0.9 * 99 / 4.2, 39 / 2) = 19.5.
        assert!(svg.contains(r#"font-size="19.5">Lab &lt;&amp;&gt;</text>"#), "{svg}");
    }
}
