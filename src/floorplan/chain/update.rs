//! Online operation (dissertation § 3.5, Fig. 3.40): the map grows while a robot explores, and
//! the chain follows it from the world it holds instead of starting over.
//!
//! A new snapshot of a growing map differs from the last one in a few places: the cells the
//! sensor saw since. The world found so far still explains everything else, so a warm chain
//! needs far fewer iterations than a cold one to explain the new map (`ksmcmc explore`
//! measures both). [`Chain::update_map`] therefore keeps the units, doors, trace and random
//! state, and redoes only what the changed cells reach:
//!
//! - the per-cell explanation changes only at the changed cells, so the log posterior stays
//!   exact with no recount ([`Explanation::set_map_class`]);
//! - the wall detector rescores only the candidates that hold a changed cell (within its
//!   tolerance) or a wall face that appeared or vanished; the others keep their weights, which
//!   are exactly what a detector run on the whole new map would give them;
//! - the door proposals, found on the old map, are forgotten and found again on first use;
//! - the units whose rectangle holds a changed cell are removed, with the units they share a
//!   door with and the fragments lying mostly inside another unit. They were fitted to space
//!   the map did not know: a corridor seen in three parts becomes three units joined by doors,
//!   and the chain's own moves seldom merge units with doors (MERGE and DELETE rarely win
//!   there), so a warm chain that kept them stayed below a cold one for good;
//! - the free-space detector runs on the new map, unless the removal left the world (almost)
//!   empty: its boxes would then hold the whole floor seen;
//! - the kernel schedule starts its phases again, ADD first, so that the changed space is
//!   explained from the rescored candidates as a cold chain would, while the rooms seen
//!   before stay as they were.
//!
//! The summed-area tables of the map's cell classes and of its object cells are counted again
//! (a linear pass each). The map's rotation and resolution stay those of the first map, so a
//! map that changes its size is refused: start a new chain for it. The wall rings deepen when
//! the robot has seen walls from both sides (`thicken_walls`), unless the configuration sets
//! the wall thickness.

use super::{Chain, ChainError, Explanation};
use crate::geometry::Rect;
use crate::grid::{Cell, Grid, OccupancyMap};
use crate::vision;

/// Below this share of the map's free cells covered by units after the changed units are
/// removed, [`Chain::update_map`] leaves the free-space detector for its next turn. After an
/// update the share is either near nothing (the change reached almost every unit) or well
/// above: 0.000 - 0.05 or 0.43 - 0.92 over the updates of `explore` on `synth --seed 1` and
/// `--seed 4` (explore seed 1).
const EMPTIED_COVERAGE: f64 = 0.1;

/// What [`Chain::update_map`] changed.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct MapUpdate {
    /// World-frame cells whose class changed.
    pub changed_cells: usize,
    /// The smallest world-frame rectangle holding them; `None` when nothing changed.
    pub window: Option<Rect>,
    /// Unit candidates the wall detector dropped because the change reached them.
    pub candidates_dropped: usize,
    /// Unit candidates it scored again on the new map and added.
    pub candidates_added: usize,
}

impl Chain {
    /// Takes a new snapshot of the map (the same size: a map that grew while a robot explored,
    /// or a person's paint stroke) and goes on from the current world, redoing only what the
    /// changed cells reach (see the module docs). The log posteriors of the current and best
    /// worlds are those on the new map from now on; the best world is the better of the two.
    ///
    /// ```
    /// use ksmcmc::floorplan::{synth, Chain, ChainConfig};
    /// use ksmcmc::grid::{Cell, OccupancyMap};
    /// let s = synth::generate(&synth::SynthConfig { width: 160, height: 120, ..Default::default() }, 2)?;
    /// // The robot has seen the left half so far.
    /// let mut seen = s.map.classified().clone();
    /// for y in 0..120 { for x in 80..160 { *seen.at_mut(x, y) = Cell::Unknown; } }
    /// let mut chain = Chain::new(&OccupancyMap::from_classified(seen), ChainConfig::default(), 1)?;
    /// chain.step(3000);
    /// let update = chain.update_map(&s.map)?;
    /// assert!(update.changed_cells > 0 && chain.check_consistency());
    /// chain.step(3000);
    /// assert!(chain.best_prediction_rate() > 0.8);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn update_map(&mut self, map: &OccupancyMap) -> Result<MapUpdate, ChainError> {
        let (w, h) = (self.map.width(), self.map.height());
        if map.width() != w || map.height() != h {
            return Err(ChainError::Map(format!(
                "the new map is {}x{} cells but the chain explains a {w}x{h} map; an update must \
                 keep the map's size (pad a growing map to its final extent, or start a new chain)",
                map.width(),
                map.height()
            )));
        }
        let (world_map, _) = vision::orientation::to_world_frame(map.classified(), self.frame.angle);
        let changed = changed_cells(&self.world_map, &world_map);
        let Some(window) = bounds(&changed, world_map.width()) else {
            self.map = map.classified().clone();
            self.walls = None;
            return Ok(MapUpdate::default());
        };
        let walls_before = self
            .config
            .wall_thickness_m
            .is_none()
            .then(|| vision::walls::ring_depth_seen_from_both_sides(&self.map, self.frame.angle, self.resolution));
        self.map = map.classified().clone();
        self.walls = None;
        self.go_to_best();
        self.state.set_map(&world_map, &changed);
        self.world_map = world_map;
        let thickened = walls_before.is_some_and(|before| self.thicken_walls(before));
        if self.objects.is_some() {
            self.objects = Some(super::object_cells(&self.world_map, self.resolution, &self.config, self.object_gain));
        }
        let (candidates_dropped, candidates_added) = self.redetect(window);
        self.remove_touched(&changed);
        self.proposer.forget_doors();
        // The free-space detector proposes a box for each component of free space no unit
        // covers: the gaps between units. On a world the change left (almost) empty the
        // components are the floor seen, whole, boxes a new chain never meets (its detector
        // starts once ADD has placed units), so the detector waits for its next turn.
        if self.iteration >= self.config.detectors.free_space_start && self.coverage() >= EMPTIED_COVERAGE {
            self.refresh_free_space();
        }
        if thickened {
            let lp = self.full_log_posterior();
            self.log_target = lp * self.posterior.inv_temperature();
            self.keep_as_best(lp);
        } else {
            self.rescore_best();
        }
        // New space needs units: the schedule's phases, ADD first, run again from here.
        self.schedule_origin = self.iteration;
        self.phase_index = 0;
        Ok(MapUpdate { changed_cells: changed.len(), window: Some(window), candidates_dropped, candidates_added })
    }

    /// Explains the map from now on under the sensor table `sensor` (Tab. 3.1), going on from
    /// the current world: the log posteriors of the current and best worlds are rescored under
    /// it, and the best world is the better of the two. An exploring chain takes the
    /// whole-map table once the robot has finished (`online::OnlineConfig::renew`): its
    /// walls are then seen from both sides, and the range-sensor table, which lays a ring
    /// behind a face seen from one side, no longer fits the map.
    ///
    /// ```
    /// use ksmcmc::floorplan::{posterior::SensorModel, synth, Chain, ChainConfig};
    /// let s = synth::generate(&synth::SynthConfig { width: 160, height: 120, ..Default::default() }, 2)?;
    /// let mut chain = Chain::new(&s.map, ChainConfig::online(), 1)?;
    /// chain.step(2000);
    /// chain.set_sensor(SensorModel::default());
    /// assert_eq!(chain.config().posterior.sensor, SensorModel::default());
    /// assert!(chain.check_consistency());
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn set_sensor(&mut self, sensor: super::posterior::SensorModel) {
        self.config.posterior.sensor = sensor;
        self.posterior = super::Posterior::at_resolution(&self.config.posterior, self.resolution);
        self.rescore_best();
    }

    /// Removes the units (with their doors) whose rectangle holds a changed cell: they were
    /// fitted to space the map did not know, and fragments of a room seen in parts merge
    /// badly. The units elsewhere stay, and the schedule's ADD phase explains the changed space
    /// again from the rescored candidates.
    fn remove_touched(&mut self, changed: &[usize]) {
        let w = self.world_map.width();
        let mut mask = Grid::new(w, self.world_map.height(), Cell::Free);
        for &i in changed {
            *mask.at_mut(i % w, i / w) = Cell::Occupied;
        }
        let touched = crate::geometry::AreaCounts::new(&mask, Cell::Occupied);
        let mut ids: Vec<u32> = self.state.units.iter().filter(|u| touched.count(u.rect()) > 0).map(|u| u.id).collect();
        // And their neighbours through doors: fragments of one room seen in parts are joined
        // by doors, and a fragment left behind blocks the whole room's unit.
        let through_doors: Vec<u32> = self
            .state
            .doors
            .iter()
            .filter_map(|d| match (ids.contains(&d.lo), ids.contains(&d.hi)) {
                (true, false) => Some(d.hi),
                (false, true) => Some(d.lo),
                _ => None,
            })
            .collect();
        ids.extend(through_doors);
        // And fragments lying mostly inside another unit: the overlap prior (eq. 3.5) is
        // against them, but a unit with doors is not removed by the chain's own moves.
        let units = &self.state.units;
        ids.extend(
            units
                .iter()
                .filter(|u| {
                    units.iter().any(|o| {
                        o.id != u.id
                            && o.rect().intersection(&u.rect()).is_some_and(|i| 2 * i.area() >= u.rect().area())
                    })
                })
                .map(|u| u.id),
        );
        while let Some(i) = self.state.units.iter().position(|u| ids.contains(&u.id)) {
            self.remove_unit_with_doors(i);
        }
    }

    /// When the walls of the new map, measured as seen from both sides
    /// ([`vision::walls::ring_depth_seen_from_both_sides`]), are thicker than on the last map
    /// (`before`) and than the chain's rings: the rings take the new depth, and the world is
    /// explained again from the detectors' candidates, as a cold chain would, while the chain
    /// keeps its candidates, trace and random state. Returns whether it did.
    ///
    /// Why: a robot's first map shows every wall from one side, a face one cell deep, and the
    /// rings are measured on it. Once the robot has been in the rooms either side of a wall it
    /// has seen both faces and the unseen core between them. Rings kept one cell deep leave
    /// every core and every outer wall's far cells unexplained; grown in place, the rings of
    /// units fitted to faces lie wrong, and the chain's moves seldom undo units with doors. A
    /// person's paint stroke on a whole map does not change how thick its walls look, so the
    /// live mapper's strokes leave the rings alone.
    fn thicken_walls(&mut self, before: i32) -> bool {
        let measured = vision::walls::ring_depth_seen_from_both_sides(&self.map, self.frame.angle, self.resolution);
        if measured <= before || measured <= self.state.wall {
            return false;
        }
        self.clear_world();
        self.state.set_wall(measured);
        self.proposer.set_wall(self.state.wall, self.state.width(), self.state.height());
        // The wall detector's candidates afresh, for rings of the new depth, as a new chain
        // finds them.
        let faces = vision::walls::faces_of(&self.world_map, &self.cells.walls);
        self.proposer.candidates = super::wall_candidates(&self.world_map, &faces, &self.cells, self.state.wall);
        self.faces = Some(faces);
        true
    }

    /// Removes every door and unit of the current world.
    fn clear_world(&mut self) {
        while !self.state.doors.is_empty() {
            self.state.apply(&super::Move::Delete(self.state.doors.len() - 1));
        }
        while !self.state.units.is_empty() {
            self.state.apply(&super::Move::Remove(self.state.units.len() - 1));
        }
    }

    /// Makes the best world the current one (on the map it was found on): the chain goes on
    /// from the best explanation it had, not from wherever its walk was.
    fn go_to_best(&mut self) {
        if self.best.units.is_empty() || self.best_log_posterior <= self.full_log_posterior() {
            return;
        }
        self.clear_world();
        let best = self.best.clone();
        let mut ids = std::collections::HashMap::new();
        for u in &best.units {
            self.state.apply(&super::Move::Add(u.rect()));
            let new = self.state.units.last_mut().expect("just added");
            new.kind = u.kind;
            ids.insert(u.id, new.id);
        }
        for d in &best.doors {
            let (Some(&lo), Some(&hi)) = (ids.get(&d.lo), ids.get(&d.hi)) else { continue };
            let door = super::DoorSpec { lo, hi, ..*d };
            if self.state.is_valid(&super::Move::Allocate(door), 1, usize::MAX) {
                self.state.apply(&super::Move::Allocate(door));
            }
        }
        self.best.units.clone_from(&self.state.units);
        self.best.doors.clone_from(&self.state.doors);
        let lp = self.full_log_posterior();
        self.log_target = lp * self.posterior.inv_temperature();
    }

    /// Rescores the wall detector's candidates that a change inside `window` reaches: those
    /// within the detector's tolerance of it, and those with a wall face that appeared or
    /// vanished on a side or inside. Returns how many were dropped and added.
    fn redetect(&mut self, window: Rect) -> (usize, usize) {
        let Some((old_xs, old_ys)) = self.faces.take() else { return (0, 0) };
        let c = self.cells.walls;
        let faces = vision::walls::faces_of(&self.world_map, &c);
        let (dx, dy) = (symmetric_difference(&old_xs, &faces.0), symmetric_difference(&old_ys, &faces.1));
        let g = c.tolerance.max(0) + 1;
        let near = Rect::new(window.x - g, window.y - g, window.w + 2 * g, window.h + 2 * g);
        let reached = |r: Rect| {
            r.intersection(&near).is_some()
                || dx.iter().any(|&x| x >= r.x && x < r.right())
                || dy.iter().any(|&y| y >= r.y && y < r.bottom())
        };
        let (min_side, wall) = (self.cells.min_side, self.state.wall);
        let found = vision::walls::candidates_where(&self.world_map, &faces, min_side, &c, &reached);
        let items: Vec<(Rect, f64)> =
            found.into_iter().filter(|&(r, _)| crate::floorplan::state::fits_unit(r, min_side, wall)).collect();
        let added = items.len();
        let dropped = self.proposer.candidates.replace_where(reached, items);
        self.faces = Some(faces);
        (dropped, added)
    }

    /// After the map changed: the current world's target, and the best world's log posterior,
    /// on the new map; the current world becomes the best if it now explains more.
    fn rescore_best(&mut self) {
        let lp = self.full_log_posterior();
        self.log_target = lp * self.posterior.inv_temperature();
        let best = self.internal_best_world();
        let units: Vec<Rect> = best.units.iter().map(|u| u.rect()).collect();
        let doors: Vec<Rect> = best.doors.iter().map(|d| d.rect()).collect();
        let explanation = Explanation::recompute(&self.world_map, &units, self.state.wall, &doors);
        self.best_log_posterior =
            self.posterior.log_posterior(&explanation, units.len()) + self.knowledge_term_for(&self.best.units);
        if lp >= self.best_log_posterior || self.best.units.is_empty() {
            self.keep_as_best(lp);
        }
    }
}

/// Row-major indices of the cells where two grids of one size differ.
fn changed_cells(old: &Grid<Cell>, new: &Grid<Cell>) -> Vec<usize> {
    old.cells().iter().zip(new.cells()).enumerate().filter(|(_, (a, b))| a != b).map(|(i, _)| i).collect()
}

/// The smallest rectangle holding the cells at row-major indices `cells` of a grid `width`
/// wide; `None` for no cells.
fn bounds(cells: &[usize], width: usize) -> Option<Rect> {
    let (mut x0, mut y0, mut x1, mut y1) = (usize::MAX, usize::MAX, 0, 0);
    for &i in cells {
        let (x, y) = (i % width, i / width);
        (x0, y0, x1, y1) = (x0.min(x), y0.min(y), x1.max(x), y1.max(y));
    }
    (!cells.is_empty()).then(|| Rect::new(x0 as i32, y0 as i32, (x1 - x0 + 1) as i32, (y1 - y0 + 1) as i32))
}

/// The values in exactly one of two sorted lists.
fn symmetric_difference(a: &[i32], b: &[i32]) -> Vec<i32> {
    let mut out: Vec<i32> = a.iter().filter(|v| b.binary_search(v).is_err()).copied().collect();
    out.extend(b.iter().filter(|v| a.binary_search(v).is_err()));
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Rooms of 30 x 30 cells in a 3 x 3 grid, walls 3 cells thick. `seen[r]` says whether
    /// the robot has been in room `r` (row-major): its floor reads free and its walls' faces
    /// occupied; a wall's core, and every wall face of rooms not seen, read unknown.
    fn rooms_seen(seen: [bool; 9]) -> Grid<Cell> {
        let mut g = Grid::new(110, 110, Cell::Unknown);
        for (r, _) in seen.iter().enumerate().filter(|&(_, &s)| s) {
            let (x0, y0) = (4 + 33 * (r % 3), 4 + 33 * (r / 3));
            for y in y0..y0 + 32 {
                for x in x0..x0 + 32 {
                    let face = x == x0 || y == y0 || x == x0 + 31 || y == y0 + 31;
                    *g.at_mut(x, y) = if face { Cell::Occupied } else { Cell::Free };
                }
            }
        }
        g
    }

    #[test]
    fn rings_deepen_once_the_robot_has_seen_walls_from_both_sides() {
        let first =
            OccupancyMap::from_classified(rooms_seen([false, false, false, false, true, false, false, false, false]));
        let all = OccupancyMap::from_classified(rooms_seen([true; 9]));
        let config = crate::floorplan::ChainConfig::online();
        let mut chain = Chain::new(&first, config.clone(), 1).unwrap();
        assert_eq!(chain.wall_thickness(), 1, "one room: every wall seen from one side");
        chain.step(2000);
        chain.update_map(&all).unwrap();
        assert_eq!(chain.wall_thickness(), 3, "face, unseen core, face");
        assert!(chain.check_consistency());
        chain.step(4000);
        assert!(chain.check_consistency());
        // The world was explained again, with the new rings: the nine rooms by units again.
        let best = chain.best_world();
        assert!(best.units.len() >= 6, "{} units", best.units.len());
        // A configured thickness stays.
        let fixed = crate::floorplan::ChainConfig { wall_thickness_m: Some(first.yaml().resolution), ..config.clone() };
        let mut chain = Chain::new(&first, fixed, 1).unwrap();
        chain.step(500);
        chain.update_map(&all).unwrap();
        assert_eq!(chain.wall_thickness(), 1);
        // A change that leaves the walls' look alone (a paint stroke on the whole map) too.
        let mut chain = Chain::new(&all, config, 1).unwrap();
        let t = chain.wall_thickness();
        chain.step(500);
        let mut stroke = all.classified().clone();
        for x in 10..20 {
            *stroke.at_mut(x, 20) = Cell::Occupied;
        }
        chain.update_map(&OccupancyMap::from_classified(stroke)).unwrap();
        assert_eq!(chain.wall_thickness(), t);
    }

    #[test]
    fn bounds_and_differences() {
        assert_eq!(bounds(&[], 10), None);
        assert_eq!(bounds(&[12, 35, 17], 10), Some(Rect::new(2, 1, 6, 3)));
        assert_eq!(symmetric_difference(&[1, 4, 9], &[4, 7, 9, 12]), vec![1, 7, 12]);
    }
}
