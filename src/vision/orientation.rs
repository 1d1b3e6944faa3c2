//! The dominant wall orientation of a map, and the upright world frame it implies.
//!
//! Buildings are mostly built at right angles, so wall directions cluster around one angle
//! `φ` and `φ + 90°`. The Hough accumulator's peakiness, folded modulo 90°, finds `φ`; the map
//! is then resampled into a frame rotated by `φ`, where units are upright rectangles.

use super::hough::Hough;
use crate::geometry::Frame;
use crate::grid::{Cell, Grid};

/// The dominant wall direction in radians, in `(-π/4, π/4]`, measured from the image x axis
/// towards y (down). 0 for a map without occupied cells.
///
/// Only the wall surfaces seen from free space vote ([`wall_surface`]): maps drawn with the
/// outside filled in as occupied (the Bormann et al. floor plans) would otherwise let the
/// outline of that solid mass, not the walls, choose the angle.
pub fn dominant_angle(grid: &Grid<Cell>) -> f64 {
    // 0.25 degree bins.
    let n = 720;
    let surface = wall_surface(grid);
    let h = Hough::occupied(if surface.cells().contains(&Cell::Occupied) { &surface } else { grid }, n, 60_000);
    let half = n / 2;
    let mut best = (0usize, -1.0f64);
    for t in 0..half {
        let score = h.peakiness(t) + h.peakiness(t + half);
        if score > best.1 {
            best = (t, score);
        }
    }
    if best.1 <= 0.0 {
        return 0.0;
    }
    // The normal angle θ and the line direction θ + 90° agree modulo 90°.
    let mut phi = h.theta(best.0);
    let quarter = std::f64::consts::FRAC_PI_2;
    while phi > quarter / 2.0 {
        phi -= quarter;
    }
    phi
}

/// The occupied cells with a free 8-neighbour (the faces of walls a range sensor sees, with
/// their corners: without them the short walls of a small room leave the angle a few degrees
/// loose); all other cells unknown.
pub fn wall_surface(grid: &Grid<Cell>) -> Grid<Cell> {
    let (w, h) = (grid.width(), grid.height());
    let mut out = Grid::new(w, h, Cell::Unknown);
    for y in 0..h {
        for x in 0..w {
            if *grid.at(x, y) != Cell::Occupied {
                continue;
            }
            let free = |dx: usize, dy: usize| {
                let (nx, ny) = ((x + dx).wrapping_sub(1), (y + dy).wrapping_sub(1));
                nx < w && ny < h && *grid.at(nx, ny) == Cell::Free
            };
            if (0..3).any(|dy| (0..3).any(|dx| free(dx, dy))) {
                *out.at_mut(x, y) = Cell::Occupied;
            }
        }
    }
    out
}

/// Resamples `grid` into a world frame rotated by `angle` (nearest cell), returning the
/// world-frame grid and the frame. Cells that fall outside the map are unknown.
pub fn to_world_frame(grid: &Grid<Cell>, angle: f64) -> (Grid<Cell>, Frame) {
    let (w, h) = (grid.width() as f64, grid.height() as f64);
    let frame = Frame::turned(grid.width() as u32, grid.height() as u32, angle);
    if angle == 0.0 {
        return (grid.clone(), frame);
    }
    let [ww, wh] = frame.world_size;
    let mut out = Grid::new(ww as usize, wh as usize, Cell::Unknown);
    let rotation = frame.rotation();
    for y in 0..wh as usize {
        for x in 0..ww as usize {
            let (mx, my) = rotation.to_map(x as f64 + 0.5, y as f64 + 0.5);
            if mx >= 0.0 && my >= 0.0 && mx < w && my < h {
                *out.at_mut(x, y) = *grid.at(mx as usize, my as usize);
            }
        }
    }
    (out, frame)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rotated_box(angle_deg: f64) -> Grid<Cell> {
        // The outline of a 60 x 40 rectangle rotated by angle_deg about (60, 50).
        let mut g = Grid::new(120, 100, Cell::Unknown);
        let a = angle_deg.to_radians();
        let (s, c) = (a.sin(), a.cos());
        for i in 0..400 {
            let t = i as f64 / 400.0;
            for (px, py) in
                [(t * 60.0 - 30.0, -20.0), (t * 60.0 - 30.0, 20.0), (-30.0, t * 40.0 - 20.0), (30.0, t * 40.0 - 20.0)]
            {
                let x = 60.0 + c * px - s * py;
                let y = 50.0 + s * px + c * py;
                *g.at_mut(x as usize, y as usize) = Cell::Occupied;
            }
        }
        g
    }

    #[test]
    fn finds_the_rotation_of_a_box() {
        for deg in [0.0, 7.0, 20.0, -15.0, 33.0] {
            let found = dominant_angle(&rotated_box(deg)).to_degrees();
            let mut err = (found - deg).rem_euclid(90.0);
            if err > 45.0 {
                err = 90.0 - err;
            }
            assert!(err < 1.0, "rotated {deg}: found {found}");
        }
    }

    #[test]
    fn world_frame_makes_walls_upright() {
        let g = rotated_box(20.0);
        let angle = dominant_angle(&g);
        let (w, frame) = to_world_frame(&g, angle);
        assert!(frame.world_size[0] >= 120 && frame.world_size[1] >= 100);
        // In the world frame, the occupied cells concentrate on few rows and columns.
        let mut rows: Vec<u32> =
            (0..w.height()).map(|y| w.row(y).iter().filter(|&&c| c == Cell::Occupied).count() as u32).collect();
        rows.sort_unstable();
        let top2: u32 = rows.iter().rev().take(4).sum();
        assert!(top2 > 90, "long walls should fill few rows: {top2}");
    }
}
