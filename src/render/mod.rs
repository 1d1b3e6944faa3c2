//! Rendering with tiny-skia: classified maps, semantic worlds and per-cell labels.
//!
//! Everything draws into a [`tiny_skia::Pixmap`]; natively that becomes a PNG, in the browser
//! the same RGBA bytes go to a `<canvas>` through `ImageData`, so both show identical pixels.
//! Nothing here touches files or threads, so the module compiles unchanged for `wasm32`.
//!
//! # What a picture shows
//!
//! The drawing follows the dissertation's figures (Fig. 3.21 d, Fig. 3.32 d), so that results
//! can be compared with the published ones at a glance:
//!
//! * the classified map `C_M` (eq. 3.7): occupied black, unknown gray, free white
//!   ([`cell_rgb`]), each cell a `scale` x `scale` block of pixels;
//! * each unit's walls, the outer ring of its rectangle, in blue ([`WALL_RGBA`]);
//! * doors in cyan ([`DOOR_RGBA`]) and object cells (unknown cells inside units, furniture) in
//!   semi-transparent green ([`OBJECT_RGBA`]); unexplained free areas, the papers' "N", in
//!   semi-transparent orange ([`UNEXPLAINED_RGBA`]);
//! * each unit's interior lightly tinted by its type ([`room_fill_rgb`], from the one palette
//!   [`unit_type_rgb`] that the scene graph uses too), multiplied into the map so that occupied
//!   cells stay black and the tint never hides the data;
//! * optionally each room's (or, without a room layer, each unit's) type and id ("room 3"), in
//!   a small built-in bitmap font ([`font`]) on a light box, because tiny-skia draws no text;
//!   [`place_labels`] puts each inside its room, shortens it ("corridor 12", "corr 12", "12")
//!   or leaves it out rather than let labels cover each other;
//! * optionally a legend of the colours drawn, in the corner that hides least
//!   ([`legend_entries`], [`legend_box`]), so that a saved picture explains itself;
//! * for a running chain, the posterior cloud: the last accepted worlds as thin
//!   semi-transparent magenta outlines ([`draw_cloud`]), as the papers overlay 1000 samples.
//!
//! [`model3d`] makes the 3D world (walls with door openings, floor slabs by room type) as
//! glTF 2.0 binary, through a small writer of its own ([`glb`]).
//!
//! [`render_scene_graph`] draws a world's scene graph (units as nodes in their type's colour,
//! doors as solid edges, shared walls as dashed ones) for display beside the map.
//!
//! Anti-aliasing is off everywhere. A map is a grid of cells, so a pixel that is half wall and
//! half floor would claim a colour no cell has; with aliased drawing every pixel is exactly a
//! map colour or a world colour, which keeps the pictures honest and the tests exact.
//!
//! # Sizes
//!
//! The output is `scale` times the map in both directions, which grows quickly: a 2000 x 2000
//! map at scale 16 would be a billion pixels. [`try_render`] refuses outputs above
//! [`MAX_PIXELS`] with a [`RenderError`] that says what to do; [`render`] and [`draw_map`]
//! never fail and never panic, lowering the scale instead. Every map that the loaders accept
//! with the default [`crate::grid::Limits`] (at most [`crate::grid::DEFAULT_MAX_CELLS`] cells)
//! fits at scale 1.
//!
//! ```
//! use ksmcmc::floorplan::{Unit, UnitType, World};
//! use ksmcmc::grid::{Cell, Grid};
//! use ksmcmc::render::{render, RenderOptions, WALL_RGBA};
//!
//! let map = Grid::new(20, 10, Cell::Free);
//! let mut world = World::empty(20, 10);
//! world.units.push(Unit::new(1, 2, 1, 8, 6, UnitType::Room));
//!
//! let pixmap = render(&map, Some(&world), &RenderOptions { scale: 2, labels: false, legend: false });
//! assert_eq!((pixmap.width(), pixmap.height()), (40, 20));
//! // Cell (2, 1) is the unit's top-left wall cell: pixels (4..6, 2..4) are blue.
//! let p = pixmap.pixel(5, 3).unwrap();
//! assert_eq!([p.red(), p.green(), p.blue()], [WALL_RGBA[0], WALL_RGBA[1], WALL_RGBA[2]]);
//! ```

mod cloud;
mod files;
pub mod font;
pub mod glb;
mod graph;
mod labels;
mod legend;
pub mod model3d;
mod palette;
mod pie;
pub mod svg;
pub mod tabletop;
mod world;

pub use cloud::{cloud_alpha, draw_cloud, CLOUD_RGB};
pub use files::{overlay_png, ExportError, Outputs};
pub use graph::{
    draw_scene_graph, graph_node_radius, render_scene_graph, scene_graph_layout, separate_nodes, GraphLayout,
    GRAPH_ADJACENT_RGBA, GRAPH_BACKGROUND_RGBA, GRAPH_DOOR_RGBA, GRAPH_FRAME_RGBA,
};
pub use labels::{label_texts, place_labels, tag_size, world_label_candidates, LabelBox, LabelCandidate};
pub use legend::{draw_legend, legend_box, legend_entries, legend_palette, LEGEND_BACKGROUND_RGBA, LEGEND_TEXT_RGBA};
pub use world::{
    draw_tag, draw_tag_box, draw_world, label_text_scale, room_fill_rgb, unit_label, unit_type_rgb, DOOR_RGBA,
    LABEL_BACKGROUND_RGBA, LABEL_OUTLINE_RGBA, LABEL_TEXT_RGBA, OBJECT_RGBA, ROOM_FILL_STRENGTH, UNEXPLAINED_RGBA,
    WALL_RGBA,
};

use crate::floorplan::World;
use crate::grid::{Cell, Grid};
use tiny_skia::{ColorU8, Pixmap, PremultipliedColorU8};

/// The most pixels an output may have: 2^26 (about 67 million, 256 MiB of RGBA).
///
/// Large enough for every map the loaders accept by default at scale 1 (they stop at 2^25
/// cells) and for building-scale maps at several pixels per cell; small enough that a browser
/// tab or a small machine can hold the picture and its PNG encoding.
pub const MAX_PIXELS: u64 = 1 << 26;

/// The colour of a classified cell: occupied black, unknown gray, free white.
pub fn cell_rgb(c: Cell) -> [u8; 3] {
    match c {
        Cell::Occupied => [0, 0, 0],
        Cell::Unknown => [160, 160, 160],
        Cell::Free => [255, 255, 255],
    }
}

/// Why a picture could not be drawn.
#[derive(Debug, Clone, PartialEq, Eq)]
#[non_exhaustive]
pub enum RenderError {
    /// The map has no cells.
    Empty {
        /// Map width in cells.
        width: usize,
        /// Map height in cells.
        height: usize,
    },
    /// The scale is 0.
    ZeroScale,
    /// The picture would have more than [`MAX_PIXELS`] pixels.
    TooLarge {
        /// Map width in cells.
        width: usize,
        /// Map height in cells.
        height: usize,
        /// The scale asked for.
        scale: u32,
        /// The largest scale that fits, 0 if none does.
        max_scale: u32,
    },
}

impl std::fmt::Display for RenderError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            RenderError::Empty { width, height } => {
                write!(f, "cannot draw a {width}x{height} map: it has no cells")
            }
            RenderError::ZeroScale => write!(f, "scale 0: the scale must be at least 1 pixel per cell"),
            RenderError::TooLarge { width, height, scale, max_scale } => {
                let pixels = (*width as u128) * (*height as u128) * (*scale as u128) * (*scale as u128);
                write!(
                    f,
                    "a {width}x{height} map at scale {scale} would be {pixels} pixels, over the limit of \
                     {MAX_PIXELS}; "
                )?;
                if *max_scale >= 1 {
                    write!(f, "use a scale of at most {max_scale}")
                } else {
                    write!(f, "crop or downsample the map")
                }
            }
        }
    }
}

impl std::error::Error for RenderError {}

/// The largest scale at which a `width` x `height` map fits in [`MAX_PIXELS`]; 0 if even scale
/// 1 does not (or the map has no cells).
pub fn max_scale(width: usize, height: usize) -> u32 {
    let cells = (width as u128) * (height as u128);
    if cells == 0 || cells > MAX_PIXELS as u128 {
        return 0;
    }
    // MAX_PIXELS / cells >= 1, and its square root is at most 2^13.
    let mut s = ((MAX_PIXELS as u128 / cells) as f64).sqrt() as u128;
    while s > 1 && s * s * cells > MAX_PIXELS as u128 {
        s -= 1;
    }
    while (s + 1) * (s + 1) * cells <= MAX_PIXELS as u128 {
        s += 1;
    }
    s as u32
}

/// Draws a classified map one pixel per cell.
///
/// Never panics. Every map the loaders accept with the default limits is drawn in full; a grid
/// that cannot be drawn (no cells, or more than [`MAX_PIXELS`] cells) gives a 1x1 transparent
/// pixmap, as with [`render`]. Use [`try_render`] to be told instead.
pub fn draw_map(classified: &Grid<Cell>) -> Pixmap {
    render(classified, None, &RenderOptions { scale: 1, labels: false, legend: false })
}

/// The pixmap as straight (not premultiplied) RGBA bytes, as a canvas `ImageData` wants.
pub fn to_rgba(pixmap: &Pixmap) -> Vec<u8> {
    let mut out = Vec::with_capacity(pixmap.data().len());
    for p in pixmap.pixels() {
        let c = p.demultiply();
        out.extend_from_slice(&[c.red(), c.green(), c.blue(), c.alpha()]);
    }
    out
}

/// How to draw a map and world.
#[derive(Debug, Clone, PartialEq)]
pub struct RenderOptions {
    /// Output pixels per map cell (1 = one pixel per cell).
    pub scale: u32,
    /// Draw each room's (or unit's) type and id inside it, where it fits ([`place_labels`]).
    pub labels: bool,
    /// Draw a legend of the world's colours in a corner ([`legend_entries`]); only when a
    /// world is drawn.
    pub legend: bool,
}

impl Default for RenderOptions {
    /// One pixel per cell, with labels and legend.
    fn default() -> Self {
        RenderOptions { scale: 1, labels: true, legend: true }
    }
}

/// Draws the classified map and, if given, a world over it.
///
/// The world's units, doors and object cells are placed through its [`crate::floorplan::Frame`],
/// so a world explained in a rotated frame lands on the map where it belongs. The world is
/// drawn as given (see [`draw_world`] for how unchecked worlds are treated).
///
/// Never fails and never panics: a scale of 0 counts as 1, a scale whose output would exceed
/// [`MAX_PIXELS`] is lowered to the largest that fits ([`max_scale`]), and a map that cannot be
/// drawn at all (no cells, or more than [`MAX_PIXELS`] cells) gives a 1x1 transparent pixmap.
/// [`try_render`] reports these cases instead.
///
/// ```
/// use ksmcmc::floorplan::{Door, Unit, UnitType, World};
/// use ksmcmc::grid::{Cell, Grid};
/// use ksmcmc::render::{render, RenderOptions, DOOR_RGBA};
///
/// // Two rooms side by side on a free 30x12 map, joined by a door in their shared wall.
/// let map = Grid::new(30, 12, Cell::Free);
/// let mut world = World::empty(30, 12);
/// world.units.push(Unit::new(1, 1, 1, 14, 10, UnitType::Room));
/// world.units.push(Unit::new(2, 14, 1, 15, 10, UnitType::Corridor));
/// world.doors.push(Door { id: 1, units: [1, 2], x0: 14, y0: 4, x1: 14, y1: 6, opening: false });
///
/// let pixmap = render(&map, Some(&world), &RenderOptions { scale: 4, labels: false, legend: false });
/// assert_eq!((pixmap.width(), pixmap.height()), (120, 48));
/// let door = pixmap.pixel(14 * 4 + 1, 5 * 4 + 1).unwrap();
/// assert_eq!([door.red(), door.green(), door.blue()], [DOOR_RGBA[0], DOOR_RGBA[1], DOOR_RGBA[2]]);
///
/// // The same picture as PNG bytes, e.g. for a file.
/// let png = ksmcmc::render::encode_png(&pixmap);
/// assert!(png.starts_with(b"\x89PNG"));
/// ```
pub fn render(classified: &Grid<Cell>, world: Option<&World>, options: &RenderOptions) -> Pixmap {
    let fitted = max_scale(classified.width(), classified.height());
    let scale = options.scale.clamp(1, fitted.max(1));
    let options = RenderOptions { scale, ..options.clone() };
    match try_render(classified, world, &options) {
        Ok(pixmap) => pixmap,
        // Only maps with no cells or more than MAX_PIXELS cells get here; 1x1 always allocates.
        Err(_) => Pixmap::new(1, 1).expect("a 1x1 pixmap is always valid"),
    }
}

/// The one size check of every picture of a map: a `width` x `height` map at `scale` pixels
/// per cell must have cells, a scale of at least 1 and at most [`MAX_PIXELS`] pixels. Returns
/// the picture's size in pixels.
///
/// ```
/// use ksmcmc::render::{check_size, RenderError, MAX_PIXELS};
/// assert_eq!(check_size(40, 30, 2), Ok((80, 60)));
/// assert_eq!(check_size(40, 30, 0), Err(RenderError::ZeroScale));
/// assert_eq!(MAX_PIXELS, 1 << 26);
/// assert_eq!(check_size(1 << 13, 1 << 13, 1), Ok((1 << 13, 1 << 13)));
/// assert!(matches!(check_size(1 << 13, 1 << 13, 2), Err(RenderError::TooLarge { max_scale: 1, .. })));
/// assert!(matches!(check_size(1 << 13, 1 << 14, 1), Err(RenderError::TooLarge { max_scale: 0, .. })));
/// ```
pub fn check_size(width: usize, height: usize, scale: u32) -> Result<(u32, u32), RenderError> {
    if width == 0 || height == 0 {
        return Err(RenderError::Empty { width, height });
    }
    if scale == 0 {
        return Err(RenderError::ZeroScale);
    }
    let pixels = (width as u128) * (height as u128) * (scale as u128) * (scale as u128);
    if pixels > MAX_PIXELS as u128 {
        return Err(RenderError::TooLarge { width, height, scale, max_scale: max_scale(width, height) });
    }
    // Both sides are now at most MAX_PIXELS (2^26), well inside u32 and tiny-skia's limits.
    Ok(((width as u64 * scale as u64) as u32, (height as u64 * scale as u64) as u32))
}

/// Like [`render`], but refuses what `render` would quietly adjust: a scale of 0, a map with
/// no cells, or an output over [`MAX_PIXELS`] pixels.
///
/// ```
/// use ksmcmc::grid::{Cell, Grid};
/// use ksmcmc::render::{try_render, RenderError, RenderOptions};
///
/// let map = Grid::new(5000, 5000, Cell::Free);
/// let err = try_render(&map, None, &RenderOptions { scale: 4, labels: false, legend: false }).unwrap_err();
/// assert!(matches!(err, RenderError::TooLarge { max_scale: 1, .. }));
/// assert!(err.to_string().contains("at most 1"));
/// ```
pub fn try_render(
    classified: &Grid<Cell>,
    world: Option<&World>,
    options: &RenderOptions,
) -> Result<Pixmap, RenderError> {
    let (width, height) = (classified.width(), classified.height());
    let scale = options.scale;
    let (out_w, out_h) = check_size(width, height, scale)?;
    let too_large = || RenderError::TooLarge { width, height, scale, max_scale: max_scale(width, height) };
    let mut pixmap = Pixmap::new(out_w, out_h).ok_or_else(too_large)?;
    paint_cells(&mut pixmap, classified, scale as usize);
    if let Some(world) = world {
        draw_world(&mut pixmap, width, height, world, options);
    }
    Ok(pixmap)
}

/// Fills each cell's `scale` x `scale` block with its class colour. The pixmap must be the
/// grid's size times `scale`.
fn paint_cells(pixmap: &mut Pixmap, classified: &Grid<Cell>, scale: usize) {
    let palette = |c: &Cell| {
        let [r, g, b] = cell_rgb(*c);
        ColorU8::from_rgba(r, g, b, 255).premultiply()
    };
    let out_w = pixmap.width() as usize;
    if out_w != classified.width() * scale || pixmap.height() as usize != classified.height() * scale {
        return;
    }
    // Draw the first pixel row of each cell row, then copy it down `scale - 1` times.
    for (y, block) in pixmap.pixels_mut().chunks_exact_mut(out_w * scale).enumerate() {
        let (first, rest) = block.split_at_mut(out_w);
        for (run, c) in first.chunks_exact_mut(scale).zip(classified.row(y)) {
            run.fill(palette(c));
        }
        for row in rest.chunks_exact_mut(out_w) {
            row.copy_from_slice(first);
        }
    }
}

/// Encodes a pixmap as PNG bytes (8-bit RGBA).
///
/// The bytes depend only on the pixels: the same picture always encodes the same way, so
/// outputs can be compared byte for byte. Encoding into memory cannot fail for a pixmap; should
/// the encoder ever report an error anyway, the result is empty rather than a panic.
pub fn encode_png(pixmap: &Pixmap) -> Vec<u8> {
    pixmap.encode_png().unwrap_or_default()
}

/// A distinct, deterministic colour for label `label` (used for segmentations and regions).
///
/// Hues follow the golden angle, so consecutive labels differ strongly; saturation and value
/// cycle through four bands, so that labels whose hues come close (those 21 or 55 apart)
/// differ in brightness. Labels 1 to 64 are pairwise clearly distinct; beyond that colours
/// can come close, as any fixed palette must. Label 0 conventionally means "no label" and gets white-ish gray,
/// though [`draw_labels`] leaves it undrawn.
pub fn label_rgb(label: u16) -> [u8; 3] {
    if label == 0 {
        return [230, 230, 230];
    }
    // Golden-ratio hue steps in integer arithmetic: 40503 / 65536 ~ 0.618034.
    let hue = ((label as u32 * 40503) % 65536) as f64 / 65536.0;
    let (sat, val) = match label % 4 {
        0 => (0.75, 0.95),
        1 => (0.5, 0.8),
        2 => (0.9, 0.7),
        _ => (0.55, 1.0),
    };
    hsv_to_rgb(hue, sat, val)
}

/// HSV (all in [0, 1]) to 8-bit RGB.
fn hsv_to_rgb(h: f64, s: f64, v: f64) -> [u8; 3] {
    let h6 = (h * 6.0) % 6.0;
    let sector = h6.floor();
    let f = h6 - sector;
    let (p, q, t) = (v * (1.0 - s), v * (1.0 - s * f), v * (1.0 - s * (1.0 - f)));
    let (r, g, b) = match sector as u8 {
        0 => (v, t, p),
        1 => (q, v, p),
        2 => (p, v, t),
        3 => (p, q, v),
        4 => (t, p, v),
        _ => (v, p, q),
    };
    [r, g, b].map(|c| (c * 255.0).round().clamp(0.0, 255.0) as u8)
}

/// Tints each labelled cell of a picture drawn at `scale` pixels per cell with its label's
/// colour ([`label_rgb`]) at `opacity` (0 = invisible, 255 = opaque). Cells labelled 0 stay as
/// they are.
///
/// Meant for region output such as a room segmentation: draw the map with [`render`], then the
/// labels over it. Cells whose block falls off the pixmap are skipped, so a label grid of the
/// wrong size draws what fits instead of panicking.
///
/// ```
/// use ksmcmc::grid::{Cell, Grid};
/// use ksmcmc::render::{draw_labels, draw_map, label_rgb};
///
/// let mut pixmap = draw_map(&Grid::new(4, 1, Cell::Free));
/// let labels = Grid::from_vec(4, 1, vec![0, 1, 1, 2]).unwrap();
/// draw_labels(&mut pixmap, &labels, 1, 255);
/// let p = pixmap.pixel(1, 0).unwrap();
/// assert_eq!([p.red(), p.green(), p.blue()], label_rgb(1));
/// assert_eq!(pixmap.pixel(0, 0).unwrap().red(), 255); // label 0: untouched white
/// ```
pub fn draw_labels(pixmap: &mut Pixmap, labels: &Grid<u16>, scale: u32, opacity: u8) {
    if scale == 0 || opacity == 0 {
        return;
    }
    let scale = scale as usize;
    let (out_w, out_h) = (pixmap.width() as usize, pixmap.height() as usize);
    let cols = labels.width().min(out_w / scale);
    let rows = labels.height().min(out_h / scale);
    let pixels = pixmap.pixels_mut();
    let mut cached: Option<(u16, [u16; 4])> = None;
    for y in 0..rows {
        for (x, &label) in labels.row(y).iter().enumerate().take(cols) {
            if label == 0 {
                continue;
            }
            let src = match cached {
                Some((l, src)) if l == label => src,
                _ => {
                    let [r, g, b] = label_rgb(label);
                    let a = opacity as u16;
                    let src = [r as u16 * a, g as u16 * a, b as u16 * a, 255 * a].map(|v| (v + 127) / 255);
                    cached = Some((label, src));
                    src
                }
            };
            for py in y * scale..(y + 1) * scale {
                let start = py * out_w + x * scale;
                for px in &mut pixels[start..start + scale] {
                    *px = over(src, *px, opacity);
                }
            }
        }
    }
}

/// Source-over compositing of a premultiplied source `src` (channels 0..=255 as u16) with
/// alpha `alpha` onto `dst`.
fn over(src: [u16; 4], dst: PremultipliedColorU8, alpha: u8) -> PremultipliedColorU8 {
    let keep = 255 - alpha as u16;
    let mix = |s: u16, d: u8| (s + (d as u16 * keep + 127) / 255).min(255) as u8;
    let a = mix(src[3], dst.alpha());
    let (r, g, b) = (mix(src[0], dst.red()), mix(src[1], dst.green()), mix(src[2], dst.blue()));
    // Each channel is at most the alpha by construction; keep `dst` if rounding ever disagreed.
    PremultipliedColorU8::from_rgba(r.min(a), g.min(a), b.min(a), a).unwrap_or(dst)
}
