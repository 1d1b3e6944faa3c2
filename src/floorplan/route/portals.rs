//! Portals: the places where a robot passes from one room to the next.
//!
//! Two rooms of the label image (`labels.pgm`) meet where a cell of one has a 4-neighbour in
//! the other: in a doorway, where the two rooms' labels meet inside the opening, or along an
//! open boundary. Each connected stretch of such contacts between two rooms is a passage;
//! a long one (an open boundary many metres wide) is cut into pieces of at most
//! [`PORTAL_SPAN`] contacts, so that a route through it may cross where it suits, not only in
//! its middle. Each piece is one [`Portal`], crossed at its middle contact.

use crate::grid::Grid;
use std::collections::{BTreeMap, HashMap};

/// Most contacts one portal stands for: 16 cells, 0.8 m at 5 cm cells. A route through a
/// wider passage crosses it within half of this of where a free path would.
pub const PORTAL_SPAN: usize = 16;

/// A crossing between two rooms: a cell of each, 4-neighbours.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Portal {
    /// The two rooms (label values), the smaller first.
    pub rooms: [u16; 2],
    /// The crossing's cell in each room (cell indices), in the order of `rooms`.
    pub cells: [u32; 2],
}

/// The portals between every pair of rooms `linked` accepts, in a fixed order (by room pair,
/// then by where their passages start in scan order).
pub fn portals(labels: &Grid<u16>, linked: &dyn Fn(u16, u16) -> bool) -> Vec<Portal> {
    let mut by_pair: BTreeMap<(u16, u16), Vec<(u32, u32)>> = BTreeMap::new();
    let (w, h) = (labels.width(), labels.height());
    let c = labels.cells();
    for y in 0..h {
        for x in 0..w {
            let i = y * w + x;
            let a = c[i];
            if a == 0 {
                continue;
            }
            for j in [(x + 1 < w).then_some(i + 1), (y + 1 < h).then_some(i + w)].into_iter().flatten() {
                let b = c[j];
                if b != 0 && b != a && linked(a.min(b), a.max(b)) {
                    let pair = if a < b { (i as u32, j as u32) } else { (j as u32, i as u32) };
                    by_pair.entry((a.min(b), a.max(b))).or_default().push(pair);
                }
            }
        }
    }
    let mut out = Vec::new();
    for ((a, b), contacts) in by_pair {
        for passage in passages(&contacts, w) {
            for piece in passage.chunks(PORTAL_SPAN) {
                let (ca, cb) = contacts[piece[piece.len() / 2]];
                out.push(Portal { rooms: [a, b], cells: [ca, cb] });
            }
        }
    }
    out
}

/// The contacts (pairs of cells) grouped into passages: contacts whose cells on either side
/// are 8-neighbours (or the same cell) belong together. Each passage lists contact indices in
/// increasing order; passages come in the order of their first contact.
fn passages(contacts: &[(u32, u32)], w: usize) -> Vec<Vec<usize>> {
    let mut sets = crate::union_find::UnionFind::new(contacts.len());
    for side in 0..2 {
        let cell = |k: usize| if side == 0 { contacts[k].0 } else { contacts[k].1 };
        let mut first: HashMap<u32, usize> = HashMap::new();
        for k in 0..contacts.len() {
            first.entry(cell(k)).or_insert(k);
        }
        for k in 0..contacts.len() {
            let c = cell(k) as i64;
            let (x, w) = (c % w as i64, w as i64);
            for dy in -1..=1i64 {
                for dx in -1..=1i64 {
                    if x + dx < 0 || x + dx >= w {
                        continue;
                    }
                    let n = c + dy * w + dx;
                    if let Some(&other) = u32::try_from(n).ok().and_then(|n| first.get(&n)) {
                        sets.union(k, other);
                    }
                }
            }
        }
    }
    let mut groups: BTreeMap<usize, Vec<usize>> = BTreeMap::new();
    for k in 0..contacts.len() {
        let r = sets.find(k);
        groups.entry(r).or_default().push(k);
    }
    groups.into_values().collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Rooms 1 (left) and 2 (right) of a 10 x 40 grid meet along column 4 | 5; room 3 below
    /// row 30 meets room 1 along a short stretch.
    fn labels() -> Grid<u16> {
        Grid::from_vec(
            10,
            40,
            (0..400)
                .map(|i| match (i % 10, i / 10) {
                    (_, y) if (30..32).contains(&y) => 0,
                    (x, y) if y >= 32 && x < 3 => 3,
                    (_, y) if y >= 32 => 0,
                    (x, _) if x < 5 => 1,
                    _ => 2,
                })
                .collect(),
        )
        .unwrap()
    }

    #[test]
    fn long_passages_are_cut_into_portals() {
        let all = portals(&labels(), &|_, _| true);
        // Rows 0..30 of the 1 | 2 boundary: 30 contacts, two portals of at most 16.
        let p12: Vec<_> = all.iter().filter(|p| p.rooms == [1, 2]).collect();
        assert_eq!(p12.len(), 2, "{all:?}");
        for p in &p12 {
            let (a, b) = (p.cells[0] as usize, p.cells[1] as usize);
            assert_eq!((a % 10, b % 10, a / 10), (4, 5, b / 10));
        }
        // Rooms 1 and 3 do not touch (rows 30 and 31 are no room's).
        assert!(all.iter().all(|p| p.rooms != [1, 3]));
        // Pairs the room graph does not link have no portals.
        assert!(portals(&labels(), &|a, b| (a, b) != (1, 2)).is_empty());
    }

    #[test]
    fn separate_stretches_are_separate_passages() {
        let mut l = labels();
        // A wall across the boundary at rows 10..12 splits it into two passages.
        for y in 10..12 {
            for x in 0..10 {
                *l.at_mut(x, y) = 0;
            }
        }
        let all = portals(&l, &|_, _| true);
        let rows: Vec<usize> = all.iter().map(|p| p.cells[0] as usize / 10).collect();
        assert_eq!(rows.len(), 3, "10 + 18 contacts: one portal, then two: {rows:?}");
        assert!(rows[0] < 10 && rows[1] >= 12 && rows[2] >= 12);
    }
}
