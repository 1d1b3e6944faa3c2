//! A simulated robot exploring a known map (dissertation § 3.5, Fig. 3.40): what the floor
//! plan sees while a SLAM map grows.
//!
//! The online chain ([`crate::floorplan::Chain::update_map`]) is judged on maps that grow
//! the way a robot's map grows, and nobody here has a robot, so this module makes such maps
//! from a finished one. A point robot with a 2D range sensor starts on a free cell. Each scan
//! casts rays over the *true* map: cells a ray crosses become free in the robot's map, the
//! first occupied cell it meets becomes occupied, and a ray stops there or at a cell the true
//! map does not know (glass, clutter, the outside). Between scans the robot drives to the
//! nearest frontier (a seen free cell beside an unseen one) along the shortest 8-connected path
//! through free cells it has seen, and stops when no frontier is left. Given [`Target`]s (the
//! placeholders of a plan, weighed for a goal), it drives instead to the target with the most
//! value per metre of the way there ([`Explorer::set_targets`]). Frontiers it has
//! reached and could not resolve (unseen space its sensor cannot see into) are not chosen
//! again. The robot's map is what a SLAM system without pose error would build.
//!
//! Everything is deterministic: the start cell (unless given) is drawn from the seed, and ties
//! between frontiers break by cell index.
//!
//! ```
//! use ksmcmc::explore::{ExploreConfig, Explorer};
//! use ksmcmc::floorplan::synth;
//! let s = synth::generate(&synth::SynthConfig { width: 160, height: 120, ..Default::default() }, 2)?;
//! let mut robot = Explorer::new(&s.map, ExploreConfig::default(), 1)?;
//! while robot.advance(50) {}
//! // The robot has seen most of the building's free space.
//! assert!(robot.seen_count(ksmcmc::grid::Cell::Free) as f64 > 0.8 * s.map.count(ksmcmc::grid::Cell::Free) as f64);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

use crate::grid::{Cell, Grid, MapYaml, OccupancyMap};
use crate::mcmc::Rng;
use serde::{Deserialize, Serialize};
use std::collections::VecDeque;

/// How the simulated robot senses and moves.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct ExploreConfig {
    /// Range of the 2D range sensor, metres (default 8).
    pub range_m: f64,
    /// Distance driven between two scans, metres (default 0.5).
    pub scan_every_m: f64,
    /// Start cell `[column, row]` of the map; `None` draws a free cell from the seed.
    pub start: Option<[u32; 2]>,
    /// Frontier cells within this distance (metres, at most half the range) of the robot when
    /// it reaches a goal are given up on if still unresolved (default 1).
    pub give_up_m: f64,
}

impl Default for ExploreConfig {
    fn default() -> Self {
        ExploreConfig { range_m: 8.0, scan_every_m: 0.5, start: None, give_up_m: 1.0 }
    }
}

/// Why a robot cannot explore a map.
#[derive(Debug, Clone, PartialEq)]
pub enum ExploreError {
    /// A setting is out of range.
    Config(String),
    /// The map gives the robot nowhere to stand.
    Map(String),
}

impl std::fmt::Display for ExploreError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            ExploreError::Config(m) => write!(f, "exploration settings: {m}"),
            ExploreError::Map(m) => write!(f, "cannot explore this map: {m}"),
        }
    }
}

impl std::error::Error for ExploreError {}

impl ExploreConfig {
    /// Checks every setting, saying which is out of range.
    pub fn validate(&self) -> Result<(), ExploreError> {
        let bad = |m: String| Err(ExploreError::Config(m));
        if !(self.range_m.is_finite() && self.range_m > 0.0 && self.range_m <= 100.0) {
            return bad(format!("range_m {} must be a number of metres in (0, 100]", self.range_m));
        }
        if !(self.scan_every_m.is_finite() && self.scan_every_m > 0.0 && self.scan_every_m <= 100.0) {
            return bad(format!("scan_every_m {} must be a number of metres in (0, 100]", self.scan_every_m));
        }
        if !(self.give_up_m.is_finite() && (0.0..=100.0).contains(&self.give_up_m)) {
            return bad(format!("give_up_m {} must be a number of metres in [0, 100]", self.give_up_m));
        }
        Ok(())
    }

    /// Settings from JSON text with any subset of the fields.
    pub fn from_json(text: &str) -> Result<ExploreConfig, ExploreError> {
        let bad = |e: String| ExploreError::Config(format!("not a settings object: {e}"));
        let v: serde_json::Value = serde_json::from_str(text).map_err(|e| bad(e.to_string()))?;
        if !v.is_object() {
            return Err(bad("expected a JSON object such as {\"range_m\": 8}".into()));
        }
        let c: ExploreConfig = serde_json::from_value(v).map_err(|e| bad(e.to_string()))?;
        c.validate()?;
        Ok(c)
    }
}

/// A place on the frontier worth driving to, and what reaching it is worth: a placeholder of
/// the plan weighed for a goal, such as its probability of leading to a hall.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Target {
    /// The cell `(column, row)` of the robot's map.
    pub cell: (usize, usize),
    /// What reaching it is worth, at least 0 (a probability, for a goal).
    pub value: f64,
}

/// How near a frontier cell a target must lie to stand for it, m: the frontier a placeholder
/// was found on moves as the robot scans, by about the width of the rays' fringe.
pub const TARGET_REACH_M: f64 = 0.5;

/// The most cells a ray is traced over (the sensor range is capped to it).
const MAX_RANGE_CELLS: f64 = 2000.0;

/// A robot exploring a map it does not know.
#[derive(Debug, Clone)]
pub struct Explorer {
    truth: Grid<Cell>,
    seen: Grid<Cell>,
    /// The true map's resolution and origin, which the robot's map shares.
    yaml: MapYaml,
    robot: (usize, usize),
    /// Cells still to drive to the current goal, next last.
    plan: Vec<(usize, usize)>,
    given_up: Vec<bool>,
    range: f64,
    scan_every: usize,
    give_up: f64,
    since_scan: usize,
    /// Path length so far, cells (diagonal steps count √2).
    travelled: f64,
    /// Where the robot scanned, in order.
    scans: Vec<(usize, usize)>,
    /// The targets it weighs when it chooses a goal ([`Explorer::set_targets`]).
    targets: Vec<Target>,
    /// Goals chosen so far.
    goals: usize,
    done: bool,
}

impl Explorer {
    /// A robot on `truth` (whose classes the sensor reads), which scans once where it starts.
    pub fn new(truth: &OccupancyMap, config: ExploreConfig, seed: u64) -> Result<Explorer, ExploreError> {
        config.validate()?;
        let grid = truth.classified();
        let (w, h) = (grid.width(), grid.height());
        let resolution = truth.yaml().resolution;
        let robot = match config.start {
            Some([x, y]) => {
                let (x, y) = (x as usize, y as usize);
                if x >= w || y >= h {
                    return Err(ExploreError::Map(format!("the start ({x}, {y}) is off the {w}x{h} map")));
                }
                if *grid.at(x, y) != Cell::Free {
                    return Err(ExploreError::Map(format!("the start ({x}, {y}) is not a free cell")));
                }
                (x, y)
            }
            None => start_cell(grid, seed)?,
        };
        let cells = |m: f64| m / resolution;
        let mut e = Explorer {
            truth: grid.clone(),
            seen: Grid::new(w, h, Cell::Unknown),
            yaml: truth.yaml().clone(),
            robot,
            plan: Vec::new(),
            given_up: vec![false; w * h],
            range: cells(config.range_m).min(MAX_RANGE_CELLS),
            scan_every: (cells(config.scan_every_m).round() as usize).max(1),
            // Never farther than half the sensor's range: a frontier farther away may yet be
            // seen from a step closer.
            give_up: cells(config.give_up_m).min(cells(config.range_m) / 2.0),
            since_scan: 0,
            travelled: 0.0,
            scans: Vec::new(),
            targets: Vec::new(),
            goals: 0,
            done: false,
        };
        e.scan();
        Ok(e)
    }

    /// Drives up to `cells` cells (scanning on the way) and returns whether there is more to
    /// explore.
    pub fn advance(&mut self, cells: usize) -> bool {
        for _ in 0..cells {
            if self.done {
                break;
            }
            if self.plan.is_empty() && !self.replan() {
                self.done = true;
                self.scan();
                break;
            }
            let next = self.plan.pop().expect("a plan was just made");
            let (dx, dy) = (next.0.abs_diff(self.robot.0), next.1.abs_diff(self.robot.1));
            self.travelled += if dx + dy == 2 { std::f64::consts::SQRT_2 } else { 1.0 };
            self.robot = next;
            self.since_scan += 1;
            if self.since_scan >= self.scan_every || self.plan.is_empty() {
                self.scan();
                // A scan may have revealed an obstacle on the path, or resolved the goal.
                if self.plan.first().is_some_and(|&(x, y)| !self.is_frontier(x, y)) || self.blocked() {
                    self.plan.clear();
                }
            }
            if self.plan.is_empty() {
                self.give_up_near();
            }
        }
        !self.done
    }

    /// The targets the robot weighs from its next goal on, replacing any before. Among the
    /// targets with a frontier cell within [`TARGET_REACH_M`] that it can reach, it drives to
    /// the one with the most value per metre, `value / (d + give_up)`, where `d` is the length
    /// of the way there and `give_up` ([`ExploreConfig::give_up_m`]) what it drives on to see
    /// past it. With no such target it drives to the nearest frontier, as without targets.
    ///
    /// Ranking by probability per cost is the order that minimises the expected cost of
    /// searching places one by one for an object that lies in at most one of them (the
    /// classical result of optimal search); here the costs change as the robot moves, so the
    /// rule is applied again at every goal.
    pub fn set_targets(&mut self, targets: Vec<Target>) {
        self.targets = targets.into_iter().filter(|t| t.value.is_finite() && t.value > 0.0).collect();
    }

    /// Goals the robot has chosen so far (one per drive to a frontier).
    pub fn goals(&self) -> usize {
        self.goals
    }

    /// Whether the robot has no frontier left.
    pub fn is_done(&self) -> bool {
        self.done
    }

    /// The robot's cell `(column, row)`.
    pub fn robot(&self) -> (usize, usize) {
        self.robot
    }

    /// Metres driven so far.
    pub fn travelled_m(&self) -> f64 {
        self.travelled * self.yaml.resolution
    }

    /// The cells where the robot scanned, in order.
    pub fn scans(&self) -> &[(usize, usize)] {
        &self.scans
    }

    /// The robot's map so far, classes only.
    pub fn seen(&self) -> &Grid<Cell> {
        &self.seen
    }

    /// How many cells of class `c` the robot's map has.
    pub fn seen_count(&self, c: Cell) -> usize {
        self.seen.cells().iter().filter(|&&s| s == c).count()
    }

    /// The robot's map so far as a map with the true map's resolution and origin: what the
    /// chain is given.
    pub fn snapshot(&self) -> OccupancyMap {
        OccupancyMap::from_classified(self.seen.clone()).with_yaml(self.yaml.clone())
    }

    /// One scan from the robot's cell: rays every `1 / range` radians, so neighbouring rays are
    /// at most a cell apart at full range.
    fn scan(&mut self) {
        self.scans.push(self.robot);
        self.since_scan = 0;
        let rays = (std::f64::consts::TAU * self.range).ceil().max(8.0) as usize;
        let (ox, oy) = (self.robot.0 as f64 + 0.5, self.robot.1 as f64 + 0.5);
        for k in 0..rays {
            let a = k as f64 * std::f64::consts::TAU / rays as f64;
            self.cast(ox, oy, libm::cos(a), libm::sin(a));
        }
    }

    /// Traces one ray in half-cell steps up to the sensor's range.
    fn cast(&mut self, ox: f64, oy: f64, dx: f64, dy: f64) {
        let (w, h) = (self.truth.width() as f64, self.truth.height() as f64);
        let steps = (2.0 * self.range) as usize;
        for s in 0..=steps {
            let t = s as f64 * 0.5;
            let (x, y) = (ox + t * dx, oy + t * dy);
            if x < 0.0 || y < 0.0 || x >= w || y >= h {
                return;
            }
            let (x, y) = (x as usize, y as usize);
            match *self.truth.at(x, y) {
                Cell::Free => *self.seen.at_mut(x, y) = Cell::Free,
                Cell::Occupied => {
                    *self.seen.at_mut(x, y) = Cell::Occupied;
                    return;
                }
                Cell::Unknown => return,
            }
        }
    }

    /// A seen free cell beside an unseen one that is not given up on.
    fn is_frontier(&self, x: usize, y: usize) -> bool {
        let (w, h) = (self.seen.width(), self.seen.height());
        *self.seen.at(x, y) == Cell::Free
            && !self.given_up[y * w + x]
            && [(x.wrapping_sub(1), y), (x + 1, y), (x, y.wrapping_sub(1)), (x, y + 1)]
                .into_iter()
                .any(|(nx, ny)| nx < w && ny < h && *self.seen.at(nx, ny) == Cell::Unknown)
    }

    /// Whether the next step of the plan is no longer a seen free cell.
    fn blocked(&self) -> bool {
        self.plan.last().is_some_and(|&(x, y)| *self.seen.at(x, y) != Cell::Free)
    }

    /// Gives up on the unresolved frontier cells near the robot: it stands at a goal it chose
    /// and its scans did not see past them.
    fn give_up_near(&mut self) {
        let r = self.give_up.ceil() as isize;
        let (w, h) = (self.seen.width() as isize, self.seen.height() as isize);
        let (rx, ry) = (self.robot.0 as isize, self.robot.1 as isize);
        for y in (ry - r).max(0)..(ry + r + 1).min(h) {
            for x in (rx - r).max(0)..(rx + r + 1).min(w) {
                let d2 = ((x - rx) * (x - rx) + (y - ry) * (y - ry)) as f64;
                if d2 <= self.give_up * self.give_up && self.is_frontier(x as usize, y as usize) {
                    self.given_up[(y * w + x) as usize] = true;
                }
            }
        }
    }

    /// Plans the shortest path through seen free cells to the next goal (breadth-first,
    /// 8-connected, no corner cutting): the nearest frontier, or the best target
    /// ([`Explorer::set_targets`]). Returns false when no frontier can be reached.
    fn replan(&mut self) -> bool {
        let (w, h) = (self.seen.width(), self.seen.height());
        let start = self.robot.1 * w + self.robot.0;
        let mut parent = vec![u32::MAX; w * h];
        let mut dist = vec![f64::INFINITY; w * h];
        parent[start] = start as u32;
        dist[start] = 0.0;
        let mut queue = VecDeque::from([start]);
        let mut nearest = None;
        while let Some(i) = queue.pop_front() {
            let (x, y) = (i % w, i / w);
            if i != start && nearest.is_none() && self.is_frontier(x, y) {
                nearest = Some(i);
                if self.targets.is_empty() {
                    break;
                }
            }
            for (nx, ny) in self.free_neighbours(x, y) {
                let j = ny * w + nx;
                if parent[j] == u32::MAX {
                    parent[j] = i as u32;
                    dist[j] = dist[i] + if nx != x && ny != y { std::f64::consts::SQRT_2 } else { 1.0 };
                    queue.push_back(j);
                }
            }
        }
        let Some(nearest) = nearest else { return false };
        let goal = self.best_target(&dist).unwrap_or(nearest);
        self.plan = path_to(&parent, start, goal, w);
        self.goals += 1;
        true
    }

    /// The frontier cell of the target with the most value per metre ([`Explorer::set_targets`])
    /// given the path lengths `dist` (cells) from the robot; `None` if no target is live.
    fn best_target(&self, dist: &[f64]) -> Option<usize> {
        let (w, h) = (self.seen.width(), self.seen.height());
        let resolution = self.yaml.resolution;
        let r = (TARGET_REACH_M / resolution).ceil() as usize;
        let mut best: Option<(f64, usize)> = None;
        for t in &self.targets {
            let (tx, ty) = t.cell;
            if tx >= w || ty >= h {
                continue;
            }
            // The reachable frontier cell nearest the robot within reach of the target.
            let mut cell: Option<usize> = None;
            for y in ty.saturating_sub(r)..(ty + r + 1).min(h) {
                for x in tx.saturating_sub(r)..(tx + r + 1).min(w) {
                    let i = y * w + x;
                    let near = (x.abs_diff(tx).pow(2) + y.abs_diff(ty).pow(2)) as f64 <= (r * r) as f64;
                    if near
                        && dist[i].is_finite()
                        && dist[i] > 0.0
                        && self.is_frontier(x, y)
                        && cell.is_none_or(|c| dist[i] < dist[c])
                    {
                        cell = Some(i);
                    }
                }
            }
            let Some(i) = cell else { continue };
            let score = t.value / (dist[i] + self.give_up.max(1.0));
            if best.is_none_or(|(s, c)| score > s || (score == s && i < c)) {
                best = Some((score, i));
            }
        }
        best.map(|(_, i)| i)
    }

    /// Seen free neighbours of a cell, 8-connected; a diagonal step needs both cells beside it
    /// free, so the robot does not squeeze between two wall corners.
    fn free_neighbours(&self, x: usize, y: usize) -> impl Iterator<Item = (usize, usize)> + '_ {
        let (w, h) = (self.seen.width() as isize, self.seen.height() as isize);
        let free = move |x: isize, y: isize| {
            x >= 0 && y >= 0 && x < w && y < h && *self.seen.at(x as usize, y as usize) == Cell::Free
        };
        let (x, y) = (x as isize, y as isize);
        [(-1, 0), (1, 0), (0, -1), (0, 1), (-1, -1), (1, -1), (-1, 1), (1, 1)]
            .into_iter()
            .filter(move |&(dx, dy)| {
                free(x + dx, y + dy) && (dx == 0 || dy == 0 || (free(x + dx, y) && free(x, y + dy)))
            })
            .map(move |(dx, dy)| ((x + dx) as usize, (y + dy) as usize))
    }
}

/// The path from `start` to `goal` in a breadth-first parent table, goal first (the next cell
/// to drive to is last).
fn path_to(parent: &[u32], start: usize, goal: usize, width: usize) -> Vec<(usize, usize)> {
    let mut path = Vec::new();
    let mut i = goal;
    while i != start {
        path.push((i % width, i / width));
        i = parent[i] as usize;
    }
    path
}

/// A free cell drawn from the seed among the free cells with free space all around (a robot
/// is placed in a room, not against a wall).
fn start_cell(grid: &Grid<Cell>, seed: u64) -> Result<(usize, usize), ExploreError> {
    let (w, h) = (grid.width(), grid.height());
    let r = 3usize;
    let open = |x: usize, y: usize| {
        x >= r
            && y >= r
            && x + r < w
            && y + r < h
            && (y - r..=y + r).all(|yy| (x - r..=x + r).all(|xx| *grid.at(xx, yy) == Cell::Free))
    };
    let candidates: Vec<(usize, usize)> =
        (0..h).flat_map(|y| (0..w).map(move |x| (x, y))).filter(|&(x, y)| open(x, y)).collect();
    if candidates.is_empty() {
        return Err(ExploreError::Map(format!(
            "no free cell has free cells {r} cells around it to start from; give a start cell"
        )));
    }
    let k = Rng::seed(seed).below(candidates.len().min(u32::MAX as usize) as u32) as usize;
    Ok(candidates[k])
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Two 20x20 rooms joined by a door, walls around; everything else unknown.
    fn two_rooms() -> OccupancyMap {
        let mut g = Grid::new(50, 30, Cell::Unknown);
        for y in 2..25 {
            for x in 2..45 {
                let wall = x == 2 || x == 44 || y == 2 || y == 24 || (x == 23 && !(12..15).contains(&y));
                *g.at_mut(x, y) = if wall { Cell::Occupied } else { Cell::Free };
            }
        }
        OccupancyMap::from_classified(g)
    }

    #[test]
    fn the_robot_sees_both_rooms_and_nothing_the_truth_does_not_hold() {
        let truth = two_rooms();
        let config = ExploreConfig { range_m: 0.5, start: Some([5, 5]), ..Default::default() };
        let mut e = Explorer::new(&truth, config, 1).unwrap();
        // A 10-cell sensor in the corner of the left room cannot see the right one yet.
        assert!((24..44).all(|x| *e.seen().at(x, 20) == Cell::Unknown));
        while e.advance(7) {}
        assert!(e.is_done());
        for (s, t) in e.seen().cells().iter().zip(truth.classified().cells()) {
            assert!(*s == Cell::Unknown || s == t, "seen {s:?} where the truth is {t:?}");
        }
        // Every free cell of both rooms is seen: the robot went through the door.
        assert_eq!(e.seen_count(Cell::Free), truth.count(Cell::Free));
        assert!(e.travelled_m() > 1.0 && e.scans().len() > 5);
        // A scan every 0.5 m (and one at each goal), not one every cell.
        let most = 2.0 * e.travelled_m() / 0.5 + 10.0;
        assert!((e.scans().len() as f64) < most, "{} scans over {} m", e.scans().len(), e.travelled_m());
        // The path stays on free cells.
        assert!(e.scans().iter().all(|&(x, y)| *truth.classified().at(x, y) == Cell::Free));
    }

    /// The two-room map at 0.1 m a cell: a target stands for frontier cells up to 5 cells away.
    fn two_rooms_coarse() -> OccupancyMap {
        let mut yaml = MapYaml::for_image("two_rooms.pgm");
        yaml.resolution = 0.1;
        two_rooms().with_yaml(yaml)
    }

    /// The robot in the left room's corner with a 2 m (20-cell) sensor: it sees the left room
    /// but for its far corner, and a little of the right room through the door.
    fn in_the_corner() -> Explorer {
        let config = ExploreConfig { range_m: 2.0, start: Some([5, 5]), give_up_m: 0.5, ..Default::default() };
        Explorer::new(&two_rooms_coarse(), config, 1).unwrap()
    }

    /// The frontier cells beyond the door (right room) and in the left room's far corner.
    fn door_and_corner(e: &Explorer) -> [Vec<(usize, usize)>; 2] {
        let cells: Vec<(usize, usize)> =
            (0..30).flat_map(|y| (0..50).map(move |x| (x, y))).filter(|&(x, y)| e.is_frontier(x, y)).collect();
        let (door, rest): (Vec<_>, Vec<_>) = cells.iter().partition(|c| c.0 >= 23);
        [door, rest.into_iter().filter(|c| c.0 >= 10 && c.1 >= 17).collect()]
    }

    #[test]
    fn targets_steer_the_robot_by_value_per_metre() {
        let e = in_the_corner();
        let [door, corner] = door_and_corner(&e);
        assert!(!door.is_empty() && !corner.is_empty(), "door {door:?} corner {corner:?}");
        // The two groups lie farther apart than twice a target's reach (5 cells).
        let d = door[door.len() / 2];
        let apart = |c: &(usize, usize)| d.0.abs_diff(c.0).pow(2) + d.1.abs_diff(c.1).pow(2);
        let c = *corner.iter().max_by_key(|c| apart(c)).unwrap();
        assert!(apart(&c) > 100, "{d:?} {c:?}");
        let goal = |targets: Vec<Target>| {
            let mut e = in_the_corner();
            e.set_targets(targets);
            assert!(e.replan());
            e.plan[0]
        };
        let near = |g: (usize, usize), t: (usize, usize)| g.0.abs_diff(t.0).pow(2) + g.1.abs_diff(t.1).pow(2) <= 25;
        // Whichever holds the value a hundred times over is driven to, whatever its distance.
        let g = goal(vec![Target { cell: d, value: 1.0 }, Target { cell: c, value: 0.01 }]);
        assert!(near(g, d) && door.contains(&g), "{g:?} for the door's {d:?}");
        let g = goal(vec![Target { cell: d, value: 0.01 }, Target { cell: c, value: 1.0 }]);
        assert!(near(g, c) && corner.contains(&g), "{g:?} for the corner's {c:?}");
        // Worthless targets, and targets off every frontier, leave the nearest frontier.
        let mut plain = in_the_corner();
        assert!(plain.replan());
        let nearest = plain.plan[0];
        assert_eq!(goal(vec![Target { cell: d, value: 0.0 }]), nearest);
        assert_eq!(goal(vec![Target { cell: (40, 20), value: 1.0 }, Target { cell: (99, 99), value: 1.0 }]), nearest);
        assert_eq!(plain.goals(), 1);
    }

    #[test]
    fn a_guided_robot_still_sees_everything() {
        let truth = two_rooms_coarse();
        let mut e = in_the_corner();
        let [_, corner] = door_and_corner(&e);
        e.set_targets(vec![Target { cell: corner[0], value: 1.0 }]);
        while e.advance(7) {}
        assert_eq!(e.seen_count(Cell::Free), truth.count(Cell::Free));
    }

    #[test]
    fn bad_settings_and_starts_are_refused() {
        let truth = two_rooms();
        for bad in [r#"{"range_m": 0}"#, r#"{"scan_every_m": -1}"#, r#"{"range": 3}"#, "[]"] {
            assert!(ExploreConfig::from_json(bad).is_err(), "{bad}");
        }
        let at = |x, y| ExploreConfig { start: Some([x, y]), ..Default::default() };
        assert!(Explorer::new(&truth, at(2, 2), 1).unwrap_err().to_string().contains("not a free cell"));
        assert!(Explorer::new(&truth, at(99, 2), 1).unwrap_err().to_string().contains("off the 50x30 map"));
        let blank = OccupancyMap::from_classified(Grid::new(10, 10, Cell::Unknown));
        assert!(Explorer::new(&blank, ExploreConfig::default(), 1).is_err());
    }

    #[test]
    fn the_seed_chooses_the_start_deterministically() {
        let truth = two_rooms();
        let a = Explorer::new(&truth, ExploreConfig::default(), 4).unwrap().robot();
        assert_eq!(a, Explorer::new(&truth, ExploreConfig::default(), 4).unwrap().robot());
        let starts: std::collections::BTreeSet<_> =
            (0..10).map(|s| Explorer::new(&truth, ExploreConfig::default(), s).unwrap().robot()).collect();
        assert!(starts.len() > 3, "{starts:?}");
    }
}
