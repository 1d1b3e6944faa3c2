//! Goal-driven exploration: the robot weighs the plan's placeholders for what it looks for
//! (issue 35; CogX report, annex 2.5).
//!
//! After each update [`GoalGuide`] finds the rooms of the chain's best world, with their
//! placeholders ([`crate::floorplan::frontier`]), and hands the robot one target per
//! placeholder, worth the probability that it leads to what the goal asks for
//! ([`Goal::value`]); the robot drives to the one with the most value per metre
//! ([`crate::explore::Explorer::set_targets`]). The same guide can watch without steering, so
//! that the nearest-frontier policy is judged by the same rule.
//!
//! Found, on a map nobody knows the truth of, is what the plan says: the first update whose
//! plan holds more rooms of the goal's type (any type for a new room) than the plan of the
//! robot's first map.

use super::online::Guide;
use super::{Chain, ChainError};
use crate::explore::{Explorer, Target};
use crate::floorplan::frontier::Goal;
use crate::floorplan::rooms::RoomConfig;
use crate::floorplan::world::World;

/// Steers the robot to the placeholders most likely to reach its goal, or watches for it.
#[derive(Debug, Clone)]
pub struct GoalGuide {
    goal: Goal,
    steer: bool,
    rooms: RoomConfig,
    first: Option<usize>,
    found_at_m: Option<f64>,
    updates: usize,
}

impl GoalGuide {
    /// A guide that steers the robot to `goal` (`steer`) or only watches for it while the
    /// robot follows the nearest frontier, finding rooms with `rooms`.
    pub fn new(goal: Goal, steer: bool, rooms: RoomConfig) -> GoalGuide {
        GoalGuide { goal, steer, rooms, first: None, found_at_m: None, updates: 0 }
    }

    /// The goal.
    pub fn goal(&self) -> Goal {
        self.goal
    }

    /// Metres the robot had driven at the first plan that held what it looks for.
    pub fn found_at_m(&self) -> Option<f64> {
        self.found_at_m
    }

    /// Plans looked at so far (one per update, and the first).
    pub fn plans(&self) -> usize {
        self.updates
    }

    /// Rooms of `world` that count for the goal.
    fn count(&self, world: &World) -> usize {
        world.rooms.iter().filter(|r| self.goal.wants(r.kind)).count()
    }
}

impl Guide for GoalGuide {
    fn targets(&mut self, chain: &mut Chain, explorer: &Explorer) -> Result<Vec<Target>, ChainError> {
        let (world, _) = chain.best_world_with_rooms(&self.rooms)?;
        self.updates += 1;
        let n = self.count(&world);
        match self.first {
            None => self.first = Some(n),
            Some(first) if n > first && self.found_at_m.is_none() => self.found_at_m = Some(explorer.travelled_m()),
            Some(_) => {}
        }
        Ok(if self.steer { self.goal.targets(&world.placeholders) } else { Vec::new() })
    }

    fn found(&mut self, _explorer: &Explorer) -> bool {
        self.found_at_m.is_some()
    }
}
