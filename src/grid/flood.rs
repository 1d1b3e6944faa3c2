//! Flood fills and wavefronts over a row-major grid of cells, by cell index (`y * width + x`).
//!
//! The detectors and metrics find connected regions in several places: free space no unit
//! explains, walls joined into one network, the unexplored outside of a building. They differ in
//! which cells may be entered and what is collected, not in how the region grows, so the growing
//! lives here once: [`Flood::fill`] pops cells off a stack, hands each to `visit`, and pushes each
//! neighbour that `enter` admits. `enter` is asked once per neighbour and must mark what it
//! admits (so that no cell is pushed twice); the stack is kept between fills, so a caller that
//! fills again and again allocates it once. [`wavefront`] grows a region breadth first instead,
//! for the distances of its cells from where it started.
//!
//! ```
//! use ksmcmc::grid::flood::{Flood, Neighbours};
//!
//! // Two regions of ones in a 4x2 grid; the fill from cell 0 finds the left one.
//! let cells = [1, 1, 0, 1, 0, 1, 0, 1];
//! let mut seen = [false; 8];
//! let mut region = Vec::new();
//! let mut enter = |j: usize| cells[j] == 1 && !std::mem::replace(&mut seen[j], true);
//! Flood::default().fill(4, 2, [0], Neighbours::Four, &mut enter, |i| region.push(i));
//! region.sort();
//! assert_eq!(region, [0, 1, 5]);
//! ```

/// Which cells are neighbours.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Neighbours {
    /// Left, right, up, down.
    Four,
    /// The eight cells around, diagonals included.
    Eight,
}

/// A flood fill's working memory: a stack of cell indices (`u32`: maps have at most 2^25
/// cells, see `grid::Limits`).
#[derive(Debug, Clone, Default)]
pub struct Flood {
    stack: Vec<u32>,
}

impl Flood {
    /// Fills a `width` x `height` grid from `seeds` (each pushed if `enter` admits it): visits
    /// every cell reachable through cells `enter` admits, in no particular order.
    pub fn fill(
        &mut self,
        width: usize,
        height: usize,
        seeds: impl IntoIterator<Item = usize>,
        neighbours: Neighbours,
        mut enter: impl FnMut(usize) -> bool,
        mut visit: impl FnMut(usize),
    ) {
        let stack = &mut self.stack;
        stack.clear();
        for s in seeds {
            if enter(s) {
                stack.push(s as u32);
            }
        }
        while let Some(i) = stack.pop() {
            let i = i as usize;
            visit(i);
            let (x, y) = (i % width, i / width);
            match neighbours {
                Neighbours::Four => {
                    if x > 0 && enter(i - 1) {
                        stack.push(i as u32 - 1);
                    }
                    if x + 1 < width && enter(i + 1) {
                        stack.push(i as u32 + 1);
                    }
                    if y > 0 && enter(i - width) {
                        stack.push((i - width) as u32);
                    }
                    if y + 1 < height && enter(i + width) {
                        stack.push((i + width) as u32);
                    }
                }
                Neighbours::Eight => {
                    for ny in y.saturating_sub(1)..(y + 2).min(height) {
                        for nx in x.saturating_sub(1)..(x + 2).min(width) {
                            let j = ny * width + nx;
                            if j != i && enter(j) {
                                stack.push(j as u32);
                            }
                        }
                    }
                }
            }
        }
    }
}

/// The neighbours of cell `i` (by index) of a `width` x `height` grid that lie inside it: left,
/// right, up, down.
///
/// ```
/// use ksmcmc::grid::flood::neighbours4;
/// // Cell 0 of a 3x2 grid (its top-left corner) has a right and a lower neighbour.
/// assert_eq!(neighbours4(0, 3, 2).collect::<Vec<_>>(), [1, 3]);
/// assert_eq!(neighbours4(4, 3, 2).collect::<Vec<_>>(), [3, 5, 1]);
/// ```
pub fn neighbours4(i: usize, width: usize, height: usize) -> impl Iterator<Item = usize> {
    steps4(i, width, height).into_iter().filter(|s| s.0).map(|s| s.1)
}

/// The four neighbours of cell `i` of a `width` x `height` grid, left, right, up, down, each
/// with whether it lies inside the grid (the index of one outside is meaningless).
fn steps4(i: usize, width: usize, height: usize) -> [(bool, usize); 4] {
    let (x, y) = (i % width, i / width);
    [(x > 0, i.wrapping_sub(1)), (x + 1 < width, i + 1), (y > 0, i.wrapping_sub(width)), (y + 1 < height, i + width)]
}

/// A breadth-first wavefront (4-neighbour steps): from the cells in `seeds`, whose `dist` the
/// caller has set, into every neighbour `enter` admits whose `dist` is still `u32::MAX`, which
/// gets its neighbour's distance + 1. Cells at distance `limit` + 1 are reached but not grown
/// from; cells never reached keep `u32::MAX`.
///
/// ```
/// use ksmcmc::grid::flood::wavefront;
///
/// // A 5x1 corridor, from its left end, up to 2 steps (the third cell out is reached, at 3).
/// let mut dist = [0, u32::MAX, u32::MAX, u32::MAX, u32::MAX];
/// wavefront(5, 1, &mut dist, [0], |_| true, 2);
/// assert_eq!(dist, [0, 1, 2, 3, u32::MAX]);
/// ```
pub fn wavefront(
    width: usize,
    height: usize,
    dist: &mut [u32],
    seeds: impl IntoIterator<Item = usize>,
    enter: impl Fn(usize) -> bool,
    limit: u32,
) {
    let mut reached: Vec<usize> = seeds.into_iter().collect();
    wavefront_listed(width, height, dist, &mut reached, enter, limit);
}

/// [`wavefront`] that lists the cells it reaches: `reached` holds the seeds (their `dist`
/// set) and gets every cell reached after them, in the order reached; it is the queue too,
/// seeds grown from whatever their distance, the others if within `limit`. A caller that runs
/// many small wavefronts on one map-sized `dist` puts back only the cells listed
/// (`frontier::stretches::Waves`), not the whole grid.
///
/// ```
/// use ksmcmc::grid::flood::wavefront_listed;
///
/// let mut dist = [0, u32::MAX, u32::MAX, u32::MAX, u32::MAX];
/// let mut reached = vec![0];
/// wavefront_listed(5, 1, &mut dist, &mut reached, |_| true, 2);
/// assert_eq!((reached, dist), (vec![0, 1, 2, 3], [0, 1, 2, 3, u32::MAX]));
/// ```
pub fn wavefront_listed(
    width: usize,
    height: usize,
    dist: &mut [u32],
    reached: &mut Vec<usize>,
    enter: impl Fn(usize) -> bool,
    limit: u32,
) {
    let seeds = reached.len();
    let mut head = 0;
    while let Some(&i) = reached.get(head) {
        head += 1;
        let d = dist[i];
        if head > seeds && d > limit {
            continue;
        }
        for (inside, j) in steps4(i, width, height) {
            if inside && dist[j] == u32::MAX && enter(j) {
                dist[j] = d + 1;
                reached.push(j);
            }
        }
    }
}

/// A breadth-first wavefront that carries labels (4-neighbour steps): every cell in `queue`
/// holds its label in `labels` (not `L::default()`, which stands for none). A neighbour with no
/// label yet that `enter(neighbour, label)` admits takes the label of the cell it is reached
/// from; cells reached first keep their label, so each cell gets the label of a nearest seed
/// (ties to the seed queued first). Cells farther than `reach` steps from every seed stay
/// unlabelled; `u32::MAX` sets no limit (and needs no distances).
///
/// ```
/// use ksmcmc::grid::flood::labelled_wavefront;
///
/// // A 7x1 corridor with a label at each end: they meet in the middle; with a reach of one
/// // step, only the cells beside the ends are labelled.
/// let mut labels = [1u16, 0, 0, 0, 0, 0, 2];
/// labelled_wavefront(7, 1, &mut labels, [0, 6].into(), |_, _| true, u32::MAX);
/// assert_eq!(labels, [1, 1, 1, 1, 2, 2, 2]);
/// let mut labels = [1u16, 0, 0, 0, 0, 0, 2];
/// labelled_wavefront(7, 1, &mut labels, [0, 6].into(), |_, _| true, 1);
/// assert_eq!(labels, [1, 1, 0, 0, 0, 2, 2]);
/// ```
pub fn labelled_wavefront<L: Copy + Default + PartialEq>(
    width: usize,
    height: usize,
    labels: &mut [L],
    mut queue: std::collections::VecDeque<u32>,
    enter: impl Fn(usize, L) -> bool,
    reach: u32,
) {
    let mut dist = if reach == u32::MAX { Vec::new() } else { vec![0u32; width * height] };
    while let Some(i) = queue.pop_front() {
        let i = i as usize;
        let d = dist.get(i).copied().unwrap_or(0);
        if d >= reach {
            continue;
        }
        let l = labels[i];
        let neighbours = steps4(i, width, height);
        for (inside, j) in neighbours {
            if inside && labels[j] == L::default() && enter(j, l) {
                labels[j] = l;
                if let Some(dj) = dist.get_mut(j) {
                    *dj = d + 1;
                }
                queue.push_back(j as u32);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn eight_neighbours_cross_diagonals_four_do_not() {
        // A diagonal line of ones in a 3x3 grid.
        let cells = [1, 0, 0, 0, 1, 0, 0, 0, 1];
        let region = |n: Neighbours| {
            let mut seen = [false; 9];
            let mut found = Vec::new();
            let enter = |j: usize| cells[j] == 1 && !std::mem::replace(&mut seen[j], true);
            Flood::default().fill(3, 3, [0], n, enter, |i| found.push(i));
            found.sort();
            found
        };
        assert_eq!(region(Neighbours::Four), [0]);
        assert_eq!(region(Neighbours::Eight), [0, 4, 8]);
    }

    #[test]
    fn several_seeds_and_no_cell_twice() {
        let cells = [1u8; 12];
        let mut seen = [false; 12];
        let mut visits = 0;
        let enter = |j: usize| cells[j] == 1 && !std::mem::replace(&mut seen[j], true);
        Flood::default().fill(4, 3, [0, 11, 0], Neighbours::Four, enter, |_| visits += 1);
        assert_eq!(visits, 12);
    }
}
