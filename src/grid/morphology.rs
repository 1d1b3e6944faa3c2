//! Square dilation and erosion of a grid of flags, separable: a window of `2r + 1` cells along
//! each row, then along each column, with prefix counts, so that each costs two passes over
//! the grid whatever the radius.
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
    let pass = |src: &[bool], n: usize, stride: usize, out: &mut [bool]| {
        // Prefix counts along one line, then a window of 2r + 1.
        let mut prefix = vec![0u32; n + 1];
        for i in 0..n {
            prefix[i + 1] = prefix[i] + u32::from(src[i * stride]);
        }
        for i in 0..n {
            let (a, b) = (i.saturating_sub(r), (i + r + 1).min(n));
            out[i * stride] = prefix[b] > prefix[a];
        }
    };
    let mut mid = vec![false; w * h];
    for y in 0..h {
        pass(&g.cells()[y * w..], w, 1, &mut mid[y * w..]);
    }
    let mut out = vec![false; w * h];
    for x in 0..w {
        pass(&mid[x..], h, w, &mut out[x..]);
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
            for r in [0, 1, 3] {
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
