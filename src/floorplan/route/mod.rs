//! Semantic routes: from a cell to another through the rooms and doors of a floor plan, as a
//! robot plans with a floor plan (dissertation Fig. 3.42).
//!
//! A route is planned twice, first coarse, then fine:
//!
//! 1. **On the room graph.** Rooms are the regions of the label image (`labels.pgm`); they
//!    are joined where the world's room layer says they open onto each other
//!    ([`Room::opens_to`](super::Room::opens_to), through a door or an open boundary), at
//!    [`portals`]: the places where their cells meet. A* (petgraph) searches a graph whose
//!    nodes are the two sides of every portal, plus the start and the goal; an edge crosses a
//!    portal, or joins two nodes of one room at the length of the shortest path between them
//!    inside that room (found on demand, when A* first looks at the edge). The heuristic is
//!    the octile distance to the goal, which no path beats.
//! 2. **On cells.** The cells of the rooms that route passes, and only those, are searched
//!    again for the shortest 8-connected path ([`cells`]): it never steps on a cell that is
//!    not free, never cuts an occupied corner, and is never longer than the room-graph route.
//!
//! The rooms and doors a [`Route`] lists are those its path actually passes, in order. Where
//! the room graph has no route (an end lies in free space no room holds, or the rooms are not
//! joined in the room layer although free cells join them), the route is planned on the free
//! cells alone ([`Planned::Cells`]). Ends off the map or not free, and goals that no free path
//! reaches, are [`RouteError`]s.
//!
//! ```
//! use ksmcmc::floorplan::route::RoutePlanner;
//! use ksmcmc::floorplan::{Door, Unit, UnitType, World};
//! use ksmcmc::grid::{Cell, Grid};
//!
//! // Two 20 x 20 rooms side by side, a wall at column 20 with a door at rows 8..12.
//! let mut map = Grid::new(41, 20, Cell::Free);
//! for y in (0..8).chain(12..20) {
//!     *map.at_mut(20, y) = Cell::Occupied;
//! }
//! let mut world = World::empty(41, 20);
//! world.units = vec![
//!     Unit::new(1, 0, 0, 21, 20, UnitType::Room),
//!     Unit::new(2, 20, 0, 21, 20, UnitType::Room),
//! ];
//! world.doors = vec![Door { id: 7, units: [1, 2], x0: 20, y0: 8, x1: 20, y1: 11, opening: false }];
//! // The room labels: room 1 up to the wall (and in its doorway), room 2 beyond it.
//! let labels = Grid::from_vec(41, 20, (0..41 * 20).map(|i| match i % 41 {
//!     20 => u16::from(map.cells()[i] == Cell::Free),
//!     x if x < 20 => 1,
//!     _ => 2,
//! }).collect()).unwrap();
//! let mut planner = RoutePlanner::new(map, labels, &world, 0.05)?;
//! let route = planner.route((2, 2), (38, 2))?;
//! assert_eq!((route.rooms.clone(), route.doors.clone()), (vec![1, 2], vec![7]));
//! assert_eq!((route.path[0], *route.path.last().unwrap()), ([2, 2], [38, 2]));
//! assert!(route.length_m > 36.0 * 0.05);
//! // A wall is no place to start from.
//! let e = planner.route((20, 2), (38, 2)).unwrap_err();
//! assert!(e.to_string().contains("occupied"), "{e}");
//! # Ok::<(), ksmcmc::floorplan::route::RouteError>(())
//! ```

pub mod cells;
mod labels;
pub mod portals;
pub mod study;

pub use labels::saved_labels;

use super::world::World;
use crate::grid::{Cell, Grid};
use cells::{octile, Search, FAR, STRAIGHT};
use petgraph::graph::{NodeIndex, UnGraph};
use petgraph::visit::EdgeRef;
use std::collections::{BTreeMap, BTreeSet, HashMap};

/// A planned route (see the module docs); serialises as the JSON `ksmcmc route` prints:
/// `{"rooms": [...], "doors": [...], "path": [[x, y], ...], "length_m": ...}`.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct Route {
    /// The rooms the path passes, in order (their ids, the values of `labels.pgm`); a room
    /// left and entered again is listed again.
    pub rooms: Vec<u32>,
    /// The doors the path passes through, in order (their ids in `world.json`).
    pub doors: Vec<u32>,
    /// Every cell of the path, `[column, row]` on the map, from start to goal: 8-connected,
    /// all free.
    pub path: Vec<[u32; 2]>,
    /// The path's length in metres: its steps (1 or sqrt 2 cells) times the map's resolution.
    pub length_m: f64,
    /// How the route was planned (not part of the JSON).
    #[serde(skip)]
    pub planned: Planned,
}

impl Route {
    /// The route as compact JSON text.
    pub fn to_json(&self) -> String {
        serde_json::to_string(self).expect("a route serialises")
    }
}

/// How a route was planned.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Planned {
    /// On the room graph, then on the cells of the rooms it passes.
    #[default]
    Rooms,
    /// On the free cells alone: the room graph had no route between the ends.
    Cells,
}

/// Which end of a route.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum End {
    /// Where the route starts.
    Start,
    /// Where it ends.
    Goal,
}

impl std::fmt::Display for End {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            End::Start => "start",
            End::Goal => "goal",
        })
    }
}

/// Why no route was planned.
#[derive(Debug, Clone, PartialEq)]
pub enum RouteError {
    /// An end lies outside the map.
    OffMap {
        /// Which end.
        end: End,
        /// Its column and row.
        at: (i64, i64),
        /// The map's width and height.
        size: (usize, usize),
    },
    /// An end is not a free cell.
    NotFree {
        /// Which end.
        end: End,
        /// Its column and row.
        at: (u32, u32),
        /// What the map says of it.
        cell: Cell,
    },
    /// No free path joins the two ends.
    Unreachable {
        /// The start's column and row.
        from: (u32, u32),
        /// The goal's column and row.
        to: (u32, u32),
    },
    /// The world or the labels do not belong to the map (the message says how).
    Mismatch(String),
}

impl std::fmt::Display for RouteError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            RouteError::OffMap { end, at, size } => write!(
                f,
                "the {end} ({}, {}) lies outside the {}x{} map: columns run from 0 to {} and rows from 0 to {}",
                at.0,
                at.1,
                size.0,
                size.1,
                size.0.saturating_sub(1),
                size.1.saturating_sub(1)
            ),
            RouteError::NotFree { end, at, cell } => {
                let what = match cell {
                    Cell::Occupied => "an occupied cell (a wall or an obstacle)",
                    _ => "an unknown cell (not mapped)",
                };
                write!(f, "the {end} ({}, {}) is {what}; a route starts and ends on free cells", at.0, at.1)
            }
            RouteError::Unreachable { from, to } => write!(
                f,
                "no route from ({}, {}) to ({}, {}): no path of free cells joins them (the goal lies in free \
                 space closed off from the start)",
                from.0, from.1, to.0, to.1
            ),
            RouteError::Mismatch(m) => f.write_str(m),
        }
    }
}

impl std::error::Error for RouteError {}

/// An edge of the room graph.
#[derive(Debug, Clone, Copy)]
enum Link {
    /// Crossing a portal: one straight step.
    Cross,
    /// Between two portal sides in one room: the shortest path inside the room.
    Within,
    /// From the start or to the goal: a length found when the query began.
    Fixed(u32),
}

/// A node of the room graph: a cell in a room.
#[derive(Debug, Clone, Copy)]
struct Side {
    cell: u32,
    room: u16,
}

/// No path: more than any path costs (paths cost under 2^32), and sums of a few stay far from
/// overflowing.
const UNREACHABLE: u64 = 1 << 40;

/// Plans routes on one map with one world and its room labels; keeps what later routes reuse
/// (the room graph, distances inside rooms, a search table).
#[derive(Debug, Clone)]
pub struct RoutePlanner {
    map: Grid<Cell>,
    labels: Grid<u16>,
    resolution: f64,
    /// The door covering each map cell that some door covers.
    doors: HashMap<u32, u32>,
    graph: UnGraph<Side, Link>,
    /// The sides in each room, and each side's place in its room's list.
    sides: BTreeMap<u16, Vec<NodeIndex>>,
    slot: Vec<usize>,
    /// Distances from a side to every side of its room (by slot), once asked for.
    within: HashMap<NodeIndex, Vec<u32>>,
    search: Search,
}

impl RoutePlanner {
    /// A planner for `map` (classified, in the map's frame), `world` (made for it) and its
    /// room `labels` (the map's size: `labels.pgm`, or [`saved_labels`]); `resolution` is
    /// metres per cell. Rooms are joined as `world.rooms` says (every pair of touching rooms
    /// when the world has no room layer).
    pub fn new(map: Grid<Cell>, labels: Grid<u16>, world: &World, resolution: f64) -> Result<RoutePlanner, RouteError> {
        let (w, h) = (map.width(), map.height());
        if (labels.width(), labels.height()) != (w, h) {
            return Err(RouteError::Mismatch(format!(
                "the room labels are {}x{} but the map is {w}x{h}: use the labels.pgm written with this world",
                labels.width(),
                labels.height()
            )));
        }
        world.fits(w, h).map_err(|e| RouteError::Mismatch(e.to_string()))?;
        let links: BTreeSet<(u16, u16)> = world
            .rooms
            .iter()
            .flat_map(|r| r.opens_to.iter().map(move |&o| (r.id.min(o), r.id.max(o))))
            .filter_map(|(a, b)| Some((u16::try_from(a).ok()?, u16::try_from(b).ok()?)))
            .collect();
        let has_layer = !world.rooms.is_empty();
        let linked = |a: u16, b: u16| !has_layer || links.contains(&(a, b));
        let mut planner = RoutePlanner {
            doors: door_cells(world, w, h),
            graph: UnGraph::default(),
            sides: BTreeMap::new(),
            slot: Vec::new(),
            within: HashMap::new(),
            search: Search::new(w * h),
            resolution: if resolution.is_finite() && resolution > 0.0 { resolution } else { 1.0 },
            map,
            labels,
        };
        for p in portals::portals(&planner.labels, &linked) {
            let a = planner.add_side(Side { cell: p.cells[0], room: p.rooms[0] });
            let b = planner.add_side(Side { cell: p.cells[1], room: p.rooms[1] });
            planner.graph.add_edge(a, b, Link::Cross);
        }
        for nodes in planner.sides.values() {
            for (k, &a) in nodes.iter().enumerate() {
                for &b in &nodes[k + 1..] {
                    planner.graph.add_edge(a, b, Link::Within);
                }
            }
        }
        Ok(planner)
    }

    fn add_side(&mut self, side: Side) -> NodeIndex {
        let n = self.graph.add_node(side);
        let list = self.sides.entry(side.room).or_default();
        self.slot.push(list.len());
        list.push(n);
        n
    }

    /// The map's width and height.
    pub fn size(&self) -> (usize, usize) {
        (self.map.width(), self.map.height())
    }

    /// The room labels the planner uses.
    pub fn labels(&self) -> &Grid<u16> {
        &self.labels
    }

    /// The map the planner routes on.
    pub fn map(&self) -> &Grid<Cell> {
        &self.map
    }

    /// The route from cell `from` to cell `to` (column, row).
    pub fn route(&mut self, from: (i64, i64), to: (i64, i64)) -> Result<Route, RouteError> {
        let s = self.check(End::Start, from)?;
        let g = self.check(End::Goal, to)?;
        let w = self.map.width();
        let at = move |i: usize| ((i % w) as u32, (i / w) as u32);
        let (ra, rb) = (self.labels.cells()[s], self.labels.cells()[g]);
        if ra != 0 && rb != 0 {
            if let Some(path) = self.on_rooms(s, g) {
                return Ok(self.finish(path, Planned::Rooms));
            }
        }
        match self.shortest(s, g) {
            Some(path) => Ok(self.finish(path, Planned::Cells)),
            None => Err(RouteError::Unreachable { from: at(s), to: at(g) }),
        }
    }

    /// The shortest path between two free cells (indices) over all free cells, with the
    /// moves of [`cells`]: what a route is measured against.
    pub fn shortest(&mut self, s: usize, g: usize) -> Option<Vec<usize>> {
        self.search.path(&self.map, &|_| true, s, g).map(|(p, _)| p)
    }

    /// The cell index of an end, if on the map and free.
    fn check(&self, end: End, (x, y): (i64, i64)) -> Result<usize, RouteError> {
        let (w, h) = self.size();
        if x < 0 || y < 0 || x >= w as i64 || y >= h as i64 {
            return Err(RouteError::OffMap { end, at: (x, y), size: (w, h) });
        }
        let cell = *self.map.at(x as usize, y as usize);
        if cell != Cell::Free {
            return Err(RouteError::NotFree { end, at: (x as u32, y as u32), cell });
        }
        Ok(y as usize * w + x as usize)
    }

    /// The route on the room graph from `s` to `g` (both in rooms), then on the cells of the
    /// rooms it passes; `None` if the room graph has none.
    fn on_rooms(&mut self, s: usize, g: usize) -> Option<Vec<usize>> {
        let (ra, rb) = (self.labels.cells()[s], self.labels.cells()[g]);
        let mut graph = self.graph.clone();
        let start = graph.add_node(Side { cell: s as u32, room: ra });
        let goal = graph.add_node(Side { cell: g as u32, room: rb });
        for (end, node, room) in [(s, start, ra), (g, goal, rb)] {
            let labels = &self.labels;
            self.search.from(&self.map, &|i| labels.cells()[i] == room, end);
            for &side in self.sides.get(&room).map(Vec::as_slice).unwrap_or(&[]) {
                let d = self.search.dist(graph[side].cell as usize);
                if d != FAR {
                    graph.add_edge(node, side, Link::Fixed(d));
                }
            }
            if node == start && ra == rb && self.search.dist(g) != FAR {
                graph.add_edge(start, goal, Link::Fixed(self.search.dist(g)));
            }
        }
        let w = self.map.width();
        let (cost, nodes) = petgraph::algo::astar(
            &graph,
            start,
            |n| n == goal,
            |e| match *e.weight() {
                Link::Cross => STRAIGHT as u64,
                Link::Fixed(d) => d as u64,
                Link::Within => self.within_cost(&graph, e.source(), e.target()),
            },
            |n| octile(graph[n].cell as usize, g, w),
        )?;
        if cost >= UNREACHABLE {
            return None;
        }
        let mut rooms = vec![false; u16::MAX as usize + 1];
        for n in nodes {
            rooms[graph[n].room as usize] = true;
        }
        let labels = &self.labels;
        self.search.path(&self.map, &|i| rooms[labels.cells()[i] as usize], s, g).map(|(p, _)| p)
    }

    /// The length of the shortest path inside their room between two portal sides.
    fn within_cost(&mut self, graph: &UnGraph<Side, Link>, a: NodeIndex, b: NodeIndex) -> u64 {
        let d = match (self.within.get(&a), self.within.get(&b)) {
            (Some(d), _) => d[self.slot[b.index()]],
            (_, Some(d)) => d[self.slot[a.index()]],
            _ => {
                let Side { cell, room } = graph[a];
                let labels = &self.labels;
                self.search.from(&self.map, &|i| labels.cells()[i] == room, cell as usize);
                let d: Vec<u32> = self.sides[&room].iter().map(|&n| self.search.dist(graph[n].cell as usize)).collect();
                let out = d[self.slot[b.index()]];
                self.within.insert(a, d);
                out
            }
        };
        if d == FAR {
            UNREACHABLE
        } else {
            d as u64
        }
    }

    /// The [`Route`] of a path of cell indices.
    fn finish(&self, path: Vec<usize>, planned: Planned) -> Route {
        let w = self.map.width();
        let (mut rooms, mut doors) = (Vec::new(), Vec::new());
        let mut last_door = None;
        for &i in &path {
            let room = self.labels.cells()[i] as u32;
            if room != 0 && rooms.last() != Some(&room) {
                rooms.push(room);
            }
            let door = self.doors.get(&(i as u32)).copied();
            if let Some(d) = door.filter(|_| door != last_door) {
                doors.push(d);
            }
            last_door = door;
        }
        let diagonal = path.windows(2).filter(|p| p[0] % w != p[1] % w && p[0] / w != p[1] / w).count();
        let straight = path.len().saturating_sub(1) - diagonal;
        let length_m = (straight as f64 + diagonal as f64 * std::f64::consts::SQRT_2) * self.resolution;
        let path = path.iter().map(|&i| [(i % w) as u32, (i / w) as u32]).collect();
        Route { rooms, doors, path, length_m, planned }
    }
}

/// The door (its id) over every map cell a door covers: map cells whose centre falls, in the
/// door's frame (its units', [`World::door_frame`]), on one of the door's cells (the first door
/// listed, where doors overlap).
fn door_cells(world: &World, w: usize, h: usize) -> HashMap<u32, u32> {
    let mut out = HashMap::new();
    for d in &world.doors {
        for (mx, my) in world.door_frame(d).map_cells(d.rect(), w, h) {
            out.entry((my * w + mx) as u32).or_insert(d.id);
        }
    }
    out
}
