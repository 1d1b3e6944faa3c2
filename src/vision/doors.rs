//! The door detector of Fig. 3.18, for one pair of facing units.
//!
//! 1. Expand the facing walls towards each other: the band between them (found by
//!    [`crate::floorplan::state::facing`]).
//! 2. Localise the part of the walls where the two units overlap: the band's span.
//! 3. Divide it into one-cell segments and verify each: a segment is open when no cell across
//!    the band is occupied and at least half are free (the `t'` test of eq. 3.25).
//! 4. Combine verified segments into runs; runs of door width become door candidates, weighted
//!    by the share of free cells in their rectangle (eq. 3.23).

use crate::floorplan::state::{door_rect, Axis, DoorSpec, State};
use crate::floorplan::world::Rect;

/// Door candidates between `lo` and `hi` over the shared span `start..=end`, with weights.
#[allow(clippy::too_many_arguments)]
pub fn detect(
    s: &State,
    lo: Rect,
    hi: Rect,
    lo_id: u32,
    hi_id: u32,
    axis: Axis,
    start: i32,
    end: i32,
) -> Vec<(DoorSpec, f64)> {
    let limits = s.door_limits;
    let w = s.wall;
    let segment = |t: i32| -> Rect {
        match axis {
            Axis::Horizontal => Rect::new(lo.right() - w, t, hi.x - lo.right() + 2 * w, 1),
            Axis::Vertical => Rect::new(t, lo.bottom() - w, 1, hi.y - lo.bottom() + 2 * w),
        }
    };
    let open = |t: i32| {
        let r = segment(t);
        s.occupied_in(r) == 0 && 2 * s.free_in(r) as i64 >= r.area()
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
        let d = DoorSpec { lo: lo_id, hi: hi_id, axis, start: run_start, end: t - 1 };
        if let Some(r) = door_rect(lo, hi, &d, &limits, w) {
            out.push((d, s.free_in(r) as f64 / r.area() as f64));
        }
    }
    out
}
