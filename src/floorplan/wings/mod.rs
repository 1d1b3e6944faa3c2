//! **The wings folder** owns buildings whose walls run several ways: the wing layout, a chain
//! per wing, and the doors between wings ([`wing_doors`]). It imports the chain, the room
//! layer and the world.
//!
//! Buildings whose walls follow several directions (issue 13): a chain per wing, each in its
//! own direction's frame, and one world of units at several angles.
//!
//! The chain's units are upright rectangles in one frame, turned by the map's dominant wall
//! angle. A building whose wings meet at an angle is explained there by rectangles cut across
//! its walls. [`Wings::run`] keeps the chain and what it finds of the rooms, and explains the
//! rooms again wing by wing:
//!
//! 1. a chain explains the whole map as [`Chain`] always does; its room layer gives the rooms
//!    and their labels;
//! 2. each room takes the wall direction most of its cells follow
//!    ([`crate::vision::regions`]); a room no direction holds 60 % of (a corridor round a
//!    pentagon) is split by its cells' own directions;
//! 3. every direction whose rooms hold `min_share` of the free cells is a wing, the dominant
//!    direction the first ([`WingLayout`]). Where the first wing holds less than
//!    [`MIN_FIRST_SHARE`] of the floor, the first chain's units cut across most of the walls,
//!    and the rooms are found again where the walls part them, with the wall gaps of every
//!    wing's direction closed ([`Chain::rooms_by_walls`]); otherwise the
//!    first chain's rooms and labels stay the result's;
//! 4. a chain turned by each wing's direction explains the wing's floor alone (the other
//!    wings' free cells read unknown), its kernels unchanged;
//! 5. the world has those rooms, with the units and doors of the wings' chains: each unit
//!    whose interior lies mostly in its wing, in the room under most of it. The units of
//!    every wing but the first carry their angle ([`World::unit_frame`]);
//! 6. where a passage of free cells leads from a unit of one wing into a unit of another,
//!    a door joins them ([`self::wing_doors`]).
//!
//! Why the rooms stay the first chain's in a building of two wings: the wings' own chains
//! find rooms whose labels move by 0.03 of precision with a chain's random path, and lose on
//! furnished maps (BENCHMARKS, "Wings at an angle"), while on the generated two-wing floors
//! the rooms by the walls lose precision where rooms open onto a corridor with no wall
//! stub to close them.
//!
//! The world's frame, object cells and room types are the first chain's; unexplained areas are
//! left out. Each chain runs the given iterations, so a map of `n` wings costs `n + 1` chains.

pub mod wing_doors;

use super::rooms::{RoomConfig, RoomLayer};
use super::world::{Door, Unit, World};
use super::{Chain, ChainConfig, ChainError, DoorLimits, RunRecord, Stopped};
use crate::grid::{Cell, Grid, OccupancyMap};
use crate::vision::orientation::WallProfile;
use crate::vision::regions::{direction_regions_from, DirectionRegions, RegionConfig, NO_REGION};
use std::collections::BTreeMap;

/// When and how a map is explained wing by wing.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WingConfig {
    /// How the regions of the wall directions are found.
    pub regions: RegionConfig,
    /// Smallest share of the free cells a direction's region needs to be a wing of its own
    /// (default 0.1); smaller regions go to the first wing.
    pub min_share: f64,
}

impl Default for WingConfig {
    fn default() -> Self {
        WingConfig { regions: RegionConfig::default(), min_share: 0.1 }
    }
}

/// The chains of a building's wings and the world they compose (module docs).
pub struct Wings {
    /// The first chain, which explains the whole map in its dominant direction, then one
    /// chain per wing (none when the map is one wing), each stopped as soon as it has run.
    pub chains: Vec<Stopped>,
    /// Per map cell: the wing whose chain explains it (free cells), [`NO_REGION`] elsewhere.
    pub wing_of: Grid<u8>,
    /// The composed world, with its rooms.
    pub world: World,
    /// Its room labels, one id per room of `world`.
    pub labels: Grid<u16>,
}

impl Wings {
    /// Explains `map` wing by wing (module docs): a chain of `config` seeded with `seed` runs
    /// `iterations` on the whole map; each of its rooms takes the wall direction most of its
    /// cells follow; the rooms of every other direction that holds `wing.min_share` of the
    /// free cells are explained again by a chain turned by that direction on them alone.
    /// With one wing, the world is the first chain's.
    ///
    /// ```
    /// use ksmcmc::floorplan::synth::{generate, SynthConfig};
    /// use ksmcmc::floorplan::wings::{WingConfig, Wings};
    /// use ksmcmc::floorplan::ChainConfig;
    /// let s = generate(&SynthConfig { wing_deg: 30.0, width: 240, height: 160, ..Default::default() }, 1)?;
    /// let wings = Wings::run(&s.map, &ChainConfig::default(), &WingConfig::default(), 1, 3000, &Default::default())?;
    /// assert_eq!(wings.chains.len(), 3); // the first chain, then one per wing
    /// let (world, labels) = (&wings.world, &wings.labels);
    /// world.validate()?;
    /// assert!(world.units.iter().any(|u| u.angle.is_some()) && world.units.iter().any(|u| u.angle.is_none()));
    /// assert!(world.rooms.iter().all(|r| labels.cells().contains(&(r.id as u16))));
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn run(
        map: &OccupancyMap,
        config: &ChainConfig,
        wing: &WingConfig,
        seed: u64,
        iterations: u64,
        rooms: &RoomConfig,
    ) -> Result<Wings, ChainError> {
        let mut first = Chain::new(map, config.clone(), seed)?;
        first.step(iterations);
        // Its tables are freed before the rooms are read ([`Stopped`]).
        let mut first = first.stop();
        let (mut world, mut labels) = first.best_world_with_rooms(rooms)?;
        // A given rotation keeps one chain; otherwise the chain has the walls' profile.
        let layout = first
            .wall_profile()
            .filter(|_| config.detectors.rotation_deg.is_none())
            .and_then(|profile| WingLayout::find_from(map, profile, &labels, first.frame().angle, wing));
        let Some(layout) = layout else {
            let wing_of = labels.map(|&l| if l > 0 { 0 } else { NO_REGION });
            return Ok(Wings { chains: vec![first], wing_of, world, labels });
        };
        let (mut chains, units): (Vec<Stopped>, Vec<World>) =
            wing_chains(&layout, map, config, seed, iterations)?.into_iter().unzip();
        let by_walls = |world: &mut World, others: &[f64]| first.rooms_by_walls(world, rooms, others);
        let doors = config.doors.cells(map.yaml().resolution);
        (world, labels) = layout.compose(map.classified(), world, labels, &units, &doors, by_walls)?;
        // Openings need only the layer's lengths, not its rules.
        RoomLayer::without_knowledge(*rooms).mark_openings(&mut world, map.classified(), map.yaml().resolution);
        chains.insert(0, first);
        Ok(Wings { chains, wing_of: layout.wing_of, world, labels })
    }
}

/// A wing's direction in degrees as its chain is configured
/// ([`super::DetectorConfig::rotation_deg`]): rounded to a millionth of a degree, so that the
/// number reads back to the same bits from JSON text, as the browser's chain of a wing is
/// configured (serde_json reads numbers of 17 digits fast, not exactly: `crate::json`).
pub fn wing_rotation_deg(angle: f64) -> f64 {
    libm::round(angle.to_degrees() * 1e6) / 1e6
}

/// The share of a room's cells its main direction needs for the whole room to follow it.
const ROOM_SHARE: f64 = 0.6;

/// The share of the free cells below which the first wing (the first chain's direction) is
/// too little of the building for its chain's units to say which of them share a room: the
/// rooms are then where the walls part them ([`Chain::rooms_by_walls`]). A
/// building of two wings has half its floor or more in the first; the benchmark's pentagon
/// (office_e, five directions) has 0.22. Set with that one floor in view.
pub const MIN_FIRST_SHARE: f64 = 1.0 / 3.0;

/// A building's wings, from the first chain's rooms ([`WingLayout::find`]).
#[derive(Debug, Clone, PartialEq)]
pub struct WingLayout {
    /// Per map cell: the wing whose chain explains it (free cells), [`NO_REGION`] elsewhere.
    pub wing_of: Grid<u8>,
    /// Each wing's direction (radians, as the frame's angle), the first chain's first.
    pub angles: Vec<f64>,
}

impl WingLayout {
    /// The wings of `map` (module docs, steps 2 and 3) given the room `labels` of a chain
    /// turned by `first_angle`; `None` for a building of one wing.
    pub fn find(map: &OccupancyMap, labels: &Grid<u16>, first_angle: f64, wing: &WingConfig) -> Option<WingLayout> {
        WingLayout::find_from(map, &WallProfile::of(map.classified()), labels, first_angle, wing)
    }

    /// [`WingLayout::find`] with the wall directions read off `profile`, the
    /// [`WallProfile`] of `map` a caller has already built (the first chain's,
    /// [`Chain::wall_profile`]).
    pub fn find_from(
        map: &OccupancyMap,
        profile: &WallProfile,
        labels: &Grid<u16>,
        first_angle: f64,
        wing: &WingConfig,
    ) -> Option<WingLayout> {
        let found = direction_regions_from(map.classified(), profile, &wing.regions, map.yaml().resolution);
        let (wing_of, angles) = wings_by_room(&found, labels, first_angle, wing.min_share)?;
        Some(WingLayout { wing_of, angles })
    }

    /// The other wings' directions when the rooms are found by the walls (the first wing
    /// holds less than [`MIN_FIRST_SHARE`] of the floor), else `None`.
    pub fn by_walls(&self) -> Option<&[f64]> {
        (first_share(&self.wing_of) < MIN_FIRST_SHARE).then(|| &self.angles[1..])
    }

    /// `map` as wing `k`'s chain sees it (module docs, step 4): the other wings' free cells
    /// unknown, so that its units explain its own floor.
    pub fn wing_map(&self, map: &OccupancyMap, k: usize) -> OccupancyMap {
        let cells = map.classified().cells().iter().zip(self.wing_of.cells()).map(|(&c, &w)| {
            if w != NO_REGION && w as usize != k {
                Cell::Unknown
            } else {
                c
            }
        });
        let grid = Grid::from_vec(map.width(), map.height(), cells.collect()).expect("the map's own size");
        OccupancyMap::from_classified(grid).with_yaml(map.yaml().clone())
    }

    /// The settings of wing `k`'s chain: `config` turned by the wing's direction
    /// ([`wing_rotation_deg`]).
    pub fn wing_config(&self, config: &ChainConfig, k: usize) -> ChainConfig {
        let mut c = config.clone();
        c.detectors.rotation_deg = self.angles.get(k).map(|&a| wing_rotation_deg(a));
        c
    }

    /// The world of the wings (module docs, steps 3 and 5) from the first chain's `world` with
    /// its rooms and their `labels`, and the typed best worlds of the wings' chains, one per
    /// wing in order ([`WingLayout::wing_map`], [`WingLayout::wing_config`]). Where the rooms
    /// go by the walls ([`WingLayout::by_walls`]), `by_walls` finds them again on `world` with
    /// the other wings' directions and returns their labels
    /// ([`Chain::rooms_by_walls`], [`super::export::RoomInput::by_walls`]). Passages of free
    /// cells of `map` between units of two wings become doors within `doors`, the chains'
    /// door limits ([`self::wing_doors`]).
    /// Fails only where `by_walls` does.
    pub fn compose<E>(
        &self,
        map: &Grid<Cell>,
        mut world: World,
        mut labels: Grid<u16>,
        wings: &[World],
        doors: &DoorLimits,
        by_walls: impl FnOnce(&mut World, &[f64]) -> Result<Grid<u16>, E>,
    ) -> Result<(World, Grid<u16>), E> {
        if let Some(others) = self.by_walls() {
            labels = by_walls(&mut world, others)?;
        }
        let mut world = compose(world, &labels, wings, &self.wing_of);
        self::wing_doors::join_wings(&mut world, map, doors);
        Ok((world, labels))
    }
}

/// The share of the free cells of `wing_of` in the first wing (all of none).
fn first_share(wing_of: &Grid<u8>) -> f64 {
    let free = wing_of.cells().iter().filter(|&&w| w != NO_REGION).count();
    if free == 0 {
        return 1.0;
    }
    wing_of.cells().iter().filter(|&&w| w == 0).count() as f64 / free as f64
}

/// Which wing explains each free cell: each room of `labels` (the first chain's) goes to the
/// direction most of its cells follow ([`direction_regions`]), free cells of no room to their
/// own cell's direction. Directions whose rooms hold less than `min_share` of the free cells
/// go to the first wing, the direction nearest `first_angle` (the first chain's). `None` when
/// one wing is left. Returns the wings per cell and each wing's angle, the first first.
fn wings_by_room(
    found: &DirectionRegions,
    labels: &Grid<u16>,
    first_angle: f64,
    min_share: f64,
) -> Option<(Grid<u8>, Vec<f64>)> {
    let n = found.directions.len();
    if n < 2 {
        return None;
    }
    let rooms = labels.cells().iter().copied().max().unwrap_or(0) as usize;
    let mut votes = vec![vec![0usize; n]; rooms + 1];
    for (&l, &r) in labels.cells().iter().zip(found.region.cells()) {
        if r != NO_REGION {
            votes[l as usize][r as usize] += 1;
        }
    }
    // A room takes the direction of most of its cells when that holds `ROOM_SHARE` of them;
    // a room the directions share (a corridor round a pentagon) is split by its cells'.
    let best = |v: &[usize]| {
        let k = (0..n).max_by_key(|&k| (v[k], std::cmp::Reverse(k))).unwrap_or(0);
        (v[k] as f64 >= ROOM_SHARE * v.iter().sum::<usize>() as f64).then_some(k)
    };
    let direction_of: Vec<Option<usize>> = votes.iter().map(|v| best(v)).collect();
    let direction = |l: u16, r: u8| match direction_of[l as usize] {
        Some(k) if l > 0 => Some(k),
        _ => (r != NO_REGION).then_some(r as usize),
    };
    let mut cells = vec![0usize; n];
    for (&l, &r) in labels.cells().iter().zip(found.region.cells()) {
        if let Some(k) = direction(l, r) {
            cells[k] += 1;
        }
    }
    let total = cells.iter().sum::<usize>().max(1) as f64;
    let apart = |a: f64, b: f64| {
        let d = (a - b).rem_euclid(std::f64::consts::FRAC_PI_2);
        d.min(std::f64::consts::FRAC_PI_2 - d)
    };
    let first = (0..n).min_by(|&a, &b| {
        apart(found.directions[a].angle, first_angle).total_cmp(&apart(found.directions[b].angle, first_angle))
    })?;
    let mut order = vec![first];
    order.extend((0..n).filter(|&k| k != first && cells[k] as f64 >= min_share * total));
    if order.len() < 2 {
        return None;
    }
    let wing_index: Vec<u8> = (0..n).map(|k| order.iter().position(|&j| j == k).unwrap_or(0) as u8).collect();
    let cells: Vec<u8> = labels
        .cells()
        .iter()
        .zip(found.region.cells())
        .map(|(&l, &r)| direction(l, r).map_or(NO_REGION, |k| wing_index[k]))
        .collect();
    let mut angles: Vec<f64> = order.iter().map(|&k| found.directions[k].angle).collect();
    angles[0] = first_angle;
    Some((Grid::from_vec(labels.width(), labels.height(), cells).expect("the labels' own size"), angles))
}

/// The world of the wings: the first chain's rooms (and labels), their units and doors those
/// of the wings' chains, each unit in the room that holds most of its interior.
fn compose(first: World, labels: &Grid<u16>, wings: &[World], wing_of: &Grid<u8>) -> World {
    let mut world = World { units: Vec::new(), doors: Vec::new(), unexplained: Vec::new(), ..first };
    for r in &mut world.rooms {
        r.units.clear();
        r.doors.clear();
    }
    let index: BTreeMap<u32, usize> = world.rooms.iter().enumerate().map(|(i, r)| (r.id, i)).collect();
    for (k, part) in wings.iter().enumerate() {
        let mut ids = BTreeMap::new();
        for unit in part.units.iter().filter(|u| mostly_in(part, u, wing_of, k as u8)) {
            let id = world.units.len() as u32 + 1;
            let angle = (k > 0).then_some(part.frame.angle);
            world.units.push(Unit { id, angle, ..*unit });
            ids.insert(unit.id, id);
            if let Some(&i) = room_under(part, unit, labels).and_then(|room| index.get(&room)) {
                world.rooms[i].units.push(id);
            }
        }
        for d in &part.doors {
            if let [Some(&a), Some(&b)] = d.units.map(|u| ids.get(&u)) {
                let id = world.doors.len() as u32 + 1;
                world.doors.push(Door { id, units: [a, b], ..*d });
            }
        }
    }
    for r in &mut world.rooms {
        r.doors = world.doors.iter().filter(|d| d.units.iter().any(|u| r.units.contains(u))).map(|d| d.id).collect();
    }
    world
}

/// The room of `labels` under most of `unit`'s interior cells (in its world's frame), if any.
fn room_under(world: &World, unit: &Unit, labels: &Grid<u16>) -> Option<u32> {
    let mut counts: BTreeMap<u16, usize> = BTreeMap::new();
    for_interior(world, unit, |mx, my| {
        if let Some(&l) = labels.get(mx, my).filter(|&&l| l > 0) {
            *counts.entry(l).or_default() += 1;
        }
    });
    counts.iter().rev().max_by_key(|&(_, &n)| n).map(|(&l, _)| l as u32)
}

/// Calls `f` with the map cell under each interior cell of `unit` (its ring excluded).
fn for_interior(world: &World, unit: &Unit, mut f: impl FnMut(i64, i64)) {
    let rotation = world.unit_frame(unit).rotation();
    let t = world.wall_thickness;
    let r = unit.rect();
    for y in r.y + t..r.bottom() - t {
        for x in r.x + t..r.right() - t {
            let (mx, my) = rotation.to_map(x as f64 + 0.5, y as f64 + 0.5);
            f(libm::floor(mx) as i64, libm::floor(my) as i64);
        }
    }
}

/// Whether most of the free map cells under `unit`'s interior (in its world's frame) lie in
/// wing `k`'s region: a wing keeps the units that explain its own floor.
fn mostly_in(world: &World, unit: &Unit, wing_of: &Grid<u8>, k: u8) -> bool {
    let (mut inside, mut free) = (0u64, 0u64);
    for_interior(world, unit, |mx, my| {
        if let Some(&w) = wing_of.get(mx, my).filter(|&&w| w != NO_REGION) {
            free += 1;
            inside += u64::from(w == k);
        }
    });
    2 * inside > free
}

/// The wings' chains of `layout`, each on its wing's map in its own direction, stepped
/// `iterations` times, with its typed best world. Natively they run side by side, a thread
/// each (a building of five wings on a laptop's cores takes the time of its slowest wing, not
/// of all five); in WebAssembly one after another. Each chain has its own seed and random
/// stream and shares nothing, so the worlds are the same either way.
fn wing_chains(
    layout: &WingLayout,
    map: &OccupancyMap,
    config: &ChainConfig,
    seed: u64,
    iterations: u64,
) -> Result<Vec<(Stopped, World)>, ChainError> {
    let one = |k: usize| -> Result<(Stopped, World), ChainError> {
        let mut chain = Chain::new(&layout.wing_map(map, k), layout.wing_config(config, k), seed)?;
        chain.step(iterations);
        let mut chain = chain.stop();
        let world = chain.best_world_typed();
        Ok((chain, world))
    };
    let n = layout.angles.len();
    #[cfg(not(target_arch = "wasm32"))]
    if n > 1 && std::thread::available_parallelism().is_ok_and(|p| p.get() > 1) {
        return std::thread::scope(|s| {
            let one = &one;
            let handles: Vec<_> = (0..n).map(|k| s.spawn(move || one(k))).collect();
            handles.into_iter().map(|h| h.join().unwrap_or_else(|e| std::panic::resume_unwind(e))).collect()
        });
    }
    (0..n).map(one).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn layout(wings: &[u8]) -> WingLayout {
        let wing_of = Grid::from_vec(wings.len(), 1, wings.to_vec()).unwrap();
        WingLayout { wing_of, angles: vec![0.0, 0.5, 1.0] }
    }

    #[test]
    fn rooms_go_by_the_walls_only_where_the_first_wing_is_a_small_part() {
        // The first wing holds 2 of 10 free cells (the cells of no wing do not count).
        let small = layout(&[0, 0, 1, 1, 1, 2, 2, 2, 1, 2, NO_REGION, NO_REGION]);
        assert_eq!(small.by_walls(), Some(&[0.5, 1.0][..]));
        // Half of the floor, as in a building of two wings, or a third and more.
        assert_eq!(layout(&[0, 0, 0, 0, 0, 1, 1, 1, 1, 1]).by_walls(), None);
        assert_eq!(layout(&[0, 0, 0, 1, 1, 1, 2, 2, 2]).by_walls(), None);
        assert_eq!(layout(&[NO_REGION; 4]).by_walls(), None, "no floor at all");
    }
}
