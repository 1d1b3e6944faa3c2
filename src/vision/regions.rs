//! Which wall direction each part of a map follows (issue 13, step 1).
//!
//! [`super::orientation::wall_directions`] finds the directions a building's walls follow over
//! the whole map, folded modulo 90°. A building whose wings meet at an angle, or a pentagon,
//! has several, and each wing follows one of them: the units that explain a wing should be
//! upright in *its* direction's frame. This module says where each direction holds, by local
//! votes:
//!
//! 1. every wall face cell (an occupied cell beside free space) votes for the direction along
//!    which the faces around it run straightest: the most face cells within `run_m` on
//!    either side along the direction or at right angles to it, when that count beats every
//!    other direction's clearly (corners and furniture outlines, which fit several, stay
//!    silent);
//! 2. every free cell takes the direction with the most votes within `radius_m` (a square
//!    window, counted with one summed-area table per direction), the first (strongest)
//!    direction where no face voted;
//! 3. pieces of one direction smaller than `min_area_m2` take the direction of most of the
//!    free cells around them, so that a desk at an angle in a room does not make a region.
//!
//! Lengths and areas are in metres, turned into cells once from the map's resolution, so the
//! same building has the same regions at any cell size. Everything is integer counting over
//! the grid in a fixed order, so the result is the same natively and in wasm.

use super::orientation::{wall_surface, WallDirection, WallProfile};
use crate::grid::flood::{neighbours4, Flood, Neighbours};
use crate::grid::{Cell, Grid};

/// How the regions are found: lengths in metres and areas in square metres, each default
/// with its physical reason, turned into cells from the map's resolution.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RegionConfig {
    /// Directions weaker than this share of the strongest are left out (as in
    /// [`wall_directions`](super::orientation::wall_directions)).
    pub min_strength: f64,
    /// How far along a direction, m, wall faces are counted on either side of a face cell
    /// (default 0.6 m: a wall face runs straight over a metre and more, a door leaf's width
    /// either side; corners and furniture outlines bend within that).
    pub run_m: f64,
    /// A face votes when its best direction's count is at least this share of the longest
    /// possible run, `2 run + 1` cells (default 0.7)...
    pub min_straight: f64,
    /// ...and at least this many times every other direction's (default 1.5).
    pub margin: f64,
    /// Half side of the square window over which free cells count votes, m (default 2 m: about
    /// half a room's width, so a free cell follows the walls of the room it stands in).
    pub radius_m: f64,
    /// Connected pieces of one direction smaller than this, m², are absorbed by their
    /// surroundings (default 4 m²: under half of the smallest office, more than a desk or a
    /// cupboard standing at an angle).
    pub min_area_m2: f64,
}

impl Default for RegionConfig {
    fn default() -> Self {
        RegionConfig { min_strength: 0.3, run_m: 0.6, min_straight: 0.7, margin: 1.5, radius_m: 2.0, min_area_m2: 4.0 }
    }
}

/// [`RegionConfig`]'s lengths in cells of one map: 12, 40 and 1,600 at 5 cm.
#[derive(Debug, Clone, Copy, PartialEq)]
struct RegionCells {
    run: i32,
    radius: usize,
    min_area: usize,
}

impl RegionConfig {
    /// These lengths in whole cells of `resolution` metres (read as 0.05 m if it is no
    /// positive number), each at least one cell.
    fn cells(&self, resolution: f64) -> RegionCells {
        let r = crate::grid::cell_size_m(resolution);
        let len = |m: f64| libm::round(m.max(0.0) / r).clamp(1.0, i32::MAX as f64 / 4.0) as i32;
        let area = libm::round(self.min_area_m2.max(0.0) / (r * r)).clamp(1.0, u32::MAX as f64) as usize;
        RegionCells { run: len(self.run_m), radius: len(self.radius_m) as usize, min_area: area }
    }
}

/// No direction: the cell is not free.
pub const NO_REGION: u8 = u8::MAX;

/// The directions of a map and where each holds.
#[derive(Debug, Clone, PartialEq)]
pub struct DirectionRegions {
    /// The directions, strongest first (at most 254).
    pub directions: Vec<WallDirection>,
    /// Per map cell: the index in `directions` of the direction its part of the building
    /// follows for free cells, [`NO_REGION`] for the others.
    pub region: Grid<u8>,
}

impl DirectionRegions {
    /// The share of the free cells in each direction's region, in the order of `directions`.
    pub fn shares(&self) -> Vec<f64> {
        let mut counts = vec![0usize; self.directions.len()];
        for &r in self.region.cells() {
            if let Some(c) = counts.get_mut(r as usize) {
                *c += 1;
            }
        }
        let total = counts.iter().sum::<usize>().max(1) as f64;
        counts.iter().map(|&c| c as f64 / total).collect()
    }
}

/// Finds the wall directions of `grid` (a map of `resolution` metres a cell) and the region of
/// free cells each holds (module docs).
///
/// ```
/// use ksmcmc::floorplan::synth::{generate, SynthConfig};
/// use ksmcmc::vision::regions::{direction_regions, RegionConfig};
/// // Two buildings, the second turned 30 degrees against the first.
/// let s = generate(&SynthConfig { wing_deg: 30.0, ..SynthConfig::default() }, 1)?;
/// let found = direction_regions(s.map.classified(), &RegionConfig::default(), 0.05);
/// let degrees: Vec<i64> = found.directions.iter().map(|d| d.angle.to_degrees().round() as i64).collect();
/// assert!(degrees.contains(&0) && degrees.contains(&30), "{degrees:?}");
/// let shares = found.shares();
/// assert!(shares.iter().filter(|&&s| s > 0.3).count() == 2, "{shares:?}");
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn direction_regions(grid: &Grid<Cell>, config: &RegionConfig, resolution: f64) -> DirectionRegions {
    direction_regions_from(grid, &WallProfile::of(grid), config, resolution)
}

/// [`direction_regions`] with the wall directions read off `profile`, the [`WallProfile`] of
/// `grid` a caller has already built (the Hough transform is most of the cost).
pub fn direction_regions_from(
    grid: &Grid<Cell>,
    profile: &WallProfile,
    config: &RegionConfig,
    resolution: f64,
) -> DirectionRegions {
    let cells = config.cells(resolution);
    let mut directions = profile.directions(config.min_strength);
    directions.truncate(NO_REGION as usize);
    let (w, h) = (grid.width(), grid.height());
    let free = |i: usize| grid.cells()[i] == Cell::Free;
    let mut region = Grid::from_vec(w, h, (0..w * h).map(|i| if free(i) { 0 } else { NO_REGION }).collect())
        .expect("the grid's own size");
    if directions.len() < 2 {
        return DirectionRegions { directions, region };
    }
    let votes = face_votes(grid, &directions, config, cells.run);
    let sums: Vec<Sums> = (0..directions.len()).map(|k| Sums::new(&votes, w, h, k as u8)).collect();
    let r = cells.radius;
    for y in 0..h {
        for x in 0..w {
            if !free(y * w + x) {
                continue;
            }
            let (x0, y0, x1, y1) = (x.saturating_sub(r), y.saturating_sub(r), (x + r + 1).min(w), (y + r + 1).min(h));
            let mut best = (0u32, 0u8);
            for (k, s) in sums.iter().enumerate() {
                let n = s.count(x0, y0, x1, y1);
                if n > best.0 {
                    best = (n, k as u8);
                }
            }
            *region.at_mut(x, y) = best.1;
        }
    }
    absorb_small_pieces(&mut region, cells.min_area);
    DirectionRegions { directions, region }
}

/// Per cell: the index of the direction a wall face cell votes for, [`NO_REGION`] elsewhere.
/// `run` is [`RegionConfig::run_m`] in cells.
fn face_votes(grid: &Grid<Cell>, directions: &[WallDirection], c: &RegionConfig, run: i32) -> Vec<u8> {
    let surface = wall_surface(grid);
    let (w, h) = (grid.width(), grid.height());
    let face = |x: i64, y: i64| {
        x >= 0 && y >= 0 && x < w as i64 && y < h as i64 && *surface.at(x as usize, y as usize) == Cell::Occupied
    };
    // Unit steps along each direction and at right angles to it.
    let steps: Vec<[(f64, f64); 2]> = directions
        .iter()
        .map(|d| {
            let (s, co) = (libm::sin(d.angle), libm::cos(d.angle));
            [(co, s), (-s, co)]
        })
        .collect();
    let longest = (2 * run + 1) as f64;
    let mut votes = vec![NO_REGION; w * h];
    let mut counts = vec![0u32; directions.len()];
    for y in 0..h {
        for x in 0..w {
            if *surface.at(x, y) != Cell::Occupied {
                continue;
            }
            for (k, pair) in steps.iter().enumerate() {
                counts[k] = pair
                    .iter()
                    .map(|&(dx, dy)| {
                        (-run..=run)
                            .filter(|&i| {
                                let (px, py) = (x as f64 + 0.5 + dx * i as f64, y as f64 + 0.5 + dy * i as f64);
                                face(libm::floor(px) as i64, libm::floor(py) as i64)
                            })
                            .count() as u32
                    })
                    .max()
                    .unwrap_or(0);
            }
            let (best, k) = counts
                .iter()
                .enumerate()
                .map(|(k, &n)| (n, k))
                .max_by_key(|&(n, k)| (n, std::cmp::Reverse(k)))
                .unwrap_or((0, 0));
            let second = counts.iter().enumerate().filter(|&(j, _)| j != k).map(|(_, &n)| n).max().unwrap_or(0);
            if best as f64 >= c.min_straight * longest && best as f64 >= c.margin * second as f64 {
                votes[y * w + x] = k as u8;
            }
        }
    }
    votes
}

/// A summed-area table of the cells voting for one direction.
struct Sums {
    width: usize,
    sums: Vec<u32>,
}

impl Sums {
    fn new(votes: &[u8], w: usize, h: usize, k: u8) -> Sums {
        let width = w + 1;
        let mut sums = vec![0u32; width * (h + 1)];
        for y in 0..h {
            let mut row = 0;
            for x in 0..w {
                row += u32::from(votes[y * w + x] == k);
                sums[(y + 1) * width + x + 1] = sums[y * width + x + 1] + row;
            }
        }
        Sums { width, sums }
    }

    /// Votes in columns `x0..x1` and rows `y0..y1`.
    fn count(&self, x0: usize, y0: usize, x1: usize, y1: usize) -> u32 {
        let s = |x: usize, y: usize| self.sums[y * self.width + x];
        s(x1, y1) + s(x0, y0) - s(x0, y1) - s(x1, y0)
    }
}

/// Relabels every 4-connected piece of one direction smaller than `min_area` cells with the
/// direction most of its free 4-neighbours outside it have (ties: the lower index), in one
/// pass over the pieces in row-major order of their first cell.
fn absorb_small_pieces(region: &mut Grid<u8>, min_area: usize) {
    let (w, h) = (region.width(), region.height());
    let mut seen = vec![false; w * h];
    let (mut flood, mut piece) = (Flood::default(), Vec::new());
    for start in 0..w * h {
        let k = region.cells()[start];
        if k == NO_REGION || seen[start] {
            continue;
        }
        piece.clear();
        let mut around = std::collections::BTreeMap::<u8, usize>::new();
        let cells = region.cells();
        let mut enter = |n: usize| cells[n] == k && !std::mem::replace(&mut seen[n], true);
        flood.fill(w, h, [start], Neighbours::Four, &mut enter, |c| {
            piece.push(c);
            for l in neighbours4(c, w, h).map(|n| cells[n]) {
                if l != k && l != NO_REGION {
                    *around.entry(l).or_default() += 1;
                }
            }
        });
        if piece.len() >= min_area {
            continue;
        }
        // The most common neighbour direction; the first key wins ties (max_by_key keeps the last).
        let Some((&to, _)) = around.iter().rev().max_by_key(|&(_, &n)| n) else { continue };
        for &c in &piece {
            region.cells_mut()[c] = to;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lengths_become_cells_of_the_maps_resolution() {
        let c = RegionConfig::default();
        // At 5 cm, the numbers these settings had in cells.
        assert_eq!(c.cells(0.05), RegionCells { run: 12, radius: 40, min_area: 1600 });
        assert_eq!(c.cells(0.1), RegionCells { run: 6, radius: 20, min_area: 400 });
        assert_eq!(c.cells(0.025), RegionCells { run: 24, radius: 80, min_area: 6400 });
        // No resolution reads as 5 cm; a setting of 0 is still one cell.
        assert_eq!(c.cells(f64::NAN), c.cells(0.05));
        let none = RegionConfig { run_m: 0.0, radius_m: 0.0, min_area_m2: 0.0, ..c };
        assert_eq!(none.cells(0.05), RegionCells { run: 1, radius: 1, min_area: 1 });
    }

    #[test]
    fn small_pieces_take_their_surroundings() {
        let mut g = Grid::new(10, 10, 0u8);
        for y in 2..4 {
            for x in 2..4 {
                *g.at_mut(x, y) = 1;
            }
        }
        for y in 0..10 {
            *g.at_mut(9, y) = NO_REGION;
        }
        let mut big = g.clone();
        absorb_small_pieces(&mut g, 5);
        assert!(g.cells().iter().all(|&c| c == 0 || c == NO_REGION));
        absorb_small_pieces(&mut big, 4);
        assert_eq!(big.cells().iter().filter(|&&c| c == 1).count(), 4, "a piece of min_area stays");
    }
}
