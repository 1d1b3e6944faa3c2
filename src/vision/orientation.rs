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
    WallProfile::of(grid).dominant_angle()
}

/// How peaked the Hough votes of a map's wall surfaces are at each angle, folded modulo 90°
/// (walls at right angles vote together): what [`dominant_angle`] and [`wall_directions`] read.
/// The Hough transform is most of their cost, so a caller that wants both, or wants them
/// again for the same map, builds this once ([`WallProfile::of`]) and asks it.
#[derive(Debug, Clone, PartialEq)]
pub struct WallProfile {
    /// Per angle bin in `[0°, 90°)`: the peakiness of that angle and of the angle 90° on.
    profile: Vec<f64>,
}

impl WallProfile {
    /// The profile of `grid`'s wall surfaces (the Hough transform of [`wall_surface`], or of
    /// every occupied cell when no wall faces free space).
    pub fn of(grid: &Grid<Cell>) -> WallProfile {
        let surface = wall_surface(grid);
        let h = Hough::occupied(if surface.cells().contains(&Cell::Occupied) { &surface } else { grid }, BINS, 60_000);
        let half = BINS / 2;
        WallProfile { profile: (0..half).map(|t| h.peakiness(t) + h.peakiness(t + half)).collect() }
    }

    /// The angle of bin `t`, radians, as [`Hough::theta`] gives it.
    fn theta(t: usize) -> f64 {
        std::f64::consts::PI * t as f64 / BINS as f64
    }

    /// [`dominant_angle`] of the map this profile is of.
    pub fn dominant_angle(&self) -> f64 {
        let mut best = (0usize, -1.0f64);
        for (t, &score) in self.profile.iter().enumerate() {
            if score > best.1 {
                best = (t, score);
            }
        }
        if best.1 <= 0.0 {
            return 0.0;
        }
        fold(Self::theta(best.0))
    }

    /// [`wall_directions`] of the map this profile is of.
    pub fn directions(&self, min_strength: f64) -> Vec<WallDirection> {
        let profile = &self.profile;
        let n = profile.len();
        let mut sorted = profile.clone();
        sorted.sort_by(f64::total_cmp);
        let median = sorted[n / 2];
        let top = sorted[n - 1] - median;
        if top <= 0.0 {
            return Vec::new();
        }
        let window = 12; // 3 degrees of 0.25 degree bins
        let mut found: Vec<WallDirection> = (0..n)
            .filter(|&t| {
                let s = profile[t];
                (1..=window).all(|d| s > profile[(t + n - d) % n] && s >= profile[(t + d) % n])
            })
            .map(|t| WallDirection { angle: fold(Self::theta(t)), strength: (profile[t] - median) / top })
            .filter(|d| d.strength >= min_strength)
            .collect();
        found.sort_by(|a, b| b.strength.total_cmp(&a.strength));
        found
    }
}

/// Hough angle bins: 0.25 degree each.
const BINS: usize = 720;

/// A Hough normal angle folded into `(-π/4, π/4]`: the normal and the line direction agree
/// modulo 90°.
fn fold(mut phi: f64) -> f64 {
    let quarter = std::f64::consts::FRAC_PI_2;
    while phi > quarter / 2.0 {
        phi -= quarter;
    }
    phi
}

/// One direction the walls of a map follow (with the direction at right angles to it).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WallDirection {
    /// Radians in `(-π/4, π/4]`, as [`dominant_angle`] gives them.
    pub angle: f64,
    /// How strongly the walls follow it, relative to the strongest direction (1): the height of
    /// its Hough peak above the median over all angles.
    pub strength: f64,
}

/// The directions the walls of a map follow, strongest first: every angle whose folded Hough
/// peak stands out of the angles within 3° on either side and reaches `min_strength` of the
/// strongest one's height above the median. The first is [`dominant_angle`]'s (when the map
/// has walls). A building whose wings meet at an angle, or a pentagon, has several; the world
/// model's units follow only the first (issue 13), so more than one says where units will
/// fit badly.
///
/// ```
/// use ksmcmc::grid::{Cell, Grid};
/// use ksmcmc::vision::orientation::wall_directions;
/// // A free 10 m x 6 m room with upright walls: one direction, 0 (to the Hough
/// // transform's resolution).
/// let mut g = Grid::new(220, 140, Cell::Unknown);
/// for y in 10..130 {
///     for x in 10..210 {
///         let wall = x == 10 || x == 209 || y == 10 || y == 129;
///         *g.at_mut(x, y) = if wall { Cell::Occupied } else { Cell::Free };
///     }
/// }
/// let found = wall_directions(&g, 0.3);
/// assert_eq!(found.len(), 1, "{found:?}");
/// assert!(found[0].angle.abs() < 0.01 && found[0].strength == 1.0, "{found:?}");
/// ```
pub fn wall_directions(grid: &Grid<Cell>, min_strength: f64) -> Vec<WallDirection> {
    WallProfile::of(grid).directions(min_strength)
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
    fn one_box_has_one_wall_direction_two_boxes_at_an_angle_two() {
        for deg in [0.0, 20.0, -15.0] {
            let found = wall_directions(&rotated_box(deg), 0.3);
            assert_eq!(found.len(), 1, "{deg}: {found:?}");
            assert!((found[0].angle.to_degrees() - deg).abs() < 1.0, "{deg}: {found:?}");
        }
        // Two boxes, upright and at 30 degrees, side by side.
        let (a, b) = (rotated_box(0.0), rotated_box(30.0));
        let mut g = Grid::new(240, 100, Cell::Unknown);
        for y in 0..100 {
            for x in 0..120 {
                *g.at_mut(x, y) = *a.at(x, y);
                *g.at_mut(x + 120, y) = *b.at(x, y);
            }
        }
        let found = wall_directions(&g, 0.3);
        let mut degs: Vec<f64> = found.iter().map(|d| d.angle.to_degrees()).collect();
        degs.sort_by(f64::total_cmp);
        assert_eq!(degs.len(), 2, "{found:?}");
        assert!(degs[0].abs() < 1.0 && (degs[1] - 30.0).abs() < 1.0, "{degs:?}");
        assert_eq!(found[0].strength, 1.0);
        assert!((found[0].angle - dominant_angle(&g)).abs() < 1e-12);
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
