//! Scores of a world against a map.

use crate::floorplan::world::{Frame, FrameGroup, Unit, World};
use crate::geometry::{facing, Axis};
use crate::grid::flood::{Flood, Neighbours};
use crate::grid::{Cell, Grid};

/// The class a world predicts for every cell of the map (eq. 3.8), in the map's frame: wall
/// rings (`world.wall_thickness` deep) occupied, unit interiors and doors free, everything
/// else unknown.
///
/// Only the part of the world frame the map covers is rasterised (one byte a cell), so the
/// memory this takes is bounded by the map, not by the world's `frame.world_size`, which a
/// hostile `world.json` chooses; a window whose size overflows predicts nothing (all unknown).
pub fn predicted_map(map_width: usize, map_height: usize, world: &World) -> Grid<Cell> {
    // Units at an angle of their own (issue 13) are rasterised in their own frame; a cell is
    // a wall if any frame's rings hold it, else free if any frame's units or doors cover it.
    let mut flags = vec![0u8; map_width * map_height];
    for g in world.frame_groups() {
        add_frame_flags(map_width, map_height, world, &g, &mut flags);
    }
    let cells = flags
        .iter()
        .map(|&f| {
            if f & WALL != 0 {
                Cell::Occupied
            } else if f & COVER != 0 {
                Cell::Free
            } else {
                Cell::Unknown
            }
        })
        .collect();
    Grid::from_vec(map_width, map_height, cells).expect("the map's own size")
}

const COVER: u8 = 1;
const WALL: u8 = 2;

/// ORs into `out` (one byte per map cell) the flags of the units and doors lying in `frame`:
/// [`WALL`] on their rings, [`COVER`] on their cells; a door's cells are [`COVER`] only.
fn add_frame_flags(map_width: usize, map_height: usize, world: &World, group: &FrameGroup, out: &mut [u8]) {
    let frame = &group.frame;
    let Some(win) = map_window(map_width, map_height, frame) else { return };
    let mut flags = vec![0u8; win.w * win.h];
    let index = |x: i32, y: i32| (y - win.y) as usize * win.w + (x - win.x) as usize;
    let (right, bottom) = (win.x + win.w as i32, win.y + win.h as i32);
    for u in group.units.iter().map(|&i| &world.units[i]) {
        let r = u.rect();
        for y in r.y.max(win.y)..r.bottom().min(bottom) {
            for x in r.x.max(win.x)..r.right().min(right) {
                let wall = if r.in_ring(x, y, world.wall_thickness) { WALL } else { 0 };
                flags[index(x, y)] |= COVER | wall;
            }
        }
    }
    for d in group.doors.iter().map(|&i| &world.doors[i]) {
        for (x, y) in d.cells() {
            if x >= win.x && y >= win.y && x < right && y < bottom {
                flags[index(x, y)] = COVER;
            }
        }
    }
    for my in 0..map_height {
        for mx in 0..map_width {
            let (wx, wy) = if frame.is_identity() {
                (mx as f64 + 0.5, my as f64 + 0.5)
            } else {
                frame.to_world(mx as f64 + 0.5, my as f64 + 0.5)
            };
            let (x, y) = (libm::floor(wx), libm::floor(wy));
            if x >= win.x as f64 && y >= win.y as f64 && x < right as f64 && y < bottom as f64 {
                out[my * map_width + mx] |= flags[index(x as i32, y as i32)];
            }
        }
    }
}

/// A rectangle of world cells, with its size as `usize`s.
struct Window {
    x: i32,
    y: i32,
    w: usize,
    h: usize,
}

/// The world cells under the map's cells: the bounding box of the map turned into the world
/// frame, clipped to the world. `None` when it is empty or its size does not fit `usize`.
fn map_window(map_width: usize, map_height: usize, frame: &Frame) -> Option<Window> {
    // Units lie at i32 coordinates: no world cell past i32::MAX can be covered.
    let [ww, wh] = frame.world_size.map(|v| f64::from(v).min(i32::MAX as f64));
    let (mw, mh) = (map_width as f64, map_height as f64);
    let (x0, y0, x1, y1) = if frame.is_identity() {
        (0.0, 0.0, mw.min(ww), mh.min(wh))
    } else {
        let corners = [(0.0, 0.0), (mw, 0.0), (0.0, mh), (mw, mh)].map(|(x, y)| frame.to_world(x, y));
        let min = |f: fn(&(f64, f64)) -> f64| corners.iter().map(f).fold(f64::INFINITY, f64::min);
        let max = |f: fn(&(f64, f64)) -> f64| corners.iter().map(f).fold(f64::NEG_INFINITY, f64::max);
        let (x0, x1) = (libm::floor(min(|c| c.0)).max(0.0), libm::ceil(max(|c| c.0)).min(ww));
        let (y0, y1) = (libm::floor(min(|c| c.1)).max(0.0), libm::ceil(max(|c| c.1)).min(wh));
        (x0, y0, x1, y1)
    };
    if !(x1 > x0 && y1 > y0) {
        return None;
    }
    let (w, h) = ((x1 - x0) as usize, (y1 - y0) as usize);
    w.checked_mul(h)?;
    Some(Window { x: x0 as i32, y: y0 as i32, w, h })
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

/// Segmentation quality by the room-segmentation benchmark's scoring (Bormann et al. 2016).
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct SegmentationScore {
    /// Mean over predicted segments of their best overlap with a truth segment, over their size.
    pub precision: f64,
    /// Mean over truth segments of their best overlap with a predicted segment, over their size.
    pub recall: f64,
    /// Predicted segments scored (after dropping small ones).
    pub predicted: usize,
    /// Truth segments scored.
    pub truth: usize,
}

/// Segments of 100 cells or fewer are dropped on both sides, as the benchmark does.
pub const MIN_SEGMENT_CELLS: usize = 101;

/// Scores predicted labels against truth labels (0 = no segment on either side).
pub fn score_segmentation(predicted: &Grid<u32>, truth: &Grid<u32>) -> SegmentationScore {
    use std::collections::BTreeMap;
    let mut pred_size: BTreeMap<u32, usize> = BTreeMap::new();
    let mut truth_size: BTreeMap<u32, usize> = BTreeMap::new();
    let mut overlap: BTreeMap<(u32, u32), usize> = BTreeMap::new();
    for (&p, &t) in predicted.cells().iter().zip(truth.cells()) {
        if p != 0 {
            *pred_size.entry(p).or_default() += 1;
        }
        if t != 0 {
            *truth_size.entry(t).or_default() += 1;
        }
        if p != 0 && t != 0 {
            *overlap.entry((p, t)).or_default() += 1;
        }
    }
    pred_size.retain(|_, n| *n >= MIN_SEGMENT_CELLS);
    truth_size.retain(|_, n| *n >= MIN_SEGMENT_CELLS);
    let mut best_for_pred: BTreeMap<u32, usize> = BTreeMap::new();
    let mut best_for_truth: BTreeMap<u32, usize> = BTreeMap::new();
    for (&(p, t), &n) in &overlap {
        if pred_size.contains_key(&p) && truth_size.contains_key(&t) {
            let b = best_for_pred.entry(p).or_default();
            *b = (*b).max(n);
            let b = best_for_truth.entry(t).or_default();
            *b = (*b).max(n);
        }
    }
    let mean = |sizes: &BTreeMap<u32, usize>, best: &BTreeMap<u32, usize>| {
        if sizes.is_empty() {
            return 0.0;
        }
        sizes.iter().map(|(k, &n)| *best.get(k).unwrap_or(&0) as f64 / n as f64).sum::<f64>() / sizes.len() as f64
    };
    SegmentationScore {
        precision: mean(&pred_size, &best_for_pred),
        recall: mean(&truth_size, &best_for_truth),
        predicted: pred_size.len(),
        truth: truth_size.len(),
    }
}

/// Truth segments from a drawn ground-truth image: the 4-connected regions of cells marked
/// `true` (white in the benchmark's images), numbered from 1.
pub fn regions(white: &Grid<bool>) -> Grid<u32> {
    let (w, h) = (white.width(), white.height());
    let mut out = Grid::new(w, h, 0u32);
    let mut next = 0;
    let mut flood = Flood::default();
    for start in 0..w * h {
        if !white.cells()[start] || out.cells()[start] != 0 {
            continue;
        }
        next += 1;
        let ids = out.cells_mut();
        let mut enter = |j: usize| white.cells()[j] && ids[j] == 0 && std::mem::replace(&mut ids[j], next) == 0;
        flood.fill(w, h, [start], Neighbours::Four, &mut enter, |_| {});
    }
    out
}

/// The confusion counts `n[C_M][C_W]` of a world on the map's own cells (classes indexed
/// free 0, unknown 1, occupied 2): where the world's predictions (eq. 3.8) and the map agree
/// (the diagonal, whose share is `K(W, M)`) and where they do not.
pub fn confusion(map: &Grid<Cell>, world: &World) -> [[u64; 3]; 3] {
    let p = predicted_map(map.width(), map.height(), world);
    let mut n = [[0u64; 3]; 3];
    for (&m, &w) in map.cells().iter().zip(p.cells()) {
        n[m as usize][w as usize] += 1;
    }
    n
}

// ---------------------------------------------------------------------------------------------
// Topological defects (section 3.7, Fig. 3.27): a quality metric of a world, on its own.

/// The share of adjacent room-room pairs whose connecting walls differ in length by more than
/// 10 % of the longer one: the topological defects of section 3.7 (Fig. 3.27). `None` when the
/// world has no adjacent room pairs.
pub fn defects(world: &World) -> Option<f64> {
    let (bad, pairs) = defect_pairs(world);
    (pairs > 0).then(|| bad as f64 / pairs as f64)
}

/// The counts behind [`defects`]: adjacent room-room pairs whose connecting walls differ by
/// more than 10 % of the longer one, and all adjacent room-room pairs. Pooled over several
/// worlds they weigh each pair alike, where averaging [`defects`] weighs each world alike.
pub fn defect_pairs(world: &World) -> (u32, u32) {
    let t = world.wall_thickness;
    let rooms: Vec<&crate::floorplan::world::Unit> =
        world.units.iter().filter(|u| u.kind == crate::floorplan::world::UnitType::Room).collect();
    let (mut bad, mut pairs) = (0u32, 0u32);
    for (i, a) in rooms.iter().enumerate() {
        for b in &rooms[i + 1..] {
            if let Some((la, lb)) = connecting_walls(a, b, t) {
                pairs += 1;
                if (la - lb).abs() as f64 > SAME_LENGTH_TOLERANCE * la.max(lb) as f64 {
                    bad += 1;
                }
            }
        }
    }
    (bad, pairs)
}

/// The lengths of the connecting walls of two adjacent units (their facing sides), cells.
pub fn connecting_walls(a: &Unit, b: &Unit, t: i32) -> Option<(i32, i32)> {
    let faces = |axis| {
        facing(a.rect(), b.rect(), axis, 2 * t, t).is_some() || facing(b.rect(), a.rect(), axis, 2 * t, t).is_some()
    };
    // Side by side, the connecting walls are the vertical sides; one above the other, the
    // horizontal ones.
    if faces(Axis::Horizontal) {
        Some((a.h, b.h))
    } else if faces(Axis::Vertical) {
        Some((a.w, b.w))
    } else {
        None
    }
}

/// Connecting walls differing by at most this share of the longer one have the same length:
/// the test of [`defect_pairs`] and of the `SaLe` atoms of [`crate::floorplan::knowledge::training_facts`].
pub const SAME_LENGTH_TOLERANCE: f64 = 0.1;

/// Whether two units are adjacent and their connecting walls have the same length within
/// [`SAME_LENGTH_TOLERANCE`]: the true value of `SaLe(a, b)`.
pub fn same_length(a: &Unit, b: &Unit, t: i32) -> bool {
    connecting_walls(a, b, t)
        .is_some_and(|(la, lb)| (la - lb).abs() as f64 <= SAME_LENGTH_TOLERANCE * la.max(lb) as f64)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn perfect_and_split_segmentations() {
        // Truth: two 20x20 halves.
        let truth = Grid::from_vec(40, 20, (0..800).map(|i| if i % 40 < 20 { 1 } else { 2 }).collect()).unwrap();
        let s = score_segmentation(&truth, &truth);
        assert_eq!((s.precision, s.recall, s.predicted, s.truth), (1.0, 1.0, 2, 2));
        // One segment over everything: precision 0.5 (best overlap 400 of 800), recall 1.
        let one = Grid::new(40, 20, 7u32);
        let s = score_segmentation(&one, &truth);
        assert_eq!((s.precision, s.recall), (0.5, 1.0));
        // Over-segmentation into four: precision 1, recall 0.5.
        let four = Grid::from_vec(40, 20, (0..800).map(|i| 1 + (i % 40 / 10) as u32).collect()).unwrap();
        let s = score_segmentation(&four, &truth);
        assert_eq!((s.precision, s.recall), (1.0, 0.5));
        // Small segments (<= 100 cells) are dropped.
        let tiny = Grid::from_vec(40, 20, (0..800).map(|i| if i < 100 { 9 } else { 0 }).collect()).unwrap();
        assert_eq!(score_segmentation(&tiny, &truth).predicted, 0);
    }

    #[test]
    fn regions_are_four_connected() {
        let w = Grid::from_vec(
            5,
            3,
            vec![true, true, false, true, true, false, false, true, false, false, true, false, false, true, true],
        )
        .unwrap();
        let r = regions(&w);
        assert_eq!(r.cells(), &[1, 1, 0, 2, 2, 0, 0, 3, 0, 0, 4, 0, 0, 5, 5]);
    }
}
