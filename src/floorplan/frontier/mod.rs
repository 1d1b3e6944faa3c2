//! Beyond the frontier: placeholders, and the rooms they are likely to lead to.
//!
//! A map holds gaps, and a robot plans by reasoning about them. The CogX report on gaps in
//! spatial knowledge (annexes 2.1, 2.3 and 2.5) puts *placeholders* on the boundary between
//! free and unknown space, and gives for each the probability that it leads to a new room and
//! of which category, so that a planner can choose which to explore. This module does the same
//! for a plan: [`placeholders`] finds the frontiers of the map (free cells beside unknown ones,
//! in stretches no wider than a space's side), describes each in metres (its width, the room
//! it opens from, a door beside it, how much unseen floor lies behind it and whether seen walls
//! close that floor in), and asks the frontier rules (`samples/knowledge/frontier-learned.mln`,
//! [`FrontierRules`]) what lies beyond: `P(NewRoom)` and the probability of each type.
//!
//! Its stages are private modules:
//!
//! * `stretches`: the frontier cells, grouped and cut into stretches, and what lies behind each;
//! * `rules`: the Markov logic network, the evidence it is given and what it answers;
//! * `goal`: what a placeholder is worth to a robot looking for a new room or a type of space
//!   ([`Goal`]), for goal-driven exploration;
//! * `truth`: what truly lies behind a placeholder of a generated floor seen in part, for
//!   learning the rules' weights and scoring them (`ksmcmc evaluate --only frontier`).
//!
//! The room layer calls [`placeholders`] last ([`crate::floorplan::rooms::RoomLayer::explain`]),
//! so every plan (the command line, the wasm plan, the wings, the edits) has them in
//! `world.json`. It imports the world, the grid, the Markov logic engine and the explorer's
//! [`crate::explore::Target`], nothing of the room layer or the chain.

mod goal;
mod rules;
mod stretches;
mod truth;

pub use goal::{Goal, UnknownGoal};
pub use rules::{evidence, FrontierRules, BUILTIN_FRONTIER_RULES, FRONTIER_EVIDENCE, FRONTIER_QUERY, FRONTIER_RULES};
pub use stretches::{Stretch, AT_DOOR_M, BEHIND_M, JAMB_M, MAX_STRETCH_M, MIN_BEHIND_M2, MIN_UNSEEN_M, MIN_WIDTH_M};
pub use truth::{
    frontier_truth, seen_shares, unentered_doors, Beyond, FrontierCase, NEW_ROOM_SEEN, TRUTH_M, TRUTH_MIN_M2,
};

use crate::floorplan::world::{Placeholder, TypeProbabilities, World};
use crate::grid::{Cell, Grid};
use crate::mln::MlnError;

/// The placeholders of a plan: `world` (with its rooms) explains `map` (classified, in its own
/// frame) at `resolution` metres per cell, `labels` numbers each free map cell with its room.
/// They are ordered by their cell, row by row, and numbered from 1. Fails only if the rules
/// cannot be grounded or inferred.
///
/// ```
/// use ksmcmc::floorplan::frontier::{placeholders, FrontierRules};
/// use ksmcmc::floorplan::World;
/// use ksmcmc::grid::{Cell, Grid};
///
/// // A 6 m x 3 m room seen on its left half only, at 0.05 m a cell, walls all round: the right
/// // half is unknown, and the frontier between them is one placeholder 3 m wide.
/// let mut map = Grid::new(120, 60, Cell::Unknown);
/// for y in 0..60 {
///     for x in 0..120 {
///         let wall = x == 0 || y == 0 || x == 119 || y == 59;
///         *map.at_mut(x, y) = if wall { Cell::Occupied } else if x < 60 { Cell::Free } else { Cell::Unknown };
///     }
/// }
/// let labels = Grid::new(120, 60, 0u16);
/// let found = placeholders(&World::empty(120, 60), &map, &labels, 0.05, &FrontierRules::builtin())?;
/// assert_eq!(found.len(), 1);
/// assert!((found[0].width_m - 2.9).abs() < 0.1, "{}", found[0].width_m);
/// assert!((0.0..=1.0).contains(&found[0].p_new_room));
/// # Ok::<(), ksmcmc::mln::MlnError>(())
/// ```
pub fn placeholders(
    world: &World,
    map: &Grid<Cell>,
    labels: &Grid<u16>,
    resolution: f64,
    rules: &FrontierRules,
) -> Result<Vec<Placeholder>, MlnError> {
    let found = stretches::stretches(world, map, labels, resolution);
    let answers = rules.weigh(world, &found)?;
    Ok(found.iter().zip(answers).enumerate().map(|(i, (s, (p, types)))| placeholder(i, s, p, types)).collect())
}

/// The placeholder of stretch `s`, the `i`-th, with `P(NewRoom)` `p` and the type
/// probabilities `types`, rounded (widths to the centimetre, probabilities to 0.001).
fn placeholder(i: usize, s: &Stretch, p: f64, types: [f64; 4]) -> Placeholder {
    let r = |v: f64, k: f64| libm::round(v * k) / k;
    let [room, corridor, hall, other] = types.map(|t| r(t, 1000.0));
    Placeholder {
        id: i as u32 + 1,
        x: s.at.0 as i32,
        y: s.at.1 as i32,
        width_m: r(s.width_m, 100.0),
        room: s.room,
        p_new_room: r(p, 1000.0),
        types: TypeProbabilities { room, corridor, hall, other },
    }
}
