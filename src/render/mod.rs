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
