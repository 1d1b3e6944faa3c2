//! The legend drawn in a corner of a world overlay: one swatch per colour the world put on the
//! picture (the unit types present, walls, doors, object cells, unexplained space).
//!
//! A PNG saved from the page or the CLI travels without the page's explanations, so the
//! picture explains itself (issue 12: "a legend of every colour on the canvas"). Only colours
//! that occur are listed, which keeps the box small. The corner is the one that hides the least
//! of the plan: of the four, the one whose box covers the fewest pixels that are neither free
//! (white) nor unknown (gray), ties going top-left, top-right, bottom-left, bottom-right, so
//! the choice depends only on the pixels and is the same everywhere.

use super::labels::LabelBox;
use super::palette::{room_fill_rgb, DOOR_RGBA, LABEL_OUTLINE_RGBA, OBJECT_RGBA, UNEXPLAINED_RGBA, WALL_RGBA};
use super::{cell_rgb, font};
use crate::floorplan::{UnitType, World};
use crate::grid::Cell;
use tiny_skia::{Color, Paint, Pixmap, Rect, Transform};

/// The legend's background: white, nearly opaque.
pub const LEGEND_BACKGROUND_RGBA: [u8; 4] = [255, 255, 255, 235];
/// The legend's text: near black.
pub const LEGEND_TEXT_RGBA: [u8; 4] = [30, 30, 30, 255];

/// What a legend row stands for, to decide whether a world puts that colour on the picture.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Drawn {
    Kind(UnitType),
    Walls,
    Doors,
    Objects,
    Unexplained,
    NewRoomLikely,
}

/// Every row a legend can have, in its order.
fn rows() -> Vec<(&'static str, [u8; 4], Drawn)> {
    let mut out: Vec<(&'static str, [u8; 4], Drawn)> = UnitType::ALL
        .into_iter()
        .map(|kind| {
            let [r, g, b] = room_fill_rgb(kind);
            (kind.name(), [r, g, b, 255], Drawn::Kind(kind))
        })
        .collect();
    out.extend([
        ("wall", WALL_RGBA, Drawn::Walls),
        ("door", DOOR_RGBA, Drawn::Doors),
        ("objects", OBJECT_RGBA, Drawn::Objects),
        ("unexplained", UNEXPLAINED_RGBA, Drawn::Unexplained),
        // The pies' dark rim: a placeholder more likely than not to lead to a new room.
        ("new room likely", LABEL_OUTLINE_RGBA, Drawn::NewRoomLikely),
    ]);
    out
}

/// Every row a legend can have: a name and the colour of its swatch (straight RGBA, drawn
/// over white as on a free cell), in the order [`legend_entries`] lists them. A page that
/// draws its legend beside the map, where it stays readable at any zoom, lists these.
///
/// ```
/// let rows = ksmcmc::render::legend_palette();
/// assert_eq!(rows.first().map(|r| r.0), Some("room"));
/// assert!(rows.iter().any(|r| r.0 == "door"));
/// ```
pub fn legend_palette() -> Vec<(&'static str, [u8; 4])> {
    rows().into_iter().map(|(name, rgba, _)| (name, rgba)).collect()
}

/// The legend's rows for `world`: those of [`legend_palette`] whose colour the world puts on
/// the picture.
pub fn legend_entries(world: &World) -> Vec<(&'static str, [u8; 4])> {
    let drawn = |d: Drawn| match d {
        Drawn::Kind(kind) => world.units.iter().any(|u| u.kind == kind && u.w >= 1 && u.h >= 1),
        Drawn::Walls => !world.units.is_empty(),
        Drawn::Doors => !world.doors.is_empty(),
        Drawn::Objects => !world.object_cells.is_empty(),
        Drawn::Unexplained => !world.unexplained.is_empty(),
        Drawn::NewRoomLikely => world.placeholders.iter().any(|p| p.p_new_room >= super::pie::NEW_ROOM_RIM),
    };
    rows().into_iter().filter(|&(_, _, d)| drawn(d)).map(|(name, rgba, _)| (name, rgba)).collect()
}

/// The size of the legend box for `entries` with text at `factor`.
fn legend_size(entries: &[(&str, [u8; 4])], factor: u32) -> (i64, i64) {
    let f = factor as i64;
    let text_w = entries.iter().map(|(n, _)| font::text_size(n, factor).0 as i64).max().unwrap_or(0);
    let swatch = (font::CAP_HEIGHT * factor) as i64;
    let row = (font::GLYPH_HEIGHT * factor) as i64 + f;
    (4 * f + swatch + 2 * f + text_w, 4 * f + entries.len() as i64 * row - f)
}

/// Where the legend goes on `pixmap`: the largest text factor up to `factor` whose box fits
/// in half the picture's width and two thirds of its height, in the corner that hides the
/// least (see the module docs). `None` if there is nothing to list or no size fits.
pub fn legend_box(pixmap: &Pixmap, entries: &[(&str, [u8; 4])], factor: u32) -> Option<(LabelBox, u32)> {
    if entries.is_empty() {
        return None;
    }
    let (pw, ph) = (pixmap.width() as i64, pixmap.height() as i64);
    let factor = (1..=factor.max(1)).rev().find(|&f| {
        let (w, h) = legend_size(entries, f);
        2 * w <= pw && 3 * h <= 2 * ph
    })?;
    let (w, h) = legend_size(entries, factor);
    let m = 2 * factor as i64;
    let corners = [(m, m), (pw - w - m, m), (m, ph - h - m), (pw - w - m, ph - h - m)];
    let background = [cell_rgb(Cell::Free), cell_rgb(Cell::Unknown)];
    let busy = |(x, y): (i64, i64)| {
        let mut n = 0usize;
        for py in y.max(0)..(y + h).min(ph) {
            for px in x.max(0)..(x + w).min(pw) {
                let c = pixmap.pixel(px as u32, py as u32).map(|p| p.demultiply());
                if c.is_some_and(|c| !background.contains(&[c.red(), c.green(), c.blue()])) {
                    n += 1;
                }
            }
        }
        n
    };
    // `min_by_key` keeps the first of equal keys: ties go to the earlier corner.
    let (left, top) = corners.into_iter().min_by_key(|&c| busy(c))?;
    Some((LabelBox { text: String::new(), left, top, width: w, height: h }, factor))
}

/// Draws the legend for `entries` in `at` (from [`legend_box`]) with text at `factor`.
pub fn draw_legend(pixmap: &mut Pixmap, at: &LabelBox, entries: &[(&str, [u8; 4])], factor: u32) {
    let f = factor as i64;
    fill(pixmap, at.left, at.top, at.width, at.height, LEGEND_BACKGROUND_RGBA);
    outline(pixmap, at.left, at.top, at.width, at.height);
    let swatch = (font::CAP_HEIGHT * factor) as i64;
    let row = (font::GLYPH_HEIGHT * factor) as i64 + f;
    for (i, (name, rgba)) in entries.iter().enumerate() {
        let (x, y) = (at.left + 2 * f, at.top + 2 * f + i as i64 * row);
        fill(pixmap, x, y, swatch, swatch, [255, 255, 255, 255]);
        fill(pixmap, x, y, swatch, swatch, *rgba);
        outline(pixmap, x, y, swatch, swatch);
        let (tx, ty) = (x + swatch + 2 * f, y);
        if let (Ok(tx), Ok(ty)) = (i32::try_from(tx), i32::try_from(ty)) {
            font::draw_text(pixmap, tx, ty, name, factor, LEGEND_TEXT_RGBA);
        }
    }
}

/// A one-pixel dark outline just inside the box.
fn outline(pixmap: &mut Pixmap, x: i64, y: i64, w: i64, h: i64) {
    for (x, y, w, h) in [(x, y, w, 1), (x, y + h - 1, w, 1), (x, y + 1, 1, h - 2), (x + w - 1, y + 1, 1, h - 2)] {
        fill(pixmap, x, y, w, h, LABEL_OUTLINE_RGBA);
    }
}

fn fill(pixmap: &mut Pixmap, x: i64, y: i64, w: i64, h: i64, rgba: [u8; 4]) {
    if let Some(rect) = Rect::from_xywh(x as f32, y as f32, w as f32, h as f32) {
        let mut paint = Paint::default();
        paint.set_color(Color::from_rgba8(rgba[0], rgba[1], rgba[2], rgba[3]));
        paint.anti_alias = false;
        pixmap.fill_rect(rect, &paint, Transform::identity(), None);
    }
}
