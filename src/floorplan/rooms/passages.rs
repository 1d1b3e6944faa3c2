//! Rooms touch only where a person can pass: the last stage of the label image.
//!
//! The wavefront that labels the free cells beyond the units runs into every hole of a wall:
//! the one-cell gaps of a scanned wall, and the dotted line a glass pane leaves (every other
//! column of the wall seen through). Where it runs through, the two rooms' labels meet in the
//! wall, and the rooms read as opening onto each other (`opens_to`, and the door links a
//! benchmark scores) where a person sees a wall and no robot passes. So each stretch along
//! which two rooms' labels touch is kept only if it is a passage: somewhere along it the free
//! space is at least [`MIN_PASSAGE_M`] wide. The cells of a narrower stretch belong to no room,
//! as the wall they lie in.
//!
//! The width is read from the free space's depth (a chamfer distance to the nearest cell that
//! is not free) with a map's specks looked past ([`super::read::SPECK_M`]): a scan's miss in a
//! doorway does not close it. Glass panes' mullions, a wall's thickness long, are no specks.

use crate::grid::flood::{neighbours4, Flood, Neighbours};
use crate::grid::Grid;

/// The narrowest passage, m, along which two rooms open onto each other: 0.5 m, a person's
/// shoulders (about 0.45 m) and the narrowest a robot takes for a door, below every door leaf
/// building codes allow (0.6 m and more). The link score counts the same half metre.
pub const MIN_PASSAGE_M: f64 = 0.5;

/// A passage of [`MIN_PASSAGE_M`] in whole cells of `resolution` m, at least one: how far two
/// rooms touch to open onto each other (ten cells at 5 cm, as the link score's
/// [`MIN_CONTACT_CELLS`](crate::floorplan::topology::MIN_CONTACT_CELLS)).
pub(crate) fn passage_cells(resolution: f64) -> usize {
    libm::round(MIN_PASSAGE_M / crate::grid::cell_size_m(resolution)).max(1.0) as usize
}

/// The depth (chamfer units, 3 per cell) the middle of a passage of [`MIN_PASSAGE_M`] reaches
/// at `resolution` m per cell: half the passage in whole cells, at least one.
pub(crate) fn passage_depth(resolution: f64) -> u32 {
    let r = crate::grid::cell_size_m(resolution);
    3 * (libm::round(MIN_PASSAGE_M / (2.0 * r)).max(1.0) as u32)
}

/// Unlabels the stretches along which two labels touch that no passage crosses: per pair of
/// labels, the 8-connected parts of the cells of either beside the other (4-neighbours) whose
/// deepest cell in `depth` (the free depth of the map, specks looked past) is shallower than
/// `min_depth`. Stretches are told apart by their pair: a hole in a wall beside the place
/// where two segments of the room behind it meet is no passage for being next to theirs.
pub(crate) fn seal_narrow_contacts(labels: &mut Grid<u16>, depth: &[u32], min_depth: u32) {
    let (w, h) = (labels.width(), labels.height());
    if depth.len() != w * h || w == 0 || h == 0 {
        return;
    }
    // Every (pair, cell) of a cell beside another label, sorted by pair.
    let cells = labels.cells();
    let mut beside: Vec<((u16, u16), usize)> = Vec::new();
    for (i, &l) in cells.iter().enumerate() {
        if l == 0 {
            continue;
        }
        for j in neighbours4(i, w, h) {
            let m = cells[j];
            if m != 0 && m != l {
                beside.push(((l.min(m), l.max(m)), i));
            }
        }
    }
    beside.sort_unstable();
    beside.dedup();
    // `mark[i]` is 1 + the index of the pair whose cells are being parted while cell i is one
    // of them not yet in a stretch, and 0 once it is: no clearing between pairs.
    let mut mark = vec![0usize; w * h];
    let (mut flood, mut part, mut sealed) = (Flood::default(), Vec::new(), Vec::new());
    for (k, run) in beside.chunk_by(|a, b| a.0 == b.0).enumerate() {
        let stamp = k + 1;
        for &(_, i) in run {
            mark[i] = stamp;
        }
        for &(_, first) in run {
            if mark[first] != stamp {
                continue;
            }
            part.clear();
            let mut enter = |j: usize| mark[j] == stamp && std::mem::replace(&mut mark[j], 0) == stamp;
            flood.fill(w, h, [first], Neighbours::Eight, &mut enter, |i| part.push(i));
            if part.iter().all(|&i| depth[i] < min_depth) {
                sealed.extend_from_slice(&part);
            }
        }
    }
    let out = labels.cells_mut();
    for i in sealed {
        out[i] = 0;
    }
}

#[cfg(test)]
mod tests {
    use super::super::segments::free_depth;
    use super::*;
    use crate::grid::Cell;

    /// Two rooms, 2 m x 2 m at 5 cm, parted by a wall three cells thick (columns 40..43) with
    /// holes at `holes` (rows), labelled 1 left of column 42 and 2 from it on, as a wavefront
    /// through the holes leaves them.
    fn parted(holes: &[std::ops::Range<usize>]) -> (Grid<u16>, Vec<u32>) {
        let (w, h) = (83, 40);
        let mut map = Grid::new(w, h, Cell::Free);
        for y in 0..h {
            for x in 40..43 {
                if !holes.iter().any(|r| r.contains(&y)) {
                    *map.at_mut(x, y) = Cell::Occupied;
                }
            }
        }
        let labels = Grid::from_vec(
            w,
            h,
            (0..w * h)
                .map(|i| match (map.cells()[i], i % w) {
                    (Cell::Occupied, _) => 0,
                    (_, x) if x < 42 => 1,
                    _ => 2,
                })
                .collect(),
        )
        .unwrap();
        (labels, free_depth(&map))
    }

    fn touching_pairs(labels: &Grid<u16>) -> usize {
        let (w, h) = (labels.width(), labels.height());
        let c = labels.cells();
        (0..w * h).filter(|&i| c[i] != 0 && neighbours4(i, w, h).any(|j| c[j] != 0 && c[j] != c[i])).count()
    }

    #[test]
    fn holes_in_a_wall_part_the_rooms_and_a_door_joins_them() {
        let min = passage_depth(0.05);
        assert_eq!(min, 15, "half of 0.5 m in 5 cm cells, 3 chamfer units each");
        // A glass pane: every other row of the wall seen through, 20 rows of it.
        let glass: Vec<_> = (10..30).step_by(2).map(|y| y..y + 1).collect();
        let (mut labels, depth) = parted(&glass);
        assert!(touching_pairs(&labels) >= 20, "the labels meet in ten holes");
        seal_narrow_contacts(&mut labels, &depth, min);
        assert_eq!(touching_pairs(&labels), 0);
        // The rooms keep their cells beside the wall: only the cells in the holes go.
        assert_eq!(*labels.at(39, 10), 1);
        assert_eq!(*labels.at(43, 10), 2);
        // A door 0.8 m wide (16 rows) is a passage: every contact across it stays, its cells
        // beside the jambs (shallow) included.
        let (mut labels, depth) = parted(std::slice::from_ref(&(12..28)));
        let before = touching_pairs(&labels);
        assert_eq!(before, 32);
        seal_narrow_contacts(&mut labels, &depth, min);
        assert_eq!(touching_pairs(&labels), before);
        // A slit 0.4 m wide (8 rows) is not.
        let (mut labels, depth) = parted(std::slice::from_ref(&(12..20)));
        seal_narrow_contacts(&mut labels, &depth, min);
        assert_eq!(touching_pairs(&labels), 0);
    }

    #[test]
    fn a_hole_where_two_segments_meet_behind_the_wall_is_no_passage() {
        // The room right of the wall in two segments (2 above row 20, 3 from it on), their
        // boundary a deep stretch that meets the hole at row 20.
        let glass: Vec<_> = (10..30).step_by(2).map(|y| y..y + 1).collect();
        let (mut labels, depth) = parted(&glass);
        for y in 20..40 {
            for x in 42..83 {
                if *labels.at(x, y) == 2 {
                    *labels.at_mut(x, y) = 3;
                }
            }
        }
        seal_narrow_contacts(&mut labels, &depth, passage_depth(0.05));
        let (w, h) = (labels.width(), labels.height());
        let c = labels.cells();
        let left_touches = (0..w * h).filter(|&i| c[i] == 1 && neighbours4(i, w, h).any(|j| c[j] > 1)).count();
        assert_eq!(left_touches, 0);
        // The two segments still meet along their boundary.
        assert_eq!((*labels.at(60, 19), *labels.at(60, 20)), (2, 3));
    }

    #[test]
    fn the_passage_is_half_a_metre_at_any_resolution() {
        // Half of 0.5 m in whole cells: 5 at 5 cm, 3 at 10 cm (2.5 rounded up), 10 at 2.5 cm.
        let depths: Vec<u32> = [0.05, 0.1, 0.025].iter().map(|&r| passage_depth(r) / 3).collect();
        assert_eq!(depths, [5, 3, 10]);
        // The whole passage: 10, 5 and 20 cells.
        let cells: Vec<usize> = [0.05, 0.1, 0.025].iter().map(|&r| passage_cells(r)).collect();
        assert_eq!(cells, [10, 5, 20]);
    }
}
