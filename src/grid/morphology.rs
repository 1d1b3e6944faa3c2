//! Square dilation and erosion of a grid of flags, separable: a window of `2r + 1` cells along
//! each row, then along each column, with running counts, so that each costs two passes over
//! the grid whatever the radius. The column pass slides a row of counts down the grid rather
//! than walking each column, so both passes read memory in order.
//!
//! The generator grows the cells a robot saw around free space; the frontier stage opens
//! unknown space (an erosion, then a dilation) so that the streaks rays leave between them at
//! long range are not unseen space. Both use these.

use super::Grid;

/// Square dilation: true where any cell within Chebyshev distance `r` is true (cells off the
/// grid are false).
///
/// ```
/// use ksmcmc::grid::{morphology::dilate, Grid};
/// let mut g = Grid::new(5, 5, false);
/// *g.at_mut(2, 2) = true;
/// let d = dilate(&g, 1);
/// assert!(*d.at(1, 1) && *d.at(3, 3) && !*d.at(0, 0));
/// ```
pub fn dilate(g: &Grid<bool>, r: usize) -> Grid<bool> {
    let (w, h) = (g.width(), g.height());
    // Along each row, a running count of the true cells in the window [x - r, x + r].
    let mut mid = vec![false; w * h];
    for (src, out) in g.cells().chunks_exact(w.max(1)).zip(mid.chunks_exact_mut(w.max(1))) {
        let mut count: u32 = src[..r.min(w)].iter().map(|&v| u32::from(v)).sum();
        for x in 0..w {
            if let Some(&v) = src.get(x + r) {
                count += u32::from(v);
            }
            out[x] = count > 0;
            if x >= r {
                count -= u32::from(src[x - r]);
            }
        }
    }
    // Then down the columns, a whole row at a time (the rows stay contiguous in memory): per
    // column the count of rows [y - r, y + r] whose row pass was true.
    let row = |y: usize| &mid[y * w..(y + 1) * w];
    let mut counts = vec![0u32; w];
    // Adds `step` per true cell of a row: 1, or u32::MAX (wrapping) to take one away.
    let add = |counts: &mut [u32], cells: &[bool], sign: u32| {
        for (c, &v) in counts.iter_mut().zip(cells) {
            *c = c.wrapping_add(sign.wrapping_mul(u32::from(v)));
        }
    };
    for y in 0..r.min(h) {
        add(&mut counts, row(y), 1);
    }
    let mut out = vec![false; w * h];
    for y in 0..h {
        if y + r < h {
            add(&mut counts, row(y + r), 1);
        }
        for (o, &c) in out[y * w..(y + 1) * w].iter_mut().zip(&counts) {
            *o = c > 0;
        }
        if y >= r {
            add(&mut counts, row(y - r), u32::MAX);
        }
    }
    Grid::from_vec(w, h, out).expect("same size")
}

/// Square erosion: true where every cell within Chebyshev distance `r` is true (cells off the
/// grid count as true: what runs off the map's edge is not cut by it). The complement of the
/// dilation of the complement.
pub fn erode(g: &Grid<bool>, r: usize) -> Grid<bool> {
    let not = |g: &Grid<bool>| Grid::from_vec(g.width(), g.height(), g.cells().iter().map(|&v| !v).collect());
    not(&dilate(&not(g).expect("same size"), r)).expect("same size")
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mcmc::Rng;

    /// Whether `f` holds of the cells of `g` within distance `r` of `(x, y)`, off-grid cells
    /// being `off`.
    fn square(g: &Grid<bool>, x: usize, y: usize, r: usize, off: bool, all: bool) -> bool {
        let (w, h) = (g.width() as isize, g.height() as isize);
        let r = r as isize;
        let mut cells =
            (y as isize - r..=y as isize + r).flat_map(|yy| (x as isize - r..=x as isize + r).map(move |xx| (xx, yy)));
        let value = |(xx, yy): (isize, isize)| {
            if xx < 0 || yy < 0 || xx >= w || yy >= h {
                off
            } else {
                *g.at(xx as usize, yy as usize)
            }
        };
        if all {
            cells.all(value)
        } else {
            cells.any(value)
        }
    }

    #[test]
    fn dilate_and_erode_match_brute_force() {
        let mut rng = Rng::seed(3);
        let (w, h) = (23, 17);
        for p in [0.05, 0.8] {
            let cells: Vec<bool> = (0..w * h).map(|_| rng.chance(p)).collect();
            let g = Grid::from_vec(w, h, cells).unwrap();
            for r in [0, 1, 3, 8, 20] {
                let (d, e) = (dilate(&g, r), erode(&g, r));
                for y in 0..h {
                    for x in 0..w {
                        assert_eq!(*d.at(x, y), square(&g, x, y, r, false, false), "dilate r {r} at ({x},{y})");
                        assert_eq!(*e.at(x, y), square(&g, x, y, r, true, true), "erode r {r} at ({x},{y})");
                    }
                }
            }
        }
    }
}
