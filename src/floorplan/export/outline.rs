//! Outlines of cell regions: the polygons (with holes) that bound a set of grid cells, such as
//! the union of a room's unit rectangles, for the vector exports ([`super::shapes`]).
//!
//! A room is one or more axis-aligned rectangles, and a polygon library would union them with
//! floating-point clipping. Rectangles on integer coordinates have an exact union instead: put
//! every rectangle edge on a grid line of a *compressed* grid (cell `(i, j)` spans
//! `xs[i]..xs[i + 1]` by `ys[j]..ys[j + 1]`), mark the cells inside, and walk the boundary
//! between marked and unmarked cells. The same walk outlines any cell mask (a room read off
//! the label image), with a uniform grid.
//!
//! The walk keeps the marked region on its left as seen on the screen (x right, y down), so
//! that exteriors run counter-clockwise on the screen and holes clockwise; flipping y (to
//! metres or longitude/latitude, y up) makes exteriors counter-clockwise, as RFC 7946 asks.
//! Two marked cells that touch only at a corner are separate (4-connected regions): the walk
//! turns towards the cell it follows there, and a boundary that comes back to a vertex is cut
//! into two rings at it. So every ring is simple, vertices are corners only (no collinear
//! ones), and rings meet at most at single points, as OGC simple features require.
//!
//! ```
//! use ksmcmc::floorplan::outline::union_of_rects;
//!
//! // An L of two rectangles sharing an edge: one ring of six corners.
//! let l = union_of_rects(&[[0, 0, 4, 2], [0, 2, 2, 4]]);
//! assert_eq!(l.len(), 1);
//! assert_eq!(l[0].exterior, vec![(0, 0), (0, 4), (2, 4), (2, 2), (4, 2), (4, 0)]);
//! assert!(l[0].holes.is_empty());
//! ```

use std::collections::HashMap;

/// A point on the grid lines.
pub type Point = (i64, i64);

/// A polygon: its exterior ring and its holes, each ring listed once around (the first vertex
/// is not repeated at the end).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Polygon {
    /// Counter-clockwise on the screen (x right, y down).
    pub exterior: Vec<Point>,
    /// Clockwise on the screen, each inside the exterior.
    pub holes: Vec<Vec<Point>>,
}

/// The union of rectangles `[x0, y0, x1, y1]` (`x0..x1` by `y0..y1`; empty ones are skipped):
/// its polygons, in the order their top-left corners come row by row.
pub fn union_of_rects(rects: &[[i64; 4]]) -> Vec<Polygon> {
    let rects: Vec<[i64; 4]> = rects.iter().copied().filter(|r| r[0] < r[2] && r[1] < r[3]).collect();
    let xs = edges(rects.iter().flat_map(|r| [r[0], r[2]]));
    let ys = edges(rects.iter().flat_map(|r| [r[1], r[3]]));
    trace_grid(&xs, &ys, |c| rects.iter().any(|r| covers(r, &c)))
}

/// Sorted distinct coordinates.
pub fn edges(values: impl Iterator<Item = i64>) -> Vec<i64> {
    let mut v: Vec<i64> = values.collect();
    crate::sort::sort(&mut v);
    v.dedup();
    v
}

/// Whether rectangle `r` covers cell `c` of a grid whose lines include `r`'s edges.
pub fn covers(r: &[i64; 4], c: &[i64; 4]) -> bool {
    r[0] <= c[0] && c[2] <= r[2] && r[1] <= c[1] && c[3] <= r[3]
}

/// The polygons bounding the cells of the grid with lines `xs` and `ys` (increasing) for which
/// `filled([x0, y0, x1, y1])` holds, in grid coordinates.
pub fn trace_grid(xs: &[i64], ys: &[i64], filled: impl Fn([i64; 4]) -> bool) -> Vec<Polygon> {
    let (nx, ny) = (xs.len().saturating_sub(1), ys.len().saturating_sub(1));
    let cell = |i: usize, j: usize| filled([xs[i], ys[j], xs[i + 1], ys[j + 1]]);
    trace(nx, ny, cell).into_iter().map(|p| map_polygon(&p, xs, ys)).collect()
}

fn map_polygon(p: &Polygon, xs: &[i64], ys: &[i64]) -> Polygon {
    let ring = |r: &Vec<Point>| r.iter().map(|&(i, j)| (xs[i as usize], ys[j as usize])).collect();
    Polygon { exterior: ring(&p.exterior), holes: p.holes.iter().map(ring).collect() }
}

/// The marked cell deepest inside the region of [`trace_grid`]'s grid: the largest chessboard
/// distance, counted in grid cells, to an unmarked cell or the grid's edge (1 for a cell on the
/// boundary); ties go to the larger cell, then to the one nearest the middle of those left (the first
/// row by row of equals). A place for a label.
pub fn deepest(xs: &[i64], ys: &[i64], filled: impl Fn([i64; 4]) -> bool) -> Option<([i64; 4], u32)> {
    let (nx, ny) = (xs.len().saturating_sub(1), ys.len().saturating_sub(1));
    let rect = |i: usize, j: usize| [xs[i], ys[j], xs[i + 1], ys[j + 1]];
    // Depths saturate at 65535 cells: two bytes a cell, as deep as any label needs.
    let mut d: Vec<u16> = (0..nx * ny).map(|k| if filled(rect(k % nx, k / nx)) { u16::MAX } else { 0 }).collect();
    let at = |d: &[u16], i: i64, j: i64| {
        if i < 0 || j < 0 || i >= nx as i64 || j >= ny as i64 {
            0
        } else {
            d[j as usize * nx + i as usize]
        }
    };
    for pass in [1i64, -1] {
        for k in 0..nx * ny {
            let k = if pass == 1 { k } else { nx * ny - 1 - k };
            let (i, j) = ((k % nx) as i64, (k / nx) as i64);
            if d[k] == 0 {
                continue;
            }
            let back = [(-1, 0), (-1, -1), (0, -1), (1, -1)].map(|(di, dj)| at(&d, i + pass * di, j + pass * dj));
            d[k] = d[k].min(back.iter().min().copied().unwrap_or(0).saturating_add(1));
        }
    }
    let area = |r: [i64; 4]| (r[2] - r[0]) * (r[3] - r[1]);
    let key = |k: usize| (d[k], area(rect(k % nx, k / nx)));
    let top = (0..d.len()).filter(|&k| d[k] > 0).map(key).max()?;
    let tied: Vec<[i64; 4]> = (0..d.len()).filter(|&k| key(k) == top).map(|k| rect(k % nx, k / nx)).collect();
    // The one nearest the middle of the tied cells (first of equals).
    let centre = |r: &[i64; 4]| ((r[0] + r[2]) as f64 / 2.0, (r[1] + r[3]) as f64 / 2.0);
    let n = tied.len() as f64;
    let (mx, my) = tied.iter().map(centre).fold((0.0, 0.0), |a, c| (a.0 + c.0 / n, a.1 + c.1 / n));
    let dist = |r: &[i64; 4]| {
        let (x, y) = centre(r);
        (x - mx) * (x - mx) + (y - my) * (y - my)
    };
    let best = tied.iter().copied().reduce(|a, b| if dist(&b) < dist(&a) { b } else { a })?;
    Some((best, top.0 as u32))
}

/// Directions: east, south, west, north (screen terms, y down).
const STEP: [(i64, i64); 4] = [(1, 0), (0, 1), (-1, 0), (0, -1)];

/// The turn to the left of heading `d` on the screen.
fn left(d: u8) -> u8 {
    (d + 3) % 4
}

/// The outlines of an `nx` x `ny` mask, with vertices as grid indices `(i, j)`.
pub fn trace(nx: usize, ny: usize, filled: impl Fn(usize, usize) -> bool) -> Vec<Polygon> {
    if nx == 0 || ny == 0 {
        return Vec::new();
    }
    let mut walk = Walk { nx, ny, filled, used: vec![0u8; (nx + 1) * (ny + 1)], rings: Vec::new() };
    for v in 0..walk.used.len() {
        while let Some(d) = walk.unused(v, None) {
            walk.follow(v, d);
        }
    }
    assemble(walk.rings)
}

/// A ring found by the walk: its corners and, for a hole, a cell centre inside the hole
/// (doubled coordinates, so odd and never on a grid line).
struct Ring {
    corners: Vec<Point>,
    area2: i64,
    inside: (i64, i64),
}

struct Walk<F> {
    nx: usize,
    ny: usize,
    filled: F,
    /// Bit `d` of vertex `v`: its outgoing edge in direction `d` has been walked.
    used: Vec<u8>,
    rings: Vec<Ring>,
}

impl<F: Fn(usize, usize) -> bool> Walk<F> {
    fn cell(&self, i: i64, j: i64) -> bool {
        i >= 0 && j >= 0 && (i as usize) < self.nx && (j as usize) < self.ny && (self.filled)(i as usize, j as usize)
    }

    fn xy(&self, v: usize) -> (i64, i64) {
        ((v % (self.nx + 1)) as i64, (v / (self.nx + 1)) as i64)
    }

    /// Bit set of the boundary edges leaving vertex `v`, marked cells on their left.
    fn outgoing(&self, v: usize) -> u8 {
        let (i, j) = self.xy(v);
        let (nw, ne, sw, se) = (self.cell(i - 1, j - 1), self.cell(i, j - 1), self.cell(i - 1, j), self.cell(i, j));
        (ne && !se) as u8 | ((se && !sw) as u8) << 1 | ((sw && !nw) as u8) << 2 | ((nw && !ne) as u8) << 3
    }

    /// An unwalked edge leaving `v`; arriving by heading `from` at a vertex with two (two
    /// marked cells meeting at a corner), the one turning left, along the same cell.
    fn unused(&self, v: usize, from: Option<u8>) -> Option<u8> {
        let free = self.outgoing(v) & !self.used[v];
        if let Some(d) = from.map(left).filter(|&d| free & (1 << d) != 0) {
            return Some(d);
        }
        (0..4).find(|d| free & (1 << d) != 0)
    }

    fn next(&self, v: usize, d: u8) -> usize {
        let (i, j) = self.xy(v);
        let (di, dj) = STEP[d as usize];
        (j + dj) as usize * (self.nx + 1) + (i + di) as usize
    }

    /// Walks from vertex `start` along `d` until every edge that the walk reaches is used,
    /// cutting off a ring each time it comes back to a vertex it passed.
    fn follow(&mut self, start: usize, mut d: u8) {
        let mut path = vec![start];
        let mut dirs: Vec<u8> = Vec::new();
        let mut on_path: HashMap<usize, usize> = HashMap::from([(start, 0)]);
        let mut v = start;
        loop {
            self.used[v] |= 1 << d;
            dirs.push(d);
            let n = self.next(v, d);
            if let Some(&p) = on_path.get(&n) {
                self.emit(&path[p..], &dirs[p..]);
                for w in &path[p + 1..] {
                    on_path.remove(w);
                }
                path.truncate(p + 1);
                dirs.truncate(p);
            } else {
                on_path.insert(n, path.len());
                path.push(n);
            }
            v = n;
            match self.unused(v, Some(d)) {
                Some(nd) => d = nd,
                None => return,
            }
        }
    }

    /// Records the closed walk through `path` (heading `dirs[k]` from `path[k]`), corners only.
    fn emit(&mut self, path: &[usize], dirs: &[u8]) {
        let n = path.len();
        let corners: Vec<usize> = (0..n).filter(|&k| dirs[(k + n - 1) % n] != dirs[k]).collect();
        let pts: Vec<Point> = corners.iter().map(|&k| self.xy(path[k])).collect();
        let area2 = signed_area2(&pts);
        // The cell on the right of the first corner's outgoing edge lies outside the region:
        // for a hole, inside the hole.
        let (i, j) = pts[0];
        let (ci, cj) = match dirs[corners[0]] {
            0 => (i, j),
            1 => (i - 1, j),
            2 => (i - 1, j - 1),
            _ => (i, j - 1),
        };
        self.rings.push(Ring { corners: pts, area2, inside: (2 * ci + 1, 2 * cj + 1) });
    }
}

/// Twice the signed area (shoelace) of a ring; negative for exteriors as traced here (y down).
pub fn signed_area2(ring: &[Point]) -> i64 {
    let n = ring.len();
    (0..n).map(|k| ring[k].0 * ring[(k + 1) % n].1 - ring[(k + 1) % n].0 * ring[k].1).sum()
}

/// Whether `p` (doubled coordinates) lies inside `ring` (plain coordinates), by ray casting;
/// `p` is never on a grid line.
fn contains(ring: &[Point], p: (i64, i64)) -> bool {
    let n = ring.len();
    let mut inside = false;
    for k in 0..n {
        let (a, b) = (ring[k], ring[(k + 1) % n]);
        let (ay, by) = (2 * a.1, 2 * b.1);
        if (ay > p.1) != (by > p.1) {
            // Vertical edges only cross a horizontal ray (horizontal edges never straddle it).
            if 2 * a.0 > p.0 {
                inside = !inside;
            }
        }
    }
    inside
}

/// Exteriors with their holes: each hole goes to the smallest exterior around it.
fn assemble(rings: Vec<Ring>) -> Vec<Polygon> {
    let (exteriors, holes): (Vec<Ring>, Vec<Ring>) = rings.into_iter().partition(|r| r.area2 < 0);
    let mut polygons: Vec<Polygon> =
        exteriors.iter().map(|r| Polygon { exterior: r.corners.clone(), holes: Vec::new() }).collect();
    for h in holes {
        let home = exteriors
            .iter()
            .enumerate()
            .filter(|(_, e)| contains(&e.corners, h.inside))
            .min_by_key(|(_, e)| -e.area2)
            .map(|(k, _)| k);
        // Every hole lies in a marked region; a hole with none around it cannot occur.
        if let Some(k) = home {
            polygons[k].holes.push(h.corners);
        }
    }
    polygons
}

#[cfg(test)]
mod tests {
    use super::*;

    fn area(p: &Polygon) -> i64 {
        -signed_area2(&p.exterior) - p.holes.iter().map(|h| signed_area2(h)).sum::<i64>()
    }

    #[test]
    fn one_rectangle_is_one_ring_of_four_corners() {
        let p = union_of_rects(&[[2, 3, 7, 5]]);
        assert_eq!(p, vec![Polygon { exterior: vec![(2, 3), (2, 5), (7, 5), (7, 3)], holes: vec![] }]);
        assert_eq!(area(&p[0]), 2 * 10);
        assert!(union_of_rects(&[]).is_empty());
        assert!(union_of_rects(&[[3, 3, 3, 9]]).is_empty(), "empty rectangles are skipped");
    }

    #[test]
    fn overlapping_and_edge_sharing_rectangles_merge_exactly() {
        // Two overlapping rectangles and a third sharing an edge: a T of 8 corners.
        let p = union_of_rects(&[[0, 0, 6, 2], [1, 0, 6, 2], [2, 2, 4, 5]]);
        assert_eq!(p.len(), 1);
        assert_eq!(p[0].exterior, vec![(0, 0), (0, 2), (2, 2), (2, 5), (4, 5), (4, 2), (6, 2), (6, 0)]);
        assert_eq!(area(&p[0]), 2 * (12 + 6));
    }

    #[test]
    fn a_frame_of_four_rectangles_has_a_hole() {
        let p = union_of_rects(&[[0, 0, 5, 1], [0, 4, 5, 5], [0, 1, 1, 4], [4, 1, 5, 4]]);
        assert_eq!(p.len(), 1);
        assert_eq!(p[0].exterior, vec![(0, 0), (0, 5), (5, 5), (5, 0)]);
        assert_eq!(p[0].holes, vec![vec![(1, 1), (4, 1), (4, 4), (1, 4)]]);
        assert!(signed_area2(&p[0].holes[0]) > 0, "holes run the other way");
        assert_eq!(area(&p[0]), 2 * (25 - 9));
    }

    #[test]
    fn disjoint_and_corner_touching_rectangles_are_separate_polygons() {
        let p = union_of_rects(&[[0, 0, 2, 2], [2, 2, 4, 4], [10, 0, 11, 1]]);
        assert_eq!(p.len(), 3);
        assert_eq!(p[0].exterior, vec![(0, 0), (0, 2), (2, 2), (2, 0)]);
        assert_eq!(p[1].exterior, vec![(10, 0), (10, 1), (11, 1), (11, 0)]);
        assert_eq!(p[2].exterior, vec![(2, 2), (2, 4), (4, 4), (4, 2)]);
    }

    #[test]
    fn a_hole_touching_the_boundary_at_a_corner_is_cut_at_that_point() {
        // A 3x3 block without its centre and without its bottom-right cell: the centre hole
        // touches the outside at the point (2, 2). The boundary is cut there into a simple
        // exterior and a simple hole sharing that one point.
        let mask = |i: usize, j: usize| !((i, j) == (1, 1) || (i, j) == (2, 2));
        let p = trace(3, 3, mask);
        assert_eq!(p.len(), 1, "{p:?}");
        assert_eq!(p[0].exterior, vec![(0, 0), (0, 3), (2, 3), (2, 2), (3, 2), (3, 0)]);
        assert_eq!(p[0].holes, vec![vec![(2, 2), (1, 2), (1, 1), (2, 1)]]);
        for ring in std::iter::once(&p[0].exterior).chain(&p[0].holes) {
            let distinct: std::collections::BTreeSet<_> = ring.iter().collect();
            assert_eq!(distinct.len(), ring.len(), "a simple ring: {ring:?}");
        }
    }

    #[test]
    fn an_island_in_a_hole_is_its_own_polygon_and_holes_find_their_ring() {
        // A 7x7 block with a 5x5 hole holding a 3x3 island with a 1x1 hole.
        let mask = |i: usize, j: usize| {
            let d = (i as i64 - 3).abs().max((j as i64 - 3).abs());
            d == 3 || d == 1
        };
        let p = trace(7, 7, mask);
        assert_eq!(p.len(), 2, "{p:?}");
        let (outer, island) = (&p[0], &p[1]);
        assert_eq!(outer.exterior, vec![(0, 0), (0, 7), (7, 7), (7, 0)]);
        assert_eq!(outer.holes, vec![vec![(1, 1), (6, 1), (6, 6), (1, 6)]]);
        assert_eq!(island.exterior, vec![(2, 2), (2, 5), (5, 5), (5, 2)]);
        assert_eq!(island.holes, vec![vec![(3, 3), (4, 3), (4, 4), (3, 4)]]);
        assert_eq!(area(outer) + area(island), 2 * (49 - 25 + 9 - 1));
    }

    #[test]
    fn the_deepest_cell_is_the_middle_of_a_blob() {
        let xs: Vec<i64> = (0..=9).collect();
        // A 9x5 block: the middle row's middle cell is 3 cells from the edge.
        assert_eq!(deepest(&xs, &xs[..6], |_| true), Some(([4, 2, 5, 3], 3)));
        // Cells of a compressed grid: the larger one wins a tie in depth.
        assert_eq!(deepest(&[0, 2, 10], &[0, 4], |_| true), Some(([2, 0, 10, 4], 1)));
        assert_eq!(deepest(&xs, &xs, |_| false), None);
    }

    #[test]
    fn traced_area_equals_the_cell_count_on_a_ragged_mask() {
        // A pseudo-random mask: the rings' area is exactly the number of marked cells.
        let mask = |i: usize, j: usize| (i * 7 + j * 13 + (i * j) % 5) % 3 != 0;
        let (nx, ny) = (23, 17);
        let p = trace(nx, ny, mask);
        let cells = (0..nx).flat_map(|i| (0..ny).map(move |j| (i, j))).filter(|&(i, j)| mask(i, j)).count();
        assert_eq!(p.iter().map(area).sum::<i64>(), 2 * cells as i64);
        for q in &p {
            assert!(signed_area2(&q.exterior) < 0);
            assert!(q.holes.iter().all(|h| signed_area2(h) > 0));
        }
    }
}
