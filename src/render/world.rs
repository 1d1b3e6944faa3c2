//! Drawing a semantic [`World`] over a rendered map: walls, doors, object cells, unexplained
//! areas, labels.
//!
//! Everything in a world is a rectangle of cells in the *world frame*. Drawing works the same
//! way for every kind of thing: list the world-frame cell rectangles, clip them to the part of
//! the world that can appear on the map, map their corners to pixels and fill all of them with
//! one tiny-skia path in one colour. One fill per colour means overlapping rectangles (the
//! corners of a wall ring, a doubly listed object cell) blend once, not twice.
//!
//! In the identity frame the corners land on whole pixels (cell `x` starts at pixel
//! `x * scale`), and with anti-aliasing off the fill covers exactly the cells' pixel blocks, so
//! the result is as crisp as the map under it. In a rotated frame the rectangles become rotated
//! quadrilaterals; anti-aliasing stays off there too, so every pixel is either untouched or the
//! pure colour, as in the papers' figures.

use super::labels::{place_labels, tag_size, world_label_candidates, LabelBox};
use super::legend::{draw_legend, legend_box, legend_entries};
use super::{font, RenderOptions};
use crate::floorplan::world::FrameGroup;
use crate::floorplan::{Frame, UnitType, World};
use tiny_skia::{BlendMode, Color, FillRule, Paint, PathBuilder, Pixmap, Rect, Transform};

pub use super::palette::{
    room_fill_rgb, unit_type_rgb, DOOR_RGBA, LABEL_BACKGROUND_RGBA, LABEL_OUTLINE_RGBA, LABEL_TEXT_RGBA, OBJECT_RGBA,
    ROOM_FILL_STRENGTH, UNEXPLAINED_RGBA, WALL_RGBA,
};

/// Output pixels per font pixel for labels on a map drawn at `scale` pixels per cell.
///
/// At least 2, so that capitals are 14 pixels high even at one pixel per cell; it grows slowly
/// with the scale so labels stay in proportion without swamping small units.
pub fn label_text_scale(scale: u32) -> u32 {
    2 + scale / 8
}

/// The label of a unit: its type name and id, e.g. `"room 3"`.
pub fn unit_label(unit: &crate::floorplan::Unit) -> String {
    format!("{} {}", unit.kind.name(), unit.id)
}

/// Draws `world` over a pixmap that holds a map of `map_width` x `map_height` cells drawn at
/// `options.scale` pixels per cell (as [`super::render`] does), and returns the labels it
/// placed.
///
/// Bottom to top: each unit's interior tinted by its type ([`room_fill_rgb`], multiplied into
/// the map so occupied cells stay black), object cells, unexplained areas, walls, doors, the
/// placeholders as pies of the types beyond them (`render::pie`), then
/// with `options.labels` a tag per room when the world has a room layer (at its largest unit),
/// else per unit, placed by [`super::place_labels`] (shortened or left out where it does not
/// fit), and with `options.legend` a legend of the colours drawn ([`super::legend_entries`]).
///
/// The world is drawn as it is, without [`World::validate`]: units and doors are clipped to
/// the map, units with a size below 1x1 and doors that are neither horizontal nor vertical are
/// skipped, and a frame with a non-finite angle draws nothing. It never panics.
pub fn draw_world(
    pixmap: &mut Pixmap,
    map_width: usize,
    map_height: usize,
    world: &World,
    options: &RenderOptions,
) -> Vec<LabelBox> {
    let scale = options.scale;
    let Some(place) = Placement::new(&world.frame, map_width, map_height, scale) else {
        return Vec::new();
    };
    // Units (with their doors) drawn in each frame they lie in: the world frame, and one per
    // angle of units that follow another wall direction (issue 13).
    let groups: Vec<(FrameGroup, Placement)> = world
        .frame_groups()
        .into_iter()
        .filter_map(|g| Placement::new(&g.frame, map_width, map_height, scale).map(|p| (g, p)))
        .collect();
    let t = world.wall_thickness.max(1) as i64;
    let units = |g: &FrameGroup| -> Vec<&crate::floorplan::Unit> {
        g.units.iter().map(|&i| &world.units[i]).filter(|u| u.w >= 1 && u.h >= 1).collect()
    };
    let cells = |u: &crate::floorplan::Unit| CellRect::new(u.x as i64, u.y as i64, u.w as i64, u.h as i64);
    for kind in UnitType::ALL {
        let [r, g, b] = room_fill_rgb(kind);
        let mut paint = solid([r, g, b, 255]);
        paint.blend_mode = BlendMode::Multiply;
        for (g, p) in &groups {
            let interiors: Vec<CellRect> =
                units(g).into_iter().filter(|u| u.kind == kind).filter_map(|u| cells(u).inset(t)).collect();
            p.fill_with(pixmap, &interiors, &paint);
        }
    }

    // Object cells first, so that walls and doors stay their pure colours where they meet.
    // Merged into rectangles: a furnished building has thousands, and one quad per cell made
    // them the slowest part of a frame.
    place.fill(pixmap, &object_rects(&world.object_cells), OBJECT_RGBA);
    place.fill(pixmap, &unexplained_rects(world), UNEXPLAINED_RGBA);

    for (g, p) in &groups {
        let walls: Vec<CellRect> = units(g).into_iter().flat_map(|u| cells(u).ring(t)).collect();
        p.fill(pixmap, &walls, WALL_RGBA);
    }
    for (g, p) in &groups {
        p.fill(pixmap, &door_rects(world, g), DOOR_RGBA);
    }
    super::pie::draw_placeholders(pixmap, world, scale);
    draw_labels_and_legend(pixmap, world, options)
}

/// The unexplained areas as cell rectangles, one per run of cells (empty runs skipped).
fn unexplained_rects(world: &World) -> Vec<CellRect> {
    world
        .unexplained
        .iter()
        .flat_map(|a| a.runs.iter())
        .filter(|r| r[1] <= r[2])
        .map(|&[y, x0, x1]| CellRect { x0: x0 as i64, y0: y as i64, x1: x1 as i64 + 1, y1: y as i64 + 1 })
        .collect()
}

/// The doors of frame group `g` as cell rectangles, whichever way round their end points are.
fn door_rects(world: &World, g: &FrameGroup) -> Vec<CellRect> {
    g.doors
        .iter()
        .map(|&i| {
            let d = &world.doors[i];
            let (x0, x1) = (d.x0.min(d.x1) as i64, d.x0.max(d.x1) as i64);
            let (y0, y1) = (d.y0.min(d.y1) as i64, d.y0.max(d.y1) as i64);
            CellRect { x0, y0, x1: x1 + 1, y1: y1 + 1 }
        })
        .collect()
}

/// Draws the labels (with `options.labels`, kept clear of the legend) and the legend (with
/// `options.legend`) on top of the drawn world, and returns the labels placed.
fn draw_labels_and_legend(pixmap: &mut Pixmap, world: &World, options: &RenderOptions) -> Vec<LabelBox> {
    let scale = options.scale;
    let factor = label_text_scale(scale);
    let entries = if options.legend { legend_entries(world) } else { Vec::new() };
    // One step smaller than the labels: the legend is read once, the plan is what matters.
    let legend = legend_box(pixmap, &entries, factor.saturating_sub(1).max(1));
    let mut placed = Vec::new();
    if options.labels {
        let blocked: Vec<LabelBox> = legend.iter().map(|(b, _)| b.clone()).collect();
        let candidates = world_label_candidates(world, scale);
        placed = place_labels(&candidates, pixmap.width(), pixmap.height(), factor, &blocked);
        for b in &placed {
            draw_tag_box(pixmap, b, factor);
        }
    }
    if let Some((at, legend_factor)) = legend {
        draw_legend(pixmap, &at, &entries, legend_factor);
    }
    placed
}

/// Draws `text` centred on pixel position `(cx, cy)` on a light box with a dark outline, with
/// each font pixel `factor` output pixels wide. Tags whose box misses the pixmap are skipped.
pub fn draw_tag(pixmap: &mut Pixmap, cx: f64, cy: f64, text: &str, factor: u32) {
    if !cx.is_finite() || !cy.is_finite() || factor == 0 {
        return;
    }
    let (box_w, box_h) = tag_size(text, factor);
    // Centre the box; positions are whole pixels so the glyphs stay crisp.
    let left = (cx - box_w as f64 / 2.0).round();
    let top = (cy - box_h as f64 / 2.0).round();
    let (width, height) = (pixmap.width() as f64, pixmap.height() as f64);
    if left >= width || top >= height || left + (box_w as f64) <= 0.0 || top + (box_h as f64) <= 0.0 {
        return;
    }
    // On the pixmap, so both fit in i64 comfortably (pixmap sides are below 2^29).
    let label = LabelBox { text: text.to_string(), left: left as i64, top: top as i64, width: box_w, height: box_h };
    draw_tag_box(pixmap, &label, factor);
}

/// Draws a tag whose box [`super::place_labels`] placed: a light box with a dark outline and
/// the text inside, each font pixel `factor` output pixels wide.
pub fn draw_tag_box(pixmap: &mut Pixmap, label: &LabelBox, factor: u32) {
    let LabelBox { left, top, width: box_w, height: box_h, .. } = *label;
    let pad = factor as i64;
    fill_box(pixmap, left, top, box_w, box_h, LABEL_BACKGROUND_RGBA);
    for (x, y, w, h) in [
        (left, top, box_w, 1),
        (left, top + box_h - 1, box_w, 1),
        (left, top + 1, 1, box_h - 2),
        (left + box_w - 1, top + 1, 1, box_h - 2),
    ] {
        fill_box(pixmap, x, y, w, h, LABEL_OUTLINE_RGBA);
    }
    let (tx, ty) = (left + pad, top + pad);
    if let (Ok(tx), Ok(ty)) = (i32::try_from(tx), i32::try_from(ty)) {
        font::draw_text(pixmap, tx, ty, &label.text, factor, LABEL_TEXT_RGBA);
    }
}

/// Fills a pixel rectangle with a straight-alpha colour, without anti-aliasing.
fn fill_box(pixmap: &mut Pixmap, x: i64, y: i64, w: i64, h: i64, rgba: [u8; 4]) {
    if let Some(rect) = Rect::from_xywh(x as f32, y as f32, w as f32, h as f32) {
        pixmap.fill_rect(rect, &solid(rgba), Transform::identity(), None);
    }
}

/// A solid, aliased paint.
fn solid(rgba: [u8; 4]) -> Paint<'static> {
    let mut paint = Paint::default();
    paint.set_color(Color::from_rgba8(rgba[0], rgba[1], rgba[2], rgba[3]));
    paint.anti_alias = false;
    paint
}

/// Object cells as few rectangles covering exactly the same cells: runs down each column,
/// then runs of equal column runs side by side.
fn object_rects(cells: &[[i32; 2]]) -> Vec<CellRect> {
    let mut v: Vec<(i64, i64)> = cells.iter().map(|&[x, y]| (x as i64, y as i64)).collect();
    crate::sort::sort(&mut v);
    v.dedup();
    let mut columns = Vec::new();
    let mut i = 0;
    while i < v.len() {
        let (x, y0) = v[i];
        let mut y1 = y0 + 1;
        while i + 1 < v.len() && v[i + 1] == (x, y1) {
            i += 1;
            y1 += 1;
        }
        columns.push(CellRect { x0: x, y0, x1: x + 1, y1 });
        i += 1;
    }
    // Keys are distinct (one run per column and rows), so the stable sort is the order.
    crate::sort::sort_by_key(&mut columns, |r| (r.y0, r.y1, r.x0));
    let mut out: Vec<CellRect> = Vec::with_capacity(columns.len());
    for r in columns {
        match out.last_mut() {
            Some(last) if last.y0 == r.y0 && last.y1 == r.y1 && last.x1 == r.x0 => last.x1 = r.x1,
            _ => out.push(r),
        }
    }
    out
}

/// A rectangle of world cells: columns `x0..x1`, rows `y0..y1` (end exclusive). `i64` so that
/// sums of `i32` coordinates from an unchecked world cannot overflow.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
struct CellRect {
    x0: i64,
    y0: i64,
    x1: i64,
    y1: i64,
}

impl CellRect {
    fn new(x: i64, y: i64, w: i64, h: i64) -> Self {
        CellRect { x0: x, y0: y, x1: x + w, y1: y + h }
    }

    /// The outer ring of cells `t` deep (eq. 3.8's walls) as four strips: top, bottom, left,
    /// right. The strips may overlap on small rectangles; they are filled as one path.
    fn ring(self, t: i64) -> [CellRect; 4] {
        let CellRect { x0, y0, x1, y1 } = self;
        let ty = t.min(y1 - y0);
        let tx = t.min(x1 - x0);
        [
            CellRect { x0, y0, x1, y1: y0 + ty },
            CellRect { x0, y0: y1 - ty, x1, y1 },
            CellRect { x0, y0, x1: x0 + tx, y1 },
            CellRect { x0: x1 - tx, y0, x1, y1 },
        ]
    }

    /// The rectangle `t` cells in from each side, if anything is left.
    fn inset(self, t: i64) -> Option<CellRect> {
        let r = CellRect { x0: self.x0 + t, y0: self.y0 + t, x1: self.x1 - t, y1: self.y1 - t };
        (r.x0 < r.x1 && r.y0 < r.y1).then_some(r)
    }

    /// The overlap with `other`, if not empty.
    fn clip(self, other: &CellRect) -> Option<CellRect> {
        let r = CellRect {
            x0: self.x0.max(other.x0),
            y0: self.y0.max(other.y0),
            x1: self.x1.min(other.x1),
            y1: self.y1.min(other.y1),
        };
        (r.x0 < r.x1 && r.y0 < r.y1).then_some(r)
    }
}

/// Where world cells land on the pixmap.
struct Placement {
    frame: Frame,
    /// World cells are map cells: corners go straight to whole pixels.
    identity: bool,
    scale: f64,
    /// The world cells that can appear on the map (a bounding box, generous by a cell).
    visible: CellRect,
}

impl Placement {
    fn new(frame: &Frame, map_width: usize, map_height: usize, scale: u32) -> Option<Placement> {
        if !frame.angle.is_finite() || scale == 0 {
            return None;
        }
        let (w, h) = (map_width as f64, map_height as f64);
        let identity = frame.is_identity();
        let visible = if identity {
            CellRect::new(0, 0, map_width as i64, map_height as i64)
        } else {
            let corners = [(0.0, 0.0), (w, 0.0), (0.0, h), (w, h)].map(|(x, y)| frame.to_world(x, y));
            let min_x = corners.iter().map(|c| c.0).fold(f64::INFINITY, f64::min);
            let max_x = corners.iter().map(|c| c.0).fold(f64::NEG_INFINITY, f64::max);
            let min_y = corners.iter().map(|c| c.1).fold(f64::INFINITY, f64::min);
            let max_y = corners.iter().map(|c| c.1).fold(f64::NEG_INFINITY, f64::max);
            if ![min_x, max_x, min_y, max_y].iter().all(|v| v.is_finite()) {
                return None;
            }
            // `as` saturates, so even an absurd frame gives a box, not an overflow.
            CellRect {
                x0: min_x.floor() as i64 - 1,
                y0: min_y.floor() as i64 - 1,
                x1: max_x.ceil() as i64 + 1,
                y1: max_y.ceil() as i64 + 1,
            }
        };
        Some(Placement { frame: *frame, identity, scale: scale as f64, visible })
    }

    /// A world-frame point (cell units) in output pixels.
    fn to_pixel(&self, x: f64, y: f64) -> (f64, f64) {
        let (mx, my) = if self.identity { (x, y) } else { self.frame.to_map(x, y) };
        (mx * self.scale, my * self.scale)
    }

    /// Fills the union of `rects` with one colour in one pass.
    fn fill(&self, pixmap: &mut Pixmap, rects: &[CellRect], rgba: [u8; 4]) {
        self.fill_with(pixmap, rects, &solid(rgba));
    }

    /// Fills the union of `rects` with `paint` in one pass. (A slice, not an iterator: one
    /// copy of this code in the mapper's wasm module, whose size is budgeted.)
    fn fill_with(&self, pixmap: &mut Pixmap, rects: &[CellRect], paint: &Paint) {
        let mut pb = PathBuilder::new();
        for r in rects.iter().filter_map(|r| r.clip(&self.visible)) {
            let corners = [(r.x0, r.y0), (r.x1, r.y0), (r.x1, r.y1), (r.x0, r.y1)];
            let [a, b, c, d] = corners.map(|(x, y)| self.to_pixel(x as f64, y as f64));
            pb.move_to(a.0 as f32, a.1 as f32);
            pb.line_to(b.0 as f32, b.1 as f32);
            pb.line_to(c.0 as f32, c.1 as f32);
            pb.line_to(d.0 as f32, d.1 as f32);
            pb.close();
        }
        // `finish` is `None` for an empty path (nothing to draw).
        if let Some(path) = pb.finish() {
            pixmap.fill_path(&path, paint, FillRule::Winding, Transform::identity(), None);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn object_rects_cover_exactly_the_cells() {
        let cells = [[3, 3], [4, 3], [3, 4], [4, 4], [5, 3], [9, 9], [3, 3], [i32::MAX, i32::MIN], [7, 1], [7, 2]];
        let rects = object_rects(&cells);
        let covered: std::collections::BTreeSet<(i64, i64)> =
            rects.iter().flat_map(|r| (r.x0..r.x1).flat_map(move |x| (r.y0..r.y1).map(move |y| (x, y)))).collect();
        let want: std::collections::BTreeSet<(i64, i64)> = cells.iter().map(|&[x, y]| (x as i64, y as i64)).collect();
        assert_eq!(covered, want);
        assert_eq!(rects.iter().map(|r| (r.x1 - r.x0) * (r.y1 - r.y0)).sum::<i64>(), want.len() as i64, "no overlaps");
        assert!(rects.len() <= 5, "{rects:?}");
        assert!(object_rects(&[]).is_empty());
    }
}
