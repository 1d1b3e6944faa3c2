//! What truly lies behind the placeholders of a generated floor seen in part: the training
//! and test cases of the frontier rules.
//!
//! A generated floor ([`crate::floorplan::synth`]) comes with its truth: per map cell the truth
//! unit whose interior it lies in, and each unit's type. A robot that has explored part of it
//! ([`crate::explore`]) leaves a partial map, which a chain explains and whose placeholders
//! are found as on any map. Behind each, a wavefront runs through the cells the robot has not
//! seen that are not walls in truth, up to [`TRUTH_M`]; the truth unit holding most of what it
//! reaches (at least [`TRUTH_MIN_M2`] of it) is what the placeholder leads to, and that unit is
//! a *new* room if less than half of its floor is seen. Where no unit holds that much, the
//! placeholder leads nowhere (the outside, or a pocket).

use super::rules::{place, FrontierRules, FRONTIER_QUERY};
use super::stretches::{door_centre, stretches, Stretch, Waves, AT_DOOR_M};
use crate::floorplan::world::{UnitType, World};
use crate::grid::{Cell, Grid};
use crate::mln::{Database, Evidence, MlnError};

/// How far behind a placeholder the truth is read, m: 2 m, a step through a doorway and into
/// the space beyond it.
pub const TRUTH_M: f64 = 2.0;
/// Least floor of one truth unit behind a placeholder for it to lead there, m²: 1 m².
pub const TRUTH_MIN_M2: f64 = 1.0;
/// A truth unit with less than this share of its floor seen is a new room.
pub const NEW_ROOM_SEEN: f64 = 0.5;

/// What truly lies behind a placeholder.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Beyond {
    /// No space of the building (the outside, or a pocket no unit holds).
    Nothing,
    /// A unit of the given type, new (mostly unseen) or already in the map.
    Space {
        /// The unit's type.
        kind: UnitType,
        /// Whether less than half of its floor is seen.
        new: bool,
    },
}

impl Beyond {
    /// Whether a room not yet in the map lies beyond.
    pub fn is_new(self) -> bool {
        matches!(self, Beyond::Space { new: true, .. })
    }

    /// The index of the kind of space beyond in the order room, corridor, hall, other; `None`
    /// for nothing (and for an untyped unit).
    pub fn kind_index(self) -> Option<usize> {
        match self {
            Beyond::Nothing => None,
            Beyond::Space { kind, .. } => {
                [UnitType::Room, UnitType::Corridor, UnitType::Hall, UnitType::Other].iter().position(|&k| k == kind)
            }
        }
    }
}

/// A placeholder's stretch with what truly lies behind it.
#[derive(Debug, Clone, PartialEq)]
pub struct FrontierCase {
    /// The stretch, as [`super::placeholders`] finds it.
    pub stretch: Stretch,
    /// What lies behind it.
    pub beyond: Beyond,
}

/// The cases of a partial map: `world` (with rooms, labels `labels`) explains `partial`, the
/// part of a generated floor a robot has seen; `truth_map` is the whole floor's classified map,
/// `truth_labels` its truth unit per cell (index + 1 into `truth.units`), both in the same
/// frame as `partial`.
pub fn frontier_truth(
    world: &World,
    partial: &Grid<Cell>,
    labels: &Grid<u16>,
    resolution: f64,
    truth: &World,
    truth_map: &Grid<Cell>,
    truth_labels: &Grid<u16>,
) -> Vec<FrontierCase> {
    let (w, h) = (partial.width(), partial.height());
    let (seen, total) = seen_cells(partial, truth_labels, truth.units.len());
    let limit = libm::ceil(TRUTH_M / resolution) as u32;
    let least = (TRUTH_MIN_M2 / (resolution * resolution)) as usize;
    let open = |j: usize| partial.cells()[j] == Cell::Unknown && truth_map.cells()[j] != Cell::Occupied;
    let found = stretches(world, partial, labels, resolution);
    let mut waves = Waves::new(w, h);
    found
        .into_iter()
        .map(|stretch| {
            let mut counts = std::collections::BTreeMap::<u16, usize>::new();
            for (j, d) in waves.behind(&stretch.cells, limit, open) {
                let l = truth_labels.cells()[j];
                if d <= limit && l > 0 && usize::from(l) <= truth.units.len() {
                    *counts.entry(l).or_default() += 1;
                }
            }
            let best = counts.into_iter().max_by(|a, b| a.1.cmp(&b.1).then(b.0.cmp(&a.0)));
            let beyond = match best {
                Some((l, n)) if n >= least.max(1) => {
                    let l = usize::from(l);
                    let new = (seen[l] as f64) < NEW_ROOM_SEEN * total[l] as f64;
                    Beyond::Space { kind: truth.units[l - 1].kind, new }
                }
                _ => Beyond::Nothing,
            };
            FrontierCase { stretch, beyond }
        })
        .collect()
}

impl FrontierRules {
    /// A training database of the rules: the evidence of `cases`' stretches on `world` and
    /// the truth of every query atom.
    pub fn training_database(&self, world: &World, cases: &[FrontierCase]) -> Result<Database, MlnError> {
        let mut db = Database::new();
        let found: Vec<Stretch> = cases.iter().map(|c| c.stretch.clone()).collect();
        self.insert_evidence(&mut db, world, &found)?;
        for (i, c) in cases.iter().enumerate() {
            let p = place(i);
            let kind = c.beyond.kind_index().map_or(4, |k| k);
            for (q, pred) in FRONTIER_QUERY.iter().enumerate() {
                let yes = if q == 0 { c.beyond.is_new() } else { q - 1 == kind };
                db.insert(self.mln(), pred, &[&p], if yes { Evidence::True } else { Evidence::False })?;
            }
        }
        Ok(db)
    }
}

/// The map centres of the truth doors into units the robot never entered (less than a tenth
/// of their floor seen) from units it has explored (at least half seen), in front of which it
/// has seen free floor within [`AT_DOOR_M`] (a door leaf's width) of the door's centre: where a
/// placeholder should stand. A unit half seen may have the door in its other half, and a door
/// the robot never came near opens onto no explored space. `resolution`: metres a cell.
pub fn unentered_doors(
    truth: &World,
    partial: &Grid<Cell>,
    truth_labels: &Grid<u16>,
    resolution: f64,
) -> Vec<(f64, f64)> {
    let (seen, total) = seen_cells(partial, truth_labels, truth.units.len());
    let share = |id: u32| {
        let l = truth.units.iter().position(|u| u.id == id).map_or(0, |k| k + 1);
        if l == 0 || total[l] == 0 {
            return None;
        }
        Some(seen[l] as f64 / total[l] as f64)
    };
    let reach = AT_DOOR_M / crate::grid::cell_size_m(resolution);
    truth
        .doors
        .iter()
        .filter(|d| {
            let [a, b] = d.units.map(share);
            let (a, b) = (a.unwrap_or(0.0), b.unwrap_or(0.0));
            (a < 0.1 && b >= 0.5) || (b < 0.1 && a >= 0.5)
        })
        .map(|d| door_centre(truth, d))
        .filter(|&centre| free_within(partial, centre, reach))
        .collect()
}

/// Whether a free cell of `map` has its centre within `reach` cells of `(cx, cy)` (map
/// coordinates).
fn free_within(map: &Grid<Cell>, (cx, cy): (f64, f64), reach: f64) -> bool {
    let r = libm::ceil(reach) as i64 + 1;
    let (x0, y0) = (libm::floor(cx) as i64, libm::floor(cy) as i64);
    (y0 - r..=y0 + r).any(|y| {
        (x0 - r..=x0 + r).any(|x| {
            map.get(x, y) == Some(&Cell::Free) && libm::hypot(x as f64 + 0.5 - cx, y as f64 + 0.5 - cy) <= reach
        })
    })
}

/// Per truth label `0..=units` (a larger label counts as `units`), the cells of
/// `truth_labels` that carry it, and of those the cells `partial` has seen free:
/// `(seen, total)`.
/// Per truth unit (by label: index + 1; 0 is no unit), the share of its floor that `partial`
/// shows free: how much of it a robot has seen.
pub fn seen_shares(partial: &Grid<Cell>, truth_labels: &Grid<u16>, units: usize) -> Vec<f64> {
    let (seen, total) = seen_cells(partial, truth_labels, units);
    seen.iter().zip(&total).map(|(&s, &t)| if t == 0 { 0.0 } else { s as f64 / t as f64 }).collect()
}

fn seen_cells(partial: &Grid<Cell>, truth_labels: &Grid<u16>, units: usize) -> (Vec<usize>, Vec<usize>) {
    let (mut seen, mut total) = (vec![0usize; units + 1], vec![0usize; units + 1]);
    for (&l, &c) in truth_labels.cells().iter().zip(partial.cells()) {
        let l = usize::from(l).min(units);
        total[l] += 1;
        seen[l] += usize::from(c == Cell::Free);
    }
    (seen, total)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_door_is_onto_explored_space_only_where_floor_was_seen_before_it() {
        // Unknown space with free floor seen at (10, 10) only; 5 cm cells, so 1 m is 20 cells.
        let mut map = Grid::new(80, 40, Cell::Unknown);
        *map.at_mut(10, 10) = Cell::Free;
        assert!(free_within(&map, (10.5, 29.0), 20.0), "18.5 cells away");
        assert!(!free_within(&map, (10.5, 31.0), 20.0), "20.5 cells away");
        assert!(!free_within(&map, (40.0, 10.5), 20.0));
        *map.at_mut(10, 10) = Cell::Occupied;
        assert!(!free_within(&map, (10.5, 10.5), 20.0), "a wall is no floor");
    }
}
