//! Door topology: which room opens onto which, scored against a drawn ground truth.
//!
//! A robot plans with the room graph, not with cells: a segmentation whose segments match the
//! truth cell for cell can still link the wrong rooms (a segment that leaks through a doorway
//! into the room behind it) or miss links (two rooms merged into one segment have no door
//! between them). Segmentation precision and recall do not see either, so the links are scored
//! on their own.
//!
//! * **Truth links.** The room-segmentation benchmark's truth images (Bormann et al. 2016)
//!   close every doorway with a drawn line. Two truth rooms are linked where such a line lies
//!   on cells that are free in the map: each 8-connected group of line cells that are free in
//!   the map links every pair of truth rooms it touches (4-neighbours).
//! * **Predicted links.** Each predicted segment stands for the truth room it overlaps most.
//!   Two truth rooms are linked when segments standing for them touch through free cells
//!   along a passable stretch: at least [`MIN_CONTACT_CELLS`] pairs of 4-neighbours with the
//!   two labels. A scanned wall is often dotted with one-cell holes, and the labels of the two
//!   rooms behind it meet there; no robot passes such a hole, and neither does the truth,
//!   which draws that wall solid.
//!
//! Only segments of [`MIN_SEGMENT_CELLS`] or more count on either side, as in the
//! segmentation score. Link precision is the share of predicted links that are true links,
//! recall the share of true links predicted.

use super::metrics::MIN_SEGMENT_CELLS;
use crate::grid::flood::{neighbours4, Flood, Neighbours};
use crate::grid::Grid;
use std::collections::{BTreeMap, BTreeSet};

/// Fewest neighbouring cell pairs along which two segments must touch to be linked: half a
/// metre at the benchmark's 5 cm cells, the narrowest passage a robot takes for a door.
pub const MIN_CONTACT_CELLS: usize = 10;

/// A link between two rooms, the smaller id first.
pub type Link = (u32, u32);

/// Door-topology quality: how well the predicted room graph matches the truth's.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct LinkScore {
    /// Share of predicted links that are true links (1 when nothing is predicted).
    pub precision: f64,
    /// Share of true links that are predicted (1 when the truth has none).
    pub recall: f64,
    /// Number of predicted links.
    pub predicted: usize,
    /// Number of true links.
    pub truth: usize,
}

fn ordered(a: u32, b: u32) -> Link {
    (a.min(b), a.max(b))
}

/// Cells of each label, indexed by label.
fn sizes(labels: &Grid<u32>) -> BTreeMap<u32, usize> {
    let mut n = BTreeMap::new();
    for &l in labels.cells().iter().filter(|&&l| l != 0) {
        *n.entry(l).or_default() += 1;
    }
    n
}

/// The truth's links: `truth` holds the truth rooms (0 on walls and drawn lines), `free` the
/// cells that are free in the map.
pub fn truth_links(truth: &Grid<u32>, free: &Grid<bool>) -> BTreeSet<Link> {
    let (w, h) = (truth.width(), truth.height());
    let big: BTreeSet<u32> =
        sizes(truth).into_iter().filter(|&(_, n)| n >= MIN_SEGMENT_CELLS).map(|(l, _)| l).collect();
    let line = |i: usize| truth.cells()[i] == 0 && free.cells()[i];
    let mut seen = vec![false; w * h];
    let mut links = BTreeSet::new();
    let mut flood = Flood::default();
    for start in 0..w * h {
        if seen[start] || !line(start) {
            continue;
        }
        // The line's 8-connected part, and the big truth rooms beside its cells (4-neighbours).
        let mut touched = BTreeSet::new();
        let mut enter = |j: usize| !seen[j] && line(j) && !std::mem::replace(&mut seen[j], true);
        flood.fill(w, h, [start], Neighbours::Eight, &mut enter, |i| {
            touched.extend(neighbours4(i, w, h).map(|j| truth.cells()[j]).filter(|l| big.contains(l)));
        });
        let touched: Vec<u32> = touched.into_iter().collect();
        for (k, &a) in touched.iter().enumerate() {
            for &b in &touched[k + 1..] {
                links.insert(ordered(a, b));
            }
        }
    }
    links
}

/// The truth room each predicted segment overlaps most (segments of at least
/// [`MIN_SEGMENT_CELLS`] on both sides).
pub fn best_truth(predicted: &Grid<u32>, truth: &Grid<u32>) -> BTreeMap<u32, u32> {
    let (ps, ts) = (sizes(predicted), sizes(truth));
    let mut overlap: BTreeMap<(u32, u32), usize> = BTreeMap::new();
    for (&p, &t) in predicted.cells().iter().zip(truth.cells()) {
        if p != 0 && t != 0 && ps[&p] >= MIN_SEGMENT_CELLS && ts[&t] >= MIN_SEGMENT_CELLS {
            *overlap.entry((p, t)).or_default() += 1;
        }
    }
    let mut best: BTreeMap<u32, (usize, u32)> = BTreeMap::new();
    for (&(p, t), &n) in &overlap {
        let b = best.entry(p).or_insert((0, t));
        if n > b.0 {
            *b = (n, t);
        }
    }
    best.into_iter().map(|(p, (_, t))| (p, t)).collect()
}

/// How many pairs of 4-neighbours carry each pair of different non-zero labels.
pub fn contacts(labels: &Grid<u32>) -> BTreeMap<Link, usize> {
    let (w, h) = (labels.width(), labels.height());
    let c = labels.cells();
    let mut pairs: BTreeMap<Link, usize> = BTreeMap::new();
    for y in 0..h {
        for x in 0..w {
            let a = c[y * w + x];
            if a == 0 {
                continue;
            }
            for (nx, ny) in [(x + 1, y), (x, y + 1)] {
                if nx < w && ny < h {
                    let b = c[ny * w + nx];
                    if b != 0 && b != a {
                        *pairs.entry(ordered(a, b)).or_default() += 1;
                    }
                }
            }
        }
    }
    pairs
}

/// Pairs of labels that touch along at least `min_contact` pairs of 4-neighbours.
pub fn touching(labels: &Grid<u32>, min_contact: usize) -> BTreeSet<Link> {
    contacts(labels).into_iter().filter(|&(_, n)| n >= min_contact).map(|(l, _)| l).collect()
}

/// The predicted links between truth rooms: segments standing for different truth rooms
/// ([`best_truth`]) that touch, along at least [`MIN_CONTACT_CELLS`] counted over all the
/// segments standing for the two rooms.
pub fn predicted_links(predicted: &Grid<u32>, truth: &Grid<u32>) -> BTreeSet<Link> {
    predicted_links_along(predicted, truth, MIN_CONTACT_CELLS)
}

/// [`predicted_links`] touching along at least `min_contact` pairs of 4-neighbours: half a
/// metre at another map's resolution.
pub fn predicted_links_along(predicted: &Grid<u32>, truth: &Grid<u32>, min_contact: usize) -> BTreeSet<Link> {
    let stand_for = best_truth(predicted, truth);
    let mut by_room: BTreeMap<Link, usize> = BTreeMap::new();
    for ((a, b), n) in contacts(predicted) {
        if let (Some(&ta), Some(&tb)) = (stand_for.get(&a), stand_for.get(&b)) {
            if ta != tb {
                *by_room.entry(ordered(ta, tb)).or_default() += n;
            }
        }
    }
    by_room.into_iter().filter(|&(_, n)| n >= min_contact).map(|(l, _)| l).collect()
}

/// Scores the predicted segmentation's links against the truth's (see the module docs).
///
/// ```
/// use ksmcmc::floorplan::topology::score_links;
/// use ksmcmc::grid::Grid;
/// // Two 12x12 truth rooms side by side, a drawn line between them (column 12) with a
/// // doorway: the line is free in the map at rows 4..8.
/// let truth = Grid::from_vec(25, 12, (0..300).map(|i| match i % 25 { 12 => 0, x if x < 12 => 1, _ => 2 }).collect()).unwrap();
/// let free = Grid::from_vec(25, 12, (0..300).map(|i| i % 25 != 12 || (4..8).contains(&(i / 25))).collect()).unwrap();
/// // A prediction that splits the floor at the same place links the two rooms: its segments
/// // touch along all 12 rows.
/// let split = Grid::from_vec(25, 12, (0..300).map(|i| if i % 25 <= 12 { 1 } else { 2 }).collect()).unwrap();
/// let s = score_links(&split, &truth, &free);
/// assert_eq!((s.precision, s.recall, s.truth), (1.0, 1.0, 1));
/// // One segment over both rooms links nothing.
/// let one = Grid::new(25, 12, 5u32);
/// assert_eq!(score_links(&one, &truth, &free).recall, 0.0);
/// ```
pub fn score_links(predicted: &Grid<u32>, truth: &Grid<u32>, free: &Grid<bool>) -> LinkScore {
    let t = truth_links(truth, free);
    let p = predicted_links(predicted, truth);
    let hits = p.intersection(&t).count();
    LinkScore {
        precision: if p.is_empty() { 1.0 } else { hits as f64 / p.len() as f64 },
        recall: if t.is_empty() { 1.0 } else { hits as f64 / t.len() as f64 },
        predicted: p.len(),
        truth: t.len(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Three truth rooms in a row, 20x20 each, separated by drawn lines at columns 20 and 41.
    /// The map has a doorway (free cells) in the first line only.
    fn three_rooms() -> (Grid<u32>, Grid<bool>) {
        let (w, h) = (62, 20);
        let truth = Grid::from_vec(
            w,
            h,
            (0..w * h)
                .map(|i| match i % w {
                    20 | 41 => 0,
                    x if x < 20 => 1,
                    x if x < 41 => 2,
                    _ => 3,
                })
                .collect(),
        )
        .unwrap();
        let free = Grid::from_vec(
            w,
            h,
            (0..w * h).map(|i| !matches!(i % w, 20 | 41) || (i % w == 20 && (4..16).contains(&(i / w)))).collect(),
        )
        .unwrap();
        (truth, free)
    }

    #[test]
    fn truth_links_follow_doorways_not_walls() {
        let (truth, free) = three_rooms();
        assert_eq!(truth_links(&truth, &free), BTreeSet::from([(1, 2)]));
        // A second doorway in the other line links rooms 2 and 3 too.
        let mut free2 = free.clone();
        *free2.at_mut(41, 3) = true;
        assert_eq!(truth_links(&truth, &free2), BTreeSet::from([(1, 2), (2, 3)]));
    }

    #[test]
    fn predicted_links_map_segments_to_truth_rooms() {
        let (truth, free) = three_rooms();
        // Room 1 split in two segments (both stand for room 1: no link between them), rooms 2
        // and 3 one segment each, and the split segments touch segment 20 (room 2).
        let pred = truth.map(|&t| match t {
            1 => 10,
            2 => 20,
            3 => 30,
            _ => 0,
        });
        let mut pred = pred;
        for y in 0..10 {
            for x in 0..20 {
                *pred.at_mut(x, y) = 11;
            }
        }
        // Fill the doorway so 10/11 touch 20 through free cells.
        for y in 4..16 {
            *pred.at_mut(20, y) = if y < 10 { 11 } else { 10 };
        }
        let s = score_links(&pred, &truth, &free);
        assert_eq!((s.predicted, s.truth, s.precision, s.recall), (1, 1, 1.0, 1.0));
        // Filling the wall line with a segment that joins 20 and 30 predicts a false link.
        for y in 0..20 {
            *pred.at_mut(41, y) = 20;
        }
        let s = score_links(&pred, &truth, &free);
        assert_eq!((s.predicted, s.precision, s.recall), (2, 0.5, 1.0));
    }

    #[test]
    fn merged_rooms_lose_their_link() {
        let (truth, free) = three_rooms();
        let pred = truth.map(|&t| if t == 0 { 0 } else { 1 });
        let s = score_links(&pred, &truth, &free);
        assert_eq!((s.predicted, s.recall, s.precision), (0, 0.0, 1.0));
    }
}
