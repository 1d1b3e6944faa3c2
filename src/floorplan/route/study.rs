//! How close routes come to the shortest path: the stretch of routes over many pairs of cells.
//!
//! A route through the room graph is planned on the cells of the rooms it passes only, so it
//! can be longer than the shortest path over all free cells: when the room graph picks a
//! sequence of rooms that is not the one the shortest path takes (it compares passages by
//! their middles, see [`super::portals`]), or when the shortest path slips between two rooms
//! the room layer does not join. The *stretch* of a route is its length over the shortest
//! path's; [`stretch`] measures it over pairs of free cells in different rooms.

use super::{Planned, RouteError, RoutePlanner};
use crate::grid::Cell;
use crate::mcmc::Rng;

/// The stretch of routes over many pairs of cells.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct Stretch {
    /// Pairs routed (pairs that free cells join).
    pub pairs: usize,
    /// Mean of route length over shortest path length.
    pub mean: f64,
    /// Largest ratio.
    pub max: f64,
    /// The pair with the largest ratio, `[[x, y], [x, y]]`.
    pub worst: [[u32; 2]; 2],
    /// Routes the room graph had none for (planned on cells, [`Planned::Cells`]).
    pub on_cells: usize,
    /// Pairs drawn that no free path joins (not routed; each gave [`RouteError::Unreachable`]).
    pub unreachable: usize,
}

/// The stretch of routes between `pairs` pairs of free cells in different rooms, drawn with
/// `seed` from the cells the planner's labels give a room. Fewer pairs are measured if the
/// labels hold fewer than two rooms.
///
/// ```
/// use ksmcmc::floorplan::route::{study::stretch, RoutePlanner};
/// use ksmcmc::floorplan::rooms::{Grouping, RoomConfig, RoomLayer, RoomMaps};
/// use ksmcmc::floorplan::{knowledge::KnowledgeConfig, synth};
/// let s = synth::generate(&synth::SynthConfig { width: 160, height: 120, ..Default::default() }, 3).unwrap();
/// let mut world = s.truth.clone();
/// let m = s.map.classified();
/// let layer = RoomLayer::new(RoomConfig::default(), &KnowledgeConfig::default()).unwrap();
/// let maps = RoomMaps { map: m, world_map: m, resolution: 0.05 };
/// let labels = layer.explain(&mut world, maps, Grouping::Units(&Default::default())).unwrap();
/// let mut planner = RoutePlanner::new(m.clone(), labels, &world, 0.05).unwrap();
/// let st = stretch(&mut planner, 20, 1);
/// assert_eq!(st.pairs + st.unreachable, 20);
/// assert!(st.max >= st.mean && st.mean >= 1.0 - 1e-9);
/// ```
pub fn stretch(planner: &mut RoutePlanner, pairs: usize, seed: u64) -> Stretch {
    let labels = planner.labels().clone();
    let (w, _) = planner.size();
    // Free cells of rooms: a room's label also covers the furniture inside it.
    let free = |i: usize| planner.map().cells()[i] == Cell::Free;
    let cells: Vec<usize> = (0..labels.len()).filter(|&i| labels.cells()[i] != 0 && free(i)).collect();
    let mut out = Stretch { pairs: 0, mean: 0.0, max: 0.0, worst: [[0; 2]; 2], on_cells: 0, unreachable: 0 };
    let first = cells.first().map(|&i| labels.cells()[i]);
    if cells.is_empty() || cells.iter().all(|&i| Some(labels.cells()[i]) == first) {
        return out;
    }
    let mut rng = Rng::seed(seed);
    let xy = |i: usize| ((i % w) as i64, (i / w) as i64);
    let mut sum = 0.0;
    for _ in 0..pairs {
        let (a, b) = loop {
            let (a, b) = (cells[rng.index(cells.len())], cells[rng.index(cells.len())]);
            if labels.cells()[a] != labels.cells()[b] {
                break (a, b);
            }
        };
        let route = match planner.route(xy(a), xy(b)) {
            Ok(r) => r,
            Err(RouteError::Unreachable { .. }) => {
                out.unreachable += 1;
                continue;
            }
            Err(_) => continue, // cannot happen: both ends are free cells of the map
        };
        let best = planner.shortest(a, b).map_or(f64::NAN, |p| length(&p, w));
        let ratio = route.length_m / (best * planner.resolution);
        out.pairs += 1;
        out.on_cells += (route.planned == Planned::Cells) as usize;
        sum += ratio;
        if ratio > out.max {
            out.max = ratio;
            out.worst = [[(a % w) as u32, (a / w) as u32], [(b % w) as u32, (b / w) as u32]];
        }
    }
    out.mean = if out.pairs > 0 { sum / out.pairs as f64 } else { 0.0 };
    out
}

/// A path's length in cells (steps of 1 and sqrt 2).
pub fn length(path: &[usize], w: usize) -> f64 {
    path.windows(2)
        .map(|p| if p[0] % w != p[1] % w && p[0] / w != p[1] / w { std::f64::consts::SQRT_2 } else { 1.0 })
        .sum()
}
