//! Scores of a world against a map.

use super::world::World;
use crate::grid::{Cell, Grid};

/// The class a world predicts for every cell of the map (eq. 3.8), in the map's frame: wall
/// rings (`world.wall_thickness` deep) occupied, unit interiors and doors free, everything
/// else unknown.
pub fn predicted_map(map_width: usize, map_height: usize, world: &World) -> Grid<Cell> {
    let [ww, wh] = world.frame.world_size;
    let (ww, wh) = (ww as usize, wh as usize);
    // Predicted classes in the world frame, from counters as in Explanation.
    let mut cover = vec![0u8; ww * wh];
    let mut wall = vec![0u8; ww * wh];
    for u in &world.units {
        let r = u.rect();
        for y in r.y.max(0)..r.bottom().min(wh as i32) {
            for x in r.x.max(0)..r.right().min(ww as i32) {
                let i = y as usize * ww + x as usize;
                cover[i] = cover[i].saturating_add(1);
                if r.in_ring(x, y, world.wall_thickness) {
                    wall[i] = wall[i].saturating_add(1);
                }
            }
        }
    }
    for d in &world.doors {
        for (x, y) in d.cells() {
            if x >= 0 && y >= 0 && (x as usize) < ww && (y as usize) < wh {
                wall[y as usize * ww + x as usize] = 0;
                cover[y as usize * ww + x as usize] = cover[y as usize * ww + x as usize].max(1);
            }
        }
    }
    let class = |i: usize| {
        if wall[i] > 0 {
            Cell::Occupied
        } else if cover[i] > 0 {
            Cell::Free
        } else {
            Cell::Unknown
        }
    };
    let mut out = Grid::new(map_width, map_height, Cell::Unknown);
    for my in 0..map_height {
        for mx in 0..map_width {
            let (wx, wy) = if world.frame.is_identity() {
                (mx as f64 + 0.5, my as f64 + 0.5)
            } else {
                world.frame.to_world(mx as f64 + 0.5, my as f64 + 0.5)
            };
            if wx >= 0.0 && wy >= 0.0 && (wx as usize) < ww && (wy as usize) < wh {
                *out.at_mut(mx, my) = class(wy as usize * ww + wx as usize);
            }
        }
    }
    out
}

/// The cell prediction rate `K(W, M)` of eq. 3.39 on the map's own cells.
pub fn prediction_rate(map: &Grid<Cell>, world: &World) -> f64 {
    prediction_rate_in(map, world, None)
}

/// `K(W, M)` restricted to cells where `region` is true (a region of interest), or the whole
/// map for `None`.
pub fn prediction_rate_in(map: &Grid<Cell>, world: &World, region: Option<&Grid<bool>>) -> f64 {
    let p = predicted_map(map.width(), map.height(), world);
    let (mut hits, mut total) = (0u64, 0u64);
    for (i, (&m, &w)) in map.cells().iter().zip(p.cells()).enumerate() {
        if region.is_some_and(|r| !r.cells()[i]) {
            continue;
        }
        total += 1;
        hits += (m == w) as u64;
    }
    if total == 0 {
        0.0
    } else {
        hits as f64 / total as f64
    }
}
