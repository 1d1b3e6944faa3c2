//! The door detector of Fig. 3.18, for one pair of facing units.
//!
//! It sees rectangles and the map's cell counts, never the chain's state: the caller turns
//! the runs it finds into doors.
//!
//! 1. Expand the facing walls towards each other: the [`Band`] between them, which the caller
//!    finds from the two units' rectangles.
//! 2. Localise the part of the walls where the two units overlap: the band's span.
//! 3. Divide it into one-cell segments and verify each: a segment is open when no cell across
//!    the band is occupied and at least half are free (the `t'` test of eq. 3.25).
//! 4. Combine verified segments into runs; runs of door width become door candidates, weighted
//!    by the share of free cells in their rectangle (eq. 3.23).

use crate::geometry::{Axis, CellCounts, Rect};

/// The band between two facing units `lo` and `hi` (walls `wall` cells deep), along the rows
/// (or columns) `start..=end` their interiors share.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Band {
    /// The left (or upper) unit's rectangle.
    pub lo: Rect,
    /// The right (or lower) unit's rectangle.
    pub hi: Rect,
    /// Which way a door would cross the walls.
    pub axis: Axis,
    /// Depth of the units' wall rings, cells.
    pub wall: i32,
    /// First shared row (or column).
    pub start: i32,
    /// Last shared row (or column), inclusive.
    pub end: i32,
}

/// Door candidates in `band`: runs `(first, last)` of open segments (rows or columns) that
/// `door` accepts as a door (it gives the door's rectangle, or `None` when the run is too short
/// or too long), each with its weight, the share of free cells in that rectangle.
pub fn detect(counts: &CellCounts, band: &Band, door: impl Fn(i32, i32) -> Option<Rect>) -> Vec<((i32, i32), f64)> {
    let Band { lo, hi, axis, wall: w, start, end } = *band;
    let segment = |t: i32| -> Rect {
        match axis {
            Axis::Horizontal => Rect::new(lo.right() - w, t, hi.x - lo.right() + 2 * w, 1),
            Axis::Vertical => Rect::new(t, lo.bottom() - w, 1, hi.y - lo.bottom() + 2 * w),
        }
    };
    let open = |t: i32| {
        let r = segment(t);
        counts.occupied_in(r) == 0 && 2 * counts.free_in(r) as i64 >= r.area()
    };
    let mut out = Vec::new();
    let mut t = start;
    while t <= end {
        if !open(t) {
            t += 1;
            continue;
        }
        let run_start = t;
        while t <= end && open(t) {
            t += 1;
        }
        if let Some(r) = door(run_start, t - 1) {
            out.push(((run_start, t - 1), counts.free_in(r) as f64 / r.area() as f64));
        }
    }
    out
}
