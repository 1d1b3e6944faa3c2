//! Rendering with tiny-skia: classified maps, semantic worlds and scene graphs.
//!
//! Everything draws into a [`tiny_skia::Pixmap`]; natively that becomes a PNG, in the browser
//! the same RGBA bytes go to a `<canvas>` through `ImageData`, so both show identical pixels.

use crate::grid::{Cell, Grid};
use tiny_skia::Pixmap;

/// The colour of a classified cell: occupied black, unknown gray, free white.
pub fn cell_rgb(c: Cell) -> [u8; 3] {
    match c {
        Cell::Occupied => [0, 0, 0],
        Cell::Unknown => [160, 160, 160],
        Cell::Free => [255, 255, 255],
    }
}

/// Draws a classified map one pixel per cell.
pub fn draw_map(classified: &Grid<Cell>) -> Pixmap {
    let mut pixmap = Pixmap::new(classified.width() as u32, classified.height() as u32)
        .expect("grid sizes are checked against Limits on load");
    for (px, c) in pixmap.pixels_mut().iter_mut().zip(classified.cells()) {
        let [r, g, b] = cell_rgb(*c);
        *px = tiny_skia::PremultipliedColorU8::from_rgba(r, g, b, 255).expect("opaque");
    }
    pixmap
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
    /// Draw each unit's type and id at its centre.
    pub labels: bool,
}

impl Default for RenderOptions {
    fn default() -> Self {
        RenderOptions {
            scale: 1,
            labels: true,
        }
    }
}

/// Draws the classified map and, if given, a world over it (placeholder: world drawing is being
/// written).
pub fn render(
    classified: &Grid<Cell>,
    world: Option<&crate::floorplan::World>,
    options: &RenderOptions,
) -> Pixmap {
    let _ = (world, options);
    draw_map(classified)
}

/// Encodes a pixmap as PNG bytes (placeholder).
pub fn encode_png(pixmap: &Pixmap) -> Vec<u8> {
    pixmap.encode_png().unwrap_or_default()
}
